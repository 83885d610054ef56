// surfcert::app scenes and batches: the `run` and `batch` front ends of the application layer
// (built on surfcert::certify for the decisions and surfcert::trace for the curve branches).
//
// A Scene names surfaces and lists queries; read_scene validates the whole document before
// anything is computed (so a bad scene produces an error and no report). run_query computes
// only what its op needs: "classify" builds the pencil and decides the topology, nothing else;
// "intersect" adds the branches of the curve (traced or produced as conics); "distance" takes
// any two surfaces (quadrics or tori), the other ops need two quadrics (checked on reading).
// process_batch reads JSON lines and writes one JSON line per input line, in input order,
// using N worker threads; a bad line yields an error line and the batch goes on.
#pragma once

#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/surface.hpp"

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace surfcert::app {

struct Query {
  core::io::Json id;       ///< as given (null when absent)
  std::string op;          ///< "classify" or "intersect"
  double tolerance = 2e-4; ///< intersect: geometric tolerance of the traced branches
  long digits = 15;        ///< distance: requested relative precision 10^-digits
  bool solid = false;      ///< distance: between solids (0 when the volumes overlap)
  std::string a, b;        ///< surface names
  certify::Mode mode = certify::Mode::Filtered;
};

struct Scene {
  std::vector<std::pair<std::string, core::Surface>> surfaces; ///< quadrics or tori
  std::vector<Query> queries;
  const core::Surface& surface(const std::string& name) const;
};

/// Throws core::InputError on any problem (with JSON path, line, column).
Scene read_scene(const core::io::Json& doc, const std::string& source,
                 certify::Mode default_mode);

/// One result object: {"id", "op", "a", "b", "status", "mode", "result" | "error"}.
core::io::Json run_query(const Scene& s, const Query& q, std::string* text_summary = nullptr);

struct BatchStats {
  long lines = 0, errors = 0, fallbacks = 0, undecided = 0;
};

/// Reads JSON lines from `in`, writes result lines to `out` in input order.
BatchStats process_batch(std::istream& in, std::ostream& out, certify::Mode default_mode,
                         int threads);

/// One batch line -> one result line (exposed for tests). line_no is 1-based.
core::io::Json process_batch_line(const std::string& line, long line_no,
                                  certify::Mode default_mode, bool* fallback = nullptr);

} // namespace surfcert::app
