// surfcert::certify::ellipses_in_box (see ellipses_in_box.hpp): exact rational arithmetic.
#include "surfcert/certify/ellipses_in_box.hpp"

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/plane_chart.hpp"
#include "surfcert/certify/affine.hpp"

#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

using V4 = std::array<Rational, 4>;

// The planes of the member e at a root of rank 1 (its nonzero rows are multiples of the double
// plane) or 2 (a rational plane pair); none otherwise.
std::vector<V4> member_planes(const core::Mat4& e, int rank) {
  if (rank == 1) {
    for (size_t i = 0; i < 4; ++i)
      if (!e[i][i].is_zero()) return {V4{e[i][0], e[i][1], e[i][2], e[i][3]}};
    return {};
  }
  if (rank == 2)
    if (const auto pp = rational_plane_pair(e)) return {(*pp)[0], (*pp)[1]};
  return {};
}

// n and m the same plane (proportional 4-vectors).
bool same_plane(const V4& n, const V4& m) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i + 1; j < 4; ++j)
      if (n[i] * m[j] != n[j] * m[i]) return false;
  return true;
}

enum class Place { NotEllipse, Inside, NotInside };

// A's section by the plane n: a real ellipse inside the box, one not inside it, or no ellipse.
Place section_place(const core::Mat4& a, const V4& n, const std::array<Rational, 3>& lo,
                    const std::array<Rational, 3>& hi) {
  const auto chart = algebra::plane_chart(plane_as_quadric(n));
  if (!chart) return Place::NotEllipse;
  const auto& col = *chart;
  auto cm = algebra::restrict_form(a, col);
  Rational s00 = cm[0][0], s01 = cm[0][1], s11 = cm[1][1], b0 = cm[0][2], b1 = cm[1][2],
           c = cm[2][2];
  const Rational det = s00 * s11 - s01 * s01;
  if (det.sign() <= 0) return Place::NotEllipse; // no definite quadratic part
  if (s00.sign() < 0) {
    s00 = -s00, s01 = -s01, s11 = -s11, b0 = -b0, b1 = -b1, c = -c;
  }
  // S^-1 = [[s11, -s01], [-s01, s00]] / det.
  auto inv = [&](const Rational& x, const Rational& y, const Rational& u, const Rational& v) {
    return (x * (s11 * u - s01 * v) + y * (-s01 * u + s00 * v)) / det; // (x, y) S^-1 (u, v)
  };
  const Rational rho = inv(b0, b1, b0, b1) - c;
  if (rho.sign() <= 0) return Place::NotEllipse; // a point or nothing
  const Rational u0 = -(s11 * b0 - s01 * b1) / det, v0 = -(-s01 * b0 + s00 * b1) / det;
  for (size_t k = 0; k < 3; ++k) {
    const Rational &g0 = col[0][k], &g1 = col[1][k], &h = col[2][k];
    const Rational m = g0 * u0 + g1 * v0 + h;
    const Rational r = rho * inv(g0, g1, g0, g1);
    const Rational up = hi[k] - m, down = m - lo[k];
    if (up.sign() < 0 || down.sign() < 0 || r > up * up || r > down * down) return Place::NotInside;
  }
  return Place::Inside;
}

} // namespace

std::optional<int> ellipses_in_box(const algebra::PencilFacts& facts, int loops,
                                   const std::array<Rational, 3>& lo,
                                   const std::array<Rational, 3>& hi) {
  const core::Mat4& a = facts.a;
  const core::Mat4& b = facts.b;
  if (a == core::Mat4{}) return std::nullopt; // the basis is not set
  std::vector<V4> seen;
  int ellipses = 0, inside = 0;
  for (const auto& root : facts.real_roots) {
    if (root.rank > 2 || !root.rational_value) continue;
    const core::Mat4 e = core::scaled(a, *root.rational_value) + core::scaled(b, -1);
    for (const V4& n : member_planes(e, root.rank)) {
      bool again = false;
      for (const V4& m : seen)
        again = again || same_plane(n, m);
      if (again) continue;
      seen.push_back(n);
      const Place p = section_place(a, n, lo, hi);
      if (p == Place::NotEllipse) continue;
      ++ellipses;
      inside += p == Place::Inside ? 1 : 0;
    }
  }
  if (ellipses != loops) return std::nullopt;
  return inside;
}

} // namespace surfcert::certify
