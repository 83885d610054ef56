// surfcert::certify::box_exits: the exact points where the intersection curve of two quadrics
// crosses the faces of an axis-aligned box with rational faces.
//
// What a BoxExits represents: when `certified`, `points` is the complete list of the real
// points of Q_A ∩ Q_B on the box's boundary, each inside the open rectangle of one face, each
// a smooth point of the curve where the curve crosses the face transversally. Then the curve
// inside the box is a set of closed loops and exactly points.size() / 2 arcs, each arc ending
// on two of these points (a traced picture must show that many open pieces, ending there).
//
// A filter first (box_exits_filter.hpp): on a face where neither surface's section is a line,
// interval arithmetic (directed rounding) over a subdivision of the face proves either that the
// two face conics have no common point in the closed face rectangle, or the complete list of
// their common points there: every cell not excluded lies in a box where the Krawczyk test
// proves exactly one root with every Jacobian nonsingular (a transversal crossing at a smooth
// point), and each root's tight enclosure lies inside the open rectangle or outside the closed
// one. A proof, not an estimate; a face it cannot prove (a tangency, a singular point, crossings
// closer than its cells, a crossing near an edge, its budget spent) goes the exact route.
// (A face it proves says nothing about a component of the curve in the face's plane wholly
// outside the rectangle, which the exact route reports as not certified.)
//
// How (exact): on the face x_k = c both quadrics restrict to conics in the face's coordinates
// (u, v); in a chart (x, y) sheared from (u, v) by a fixed rational matrix, chosen so that
// conic A has a nonzero y^2 coefficient and every real root of R(x) = Res_y(A, B) (degree <= 4,
// over Q) is simple (multiple non-real roots are allowed: a double component missing the
// face), every real root of R is exactly one common point, of intersection multiplicity
// one, i.e. a transversal crossing at a smooth point of the curve; y = -s10(x)/s11(x) (first
// subresultant). Roots are isolated exactly (algebra::isolate_real_roots) and the point's
// membership in the face rectangle is decided from Arb enclosures of shrinking isolating
// intervals. Not certified (with the reason) when a face plane carries a common component,
// when every chart leaves R with a multiple real root (a tangency, a singular point, two
// components meeting on the face, a double component crossing it), or when a crossing lies on an
// edge of the box (or within 2^-200 of one, relative to the box).
//
// A face where one form has no quadratic part (a plane's section: a line of the face) is read in
// closed form (box_exits_line_conic): the other form along that line is a quadratic whose roots
// a +- b sqrt(D) are placed against the face rectangle by exact signs; a simple root is a
// transversal crossing at a smooth point, a double root in the closed rectangle or a root on its
// boundary is not certified (tangency, edge), and the line lying on the other conic is a
// component in the face's plane. Its interval filter first (box_exits_filter.hpp,
// line_face_crossings): the quadratic's coefficients enclosed; a discriminant proved negative
// is no crossing, one proved positive with A proved nonzero two simple roots, each enclosed
// within 2^-46 of the face and proved inside the open rectangle or outside the closed one;
// anything else (a double or nearly double root, A near 0, a point near an edge) the exact
// signs above.
//
// One exception is read differently, exactly: a plane tangent to the other quadric along a line
// (the plane's section is a rank-1 conic: a plane along a cylinder's ruling at distance r, a
// cone's tangent plane). The curve is then that rational line counted twice; as a set it is a
// line, and its crossings with the faces (rational points, transversal unless the line lies in a
// face's plane, which is not certified) are the points, with an edge crossing not certified.
// lines_box_exits reads a union of rational lines through one point the same way, and lines of
// algebraic directions through it by signs at their roots (algebraic_lines_box_exits.cpp).
#pragma once

#include "surfcert/algebra/upoly.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <string>
#include <vector>

namespace surfcert::certify {

struct BoxCrossing {
  int axis = 0; ///< the face is x_axis = (at_max ? hi : lo)[axis]
  bool at_max = false;
  std::array<double, 3> approx{}; ///< midpoint of an enclosure (the point, to double)
  double radius = 0; ///< max over coordinates of the enclosure's radius (infinite: none found)
};

struct BoxExits {
  bool certified = false;
  std::vector<BoxCrossing> points; ///< complete when certified
  std::string reason;              ///< why not certified
  /// Faces whose crossings (at least one) the interval filter proved; the other faces were
  /// read by the filter's subdivision alone (no crossing), in closed form or by the exact route.
  /// Information for tests and profiles: no certified field depends on the route.
  int filtered_faces = 0;
};

/// The crossings of Q_A ∩ Q_B with the faces of [lo, hi] (lo < hi coordinate-wise; a flat or
/// empty box, lo >= hi somewhere, is answered not certified with that reason: its crossings
/// would be refined to a width of 0, for ever).
/// interval_filter false: every face by the exact route (the filter's proofs compared with it
/// in tests; the answer is the same wherever both are certified).
BoxExits box_exits(const core::Mat4& a, const core::Mat4& b,
                   const std::array<core::Rational, 3>& lo, const std::array<core::Rational, 3>& hi,
                   bool interval_filter = true);

/// The crossings of a curve known to be the lines p + t d_i (rational p and directions,
/// distinct directions: two cones with the common apex p, a plane pair through it), exact:
/// a line meets a face's plane once unless parallel to it. Certified when every crossing lies
/// in a face's open rectangle, no line lies in a face's plane, and p is not on the boundary
/// (the lines meet only at p, so their crossings are then distinct). A line counts once
/// whatever its multiplicity on the surfaces (a tangency along it is no multiple crossing).
/// A flat or empty box is not certified, as for box_exits.
BoxExits lines_box_exits(const std::array<core::Rational, 3>& p,
                         const std::vector<std::array<core::Rational, 3>>& directions,
                         const std::array<core::Rational, 3>& lo,
                         const std::array<core::Rational, 3>& hi);

/// A direction (d_0(t*) : d_1(t*) : d_2(t*)) at the root t* of the irreducible `polynomial`
/// (degree >= 2) isolated in (lo, hi): a point at infinity that is not rational
/// (AffineTopology's points_at_infinity give them so).
struct AlgebraicDirection {
  algebra::UPolyZ polynomial;
  core::Rational lo, hi;
  std::array<algebra::UPolyQ, 3> dir;
};

/// lines_box_exits with lines of algebraic directions besides the rational ones (two cones with
/// a common apex meeting in a double rational line and two conjugate ones: there the pair's
/// crossings are double on the double line and box_exits is never certified). Each
/// comparison of a crossing with a face's bounds is the sign at t* of a polynomial: zero
/// exactly when `polynomial` divides it, otherwise read by Arb on the narrowed bracket; a sign
/// Arb does not separate from 0 is answered not certified. The crossings of algebraic lines
/// carry a rigorous radius.
BoxExits lines_box_exits(const std::array<core::Rational, 3>& p,
                         const std::vector<std::array<core::Rational, 3>>& rational_directions,
                         const std::vector<AlgebraicDirection>& algebraic_directions,
                         const std::array<core::Rational, 3>& lo,
                         const std::array<core::Rational, 3>& hi);

} // namespace surfcert::certify
