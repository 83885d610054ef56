// surfcert::certify::surface_distance: the minimum distance between two surfaces, as a typed
// answer with three outcomes: certified, undecided (with what was established), uncertified
// (a float estimate).
//
// Contract of a DistanceResult:
// - `distance` is an Enclosure (enclosure.hpp): built only from a proof, so no float can fill
//   it; a certified answer's enclosure meets upper - lower <= 10^-digits lower on the printed
//   decimals. surface_distance checks that once for every route; a route that stops short is
//   rerun up to three times, each doubling the working digits (+10, at most 1000), and the
//   answer is undecided if it still misses.
// - `estimate` holds a float-mode answer (status Uncertified); it never fills `distance`.
// - `minimizers` (minimizers.hpp) is a proven count, a continuum, "not attained", or
//   undecided when the count is not proven (several candidates whose equality is unproven,
//   ties "unproven", or a route that set count_unproven), with the number of candidates; each
//   established value says whether exact arithmetic or rigorous enclosures proved it.
// - `method` (method.hpp) is the registry route that answered; `reduced_by` the route that
//   solved a reduced problem (a parametric surface through its implicit equation).
// - `pairs` are approximate points (doubles), for display; `tie_regions` are outward boxes
//   handed to the tie proof (symmetry.hpp).
//
// How an answer is found: the route registry (route.hpp) puts the pair in canonical order and
// tries the routes of its pair kind in table order (closed forms, convex dualities, branch and
// bounds with Krawczyk certificates, the exact offset systems; the README has the table), then
// applies once, for every route, the contact fallback, the tie proof, the width contract and
// the count rule. Whether two quadrics meet is decided by the certified QSIC topology (an exact
// special point or an exact argument proves an affine common point; a traced point is display
// only).
#pragma once

#include "surfcert/algebra/arb.hpp"
#include "surfcert/certify/distance/enclosure.hpp"
#include "surfcert/certify/distance/method.hpp"
#include "surfcert/certify/distance/minimizers.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/surface.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace surfcert::certify {

/// Whether several minimizers are proven to be at the same distance (JSON "ties":
/// absent, "proven", "unproven").
enum class Ties { None, Proven, Unproven };
const char* to_string(Ties t);

struct DistanceResult {
  Status status = Status::Error;
  std::string note;
  /// The proven enclosure of the minimum distance (built only from a proof: enclosure.hpp).
  /// A certified answer has one meeting the width contract; an undecided answer may carry
  /// what it established (e.g. [0, upper] or [lower, inf]).
  std::optional<Enclosure> distance;
  /// A float answer (float mode): never in `distance`, never certified.
  std::optional<Estimate> estimate;
  /// Decimal bounds of `distance` ("" when there is none), for reading.
  const std::string lower() const { return distance ? distance->lower() : std::string(); }
  const std::string upper() const { return distance ? distance->upper() : std::string(); }
  double approx() const { return distance ? distance->approx() : estimate ? estimate->value : 0.0; }
  /// How many minimizers, and how that is proven (minimizers.hpp); Undecided for a certified
  /// distance whose count is not proven (it then holds the number of candidates).
  Minimizers minimizers;
  long minimizer_candidates() const { return minimizers.is_undecided() ? minimizers.value() : 0; }
  /// Set by a route whose count rests on an unproven step (e.g. candidates merged by a
  /// float test): the count is then reported as "undecided".
  bool count_unproven = false;
  /// Undecided because the offset system has a curve of solutions in the tried position (the
  /// quadric pair route then retries after a rational rotation).
  bool offset_curve_of_solutions = false;
  /// Undecided only because the enclosure (which holds) is wider than asked: more working
  /// digits may certify it (surface_distance retries).
  bool width_short = false;
  /// Undecided because the query's time budget ran out (core/budget.hpp): what earlier
  /// routes established is kept (JSON "reason": "budget").
  bool budget_exhausted = false;
  /// Undecided because a surface has no real point, proven exactly (a quadric such as
  /// x^2 + y^2 + z^2 = -1): there is no distance (JSON "reason": "no_real_point").
  bool no_real_point = false;
  std::vector<std::array<std::array<double, 3>, 2>> pairs; ///< (point on a, point on b), approx
  int critical_candidates = 0;
  int eliminated_degree = 0; ///< degree of the eliminated univariate polynomial
  /// Degrees of the offset system (quadric pairs): the equations, the two resultants in
  /// (x, y), the univariate eliminants onto x, y, z, and their square-free parts (compare
  /// seed 000 Table 1). Empty when the closed forms or the point-quadric sextic applied.
  std::vector<long> system_degrees, bivariate_degrees, univariate_degrees, squarefree_degrees;
  bool solid = false; ///< solid distance requested (0 when the volumes overlap)
  /// Which route produced the answer (the JSON "method"; method.hpp); None when not recorded.
  Method method = Method::None;
  /// A reduction's answer (parametric_reduction): the route that solved the reduced problem.
  Method reduced_by = Method::None;
  Mode mode = Mode::Filtered; ///< the mode the query ran in
  /// Several minimizers: Unproven (their distances agree to the requested precision only;
  /// the count is then reported "undecided") or Proven (equal distances proven by an exact
  /// symmetry, symmetry.hpp, or equal exact values); None for one minimizer or a continuum.
  Ties ties = Ties::None;
  /// For that proof, from routes that can give them: one region per minimizer (outward double
  /// intervals, three per point or direction) such that every global minimizer lies in a
  /// region and no region holds two; directions (unit normals) when tie_directions.
  std::vector<std::vector<std::array<double, 2>>> tie_regions;
  bool tie_directions = false;
  /// Regions are unit directions of lines through a fixed point (a cone's generators): the
  /// image of a region is taken with both signs.
  bool tie_lines = false;
};

/// mode: Filtered (default) tries the elimination-free certificates first (convex duality
/// for separated or nested convex solids, the torus circle bound) and falls back to the exact
/// offset method; Exact runs the offset method (and the exact topology) only; Float returns
/// the double-precision answer of the convex search, status Uncertified, when one exists, and
/// otherwise answers as Filtered.
DistanceResult surface_distance(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                long digits, bool solid, Mode mode = Mode::Filtered);

/// Any two supported surfaces (quadrics, tori, canal surfaces, implicit and parametric
/// surfaces; route.hpp lists the pair kinds). `solid` asks for the distance between the
/// solids: for two quadrics, and for closed surfaces of the other kinds (0 when one solid
/// holds a point of the other).
DistanceResult surface_distance(const core::Surface& a, const core::Surface& b, long digits,
                                bool solid, Mode mode = Mode::Filtered);

/// When count > 1: appends to the note that the listed minimizers agree to the requested
/// precision without their equality being proven (the wording every route uses for ties), and
/// sets out.ties = "unproven".
void note_unproven_ties(DistanceResult& out, size_t count);

/// The sentence note_unproven_ties appends (prove_ties replaces it when it proves the tie).
extern const char* const kUnprovenTiesNote;

/// out.distance = the enclosure of the ball d (lower clamped at 0).
void set_distance_enclosure(DistanceResult& out, const arb_t d, long digits);

/// {"status", "note"?, "result": {"distance"?: {"lower", "upper", "approx"}, "estimate"?:
/// {"value", "certified": false}, "minimizers"?, "minimizers_proof"?, "minimizer_candidates"?,
/// "pairs", "pair_points_approximate", "critical_candidates", "eliminated_degree",
/// "degrees"?, "digits", "solid", "mode", "method"?, "reduced_by"?, "ties"?}}.
/// detail (certify/detail.hpp) Full, the default: all of it; any lower level is Value:
/// "detail": "value" in the envelope, and without the certificate data "critical_candidates",
/// "eliminated_degree", "degrees".
core::io::Json distance_envelope_json(const DistanceResult& r, long digits,
                                      Detail detail = Detail::Full);

/// Appends that envelope as compact JSON text, the bytes dump(distance_envelope_json(...))
/// writes (the batch writes it directly; distance_envelope_json reads this text back).
void append_distance_envelope(std::string& out, const DistanceResult& r, long digits,
                              Detail detail = Detail::Full);

} // namespace surfcert::certify
