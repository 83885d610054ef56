// surfcert::certify::proven_loops: a proven LOWER bound on the number of bounded loops of the
// real affine intersection curve of two quadrics, from boxes proposed by the caller (the
// tracer's closed branches, each in a tight box), and the affine readings it settles.
//
// Why: for two smooth ovals with four real points at infinity the exact facts allow {1 loop,
// 4 unbounded} (one oval carries every point at infinity) and {0 loops, 4 unbounded} (two
// each); certify/cone_ovals.hpp decides only when a member of the pencil is a real cone or
// cylinder with a rational apex. A traced closed branch proposes the first reading; this turns
// the proposal into a proof (floats choose the boxes, only exact arithmetic decides).
//
// The argument, per box B = [lo, hi] (rational corners). box_exits(B) (box_exits.hpp)
// certified with no crossing: the complete list of the curve's real points on the boundary of
// B is empty, so the curve does not meet the boundary at all. B split by a plane x_k = c
// (lo_k < c < hi_k; the mid-plane of an axis, then planes nudged off it when a split is not
// generic): box_exits of the half [lo, hi with x_k <= c] certified with at least one crossing
// gives a real point p of the curve on that half's boundary, inside the closed B, so (the
// boundary of B holding none) in the interior of B, and a smooth point where the curve is
// transversal to the plane. The connected component of the real affine curve through p is
// connected and misses the boundary of B: it lies wholly in the interior of B, so it is
// compact, holds no point at infinity, and is one-dimensional at p: a loop in the affine
// counting (certify/affine.hpp: a piece without a point at infinity; a figure eight or crossing
// components count at least one there). Boxes that are pairwise disjoint (as closed sets)
// hold distinct loops: `count` of them prove loops >= count. A box that proves nothing
// (a crossing on its boundary, no crossing of any split, a box_exits not certified) is listed
// with the reason and counts 0; nothing is a guess.
//
// A lower bound alone cannot rule out a loop the tracer missed. loops_upper_bound is the
// other side, with no float proposal at all: for each axis k, every real solution of
// f = g = h_k = 0 (h_k = (grad f x grad g)_k: where x_k is critical on the curve, or the curve
// is singular) has its x_k among the real roots of P_k = Res_v(Res_u(f, g), Res_u(f, h_k)) (u, v
// the other two coordinates; a resultant lies in the ideal of its two polynomials, so P_k
// vanishes at every common zero, whatever the leading coefficients do; P_k == 0 identically,
// in both elimination orders, gives no bound). A compact component of the real affine curve
// attains its maximum and minimum of x_k, at solutions of that system: so it lies in the
// open slab between the least and the largest real root of P_k (isolated exactly); the slab is
// taken from critical_value_polynomial's D_k first (degree <= 8, same argument), P_k only when
// D_k is zero or its root range does not prove out. Every
// compact component lies inside the box B of the three slabs (widened to dyadic doubles; no
// root at all: no compact component). certify/inner_loops.hpp then bounds the compact
// components wholly inside B (box_exits of B certified, B nudged outwards when not), i.e. all
// of them.
#pragma once

#include "surfcert/algebra/upoly.hpp"
#include "surfcert/certify/affine.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace surfcert::certify {

/// An axis-aligned box with rational corners, lo < hi coordinate-wise.
struct RationalBox {
  std::array<core::Rational, 3> lo, hi;
};

/// The proof for one box: `proven` when a loop lies wholly inside; then the split that found
/// its point (the plane x_axis = cut and the number of crossings of the curve with the half
/// box x_axis <= cut, all on that plane). Else `reason`.
struct LoopInBox {
  bool proven = false;
  int axis = -1;
  core::Rational cut;
  int crossings = 0;
  std::string reason;
};

LoopInBox prove_loop_in_box(const core::Mat4& a, const core::Mat4& b, const RationalBox& box);

struct ProvenLoops {
  int count = 0;                     ///< proven: the curve has at least this many bounded loops
  std::vector<RationalBox> boxes;    ///< pairwise disjoint, one proven loop wholly inside each
  std::vector<std::string> rejected; ///< why each other box given proved nothing
};

/// Each entry of `proposals` is one proposed loop: boxes around it (e.g. tighter and looser
/// margins), tried in order until one proves a loop (prove_loop_in_box); a box meeting one
/// already proven (as closed boxes) is not tried. Proposals are taken in order.
ProvenLoops proven_loops(const core::Mat4& a, const core::Mat4& b,
                         const std::vector<std::vector<RationalBox>>& proposals);

/// D_k(c), a polynomial whose real roots include every critical value of x_k on the real
/// curve (k = 0, 1, 2): the discriminant of the binary cubic det(l F_c + m G_c), F_c and G_c
/// the conics the two quadrics cut from the plane x_k = c (entries of degree <= 2 in c, so
/// degree <= 8, against 16 for the resultant P_k above, and no multivariate elimination). Where
/// x_k is critical at a smooth point P of the curve, the plane x_k = c is tangent to it there:
/// the two conics meet at P with multiplicity >= 2 (the plane's intersection multiplicity with
/// the complete intersection), the pencil's base is not four distinct points, and the cubic has
/// a repeated root or vanishes identically, so D_k(c) = 0. A singular point of the curve, and a
/// conic of the curve lying in such a plane, are roots too. Other roots (tangency at complex
/// points or on the plane's line at infinity) only widen the slab. Primitive over Z; the zero
/// polynomial when the discriminant vanishes identically (no information: loops_upper_bound
/// then eliminates with P_k).
algebra::UPolyZ critical_value_polynomial(const core::Mat4& a, const core::Mat4& b, int k);

struct LoopUpperBound {
  std::optional<int> bound; ///< proven: the curve has at most this many compact components
  RationalBox box;          ///< every compact component lies inside (when bound is set)
  std::string reason;       ///< why no bound
};

/// The bound above; inner_component_bound is asked for `wanted` (the least bound it may stop
/// at) with `budget` cells per direction.
LoopUpperBound loops_upper_bound(const core::Mat4& a, const core::Mat4& b, int wanted,
                                 long budget = 20000);

/// Keeps the readings of `t` (AffineTopology::readings, the (loops, unbounded) pairs the exact
/// facts allow when they leave loops or unbounded_branches undecided) with loops >= p.count.
/// When exactly one remains, loops and unbounded_branches are set from it, their `undecided`
/// entries removed, the route becomes "proven_loops" and `loop_boxes` records p.boxes; returns
/// true then. Otherwise t is unchanged (false). p.count == 0 never changes anything.
/// With `upper` (set: a proven upper bound), only the readings with loops <= *upper->bound are
/// kept too, and `all_loops_box` records upper->box; p.count == 0 then needs no box.
bool settle_by_proven_loops(AffineTopology& t, const ProvenLoops& p,
                            const LoopUpperBound* upper = nullptr);

} // namespace surfcert::certify
