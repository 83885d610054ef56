// surfcert::certify::cubic_and_line: the exact components of a QSIC made of a twisted cubic
// and a line (Tu cases 10, 11, 12: Segre [22] with real or conjugate roots, Segre [4]).
//
// What a CubicAndLine represents (when `found`): the line is the span of the rational points
// line[0], line[1] of P^3; the cubic is the image of P^1 under the homogeneous cubic map
// (s : t) -> X(s, t), X_i = sum_k cubic[i][k] s^(3-k) t^k, with rational coefficients. Both
// are proved exactly, not assumed: every quadric of the pencil vanishes on the line
// (u^T Q v = 0 for u, v in {line[0], line[1]}) and Q_A(X(s, t)) and Q_B(X(s, t)) vanish
// identically as polynomials; X has no common factor and spans P^3 (a twisted cubic).
//
// How: the line is ker p(T), T = A'^-1 B with A' = A + k B a regular member and p the monic
// square root of det(l A' - B) (for [22], p = (l - l1)(l - l2) and the kernel is spanned by
// the two cones' vertices, real or conjugate; for [4], p = (l - l0)^2 and the kernel is
// ker (T - l0)^2); computed as the kernel of the rational matrix B A'^-1 B + p1 B + p0 A'.
// The cubic: the planes through the line, H(s : t) = span(line, s e3 + t e4), meet each
// quadric in the line and one more line; the two residual lines meet in the cubic's third
// point of H, their cross product in H's coordinates (degree 3 in (s, t)). The cubic meets
// the line where that point's e3/e4 coordinate, a binary quadratic `meet`, vanishes.
//
// Affine facts (w = x_3): the line's affine point and direction (rational; the line may lie
// at infinity), and the cubic's points at infinity, the real roots of X_3(s, t): the affine
// cubic is P^1(R) minus those roots, one unbounded branch per distinct real root.
#pragma once

#include "surfcert/core/quadric.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <optional>
#include <string>

namespace surfcert::certify {

struct CubicAndLine {
  bool found = false;
  std::string reason; ///< why not found (the pencil is not of these cases, or a check failed)
  std::array<std::array<core::Rational, 4>, 2> line;  ///< two points spanning the line
  std::array<std::array<core::Rational, 4>, 4> cubic; ///< X_i = sum_k cubic[i][k] s^(3-k) t^k
  std::array<core::Rational, 3> meet;                 ///< meet[0] s^2 + meet[1] s t + meet[2] t^2
  bool line_at_infinity = false;
  std::array<core::Rational, 3> line_point;     ///< affine point (unless line_at_infinity)
  std::array<core::Rational, 3> line_direction; ///< the line's direction (its point at infinity)
  int cubic_points_at_infinity = 0; ///< distinct real roots (s : t) of X_3: its unbounded branches
};

/// The exact line and cubic of the pair (any regular pencil whose curve is a twisted cubic
/// and a line; otherwise found = false with the reason).
CubicAndLine cubic_and_line(const core::Mat4& a, const core::Mat4& b);

} // namespace surfcert::certify
