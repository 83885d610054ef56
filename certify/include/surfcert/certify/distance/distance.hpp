// surfcert::certify::surface_distance: the minimum distance between two surfaces, as a typed
// answer with three outcomes: certified, undecided (with what was established), uncertified
// (a float estimate).
//
// Contract of a DistanceResult:
// - `distance` is an Enclosure (enclosure.hpp): built only from a proof, so no float can fill
//   it; a certified answer's enclosure meets upper - lower <= 10^-digits lower on the printed
//   decimals. surface_distance checks that once for every route; a route that stops short is
//   run once more with 2 digits + 10, and the answer is undecided if it still misses.
// - `estimate` holds a float-mode answer (status Uncertified); it never fills `distance`.
// - `minimizers` is a proven count, "infinite", "0" (not attained), or "undecided" when the
//   count is not proven: several candidates whose equality is unproven (ties "unproven"), or
//   a route that set count_unproven; minimizer_candidates then says how many.
// - `pairs` are approximate points (doubles), for display; `tie_regions` are outward boxes
//   handed to the tie proof (symmetry.hpp).
//
// Routes (each falls through to the next when it cannot prove its answer): the convex
// dualities, closed forms and branch and bounds of the README's table; pairs with a sphere
// through the exact point-quadric sextic: d_min and d_max are [min lower, min upper] and
// [max lower, max upper] over every critical candidate (never a float-sorted first), the side
// decided against them, candidates re-enclosed until |d - r| meets the width and the
// minimizers separate or are proven tied; two quadrics through the offset system
// (quadric_pair.hpp); tori, canal, implicit and parametric surfaces through their own files.
// Whether two quadrics meet is decided by the certified QSIC topology (an exact special point
// or an exact argument proves an affine common point; a traced point is display only).
#pragma once

#include "surfcert/certify/distance/enclosure.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/surface.hpp"

#include <arb.h>

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
  /// A proven count ("1", "2", ...), "infinite" (a continuum), "0" (an infimum that is not
  /// attained), or "undecided" (a certified distance whose minimizer count is not proven:
  /// minimizer_candidates then holds the number of candidates not separated from it).
  std::string minimizers;
  long minimizer_candidates = 0;
  /// Set by a route whose count rests on an unproven step (e.g. candidates merged by a
  /// float test): the count is then reported as "undecided".
  bool count_unproven = false;
  /// Undecided because the offset system has a curve of solutions in the tried position (the
  /// quadric pair route then retries after a rational rotation).
  bool offset_curve_of_solutions = false;
  /// Undecided only because the enclosure (which holds) is wider than asked: more working
  /// digits may certify it (surface_distance retries).
  bool width_short = false;
  std::vector<std::array<std::array<double, 3>, 2>> pairs; ///< (point on a, point on b), approx
  int critical_candidates = 0;
  int eliminated_degree = 0; ///< degree of the eliminated univariate polynomial
  /// Degrees of the offset system (quadric pairs): the equations, the two resultants in
  /// (x, y), the univariate eliminants onto x, y, z, and their square-free parts (compare
  /// seed 000 Table 1). Empty when the closed forms or the point-quadric sextic applied.
  std::vector<long> system_degrees, bivariate_degrees, univariate_degrees, squarefree_degrees;
  bool solid = false; ///< solid distance requested (0 when the volumes overlap)
  /// Which route produced the answer ("convex_duality", "nested_convex_duality",
  /// "offset_system", "closed_form", ...); empty when not recorded.
  std::string method;
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

/// Any two supported surfaces: two quadrics as above; a quadric and a ring torus
/// (quadric_torus_distance). Two tori: undecided ("not supported yet"). `solid` applies to
/// two ellipsoids only.
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

/// {"status", "note"?, "result": {"distance": {"lower", "upper", "approx"}, "minimizers",
/// "pairs", "critical_candidates", "eliminated_degree", "digits", "solid", "mode",
/// "method"?, "ties"?}}
core::io::Json distance_envelope_json(const DistanceResult& r, long digits);

} // namespace surfcert::certify
