// surfcert::certify::point_quadric_critical: every critical distance from a rational point x to
// a quadric surface Q, certified.
//
// Method (offset / Lagrange): a foot point p of x on Q satisfies x - p = alpha (Q3 p + b) with
// Q3 the quadratic block and b half the linear part, so p(alpha) = (I + alpha Q3)^-1 (x - alpha b)
// = N(alpha) / D(alpha) (adjugate over the cubic D = det(I + alpha Q3)), and Q(p(alpha)) = 0
// clears to a polynomial P(alpha) of degree <= 6 over Q (the point-quadric sextic). Its real
// roots are isolated exactly; each root with D != 0 gives one foot point; a root where D
// vanishes too (decided exactly by a gcd) means a continuum of foot points (x on an axis of a
// surface of revolution) and is reported as such; the singular points of Q (the vertex of a
// cone: kernel of the 4x4 matrix when it lies on Q) are added as candidates. Each critical
// distance is enclosed with Arb (ball arithmetic from the exact root's isolating interval),
// refined until its relative width is <= 10^-digits (ok = false when ten refinement rounds do
// not get there). More digits give narrower enclosures of the same values (the roots are
// isolated exactly), which is how callers separate near ties or beat cancellation in d - r.
// Invariants: each enclosure contains the exact value; foot points are approximations
// (doubles) of exact algebraic points. `criticals` is sorted by the certified lower bounds
// (compared exactly), so [front().lower, front().upper] encloses the minimum distance; the
// order is NOT a decision of which candidate attains it (two distances closer than their
// enclosures may come in either order). The tightest enclosure of the minimum (maximum) is
// [min lower, min upper] ([max lower, max upper]) over every entry; back() alone does not
// enclose the maximum.
#pragma once

#include "surfcert/core/quadric.hpp"

#include <array>
#include <string>
#include <vector>

namespace surfcert::certify {

struct CriticalDistance {
  std::string lower, upper;     ///< decimal enclosure of the distance |x - p| (lower <= d <= upper)
  double approx = 0;            ///< midpoint as a double
  std::array<double, 3> foot{}; ///< a foot point (approximate)
  bool continuum = false;       ///< a whole circle (or more) of foot points at this distance
  bool singular_point = false;  ///< the foot point is a singular point of Q (cone vertex)
  /// The squared distance as an exact rational when known: a rational multiplier with
  /// D(alpha) = 0 (the symmetric foot points of a surface of revolution share it exactly, and a
  /// continuum is at it), and a rational singular point. Such entries compare exactly.
  bool d2_exact = false;
  core::Rational d2;
};

struct PointQuadricResult {
  bool ok = false; ///< false: not decided (note says why)
  std::string note;
  std::vector<CriticalDistance> criticals; ///< sorted by lower bound (see above)
  int sextic_degree = 0;                   ///< degree of the eliminated polynomial in alpha
};

/// Critical distances from x to the quadric q (any quadric with a nonzero quadratic part).
PointQuadricResult point_quadric_critical(const std::array<core::Rational, 3>& x,
                                          const core::QuadricMatrix& q, long digits);

} // namespace surfcert::certify
