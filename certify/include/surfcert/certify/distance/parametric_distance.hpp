// surfcert::certify::parametric_distance: the certified distance between a rational
// parametric surface P(u, v) = (X, Y, Z) / W and another surface.
//
// The distance is taken to the CLOSURE of the parametrised surface, so the points a
// parametrisation misses count (seed 000's parametrised ellipsoid misses (0, 0, -6)). How: the
// implicit equation is found exactly by linear algebra (the coefficients of the F of degree
// <= 2 with F(X/W, Y/W, Z/W) W^2 = 0 identically: an integer nullspace, FLINT), and the
// implicit route answers; the missed points are the limits of P at infinity (top-degree parts:
// listed when they are a single point) and the note says whether a minimizer is one of them.
// Scope: parametrisations of planes and quadrics (implicit degree <= 2); others: undecided.
// The closure is assumed to be the whole real quadric (true for the usual stereographic and
// Bezier-type parametrisations; the note says so).
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

#include <optional>

namespace surfcert::certify {

/// The implicit quadric (or plane) of a parametric surface; nullopt when its degree is > 2
/// or the image is not a surface.
std::optional<core::QuadricMatrix> implicit_quadric(const core::ParametricSurface& p);

DistanceResult parametric_distance(const core::ParametricSurface& p, const core::Surface& other,
                                   long digits, bool parametric_first);

} // namespace surfcert::certify
