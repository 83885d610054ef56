// Internal to certify/box_exits: the crossings of a plane section with one face in closed form.
// On a face, a plane restricts to a line and the other quadric to a conic; their common points
// are the roots of one quadratic along the line, t = a +- b sqrt(D) with rational a, b and an
// integer D, so the crossings, their multiplicity and their place against the face rectangle
// are decided by exact signs of such numbers (algebra::QuadraticNumber::sign), without the
// resultant, root isolation and Arb refinement of the generic reading (30% of a plane section's
// time).
#pragma once

#include "surfcert/core/rational.hpp"

#include <array>
#include <vector>

namespace surfcert::certify::detail {

using FaceForm = std::array<std::array<core::Rational, 3>, 3>; ///< a form in (u, v, 1)

/// One crossing in the face's coordinates: double midpoints of enclosures of the exact
/// coordinates (128-bit Arb balls here, intervals in box_exits_filter), and the larger of their
/// radii.
struct FacePoint {
  double u = 0, v = 0, radius = 0;
};

enum class LineConic {
  Complete,  ///< every common point in the open rectangle found, each a simple root
  Component, ///< the line lies on the conic: a component of the curve in the face's plane
  Tangent,   ///< a double root in the closed rectangle
  Edge       ///< a simple root on the rectangle's boundary: a crossing on an edge of the box
};

/// The common points of the face line `line` (no quadratic part, not constant) and `conic`
/// inside the open rectangle (u_lo, u_hi) x (v_lo, v_hi), appended to `out`. Complete when each
/// is a simple root along the line: a transversal crossing at a smooth point of the curve
/// (gradient of the conic's quadric not orthogonal to the line, which lies in both the face and
/// the first quadric's section). A double root outside the closed rectangle is no point of the
/// face. `out` is meaningful only when Complete.
LineConic line_conic_crossings(const FaceForm& line, const FaceForm& conic,
                               const core::Rational& u_lo, const core::Rational& u_hi,
                               const core::Rational& v_lo, const core::Rational& v_hi,
                               std::vector<FacePoint>& out);

} // namespace surfcert::certify::detail
