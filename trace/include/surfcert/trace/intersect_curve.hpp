// surfcert::trace::intersect_curve: the certified topology of the intersection of two
// quadrics (from surfcert::certify) plus every branch of the curve as a polyline, checked
// against that topology. This is the tracer layer's entry point: built on certify, used by
// the application layer (surfcert::app) and the CLI.
//
// The topology (certify::classify_qsic) is certified. The branches come from the float tracer
// (trace/curve.hpp, trace/conics.hpp) and are approximations: every point is corrected onto
// both exact surfaces (to 1e-13 of the curve's size; Newton on double-double coefficients
// where the rounded ones are not enough) and the largest geometric residual is reported. Invariant:
// status is Certified only when the branches returned have exactly the number and kinds the
// certified morphology prescribes (loops, figure eight, loop with cusp, conics, double conic,
// isolated points); otherwise Undecided, with what was found and why. Scope: an ellipsoid (or
// sphere) and any second quadric, where the real curve is bounded and the projective topology is
// the affine one (traced whole, unless a box is given); for other pairs (regular pencils), and
// for any pair given TraceOptions::box, the curve is traced inside a box (the given one, or one
// chosen to contain the special points, the extreme points and every closed loop, with a
// margin): loops closed, pieces cut by the box (and of unbounded branches) open with both ends on
// the box's faces, conics in closed form clipped to the box.
// There status is Certified only when the affine topology (certify/affine.hpp) is certified,
// the traced closed loops and isolated points have its counts (a given box may cut loops:
// certified then only when the loops lying wholly inside it are exactly those traced closed —
// decided exactly when the loops are conics of singular members' planes,
// certify/ellipses_in_box.hpp — or when certify/inner_loops.hpp proves that no more lie inside,
// or, when the affine curve is loops only, when each loop is proven in a box of its own (the
// pair traced whole) and every exact crossing of the faces lies in one of them,
// or when the whole curve is one loop and it crosses the faces, or when the affine curve is one
// loop beside isolated points and crosses no face: a certified crossing of the faces of a
// small box around one of its points, outside the given box or inside it, places it; the
// isolated points in a box
// are those of the exact special points lying in it, decided exactly; a curve of isolated
// points only is not walked),
// no crunode (cusp) has more than 4 (2) traced arms leaving it (a walk on another piece of
// curve drawn through it), the exact crossings of the
// curve with the box's faces are certified (certify/box_exits.hpp: complete, transversal, off
// the edges) and the traced open pieces are exactly half as many, their ends matched one to
// one with those crossings (so a branch crossing the box twice is two certified pieces); an
// automatic box must also show at least one piece per unbounded branch (it is doubled, up to 12
// times, while its pieces' distinct face crossings are fewer; when no doubling shows them, or
// the picture does not match, it is placed once more without the sizing points lying 1000 times
// farther out than their typical distance: float extreme points next to a singular point at
// infinity), and no point may stay
// more than 1e-9 of the box's diagonal off the surfaces (a picture of another curve whose ends
// happen to match). The automatic box has short dyadic faces, moved a little (unevenly, by
// different ratios at each try) when a face meets the curve non-generically. Pairs beyond 2^+-8 are
// traced at unit size (exact power-of-two scaling), or, when only their distance from the origin
// (up to 2^40) is large, where they are first — on the pair translated exactly to its least-squares
// centre (a centre, an apex, a vertex) — and at unit size when that is undecided (docs/methods.md).
// Points that far out are doubles: max_residual then includes their rounding (~2^-53 of the
// distance). Two smooth ovals whose points at infinity leave the loop count open (no cone member of
// the pencil decides, certify/affine.hpp) are settled after a first trace: each traced closed
// branch proposes tight dyadic boxes, certify/proven_loops.hpp proves exactly that a loop lies
// in each (a lower bound) and bounds the compact components from above by the coordinates'
// exact critical points; when readings remain, loops_in_oval_chart (below) asks which ovals
// meet infinity in a chart where all are bounded; when one reading is left the pair is traced
// again against it.
// Whatever the route, a certified picture has no straight-line branch where the affine reading
// has no line, and every traced point lies within 1e-9 of the curve's own size (plus 16 ulps of
// its coordinates) of both exact surfaces; otherwise it is undecided.
// A regular pair undecided where it is (the curve passing a cone's apex closer than the rounded
// cone resolves, ~1e-8 at |apex| ~ 1) is traced once more translated exactly to either
// quadric's own centre (the apex to double precision) and returned when certified there; if
// not, and its features are extreme in that frame (a plane 1e-15 off a cone's generator), it
// is traced there once more at unit size.
// Degenerate pencils and two planes whose affine curve is lines (certify/affine.hpp routes
// plane_section / pencil_plane with a degenerate section, plane_plane, plane_pair,
// common_apex) are answered with those lines in closed form, clipped to the box and checked
// the same way; on the plane routes the face crossings are those of the plane's section (a
// tangency along a ruling, a double line, is then a rank-1 section, not a multiple crossing),
// on plane_pair those of both sections, on common_apex those of the rational lines
// (certify::lines_box_exits). Other degenerate pencils are not traced (undecided). A twisted
// A regular pencil whose curve is lines only is drawn from its exact lines when they are found
// (certify/curve_lines.hpp: a real double line too), and their crossings are read exactly; a
// double conic's crossings are those of its plane's section of the other quadric. A twisted
// cubic and a line (cases 10-12) come from their exact parametrisations
// (certify/cubic_line.hpp): the line in closed form, the cubic's arcs sampled from its rational
// map, checked against the box the same way.
#pragma once

#include "surfcert/certify/affine.hpp"
#include "surfcert/certify/box_exits.hpp"
#include "surfcert/certify/oval_chart.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/trace/curve.hpp"

#include <optional>
#include <string>
#include <vector>

namespace surfcert::trace {

struct CurveResult {
  certify::QsicResult topology;
  certify::AffineTopology affine; ///< the affine reading (certify/affine.hpp)
  certify::Status status = certify::Status::Error;
  std::vector<Branch> branches;
  std::vector<Point3> isolated_points;
  /// The largest geometric residual max(|f| / |grad f|, |g| / |grad g|) over the returned
  /// points, on the exact quadrics: a distance in the input's length unit. Every point is
  /// brought within 1e-13 of the curve's size where Newton on the exact pair can.
  double max_residual = 0;
  /// The same over the traced branches' points alone (max_residual also counts the isolated
  /// points, exact points rounded); not in the JSON: the tracer's own check of its picture.
  double branch_residual = 0;
  double tolerance = 2e-4;
  bool matches_topology = false;
  bool exact_start_points = false; ///< the float start points missed a branch: exact ones used
  std::optional<Box> box;     ///< the box the curve was traced in (non-ellipsoid pairs, or given)
  bool box_automatic = false; ///< chosen by the tracer (not given)
  /// The exact crossings of the curve with the box's faces (certify/box_exits.hpp), each
  /// matched with one end of one traced open piece when the answer is certified.
  std::optional<certify::BoxExits> box_exits;
  std::string note;
};

/// Topology (in `mode`), special points, and branches (tracing only what the topology needs:
/// conics from the factored singular members, quartic branches by marching from exact extreme
/// points, isolated points from the exact special points). `detail` (certify/detail.hpp): the
/// report data computed besides (the branches and special points are computed at every level).
CurveResult intersect_curve(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                            certify::Mode mode, const TraceOptions& opt,
                            certify::Detail detail = certify::Detail::Full);

/// The same from a topology already computed by certify::classify_qsic
/// (certify::complete_report_data is not needed: the special points are computed here when
/// missing).
CurveResult trace_curve(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                        certify::QsicResult topology, const TraceOptions& opt);

/// The curve's affine loops when it is two smooth ovals (`m`: loops == connected_components
/// == 2) with `points_at_infinity` distinct real points at infinity: the ovals that miss the
/// plane at infinity, decided in a chart whose plane at infinity misses the curve
/// (certify/oval_chart.hpp). The pair is traced there (every oval a closed loop), a direction
/// separating the two traced loops becomes a chart axis, certify::proven_loops boxes each
/// oval, and the old plane at infinity's crossings inside each box are counted exactly. The
/// floats choose the member, the plane, the direction and the boxes; nullopt when a step
/// proves nothing. `frame` (the curve's centre and size in floats, e.g. a traced picture's
/// box): see certify::oval_chart.
std::optional<int> loops_in_oval_chart(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                       const certify::Morphology& m, int points_at_infinity,
                                       const TraceOptions& opt = {},
                                       const certify::ChartFrame* frame = nullptr);

/// {"status", "mode", ..., "result": {classification fields..., "branches": [...],
/// "isolated_points": [...], "max_residual", "tolerance", "branches_match_topology"}}; the
/// classification fields those of `detail` (certify/report.hpp), the branch fields always.
core::io::Json curve_envelope_json(const CurveResult& r, const core::QuadricMatrix& a,
                                   const core::QuadricMatrix& b,
                                   certify::Detail detail = certify::Detail::Full);

/// Appends dump(curve_envelope_json(r, a, b, detail)) byte for byte, the branches' polylines
/// written directly (no document of them is built: the batch's answers; tests compare the two).
void append_curve_envelope(std::string& out, const CurveResult& r, const core::QuadricMatrix& a,
                           const core::QuadricMatrix& b,
                           certify::Detail detail = certify::Detail::Full);

/// One line saying truthfully what was traced (the SVG caption): the certified topology,
/// then "nothing traced" (with why), or the counts of closed and open branches traced (in the
/// box) and whether they match the certified (affine) topology.
std::string curve_caption(const CurveResult& r);

/// Expected branch kinds for a Tu case (ellipsoid cases), e.g. {"loop", "loop"} for case 1.
std::vector<std::string> expected_branch_kinds(int tu_case);

} // namespace surfcert::trace
