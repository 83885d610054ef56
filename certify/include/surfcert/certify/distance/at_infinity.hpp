// surfcert::certify::minimum_attained: an exact sufficient condition for the distance between
// two unbounded quadrics to be attained at a finite pair of points.
//
// If points p_n of A and q_n of B stay within bounded distance while |p_n| -> infinity, their
// directions converge (a subsequence) to one real point u at infinity of both: u^T M_A u = 0 =
// u^T M_B u (M the quadratic blocks). So when the real conics at infinity of A and B have no
// common point, the distance tends to infinity far out and the minimum over the critical pairs
// (which the offset system covers) is the global minimum. Decided exactly when one of the two
// conics at infinity is a single point (semidefinite block of rank 2: paraboloids, elliptic
// cylinders; the kernel direction k, common iff k^T M k = 0) or a double line (rank 1:
// parabolic cylinders, parallel planes; common iff the other form restricted to that line is
// not definite). Other combinations (two proper conics, line pairs): a chart l.X = 1 of the
// projective plane whose line l.X = 0 holds no common point (nonzero resultant of the two
// binary forms there), then an exact real solution cover of the two conics in that chart:
// no box proves no common real point. A common point, or a cover that cannot decide, returns
// false: the caller keeps its answer undecided.
#pragma once

#include "surfcert/core/quadric.hpp"

#include <array>

namespace surfcert::certify {

/// True when proven: the real points at infinity of a and b are disjoint (then the minimum
/// distance is attained). False when they meet or when this test cannot decide.
bool minimum_attained(const core::QuadricMatrix& a, const core::QuadricMatrix& b);

/// Ternary quadratic forms x^T A x, x^T B x (symmetric, rational): true when proven to have no
/// common real zero in the projective plane (a chart and an exact solution cover, see above);
/// false when they have one or when this cannot be decided.
bool real_conics_disjoint(const std::array<std::array<core::Rational, 3>, 3>& a,
                          const std::array<std::array<core::Rational, 3>, 3>& b);

} // namespace surfcert::certify
