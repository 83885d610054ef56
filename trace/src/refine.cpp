// RefinedPair: the pair's exact coefficients in double-double, geometric residuals and a final
// Newton correction of traced points onto the exact surfaces (see curve.hpp).
//
// Why: the tracer works on the coefficients rounded to doubles, i.e. on a nearby pair. Away
// from singular points of the surfaces that moves the curve by ~u (relative); near a cone's
// apex it does not: perturbing a cone's equation by u turns it into a hyperboloid with a waist
// of radius ~sqrt(u) ~ 1e-8, so traced points near the apex lie ~1e-8 off the exact cone.
// Double-double coefficients (~1e-32) shrink that waist below 1e-15.
#include "surfcert/trace/curve.hpp"

#include "double_double.hpp"

#include <flint/fmpq.h>

#include <algorithm>
#include <climits>
#include <cmath>

namespace surfcert::trace {

namespace {

double dot3(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

} // namespace

RefinedPair::RefinedPair(const core::QuadricMatrix& qa, const core::QuadricMatrix& qb) {
  auto fill = [](const core::QuadricMatrix& q, Form& out) {
    // Scaled by a power of two (exact) so that the largest entry is ~1: its binary order from
    // the exact numerators' and denominators' bits, not from doubles (entries beyond the
    // doubles, a paraboloid of radius 5e-91 posed exactly, rounded to inf and the scale was
    // never applied: an internal error; helper-26's probe).
    long e = LONG_MIN;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const core::Rational& v = q(i, j);
        if (v.is_zero()) continue;
        e = std::max(e, static_cast<long>(fmpz_bits(fmpq_numref(v.raw()))) -
                            static_cast<long>(fmpz_bits(fmpq_denref(v.raw()))));
      }
    const core::Rational s = core::pow2(e == LONG_MIN ? 0 : -e);
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        out.hi[i][j] = (q(static_cast<int>(i), static_cast<int>(j)) * s).to_double_approx();
    dd::remainders(q, s, out.hi, out.lo);
  };
  fill(qa, a_);
  fill(qb, b_);
}

double RefinedPair::value(const Form& m, const Point3& p) {
  return dd::form(m.hi, m.lo, p);
}

Point3 RefinedPair::gradient(const Form& m, const Point3& p) {
  Point3 g{};
  for (size_t i = 0; i < 3; ++i)
    g[i] = 2 * (m.hi[i][0] * p[0] + m.hi[i][1] * p[1] + m.hi[i][2] * p[2] + m.hi[i][3]);
  return g;
}

double RefinedPair::distance(const Form& m, const Point3& p) {
  // The evaluation error of value(): ten double-double products and sums of terms of size
  // |m_ij x_i x_j|, each good to ~2^-104 of the running sum: 2^-98 of the terms' size bounds it
  // with room (the size itself in double: an estimate of the bound's scale, rounded up).
  const double x[4] = {p[0], p[1], p[2], 1.0};
  double terms = 0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j)
      terms += (i == j ? 1 : 2) * std::fabs(m.hi[i][j] * x[i] * x[j]);
  const double f = std::fabs(value(m, p)) + 0x1p-98 * terms;
  const Point3 g = gradient(m, p);
  const double gn = std::sqrt(dot3(g, g));
  return gn > 0 ? f / gn : f; // at a vanishing gradient (a cone's apex) f itself, as 0 there
}

double RefinedPair::distance(const Point3& p) const {
  return std::max(distance(a_, p), distance(b_, p));
}

double RefinedPair::refine(Point3& p, double target, int face_axis) const {
  double best = distance(p);
  Point3 x = p;
  for (int it = 0; it < 8 && best > target; ++it) {
    const double fv = value(a_, x), gv = value(b_, x);
    Point3 gf = gradient(a_, x), gg = gradient(b_, x);
    if (face_axis >= 0) { // the step stays in the face's plane
      gf[static_cast<size_t>(face_axis)] = 0;
      gg[static_cast<size_t>(face_axis)] = 0;
    }
    // Minimum-norm Gauss-Newton step (on a face: Newton in the face's two coordinates).
    const double a11 = dot3(gf, gf), a12 = dot3(gf, gg), a22 = dot3(gg, gg);
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 1e-30 * a11 * a22) || !std::isfinite(det)) break;
    const double m1 = (a22 * fv - a12 * gv) / det, m2 = (a11 * gv - a12 * fv) / det;
    // A step far longer than the distance it corrects (64 times, plus 4 ulps of the point) is
    // refused: there the surfaces are nearly tangent (along a double line or conic, sin ~1e-8)
    // and {f = g = 0} barely constrains the point sideways; such steps moved the points of a
    // double line shrunk to 2^-30 (each within 1e-17 of both surfaces) 2e-10 off the line.
    Point3 step{};
    for (size_t i = 0; i < 3; ++i)
      step[i] = m1 * gf[i] + m2 * gg[i];
    const double big = std::max({std::fabs(x[0]), std::fabs(x[1]), std::fabs(x[2])});
    if (!(std::sqrt(dot3(step, step)) <= 64 * best + 0x1p-50 * big)) break;
    for (size_t i = 0; i < 3; ++i)
      x[i] -= step[i];
    const double d = distance(x);
    if (!(d < best)) break;
    best = d;
    p = x;
  }
  return best;
}

} // namespace surfcert::trace
