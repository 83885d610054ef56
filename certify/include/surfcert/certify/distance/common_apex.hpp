// surfcert::certify::common_apex_contact: two quadrics sharing a real affine singular point p
// (two cones with one apex, a cone and a plane pair through it, ...). Their pencil is then
// degenerate (every member is singular at p), so the projective classification says nothing;
// but they meet at p: the distance is 0, with p as an exact witness.
//
// The minimizer set is p together with the common real lines through p: both equations are
// quadratic forms in x - p, so a common point x != p brings its whole line. Decided exactly:
// - only p when the two direction conics (the 3x3 blocks as conics of the projective plane)
//   have no common real point (at_infinity.hpp: a chart and an exact solution cover);
// - lines when one form takes both signs (Arb) at certified points of the other's real
//   direction conic (a real conic of the projective plane is connected and the forms are even),
//   or when a member B - lambda A of rank 1 (lambda a rational root of det(B - lambda A), or A
//   or B itself) is a double line meeting the other conic in real points (a tangency along a
//   common line, which no sign change sees).
// Neither: status undecided with the exact enclosure [0, 0] (the minimizer set is open).
// nullopt when there is no common real affine singular point.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/quadric.hpp"

#include <optional>

namespace surfcert::certify {

std::optional<DistanceResult> common_apex_contact(const core::QuadricMatrix& a,
                                                  const core::QuadricMatrix& b);

} // namespace surfcert::certify
