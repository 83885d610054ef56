// Internal to certify/box_exits: the exits of a plane tangent to a quadric along a line (a plane
// tangent to a cylinder or to a cone along a ruling). There the curve is one line counted twice,
// every face it crosses carries a double root of the face resultant, and the generic reading
// (simple roots only) cannot certify it; the line itself is rational and its crossings are exact.
#pragma once

#include "surfcert/certify/box_exits.hpp"

#include <optional>

namespace surfcert::certify::detail {

/// When one of a, b is a plane (no quadratic part) and the other's section by it is a double
/// line (a rank-1 conic; or the line at infinity, no affine point): the exact exits of that
/// line (certified, or not with the reason: a crossing on an edge, the line in a face's plane).
/// nullopt otherwise (the generic reading applies).
std::optional<BoxExits> double_line_exits(const core::Mat4& a, const core::Mat4& b,
                                          const std::array<core::Rational, 3>& lo,
                                          const std::array<core::Rational, 3>& hi);

} // namespace surfcert::certify::detail
