// surfcert::certify::cylinder_pair_distance: the certified distance between two real elliptic
// cylinders (ConvexQuadric kind Cylinder) whose solids are disjoint.
//
// Crossed axes a, b (a x b != 0): the only direction along which both support functions are
// finite is n = a x b (up to sign), so by support-function duality (the distance of disjoint
// closed convex sets is the best slab width)
//   d = (|n.(c_B - c_A)| - sqrt(n^T W_A n) - sqrt(n^T W_B n)) / |n|
// when positive, decided exactly (squares of rationals) and enclosed with Arb; the closest
// pair is unique: the common perpendicular of the two support lines (parallel to a and b).
// If the bracket is <= 0 the solids overlap, and since neither solid can contain the other
// their surfaces meet: nullopt, and the caller's exact topology gives the witness.
// Parallel axes: the cross-sections are two ellipses in one plane; the separated convex duality
// (convex_distance.hpp) over the directions orthogonal to the axis gives d, and the closest
// pairs form a line (minimizers "infinite"). nullopt when not certified.
#pragma once

#include "surfcert/certify/distance/convex_quadric.hpp"
#include "surfcert/certify/distance/distance.hpp"

#include <optional>

namespace surfcert::certify {

std::optional<DistanceResult> cylinder_pair_distance(const ConvexQuadric& a, const ConvexQuadric& b,
                                                     long digits);

} // namespace surfcert::certify
