// surfcert::certify::ConvexQuadric: the convex solid of a real ellipsoid, a real elliptic
// cylinder or an elliptic paraboloid, described by its support function, exactly.
//
// Ellipsoid / cylinder: the solid is {x : (x - c)^T M (x - c) <= 1} with M positive definite
// (ellipsoid) or positive semidefinite of rank 2 with kernel spanned by `axis` (cylinder). We
// store the centre c (a point of the axis for a cylinder) and W with n^T W n = n^T M^+ n for
// every admissible direction n (all n for an ellipsoid, n . axis = 0 for a cylinder):
//   W = M^-1 (ellipsoid), W = k (A + axis axis^T)^-1 (cylinder; A = k M, see the .cpp).
// Then h(n) = n . c + sqrt(n^T W n) and p(n) = c + W n / sqrt(n^T W n).
// Paraboloid: f = x^T A x + 2 b.x + e with A positive semidefinite of rank 2, kernel `axis`
// = a, a.b != 0; the solid is f <= 0. With P = A^+ (stored in W), the support function is
//   h(n) = (a.b) n^T P n / (2 n.a) - n.P b + (b^T P b - e) (n.a) / (2 a.b)
// for the admissible n, (n.a) / (a.b) > 0 (an open half-space; h = +inf elsewhere), and the
// support point is p(n) = y + t a with y = s P n - P b, s = (a.b) / (n.a),
// t = -(s n.y + b.y + e) / (2 a.b) (Lagrange: n = 2 mu grad f).
// h and p are exact real numbers, enclosed here by Arb balls (a ball support point contains a
// genuine surface point), or evaluated in double for the float searches that only choose where
// to certify.
// Invariants: every stored number is an exact rational; W is symmetric, positive definite for
// an ellipsoid or cylinder and equal to A^+ (rank 2) for a paraboloid; axis != 0 when set.
#pragma once

#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/core/quadric.hpp"

#include <array>
#include <optional>

namespace surfcert::certify {

struct ConvexQuadric {
  enum class Kind { Ellipsoid, Cylinder, Paraboloid };
  Kind kind = Kind::Ellipsoid;
  std::array<core::Rational, 3> c; ///< centre (ellipsoid, cylinder)
  std::array<std::array<core::Rational, 3>, 3> W;
  std::optional<std::array<core::Rational, 3>> axis; ///< cylinder, paraboloid
  // Paraboloid only: b, e of f, P b, a.b, and the two coefficients (a.b)/2, (b^T P b - e)/(2 a.b).
  std::array<core::Rational, 3> b, Pb;
  core::Rational e, ab, alpha, gamma;
  std::array<double, 3> cd{}, bd{}, Pbd{}, ad{}; ///< doubles (float searches only)
  std::array<std::array<double, 3>, 3> Wd{};     ///< W in double (float searches only)
  double ed = 0, abd = 0, alphad = 0, gammad = 0;
  bool is_cylinder() const { return kind == Kind::Cylinder; }
  bool is_ellipsoid() const { return kind == Kind::Ellipsoid; }
  bool is_paraboloid() const { return kind == Kind::Paraboloid; }
};

/// The convex description of q when q is a real ellipsoid (spheres included), a real
/// elliptic cylinder or an elliptic paraboloid, decided exactly from the rational matrix (for
/// an ellipsoid posed in doubles, core::ShapeSpec, by its type and built from its doubles in
/// exact dyadic arithmetic: the same exact c and W); nullopt for every other quadric (planes,
/// cones, hyperbolic paraboloids, hyperboloids, imaginary or degenerate quadrics).
std::optional<ConvexQuadric> convex_quadric(const core::QuadricMatrix& q);

/// The kind convex_quadric(q) would give (nullopt when it gives nothing), without computing
/// the description when q is a shape posed in doubles (decided by its type: what routes'
/// applicability tests need).
std::optional<ConvexQuadric::Kind> convex_kind(const core::QuadricMatrix& q);

/// Float support function and support point (inexact: used only to steer searches); +inf
/// (and a nan point) outside a paraboloid's admissible half-space.
double support_float(const ConvexQuadric& s, const std::array<double, 3>& n);
std::array<double, 3> support_point_float(const ConvexQuadric& s, const std::array<double, 3>& n);

/// Certified h(n) for a ball direction n (admissible: n . axis = 0 for a cylinder, which the
/// caller guarantees exactly); also the support point when p != nullptr. For a paraboloid,
/// h is set to an indeterminate (non-finite) ball unless n is certified admissible.
void support_ball(arb_t h, Ball (*p)[3], const ConvexQuadric& s, const Ball (&n)[3], long prec);

/// For an ellipsoid posed in doubles: its exact support matrix W = R D^2 R^T (the W of
/// convex_quadric) enclosed in Arb balls at prec straight from the doubles (exact dyadic
/// numerators, one rounded division each: no canonical rationals, whose gcds dominate
/// convex_quadric's cost), and Wd, its doubles (the balls' midpoints).
void posed_support_balls(Ball (&W)[3][3], std::array<std::array<double, 3>, 3>& Wd,
                         const core::ShapeSpec& sp, long prec);

} // namespace surfcert::certify
