// surfcert::core vector arithmetic on exact 3-vectors (std::array<Rational, 3>): dot, cross,
// sum, difference, multiple, p + t d. Exact (no rounding anywhere); header-only because each
// is a line of Rational arithmetic that the routes computing with exact points, lines and
// directions (distance routes, tie proofs) would otherwise each write again.
#pragma once

#include "surfcert/core/rational.hpp"

#include <array>

namespace surfcert::core {

using RVec3 = std::array<Rational, 3>;

inline Rational dot(const RVec3& a, const RVec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline RVec3 cross(const RVec3& a, const RVec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline RVec3 add(const RVec3& a, const RVec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline RVec3 sub(const RVec3& a, const RVec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline RVec3 scale(const Rational& s, const RVec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
/// p + t d.
inline RVec3 along(const RVec3& p, const Rational& t, const RVec3& d) {
  return {p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]};
}

} // namespace surfcert::core
