// surfcert::app the answer of one batch line as text (what `surfcert batch` writes).
//
// What it represents: answer_batch_line(line) is byte for byte dump(process_batch_line(line))
// (scene.hpp) apart from the answer's own "time_ms": the same fields, values and errors. The
// common lines (classify, intersect, distance on double shapes, double 4x4 matrices and
// equations) are read by a fast reader (simdjson On-Demand: the number literals' text, read
// with the same exact semantics as surface_reader.hpp) and a classify answer at detail
// "topology" is written directly; anything else, any error and any unusual form takes the
// document route of process_batch_line, so error messages keep their lines, columns and JSON
// paths.
#pragma once

#include "surfcert/app/batch_stream.hpp"
#include "surfcert/certify/detail.hpp"
#include "surfcert/core/io/json.hpp"

#include <string>

namespace surfcert::app {

/// One batch line -> its answer line (see above). line_no is 1-based.
BatchLineAnswer answer_batch_line(const std::string& line, long line_no, certify::Mode default_mode,
                                  double default_budget_ms = 0,
                                  certify::Detail default_detail = certify::Detail::Full);

/// The answer line of an answer document r: its text, status and error kind (the fields the
/// batch's summary counts); the caller sets the exact-fallback flag.
void set_answer_from_document(BatchLineAnswer& a, const core::io::Json& r);

} // namespace surfcert::app
