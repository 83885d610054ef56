// surfcert::certify::ellipsoid_torus_fast: the certified distance between an ellipsoid E and a
// ring torus T when the solid E lies outside the solid torus, without elimination.
//
// With K the core circle (radius R) and r the tube radius, E misses the solid torus iff
// D = dist(E, K) > r, and then the surface distance is D - r. For a point x outside E,
// dist(x, E) = max over unit n of n.x - h_E(n) (support function h_E), so every direction n
// gives the certified lower bound n.K(tau) - h_E(n) for the points K(tau) of the circle
// (K(tau) = o + R (cos(pi tau) u + sin(pi tau) v), tau in [0, 2], u, v an orthonormal frame of
// the torus plane held as Arb balls). Branch and bound over tau: on an interval, n varies
// linearly with tau (n0 + (tau - tau0) n1, chosen in double as the optimal normal and its
// derivative), and the second-order Taylor form of the bound (value and slope at tau0, the
// second derivative enclosed over the interval) bounds it from below; the upper bound is a
// genuine pair, the support point p_E(n0) (an exact point of E, as a ball) and its exact
// distance to T. Intervals whose lower bound exceeds the best upper bound are dropped. Near a
// minimizer the bound is sharp to second order in the error of (tau0, n0); for many digits
// (tau0, n0) are refined by Newton in MPFR on the stationarity system and certified again at
// the working precision.
//
// It answers only what it proves: nullopt whenever E may meet (or enclose) the solid torus,
// whenever the minimizers may form a continuum (all of the circle alive, e.g. coaxial
// ellipsoids of revolution), or when the enclosure does not reach 10^-digits relative width.
// Reported: status Certified, the enclosure of D - r, one pair per cluster of surviving
// intervals (ties are listed, their equality not proven), eliminated_degree 0.
#pragma once

#include "surfcert/certify/distance/convex_quadric.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/torus.hpp"

#include <optional>

namespace surfcert::certify {

/// e must be an ellipsoid (e.is_ellipsoid(); nullopt otherwise). quadric_first: the ellipsoid
/// is the query's first surface (pairs in query order).
std::optional<DistanceResult> ellipsoid_torus_fast(const ConvexQuadric& e, const core::Torus& t,
                                                   long digits, bool quadric_first);

} // namespace surfcert::certify
