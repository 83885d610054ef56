// box_exits of a double line (see box_exits_double_line.hpp): all exact rational arithmetic.
#include "box_exits_double_line.hpp"

#include "surfcert/algebra/form_restriction.hpp"

#include <string>

namespace surfcert::certify::detail {

namespace {

using core::Rational;
using V4 = std::array<Rational, 4>;

bool is_plane(const core::Mat4& m) {
  bool linear_part = false;
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j)
      if (!m[i][j].is_zero()) return false;
    linear_part = linear_part || !m[i][3].is_zero();
  }
  return linear_part;
}

} // namespace

std::optional<BoxExits> double_line_exits(const core::Mat4& a, const core::Mat4& b,
                                          const std::array<Rational, 3>& lo,
                                          const std::array<Rational, 3>& hi) {
  const bool pa = is_plane(a), pb = is_plane(b);
  if (pa == pb) return std::nullopt; // two planes, or no plane: the generic reading
  const core::Mat4& plane = pa ? a : b;
  const core::Mat4& other = pa ? b : a;
  // The plane 2 (p0 x + p1 y + p2 z) + p3 = 0 (p_i = plane[i][3], p3 = plane[3][3]) in the
  // chart of two free coordinates (s, t): x_m solved for, m with p_m != 0.
  size_t m = 0;
  while (plane[m][3].is_zero())
    ++m;
  const size_t f0 = (m + 1) % 3, f1 = (m + 2) % 3;
  const Rational two_pm = Rational(2) * plane[m][3];
  std::array<V4, 3> cols; // (s, t, 1) -> homogeneous point of the plane
  cols[0][f0] = Rational(1);
  cols[0][m] = -(Rational(2) * plane[f0][3]) / two_pm;
  cols[1][f1] = Rational(1);
  cols[1][m] = -(Rational(2) * plane[f1][3]) / two_pm;
  cols[2][3] = Rational(1);
  cols[2][m] = -plane[3][3] / two_pm;
  const auto c = algebra::restrict_form(other, cols);
  // Rank 1 exactly: some diagonal entry nonzero, every 2x2 minor zero.
  size_t r = 3;
  for (size_t i = 0; i < 3 && r == 3; ++i)
    if (!c[i][i].is_zero()) r = i;
  if (r == 3) return std::nullopt; // zero (the plane on the quadric) or not rank 1
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      if (!(c[i][j] * c[r][r] - c[i][r] * c[r][j]).is_zero()) return std::nullopt;
  // c = c[r][r]^-1 l l^T with l = row r: the section is the line l0 s + l1 t + l2 = 0, twice.
  const std::array<Rational, 3>& l = c[r];
  BoxExits out;
  if (l[0].is_zero() && l[1].is_zero()) {
    out.certified = true; // the line at infinity: no affine point at all
    return out;
  }
  // A point and a direction of the line, in (s, t), then in space.
  Rational s0, t0;
  if (!l[0].is_zero())
    s0 = -l[2] / l[0];
  else
    t0 = -l[2] / l[1];
  const Rational ds = l[1], dt = -l[0];
  std::array<Rational, 3> p, d;
  for (size_t k = 0; k < 3; ++k) {
    p[k] = cols[0][k] * s0 + cols[1][k] * t0 + cols[2][k];
    d[k] = cols[0][k] * ds + cols[1][k] * dt;
  }
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      const size_t ku = static_cast<size_t>(k);
      const Rational& face = side ? hi[ku] : lo[ku];
      const std::string name =
          std::string(side ? "max" : "min") + " face of axis " + std::to_string(k);
      if (d[ku].is_zero()) {
        if (p[ku] == face) {
          out.reason = "the curve has a component in the plane of the " + name;
          return out;
        }
        continue; // parallel to the face
      }
      const Rational t = (face - p[ku]) / d[ku];
      // Outside when a coordinate lies strictly outside its range; else on an edge when one
      // equals a bound; else inside the open face.
      bool outside = false, edge = false;
      BoxCrossing bc;
      bc.axis = k;
      bc.at_max = side == 1;
      for (size_t i = 0; i < 3; ++i) {
        const Rational x = i == ku ? face : p[i] + t * d[i];
        bc.approx[i] = x.to_double_approx();
        if (i == ku) continue;
        outside = outside || x < lo[i] || x > hi[i];
        edge = edge || x == lo[i] || x == hi[i];
      }
      if (outside) continue;
      if (edge) {
        out.points.clear();
        out.reason = "a crossing on an edge of the box on the " + name;
        return out;
      }
      out.points.push_back(bc);
    }
  out.certified = true;
  return out;
}

} // namespace surfcert::certify::detail
