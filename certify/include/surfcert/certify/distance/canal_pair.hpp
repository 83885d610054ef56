// surfcert::certify::canal_pair_distance: the certified distance between two canal surfaces,
// or a canal surface and a ring torus, whose solids are disjoint.
//
// Both solids are unions of balls: a canal surface's B(C(t), r(t)), t in [t0, t1] (C, r
// rational polynomials), a torus's B(K(t), r) over its core circle K(t) = o + R (cos(pi t) u +
// sin(pi t) v), t in [0, 2). Two unions of balls are disjoint iff every pair of balls is, so with
//   F(s, t) = |C1(s) - C2(t)| - r1(s) - r2(t)
// the solids are disjoint iff min F > 0, and then the distance of the surfaces is min F (the
// closest points of disjoint solids lie on their boundaries). F is minimised by a branch and
// bound over parameter boxes (exact dyadic bisection): per box a certified lower bound (the
// better of the interval extension and the mean-value form F(m) + grad F(box).(box - m), Arb),
// F(m) as an upper bound (a value of F: the pair C1 + r1 w, C2 - r2 w lies in the solids, so it
// bounds the solid distance, which equals the surface distance once the solids are disjoint),
// boxes above the best upper bound dropped, until upper - lower <= 10^-digits lower.
// Surviving boxes are grouped (adjacent ones, across t = 0 = 2 for a torus); one pair per
// group; several groups are ties (proven by symmetry where possible, symmetry.hpp).
// Returns nullopt when the route does not apply: the lower bound is not positive (the solids
// may meet or nest), a radius may vanish, too many boxes survive (a continuum of minimizers,
// or a flat minimum), or the budget runs out. Never a guess.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

#include <optional>

namespace surfcert::certify {

/// a, b: canal surfaces or tori, at least one canal surface (two tori: torus_pair.hpp). The
/// first surface's point comes first in each pair.
std::optional<DistanceResult> canal_pair_distance(const core::Surface& a, const core::Surface& b,
                                                  long digits);

} // namespace surfcert::certify
