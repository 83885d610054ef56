// surfcert::app a batch line once read: what its answer needs, and the answer's fields.
//
// What it represents: the op, mode, detail, budget and op parameters of a classify, intersect
// or distance line (read by either batch reader: process_batch_line's document route or the
// fast reader of batch_line.hpp), and the one place that turns them and the two surfaces into
// the answer's fields after "id" (batch_envelope): the decision under the line's time budget
// (core/budget.hpp), or the budget's undecided answer when it runs out.
// Also the readers of a line's scalar fields, shared by both routes (errors: InputError at
// the given source and JSON path).
#pragma once

#include "surfcert/certify/detail.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/surface.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <array>
#include <functional>
#include <optional>
#include <string>

namespace surfcert::app {

struct BatchQuery {
  std::string op; ///< "classify", "intersect" or "distance"
  certify::Mode mode = certify::Mode::Filtered;
  certify::Detail detail = certify::Detail::Full;
  double budget_ms = 0;            ///< 0: none
  long digits = 15;                ///< distance
  bool solid = false;              ///< distance
  std::optional<double> tolerance; ///< intersect (else trace::TraceOptions' default)
  /// intersect: the box {min x, y, z, max x, y, z} the branches are traced in, if any
  std::optional<std::array<double, 6>> box;
};

/// The fields of the answer after "id": {"status", "mode", ..., "result"} of the decision, or
/// {"status": "undecided", "reason": "budget", "note"} when q.budget_ms ran out. classify and
/// intersect need two quadrics (the readers check). fallback: whether the filtered decision
/// fell back to exact arithmetic.
core::io::Json batch_envelope(const BatchQuery& q, const core::Surface& a, const core::Surface& b,
                              bool* fallback);

/// `decide` under a budget of budget_ms (0: none); its answer, or the budget's undecided one.
core::io::Json budget_limited(double budget_ms, const std::function<core::io::Json()>& decide);

/// The undecided answer of a line whose budget ran out.
core::io::Json budget_undecided_envelope(double budget_ms);

/// The decision of a classify line, completed to q.detail (certify/report.hpp).
certify::QsicResult batch_classify(const BatchQuery& q, const core::QuadricMatrix& a,
                                   const core::QuadricMatrix& b);

/// The decision and branches of an intersect line (trace/intersect_curve.hpp), its report data
/// those of q.detail.
trace::CurveResult batch_intersect(const BatchQuery& q, const core::QuadricMatrix& a,
                                   const core::QuadricMatrix& b);

certify::Mode read_mode(const core::io::Json& v, const std::string& source,
                        const std::string& path);
/// A detail level that op has (certify/detail.hpp).
certify::Detail read_detail(const core::io::Json& v, const std::string& source,
                            const std::string& path, const std::string& op);
/// digits: an integer from 1 to 1000.
long read_digits(const core::io::Json& v, const std::string& source, const std::string& path);
bool read_bool(const core::io::Json& v, const std::string& source, const std::string& path);
/// tolerance: 1e-12 to 1.
double read_tolerance(const core::io::Json& v, const std::string& source, const std::string& path);
/// budget_ms: a time limit in milliseconds, 0 (none) to 1e9.
double read_budget(const core::io::Json& v, const std::string& source, const std::string& path);

} // namespace surfcert::app
