// surfcert::certify::nested_convex_distance: a certified fast path for the distance between
// the surfaces of two NESTED convex solids, an ellipsoid strictly inside another ellipsoid or
// inside an elliptic cylinder.
//
// For convex solids A inside B, a point a of A lies at distance min_n (h_B(n) - n.a) from the
// boundary of B (n over the unit directions, h the support function); that distance is
// concave in a, so its minimum over A is reached on the boundary of A, and swapping the minima
//   d(boundary A, boundary B) = min_{|n| = 1} F(n),   F(n) = h_B(n) - h_A(n).
// F > 0 on every direction proves A inside the interior of B. For a cylinder B only the
// directions orthogonal to its axis count (h_B is infinite elsewhere). The closest pairs are
// (p_A(n*), p_A(n*) + d n*) at the global minimizers n* (p_A the support point), one pair per
// minimizing direction since an ellipsoid is strictly convex.
// F is not convex (seed 000's pair has a decoy critical value 1 beside the minimum 0.5302...
// reached twice), so the minimum is found by a certified global search over the cube-face
// charts of the direction sphere (four charts of the circle for a cylinder), on which
//   G(u) = F(n(u)) / |n(u)| = (l(u) + sqrt(Qo(u)) - sqrt(Qi(u))) / sqrt(N(u))
// with l affine and Qo, Qi, N exact quadratic polynomials of the chart coordinates u:
// - a float grid and Newton search only picks a direction; G there is a certified upper bound;
// - an ellipsoid inside an ellipsoid first tries a Lagrangian (S-lemma) certificate: with the
//   float minimizer's KKT multipliers, Lag = |p - q|^2 + lambda g_in(p) - mu g_out(q) <=
//   |p - q|^2 on every pair with p in the inner solid and q outside the outer one; an interval
//   Cholesky proving its Hessian >= 2 s I confines every pair at distance <= the upper bound,
//   hence every direction with G <= it, to one tiny chart box, which the Krawczyk test proves
//   to hold a single critical point: the unique minimizer (about 99% of random nested pairs;
//   the others, where the relaxation is not tight or there are several minima, go on to the
//   branch and bound);
// - branch and bound in outward-rounded double intervals (CGAL::Interval_nt): per box a cubic
//   Taylor model of G at the box centre with a rigorous remainder drops boxes above the upper
//   bound (the children of a split box first by their parent's model, valid on them too),
//   derivative enclosures drop boxes without critical point, and the Krawczyk test proves the
//   boxes left to hold exactly one critical point;
// - each proven box that can hold the minimum is contracted (Krawczyk / interval Newton,
//   quadratic convergence), first in double intervals, then its value enclosed by the mean-value
//   form (G at a point in Arb at bits_for(digits + 10), the gradient over the box in double
//   intervals) or, when that is not within the relative width 10^-digits, contracted in Arb
//   until it is.
// d is the least of those critical values: every minimizer is a critical point, and every
// dropped box has G above a genuine value of G on it, or no critical point. Every critical
// direction whose enclosure meets the optimal one is a reported minimizer (their equality is not
// proven when there are several); a positive lower bound also proves the strict nesting. Returns
// nullopt (the caller falls back to the exact offset method) when the pair is not strictly nested,
// the kinds do not fit (two cylinders, paraboloids), or anything cannot be proven: continua of
// minimizers (concentric spheres, coaxial surfaces of revolution) exhaust the box budget instead.
#pragma once

#include "surfcert/certify/distance/convex_quadric.hpp"
#include "surfcert/certify/distance/distance.hpp"

#include <optional>

namespace surfcert::certify {

/// The certified surface distance when one solid lies strictly inside the other (either
/// order; the first surface's point comes first in each pair), nullopt otherwise or when not
/// proven.
std::optional<DistanceResult> nested_convex_distance(const ConvexQuadric& a, const ConvexQuadric& b,
                                                     long digits);

/// The same for two ellipsoids posed in doubles (spheres included), with their support
/// matrices enclosed in Arb straight from the doubles (posed_support_balls): the same exact
/// surfaces and the same certificate, without forming the exact rational W.
std::optional<DistanceResult> nested_posed_ellipsoids(const core::ShapeSpec& a,
                                                      const core::ShapeSpec& b, long digits);

} // namespace surfcert::certify
