// surfcert::app scenes and batches: the `run` and `batch` front ends of the application layer
// (built on surfcert::certify for the decisions and surfcert::trace for the curve branches).
//
// A Scene names surfaces and lists queries; read_scene validates the whole document before
// anything is computed (so a bad scene produces an error and no report). run_query computes
// only what its op needs: "classify" builds the pencil and decides the topology, nothing else;
// "intersect" adds the branches of the curve (traced or produced as conics); "distance" takes
// any two surfaces (quadrics, tori, canal, implicit and parametric surfaces: the distance
// registry's pair kinds), as does "verify" (its claims, verify.hpp, are validated on reading:
// a quadric-only claim needs two quadrics); the other ops need two quadrics (checked on
// reading). Surfaces are
// read exactly (surface_reader.hpp); how float data was read is reported ("readings").
// process_batch reads JSON lines and writes one JSON line per input line, in input order,
// through a TBB pipeline (serial in-order read -> parallel answer -> serial in-order write and
// flush), so each answer is written as soon as it and all earlier ones are done; at most N
// lines are answered at once. A bad line yields an error line and the batch goes on; so does a
// line on which FLINT/Arb aborts (flint_abort is turned into a FlintAbort exception by
// install_flint_abort_handler and answered as an "internal" error line).
#pragma once

#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/surface.hpp"

#include <array>
#include <functional>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace surfcert::app {

struct Query {
  core::io::Json id;       ///< as given (null when absent)
  std::string op;          ///< "classify", "intersect", "distance" or "verify"
  double tolerance = 2e-4; ///< intersect: geometric tolerance of the traced branches
  long digits = 15;        ///< distance: requested relative precision 10^-digits
  bool solid = false;      ///< distance: between solids (0 when the volumes overlap)
  std::string a, b;        ///< surface names
  core::io::Json claims;   ///< verify: the query object holding "claims" (validated)
  std::string path;        ///< the query's JSON path ("$.queries[i]")
  certify::Mode mode = certify::Mode::Filtered;
  /// How much the answer carries (certify/detail.hpp; a level the op has, checked on reading).
  certify::Detail detail = certify::Detail::Full;
  /// intersect: the box {"min": [x, y, z], "max": [x, y, z]} unbounded curves are traced in
  /// (min then max; absent: chosen automatically).
  std::optional<std::array<double, 6>> box;
};

struct Scene {
  std::vector<std::pair<std::string, core::Surface>> surfaces; ///< any supported surface
  std::vector<Query> queries;
  const core::Surface& surface(const std::string& name) const;
};

/// Throws core::InputError on any problem (with JSON path, line, column).
Scene read_scene(const core::io::Json& doc, const std::string& source, certify::Mode default_mode);

/// One result object: {"id", "op", "a", "b", "status", "mode", "result" | "error"}.
core::io::Json run_query(const Scene& s, const Query& q, std::string* text_summary = nullptr);

/// Thrown (through FLINT's C frames) by the handler install_flint_abort_handler installs, in
/// place of FLINT's default flint_abort (which calls abort()).
struct FlintAbort : std::runtime_error {
  FlintAbort();
};

/// Installs (once, idempotent) a flint_abort handler that flushes stdout (where FLINT prints
/// its diagnostic) and throws FlintAbort.
void install_flint_abort_handler();

struct BatchStats {
  long lines = 0, errors = 0, fallbacks = 0, undecided = 0, certified = 0;
  long internal = 0; ///< error lines of kind "internal" (also counted in errors)
};

/// How a batch answers one line (default: process_batch_line; tests substitute their own).
using BatchAnswer = std::function<core::io::Json(const std::string& line, long line_no,
                                                 certify::Mode default_mode, bool* fallback)>;

/// Reads JSON lines from `in`, writes result lines to `out` in input order, each flushed as
/// soon as it and every earlier line are answered; at most `threads` lines answered at once.
/// Any exception escaping `answer` (e.g. FlintAbort) gives that line an "internal" error line.
/// `progress`, when given, is called after each written line with the counts so far (from the
/// writing stage: one call at a time). ordered = false writes each answer as soon as it is done
/// (input order is then not kept: callers key answers by their "id").
BatchStats process_batch(std::istream& in, std::ostream& out, certify::Mode default_mode,
                         int threads, const BatchAnswer& answer = {},
                         const std::function<void(const BatchStats&)>& progress = {},
                         bool ordered = true);

/// The error line of a line whose computation failed inside (not a bad input):
/// {"id": id, "status": "error", "error": {"kind": "internal", "message": message}}.
core::io::Json internal_error_line(const core::io::Json& id, const std::string& message);

/// One batch line -> one result line (exposed for tests). line_no is 1-based. The line's
/// "budget_ms" (else default_budget_ms; 0 = none) limits its wall time: past it the answer is
/// undecided with "reason": "budget" (core/budget.hpp). Every answer carries "time_ms".
/// The line's "detail" (a level its op has, certify/detail.hpp) else default_detail mapped
/// onto the op (detail_for_op) sets how much the answer carries and so computes.
/// The line's "label" (any JSON value; `surfcert generate` writes one) is not read, only
/// echoed in the answer as "label".
core::io::Json process_batch_line(const std::string& line, long line_no, certify::Mode default_mode,
                                  bool* fallback = nullptr, double default_budget_ms = 0,
                                  certify::Detail default_detail = certify::Detail::Full);

} // namespace surfcert::app
