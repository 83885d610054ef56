// surfcert::certify::plane_pair_distance: the distance between a rational plane pair (a quadric
// that splits over Q into two real planes: z^2 = 1, x y = 0, (x - 1)(y + 2z) = 0) and another
// quadric, as the smaller of the two plane distances.
//
// The pair's surface is the union of its planes P1, P2, so d = min(d(P1, S), d(P2, S)), each
// answered by the plane routes (closed forms, exact). Decided exactly on the enclosures: one
// strictly below the other gives that plane's answer (its pairs and minimizer count); both 0
// is contact (a continuum if either plane meets S in a curve, else the count is undecided: the
// planes' contact points may coincide on their common line); overlapping positive enclosures
// give their hull's minimum (certified) with the count undecided and the ties unproven — a
// symmetric position (an ellipsoid midway between z = +-1) is such a tie. An undecided plane
// keeps the answer undecided with the bounds that hold for the minimum. nullopt when the
// quadric is no rational plane pair, when the other is a plane or plane pair, or for a solid
// query (the slab between two parallel planes is a solid: not modelled here).
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/quadric.hpp"

#include <optional>

namespace surfcert::certify {

/// `pair` the plane pair, `other` the second quadric; `pair_is_a`: the pair is the query's
/// first surface (pairs are oriented (point on a, point on b)).
std::optional<DistanceResult> plane_pair_distance(const core::QuadricMatrix& pair,
                                                  const core::QuadricMatrix& other, bool pair_is_a,
                                                  long digits, Mode mode);

} // namespace surfcert::certify
