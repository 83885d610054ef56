// surfcert::trace: approximate (floating-point) pieces of the intersection curve of two
// quadrics, produced to match a certified topology. Nothing in this namespace claims
// certainty: intersect_curve (trace/intersect_curve.hpp) compares what the tracer returns with
// the certified morphology from surfcert::certify and reports "undecided" when they disagree.
// The tracer sits above certify (it uses certify's decisions, never the other way round).
//
// Conventions: points are affine (x, y, z) doubles; every returned point has been corrected
// by Newton steps onto both surfaces; `max_residual` (intersect_curve.hpp) is a geometric
// distance bound, max(|f| / |grad f|, |g| / |grad g|) over the returned points.
#pragma once

#include "surfcert/core/quadric.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace surfcert::trace {

using Point3 = std::array<double, 3>;

/// One connected piece of curve as a polyline.
struct Branch {
  std::string kind; ///< "loop", "figure_eight", "loop_with_cusp", "conic", "line", "double_conic",
                    ///< "cubic"
  bool closed = true;
  std::vector<Point3> points; ///< for closed branches the first point is not repeated at the end
  /// Open pieces in a box: the indices, in the exact box crossings (certify/box_exits.hpp),
  /// of the crossings its two ends were matched with (empty when not matched).
  std::vector<int> exits;
  /// The plane n.x + d = 0 (|n| = 1) of a conic or line component, when known (not in the
  /// JSON): a piece is cut at a box face on {face, plane, one surface}, transversal even along a
  /// double conic, where the two surfaces are tangent and f = g = 0 on the face is singular.
  std::optional<std::array<double, 4>> plane;
};

/// An axis-aligned box: the region in which unbounded curves are traced.
struct Box {
  Point3 min{}, max{};
  bool contains(const Point3& p, double slack = 0) const {
    for (size_t k = 0; k < 3; ++k)
      if (p[k] < min[k] - slack || p[k] > max[k] + slack) return false;
    return true;
  }
  double diagonal() const;
};

struct TraceOptions {
  /// Bound on chord error and on the step, relative to the scene size: the box's diagonal for
  /// a walk in a box; for conics drawn in closed form, the extent they are sampled over (an
  /// open conic in a box is sampled out past the box, so its chords there may be ~10 times
  /// coarser relative to the box).
  double tolerance = 2e-4;
  /// The chord error's bound alone is tolerance * chord_scale (the step's stays tolerance): a
  /// retrace in a box far larger than the curve's features refines the chords near them
  /// without shortening the steps along the straight stretches far out.
  double chord_scale = 1;
  int max_points_per_branch = 200000;
  /// A walk further than this many scene sizes from its start is on a non-compact branch and
  /// stops (without a box; with one, walks stop on its faces).
  double escape_scenes = 100;
  /// When set, march() stops each walk where it leaves the box (the last point lies on a face)
  /// and walks starting on a face only inwards; the scene size is the box's diagonal.
  std::optional<Box> box;
  /// The singular points given to march() are all the curve has (computed exactly). A start
  /// at which the rounded pair's curve looks singular is then not made one: the exact curve is
  /// smooth there and the rounded pair cannot tell its pieces apart (a cylinder pair 1e-20 off
  /// Steinmetz rounds to Steinmetz, whose crossing joined the two loops into two mixed ones).
  bool singular_points_complete = false;
};

/// The pair as float data, normalised; shared by the tracer's parts.
struct QuadricPair {
  /// Symmetric, each scaled by a power of two to a largest |entry| in [1/2, 1) (scaling
  /// rounds nothing: a pair posed in doubles is traced exactly as posed).
  std::array<std::array<double, 4>, 4> a, b;
  /// For a matrix of doubles that is not exactly symmetric: its symmetric part is a + a_lo
  /// (b + b_lo) exactly, and f, g evaluate with the sums; zero otherwise (split false).
  std::array<std::array<double, 4>, 4> a_lo{}, b_lo{};
  bool split = false;
  /// Relative size of the perturbation of f and g at a point (per unit of the terms' size F,
  /// see noise_radius): the rounding of the coefficients (2^-53) plus the evaluation's, or the
  /// evaluation's alone when a and b are the exact matrices scaled (posed in doubles).
  double noise_unit = 0x1p-53;
  /// True in a pair made by refined(): f and g evaluate a + a_lo, b + b_lo (the exact matrices
  /// scaled, to ~2^-106 per entry) in double-double.
  bool refined_form = false;
  /// The powers of two each matrix was scaled by (a = A 2^-a_scale, rounded entrywise), and
  /// whether that scaling was exact (false for entries beyond the doubles, divided exactly).
  int a_scale = 0, b_scale = 0;
  bool scaled_by_pow2 = true;
  explicit QuadricPair(const core::QuadricMatrix& qa, const core::QuadricMatrix& qb);
  /// This pair (built from qa, qb) with f and g evaluated in double-double on the exact
  /// matrices, scaled by the same powers of two: a, b and the gradients are unchanged, a_lo
  /// and b_lo become the exact matrices' remainders (rounded once, ~2^-106 of an entry), and
  /// noise_unit 2^-96 (the remainders' rounding and the evaluation's 2^-98 of the terms). The
  /// zero set a walk then follows is the exact pair's to ~1e-29 of the terms instead of ~1e-16
  /// (a neck of ~1e-8 between two pieces of curve, which the rounded coefficients cannot place,
  /// is walked). Several times the cost of f and g: for retries. Nullopt where the scaling was
  /// not exact.
  std::optional<QuadricPair> refined(const core::QuadricMatrix& qa,
                                     const core::QuadricMatrix& qb) const;
  double f(const Point3& p) const; ///< X^T A X with X = (p, 1)
  double g(const Point3& p) const;
  Point3 grad_f(const Point3& p) const;
  Point3 grad_g(const Point3& p) const;
  /// An estimate of p's distance to the EXACT surfaces from these rounded coefficients:
  /// max over f, g of (|f(p)| + 2^-53 F) / |grad f(p)|, F = sum |a_ij x_i x_j| bounding how
  /// far the rounding of the coefficients moves f at p (infinite where a gradient vanishes).
  /// With `enough`: where |f| evaluated in double plus its rounding bound (8 units, 8.9e-16 F)
  /// already gives a value <= enough, that (slightly larger) value, without the extended
  /// evaluation (~5% of a traced pair's time, one per output point).
  double distance_bound(const Point3& p, double enough = -1) const;
  /// How far the curve of these rounded coefficients may lie from the exact curve near p: the
  /// rounding moves f by up to noise_unit F, so the surface by that over |grad f| along its normal,
  /// and the curve by the larger of the two surfaces' moves over the sine of the angle between
  /// them (infinite where a gradient vanishes or they are parallel). Large near a cone's apex
  /// (at distance r from an apex ~1 from the origin, ~1e-16 / r) and where the surfaces are
  /// nearly tangent: there a walk cannot tell two pieces of curve apart. When noise_unit is
  /// below 2^-53 (traced as posed, or refined) at least 2^-48 max(1, |p|_inf): a few units in
  /// the last place of the double points, below which no double point tells two pieces apart
  /// whatever the evaluation resolves.
  double noise_radius(const Point3& p) const;
};

/// The pair's exact coefficients in double-double (each entry hi + lo, read from the exact
/// rationals, the matrix scaled by a power of two): f and g evaluate to ~1e-30 relative at a
/// double point. For the final correction of traced points onto the exact surfaces and for
/// measuring how far a point lies from them. The tracer walks on QuadricPair's doubles (exact
/// for a pair posed in doubles; else rounded, a curve that differs from the exact one by
/// ~1e-16 relative except near a singular point of a surface, a cone's apex, where it differs
/// by up to ~1e-8), and retraces a picture that failed on QuadricPair::refined, whose
/// coefficients are these.
class RefinedPair {
public:
  RefinedPair(const core::QuadricMatrix& a, const core::QuadricMatrix& b);
  /// Geometric residual max(|f| / |grad f|, |g| / |grad g|) at p (first-order distance to the
  /// farther surface; |f| where a gradient vanishes), |f| enlarged by a bound on its
  /// double-double evaluation error (2^-98 of the terms' size): never 0 for a point off the
  /// surfaces that the evaluation cannot resolve (far from the origin the terms are ~|p|^2:
  /// a point 5e-17 off a paraboloid 2^30 out read 0). First order: near a cone's apex the
  /// true distance can exceed it (by up to ~5x seen).
  double distance(const Point3& p) const;
  /// Gauss-Newton steps on the exact pair while they reduce distance(p) and it is above
  /// `target`; p is left at the best point found. Returns distance(p). With face_axis k in
  /// 0..2 the coordinate p[k] is kept (a point on a face of a box stays on it). A step longer
  /// than 64 times the distance it corrects (plus 4 ulps of p) is not taken: there the
  /// surfaces are nearly tangent and the step slides p along them, off the curve.
  double refine(Point3& p, double target, int face_axis = -1) const;

private:
  struct Form {
    std::array<std::array<double, 4>, 4> hi{}, lo{};
  };
  static double value(const Form& m, const Point3& p);
  static Point3 gradient(const Form& m, const Point3& p);
  static double distance(const Form& m, const Point3& p);
  Form a_, b_;
};

/// Newton (minimum-norm Gauss-Newton) projection of p onto f = g = 0. Returns false when it
/// does not converge to max(|f| / F, |g| / G) <= 1e-15 within `iterations`, where
/// F = sum |a_ij x_i x_j| (x = (p, 1)) is the size of the terms of f at p (so the criterion
/// holds at any scale and translation: the rounding floor of f's evaluation is ~1e-19 F).
/// Where the surfaces meet at a small angle, or at any angle when noise_unit is below 2^-53
/// (next to a cone's apex the criterion allows points ~1e-15 F / |grad f| off), Gauss-Newton
/// then goes on while its steps shrink.
bool project_onto_curve(const QuadricPair& q, Point3& p, int iterations = 30);

/// Start points: for a random-ish direction d, the points of the curve where d.x is critical
/// (every compact branch has at least two), computed from the exact real roots of a
/// univariate resultant in the slice parameter (see start_points.cpp). Points at which the
/// surfaces are tangent or the curve is singular are included when they are extreme.
std::vector<Point3> extreme_points(const core::QuadricMatrix& a, const core::QuadricMatrix& b);

/// The same construction in plain doubles (slice polynomials, float roots of R): cheap, with
/// no guarantee. Callers use it first and fall back to extreme_points when the branches traced
/// from these starts do not reproduce the certified topology.
std::vector<Point3> extreme_points_float(const QuadricPair& q);

/// The points where the curve crosses the faces of the box (float proposals: each face plane
/// meets both quadrics in a conic, the two conics are intersected through a float resultant
/// and the roots polished by Newton onto f = g = 0 on the face). No guarantee that none is
/// missed; tangential crossings may be reported once or not at all.
std::vector<Point3> box_face_points(const QuadricPair& q, const Box& box);

/// Newton on f = g = 0, x_k = c from x (x_k is set to c). False when it does not converge.
bool newton_on_face(const QuadricPair& q, size_t k, double c, Point3& x);

/// Newton on x_k = c, n.x + d = 0 and f = 0 (or g = 0 where f's gradient is nearly normal to
/// the plane) from x: the point of a planar component (a conic in plane) on a face. False when
/// it does not converge.
bool newton_on_face_in_plane(const QuadricPair& q, size_t k, double c,
                             const std::array<double, 4>& plane, Point3& x);

/// Where the segment from `in` (inside the box) to `out` first leaves the box: the curve's
/// point on that face, by newton_on_face from the segment's crossing (y[k] = c exactly).
/// False when the segment does not leave through a face or Newton fails.
bool face_crossing(const QuadricPair& q, const Box& box, const Point3& in, const Point3& out,
                   Point3& y);

/// Marches along the smooth parts of the curve from the start points, with a step adapted to
/// curvature and Newton correction, passing through the given singular points along their
/// tangent directions; closes loops. Each start point lying on an already traced branch is
/// skipped, and so is each start within 1e-7 of the scene of a given singular point (isolated
/// points, acnodes, may be given too: no walk starts at them). With opt.box, walks end on the
/// box's faces (open branches, closed = false) and start points outside the box are ignored.
/// `unresolved_walks`, when given, receives the number of walks that ended where the pair's
/// evaluation noise exceeds the gap to the next piece of curve (QuadricPair::noise_radius: the
/// neck of two pipes rounded to doubles): a walk there stops rather than guess, and the pair
/// evaluated more precisely (QuadricPair::refined) may pass.
std::vector<Branch> march(const QuadricPair& q, const std::vector<Point3>& starts,
                          const std::vector<Point3>& singular_points, const TraceOptions& opt,
                          int* unresolved_walks = nullptr);

} // namespace surfcert::trace
