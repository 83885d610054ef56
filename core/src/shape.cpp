#include "surfcert/core/shape.hpp"

#include "surfcert/core/quadric.hpp"

namespace surfcert::core {

LocalForm local_form(ShapeType t) {
  switch (t) {
  case ShapeType::Sphere:
  case ShapeType::Ellipsoid:
    return {{1, 1, 1}, 0, -1};
  case ShapeType::Cylinder:
    return {{1, 1, 0}, 0, -1};
  case ShapeType::Cone:
    return {{1, 1, -1}, 0, 0};
  case ShapeType::EllipticParaboloid:
    return {{1, 1, 0}, -1, 0};
  case ShapeType::HyperbolicParaboloid:
    return {{1, -1, 0}, -1, 0};
  case ShapeType::HyperboloidOneSheet:
    return {{1, 1, -1}, 0, -1};
  case ShapeType::HyperboloidTwoSheets:
    return {{1, 1, -1}, 0, 1};
  }
  return {{0, 0, 0}, 0, 0};
}

Mat3 quaternion_rotation(const std::array<Rational, 4>& q) {
  const Rational &w = q[0], &x = q[1], &y = q[2], &z = q[3];
  const Rational n = w * w + x * x + y * y + z * z;
  const Rational two(2);
  Mat3 r = {{{w * w + x * x - y * y - z * z, two * (x * y - w * z), two * (x * z + w * y)},
             {two * (x * y + w * z), w * w - x * x + y * y - z * z, two * (y * z - w * x)},
             {two * (x * z - w * y), two * (y * z + w * x), w * w - x * x - y * y + z * z}}};
  for (auto& row : r)
    for (auto& e : row)
      e = e / n;
  return r;
}

Mat4 posed_quadric_matrix(ShapeType t, const std::array<Rational, 3>& radii,
                          const std::array<Rational, 3>& center, const Mat3& inv) {
  const LocalForm f = local_form(t);
  Mat4 local;
  for (size_t i = 0; i < 3; ++i)
    if (f.q_sign[i] != 0) {
      Rational q = Rational(1) / (radii[i] * radii[i]);
      local[i][i] = f.q_sign[i] > 0 ? q : -q;
    }
  local[2][3] = local[3][2] = Rational(f.linear_z) * Rational(1, 2);
  local[3][3] = Rational(f.constant);
  // World point x = R u + c, so u = R^-1 (x - c): T = [[R^-1, -R^-1 c], [0, 1]], M = T^T L T.
  Mat4 tm;
  for (size_t i = 0; i < 3; ++i) {
    Rational s;
    for (size_t j = 0; j < 3; ++j) {
      tm[i][j] = inv[i][j];
      s += inv[i][j] * center[j];
    }
    tm[i][3] = -s;
  }
  tm[3][3] = Rational(1);
  return congruence(tm, local);
}

Mat4 exact_matrix(const ShapeSpec& s) {
  std::array<Rational, 3> radii, center;
  for (size_t i = 0; i < 3; ++i) {
    radii[i] = Rational::exact_from_double(s.radii[i]);
    center[i] = Rational::exact_from_double(s.center[i]);
  }
  Mat3 inv{};
  if (s.rotated) {
    std::array<Rational, 4> q;
    for (size_t i = 0; i < 4; ++i)
      q[i] = Rational::exact_from_double(s.quaternion[i]);
    const Mat3 r = quaternion_rotation(q);
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        inv[i][j] = r[j][i]; // exactly orthogonal: R^-1 = R^T
  } else {
    for (size_t i = 0; i < 3; ++i)
      inv[i][i] = Rational(1);
  }
  return posed_quadric_matrix(s.type, radii, center, inv);
}

} // namespace surfcert::core
