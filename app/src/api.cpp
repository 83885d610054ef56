// The embedding API (surfcert/surfcert.hpp). Every surface constructor goes through the JSON
// reader (core/io/surface_reader.hpp) so that a matrix or shape given here is read exactly
// as the same numbers on a batch line would be (doubles written with 17 significant digits
// round-trip to themselves), readings and errors included. The operations follow
// app::process_batch_line step for step; to_json() builds the same envelope it does.
#include "surfcert/surfcert.hpp"

#include "surfcert/app/batch_query.hpp"
#include "surfcert/app/generate.hpp"
#include "surfcert/app/verify.hpp"
#include "surfcert/certify/report.hpp"
#include "surfcert/core/budget.hpp"
#include "surfcert/core/io/expression.hpp"

#include <flint/flint.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

#ifndef SURFCERT_VERSION
#define SURFCERT_VERSION "unknown"
#endif

namespace surfcert {

namespace {

using core::io::json_path_child;

Json number(double v, const std::string& path, const char* what) {
  if (!std::isfinite(v)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    throw InputError(Location{"<" + path + ">", 0, 0, path}, std::string("a finite ") + what, buf);
  }
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return Json::number_text(buf);
}

Json triple(const std::array<double, 3>& v, const std::string& path, const char* what) {
  Json a = Json::array();
  for (double x : v)
    a.push_back(number(x, path, what));
  return a;
}

// How many radii a shape type takes in the JSON form ("radii"); 0: a sphere ("radius").
std::size_t shape_radii(const std::string& type) {
  const auto t = core::io::shape_type_of_name(type);
  if (!t || *t == core::ShapeType::Sphere)
    return 0; // a sphere, or an unknown type the reader reports
  return core::io::shape_radii_count(*t);
}

Location option_at(const std::string& key) {
  return Location{"<options>", 0, 0, "$." + key};
}

// The checks a batch line makes on its options (app/src/scene.cpp), for the op.
void check_options(const std::string& op, const Options& o) {
  if (!certify::detail_accepted(op, o.detail))
    throw InputError(option_at("detail"),
                     std::string("a detail for ") + op + ": " + certify::detail_spellings(op),
                     std::string("\"") + certify::to_string(o.detail) + "\"");
  if (o.digits < 1 || o.digits > 1000)
    throw InputError(option_at("digits"), "digits: an integer from 1 to 1000",
                     std::to_string(o.digits));
  if (!(o.tolerance >= 1e-12 && o.tolerance <= 1)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", o.tolerance);
    throw InputError(option_at("tolerance"), "a tolerance between 1e-12 and 1", buf);
  }
  if (!(o.budget_ms >= 0 && o.budget_ms <= 1e9)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", o.budget_ms);
    throw InputError(option_at("budget_ms"), "a budget in milliseconds, 0 (none) to 1e9", buf);
  }
}

// classify and intersect need two quadrics (the batch line's error, at the surface's path).
const core::QuadricMatrix& need_quadric(const Surface& s, const std::string& op,
                                        const std::string& key) {
  if (const core::QuadricMatrix* q = s.quadric()) return *q;
  throw InputError(Location{"<" + key + ">", 0, 0, "$." + key},
                   "a quadric (\"" + op + "\" needs two quadrics)", core::surface_found(s.value()));
}

template <class A> void start(A& ans, const Surface& a, const Surface& b, const Options& o) {
  ans.detail = o.detail;
  ans.budget_ms = o.budget_ms;
  ans.readings = a.readings();
  ans.readings.insert(ans.readings.end(), b.readings().begin(), b.readings().end());
}

Json finish(const Answer& ans, Json env) {
  if (ans.budget_exhausted) env = app::budget_undecided_envelope(ans.budget_ms);
  if (!ans.readings.empty()) env.set("readings", core::io::readings_json(ans.readings));
  return env;
}

} // namespace

const char* version() {
  return SURFCERT_VERSION;
}

Surface Surface::parse(const std::string& text, const std::string& source,
                       const std::string& path) {
  if (!text.empty() && text[0] == '{')
    return from_json(core::io::parse_json(text, source), source, path);
  // An equation, as the command line reads one (degree 3 and more: an implicit surface).
  const Location where{source, 1, 1, path == "$" ? "" : path};
  core::Poly3 p = core::io::parse_polynomial(text, where);
  if (p.total_degree() >= 3) {
    if (p.total_degree() > core::kMaxImplicitDegree)
      throw InputError(
          where, "a surface of total degree at most " + std::to_string(core::kMaxImplicitDegree),
          "total degree " + std::to_string(p.total_degree()));
    return Surface(core::ImplicitSurface{std::move(p)});
  }
  return Surface(core::io::quadric_from_equation(text, where));
}

Surface Surface::from_json(const Json& value, const std::string& source, const std::string& path) {
  core::io::Readings r;
  core::Surface v = core::io::read_surface(value, source, path, &r);
  return Surface(std::move(v), std::move(r));
}

Surface Surface::from_matrix(const std::array<std::array<double, 4>, 4>& m,
                             const std::string& path) {
  Json rows = Json::array();
  for (const auto& row : m) {
    Json r = Json::array();
    for (double v : row)
      r.push_back(number(v, json_path_child(path, "matrix"), "matrix entry"));
    rows.push_back(std::move(r));
  }
  Json o = Json::object();
  o.set("matrix", std::move(rows));
  return from_json(o, "<matrix>", path);
}

Surface Surface::from_matrix(const std::array<std::array<Rational, 4>, 4>& m,
                             const std::string& path) {
  Json rows = Json::array();
  for (const auto& row : m) {
    Json r = Json::array();
    for (const Rational& v : row)
      r.push_back(Json::string(v.to_string()));
    rows.push_back(std::move(r));
  }
  Json o = Json::object();
  o.set("matrix", std::move(rows));
  return from_json(o, "<matrix>", path);
}

Surface Surface::from_shape(const std::string& type, const std::array<double, 3>& center,
                            const std::array<double, 3>& radii,
                            const std::optional<std::array<double, 4>>& quaternion,
                            const std::string& path) {
  Json o = Json::object();
  o.set("type", Json::string(type));
  o.set("center", triple(center, json_path_child(path, "center"), "centre"));
  const std::size_t n = shape_radii(type);
  if (n == 0) {
    o.set("radius", number(radii[0], json_path_child(path, "radius"), "radius"));
  } else {
    Json r = Json::array();
    for (std::size_t i = 0; i < n; ++i)
      r.push_back(number(radii[i], json_path_child(path, "radii"), "radius"));
    o.set("radii", std::move(r));
  }
  if (quaternion) {
    Json q = Json::array();
    for (double v : *quaternion)
      q.push_back(number(v, json_path_child(path, "rotation"), "quaternion entry"));
    Json rot = Json::object();
    rot.set("quaternion", std::move(q));
    o.set("rotation", std::move(rot));
  }
  return from_json(o, "<shape>", path);
}

Json Classification::to_json() const {
  return finish(*this, certify::qsic_envelope_json(qsic, a, b, detail));
}

Json Intersection::to_json() const {
  return finish(*this, trace::curve_envelope_json(curve, a, b, detail));
}

Json Distance::to_json() const {
  return finish(*this, certify::distance_envelope_json(result, digits, detail));
}

Status Verification::status() const {
  if (budget_exhausted) return Status::Undecided;
  const Json* s = verdicts.find("status");
  return s && s->text() == "certified" ? Status::Certified : Status::Undecided;
}

Json Verification::to_json() const {
  return finish(*this, verdicts);
}

Classification classify(const Surface& a, const Surface& b, const Options& opt) {
  check_options("classify", opt);
  Classification c(need_quadric(a, "classify", "a"), need_quadric(b, "classify", "b"));
  start(c, a, b, opt);
  core::BudgetScope budget(opt.budget_ms);
  try {
    c.qsic = certify::classify_qsic(c.a, c.b, opt.mode);
    certify::complete_report_data(c.qsic, c.a, c.b, opt.detail);
  } catch (const core::BudgetExceeded&) {
    c.budget_exhausted = true;
  }
  return c;
}

Intersection intersect(const Surface& a, const Surface& b, const Options& opt) {
  check_options("intersect", opt);
  Intersection r(need_quadric(a, "intersect", "a"), need_quadric(b, "intersect", "b"));
  start(r, a, b, opt);
  core::BudgetScope budget(opt.budget_ms);
  try {
    trace::TraceOptions t;
    t.tolerance = opt.tolerance;
    r.curve = trace::intersect_curve(r.a, r.b, opt.mode, t, opt.detail);
  } catch (const core::BudgetExceeded&) {
    r.budget_exhausted = true;
  }
  return r;
}

Distance distance(const Surface& a, const Surface& b, const Options& opt) {
  check_options("distance", opt);
  Distance d;
  start(d, a, b, opt);
  d.digits = opt.digits;
  core::BudgetScope budget(opt.budget_ms);
  try {
    d.result = certify::surface_distance(a.value(), b.value(), opt.digits, opt.solid, opt.mode);
  } catch (const core::BudgetExceeded&) {
    d.budget_exhausted = true;
  }
  return d;
}

Verification verify(const Surface& a, const Surface& b, const Json& claims, const Options& opt) {
  Options o = opt;
  o.detail = Detail::Full; // verify has no detail levels; its answer is whole
  check_options("distance", o);
  Verification v;
  start(v, a, b, opt);
  Json line = Json::object();
  line.set("claims", claims);
  core::BudgetScope budget(opt.budget_ms);
  try {
    v.verdicts = app::verify_claims(a.value(), b.value(), line, "<claims>", opt.mode);
  } catch (const core::BudgetExceeded&) {
    v.budget_exhausted = true;
  }
  return v;
}

std::vector<GeneratedCase> generate(const GenerateOptions& opt) {
  app::GenerateRequest r;
  r.what = opt.cases;
  r.family = opt.family;
  r.gaps = opt.gaps;
  r.count = opt.count;
  r.seed = opt.seed;
  r.threads = opt.threads;
  const auto enc = app::parse_encoding(opt.encoding);
  if (!enc)
    throw InputError(option_at("encoding"), "an encoding: \"exact\", \"double\" or \"shape\"",
                     "\"" + opt.encoding + "\"");
  r.encoding = *enc;
  std::vector<Json> lines;
  try {
    lines = app::generate(r);
  } catch (const app::GenerateRefusal& e) {
    // The option at fault by its JSON path ($.case, $.gaps[1], ...), as for the other options.
    throw InputError(Location{"<options>", 0, 0, e.option_path()}, e.expected(), e.found());
  }
  std::vector<GeneratedCase> out;
  for (Json& line : lines) {
    GeneratedCase c;
    c.id = line.find("id")->text();
    c.op = line.find("op")->text();
    c.a = *line.find("a");
    c.b = *line.find("b");
    c.label = *line.find("label");
    c.status = c.label.find("status")->text();
    if (const Json* m = c.label.find("morphology")) c.morphology = m->text();
    if (const Json* t = c.label.find("tu_case"); t && t->is_number())
      c.tu_case = std::stol(t->text());
    c.line = std::move(line);
    out.push_back(std::move(c));
  }
  return out;
}

void for_each_parallel(std::size_t n, int threads, const std::function<void(std::size_t)>& job) {
  const std::size_t t = std::min<std::size_t>(n, static_cast<std::size_t>(std::max(threads, 1)));
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i; (i = next++) < n;)
      job(i);
    flint_cleanup(); // this thread's FLINT caches
  };
  if (t <= 1) {
    for (std::size_t i = 0; i < n; ++i)
      job(i);
    return;
  }
  std::vector<std::thread> pool;
  for (std::size_t k = 0; k < t; ++k)
    pool.emplace_back(work);
  for (auto& th : pool)
    th.join();
}

} // namespace surfcert
