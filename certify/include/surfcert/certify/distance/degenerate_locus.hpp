// surfcert::certify::real_locus and line_quadric_distance: degenerate quadrics whose real
// points form a plane, a line or a single point, decided exactly, and the distance from such a
// line to another quadric.
//
// A quadric X^T M X = 0 (X = (x, y, z, 1)) with M semidefinite has as real points exactly the
// affine points of ker M (X^T M X = 0 iff M X = 0 for semidefinite M). Decided over Q (inertia
// by LDL^T, kernel by FLINT's nullspace), real_locus reports:
// - Plane: rank 1, M = k v v^T, the double plane (v . X)^2 = 0, whose real points are the
//   plane v . X = 0 (v is a row of M);
// - Line: rank 2 semidefinite, the kernel a projective line whose affine part is the real line
//   p + t d (p from a kernel vector with w != 0, d from one with w = 0): x^2 + y^2 = 0 is the
//   z-axis, (x + 2y - z)^2 + (y - 3z + 1)^2 = 0 a line in general pose;
// - Point: rank 3 semidefinite, the kernel's affine point (x^2 + y^2 + z^2 = 0);
// - Other: anything else — an indefinite matrix, rank 4, a plane (is_plane: it has its own
//   routes), a posed shape (never degenerate), or a semidefinite quadric whose kernel lies at
//   infinity (no real point: the registry says so before any route).
// p, d and the plane are exact rationals (d an integer vector); no tolerance is involved.
//
// line_quadric_distance(line, S): d(L, S) = the distance in the plane orthogonal to d from the
// projected line (one point) to the projection of S, its shadow. With S: g(x) = 0 and
// g(x + t d) = a t^2 + b(x) t + g(x) (a = d^T A d, b affine), exactly:
// - a != 0: the shadow is {disc >= 0}, disc(x) = b(x)^2 - 4 a g(x), a quadric cylinder Z along
//   d (matrix B B^T - 4 a M). disc(p) >= 0: the line meets S (two points, or one tangency:
//   distance 0, count exact). Otherwise d(L, S) = d(p, Z) (the nearest shadow point lies on
//   its boundary), from the exact point-quadric critical distances (sphere_gap.hpp with r = 0)
//   or, when Z is a plane (a parabolic cylinder's shadow is a half-plane), in closed form. Each
//   nearest point of Z lifts to exactly one point of S (a double root along d), so the count
//   carries over; the pairs are the feet moved along d to that point.
// - a = 0 (d an asymptotic direction of S), b not constant: the line meets S once when
//   b(p) != 0 (an exact rational point), lies in S when b(p) = g(p) = 0, and otherwise is at
//   distance 0 not attained (nearby parallel lines meet S ever farther out: minimizers "0").
// - a = 0, b constant: != 0, one rational meeting point; = 0, S is a cylinder along d: the line
//   lies in it (g(p) = 0) or d(L, S) = d(p, S), attained along whole lines (a continuum).
// Against another line (closed form: skew, crossing, parallel or equal) and a point (the
// exact squared distance). nullopt when `other` is a plane or a double plane (the plane routes
// answer those) or has no real point.
//
// line_torus_distance(line, T): d(L, T) = max(0, d(L, K) - r), K the core circle (centre c,
// axis a, radius R). Whether L meets T is decided exactly: the torus quartic along the line
// (degree 4 over Q) has a real root (distance 0; its distinct real roots, counted exactly, are
// the meeting points: a tangency is a double root). Otherwise the squared distance from
// x(t) to K, F = |x - c|^2 + R^2 - 2 R rho(t) (rho the distance from the axis), is least at a
// root of the degree <= 4 polynomial Q'^2 P - R^2 P'^2 (P = rho^2, Q = |x - c|^2; a point where
// the line crosses the axis is never a minimum), isolated exactly and enclosed in Arb balls
// refined until the width meets `digits`; the axis itself is a closed form (a circle of
// nearest points). Several candidates left within the enclosures are reported as ties (with
// tie regions for the symmetry proof). Certified always, except when the precision cap
// (2^16 bits) leaves the enclosure wider than asked (the width contract then says so).
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/torus.hpp"

#include <array>
#include <optional>

namespace surfcert::certify {

struct RealLocus {
  enum class Kind { Other, Plane, Line, Point };
  Kind kind = Kind::Other;
  std::array<core::Rational, 4> plane;     ///< Plane: plane . (x, y, z, 1) = 0
  std::array<core::Rational, 3> point;     ///< Line: a point of it; Point: the point
  std::array<core::Rational, 3> direction; ///< Line: its direction (nonzero integer vector)
};

/// The real locus of a degenerate quadric, exactly (see above).
RealLocus real_locus(const core::QuadricMatrix& q);

/// The distance from the line `line` (kind Line) to the quadric `other`; line_first: the line
/// is the query's first surface (pairs are (point on a, point on b)).
std::optional<DistanceResult> line_quadric_distance(const RealLocus& line,
                                                    const core::QuadricMatrix& other,
                                                    bool line_first, long digits);

/// The distance from the line `line` (kind Line) to the ring torus `torus` (see above);
/// nullopt when `line` is not a line.
std::optional<DistanceResult> line_torus_distance(const RealLocus& line, const core::Torus& torus,
                                                  bool line_first, long digits);

} // namespace surfcert::certify
