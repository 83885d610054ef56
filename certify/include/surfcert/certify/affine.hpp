// surfcert::certify::affine_topology: the affine reading of a certified (projective) QSIC
// topology: bounded loops, unbounded branches, isolated points, the curve's exact points at
// infinity and the components lying entirely at infinity.
//
// What an AffineTopology represents: the real affine curve Q_A ∩ Q_B ∩ {w != 0}. The points
// at infinity of the curve are the common points of the two conics at infinity (the quadratic
// parts, w = 0); they are computed exactly: in a unimodular chart (u : v : s) of the plane at
// infinity, checked exactly to put no common point on s = 0 and no two on one vertical line,
// R(u) = Res_v(A'(u, v, 1), B'(u, v, 1)) has degree 4, each root u0 is one point with
// v0 = -s10(u0) / s11(u0) (first subresultant), and the multiplicity of u0 in R is the
// intersection multiplicity of the curve with the plane at infinity there. Directions are
// rational, or algebraic: a root of an irreducible polynomial in an isolating interval.
//
// Counting conventions (as the morphology table's): per real component of the curve, its
// affine part splits into connected pieces; a piece without a point at infinity is a loop,
// every other piece an unbounded branch (a real line is one unbounded branch). Components
// that cross, as two conics, are counted separately. A figure eight whose node is affine is
// one piece (a loop when it misses infinity).
//
// Invariant: a count is set only when it is proved from exact facts: the points at infinity
// with their multiplicities, the exact special points at infinity, and the parity of each
// component's intersection with a plane (an oval of a bounded morphology, a conic: even; a
// branch meeting every plane, a twisted cubic, a line: odd). Every assignment of the points at
// infinity to the components that these facts allow is enumerated; a count is certified when
// all of them agree, otherwise it stays unset with a reason (for smooth ovals the readings left
// are kept in `readings`: certify/proven_loops.hpp may settle them with proven loop bounds).
// Two exact sweeps settle ambiguous readings first: for smooth ovals, a real cone or cylinder
// of the pencil whose generators tell which oval each point at infinity lies on
// (certify/cone_ovals.hpp); for a figure eight with its node p affine, the member singular at p
// (a cone with apex p): projecting from p maps each lobe onto an arc of that cone's conic at
// infinity between the directions of the node's two branches (its generators in the other
// quadric's tangent plane n . x = 0 at p), and a point at infinity d of the curve lies on the arc
// given by the sign of (n . d) / (m . d), m . d = 0 a line missing that conic (exact signs; Arb
// refined at algebraic directions). When
// one quadric is a plane (written as a degenerate quadric: plane ∪ plane at infinity) the affine
// curve is the plane section, classified exactly as a plane conic; the other quadric's conic at
// infinity is then a component lying at infinity. The same holds when the quadratic parts are
// proportional (B_inf = c A_inf, e.g. two paraboloids with parallel axes and equal shapes, parallel
// cylinders of equal radii): B - c A is then such a plane (route "pencil_plane"). Two planes
// (route "plane_plane") meet in one line with the rational direction n_A x n_B, or nowhere
// (parallel), or coincide (not computed); the plane at infinity they share as quadrics is not
// listed. Two cones with one common affine apex p (a degenerate pencil, route "common_apex"):
// the curve is the lines p + t d over the real points d at infinity (p alone when there is
// none; the apex is read off whichever quadric is a cone, the other may be a plane pair or a
// cylinder through it; where neither is a cone, two plane pairs whose axes meet at one affine
// point, that point, the kernel of A^2 + B^2, when no other route reads the pair). A rational plane
// pair in a degenerate pencil (route "plane_pair": x y = 0 or x^2 = 1/4 against a cylinder or a
// cone): the union of the two plane sections, when it is read off them exactly (see
// plane_pair_route). Two cylinders (or plane pairs) along one rational direction d, both matrices
// vanishing on (d, 0) (a degenerate pencil, route "parallel_cylinders": an elliptic against a
// parabolic cylinder, pipes of unequal shapes with parallel axes): f(x + t d) = f(x) on each, so
// the curve is the union of the lines b + t d over the real common points b of the two sections by
// the plane x_k = 0 (d_k != 0), exactly (the resultant of the two conics of that plane, roots
// isolated exactly); a common point of the sections at infinity is a line at infinity (listed in
// at_infinity_only, kind "line"), and every affine line meets infinity at d (one point at infinity,
// multiplicity the number of affine lines over C with multiplicity; d alone at infinity, kind
// "point", when none of them is real). The two sections sharing a line (the cylinders share a
// plane: part of the intersection is a surface) is not certified. A twisted cubic and a line (cases
// 10-12, route "cubic_line"): the counts come from their exact parametrisations
// (certify/cubic_line.hpp): one unbounded branch per distinct real point at infinity of the cubic,
// one for the line; when the line lies at infinity (the conics at infinity then share it) the
// affine curve is the cubic alone, its points at infinity are the real roots of X_3, and the line
// is listed in at_infinity_only (kind "line"). Lines only with one real line at infinity (route
// "exact_lines"; the conics at infinity share it, gcd of the two, and are not proportional): the
// other real lines are affine, one unbounded branch each, found exactly (certify/curve_lines.hpp:
// kernel lines, the line through the remaining common point P of the conics at infinity, lines in
// the planes of rational singular members) and all required; a point at infinity's multiplicity is
// then the number of those lines through it, and the line at infinity is listed apart. Requires a
// certified topology, except on these plane and apex routes.
#pragma once

#include "surfcert/algebra/upoly.hpp"
#include "surfcert/certify/cubic_line.hpp"
#include "surfcert/certify/curve_lines.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace surfcert::certify {

/// A real point of the curve at infinity: a direction (x : y : z : 0).
struct PointAtInfinity {
  int multiplicity = 1; ///< intersection multiplicity of the curve with w = 0 there
  bool rational = false;
  std::array<std::string, 3> direction; ///< exact text: rational or a + b*sqrt(d) (else empty)
  std::array<double, 3> approx{};       ///< unit vector, decimal approximation
  /// Algebraic (degree >= 2, set when `direction` is empty): t is the unique root of
  /// `polynomial` in (lo, hi) and the direction is (dir_in_t[0](t) : ... : dir_in_t[2](t)).
  algebra::UPolyZ polynomial;
  core::Rational lo, hi;
  std::array<algebra::UPolyQ, 3> dir_in_t;
  std::string lies_on = "curve"; ///< "curve", or the kind of the special point there
};

/// A real component lying entirely in the plane at infinity (never drawn).
struct ComponentAtInfinity {
  std::string kind;                     ///< "point", "conic", "line_pair", "double_line", "line"
  std::array<std::string, 3> direction; ///< for "point": exact direction
  std::string equation;                 ///< the conic x^T M x = 0 of the plane w = 0, as text
};

struct AffineTopology {
  bool computed = false; ///< false: nothing established (see reason)
  std::string route;     ///< "pencil", "plane_section", "pencil_plane", "plane_plane",
                         ///< "plane_pair", "common_apex", "parallel_cylinders", "cubic_line",
                         ///< "exact_lines" or "proven_loops" (certify/proven_loops.hpp)
  std::optional<int> loops, unbounded_branches, isolated_points, lines, conics;
  std::vector<PointAtInfinity> points_at_infinity;
  bool points_at_infinity_complete = false;
  std::vector<ComponentAtInfinity> at_infinity_only;
  std::vector<std::pair<std::string, std::string>> undecided; ///< (field, why)
  std::string reason;                                         ///< when !computed
  /// Plane routes ("plane_section", "pencil_plane", "plane_plane"): the affine curve is
  /// `plane` (a plane written as a quadric: zero quadratic block) cut by `section_of`
  /// (a quadric, or the other plane). Route "plane_pair": the union of the sections of
  /// `plane` and `plane2` (the two planes of a rational plane pair) by `section_of`.
  std::optional<core::Mat4> plane, plane2, section_of;
  /// Route "common_apex" (a degenerate pencil of two quadrics singular at one affine point, two
  /// cones or plane pairs with that apex): the apex;
  /// the curve is the lines from it along the points at infinity (the apex alone if none).
  std::optional<std::array<core::Rational, 3>> apex;
  /// Route "parallel_cylinders": the common ruling direction d and the lines' base points b in
  /// the plane x_k = 0 (the curve is the lines b + t d): exact when rational, else (an
  /// algebraic common point of the two sections) to double precision only.
  std::optional<std::array<core::Rational, 3>> ruling;
  struct RulingLine {
    std::optional<std::array<core::Rational, 3>> base; ///< exact base point, when rational
    std::array<double, 3> approx{};                    ///< base point, to double
  };
  std::vector<RulingLine> ruling_lines;
  /// Route "cubic_line": the exact line and cubic.
  std::optional<CubicAndLine> cubic_line;
  /// Route "exact_lines" (lines only, one at infinity): the curve's real affine lines, exact.
  std::vector<ExactLine> exact_lines;
  /// Every (loops, unbounded_branches) reading the exact facts allow, when they allow several
  /// (the points at infinity shared among smooth ovals in several ways); empty otherwise. A
  /// proven lower bound on the loops may leave one (certify/proven_loops.hpp).
  std::vector<std::pair<int, int>> readings;
  /// Route "proven_loops": pairwise disjoint boxes (min corner, max corner; in the
  /// coordinates of the pair the reading was made for), each holding one loop wholly inside
  /// (proven exactly); the loops are at least as many.
  std::vector<std::array<std::array<core::Rational, 3>, 2>> loop_boxes;
  /// Route "proven_loops" with an upper bound: a box proven to hold every compact component,
  /// where no more loops than `loops` were proven to lie (certify/proven_loops.hpp).
  std::optional<std::array<std::array<core::Rational, 3>, 2>> all_loops_box;
  bool certified() const {
    return computed && loops && unbounded_branches && isolated_points && lines && conics &&
           points_at_infinity_complete;
  }
};

/// The two planes of a rational plane pair (a rank-2 symmetric matrix whose binary form splits
/// over Q), as 4-vectors n with n . (x, y, z, 1) = 0 on the plane, exactly; nullopt for rank
/// != 2, a double plane, conjugate complex planes or planes over Q(sqrt d).
std::optional<std::array<std::array<core::Rational, 4>, 2>>
rational_plane_pair(const core::Mat4& m);

/// The rational planes of a singular member e of the pencil at a root of rank 1 (the double
/// plane: any row with a nonzero diagonal entry) or 2 (rational_plane_pair's two planes); empty
/// otherwise (other ranks, conjugate planes, planes over Q(sqrt d)).
std::vector<std::array<core::Rational, 4>> rational_member_planes(const core::Mat4& e, int rank);
/// The plane n . (x, y, z, 1) = 0 written as a quadric (zero quadratic block).
core::Mat4 plane_as_quadric(const std::array<core::Rational, 4>& n);
/// Keeps only the reading `r` (one of t.readings, proven by the caller): loops and
/// unbounded_branches set from it, their `undecided` entries removed, the route set, the loop
/// boxes cleared (the caller records its own).
void keep_reading(AffineTopology& t, std::pair<int, int> r, const std::string& route);

/// The affine topology from a classification (special points are computed here when needed).
AffineTopology affine_topology(QsicResult& topology, const core::QuadricMatrix& a,
                               const core::QuadricMatrix& b);

/// {"status": "certified"|"undecided", "route", "loops", "unbounded_branches",
/// "isolated_points", "lines", "conics" (null when undecided), "points_at_infinity": [...],
/// "at_infinity_only": [...], "undecided": [{"field", "reason"}]}.
core::io::Json affine_json(const AffineTopology& t);

} // namespace surfcert::certify
