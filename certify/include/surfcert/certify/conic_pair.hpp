// surfcert::certify::conic_pair: two conics of one plane, given as symmetric 3x3 forms in
// (u, v, 1) with exact rational entries, read through a resultant in a sheared chart.
//
// A chart is (u, v, 1) = x t0 + y t1 + t2 for a fixed small rational shear (conic_charts();
// the first is the identity). In a chart where conic A has a nonzero y^2 coefficient a2 (A and
// B are swapped when only B has one): R(x) = Res_y(A, B), of degree <= 4, and the first
// subresultant s11(x) y + s10(x) = b2 A - a2 B. R is identically zero exactly when the conics
// share a component. At a real root x0 of R with s11(x0) != 0 the conics have exactly one
// common point over x0, (x0, -s10(x0) / s11(x0)), which is real; where s11(x0) = 0 the two
// restrictions to the line x = x0 are proportional and their common points are the roots of
// A(x0, y). Shared by box_exits (a curve's crossings with a box face) and conics_meet.
#pragma once

#include "surfcert/algebra/upoly.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <optional>
#include <vector>

namespace surfcert::certify {

using ConicForm = std::array<std::array<core::Rational, 3>, 3>;

struct ConicResultant {
  std::array<std::array<core::Rational, 3>, 3> t; ///< the chart's columns t0, t1, t2
  algebra::UPolyQ r;                              ///< Res_y(A, B)
  algebra::UPolyQ s11, s10;                       ///< first subresultant s11 y + s10
  core::Rational a2;                              ///< A (after the swap): a2 y^2 + a1 y + a0
  algebra::UPolyQ a1, a0;
};

/// The charts tried by the readers of this header, in order.
const std::vector<std::array<std::array<core::Rational, 3>, 3>>& conic_charts();

/// The resultant data of the conics in chart `chart` (an index into conic_charts()), or
/// nullopt when neither conic has a y^2 term there.
std::optional<ConicResultant> conic_resultant(const ConicForm& ca, const ConicForm& cb,
                                              size_t chart);

/// Whether the two conics have a real affine common point: true or false proven exactly
/// (real roots of R isolated exactly; at each, s11 != 0 proves a real point, or else the sign
/// of A's discriminant in y, exact when it vanishes there, from Arb enclosures otherwise);
/// nullopt when not decided (the conics share a component, or a sign was not separated).
std::optional<bool> conics_meet(const ConicForm& ca, const ConicForm& cb);

} // namespace surfcert::certify
