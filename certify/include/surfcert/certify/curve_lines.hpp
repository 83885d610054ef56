// surfcert::certify::curve_lines: the real lines of a QSIC made of lines only, each exactly
// (a rational point and a rational direction), and their crossings with a box's faces.
//
// What it is for: where the curve holds a real double line (Tu cases 34 and 35, Segre [(22)]:
// the surfaces are tangent along it), every face that line crosses carries a double root of
// the face's resultant, which box_exits' generic reading (simple roots only) cannot certify;
// the tracer cannot find that line by marching either (grad f x grad g vanishes along it), nor
// as the meet of the two diametral planes (they coincide along a tangency). Written as exact
// lines the curve's crossings are exact rational points, and the lines are drawn, not traced.
//
// How (exact rational arithmetic throughout):
//  - kernel lines: at a rational root theta of rank 2, the member E = theta A - B vanishes on
//    the projective line ker E; when A vanishes on it too (three bilinear values), so does B
//    (B = theta A - E): the line lies on the curve. For [(22)] that line is the double line.
//  - a line through a rational point at infinity d of the curve: every line of A in direction
//    d lies in A's diametral plane {p : d . (A_3 p + a_4) = 0}, so the curve's line in
//    direction d is the meet of A's and B's diametral planes when their normals A_3 d, B_3 d
//    are independent; kept when it lies on both surfaces (checked exactly).
//  - a line in a plane of a rational singular member (a double plane at a rank-1 root, either
//    plane of a rational plane pair at a rank-2 root) whose line at infinity lies on A: A's
//    section by that plane is then that line at infinity and one affine line (or none); kept
//    when it lies on B too. (Two lines of the curve meeting at infinity: a plane through both
//    holds the one at infinity.)
// The lines found (duplicates merged) are returned only when their number is the morphology's
// count of real lines less `lines_at_infinity` (the distinct real lines of the curve the caller
// proved to lie at infinity; a kernel line at infinity is then one of them and skipped), and,
// when lines_at_infinity is 0, none lies at infinity; otherwise nullopt (the caller keeps its
// generic route). Preconditions on the caller: a certified classification whose morphology has
// lines only (no loop, conic or cubic); `directions`: rational real points at infinity of the
// curve (each line through one of them is looked for).
#pragma once

#include "surfcert/algebra/pencil.hpp"
#include "surfcert/certify/box_exits.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <optional>
#include <vector>

namespace surfcert::certify {

/// The affine line point + t direction (direction != 0), exact.
struct ExactLine {
  std::array<core::Rational, 3> point;
  std::array<core::Rational, 3> direction;
};

/// The curve's real affine lines (see above), or nullopt.
std::optional<std::vector<ExactLine>>
exact_curve_lines(const algebra::PencilFacts& facts, int real_lines,
                  const std::vector<std::array<core::Rational, 3>>& directions,
                  int lines_at_infinity = 0);

/// The crossings of the union of the distinct lines with the faces of [lo, hi], exact. Each
/// line as lines_box_exits reads one (a line counts once whatever its multiplicity); certified
/// when each line's reading is and no two lines meet on the box's boundary (distinct lines
/// share at most their meeting point, so their crossings are then distinct).
BoxExits exact_lines_box_exits(const std::vector<ExactLine>& lines,
                               const std::array<core::Rational, 3>& lo,
                               const std::array<core::Rational, 3>& hi);

} // namespace surfcert::certify
