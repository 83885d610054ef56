// surfcert::trace::conic_branches: the conic components of a QSIC, produced as plane ∩ quadric
// from the factored singular members of the pencil, never traced. Also the lines of a
// degenerate plane section (section_lines, read exactly), a line clipped to a box, and the
// arcs of an exact twisted cubic in a box (cubic_in_box).
//
// At a multiple root theta of f with rank(theta*A - B) <= 2 the member is a pair of planes
// (rank 2, real when its inertia is (1,1)) or a double plane (rank 1). Each real plane meets
// Q_A in a conic; the real, non-empty ones are the conic components (for a double plane the
// conic is a double component: the surfaces are tangent along it, and a tracer using
// grad f x grad g would stall there). Points are sampled so that the chord error stays below
// the tolerance (and, in a box, at the conic's crossings with the faces' planes and between
// them) and corrected onto both surfaces. Approximate (floating point), like all of
// surfcert::trace.
#pragma once

#include "surfcert/algebra/pencil.hpp"
#include "surfcert/certify/cubic_line.hpp"
#include "surfcert/trace/curve.hpp"

#include <optional>
#include <utility>
#include <vector>

namespace surfcert::trace {

/// Lines and points of a degenerate plane section, read exactly: the plane `plane` (written as
/// a quadric: zero quadratic block) cut by `other` (a quadric or another plane). Each line is
/// a point and a direction (doubles rounded from exact data). `doubled`: one line counted
/// twice (the surfaces are tangent along it). nullopt when the section is a proper conic (or
/// the plane lies on `other`).
struct SectionComponents {
  std::vector<std::pair<Point3, Point3>> lines; ///< (point, direction)
  std::vector<Point3> points;                   ///< a real point of two imaginary lines
  bool doubled = false;
};
std::optional<SectionComponents> section_lines(const core::Mat4& plane, const core::Mat4& other);

/// The part of the line p + t d inside the box as an open branch (kind "line", both ends on
/// faces), or nullopt when the line misses the box.
std::optional<Branch> line_in_box(const Point3& p, const Point3& d, const Box& box);

/// The line of the curve of a and b in direction d (a real point at infinity of a curve made of
/// lines, none at infinity): a line X = p + t d lies on A exactly when d^T A d = 0 (d is at
/// infinity on A), d . (A_3 p + a_4) = 0 and p is on A; the first two put it in the plane
/// Pi_A = {p : d . (A_3 p + a_4) = 0}, parallel to d, where A is constant along d. So the
/// curve's line in direction d is Pi_A ∩ Pi_B when their normals A_3 d, B_3 d are independent.
/// Returns (point nearest the origin, d) in doubles, or nullopt when the normals are nearly
/// parallel or the point found is not on both surfaces to ~1e-9 of the terms (a guess: the
/// caller's exact box crossings judge the picture).
std::optional<std::pair<Point3, Point3>>
line_in_direction(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const Point3& d);

/// The arcs of the exact twisted cubic of cases 10-12 (certify/cubic_line.hpp) inside the
/// box: open branches (kind "cubic") sampled from its rational parametrisation with chord
/// error about `chord` (at most ~max_points points each), both ends on faces (each the
/// cubic's point at its face crossing's parameter, computed exactly and rounded, then put
/// onto the face plane). An arc touching a face from inside is cut there (two pieces).
std::vector<Branch> cubic_in_box(const certify::CubicAndLine& cl, const Box& box, double chord,
                                 int max_points);

/// One point of each affine arc of that cubic (a sample near the origin), for sizing a box.
std::vector<Point3> cubic_arc_points(const certify::CubicAndLine& cl);

/// What the certified topology says of the plane sections, which the rounded section's
/// reading (a centre value or a linear term against a float threshold) must follow.
enum class SectionKinds {
  Any,       ///< nothing known: the rounded section decides proper conic or lines
  LinesOnly, ///< the curve has lines and no proper conic: every section drawn as lines
  /// The affine curve has no lines (certified): a section with real crossing or parallel lines
  /// in the rounding is a thin hyperbola or a parabola (a section 2^-20 across, 0.4 from the
  /// origin: its centre value is 1e-11 of its terms, which read as crossing lines).
  ProperOnly,
};

/// Conic branches (kind "conic" or "double_conic"; "line" for the lines of a plane's
/// degenerate section: crossing, parallel, or one affine line and the line at infinity) for the
/// exact pencil facts of a pair whose morphology has conic or line components; a line found in
/// two planes is returned once. `kinds`: what the certified topology says the sections are.
/// Empty when there are none.
std::vector<Branch> conic_branches(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                   const algebra::PencilFacts& facts, const TraceOptions& opt,
                                   SectionKinds kinds = SectionKinds::Any);

/// The section of `other` by one exact plane (written as a quadric: n / 2 in its last column,
/// d in its corner) as branches, as conic_branches draws each plane's conic: for degenerate
/// pencils whose curve is that plane section (a plane across a parabolic cylinder's rulings).
std::vector<Branch> section_branches(const core::Mat4& plane, const core::QuadricMatrix& other,
                                     const TraceOptions& opt);

} // namespace surfcert::trace
