// Helpers shared by the curve tests that read generated pairs and check traced points exactly:
// a quadric from integer matrix rows (as `surfcert generate` prints them), and a point's exact
// value on a quadric relative to the matrix's size (the double read exactly: an independent
// check of "on the surface", no tolerance of the tracer's involved).
#pragma once

#include "surfcert/core/quadric.hpp"
#include "surfcert/trace/curve.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace surfcert::testing {

/// The quadric of the symmetric integer matrix given by its rows.
inline core::QuadricMatrix from_ints(const std::array<std::array<long, 4>, 4>& rows) {
  core::Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = core::Rational(rows[i][j]);
  return core::QuadricMatrix(m);
}

/// |X^T M X| / (max |M_ij| (1 + |p|^2)) at X = (p, 1), computed exactly.
inline double relative_value(const core::QuadricMatrix& q, const trace::Point3& p) {
  std::array<core::Rational, 4> x{core::Rational::exact_from_double(p[0]),
                                  core::Rational::exact_from_double(p[1]),
                                  core::Rational::exact_from_double(p[2]), core::Rational(1)};
  core::Rational v(0);
  double big = 0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      v += x[i] * q.matrix()[i][j] * x[j];
      big = std::max(big, std::fabs(q.matrix()[i][j].to_double_approx()));
    }
  return std::fabs(v.to_double_approx()) / (big * (1 + p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
}

} // namespace surfcert::testing
