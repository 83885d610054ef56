// surfcert: the embedding API (namespace surfcert), the operations of the command line —
// classify, intersect, distance, verify, generate — as C++ calls with typed answers.
//
// What it represents: a thin, stable front over the engine. A Surface is read exactly from
// text (an equation or a JSON surface, docs/input.md), from a 4x4 matrix of doubles or of
// rationals, or from a posed shape; every double stands for its exact binary value, and how
// float data was read is kept as readings. An operation takes two surfaces and Options and
// returns the engine's own typed result (certify::QsicResult, trace::CurveResult,
// certify::DistanceResult; verify's verdicts as their JSON) wrapped with what its JSON needs.
// generate returns the labelled test cases of `surfcert generate` (app/generate.hpp).
//
// Contract:
// - Every status is the engine's: Certified only when proven; Undecided never guesses;
//   Uncertified only in Mode::Float (an estimate). Nothing here decides anything itself.
// - to_json() of a result is exactly the result object of the `surfcert batch` line that asks
//   the same question ({"op", "a", "b", options...}) without its "id" and "time_ms": the
//   same fields, in the same order, the same text (docs/json-contract.md). A surface read at
//   JSON path "$.a" (the `path` argument of the Surface readers) names that path in its
//   readings and errors, as the batch line does.
// - Bad input (a surface, an option out of range, a detail the op does not have, a claim)
//   throws core::InputError (alias surfcert::InputError) with its source, line, column and
//   JSON path, before anything is computed; the batch line reports the same error as an error
//   line. An engine failure throws another std::exception (a FLINT abort: app::FlintAbort once
//   install_flint_abort_handler() ran, which the Python module does).
// - A time budget (Options::budget_ms > 0) that runs out gives status Undecided with
//   budget_exhausted set (JSON "reason": "budget"); for a distance, what the earlier routes
//   established is kept.
// - Calls are thread-safe: each works on its own data (FLINT keeps per-thread caches; a
//   thread that made calls should call flint_cleanup() before it ends, as for_each_parallel
//   does).
#pragma once

#include "surfcert/certify/detail.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/error.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/core/rational.hpp"
#include "surfcert/core/shape.hpp"
#include "surfcert/core/surface.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace surfcert {

using certify::Detail;
using certify::Mode;
using certify::Status;
using core::InputError;
using core::Location;
using core::Rational;
using core::io::Json;

/// The version of the library (project(VERSION) of the build).
const char* version();

/// A surface read exactly, with the readings of its float data (docs/input.md).
class Surface {
public:
  /// An equation ("x^2 + y^2 = 1"; degree 3..12 is an implicit surface) or, when the text
  /// starts with '{', a JSON surface (shapes, matrices, tori, canal, parametric surfaces).
  /// `source` names the text in errors; `path` is the JSON path the surface has in a batch
  /// line ("$.a", "$.b"), used in readings and errors.
  static Surface parse(const std::string& text, const std::string& source = "<string>",
                       const std::string& path = "$");
  /// A JSON surface value (a string value is an equation).
  static Surface from_json(const Json& value, const std::string& source = "<json>",
                           const std::string& path = "$");
  /// The quadric p^T M p, p = (x, y, z, 1), each double read as its exact value; a
  /// non-symmetric M means its symmetric part (reported as a reading). NaN or infinity is an
  /// InputError.
  static Surface from_matrix(const std::array<std::array<double, 4>, 4>& m,
                             const std::string& path = "$");
  /// The same from exact rationals.
  static Surface from_matrix(const std::array<std::array<Rational, 4>, 4>& m,
                             const std::string& path = "$");
  /// A posed shape of `type` ("sphere" takes radii[0], "cylinder" and "cone" radii[0..1], the
  /// others radii[0..2], as in the JSON form; docs/input.md), centred at `center`, rotated by
  /// the unit quaternion q / |q| (w, x, y, z) when given; doubles read exactly.
  static Surface from_shape(const std::string& type, const std::array<double, 3>& center,
                            const std::array<double, 3>& radii,
                            const std::optional<std::array<double, 4>>& quaternion = {},
                            const std::string& path = "$");
  /// An engine surface as it is (no readings).
  explicit Surface(core::Surface s) : value_(std::move(s)) {}

  const core::Surface& value() const { return value_; }
  /// "quadric", "torus", "canal", "implicit" or "parametric".
  std::string kind() const { return core::surface_kind(value_); }
  /// Null when the surface is not a quadric (classify and intersect need quadrics).
  const core::QuadricMatrix* quadric() const { return std::get_if<core::QuadricMatrix>(&value_); }
  const core::io::Readings& readings() const { return readings_; }

private:
  Surface(core::Surface s, core::io::Readings r) : value_(std::move(s)), readings_(std::move(r)) {}
  core::Surface value_;
  core::io::Readings readings_;
};

/// What a query asks besides its surfaces (the batch line's fields of the same names).
struct Options {
  Mode mode = Mode::Filtered;
  /// How much the answer carries (certify/detail.hpp): must be a level the op has (classify
  /// and intersect: topology, certificate, full; distance: value, full).
  Detail detail = Detail::Full;
  long digits = 15;        ///< distance: 10^-digits relative width, 1..1000
  bool solid = false;      ///< distance: between the solids
  double tolerance = 2e-4; ///< intersect: the tracer's tolerance, 1e-12..1
  double budget_ms = 0;    ///< wall-time budget of the query; 0 = none
};

/// Fields shared by every answer.
struct Answer {
  Detail detail = Detail::Full;
  core::io::Readings readings; ///< how the float data of both surfaces was read
  bool budget_exhausted = false;
  double budget_ms = 0;
};

struct Classification : Answer {
  Classification(core::QuadricMatrix qa, core::QuadricMatrix qb)
      : a(std::move(qa)), b(std::move(qb)) {}
  certify::QsicResult qsic; ///< the certified topology (status, morphology, Segre, facts, ...)
  core::QuadricMatrix a, b;
  Status status() const { return budget_exhausted ? Status::Undecided : qsic.status; }
  Json to_json() const;
};

struct Intersection : Answer {
  Intersection(core::QuadricMatrix qa, core::QuadricMatrix qb)
      : a(std::move(qa)), b(std::move(qb)) {}
  trace::CurveResult curve; ///< topology (curve.topology), branches, isolated points
  core::QuadricMatrix a, b;
  Status status() const { return budget_exhausted ? Status::Undecided : curve.status; }
  Json to_json() const;
};

struct Distance : Answer {
  /// The enclosure (exact bounds: distance->lower_arf(), decimals: lower() / upper()), the
  /// minimizers with their proof kind, pairs, method.
  certify::DistanceResult result;
  long digits = 15;
  Status status() const { return budget_exhausted ? Status::Undecided : result.status; }
  Json to_json() const;
};

struct Verification : Answer {
  /// {"status", "result": {"verdicts": [...]}} (app/verify.hpp: each claim confirmed,
  /// refuted with a counterexample, or undecided).
  Json verdicts;
  Status status() const;
  Json to_json() const;
};

/// The certified topology of the intersection of two quadrics (InputError when one is not a
/// quadric).
Classification classify(const Surface& a, const Surface& b, const Options& opt = {});
/// The topology plus every branch of the curve, checked against it.
Intersection intersect(const Surface& a, const Surface& b, const Options& opt = {});
/// The minimum distance: a proven enclosure to opt.digits, the minimizers, closest pairs.
Distance distance(const Surface& a, const Surface& b, const Options& opt = {});
/// Verdicts on claims: a JSON array of claim objects (docs/json-contract.md, op verify).
/// verify has no detail levels (a batch line's "detail" on op verify is an input error):
/// opt.detail is not read, the answer is always whole.
Verification verify(const Surface& a, const Surface& b, const Json& claims,
                    const Options& opt = {});

/// What to generate: the options of `surfcert generate` (docs/cli.md, app/generate.hpp).
struct GenerateOptions {
  /// --case: "1".."35", "all", "degenerate_pencil", "coincident", "ellipsoid", "natural" or
  /// "distance"; ignored when `family` is set.
  std::string cases = "all";
  std::string family;                ///< --family: "" (none), a family name or "all"
  std::vector<int> gaps{10, 20, 40}; ///< --gaps: family points at g = +-2^-k and 0
  long count = 1;                    ///< --count, 1..1000000
  std::uint64_t seed = 1;            ///< --seed
  std::string encoding = "exact";    ///< --encoding: "exact", "double" or "shape"
  int threads = 1;                   ///< labelling threads (the cases do not depend on it)
};

/// One generated case: a batch line {"id", "op", "a", "b", "label"} and its parts.
struct GeneratedCase {
  std::string id;
  std::string op; ///< "classify" or "distance"
  Json a, b;      ///< the surfaces as written (JSON surfaces; Surface::from_json reads them)
  /// The certified label: "status" ("certified", "undecided", or "error" when labelling
  /// failed inside), the classifier's tu_case / morphology / segre / pencil (op classify) or
  /// the distance engine's distance / minimizers / method (op distance), "certified_by" and
  /// "construction".
  Json label;
  Json line;          ///< the whole line, as `surfcert generate` writes it
  std::string status; ///< label.status
  /// label.morphology and label.tu_case (op classify, when certified; else "" and 0).
  std::string morphology;
  long tu_case = 0;
  /// The surfaces read as a batch line reads them (at JSON paths $.a, $.b).
  Surface surface_a() const { return Surface::from_json(a, "<generate>", "$.a"); }
  Surface surface_b() const { return Surface::from_json(b, "<generate>", "$.b"); }
};

/// The lines `surfcert generate` writes for the same options, in the same order, the same
/// JSON. A request that cannot be met (unknown case, family or encoding, count or gap out of
/// range) throws InputError before anything is labelled.
std::vector<GeneratedCase> generate(const GenerateOptions& opt = {});

/// Runs job(i) for every i in [0, n) on up to `threads` native threads (threads < 1: one),
/// each thread freeing FLINT's caches when it ends. job must not throw (catch per item).
void for_each_parallel(std::size_t n, int threads, const std::function<void(std::size_t)>& job);

} // namespace surfcert
