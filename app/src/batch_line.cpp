#include "surfcert/app/batch_line.hpp"

#include "surfcert/app/batch_query.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/report.hpp"
#include "surfcert/core/budget.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <simdjson.h>

#include <array>
#include <cfloat>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string_view>

namespace surfcert::app {

using core::io::Json;
namespace od = simdjson::ondemand;

namespace {

// Any reason the fast reader does not take a line: the document route answers it instead.
struct NotFast {};

template <class T> T get(simdjson::simdjson_result<T>&& r) {
  T v;
  if (std::move(r).get(v) != simdjson::SUCCESS) throw NotFast{};
  return v;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() &&
         (s.back() == ' ' || s.back() == '\t' || s.back() == '\n' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

// What one pass over a number literal found (RFC 8259 grammar, as the document parser accepts
// it): valid, an integer (no fraction, no exponent) of how many digits, and whether a digit of
// its mantissa is nonzero.
struct NumberScan {
  bool valid = false, integer = true, nonzero = false;
  size_t int_digits = 0;
};

NumberScan scan_json_number(std::string_view s) {
  NumberScan r;
  size_t i = 0;
  auto digit = [&](size_t k) { return k < s.size() && s[k] >= '0' && s[k] <= '9'; };
  if (i < s.size() && s[i] == '-') ++i;
  if (!digit(i)) return r;
  if (s[i] == '0') {
    ++i;
    r.int_digits = 1;
  } else {
    for (; digit(i); ++i, ++r.int_digits)
      r.nonzero = true;
  }
  if (i < s.size() && s[i] == '.') {
    ++i;
    r.integer = false;
    if (!digit(i)) return r;
    for (; digit(i); ++i)
      r.nonzero = r.nonzero || s[i] != '0';
  }
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    r.integer = false;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (!digit(i)) return r;
    while (digit(i))
      ++i;
  }
  r.valid = i == s.size();
  return r;
}

// The raw text of a number value (not validated).
std::string_view raw_number(od::value v) {
  if (get(v.type()) != od::json_type::number) throw NotFast{};
  return trimmed(v.raw_json_token());
}

// The raw text of a number value (validated).
std::string_view number_text(od::value v) {
  const std::string_view t = raw_number(v);
  if (!scan_json_number(t).valid) throw NotFast{};
  return t;
}

// The common literal -?(0|[1-9][0-9]*)\.[0-9]+ of at most 19 digits takes a shorter road first:
// its digits read 8 at a time, then simdjson's own conversion of those digits and exponent
// (numberparsing::compute_float_64 of the kernel that get_double runs: the same function on the
// same integer and power of ten, so the same double). simdjson's internal API, pinned by the
// system package: batch_line_test compares this reader with the document parser on hard cases.
// It answers only normal values; zero, subnormals and the rare case compute_float_64 declines
// go the general way. The value is left unconsumed (the array or object iteration skips it).
bool plain_decimal(std::string_view t, double& out) {
  namespace np = simdjson::SIMDJSON_BUILTIN_IMPLEMENTATION::numberparsing;
  const char* p = t.data();
  const char* const end = p + t.size();
  auto digit = [&end](const char* q) { return q != end && static_cast<unsigned>(*q - '0') <= 9; };
  const bool negative = p != end && *p == '-';
  p += negative;
  if (!digit(p)) return false;
  const char* const first = p;
  uint64_t w = 0; // overflows only past 19 digits, which are refused below
  if (*p == '0') {
    ++p;
  } else {
    while (digit(p))
      w = 10 * w + static_cast<uint64_t>(*p++ - '0');
  }
  const auto int_digits = p - first;
  if (p == end || *p != '.') return false;
  const char* const frac = ++p;
  while (end - p >= 8 && np::is_made_of_eight_digits_fast(reinterpret_cast<const uint8_t*>(p))) {
    w = w * 100000000 + simdjson::SIMDJSON_BUILTIN_IMPLEMENTATION::parse_eight_digits_unrolled(p);
    p += 8;
  }
  while (digit(p))
    w = 10 * w + static_cast<uint64_t>(*p++ - '0');
  const auto frac_digits = p - frac;
  if (p != end || frac_digits == 0 || int_digits + frac_digits > 19) return false;
  double d = 0;
  if (!np::compute_float_64(-static_cast<int64_t>(frac_digits), w, negative, d)) return false;
  if (!(std::fabs(d) >= DBL_MIN) || !std::isfinite(d)) return false;
  out = d;
  return true;
}

// A number literal read as the shape reader reads one (surface_reader.cpp, literal_double): a
// non-integer literal is the double it rounds to (correctly rounded, as strtod), an integer
// literal of at most 15 digits its exact value. Anything else (longer integers: exact
// rationals; overflow; underflow to zero or subnormals, kept for the exact reader) is not fast.
// simdjson checks the JSON number grammar and rounds correctly (Eisel-Lemire, with its exact
// fallback) in one pass; only the rare values that may be one of the exceptions (|d| >= 1e15:
// an integer of more than 15 digits?; d = 0: an underflow?) look at the text again.
double literal_double(od::value v) {
  const std::string_view t = v.raw_json_token(); // the literal (and trailing white space)
  double d = 0;
  if (plain_decimal(trimmed(t), d)) return d;
  if (v.get_double().get(d) != simdjson::SUCCESS) throw NotFast{};
  const double a = std::fabs(d);
  if (a >= 1e15 || d == 0) {
    const NumberScan n = scan_json_number(trimmed(t));
    if (!n.valid || (n.integer && n.int_digits > 15)) throw NotFast{};
    if (d == 0 && n.nonzero) throw NotFast{}; // underflow to zero (a literal zero is fast)
  }
  if (!std::isfinite(d) || (d != 0 && a < DBL_MIN)) throw NotFast{};
  return d;
}

template <size_t N> std::array<double, N> literal_doubles(od::value v) {
  std::array<double, N> out{};
  size_t n = 0;
  for (auto item : get(v.get_array())) {
    if (n == N) throw NotFast{};
    out[n++] = literal_double(get(std::move(item)));
  }
  if (n != N) throw NotFast{};
  return out;
}

// A string without escapes or control characters: its text is its raw bytes (as the document
// parser and dump() read and write it).
std::string_view plain_string(od::value v) {
  if (get(v.type()) != od::json_type::string) throw NotFast{};
  const std::string_view raw = trimmed(v.raw_json_token());
  if (raw.size() < 2 || raw.find('\\') != std::string_view::npos) throw NotFast{};
  for (char c : raw)
    if (static_cast<unsigned char>(c) < 0x20) throw NotFast{};
  return raw.substr(1, raw.size() - 2);
}

// The keys of one JSON object met so far, by number: each at most once (the document parser
// rejects duplicates).
class Seen {
public:
  void mark(unsigned key) {
    if (has(key)) throw NotFast{};
    bits_ |= 1u << key;
  }
  bool has(unsigned key) const { return (bits_ >> key) & 1u; }
  bool only(unsigned key) const { return bits_ == 1u << key; }

private:
  unsigned bits_ = 0;
};

// A surface the fast reader takes: an equation string, {"equation": string}, {"matrix": 4x4
// doubles} or a quadric shape in doubles ({"type", "center", "radius"/"radii", "rotation":
// {"quaternion"}}); read as read_surface reads it (surface_reader.hpp).
core::Surface read_surface_fast(od::value v, const std::string& path, core::io::Readings& rd) {
  const auto type = get(v.type());
  if (type == od::json_type::string)
    return core::io::read_surface(Json::string(std::string(plain_string(v))), "<stdin>", path, &rd);
  if (type != od::json_type::object) throw NotFast{};
  enum : unsigned { kEq, kMat, kType, kCenter, kRadius, kRadii, kRot };
  Seen seen;
  std::string equation;
  std::array<std::array<double, 4>, 4> m{};
  std::optional<core::ShapeType> shape;
  double radius = 0;
  std::array<double, 3> radii{1, 1, 1}, center{};
  std::array<double, 4> quaternion{};
  size_t radii_read = 0;
  for (auto field : get(v.get_object())) {
    od::field f = get(std::move(field));
    const std::string_view key = get(f.unescaped_key());
    od::value val = f.value();
    if (key == "equation") {
      seen.mark(kEq);
      equation = plain_string(val);
    } else if (key == "matrix") {
      seen.mark(kMat);
      size_t i = 0;
      for (auto row : get(val.get_array())) {
        if (i == 4) throw NotFast{};
        m[i++] = literal_doubles<4>(get(std::move(row)));
      }
      if (i != 4) throw NotFast{};
    } else if (key == "type") {
      seen.mark(kType);
      shape = core::io::shape_type_of_name(plain_string(val));
      if (!shape) throw NotFast{};
    } else if (key == "center") {
      seen.mark(kCenter);
      center = literal_doubles<3>(val);
    } else if (key == "radius") {
      seen.mark(kRadius);
      radius = literal_double(val);
    } else if (key == "radii") {
      seen.mark(kRadii);
      // The count depends on the type, which may come later: 2 or 3, checked below.
      for (auto item : get(val.get_array())) {
        if (radii_read == 3) throw NotFast{};
        radii[radii_read++] = literal_double(get(std::move(item)));
      }
    } else if (key == "rotation") {
      seen.mark(kRot);
      Seen rseen;
      for (auto rf : get(val.get_object())) {
        od::field g = get(std::move(rf));
        if (get(g.unescaped_key()) != "quaternion") throw NotFast{};
        rseen.mark(0);
        quaternion = literal_doubles<4>(g.value());
      }
      if (!rseen.only(0)) throw NotFast{};
    } else {
      throw NotFast{};
    }
  }
  if (seen.only(kEq))
    return core::io::read_surface(Json::string(equation), "<stdin>",
                                  core::io::json_path_child(path, "equation"), &rd);
  if (seen.only(kMat)) {
    auto q = core::io::quadric_of_double_matrix(m, core::io::json_path_child(path, "matrix"), &rd);
    if (!q) throw NotFast{};
    return *q;
  }
  if (!seen.has(kType) || seen.has(kEq) || seen.has(kMat)) throw NotFast{};
  // The fields a shape of this type allows (read_shape): a sphere its radius, a cylinder its
  // radius or radii, the others their radii.
  const bool sphere = *shape == core::ShapeType::Sphere;
  const bool cylinder = *shape == core::ShapeType::Cylinder;
  const bool by_radius = seen.has(kRadius);
  if ((by_radius && seen.has(kRadii)) || (by_radius && !sphere && !cylinder) ||
      (!by_radius && (!seen.has(kRadii) || sphere)))
    throw NotFast{};
  if (!by_radius && radii_read != core::io::shape_radii_count(*shape)) throw NotFast{};
  auto spec = core::io::double_shape_spec(
      *shape, by_radius ? &radius : nullptr, by_radius ? nullptr : &radii,
      seen.has(kCenter) ? &center : nullptr, seen.has(kRot) ? &quaternion : nullptr);
  if (!spec) throw NotFast{};
  return core::QuadricMatrix(*spec);
}

// A line the fast reader takes (batch_line.hpp), read.
struct FastLine {
  std::string id = "null"; ///< the id's JSON text, as dump() writes it
  BatchQuery q;
  std::optional<core::Surface> a, b;
  core::io::Readings readings; ///< a's, then b's (as the document route reads them)
};

FastLine read_fast(const std::string& line, certify::Mode default_mode, double default_budget_ms,
                   certify::Detail default_detail) {
  // simdjson reads up to SIMDJSON_PADDING bytes past the end: the batch reader leaves room,
  // other callers' lines are copied.
  thread_local od::parser parser;
  thread_local std::string padded;
  simdjson::padded_string_view view;
  if (line.capacity() - line.size() >= simdjson::SIMDJSON_PADDING) {
    view = simdjson::padded_string_view(line.data(), line.size(), line.capacity());
  } else {
    padded.reserve(line.size() + simdjson::SIMDJSON_PADDING);
    padded.assign(line);
    view = simdjson::padded_string_view(padded.data(), padded.size(), padded.capacity());
  }
  od::document doc = get(parser.iterate(view));
  enum : unsigned { kId, kOp, kA, kB, kMode, kDetail, kBudget, kDigits, kSolid, kTol };
  Seen seen;
  FastLine fl;
  std::string_view detail_text, budget_text, digits_text, tolerance_text;
  core::io::Readings rb;
  bool solid = false;
  for (auto field : get(doc.get_object())) {
    od::field f = get(std::move(field));
    const std::string_view key = get(f.unescaped_key());
    od::value v = f.value();
    if (key == "id") {
      seen.mark(kId);
      switch (get(v.type())) {
      case od::json_type::number:
        fl.id = number_text(v);
        break;
      case od::json_type::string:
        fl.id = "\"" + std::string(plain_string(v)) + "\"";
        break;
      case od::json_type::boolean:
        fl.id = get(v.get_bool()) ? "true" : "false";
        break;
      case od::json_type::null:
        if (!get(v.is_null())) throw NotFast{};
        break;
      default:
        throw NotFast{};
      }
    } else if (key == "op") {
      seen.mark(kOp);
      const std::string_view op = plain_string(v); // compared in place, then copied
      if (op != "classify" && op != "intersect" && op != "distance") throw NotFast{};
      fl.q.op = op;
    } else if (key == "a") {
      seen.mark(kA);
      fl.a = read_surface_fast(v, "$.a", fl.readings);
    } else if (key == "b") {
      seen.mark(kB);
      fl.b = read_surface_fast(v, "$.b", rb);
    } else if (key == "mode") {
      seen.mark(kMode);
      auto m = certify::parse_mode(std::string(plain_string(v)));
      if (!m) throw NotFast{};
      default_mode = *m;
    } else if (key == "detail") {
      seen.mark(kDetail);
      detail_text = plain_string(v);
    } else if (key == "budget_ms") {
      seen.mark(kBudget);
      budget_text = number_text(v);
    } else if (key == "digits") {
      seen.mark(kDigits);
      digits_text = number_text(v);
    } else if (key == "solid") {
      seen.mark(kSolid);
      solid = get(v.get_bool());
    } else if (key == "tolerance") {
      seen.mark(kTol);
      tolerance_text = number_text(v);
    } else {
      throw NotFast{};
    }
  }
  // Nothing after the object (the document is exhausted: no location left in it).
  if (doc.current_location().error() != simdjson::OUT_OF_BOUNDS) throw NotFast{};
  if (!seen.has(kOp) || !seen.has(kA) || !seen.has(kB)) throw NotFast{};
  fl.readings.insert(fl.readings.end(), rb.begin(), rb.end());
  BatchQuery& q = fl.q;
  const std::string_view op = q.op; // views compare inline (std::string's == calls compare)
  q.mode = default_mode;
  q.detail = certify::detail_for_op(op, default_detail);
  if (seen.has(kDetail)) {
    auto d = certify::parse_detail(detail_text);
    if (!d || !certify::detail_accepted(op, *d)) throw NotFast{};
    q.detail = *d;
  }
  if (op != "distance" && (!std::holds_alternative<core::QuadricMatrix>(*fl.a) ||
                           !std::holds_alternative<core::QuadricMatrix>(*fl.b)))
    throw NotFast{};
  // The scalar fields through the document route's own readers (an error: not fast).
  auto number = [](std::string_view t) { return Json::number_text(std::string(t)); };
  q.budget_ms = default_budget_ms;
  if (seen.has(kBudget)) q.budget_ms = read_budget(number(budget_text), "<stdin>", "$.budget_ms");
  if (op == "distance") {
    if (seen.has(kDigits)) q.digits = read_digits(number(digits_text), "<stdin>", "$.digits");
    q.solid = solid;
  } else if (op == "intersect" && seen.has(kTol)) {
    q.tolerance = read_tolerance(number(tolerance_text), "<stdin>", "$.tolerance");
  }
  return fl;
}

BatchLineAnswer document_route(const std::string& line, long line_no, certify::Mode mode,
                               double budget_ms, certify::Detail detail) {
  BatchLineAnswer a;
  const Json r = process_batch_line(line, line_no, mode, &a.fallback, budget_ms, detail);
  set_answer_from_document(a, r);
  return a;
}

// A wall time in milliseconds with 3 decimals (as "%.3f" writes it, up to a tie's rounding),
// without printf's cost.
void append_ms(std::string& out, std::chrono::steady_clock::duration d) {
  const long long us =
      (std::chrono::duration_cast<std::chrono::nanoseconds>(d).count() + 500) / 1000;
  char buf[32];
  char* p = std::to_chars(buf, buf + 24, us / 1000).ptr;
  const long long frac = us % 1000;
  *p++ = '.';
  *p++ = static_cast<char>('0' + frac / 100);
  *p++ = static_cast<char>('0' + frac / 10 % 10);
  *p++ = static_cast<char>('0' + frac % 10);
  out.append(buf, p);
}

// The members of an envelope, as dump() writes them inside the answer object.
void append_members(std::string& out, const Json& env) {
  for (const auto& [k, v] : env.members()) {
    out += ',';
    core::io::append_json_string(out, k);
    out += ':';
    out += core::io::dump(v);
  }
}

// Runs compute() within a budget of budget_ms and continues the answer object in out with its
// answer's members: write(o, r) appends the whole answer object, whose '{' becomes the ','
// continuing out's object and whose '}' is dropped; status is the answer's. When the budget
// runs out, the budget's undecided envelope instead. The result is built in place in the
// optional (a QsicResult holds dozens of exact numbers: no default and move).
template <class Compute, class Write>
void append_within_budget(std::string& out, std::string& status, double budget_ms, Compute compute,
                          Write write) {
  using Result = decltype(compute());
  const std::optional<Result> r = [&]() -> std::optional<Result> {
    try {
      core::BudgetScope budget(budget_ms);
      return compute();
    } catch (const core::BudgetExceeded&) {
      return std::nullopt;
    }
  }();
  if (r) {
    status = certify::to_string(r->status);
    const size_t start = out.size();
    write(out, *r);
    out[start] = ','; // its members continue the answer object
    out.pop_back();
  } else {
    const Json env = budget_undecided_envelope(budget_ms);
    status = env.find("status")->text();
    append_members(out, env);
  }
}

// The readings as dump(readings_json(rs)) writes them, without building the document (the
// deviation names of a reading are distinct, as readings_json needs).
void append_readings(std::string& out, const core::io::Readings& rs) {
  out += '[';
  for (size_t i = 0; i < rs.size(); ++i) {
    const core::io::Reading& r = rs[i];
    out += i ? ",{\"path\":" : "{\"path\":";
    core::io::append_json_string(out, r.path);
    out += ",\"reading\":";
    core::io::append_json_string(out, r.reading);
    out += ",\"deviations\":{";
    for (size_t k = 0; k < r.deviations.size(); ++k) {
      if (k) out += ',';
      core::io::append_json_string(out, r.deviations[k].first);
      out += ':';
      core::io::append_json_string(out, r.deviations[k].second);
    }
    out += "}}";
  }
  out += ']';
}

} // namespace

BatchLineAnswer answer_batch_line(const std::string& line, long line_no, certify::Mode default_mode,
                                  double default_budget_ms, certify::Detail default_detail) {
  const auto t0 = std::chrono::steady_clock::now();
  std::optional<FastLine> fl;
  try {
    fl = read_fast(line, default_mode, default_budget_ms, default_detail);
  } catch (...) { // not a line for the fast reader (or a bad one): the document route
  }
  if (!fl) return document_route(line, line_no, default_mode, default_budget_ms, default_detail);
  try {
    BatchLineAnswer ans;
    std::string& out = ans.text;
    out.reserve(640);
    out += "{\"id\":";
    out += fl->id;
    const BatchQuery& q = fl->q;
    const std::string_view op = q.op;
    if (op == "classify" && q.detail == certify::Detail::Topology) {
      const auto& a = std::get<core::QuadricMatrix>(*fl->a);
      const auto& b = std::get<core::QuadricMatrix>(*fl->b);
      append_within_budget(
          out, ans.status, q.budget_ms, [&] { return batch_classify(q, a, b); },
          [&](std::string& o, const certify::QsicResult& r) {
            ans.fallback = r.exact_fallback;
            certify::append_qsic_topology_envelope(o, r);
          });
    } else if (op == "distance") {
      // Written directly as well (batch_envelope's bytes: tests compare the two).
      append_within_budget(
          out, ans.status, q.budget_ms,
          [&] { return certify::surface_distance(*fl->a, *fl->b, q.digits, q.solid, q.mode); },
          [&](std::string& o, const certify::DistanceResult& r) {
            certify::append_distance_envelope(o, r, q.digits, q.detail);
          });
    } else if (q.op == "intersect") {
      // Written directly too: the branches' points are almost all of the answer's bytes.
      const auto& a = std::get<core::QuadricMatrix>(*fl->a);
      const auto& b = std::get<core::QuadricMatrix>(*fl->b);
      append_within_budget(
          out, ans.status, q.budget_ms, [&] { return batch_intersect(q, a, b); },
          [&](std::string& o, const trace::CurveResult& r) {
            ans.fallback = r.topology.exact_fallback;
            trace::append_curve_envelope(o, r, a, b, q.detail);
          });
    } else {
      const Json env = batch_envelope(q, *fl->a, *fl->b, &ans.fallback);
      if (const Json* s = env.find("status")) ans.status = s->text();
      append_members(out, env);
    }
    if (!fl->readings.empty()) {
      out += ",\"readings\":";
      append_readings(out, fl->readings);
    }
    out += ",\"time_ms\":";
    append_ms(out, std::chrono::steady_clock::now() - t0);
    out += '}';
    return ans;
  } catch (...) { // e.g. an internal error: the document route answers it as it always has
    return document_route(line, line_no, default_mode, default_budget_ms, default_detail);
  }
}

void set_answer_from_document(BatchLineAnswer& a, const Json& r) {
  if (const Json* s = r.find("status")) a.status = s->text();
  if (const Json* e = r.find("error"))
    if (const Json* k = e->is_object() ? e->find("kind") : nullptr)
      if (k->is_string()) a.error_kind = k->text();
  a.text = core::io::dump(r);
}

} // namespace surfcert::app
