// surfcert::certify::ConvexQuadric: the convex solid of a real ellipsoid or a real elliptic
// cylinder, described by its support function, exactly.
//
// The solid is {x : (x - c)^T M (x - c) <= 1} with M positive definite (ellipsoid) or positive
// semidefinite of rank 2 with kernel spanned by `axis` (elliptic cylinder). We store the
// centre c (a point of the axis for a cylinder) and W with n^T W n = n^T M^+ n for every
// admissible direction n (all n for an ellipsoid, n . axis = 0 for a cylinder):
//   W = M^-1 (ellipsoid), W = k (A + axis axis^T)^-1 (cylinder; A = k M, see the .cpp).
// Then the support function is h(n) = n . c + sqrt(n^T W n) and the support point (the point of
// the surface where the outer normal is n) is p(n) = c + W n / sqrt(n^T W n); both are exact
// real numbers, enclosed here by Arb balls (so a ball support point contains a genuine surface
// point) or evaluated in double for the float searches that only choose where to certify.
// Invariants: c, W, axis are exact rationals; W is symmetric and positive definite; for a
// cylinder axis != 0 and every admissible n gives p(n) on the surface exactly.
#pragma once

#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/core/quadric.hpp"

#include <array>
#include <optional>

namespace surfcert::certify {

struct ConvexQuadric {
  std::array<core::Rational, 3> c;
  std::array<std::array<core::Rational, 3>, 3> W;
  std::optional<std::array<core::Rational, 3>> axis; ///< set for an elliptic cylinder
  std::array<double, 3> cd{};                        ///< c in double (float searches only)
  std::array<std::array<double, 3>, 3> Wd{};         ///< W in double (float searches only)
  bool is_cylinder() const { return axis.has_value(); }
};

/// The convex description of q when q is a real ellipsoid (spheres included) or a real
/// elliptic cylinder, decided exactly from the rational matrix; nullopt for every other
/// quadric (planes, cones, paraboloids, hyperboloids, imaginary or degenerate quadrics).
std::optional<ConvexQuadric> convex_quadric(const core::QuadricMatrix& q);

/// Float support function h(n) = n.c + sqrt(n^T W n) and support point (inexact: used only to
/// steer searches).
double support_float(const ConvexQuadric& s, const std::array<double, 3>& n);
std::array<double, 3> support_point_float(const ConvexQuadric& s, const std::array<double, 3>& n);

/// Certified h(n) for a ball direction n (admissible: n . axis = 0 for a cylinder, which the
/// caller guarantees exactly); also the support point when p != nullptr.
void support_ball(arb_t h, Ball (*p)[3], const ConvexQuadric& s, const Ball (&n)[3], long prec);

} // namespace surfcert::certify
