// surfcert::certify::separated_convex_distance: a certified fast path for two disjoint convex
// solids (ellipsoid, elliptic cylinder or elliptic paraboloid; at least one ellipsoid), by
// support-function duality.
//
// For every direction n, the slab between the supporting planes separates the solids:
//   L(n) = (-h_B(-n) - h_A(n)) / |n|  <=  dist(A, B),
// and the support points p_A(n), p_B(-n) are genuine surface points, so
//   U(n) = |p_B(-n) - p_A(n)|  >=  dist(A, B).
// At the optimal direction both are equal; the gap U - L is quadratic in the error of n. A
// float Newton search (double, then MPFR for more digits) only chooses n; the certificate is
// the Arb evaluation of L and U at that exact n. L > 0 proves the solids disjoint, hence the
// surfaces disjoint with the same distance (closest points of disjoint convex solids lie on
// their boundaries), and the closest pair is unique (an ellipsoid is strictly convex and the
// minimal difference vector of two convex sets is unique).
// Returns nullopt (the caller falls back to the exact offset method) when L > 0 cannot be
// certified or the gap does not reach the relative width 10^-digits: this path never decides
// anything it has not proven.
#pragma once

#include "surfcert/certify/distance/convex_quadric.hpp"
#include "surfcert/certify/distance/distance.hpp"

#include <optional>

namespace surfcert::certify {

std::optional<DistanceResult> separated_convex_distance(const ConvexQuadric& a,
                                                        const ConvexQuadric& b, long digits);

/// The same certificate for two ellipsoids (or spheres) posed in doubles (core::ShapeSpec),
/// straight from the doubles: the float search chooses n, and h, p are evaluated in Arb from
/// the exact doubles (the quaternion's polynomial rotation, its squared norm, the radii and
/// the centre as balls), never forming the exact rationals. The same answer and contract as
/// separated_convex_distance on convex_quadric() of the two shapes (the same exact solids);
/// nullopt whenever the double direction does not certify (then the caller runs that route,
/// which refines the direction in MPFR). *no_separation (when given) tells that the float
/// search found no separating direction at all (the solids clearly overlap or nest): the
/// exact route's search, on the same solids, would find none either. A hint for skipping
/// that route, never a claim: other routes answer such pairs.
std::optional<DistanceResult> separated_posed_ellipsoids(const core::ShapeSpec& a,
                                                         const core::ShapeSpec& b, long digits,
                                                         bool* no_separation = nullptr);

/// Float mode: the same search in double only, status Uncertified (lower = upper = the double
/// distance of the float pair, not an enclosure); nullopt when no separating direction is
/// found.
std::optional<DistanceResult> separated_convex_distance_float(const ConvexQuadric& a,
                                                              const ConvexQuadric& b);

} // namespace surfcert::certify
