// surfcert::certify::exact_curve_lines and exact_lines_box_exits (see curve_lines.hpp): all
// exact rational arithmetic.
#include "surfcert/certify/curve_lines.hpp"

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/kernel.hpp"
#include "surfcert/algebra/plane_chart.hpp"
#include "surfcert/certify/affine.hpp"

#include <flint/fmpz.h>

namespace surfcert::certify {

using core::Integer;
using core::Rational;

namespace {

using V3 = std::array<Rational, 3>;
using V4 = std::array<Rational, 4>;

V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Rational dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V3 sub(const V3& a, const V3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
bool is_zero(const V3& v) {
  return v[0].is_zero() && v[1].is_zero() && v[2].is_zero();
}

// Whether the line p + t d lies on the quadric m: X^T m X vanishes identically in t, i.e. at
// (p, 1), bilinearly between (p, 1) and (d, 0), and at (d, 0).
bool on_quadric(const core::Mat4& m, const ExactLine& l) {
  const V4 p{l.point[0], l.point[1], l.point[2], Rational(1)};
  const V4 d{l.direction[0], l.direction[1], l.direction[2], Rational(0)};
  return algebra::bilinear(m, p, p).is_zero() && algebra::bilinear(m, p, d).is_zero() &&
         algebra::bilinear(m, d, d).is_zero();
}

bool same_line(const ExactLine& x, const ExactLine& y) {
  return is_zero(cross(x.direction, y.direction)) &&
         is_zero(cross(sub(y.point, x.point), x.direction));
}

// The affine line spanned by two projective points u, v (a basis of a kernel), nullopt when
// it lies at infinity.
std::optional<ExactLine> affine_line(const V4& u, const V4& v) {
  const V4& f = u[3].is_zero() ? v : u; // a point off the plane at infinity
  if (f[3].is_zero()) return std::nullopt;
  ExactLine l;
  for (size_t k = 0; k < 3; ++k) {
    l.point[k] = f[k] / f[3];
    l.direction[k] = u[3] * v[k] - v[3] * u[k]; // the point at infinity of the span
  }
  if (is_zero(l.direction)) return std::nullopt;
  return l;
}

// The meet of the diametral planes of a and b for the direction d, n_m . p + c_m = 0 with
// n_m = M_3 d, c_m = d . m_4; nullopt when the normals are parallel (or vanish).
std::optional<ExactLine> diametral_meet(const core::Mat4& a, const core::Mat4& b, const V3& d) {
  auto plane = [&d](const core::Mat4& m, V3& n, Rational& c) {
    for (size_t i = 0; i < 3; ++i)
      n[i] = m[i][0] * d[0] + m[i][1] * d[1] + m[i][2] * d[2];
    c = m[3][0] * d[0] + m[3][1] * d[1] + m[3][2] * d[2];
  };
  V3 n1, n2;
  Rational c1, c2;
  plane(a, n1, c1);
  plane(b, n2, c2);
  const V3 dir = cross(n1, n2);
  if (is_zero(dir)) return std::nullopt;
  // The point of the meet on the plane through the origin normal to dir: the solution of
  // n1 . p = -c1, n2 . p = -c2, dir . p = 0, by Cramer (the rows' determinant is |dir|^2).
  const Rational det = dot(dir, dir);
  const V3 p1 = cross(n2, dir), p2 = cross(dir, n1); // n_i . p_j = det [i == j]
  ExactLine l;
  for (size_t k = 0; k < 3; ++k)
    l.point[k] = (-c1 * p1[k] - c2 * p2[k]) / det;
  l.direction = dir;
  return l;
}

// The lines in direction d on the quadric m inside its diametral plane Pi = {n . p + c = 0}
// (n = M_3 d, c = d . m_4), for when a's and b's planes coincide (two parallel lines of the
// curve in direction d, or a line along which the surfaces are tangent): m is constant along d
// on Pi (its derivative along d is the plane's equation), so on Pi it is a quadratic q(s) in
// the coordinate s across d, p = p0 + s u; each rational root is a line p0 + s u + t d.
std::vector<ExactLine> lines_in_diametral_plane(const core::Mat4& m, const V3& d) {
  V3 n;
  for (size_t i = 0; i < 3; ++i)
    n[i] = m[i][0] * d[0] + m[i][1] * d[1] + m[i][2] * d[2];
  const Rational c = m[3][0] * d[0] + m[3][1] * d[1] + m[3][2] * d[2];
  const V3 u = cross(n, d);
  if (is_zero(n) || is_zero(u)) return {};
  const Rational nn = dot(n, n);
  const V4 p0{-c * n[0] / nn, -c * n[1] / nn, -c * n[2] / nn, Rational(1)};
  const V4 u4{u[0], u[1], u[2], Rational(0)};
  // q(s) = alpha s^2 + 2 beta s + gamma.
  const Rational alpha = algebra::bilinear(m, u4, u4), beta = algebra::bilinear(m, p0, u4),
                 gamma = algebra::bilinear(m, p0, p0);
  std::vector<Rational> roots;
  if (alpha.is_zero()) {
    if (!beta.is_zero()) roots.push_back(-gamma / (Rational(2) * beta));
  } else {
    const Rational disc = beta * beta - alpha * gamma;
    if (disc.sign() < 0) return {};
    Integer sn, sd;
    if (!fmpz_is_square(disc.num().raw()) || !fmpz_is_square(disc.den().raw())) return {};
    fmpz_sqrt(sn.raw_mut(), disc.num().raw());
    fmpz_sqrt(sd.raw_mut(), disc.den().raw());
    const Rational root(sn, sd);
    roots.push_back((-beta + root) / alpha);
    if (!root.is_zero()) roots.push_back((-beta - root) / alpha);
  }
  std::vector<ExactLine> out;
  for (const Rational& s : roots) {
    ExactLine l;
    for (size_t k = 0; k < 3; ++k)
      l.point[k] = p0[k] + s * u[k];
    l.direction = d;
    out.push_back(l);
  }
  return out;
}

// The affine line of m's section by the plane n . (x, y, z, 1) = 0 when the plane's line at
// infinity lies on m (the section's quadratic part vanishes in the plane's chart: the section is
// that line and 2 e s + 2 f t + g = 0); nullopt otherwise, for the plane at infinity, or when
// the affine section is empty or the whole plane.
std::optional<ExactLine> line_beside_infinity(const core::Mat4& m, const V4& n) {
  const auto chart = algebra::plane_chart(plane_as_quadric(n));
  if (!chart) return std::nullopt;
  const auto& col = *chart;
  const auto cm = algebra::restrict_form(m, col);
  if (!(cm[0][0].is_zero() && cm[0][1].is_zero() && cm[1][1].is_zero())) return std::nullopt;
  const Rational &e = cm[0][2], &f = cm[1][2], &g = cm[2][2];
  if (e.is_zero() && f.is_zero()) return std::nullopt;
  // (s, t) = (-g / 2e, 0) or (0, -g / 2f); direction (-f, e) in (s, t).
  const Rational s = e.is_zero() ? Rational(0) : -g / (Rational(2) * e);
  const Rational t = e.is_zero() ? -g / (Rational(2) * f) : Rational(0);
  ExactLine l;
  for (size_t k = 0; k < 3; ++k) {
    l.point[k] = col[0][k] * s + col[1][k] * t + col[2][k];
    l.direction[k] = e * col[1][k] - f * col[0][k];
  }
  if (is_zero(l.direction)) return std::nullopt;
  return l;
}

} // namespace

std::optional<std::vector<ExactLine>>
exact_curve_lines(const algebra::PencilFacts& facts, int real_lines,
                  const std::vector<std::array<Rational, 3>>& directions, int lines_at_infinity) {
  const core::Mat4& a = facts.a;
  const core::Mat4& b = facts.b;
  const int affine_lines = real_lines - lines_at_infinity;
  if (a == core::Mat4{} || real_lines <= 0 || affine_lines < 0)
    return std::nullopt; // the basis is not set
  std::vector<ExactLine> lines;
  auto add = [&lines](ExactLine l) {
    for (const auto& x : lines)
      if (same_line(x, l)) return;
    // The point nearest the origin (one line, one point: what a picture rounds to doubles).
    const Rational t = dot(l.point, l.direction) / dot(l.direction, l.direction);
    for (size_t k = 0; k < 3; ++k)
      l.point[k] -= t * l.direction[k];
    lines.push_back(std::move(l));
  };
  for (const auto& r : facts.real_roots) {
    if (r.rank != 2 || !r.rational_value) continue;
    const core::Mat4 e = core::scaled(a, *r.rational_value) + core::scaled(b, -1);
    const auto ker = algebra::kernel_basis(e);
    if (ker.size() != 2) continue;
    if (!(algebra::bilinear(a, ker[0], ker[0]).is_zero() &&
          algebra::bilinear(a, ker[0], ker[1]).is_zero() &&
          algebra::bilinear(a, ker[1], ker[1]).is_zero()))
      continue; // the kernel line is not on the curve
    const auto l = affine_line(ker[0], ker[1]);
    if (!l) {
      if (lines_at_infinity > 0) continue; // one of the lines at infinity the caller counted
      return std::nullopt;                 // a line at infinity: not this reading
    }
    add(*l);
  }
  for (const auto& r : facts.real_roots) {
    if (r.rank > 2 || !r.rational_value) continue;
    const core::Mat4 e = core::scaled(a, *r.rational_value) + core::scaled(b, -1);
    for (const V4& n : rational_member_planes(e, r.rank))
      if (const auto l = line_beside_infinity(a, n))
        if (on_quadric(b, *l)) add(*l);
  }
  for (const auto& d : directions) {
    if (is_zero(d)) return std::nullopt;
    if (const auto l = diametral_meet(a, b, d)) {
      if (on_quadric(a, *l) && on_quadric(b, *l)) add(*l);
      continue;
    }
    for (const auto& l : lines_in_diametral_plane(a, d))
      if (on_quadric(a, l) && on_quadric(b, l)) add(l);
  }
  if (static_cast<int>(lines.size()) != affine_lines) return std::nullopt;
  for (const auto& l : lines)
    if (!on_quadric(a, l) || !on_quadric(b, l)) return std::nullopt; // (a kernel line on A is)
  return lines;
}

BoxExits exact_lines_box_exits(const std::vector<ExactLine>& lines,
                               const std::array<Rational, 3>& lo,
                               const std::array<Rational, 3>& hi) {
  BoxExits all;
  for (size_t i = 0; i < lines.size(); ++i) {
    BoxExits one = lines_box_exits(lines[i].point, {lines[i].direction}, lo, hi);
    if (!one.certified) return one;
    all.points.insert(all.points.end(), one.points.begin(), one.points.end());
    // Where line i meets an earlier line j (coplanar, not parallel): on the box's boundary
    // the two share a crossing, which would be read twice.
    for (size_t j = 0; j < i; ++j) {
      const ExactLine &x = lines[j], &y = lines[i];
      const V3 n = cross(x.direction, y.direction);
      const V3 w = sub(y.point, x.point);
      if (is_zero(n) || !dot(w, n).is_zero()) continue; // parallel or skew
      // x.point + s x.direction = y.point + t y.direction: s = ((w x y.d) . n) / |n|^2.
      const Rational s = dot(cross(w, y.direction), n) / dot(n, n);
      bool within = true, inside = true;
      for (size_t k = 0; k < 3; ++k) {
        const Rational c = x.point[k] + s * x.direction[k];
        within = within && lo[k] <= c && c <= hi[k];
        inside = inside && lo[k] < c && c < hi[k];
      }
      if (within && !inside) {
        BoxExits out;
        out.reason = "two lines of the curve meet on the boundary of the box";
        return out;
      }
    }
  }
  all.certified = true;
  return all;
}

} // namespace surfcert::certify
