// surfcert::certify::plane_quadric_distance: the certified distance between a plane and any
// quadric (another plane included), decided exactly.
//
// With the plane n.x = delta and l(x) = n.x - delta, the quadric meets the parallel plane
// l = s iff the conic q_s(u, v) (the quadric restricted to that plane, in a rational basis
// e1, e2 of n-perp) has a real point. Its quadratic part A is the same for every s; only the
// linear part g(s) (affine in s) and the constant f(s) (quadratic in s) move. So the set S of
// levels s met by the quadric is decided exactly:
// - A indefinite: every level is met (the surfaces meet);
// - A definite (sign normalised to positive): S = {m(s) <= 0}, m = f - g^T A^-1 g (the
//   minimum of q_s, degree <= 2 in s), one tangency point per boundary level;
// - A of rank 1 (kernel k): if g.k is not identically 0 every level but its root is met; else
//   S = {f - (g.w)^2 / a <= 0} and each boundary level touches along a line;
// - A = 0: if g is not identically 0 every level but the common root of g is met; else
//   S = {f(s) = 0} (parallel planes, or a pair of planes), each met along a whole plane.
// d = inf {|s| : s in S} / |n|: 0 (with a witness point) when 0 is in S; otherwise the least
// |root| of a polynomial of degree <= 2 over Q (which root is nearer 0, and whether two are
// equally near, is decided by rational signs), enclosed with Arb to 10^-digits. When S misses
// 0 but comes arbitrarily close (the surfaces approach each other at infinity) the distance is
// the infimum 0, not attained (minimizers "0"). Everything is exact; no tolerance decides.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/quadric.hpp"

namespace surfcert::certify {

/// `plane` must satisfy is_plane(). plane_first: the plane is surface a (its points first).
DistanceResult plane_quadric_distance(const core::QuadricMatrix& plane,
                                      const core::QuadricMatrix& q, long digits, bool plane_first);

} // namespace surfcert::certify
