// surfcert::certify::implicit_pair_distance: the certified minimum distance between two bounded
// smooth implicit surfaces f = 0 and g = 0 of any degree (rational Poly3 coefficients; a torus
// enters as its quartic, an ellipsoid as its quadratic polynomial), by branch and bound over
// pairs of boxes and Krawczyk on the Lagrange system.
//
// Method (every decision by outward-rounded interval arithmetic or Arb balls, never a
// tolerance):
// 1. Boundedness: the leading form of each polynomial is proven definite on the faces of the
//    cube |x|_inf = 1 (interval bisection, a positive lower bound c of its modulus); then
//    f != 0 for |x|_inf > max(1, sum_k<d A_k / c) (A_k: sum of |coefficients| of degree k), a
//    box containing the zero set. Unprovable (odd degree, indefinite form): undecided.
// 2. Pairs of boxes (A, B), one octree per surface split lazily along the longest edge, are
//    dropped when 0 is not in f(A) (mean-value form) or g(B), when no pair in A x B can be
//    critical (a component of (A - B) x grad f(A) or (A - B) x grad g(B) excludes 0: at a
//    closest pair of smooth points p - q is normal to both surfaces; at singular points the
//    product vanishes too, so the test is sound), or when their box distance exceeds an upper
//    bound that comes from genuine surface points (a double guess p, 1-D interval Newton along
//    the gradient line proves a point of f = 0 in a small segment).
// 3. Surviving pairs at the resolution h are grouped into clusters (touching boxes); per
//    cluster Krawczyk (Arb) on the 8 unknowns (p, q, lambda, mu) of
//      p - q - lambda grad f(p) = 0, p - q + mu grad g(q) = 0, f(p) = 0, g(q) = 0
//    over a box X containing the cluster's hulls and the ranges of lambda, mu that any critical
//    pair in the hulls must have (lambda = (p - q).grad f / |grad f|^2, which needs grad f != 0
//    on the hull: smoothness proven). K(X) inside X proves one critical pair, hence the closest
//    pair in the cluster if any. Failed clusters are refined (h / 8) down to a floor, then the
//    answer is undecided. The proven pair is refined at the requested precision by Newton
//    steps in Arb and a Krawczyk test on a tiny box inside X (no further subdivision).
// 4. Contact: a pair of touching boxes triggers a witness search: one coordinate fixed at a
//    rational value, 2-D Krawczyk on (f, g) in the two others proves a common zero, distance 0
//    (minimizers "infinite": a curve of contact, or the touching point only; the pair reported
//    is that witness). Tangential contact without a witness: undecided with [0, upper].
// Invariants of the result: Certified means [lower, upper] contains the minimum distance between
// the surfaces (not the solids: nested surfaces have a positive distance), relative width
// <= 10^-digits, every reported pair a proven critical pair (Krawczyk) within the enclosure;
// several pairs whose distances are not separated are all reported with ties "unproven".
// method = "implicit_bnb". The work is bounded by a box budget, so nothing hangs.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/poly3.hpp"
#include "surfcert/core/torus.hpp"

namespace surfcert::certify {

/// f = 0 is surface a, g = 0 is surface b. Returns an Undecided result (never a guess) when
/// boundedness, smoothness, or separation of the minimum cannot be proven within the budget.
DistanceResult implicit_pair_distance(const core::Poly3& f, const core::Poly3& g, long digits);

/// f = 0 bounded (as above), g = 0 any smooth or singular surface, possibly unbounded (a
/// cylinder, cone, paraboloid, hyperboloid): g's zero set is taken inside the cube
/// |x|_inf <= Ta + c (Ta: f's bounding radius), and a certified answer is kept only when the
/// minimum is below c, since every point of g outside the cube is farther than c from f = 0
/// (c = 4, then twice the minimum found + 1, three attempts). f is surface a.
DistanceResult bounded_unbounded_distance(const core::Poly3& f, const core::Poly3& g, long digits);

/// The quartic of a ring torus (exact):
/// (|x-c|^2 + R^2 - r^2)^2 - 4 R^2 (|x-c|^2 - ((x-c).a)^2 / |a|^2).
core::Poly3 torus_polynomial(const core::Torus& t);

} // namespace surfcert::certify
