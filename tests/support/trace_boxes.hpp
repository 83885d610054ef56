// Helpers shared by the tracer's box tests: trace options with a given box (the curve is
// clipped to [lo, hi], its exits on the box's faces counted), instead of the automatic one;
// the geometric residual of a traced point against an exact quadric.
#pragma once

#include "surfcert/core/rational.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <cmath>

namespace surfcert::testing {

/// Default trace options but for the box [lo, hi] (componentwise lo <= hi).
inline trace::TraceOptions given_box(trace::Point3 lo, trace::Point3 hi) {
  trace::TraceOptions opt;
  trace::Box box;
  box.min = lo;
  box.max = hi;
  opt.box = box;
  return opt;
}

// |f(p)| / |grad f(p)|, with f(p) exact (the double point read exactly): the first-order
// distance from p to the surface. Exact f matters at a cone's apex, where the gradient
// vanishes and the rounding error of a float f would dominate the quotient.
inline double geometric_residual(const core::QuadricMatrix& m, const trace::Point3& p) {
  const core::Rational x[4] = {core::Rational::exact_from_double(p[0]),
                               core::Rational::exact_from_double(p[1]),
                               core::Rational::exact_from_double(p[2]), core::Rational(1)};
  core::Rational f;
  double g[3] = {0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      f += x[i] * m(i, j) * x[j];
      if (i < 3) g[i] += 2 * (m(i, j) * x[j]).to_double_approx();
    }
  const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  const double fa = std::fabs(f.to_double_approx());
  return gn > 0 ? fa / gn : fa;
}

} // namespace surfcert::testing
