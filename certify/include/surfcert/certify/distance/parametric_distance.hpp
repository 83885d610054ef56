// surfcert::certify::parametric_distance: the certified distance between a rational
// parametric surface P(u, v) = (X, Y, Z) / W and another surface.
//
// The distance is taken to the CLOSURE of the parametrised surface, so the points a
// parametrisation misses count (seed 000's parametrised ellipsoid misses (0, 0, -6)). How: the
// implicit equation F is found exactly by linear algebra (the F of least degree <= 6 with
// F(X/W, Y/W, Z/W) W^deg = 0 identically: an integer nullspace, FLINT), and the implicit
// surface's distance is computed by the usual routes, in the caller's mode and with its solid
// option. The image may cover only part of F = 0 (u^2 covers x >= 0 only), so that distance
// is only a certified LOWER bound here. Certified answers need, in addition, a certified upper
// bound: an exact image point q = P(u, v) (rational u, v proposed by a float search; near a
// missed point, P(2^k dir) tending to it) and a point y of the other surface proven by an exact
// sign change of its polynomial on a short ray segment from q, with |q - y| within the
// requested relative width of the lower bound. Distance 0 needs an exact sign change of the
// other surface's polynomial between two image points on a parameter segment with W nonzero
// on it (or, solid, an exact image point inside the other solid). Floats never decide; without
// such a witness the answer is undecided, keeping the implicit lower bound. Minimizer counts
// are those of the implicit minimizers that have a witness (membership not proven).
// Scope: implicit degree <= 6; the other surface a quadric, implicit surface or torus (a
// canal surface has no polynomial here: undecided); two parametric surfaces: undecided.
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

/// p against other (p the first surface when parametric_first: pairs are ordered so); mode and
/// solid are those of surface_distance and are passed to the implicit surface's routes.
DistanceResult parametric_distance(const core::ParametricSurface& p, const core::Surface& other,
                                   long digits, bool parametric_first, Mode mode, bool solid);

} // namespace surfcert::certify
