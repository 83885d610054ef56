// surfcert::certify::capsule_pair_distance: two capsules (canal surfaces with a straight spine
// segment and a constant radius) in closed form.
//
// A capsule solid is S + B(r) (segment S, closed ball of radius r), so for disjoint solids
//   dist = dist(S1, S2) - r1 - r2,
// and dist(S1, S2)^2 is an exact rational: the minimum of the convex quadratic
// |P(s) - Q(t)|^2 on [0, 1]^2 is attained at the interior stationary point or on an edge at a
// clamped projection, all rational candidates. Disjointness (dist(S1, S2) > r1 + r2) is decided
// by an exact comparison of squares; the square root is enclosed with Arb. The closest pair is
// unique unless the segments are parallel with overlapping projections ("infinite").
// Returns nullopt when either surface is not a capsule or the solids meet (the caller keeps
// its previous answer).
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

#include <optional>

namespace surfcert::certify {

std::optional<DistanceResult> capsule_pair_distance(const core::CanalSurface& a,
                                                    const core::CanalSurface& b, long digits);

} // namespace surfcert::certify
