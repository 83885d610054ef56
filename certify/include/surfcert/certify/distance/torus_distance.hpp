// surfcert::certify::quadric_torus_distance: the certified minimum distance between a quadric
// S1 and a ring torus T (the tube of radius r around the circle K of radius R).
//
// A sphere: its centre's critical distances to T are |D - r| and D + r for the distances D to
// the nearest and farthest points of K (closed form, Arb); the sphere meets T iff its radius
// lies between the smallest and the largest (T is connected), else d = d_min - rho or
// rho - d_max; a centre on the axis (or on K) gives a circle of minimizers.
// Any other quadric: the offset system of seed 000 §3.5 in general position: the normal line
// of S1 at p is coplanar with the axis, det[grad f, p - c, a] = 0, and meets K,
// |(N.a)(p - c) - ((p - c).a) N|^2 = R^2 (N.a)^2, with f = 0 (degrees 2, 2, 4); its real
// solutions are covered by boxes and refined by minimize_over_cover with the exact point-torus
// distance |dist(p, K) - r| as lower and upper bound. Contact first: the critical values of
// the torus quartic on S1 (same machinery) decide whether S1 has points inside and outside
// the solid torus (every component of a non-ellipsoid quadric is unbounded, hence reaches the
// outside); a critical value not separated from 0 (touching) leaves the answer undecided.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/poly3.hpp"
#include "surfcert/core/torus.hpp"

namespace surfcert::certify {

/// quadric_first: the quadric is the query's first surface (pairs reported in query order).
/// A (non-spherical, non-coaxial) ellipsoid outside the solid torus is answered by
/// ellipsoid_torus_fast (torus_fast.hpp) when it proves its enclosure, else by the methods above.
DistanceResult quadric_torus_distance(const core::QuadricMatrix& q, const core::Torus& t,
                                      long digits, bool quadric_first);

/// The methods above only (closed forms, contact test, offset system): the independent route
/// the fast path is tested against.
DistanceResult quadric_torus_distance_exact(const core::QuadricMatrix& q, const core::Torus& t,
                                            long digits, bool quadric_first);

/// An implicit surface f = 0 (degree 3 to 6) against a ring torus: disjointness from T > 0 at
/// every critical point of the torus equation T on f = 0 (T's least value on each component),
/// then the same offset system with f as the source; undecided otherwise (the caller's
/// contact proofs may still show that they meet).
DistanceResult implicit_torus_distance(const core::Poly3& f, const core::Torus& t, long digits,
                                       bool implicit_first);

} // namespace surfcert::certify
