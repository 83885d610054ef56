// surfcert::app claim geometry: the certified facts about claimed points that verify's
// closest_points and curve claims are decided from (verify.hpp).
//
// What it holds, each a proof the caller of verify can re-check with exact arithmetic:
//   - surface_value: the exact value at a rational point of a polynomial whose real zero set
//     is the surface (a quadric, a ring torus's quartic, an implicit surface); nullopt for
//     canal and parametric surfaces.
//   - SurfaceWitness: a segment [from, to] with rational ends at which that polynomial takes
//     values of opposite signs (or 0), so a point of the surface lies on the segment.
//   - point_surface_distance: bounds of the distance from a rational point to a quadric
//     (point_quadric.hpp; planes in closed form) or a ring torus (closed form), both in Arb.
//   - CurveWitness: a box (rational centre, rational half-width per axis) proven by a
//     Krawczyk test to hold exactly one point of the intersection of two quadrics in the
//     plane x_k = centre_k (k = fixed_axis), so it holds a point of the curve.
//   - segment distances: exact squared distance from a rational point to a segment.
//   - prove_coverage: a subdivision proving every point of a ∩ b in a box within tol of
//     claimed segments (the "confirmed" side of a curve claim).
// Floats only propose (Newton steps, gradients); every returned fact is decided exactly or in
// ball arithmetic. A nullopt means "not found", never "false".
#pragma once

#include "surfcert/core/quadric.hpp"
#include "surfcert/core/rational.hpp"
#include "surfcert/core/surface.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace surfcert::app {

using RPoint = std::array<core::Rational, 3>;

/// |p - q|^2, exactly.
core::Rational dist2(const RPoint& p, const RPoint& q);

/// The exact value at p of the surface's defining polynomial (see above); nullopt when the
/// surface has none whose zero set is the surface (canal, parametric).
std::optional<core::Rational> surface_value(const core::Surface& s, const RPoint& p);

struct SurfaceWitness {
  RPoint from, to; ///< surface_value(from) * surface_value(to) <= 0
};

/// A witness segment starting at p whose far end lies within sqrt(reach2) of p (so a point of
/// the surface lies within sqrt(reach2) of p); p itself when the value at p is exactly 0.
std::optional<SurfaceWitness> surface_witness(const core::Surface& s, const RPoint& p,
                                              const core::Rational& reach2);

/// Proven bounds lo <= d <= hi of a distance, as printed decimals (rounded outward) and as the
/// exact rationals they denote.
struct DistanceBounds {
  std::string lower, upper;
  core::Rational lo, hi;
};

/// Bounds of the distance from p to the surface (quadrics with a real point, ring tori);
/// nullopt for the other kinds or when they are not established.
std::optional<DistanceBounds> point_surface_distance(const core::Surface& s, const RPoint& p,
                                                     long digits);

struct CurveWitness {
  RPoint centre;
  core::Rational half_width; ///< the box is centre +- half_width on the two free axes
  int fixed_axis = 0;        ///< the box is flat in this coordinate
};

/// A certified point of a ∩ b near the approximate point p (Newton in the plane through p
/// orthogonal to the axis along which the curve's tangent is largest, then a Krawczyk test
/// in ball arithmetic); nullopt when the test fails (singular or tangential points, p far
/// from the curve).
std::optional<CurveWitness> curve_witness(const core::QuadricMatrix& a,
                                          const core::QuadricMatrix& b,
                                          const std::array<double, 3>& p);

/// The exact squared distance from p to the segment [s, t] (a point when s == t).
core::Rational segment_dist2(const RPoint& p, const RPoint& s, const RPoint& t);

/// sqrt(a) + sqrt(b) <= t for a, b >= 0, decided exactly (false when t < 0).
bool sqrt_sum_within(const core::Rational& a, const core::Rational& b, const core::Rational& t);

/// sqrt(u) + t < sqrt(v) for u, v, t >= 0, decided exactly.
bool sqrt_plus_less(const core::Rational& u, const core::Rational& t, const core::Rational& v);

} // namespace surfcert::app

namespace surfcert::app {

/// An axis-aligned box [lo_i, hi_i] with double (exact dyadic) bounds.
using DBox = std::array<std::array<double, 2>, 3>;

/// A box holding every real point of the quadric when it is a real ellipsoid (its exact
/// extents, rounded outward to doubles); nullopt otherwise.
std::optional<DBox> ellipsoid_bounding_box(const core::QuadricMatrix& q);

struct Coverage {
  bool proven = false; ///< every real point of a ∩ b in the box is within tol of a segment
  long boxes = 0;      ///< boxes examined
  /// When it stopped at a box too small to split: its centre, a float point close to both
  /// surfaces and farther than about tol from the claim (a candidate for a certified missed
  /// point); nullopt otherwise.
  std::optional<std::array<double, 3>> stuck;
};

/// Subdivision of `box`: each piece either has an enclosure of a's or b's equation (centred
/// form, Arb) without 0, or lies within tol of one segment of the polylines (decided exactly
/// from its centre and half-diagonal); gives up (proven = false) after max_boxes pieces or at
/// a piece too small to split (depth first: a point the claim misses is reached quickly).
/// Calls core::check_budget() as it goes.
Coverage prove_coverage(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                        const std::vector<std::vector<RPoint>>& lines, const core::Rational& tol,
                        const DBox& box, long max_boxes);

} // namespace surfcert::app
