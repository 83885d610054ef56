#include "surfcert/certify/distance/at_infinity.hpp"

#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/algebra/solution_cover.hpp"
#include "surfcert/certify/distance/quadratic_forms.hpp"
#include "surfcert/core/torus.hpp"

namespace surfcert::certify {

using core::Rational;

namespace {

using V3 = RVec3;
using M3 = RMat3;

V3 cross(const V3& x, const V3& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}

bool zero(const V3& v) {
  return v[0].is_zero() && v[1].is_zero() && v[2].is_zero();
}

algebra::Inertia inertia3(const M3& m) {
  core::Mat4 x;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      x[i][j] = m[i][j];
  return algebra::inertia_ldlt(x);
}

// 1: the conic at infinity of `m` is a point and misses `other`'s; 0: it is a point or a
// double line meeting `other`'s, or another shape (not decided here); -1 never used.
bool disjoint_from(const M3& m, const M3& other) {
  const algebra::Inertia in = inertia3(m);
  if (in.rank() == 2 && in.semidefinite()) { // a single real point: the kernel direction
    V3 k{Rational(0), Rational(0), Rational(0)};
    for (size_t i = 0; i < 3 && zero(k); ++i)
      for (size_t j = i + 1; j < 3 && zero(k); ++j)
        k = cross(m[i], m[j]);
    return !zero(k) && !bilinear(other, k, k).is_zero();
  }
  if (in.rank() == 1) { // the double line r.u = 0: the other form must be definite on it
    V3 r = m[0];
    for (size_t i = 1; i < 3 && zero(r); ++i)
      r = m[i];
    size_t kk = 0;
    for (size_t i = 1; i < 3; ++i)
      if (core::abs(r[i]) < core::abs(r[kk])) kk = i;
    V3 e{Rational(0), Rational(0), Rational(0)};
    e[kk] = Rational(1);
    const V3 e1 = cross(r, e), e2 = cross(r, e1);
    const Rational a = bilinear(other, e1, e1), b = bilinear(other, e1, e2),
                   c = bilinear(other, e2, e2);
    return (a * c - b * b).sign() > 0;
  }
  return false;
}

// The form x^T m x (exact: Poly3 takes the rational entries as they are).
core::Poly3 form_poly(const M3& m) {
  core::Poly3 f;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      f = f + core::Poly3(m[i][j]) * core::Poly3::variable(static_cast<int>(i)) *
                  core::Poly3::variable(static_cast<int>(j));
  return f;
}

// Any two conics at infinity (proper conics, line pairs): no common real point, proven. A chart
// l.X = 1 of the projective plane whose line l.X = 0 meets neither common point (the binary
// forms of both conics on that line have a nonzero resultant: no common point there, real or
// complex), then an exact real solution cover of {x^T A x, x^T B x, l.x - 1} with no box.
bool conics_disjoint(const M3& ma, const M3& mb) {
  const std::array<V3, 4> ls{{{Rational(3), Rational(-5), Rational(7)},
                              {Rational(2), Rational(7), Rational(-11)},
                              {Rational(1), Rational(1), Rational(1)},
                              {Rational(0), Rational(0), Rational(1)}}};
  for (const auto& l : ls) {
    const auto fr = core::plane_frame(l);
    const Rational res = restricted_resultant(ma, mb, fr[0], fr[1]);
    if (res.is_zero()) continue;
    core::Poly3 chart(-1);
    for (size_t i = 0; i < 3; ++i)
      chart = chart + core::Poly3(l[i]) * core::Poly3::variable(static_cast<int>(i));
    const algebra::SolutionCover c =
        algebra::cover_real_solutions({form_poly(ma), form_poly(mb), chart}, Rational(1, 16));
    return c.ok && c.boxes.empty();
  }
  return false;
}

} // namespace

bool minimum_attained(const core::QuadricMatrix& a, const core::QuadricMatrix& b) {
  const M3 ma = quadratic_block(a), mb = quadratic_block(b);
  return disjoint_from(ma, mb) || disjoint_from(mb, ma) || conics_disjoint(ma, mb);
}

bool real_conics_disjoint(const std::array<std::array<core::Rational, 3>, 3>& a,
                          const std::array<std::array<core::Rational, 3>, 3>& b) {
  return conics_disjoint(a, b);
}

} // namespace surfcert::certify
