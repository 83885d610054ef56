// surfcert::certify::quadric_pair_distance: the certified minimum distance between two
// quadrics that do not meet, neither of them a sphere (the offset method, seed 000 eq. 2-6).
//
// Offset system over Z: with S1: f = 0 the source and S2: g = 0 the target, a closest pair
// (p, q) has q = p + mu grad f(p) and grad g(q) parallel to grad f(p). As g is quadratic,
// grad g(q) = X + mu Y with X = grad g(p), Y = Hess(g) grad f(p), so
//   f(p) = 0,  C(p) = det[grad f, X, Y] = 0,  G(p) = 2 g Q^2 - 2 (X.N) P Q + (N.Y) P^2 = 0
// where N = grad f, P = l.(N x X), Q = l.(N x Y) for a fixed integer vector l (mu = -P/Q, and
// P = Q = 0 keeps G = 0, so every closest p, singular or not, solves the system). The real
// solutions are covered by boxes (algebra::SolutionCover: FLINT resultants, exact isolation).
// Each box gets a certified LOWER bound for the distance of any closest pair with p in it (the
// real roots mu of g(p + mu N) = 0 over the box, in Arb; from the exact point-quadric sextic
// when grad f may vanish there), and the best boxes a certified UPPER bound from a genuine
// pair (a point of S1 near the box, the point of S2 on its normal line). Boxes are refined by
// exact bisection until upper - lower <= 10^-digits lower. Boxes whose lower bound exceeds
// the best upper bound are dropped (they cannot hold the minimum). Minimizers: the boxes left
// whose lower bound is <= the upper bound; equality of two minimal distances is not proven
// (noted), the distance enclosure is certified regardless.
// Preconditions: the quadrics do not meet (the caller decided it from the certified topology).
// If neither surface is bounded the minimum may not be attained: status undecided with the
// enclosure [0, upper].
#pragma once

#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/poly3.hpp"

namespace surfcert::certify {

/// The offset system is not attempted (undecided, at once) for a quadric whose quadratic part's
/// nonzero entries span more than 2^kOffsetMaxSpreadBits (semi-axes 2^200 apart): its
/// eliminants' isolation ran without end.
constexpr long kOffsetMaxSpreadBits = 400;

DistanceResult quadric_pair_distance(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                     long digits);

/// An implicit surface f = 0 of degree 3 to 6 against an ellipsoid: contact from the sign of
/// f at its critical points on the ellipsoid (certified points of both signs: they cross;
/// one sign everywhere: disjoint), then the same offset system with f as the source
/// (degrees n, 2n - 1, 4n - 2: practical for cubics, slow beyond). Other quadrics only when
/// f = 0 is proven bounded (definite leading form): disjoint when the quadric's equation has
/// one strict sign at its critical points on f = 0, or f the sign of its leading form at its
/// critical points on the quadric; a crossing from a certified point of the quadric inside
/// f = 0 (f = 0 may be disconnected, so both signs of the quadric's equation on it prove
/// nothing); otherwise undecided.
DistanceResult implicit_quadric_distance(const core::Poly3& f, const core::QuadricMatrix& q,
                                         long digits, bool implicit_first);

} // namespace surfcert::certify
