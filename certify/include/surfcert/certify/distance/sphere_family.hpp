// surfcert::certify::sphere_family_distance: the certified distance between two surfaces that
// are boundaries of one-parameter unions of balls (canal surfaces and ring tori), when their
// solids are disjoint.
//
// A canal surface's solid is the union of B(C(s), r(s)), s in [s0, s1] (C, r rational
// polynomials; r > 0 on the whole interval is certified by an Arb bisection, otherwise the route
// refuses); a ring torus's is the union of B(K(s), r) over its core circle K(s) = o + R (cos(pi s)
// u + sin(pi s) v), s in [0, 2), periodic. Two unions of balls are disjoint iff every pair of
// balls is, so with
//   F(s, t) = |C1(s) - C2(t)| - r1(s) - r2(t)
// min F > 0 proves the solids disjoint, and then it is the distance of the surfaces. Invariants
// of the answer:
// - lower/upper enclose min F with relative width <= 10^-digits; every lower bound is certified
//   (Arb: interval extension or the mean-value form over a parameter box), every upper bound is
//   a value of F at an exact parameter point (the pair C1 + r1 u, C2 - r2 u lies in the solids);
// - a 2-D branch and bound (exact dyadic boxes) runs to about 10 digits; every cluster of
//   surviving boxes is then proven to hold one candidate where possible (Krawczyk on grad F = 0
//   for an interior minimum, on the 1-D restriction for a minimum on an edge where the normal
//   derivative has a certified sign, a corner directly) and refined by Arb Newton steps at
//   doubling precision; clusters that resist the proof are bisected on to the full precision;
// - one pair (point on a, point on b) per cluster that can hold the minimum; several clusters
//   are reported as unproven ties (note_unproven_ties).
// Returns nullopt when the route does not apply: a surface is neither a canal surface nor a
// torus, a radius may vanish, the lower bound cannot be made positive (the solids may meet or
// nest), too many boxes survive (a continuum or a flat minimum) or the budget runs out. Never a
// guess.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

#include <optional>

namespace surfcert::certify {

/// Disjoint canal surfaces / tori as unions of balls. nullopt when the route does not apply
/// (e.g. the lower bound is not positive), so the caller can try another route. a and b: each a
/// CanalSurface or a Torus; the point on a comes first in each pair.
std::optional<DistanceResult> sphere_family_distance(const core::Surface& a, const core::Surface& b,
                                                     long digits);

} // namespace surfcert::certify
