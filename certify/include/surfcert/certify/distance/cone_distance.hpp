// surfcert::certify::ellipsoid_cone_distance: a certified fast path for an ellipsoid and a
// (real, elliptic) quadratic cone that do not meet, through the cone's generator lines.
//
// The cone C = {x : (x - v)^T A (x - v) = 0} (A of signature (2, 1), vertex v) is the union
// of the lines L(t) = v + R g(t) whose directions g(t) run over the conic g^T A g = 0; with
// A = L D L^T (exact rational LDL^T after a coordinate permutation) they are
// g(t) = L^-T (cos(pi t)/sqrt(d_i), sin(pi t)/sqrt(d_j), 1/sqrt(-d_k)), t in [0, 2), one
// direction per line. Hence d(E, C) = min_t dist(E, L(t)), and for every unit n orthogonal to
// g(t) the slab bound n.v - h_E(n) <= dist(E, L(t)) (support function of the ellipsoid).
// Branch and bound on t: per interval n(t) is a fixed float direction n0 projected onto
// g(t)^perp (exactly orthogonal, as Arb balls), the lower bound the better of the interval
// extension and the mean-value form of t -> n(t).v - h_E(n(t)); upper bounds are genuine
// pairs (the support point of E and its foot on the line). A positive lower bound proves that
// E and C do not meet. Returns nullopt (the exact offset method answers) when the surfaces may
// meet, when the minimizers may form a continuum (coaxial surfaces of revolution: too many
// surviving intervals), beyond 25 digits (the float guidance is double), or when the cone is
// not of this form.
#pragma once

#include "surfcert/certify/distance/convex_quadric.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/quadric.hpp"

#include <optional>

namespace surfcert::certify {

/// e: the ellipsoid (convex_quadric(...) of kind Ellipsoid); cone: any quadric (nullopt when it
/// is not a real cone with a rational vertex); ellipsoid_first: query order of the pairs.
std::optional<DistanceResult> ellipsoid_cone_distance(const ConvexQuadric& e,
                                                      const core::QuadricMatrix& cone, long digits,
                                                      bool ellipsoid_first);

} // namespace surfcert::certify
