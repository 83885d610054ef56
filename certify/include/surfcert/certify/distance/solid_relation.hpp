// surfcert::certify::solids_nested: for two CLOSED surfaces (ellipsoids, ring tori, canal
// surfaces) whose surfaces are known to be disjoint, whether one solid contains the other.
//
// With disjoint boundaries and connected solids, either one solid lies inside the other or the
// solids are disjoint (a connected boundary lies wholly inside or wholly outside the other
// solid). So one certified point of each boundary, tested for being inside the other solid,
// decides: a point of surface a inside solid b (or of b inside a) means nested; both outside
// means disjoint solids, whose distance is then the surface distance. Points are Arb balls
// holding a genuine surface point (an ellipsoid's axis point, a torus's outer equator point, a
// canal surface's support point in direction x, its parameter enclosed by a certified branch
// and bound); the tests are certified signs (ellipsoid and torus polynomials; for a canal
// surface the minimum over t of |p - C(t)|^2 - r(t)^2, by branch and bound with Arb).
// Anything not certified returns 0 (undecided), never a guess.
// The same holds when the surfaces touch at finitely many points without crossing (each
// surface minus those points is still connected and lies on one side of the other): then -1
// means the solids meet only at those points (the surface distance's count stands for the
// solids) and +1 a continuum of common points (apply_solid_option uses it so).
#pragma once

#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

namespace surfcert::certify {

/// True for the surfaces that bound a solid here: real ellipsoids, tori, canal surfaces.
bool is_closed_surface(const core::Surface& s);

/// Precondition: the surfaces are disjoint, or touch at finitely many points without crossing.
/// +1: one solid contains the other; -1: the solids are disjoint (meet only at the touching
/// points); 0: not decided (or a surface is not closed).
int solids_nested(const core::Surface& a, const core::Surface& b);

/// A ball holding the support point of the canal solid in the unit direction e (a genuine
/// point of the canal surface, on the boundary of the unbounded complement); false when not
/// enclosed.
bool canal_support_point(const core::CanalSurface& c, const std::array<core::Rational, 3>& e,
                         Ball (&p)[3]);

/// The certified side of the ball point p (which must not meet the surface for an answer):
/// -1 inside a closed surface's solid (or where a quadric's or implicit polynomial is
/// negative), +1 outside (positive), 0 not certified. The surface is the zero set of a
/// continuous function with exactly these signs, so a sign change along a path meets it.
int side_of(const core::Surface& s, const Ball (&p)[3]);

/// Applies the `solid` option to a certified surface distance r between closed surfaces:
/// nested solids give 0, disjoint solids keep r, undecided nesting makes r undecided with the
/// enclosure [0, upper]. Meeting surfaces (distance 0) stay 0. A plane bounds no solid (its
/// solid is the plane itself, as a collision library's plane): against a closed surface or a
/// plane the solid distance is the surface distance (a plane meeting a bounded solid crosses
/// its boundary). Any other surface's solid is not modelled: r becomes undecided with
/// [0, upper] unless it is 0.
void apply_solid_option(DistanceResult& r, const core::Surface& a, const core::Surface& b);

} // namespace surfcert::certify
