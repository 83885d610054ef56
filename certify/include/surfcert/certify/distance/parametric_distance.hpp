// surfcert::certify::parametric_distance: the certified distance between a rational
// parametric surface P(u, v) = (X, Y, Z) / W and another surface.
//
// The distance is taken to the CLOSURE of the parametrised surface, so the points a
// parametrisation misses count (seed 000's parametrised ellipsoid misses (0, 0, -6)). How: the
// implicit equation is found exactly by linear algebra (the coefficients of the F of degree
// <= 2 with F(X/W, Y/W, Z/W) W^2 = 0 identically: an integer nullspace, FLINT), and the
// implicit route answers; the missed points are the limits of P at infinity (top-degree parts:
// listed when they are a single point) and the note says whether a minimizer is one of them.
// Scope: implicit degree <= 6 (planes and quadrics go to the quadric routes, degree 3 to 6 to
// the implicit-surface routes); higher degrees: undecided.
// The closure is assumed to be the whole real quadric (true for the usual stereographic and
// Bezier-type parametrisations; the note says so).
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

#include <optional>

namespace surfcert::certify {

/// The implicit equation of least degree (<= max_degree) of a parametric surface, exact (the
/// one-dimensional integer nullspace of the substitution map, content removed); nullopt when
/// the degree exceeds max_degree or the image is not a surface.
std::optional<core::Poly3> implicit_polynomial(const core::ParametricSurface& p, int max_degree);

/// The implicit quadric (or plane) of a parametric surface; nullopt when its degree is > 2
/// or the image is not a surface.
std::optional<core::QuadricMatrix> implicit_quadric(const core::ParametricSurface& p);

DistanceResult parametric_distance(const core::ParametricSurface& p, const core::Surface& other,
                                   long digits, bool parametric_first);

} // namespace surfcert::certify
