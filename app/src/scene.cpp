#include "surfcert/app/scene.hpp"

#include "surfcert/app/batch_line.hpp"
#include "surfcert/app/batch_query.hpp"
#include "surfcert/app/batch_stream.hpp"
#include "surfcert/app/generate.hpp"
#include "surfcert/app/verify.hpp"

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/report.hpp"
#include "surfcert/core/budget.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <flint/flint.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <istream>
#include <mutex>
#include <ostream>
#include <set>
#include <tuple>

namespace surfcert::app {

using certify::classify_qsic;
using certify::complete_report_data;
using certify::distance_envelope_json;
using certify::DistanceResult;
using certify::input_error_json;
using certify::Mode;
using certify::parse_mode;
using certify::qsic_envelope_json;
using certify::qsic_result_text;
using certify::QsicResult;
using certify::surface_distance;
using certify::to_string;
using core::InputError;
using core::Location;
using core::Rational;
using core::io::Json;
using core::io::json_path_child;
using core::io::json_path_index;
using trace::curve_envelope_json;
using trace::CurveResult;
using trace::intersect_curve;

namespace {

using core::io::check_fields;

Location at(const Json& v, const std::string& source, const std::string& path) {
  return core::io::json_location(v, source, path);
}

const char* kSupportedOps = "\"classify\", \"intersect\", \"distance\" or \"verify\"";

bool known_op(const Json* op) {
  return op && op->is_string() &&
         (op->text() == "classify" || op->text() == "intersect" || op->text() == "distance" ||
          op->text() == "verify");
}

std::string curve_summary(const CurveResult& c) {
  std::string s = "curve: " + std::string(to_string(c.status)) + ", " +
                  std::to_string(c.branches.size()) + " branch(es):";
  for (const auto& b : c.branches)
    s += " " + b.kind + "(" + std::to_string(b.points.size()) + " pts)";
  s += ", " + std::to_string(c.isolated_points.size()) + " isolated point(s), max residual ";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", c.max_residual);
  s += buf;
  if (!c.note.empty()) s += "\nnote: " + c.note;
  return s + "\n";
}

} // namespace

Mode read_mode(const Json& v, const std::string& source, const std::string& path) {
  auto m = v.is_string() ? parse_mode(v.text()) : std::nullopt;
  if (!m)
    throw InputError(at(v, source, path), "a mode: \"exact\", \"filtered\" or \"float\"",
                     v.is_string() ? "\"" + v.text() + "\"" : core::io::type_name(v.type()));
  return *m;
}

certify::Detail read_detail(const Json& v, const std::string& source, const std::string& path,
                            const std::string& op) {
  auto d = v.is_string() ? certify::parse_detail(v.text()) : std::nullopt;
  if (!d || !certify::detail_accepted(op, *d))
    throw InputError(at(v, source, path),
                     std::string("a detail for ") + op + ": " + certify::detail_spellings(op),
                     v.is_string() ? "\"" + v.text() + "\"" : core::io::type_name(v.type()));
  return *d;
}

long read_digits(const Json& v, const std::string& source, const std::string& path) {
  Rational d = core::io::read_number(v, source, path);
  if (!d.is_integer() || d < Rational(1) || d > Rational(1000))
    throw InputError(at(v, source, path), "digits: an integer from 1 to 1000", d.to_string());
  return static_cast<long>(d.to_double_approx());
}

bool read_bool(const Json& v, const std::string& source, const std::string& path) {
  if (!v.is_bool())
    throw InputError(at(v, source, path), "true or false", core::io::type_name(v.type()));
  return v.as_bool();
}

double read_tolerance(const Json& v, const std::string& source, const std::string& path) {
  Rational t = core::io::read_number(v, source, path);
  double d = t.to_double_approx();
  if (!(d >= 1e-12 && d <= 1))
    throw InputError(at(v, source, path), "a tolerance between 1e-12 and 1",
                     t.to_decimal_approx(6));
  return d;
}

namespace {

// box: {"min": [x, y, z], "max": [x, y, z]} with min < max in every coordinate.
std::array<double, 6> read_box(const Json& v, const std::string& source, const std::string& path) {
  if (!v.is_object())
    throw InputError(at(v, source, path), "a box {\"min\": [x, y, z], \"max\": [x, y, z]}",
                     core::io::type_name(v.type()));
  check_fields(v, {"min", "max"}, source, path);
  std::array<double, 6> out{};
  for (int e = 0; e < 2; ++e) {
    const char* key = e == 0 ? "min" : "max";
    const std::string kp = json_path_child(path, key);
    const Json* c = v.find(key);
    if (!c || !c->is_array() || c->items().size() != 3)
      throw InputError(at(c ? *c : v, source, kp), "an array of three numbers",
                       c ? core::io::type_name(c->type()) : "none");
    for (size_t k = 0; k < 3; ++k) {
      const double d =
          core::io::read_number(c->items()[k], source, json_path_index(kp, k)).to_double_approx();
      if (!std::isfinite(d))
        throw InputError(at(c->items()[k], source, json_path_index(kp, k)), "a finite number",
                         "a number beyond the double range");
      out[static_cast<size_t>(3 * e) + k] = d;
    }
  }
  for (size_t k = 0; k < 3; ++k)
    if (!(out[k] < out[k + 3]))
      throw InputError(at(v, source, path), "min < max in every coordinate",
                       "min[" + std::to_string(k) + "] >= max[" + std::to_string(k) + "]");
  return out;
}

trace::TraceOptions trace_options(double tolerance,
                                  const std::optional<std::array<double, 6>>& box) {
  trace::TraceOptions opt;
  opt.tolerance = tolerance;
  if (box) {
    trace::Box b;
    for (size_t k = 0; k < 3; ++k) {
      b.min[k] = (*box)[k];
      b.max[k] = (*box)[k + 3];
    }
    opt.box = b;
  }
  return opt;
}

} // namespace

double read_budget(const Json& v, const std::string& source, const std::string& path) {
  Rational t = core::io::read_number(v, source, path);
  double d = t.to_double_approx();
  if (!(d >= 0 && d <= 1e9))
    throw InputError(at(v, source, path), "a budget in milliseconds, 0 (none) to 1e9",
                     t.to_decimal_approx(6));
  return d;
}

Json budget_undecided_envelope(double budget_ms) {
  Json env = Json::object();
  env.set("status", Json::string("undecided"));
  env.set("reason", Json::string("budget"));
  char ms[32];
  std::snprintf(ms, sizeof ms, "%g", budget_ms);
  env.set("note", Json::string(std::string("the time budget of ") + ms +
                               " ms ran out before the answer was proven"));
  return env;
}

Json budget_limited(double budget_ms, const std::function<Json()>& decide) {
  // Past the budget the line answers undecided with reason "budget" (a distance keeps what
  // its earlier routes established; core/budget.hpp); other lines are not held up by it.
  core::BudgetScope budget(budget_ms);
  try {
    return decide();
  } catch (const core::BudgetExceeded&) {
    return budget_undecided_envelope(budget_ms);
  }
}

QsicResult batch_classify(const BatchQuery& q, const core::QuadricMatrix& a,
                          const core::QuadricMatrix& b) {
  QsicResult r = classify_qsic(a, b, q.mode);
  complete_report_data(r, a, b, q.detail);
  return r;
}

CurveResult batch_intersect(const BatchQuery& q, const core::QuadricMatrix& a,
                            const core::QuadricMatrix& b) {
  trace::TraceOptions opt;
  if (q.tolerance) opt.tolerance = *q.tolerance;
  if (q.box) opt = trace_options(opt.tolerance, q.box);
  return intersect_curve(a, b, q.mode, opt, q.detail);
}

Json batch_envelope(const BatchQuery& q, const core::Surface& sa, const core::Surface& sb,
                    bool* fallback) {
  return budget_limited(q.budget_ms, [&]() -> Json {
    if (q.op == "distance")
      return distance_envelope_json(surface_distance(sa, sb, q.digits, q.solid, q.mode), q.digits,
                                    q.detail);
    const auto& a = std::get<core::QuadricMatrix>(sa);
    const auto& b = std::get<core::QuadricMatrix>(sb);
    if (q.op == "intersect") {
      CurveResult c = batch_intersect(q, a, b);
      if (fallback) *fallback = c.topology.exact_fallback;
      return curve_envelope_json(c, a, b, q.detail);
    }
    QsicResult r = batch_classify(q, a, b);
    if (fallback) *fallback = r.exact_fallback;
    return qsic_envelope_json(r, a, b, q.detail);
  });
}

const core::Surface& Scene::surface(const std::string& name) const {
  for (const auto& [n, q] : surfaces)
    if (n == name) return q;
  throw std::out_of_range("no surface " + name);
}

Scene read_scene(const Json& doc, const std::string& source, Mode default_mode) {
  Scene s;
  if (!doc.is_object())
    throw InputError(at(doc, source, "$"),
                     "a scene object {\"surfaces\": {...}, \"queries\": [...]}",
                     core::io::type_name(doc.type()));
  check_fields(doc, {"surfaces", "queries", "mode", "description"}, source, "$");
  if (const Json* m = doc.find("mode")) default_mode = read_mode(*m, source, "$.mode");
  const Json* surf = doc.find("surfaces");
  if (!surf || !surf->is_object())
    throw InputError(at(surf ? *surf : doc, source, "$.surfaces"),
                     "an object mapping names to surfaces",
                     surf ? core::io::type_name(surf->type()) : "no \"surfaces\" field");
  for (const auto& [name, v] : surf->members())
    s.surfaces.emplace_back(name,
                            core::io::read_surface(v, source, json_path_child("$.surfaces", name)));
  const Json* qs = doc.find("queries");
  if (!qs || !qs->is_array())
    throw InputError(at(qs ? *qs : doc, source, "$.queries"), "an array of queries",
                     qs ? core::io::type_name(qs->type()) : "no \"queries\" field");
  for (size_t i = 0; i < qs->size(); ++i) {
    const Json& q = qs->items()[i];
    std::string path = json_path_index("$.queries", i);
    if (!q.is_object())
      throw InputError(at(q, source, path), "a query object", core::io::type_name(q.type()));
    check_fields(
        q,
        {"id", "op", "a", "b", "mode", "tolerance", "digits", "solid", "detail", "claims", "box"},
        source, path);
    Query query;
    query.mode = default_mode;
    if (const Json* id = q.find("id")) query.id = *id;
    const Json* op = q.find("op");
    if (!known_op(op))
      throw InputError(
          at(op ? *op : q, source, json_path_child(path, "op")),
          std::string("an op: ") + kSupportedOps,
          op ? (op->is_string() ? "\"" + op->text() + "\"" : core::io::type_name(op->type()))
             : "none");
    query.op = op->text();
    for (const char* key : {"a", "b"}) {
      const Json* n = q.find(key);
      std::string kp = json_path_child(path, key);
      if (!n || !n->is_string())
        throw InputError(at(n ? *n : q, source, kp), "the name of a surface of $.surfaces",
                         n ? core::io::type_name(n->type()) : "none");
      const core::Surface* found = nullptr;
      for (const auto& sf : s.surfaces)
        if (sf.first == n->text()) found = &sf.second;
      if (!found)
        throw InputError(at(*n, source, kp), "the name of a surface of $.surfaces",
                         "\"" + n->text() + "\"");
      if (query.op != "distance" && query.op != "verify" &&
          !std::holds_alternative<core::QuadricMatrix>(*found))
        throw InputError(at(*n, source, kp), "a quadric (\"" + query.op + "\" needs two quadrics)",
                         "\"" + n->text() + "\" (" + core::surface_found(*found) + ")");
      (std::string(key) == "a" ? query.a : query.b) = n->text();
    }
    if (const Json* m = q.find("mode"))
      query.mode = read_mode(*m, source, json_path_child(path, "mode"));
    if (const Json* t = q.find("tolerance"))
      query.tolerance = read_tolerance(*t, source, json_path_child(path, "tolerance"));
    if (const Json* bx = q.find("box"))
      query.box = read_box(*bx, source, json_path_child(path, "box"));
    if (const Json* d = q.find("digits"))
      query.digits = read_digits(*d, source, json_path_child(path, "digits"));
    if (const Json* sd = q.find("solid"))
      query.solid = read_bool(*sd, source, json_path_child(path, "solid"));
    if (const Json* dj = q.find("detail"))
      query.detail = read_detail(*dj, source, json_path_child(path, "detail"), query.op);
    if (query.op == "verify") {
      check_claims(s.surface(query.a), s.surface(query.b), q, source, path);
      query.claims = q;
    } else if (const Json* c = q.find("claims")) {
      throw InputError(at(*c, source, json_path_child(path, "claims")),
                       "no \"claims\" (only a verify query has them)", "claims");
    }
    query.path = path;
    s.queries.push_back(std::move(query));
  }
  return s;
}

Json run_query(const Scene& s, const Query& q, std::string* text_summary) {
  Json env;
  if (q.op == "distance") {
    DistanceResult d = surface_distance(s.surface(q.a), s.surface(q.b), q.digits, q.solid, q.mode);
    env = distance_envelope_json(d, q.digits, certify::detail_for_op(q.op, q.detail));
    if (text_summary)
      *text_summary =
          "distance: " + std::string(to_string(d.status)) +
          (d.distance
               ? " in [" + d.lower() + ", " + d.upper() + "], minimizers " + d.minimizers.str()
           : d.estimate ? " estimate " + std::to_string(d.estimate->value)
                        : std::string()) +
          (d.note.empty() ? "" : "\nnote: " + d.note) +
          (d.method == certify::Method::None ? ""
                                             : "\nmethod: " + std::string(to_string(d.method)) +
                                                   " (mode " + to_string(d.mode) + ")") +
          "\n";
  } else if (q.op == "verify") {
    env = verify_claims(s.surface(q.a), s.surface(q.b), q.claims, "", q.mode, q.path);
    if (text_summary) {
      *text_summary = "verify: " + env.find("status")->text() + "\n";
      const Json& vs = *env.find("result")->find("verdicts");
      for (size_t i = 0; i < vs.size(); ++i)
        *text_summary += "  claim " + std::to_string(i + 1) + " (" +
                         vs.items()[i].find("kind")->text() +
                         "): " + vs.items()[i].find("verdict")->text() + "\n";
    }
  } else if (q.op == "intersect") {
    const auto& a = std::get<core::QuadricMatrix>(s.surface(q.a));
    const auto& b = std::get<core::QuadricMatrix>(s.surface(q.b));
    const trace::TraceOptions opt = trace_options(q.tolerance, q.box);
    CurveResult c = intersect_curve(a, b, q.mode, opt, q.detail);
    env = curve_envelope_json(c, a, b, q.detail);
    if (text_summary) *text_summary = qsic_result_text(c.topology, a, b) + curve_summary(c);
  } else {
    const auto& a = std::get<core::QuadricMatrix>(s.surface(q.a));
    const auto& b = std::get<core::QuadricMatrix>(s.surface(q.b));
    QsicResult r = classify_qsic(a, b, q.mode);
    complete_report_data(r, a, b, q.detail);
    env = qsic_envelope_json(r, a, b, q.detail);
    if (text_summary) *text_summary = qsic_result_text(r, a, b);
  }
  Json o = Json::object();
  o.set("id", q.id);
  o.set("op", Json::string(q.op));
  o.set("a", Json::string(q.a));
  o.set("b", Json::string(q.b));
  for (auto& [k, v] : env.take_members())
    o.set(k, std::move(v));
  return o;
}

Json process_batch_line(const std::string& line, long line_no, Mode default_mode, bool* fallback,
                        double default_budget_ms, certify::Detail default_detail) {
  const auto t0 = std::chrono::steady_clock::now();
  // Every answer reports its own wall time (parse, decide, build the answer).
  auto timed = [t0](Json o) {
    char buf[32];
    std::snprintf(
        buf, sizeof buf, "%.3f",
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    o.set("time_ms", Json::number_text(buf));
    return o;
  };
  Json out = Json::object();
  out.set("id", Json::null());
  const std::string source = "<stdin>";
  try {
    Json doc;
    try {
      doc = core::io::parse_json(line, source);
    } catch (const InputError& e) {
      Location w = e.where();
      w.line = static_cast<int>(line_no);
      throw InputError(w, e.expected(), e.found());
    }
    if (const Json* id = doc.is_object() ? doc.find("id") : nullptr) out.set("id", *id);
    auto fix = [&](const InputError& e) {
      Location w = e.where();
      w.line = static_cast<int>(line_no);
      return InputError(w, e.expected(), e.found());
    };
    try {
      if (!doc.is_object())
        throw InputError(at(doc, source, "$"), "a JSON object {\"id\", \"op\", \"a\", \"b\"}",
                         core::io::type_name(doc.type()));
      const Json* op = doc.find("op");
      // generate (app/generate.hpp): no surfaces; the answer's result holds the generated lines.
      if (op && op->is_string() && op->text() == "generate") {
        Json env = generate_envelope(read_generate_line(doc, source), doc, source);
        for (auto& [k, v] : env.take_members())
          out.set(k, std::move(v));
        return timed(std::move(out));
      }
      check_fields(doc,
                   {"id", "op", "a", "b", "mode", "tolerance", "digits", "solid", "budget_ms",
                    "claims", "detail", "label", "box"},
                   source, "$");
      if (!known_op(op))
        throw InputError(
            at(op ? *op : doc, source, "$.op"),
            std::string("an op: ") + kSupportedOps + " (or \"generate\")",
            op ? (op->is_string() ? "\"" + op->text() + "\"" : core::io::type_name(op->type()))
               : "none");
      Mode mode = default_mode;
      if (const Json* m = doc.find("mode")) mode = read_mode(*m, source, "$.mode");
      // The batch default maps onto the nearest level the op has; a line's own must be one.
      certify::Detail detail = certify::detail_for_op(op->text(), default_detail);
      if (const Json* dj = doc.find("detail"))
        detail = read_detail(*dj, source, "$.detail", op->text());
      const Json* ja = doc.find("a");
      const Json* jb = doc.find("b");
      if (!ja) throw InputError(at(doc, source, "$.a"), "a surface \"a\"", "none");
      if (!jb) throw InputError(at(doc, source, "$.b"), "a surface \"b\"", "none");
      core::io::Readings readings; // how float data was read exactly (surface_reader.hpp)
      const core::Surface sa = core::io::read_surface(*ja, source, "$.a", &readings);
      const core::Surface sb = core::io::read_surface(*jb, source, "$.b", &readings);
      const core::QuadricMatrix* a = std::get_if<core::QuadricMatrix>(&sa);
      const core::QuadricMatrix* b = std::get_if<core::QuadricMatrix>(&sb);
      // distance and verify take any two surfaces (verify refuses a quadric-only claim).
      if (op->text() != "distance" && op->text() != "verify")
        for (const auto& [q, s, j, key] :
             {std::make_tuple(a, &sa, ja, "$.a"), std::make_tuple(b, &sb, jb, "$.b")})
          if (!q)
            throw InputError(at(*j, source, key),
                             "a quadric (\"" + op->text() + "\" needs two quadrics)",
                             core::surface_found(*s));
      BatchQuery q;
      q.op = op->text();
      q.mode = mode;
      q.detail = detail;
      q.budget_ms = default_budget_ms;
      if (const Json* bj = doc.find("budget_ms"))
        q.budget_ms = read_budget(*bj, source, "$.budget_ms");
      if (q.op == "distance") {
        if (const Json* d = doc.find("digits")) q.digits = read_digits(*d, source, "$.digits");
        if (const Json* sd = doc.find("solid")) q.solid = read_bool(*sd, source, "$.solid");
      } else if (q.op == "intersect") {
        if (const Json* t = doc.find("tolerance"))
          q.tolerance = read_tolerance(*t, source, "$.tolerance");
        if (const Json* bx = doc.find("box")) q.box = read_box(*bx, source, "$.box");
      }
      Json env = q.op == "verify"
                     ? budget_limited(q.budget_ms,
                                      [&] { return verify_claims(sa, sb, doc, source, mode); })
                     : batch_envelope(q, sa, sb, fallback);
      for (auto& [k, v] : env.take_members()) // moved: the branches' points are most of it
        out.set(k, std::move(v));
      if (!readings.empty()) out.set("readings", core::io::readings_json(readings));
      // A line's "label" (any JSON, e.g. what `surfcert generate` wrote) is echoed untouched,
      // so answers and expectations travel together.
      if (const Json* label = doc.find("label")) out.set("label", *label);
    } catch (const InputError& e) {
      throw fix(e);
    }
  } catch (const InputError& e) {
    out.set("status", Json::string("error"));
    // Every input error of a line has a JSON path: "$", the line as a whole, when it is not in
    // one value (a line that is not JSON; its column says where parsing stopped).
    Location w = e.where();
    if (w.json_path.empty()) w.json_path = "$";
    out.set("error", input_error_json(InputError(w, e.expected(), e.found())));
  } catch (const std::exception& e) {
    return timed(internal_error_line(*out.find("id"), e.what()));
  }
  return timed(std::move(out));
}

Json internal_error_line(const Json& id, const std::string& message) {
  Json out = Json::object();
  out.set("id", id);
  out.set("status", Json::string("error"));
  Json err = Json::object();
  err.set("kind", Json::string("internal"));
  err.set("message", Json::string(message));
  out.set("error", err);
  return out;
}

FlintAbort::FlintAbort()
    : std::runtime_error("FLINT/Arb aborted (flint_abort: an internal error in the arithmetic "
                         "library)") {}

namespace {

[[noreturn]] void throw_flint_abort() {
  std::fflush(stdout); // FLINT printed its diagnostic with printf just before aborting
  throw FlintAbort();
}

} // namespace

void install_flint_abort_handler() {
  static std::once_flag once;
  std::call_once(once, [] { flint_set_abort(&throw_flint_abort); });
}

BatchStats process_batch(std::istream& in, std::ostream& out, Mode default_mode, int threads,
                         const BatchAnswer& answer,
                         const std::function<void(const BatchStats&)>& progress, bool ordered) {
  auto text_answer = [&answer](const std::string& line, long line_no, Mode mode) {
    BatchLineAnswer a;
    const Json r = answer ? answer(line, line_no, mode, &a.fallback)
                          : process_batch_line(line, line_no, mode, &a.fallback);
    set_answer_from_document(a, r);
    return a;
  };
  return detail::run_batch_pipeline(
      // One line per chunk (never "already there"): a stream cannot say whether its next line
      // has arrived, and a caller may be waiting for this answer before it sends more.
      [&in, held = std::string()](std::string_view& line, bool may_wait) mutable {
        if (!may_wait) return detail::NextLine::WouldBlock;
        if (!std::getline(in, held)) return detail::NextLine::End;
        line = held;
        return detail::NextLine::Line;
      },
      [&out](const BatchLineAnswer& a) {
        out << a.text << '\n';
        out.flush();
      },
      default_mode, text_answer, threads, ordered, progress);
}

} // namespace surfcert::app
