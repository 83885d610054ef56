// surfcert::certify::sphere_quadric_gap: the certified distance between a sphere |x - c| = r
// (r >= 0: r = 0 is the point c) and a quadric that does not meet it, from the exact
// point-quadric critical distances of c (point_quadric.hpp).
//
// The answer is d_min - r (the quadric outside the ball) or r - d_max (a compact quadric
// inside it), each extreme enclosed over EVERY candidate; which side holds is decided on those
// enclosures. More digits narrow the same exact roots until the side is decided, the gap meets
// the width contract despite cancellation, and the minimizers separate or are proven tied (the
// same exact rational squared distance); what fails within its budget is undecided (the note
// says which). Contract for the caller: the sphere and the quadric are proven disjoint (for
// r = 0: c is proven not on the quadric), the quadric has a nonzero quadratic part, and r2 is
// the exact squared radius. Pairs are (sphere point, foot) when sphere_first, approximate.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/quadric.hpp"

#include <array>

namespace surfcert::certify {

DistanceResult sphere_quadric_gap(const std::array<core::Rational, 3>& c, const core::Rational& r2,
                                  const core::QuadricMatrix& other, long digits, bool sphere_first);

} // namespace surfcert::certify
