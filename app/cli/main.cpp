// The `surfcert` command line (CLI11): classify, intersect, distance, verify, run, batch,
// generate. Exit
// codes:
// 0 success, 2 bad input or bad command line (message with location or option on stderr,
// nothing written), 3 finished with undecided results, 1 internal error (for batch: some line
// was answered with an "internal" error line, e.g. FLINT/Arb aborted on it).
#include "../src/write_all.hpp"

#include "surfcert/app/batch_line.hpp"
#include "surfcert/app/batch_mpi.hpp"
#include "surfcert/app/batch_stream.hpp"
#include "surfcert/app/generate.hpp"
#include "surfcert/app/scene.hpp"
#include "surfcert/app/verify.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/report.hpp"
#include "surfcert/core/io/expression.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/trace/export.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <CLI/CLI.hpp>
#include <flint/flint.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#ifndef SURFCERT_VERSION
#error "SURFCERT_VERSION comes from project(surfcert VERSION ...) (app/CMakeLists.txt)"
#endif

using namespace surfcert;
using core::InputError;
using core::Location;
using core::io::Json;

namespace {

const std::string kUsage =
    "surfcert " SURFCERT_VERSION ": certified topology of the intersection of two quadrics\n"
    "\n"
    "usage:\n"
    "  surfcert classify 'EQ_A' 'EQ_B' [--mode exact|filtered|float] [--json]\n"
    "                   [--detail topology|certificate|full]\n"
    "  surfcert intersect 'EQ_A' 'EQ_B' [--mode M] [--tol T] [--json] [--export F.obj|F.ply] "
    "[--svg F.svg]\n"
    "                   [--box X0,Y0,Z0,X1,Y1,Z1]\n"
    "  surfcert distance 'SURF_A' 'SURF_B' [--digits N] [--solid] [--mode M] [--json]\n"
    "                   [--detail value|full]   "
    "(equations, or JSON "
    "surfaces incl. {\"type\":\"torus\",...})\n"
    "  surfcert verify 'SURF_A' 'SURF_B' --claim JSON [--claim JSON ...] [--mode M] [--json]\n"
    "                                              (verdicts on another program's claims)\n"
    "  surfcert run SCENE.json [-o REPORT.json] [--json] [--mode M]\n"
    "  surfcert batch [--mode M] [--threads N] [--budget-ms MS] [--unordered] [--detail D]\n"
    "                                              (JSON lines on stdin -> JSON lines on stdout)\n"
    "  mpirun [--enable-recovery] -n P surfcert batch --mpi [--checkpoint F]\n"
    "                   [--retry-undecided MS] [--rank-timeout S] [batch options]\n"
    "  surfcert generate [--case N|all|degenerate_pencil|coincident|ellipsoid|natural|distance]\n"
    "                   [--count K] [--seed S] [--encoding exact|double|shape]\n"
    "                   [--family F --gaps 10,20,40]\n"
    "                                              (labelled test cases as batch lines)\n"
    "  surfcert --help | --version | COMMAND --help\n"
    "\n"
    "A batch line: {\"id\": ANY, \"op\": \"classify\"|\"intersect\"|\"distance\"|\"verify\",\n"
    "  \"a\": SURFACE, \"b\": SURFACE, optional \"mode\", \"detail\", \"budget_ms\", \"digits\",\n"
    "  \"solid\", \"tolerance\", \"claims\", \"label\" (echoed)}; SURFACE: an equation string, "
    "{\"matrix\": 4x4},\n"
    "  {\"equation\": ...} or a shape {\"type\": \"ellipsoid\", \"center\": [x,y,z], \"radii\": "
    "[a,b,c],\n"
    "  \"rotation\": {\"quaternion\": [w,x,y,z]}} (doubles read exactly; see docs/input.md).\n"
    "\n"
    "Options take their value as `--opt value` or `--opt=value`; --mode is exact, filtered or\n"
    "float, --digits 1..1000, --tol 1e-12..1, --threads 1..256. batch writes one answer line per\n"
    "input line, in input order, each as soon as it and all earlier lines are answered\n"
    "(written at once when the input waits, else within 20 ms; SIGTERM/SIGINT/SIGHUP write\n"
    "every completed line before the batch ends).\n"
    "Exit codes: 0 success; 2 bad input or command line (nothing written); 3 some result\n"
    "undecided; 1 internal error (batch: some line got an \"internal\" error line, e.g. FLINT\n"
    "aborted on it; the other lines are still answered).\n"
    "\n"
    "Equations are polynomials in x, y, z (e.g. 'x^2 + y^2/4 + z^2 = 1'); numbers are read\n"
    "exactly (0.1 = 1/10). Mode filtered (default) answers from interval arithmetic when it is\n"
    "provably right and falls back to exact arithmetic otherwise; float is uncertified.\n"
    "See docs/json-contract.md for the JSON contract (README.md for an overview).\n";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

certify::Mode mode_arg(const std::string& v) {
  auto m = certify::parse_mode(v);
  if (!m)
    throw InputError(Location{"<command line>", 0, 0, ""}, "--mode exact, filtered or float",
                     "\"" + v + "\"");
  return *m;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(Location{path, 0, 0, ""}, "a readable file", "cannot open \"" + path + "\"");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Writes to a temporary file next to the target and renames it, so a reader never sees a
// half-written report and a failure leaves no file behind.
void write_atomically(const std::string& path, const std::string& content) {
  std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw InputError(Location{path, 0, 0, ""}, "a writable output path",
                       "cannot create \"" + tmp + "\"");
    out << content;
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw InputError(Location{path, 0, 0, ""}, "a writable output path", "write failure");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(Location{path, 0, 0, ""}, "a writable output path", "rename failure");
  }
}

// The options CLI11 parsed (the equations are CLI11's leftovers: an equation may start with
// '-', e.g. '-x^2 + y = 0', which CLI11 would otherwise take for a short option).
struct Opts {
  std::string mode = "filtered";
  bool mode_given = false;
  bool json = false, solid = false;
  std::string tol, export_path, svg_path, out_path, scene_path;
  std::string box;                 ///< intersect --box "x0,y0,z0,x1,y1,z1"
  std::vector<std::string> claims; ///< verify: each a JSON claim or array of claims
  long digits = 15;
  int threads = 1;
  double budget_ms = 0;       ///< batch: default per-line time budget (0 = none)
  bool unordered = false;     ///< batch: write answers as they complete
  bool mpi = false;           ///< batch --mpi (app/batch_mpi.hpp)
  bool mpi_child = false;     ///< batch --mpi-child: a compute child of batch --mpi (hidden)
  std::string checkpoint;     ///< batch --mpi --checkpoint FILE
  double retry_undecided = 0; ///< batch --mpi --retry-undecided MS (0: none)
  double rank_timeout = 30;   ///< batch --mpi --rank-timeout S (with Open MPI's recovery)
  bool rank_timeout_set = false;
  std::string detail = "full"; ///< --detail (certify/detail.hpp; checked by CLI11 per command)
  app::GenerateRequest gen;    ///< generate
  std::string encoding = "exact", gaps = "10,20,40";
};

certify::Detail detail_arg(const std::string& v) {
  auto d = certify::parse_detail(v);
  if (!d)
    throw InputError(Location{"<command line>", 0, 0, ""},
                     "--detail value, topology, certificate or full", "\"" + v + "\"");
  return *d;
}

// The equations of classify / intersect / distance: the arguments CLI11 left over, of which
// any `--name` is an unknown option.
std::vector<std::string> equations(const CLI::App& sub) {
  std::vector<std::string> eq;
  for (const auto& a : sub.remaining()) {
    if (a.size() > 1 && a[0] == '-' && a[1] == '-')
      throw UsageError("unknown option " + a + " for " + sub.get_name());
    eq.push_back(a);
  }
  return eq;
}

// A quadric argument: a JSON surface when it starts with '{' (shapes, matrices), else an
// equation; readings receives how float data in it was read exactly.
core::QuadricMatrix quadric_arg(const std::string& text, const std::string& src,
                                core::io::Readings& readings) {
  if (!text.empty() && text[0] == '{')
    return core::io::read_quadric(core::io::parse_json(text, src), src, "$", &readings);
  return core::io::quadric_from_equation(text, Location{src, 1, 1, ""});
}

// The readings of float input: a "readings" field of the JSON answer, or text lines.
void report_readings(const core::io::Readings& readings, core::io::Json* envelope) {
  if (readings.empty()) return;
  if (envelope) {
    envelope->set("readings", core::io::readings_json(readings));
    return;
  }
  for (const auto& r : readings) {
    std::cout << "reading " << r.path << ": " << r.reading;
    for (const auto& [name, value] : r.deviations)
      std::cout << "; " << name << " = " << value;
    std::cout << "\n";
  }
}

int cmd_classify(const std::vector<std::string>& eq, const Opts& o) {
  certify::Mode mode = mode_arg(o.mode);
  bool json = o.json;
  if (eq.size() != 2) throw UsageError("classify needs exactly two surfaces");
  core::io::Readings readings;
  auto a = quadric_arg(eq[0], "<argument 1>", readings);
  auto b = quadric_arg(eq[1], "<argument 2>", readings);
  const certify::Detail detail = detail_arg(o.detail);
  certify::QsicResult r = certify::classify_qsic(a, b, mode);
  certify::complete_report_data(r, a, b, json ? detail : certify::Detail::Full);
  if (json) {
    core::io::Json env = certify::qsic_envelope_json(r, a, b, detail);
    report_readings(readings, &env);
    std::cout << core::io::dump(env, 2) << "\n";
  } else {
    report_readings(readings, nullptr);
    std::cout << certify::qsic_result_text(r, a, b);
  }
  return r.status == certify::Status::Undecided ? 3 : 0;
}

// --tol: a number (read exactly, e.g. 1/1000 or 2e-4) from 1e-12 to 1; 0 when it is none.
// CLI::Range lets NaN through (both its comparisons are false): "--budget-ms nan" ran as no
// budget. Checked before the range.
CLI::Validator not_nan() {
  return CLI::Validator(
      [](std::string& v) {
        return std::isnan(std::strtod(v.c_str(), nullptr))
                   ? "expected a number, found \"" + v + "\""
                   : std::string();
      },
      "", "NOT_NAN");
}

double tol_value(const std::string& v) {
  auto t = core::Rational::from_string(v);
  double d = t ? t->to_double_approx() : 0;
  return d >= 1e-12 && d <= 1 ? d : 0;
}

// --box X0,Y0,Z0,X1,Y1,Z1: six exact numbers, each any constant the equation reader takes
// (docs/input.md: "1/3", "0.1", "2e-3", "1-1/2^64", "(1+1/3)/2"), rounded once to a double;
// min < max in every coordinate. An error is located at the column of the --box value where
// it is (source "--box") and names the corner.
trace::Box box_arg(const std::string& text) {
  static const char* const kCorner[6] = {"X0", "Y0", "Z0", "X1", "Y1", "Z1"};
  const std::string src = "--box";
  std::vector<std::pair<std::string, int>> items; // a corner's text, its 1-based column
  for (std::size_t start = 0;;) {
    const std::size_t comma = text.find(',', start);
    items.emplace_back(text.substr(start, comma == std::string::npos ? comma : comma - start),
                       static_cast<int>(start) + 1);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (items.size() != 6)
    throw InputError(Location{src, 1, 1, ""},
                     "--box X0,Y0,Z0,X1,Y1,Z1: six corners separated by commas",
                     std::to_string(items.size()) + " corners in \"" + text + "\"");
  std::array<double, 6> v{};
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& [item, column] = items[i];
    const std::string corner = std::string("--box corner ") + kCorner[i] + ": ";
    core::Poly3 p;
    try {
      p = core::io::parse_polynomial(item, Location{src, 1, column, ""});
    } catch (const InputError& e) {
      throw InputError(e.where(), corner + e.expected(), e.found());
    }
    if (p.total_degree() > 0)
      throw InputError(Location{src, 1, column, ""}, corner + "a number (no x, y or z)",
                       "\"" + item + "\"");
    const core::Rational r = p.is_zero() ? core::Rational(0) : p.coeff(0, 0, 0);
    v[i] = r.to_double_approx();
    if (!std::isfinite(v[i]))
      throw InputError(Location{src, 1, column, ""}, corner + "a number in the double range",
                       "\"" + item + "\"");
    // The box is one of doubles (its exits are certified for that box, which the answer
    // reports): say so when a corner moved, e.g. 1-1/2^64 onto 1, a node's plane.
    if (!(core::Rational::exact_from_double(v[i]) == r))
      std::cerr << "note: --box " << item << " is used as the double " << std::setprecision(17)
                << v[i] << "\n";
  }
  trace::Box bx;
  for (std::size_t k = 0; k < 3; ++k) {
    bx.min[k] = v[k];
    bx.max[k] = v[k + 3];
    if (!(v[k] < v[k + 3])) {
      std::ostringstream found;
      found << std::setprecision(17) << kCorner[k + 3] << " = " << v[k + 3] << ", " << kCorner[k]
            << " = " << v[k] << " (as doubles)";
      throw InputError(Location{src, 1, items[k + 3].second, ""},
                       std::string("--box corner ") + kCorner[k + 3] + ": greater than " +
                           kCorner[k] + " (min < max in every coordinate)",
                       found.str());
    }
  }
  return bx;
}

int cmd_intersect(const std::vector<std::string>& eq, const Opts& o) {
  certify::Mode mode = mode_arg(o.mode);
  bool json = o.json;
  const std::string& export_path = o.export_path;
  const std::string& svg_path = o.svg_path;
  trace::TraceOptions opt;
  if (!o.tol.empty()) opt.tolerance = tol_value(o.tol);
  if (!o.box.empty()) opt.box = box_arg(o.box);
  if (eq.size() != 2) throw UsageError("intersect needs exactly two surfaces");
  auto ends_with = [](const std::string& s, const std::string& e) {
    return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
  };
  if (!export_path.empty() && !ends_with(export_path, ".obj") && !ends_with(export_path, ".ply"))
    throw InputError(Location{"<command line>", 0, 0, ""}, "--export FILE.obj or FILE.ply",
                     "\"" + export_path + "\"");
  core::io::Readings readings;
  auto a = quadric_arg(eq[0], "<argument 1>", readings);
  auto b = quadric_arg(eq[1], "<argument 2>", readings);
  if (!json) report_readings(readings, nullptr);
  const certify::Detail detail = json ? detail_arg(o.detail) : certify::Detail::Full;
  trace::CurveResult c = trace::intersect_curve(a, b, mode, opt, detail);
  // Everything formed before anything is written: an exception on the way (an internal
  // error) leaves no file behind and nothing half-printed. No non-finite coordinate is drawn.
  std::vector<trace::Point3> special;
  for (const auto& p : c.topology.special_points)
    if (!p.at_infinity && std::isfinite(p.approx[0]) && std::isfinite(p.approx[1]) &&
        std::isfinite(p.approx[2]))
      special.push_back(p.approx);
  std::string export_text, svg_text;
  if (!export_path.empty())
    export_text = ends_with(export_path, ".obj") ? trace::to_obj(c.branches, c.isolated_points)
                                                 : trace::to_ply(c.branches, c.isolated_points);
  if (!svg_path.empty()) {
    trace::Picture pic;
    pic.branches = c.branches;
    pic.special_points = special;
    pic.caption = trace::curve_caption(c);
    pic.box = c.box;
    svg_text = trace::to_svg(a, b, pic);
  }
  std::ostringstream os;
  if (json) {
    core::io::Json env = trace::curve_envelope_json(c, a, b, detail);
    report_readings(readings, &env);
    os << core::io::dump(env, 2) << "\n";
  } else {
    os << certify::qsic_result_text(c.topology, a, b);
    os << "curve: " << certify::to_string(c.status) << ", " << c.branches.size() << " branch(es):";
    for (const auto& br : c.branches)
      os << " " << br.kind << "(" << br.points.size() << " points)";
    os << ", " << c.isolated_points.size() << " isolated point(s), max residual " << c.max_residual
       << "\n";
    const auto& af = c.affine;
    if (af.computed) {
      auto n = [](const std::optional<int>& v) { return v ? std::to_string(*v) : "undecided"; };
      os << "affine (" << (af.certified() ? "certified" : "undecided") << "): " << n(af.loops)
         << " loop(s), " << n(af.unbounded_branches) << " unbounded branch(es), "
         << n(af.isolated_points) << " isolated point(s), " << n(af.lines) << " line(s), "
         << n(af.conics) << " conic(s), " << af.points_at_infinity.size()
         << " point(s) at infinity, " << af.at_infinity_only.size()
         << " component(s) at infinity only\n";
    }
    if (c.box)
      os << "box" << (c.box_automatic ? " (automatic)" : "") << ": [" << c.box->min[0] << ", "
         << c.box->max[0] << "] x [" << c.box->min[1] << ", " << c.box->max[1] << "] x ["
         << c.box->min[2] << ", " << c.box->max[2] << "]\n";
    if (!c.note.empty()) os << "note: " << c.note << "\n";
  }
  if (!export_path.empty()) write_atomically(export_path, export_text);
  if (!svg_path.empty()) write_atomically(svg_path, svg_text);
  std::cout << os.str();
  return c.status == certify::Status::Undecided ? 3 : 0;
}

// A surface argument of distance / verify: a JSON surface when it starts with '{' (shapes,
// matrices, a torus, ...), else an equation (of degree 3..kMaxImplicitDegree: an implicit
// surface); readings receives how float data in it was read exactly.
core::Surface surface_arg(const std::string& text, const std::string& src,
                          core::io::Readings& readings) {
  if (!text.empty() && text[0] == '{')
    return core::io::read_surface(core::io::parse_json(text, src), src, "$", &readings);
  core::Poly3 p = core::io::parse_polynomial(text, Location{src, 1, 1, ""});
  if (p.total_degree() >= 3) {
    if (p.total_degree() > core::kMaxImplicitDegree)
      throw InputError(Location{src, 1, 1, ""},
                       "a surface of total degree at most " +
                           std::to_string(core::kMaxImplicitDegree),
                       "total degree " + std::to_string(p.total_degree()));
    return core::ImplicitSurface{std::move(p)};
  }
  return core::io::quadric_from_equation(text, Location{src, 1, 1, ""});
}

int cmd_distance(const std::vector<std::string>& eq, const Opts& o) {
  long digits = o.digits;
  bool json = o.json, solid = o.solid;
  certify::Mode mode = mode_arg(o.mode);
  if (eq.size() != 2) throw UsageError("distance needs exactly two surfaces");
  core::io::Readings readings;
  auto surface = [&readings](const std::string& text, const std::string& src) {
    return surface_arg(text, src, readings);
  };
  certify::DistanceResult d = certify::surface_distance(
      surface(eq[0], "<argument 1>"), surface(eq[1], "<argument 2>"), digits, solid, mode);
  if (json) {
    core::io::Json env = certify::distance_envelope_json(d, digits, detail_arg(o.detail));
    report_readings(readings, &env);
    std::cout << core::io::dump(env, 2) << "\n";
  } else {
    report_readings(readings, nullptr);
    std::cout << "distance: " << certify::to_string(d.status);
    if (d.estimate) {
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.17g", d.estimate->value);
      std::cout << " ~ " << buf << " (an estimate, not an enclosure), minimizers " << d.minimizers;
    } else if (d.distance)
      std::cout << " in [" << d.lower() << ", " << d.upper() << "], minimizers " << d.minimizers;
    std::cout << "\n";
    for (const auto& p : d.pairs)
      std::cout << "  pair (" << p[0][0] << ", " << p[0][1] << ", " << p[0][2] << ") - (" << p[1][0]
                << ", " << p[1][1] << ", " << p[1][2] << ")\n";
    if (!d.note.empty()) std::cout << "note: " << d.note << "\n";
    if (d.method != certify::Method::None) std::cout << "method: " << to_string(d.method) << "\n";
  }
  return d.status == certify::Status::Undecided ? 3 : 0;
}

// verify: the claims of every --claim (an object, or an array of objects) in order, as the
// "claims" of a verify line (app/verify.hpp); the answer is the batch line's status and result.
int cmd_verify(const std::vector<std::string>& eq, const Opts& o) {
  certify::Mode mode = mode_arg(o.mode);
  if (eq.size() != 2) throw UsageError("verify needs exactly two surfaces");
  if (o.claims.empty()) throw UsageError("verify needs at least one --claim JSON");
  core::io::Readings readings;
  core::Surface a = surface_arg(eq[0], "<argument 1>", readings);
  core::Surface b = surface_arg(eq[1], "<argument 2>", readings);
  Json claims = Json::array();
  for (const auto& text : o.claims) {
    Json c = core::io::parse_json(text, "<--claim>");
    if (c.is_array())
      for (const auto& item : c.items())
        claims.push_back(item);
    else
      claims.push_back(c);
  }
  Json line = Json::object();
  line.set("claims", claims);
  Json env = app::verify_claims(a, b, line, "<--claim>", mode);
  if (o.json) {
    report_readings(readings, &env);
    std::cout << core::io::dump(env, 2) << "\n";
  } else {
    report_readings(readings, nullptr);
    const Json& verdicts = *env.find("result")->find("verdicts");
    for (size_t i = 0; i < verdicts.size(); ++i) {
      const Json& v = verdicts.items()[i];
      std::cout << "claim " << i + 1 << " (" << v.find("kind")->text()
                << "): " << v.find("verdict")->text() << "\n";
      for (const char* key : {"counterexample", "established"})
        if (const Json* e = v.find(key))
          std::cout << "  " << key << ": " << core::io::dump(*e) << "\n";
      if (const Json* n = v.find("note")) std::cout << "  note: " << n->text() << "\n";
    }
  }
  return env.find("status")->text() == "undecided" ? 3 : 0;
}

int cmd_run(const Opts& o) {
  const std::string& scene_path = o.scene_path;
  const std::string& out_path = o.out_path;
  bool json = o.json;
  std::optional<certify::Mode> mode;
  if (o.mode_given) mode = mode_arg(o.mode);
  Json doc = core::io::parse_json(read_file(scene_path), scene_path);
  app::Scene scene = app::read_scene(doc, scene_path, mode.value_or(certify::Mode::Filtered));
  if (mode)
    for (auto& q : scene.queries)
      q.mode = *mode; // the command line wins over the scene
  Json report = Json::object();
  report.set("surfcert_version", Json::string(SURFCERT_VERSION));
  report.set("scene", Json::string(scene_path));
  Json results = Json::array();
  std::string text;
  bool undecided = false;
  for (const auto& q : scene.queries) {
    std::string summary;
    Json r = app::run_query(scene, q, &summary);
    if (const Json* s = r.find("status")) undecided = undecided || s->text() == "undecided";
    text += "== query " +
            (q.id.is_null() ? std::string("?")
                            : (q.id.is_string() ? q.id.text() : core::io::dump(q.id))) +
            ": " + q.op + " " + q.a + " / " + q.b + "\n" + summary + "\n";
    results.push_back(r);
  }
  report.set("results", results);
  std::string dumped = core::io::dump(report, 2) + "\n";
  if (!out_path.empty()) write_atomically(out_path, dumped);
  std::cout << (json ? dumped : text);
  return undecided ? 3 : 0;
}

// The command line of a compute child of `batch --mpi`: this executable with the batch's
// options (a line's own fields override them there as in the single-process batch).
std::vector<std::string> mpi_child_command(const Opts& o) {
  char exe[4096];
  const ssize_t n = ::readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n <= 0) throw std::runtime_error("batch --mpi: cannot find its own executable");
  exe[n] = '\0';
  char budget[64];
  std::snprintf(budget, sizeof budget, "%.17g", o.budget_ms);
  return {exe,      "batch", "--mpi-child", "--threads", std::to_string(o.threads),
          "--mode", o.mode,  "--detail",    o.detail,    "--budget-ms",
          budget};
}

// main's arguments, for exec_mpi_executable.
char** g_argv = nullptr;

// batch --mpi in an executable that does not run it (app::mpi_executable(), batch_mpi.hpp):
// replaces this process's image by that executable, in this one's directory, with the same
// arguments (execv keeps the pid, the open descriptors and the environment mpirun set up, so
// MPI_Init runs there as it would have here). Returns only if it could not: exit code 2, with
// the file named (an installation without surfcert-mpi cannot run --mpi).
int exec_mpi_executable(const char* name) {
  char self[4096];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) throw std::runtime_error("batch --mpi: cannot find its own executable");
  self[n] = '\0';
  std::string path(self);
  const size_t slash = path.rfind('/');
  path = (slash == std::string::npos ? std::string() : path.substr(0, slash + 1)) + name;
  std::vector<char*> args;
  args.push_back(const_cast<char*>(path.c_str()));
  for (char** a = g_argv + 1; *a; ++a)
    args.push_back(*a);
  args.push_back(nullptr);
  std::cout.flush();
  std::fflush(stdout);
  ::execv(path.c_str(), args.data());
  const int err = errno;
  std::cerr << "surfcert: error: batch --mpi runs in " << path << " (built and installed next to "
            << "this surfcert when MPI is found), which cannot be executed: " << std::strerror(err)
            << "\n";
  return 2;
}

int batch_exit_code(const app::BatchStats& st) {
  // Every line is answered whatever happens; the exit code summarises the worst outcome so
  // that a caller's script notices: internal failures, then bad input lines, then undecided.
  if (st.internal > 0) return 1;
  if (st.errors > 0) return 2;
  return st.undecided > 0 ? 3 : 0;
}

// A summary line reaches stderr in one write(2): under mpirun, Open MPI's own messages share
// rank 0's stderr, and a line written piecewise (std::cerr writes every << at once) came out
// cut in two by one of them (CI, session 27), breaking whoever parses the line.
void stderr_line(const std::ostringstream& line) {
  const std::string s = line.str();
  app::write_all(STDERR_FILENO, s.data(), s.size());
}

void print_batch_summary(const app::BatchStats& st) {
  std::ostringstream s;
  s << "surfcert batch: " << st.lines << " lines, " << st.errors << " errors (" << st.internal
    << " internal), " << st.undecided << " undecided, " << st.fallbacks << " exact fallbacks\n";
  stderr_line(s);
}

// batch --mpi (and its hidden compute child, --mpi-child): app/batch_mpi.hpp.
int cmd_batch_mpi(const Opts& o, int out_fd) {
  app::MpiBatchOptions mo;
  mo.mode = mode_arg(o.mode);
  mo.detail = detail_arg(o.detail);
  mo.budget_ms = o.budget_ms;
  mo.threads = o.threads;
  mo.ordered = !o.unordered;
  mo.checkpoint = o.checkpoint;
  mo.retry_budget_ms = o.retry_undecided;
  mo.rank_timeout_s = o.rank_timeout;
  if (o.mpi_child) {
    app::run_batch_child(0, out_fd, mo);
    return 0;
  }
  mo.child_command = mpi_child_command(o);
  bool root = false;
  app::MpiBatchReport rep;
  const app::BatchStats st = app::run_batch_mpi(out_fd, mo, &root, &rep);
  if (!root) return 0;
  print_batch_summary(st);
  // Counts as key=value (docs/cli.md): from the checkpoint, sent again after their compute
  // process died, lost twice (internal error lines), run again with --retry-undecided, given
  // back unstarted by a worker whose threads were all on slow lines, worker ranks found dead;
  // the exit code (mpirun under --enable-recovery exits 0 whatever rank 0 returns); whether
  // rank 0 answered lines itself, no worker being left. New keys go last (a contract).
  const int rc = batch_exit_code(st);
  std::ostringstream s;
  s << "surfcert batch --mpi: resumed=" << rep.resumed << " retried=" << rep.retried
    << " lost_twice=" << rep.lost_twice << " second_pass=" << rep.second_pass
    << " returned=" << rep.returned << " dead_ranks=" << rep.dead_ranks
    << " recovery=" << (rep.recovery ? 1 : 0) << " exit=" << rc
    << " local_fallback=" << (rep.local_fallback ? 1 : 0) << "\n";
  stderr_line(s);
  return rc;
}

int cmd_batch(const Opts& o) {
  certify::Mode mode = mode_arg(o.mode);
  if (o.mpi || o.mpi_child) {
    if (!app::mpi_available())
      throw UsageError("--mpi: this surfcert was built without MPI (install openmpi-bin and "
                       "libopenmpi-dev, e.g. with scripts/setup.sh, and build again)");
    // `surfcert` of a build with MPI: the MPI code is in surfcert-mpi (app/CMakeLists.txt).
    if (o.mpi)
      if (const char* exe = app::mpi_executable()) return exec_mpi_executable(exe);
  } else if (!o.checkpoint.empty() || o.retry_undecided > 0 || o.rank_timeout_set) {
    throw UsageError(std::string(!o.checkpoint.empty() ? "--checkpoint"
                                 : o.rank_timeout_set  ? "--rank-timeout"
                                                       : "--retry-undecided") +
                     " needs --mpi");
  }
  // FLINT prints the diagnostic of an abort with printf on stdout: while the batch runs, fd 1
  // is stderr and the answers go to a private duplicate of the original stdout.
  std::cout.flush();
  std::fflush(stdout);
  int out_fd = ::dup(1);
  if (out_fd < 0 || ::dup2(2, 1) < 0) throw std::runtime_error("cannot duplicate stdout");
  if (o.mpi || o.mpi_child) {
    const int rc = cmd_batch_mpi(o, out_fd);
    ::close(out_fd);
    return rc;
  }
  app::BatchStats st;
  {
    const double budget = o.budget_ms;
    const certify::Detail detail = detail_arg(o.detail);
    app::BatchStreamOptions opt;
    opt.threads = o.threads;
    opt.ordered = !o.unordered;
    // A timeout-killed batch (SIGTERM, SIGINT, SIGHUP) writes every completed answer first.
    opt.flush_on_signal = true;
    // A progress line on a terminal (stderr): lines/s and the outcomes so far, twice a second.
    const auto t0 = std::chrono::steady_clock::now();
    auto last = t0;
    if (::isatty(2))
      opt.progress = [&](const app::BatchStats& s) {
        const auto now = std::chrono::steady_clock::now();
        if (now - last < std::chrono::milliseconds(500)) return;
        last = now;
        const double secs = std::chrono::duration<double>(now - t0).count();
        std::fprintf(stderr, "\r%ld lines, %.1f lines/s, %ld certified, %ld undecided, %ld errors ",
                     s.lines, secs > 0 ? static_cast<double>(s.lines) / secs : 0.0, s.certified,
                     s.undecided, s.errors);
        std::fflush(stderr);
      };
    st = app::process_batch_fd(
        0, out_fd, mode,
        [budget, detail](const std::string& line, long no, certify::Mode m) {
          return app::answer_batch_line(line, no, m, budget, detail);
        },
        opt);
    if (opt.progress) std::fputs("\n", stderr);
  }
  ::close(out_fd);
  print_batch_summary(st);
  return batch_exit_code(st);
}

// generate: the labelled lines on stdout. Exit code 3 when some label is not certified, 1
// when labelling some line failed inside (its label says "error").
int cmd_generate(Opts& o) {
  app::GenerateRequest& r = o.gen;
  r.encoding = *app::parse_encoding(o.encoding); // checked by CLI11
  r.threads = o.threads;
  r.gaps.clear();
  std::stringstream in(o.gaps);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty() || item.size() > 4 ||
        item.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(Location{"<command line>", 0, 0, ""},
                       "--gaps: comma-separated integers k (the gaps are 2^-k)",
                       "\"" + o.gaps + "\"");
    r.gaps.push_back(std::stoi(item));
  }
  const std::vector<Json> lines = app::generate(r);
  std::ios::sync_with_stdio(false);
  bool undecided = false, failed = false;
  for (const Json& line : lines) {
    const std::string status = line.find("label")->find("status")->text();
    undecided = undecided || status == "undecided";
    failed = failed || status == "error";
    std::cout << core::io::dump(line) << '\n';
  }
  std::cout.flush();
  return failed ? 1 : undecided ? 3 : 0;
}

CLI::Option* add_mode(CLI::App* sub, Opts& o) {
  return sub
      ->add_option("--mode", o.mode,
                   "exact, filtered (default: interval filter, exact fallback) or float")
      ->check(CLI::IsMember({"exact", "filtered", "float"}))
      ->type_name("exact|filtered|float");
}

// --detail: the levels `levels` (certify/detail.hpp) of the command's answers (JSON only; the
// text output is the same at every level).
void add_detail(CLI::App* sub, Opts& o, const std::vector<std::string>& levels,
                const std::string& help) {
  std::string type;
  for (const auto& l : levels)
    type += (type.empty() ? "" : "|") + l;
  sub->add_option("--detail", o.detail, help)->check(CLI::IsMember(levels))->type_name(type);
}

const char* kQsicDetailHelp =
    "how much the JSON answer carries: topology (the decision), certificate (+ what re-checks "
    "it: matrices, f, invariants, roots, separators), full (default: + special points)";

} // namespace

int main(int argc, char** argv) {
  app::install_flint_abort_handler(); // a FLINT abort becomes an internal error (exit code 1)
  g_argv = argv;
  int rc = 1;
  Opts o;
  CLI::App cli{"surfcert: certified topology of the intersection of two quadrics", "surfcert"};
  cli.set_version_flag("--version", "surfcert " SURFCERT_VERSION);
  cli.require_subcommand(1);
  cli.footer("See docs/json-contract.md for the JSON contract (README.md for an overview).");

  CLI::App* classify =
      cli.add_subcommand("classify", "classify 'EQ_A' 'EQ_B': topology of the curve");
  classify->allow_extras();
  add_mode(classify, o);
  classify->add_flag("--json", o.json, "JSON envelope on stdout");
  add_detail(classify, o, {"topology", "certificate", "full"}, kQsicDetailHelp);

  CLI::App* intersect =
      cli.add_subcommand("intersect", "intersect 'EQ_A' 'EQ_B': topology and traced branches");
  intersect->allow_extras();
  add_mode(intersect, o);
  intersect->add_flag("--json", o.json, "JSON envelope on stdout");
  add_detail(intersect, o, {"topology", "certificate", "full"}, kQsicDetailHelp);
  intersect->add_option("--tol", o.tol, "geometric tolerance of the traced branches, 1e-12 to 1")
      ->check(CLI::Validator(
          [](std::string& v) {
            return tol_value(v) > 0 ? std::string()
                                    : "expected a number from 1e-12 to 1, found \"" + v + "\"";
          },
          "1e-12..1"));
  intersect->add_option("--export", o.export_path, "write the branches to F.obj or F.ply");
  intersect->add_option("--svg", o.svg_path, "draw the curve to F.svg");
  intersect->add_option("--box", o.box,
                        "trace unbounded curves in the box X0,Y0,Z0,X1,Y1,Z1 (min then max; "
                        "exact numbers such as 1/3 or 1-1/2^64, rounded once to doubles; "
                        "default: chosen automatically)");

  CLI::App* distance = cli.add_subcommand(
      "distance", "distance 'SURF_A' 'SURF_B': certified distance (equations or JSON surfaces)");
  distance->allow_extras();
  add_mode(distance, o);
  distance->add_flag("--json", o.json, "JSON envelope on stdout");
  distance->add_flag("--solid", o.solid, "distance between solids (0 when they overlap)");
  add_detail(distance, o, {"value", "full"},
             "how much the JSON answer carries: value (enclosure, minimizers, pairs, method) or "
             "full (default: + candidate counts and the eliminated system's degrees)");
  distance->add_option("--digits", o.digits, "requested relative precision 10^-N, 1 to 1000")
      ->check(CLI::Range(1L, 1000L));

  CLI::App* verify = cli.add_subcommand(
      "verify", "verify 'SURF_A' 'SURF_B' --claim JSON: verdicts on another program's claims");
  verify->allow_extras();
  add_mode(verify, o);
  verify->add_flag("--json", o.json,
                   "JSON answer {\"status\", \"result\": {\"verdicts\"}} on stdout");
  verify
      ->add_option("--claim", o.claims,
                   "a claim {\"kind\", \"value\", ...} or an array of claims (repeatable)")
      ->allow_extra_args(false);

  CLI::App* run = cli.add_subcommand("run", "run SCENE.json: every query of a scene");
  run->add_option("scene", o.scene_path, "the scene file")->required();
  run->add_option("-o", o.out_path, "also write the JSON report to this file (atomically)");
  run->add_flag("--json", o.json, "JSON report on stdout");
  add_mode(run, o);

  CLI::App* batch =
      cli.add_subcommand("batch", "JSON lines on stdin -> JSON lines on stdout, in input order");
  add_mode(batch, o);
  batch->add_option("--threads", o.threads, "lines answered at once, 1 to 256")
      ->check(CLI::Range(1, 256));
  batch
      ->add_option("--budget-ms", o.budget_ms,
                   "default time budget per line in ms (a line's \"budget_ms\" overrides; past "
                   "it the line answers undecided, reason \"budget\"); 0 = none")
      ->check(not_nan())
      ->check(CLI::Range(0.0, 1e9));
  add_detail(batch, o, {"value", "topology", "certificate", "full"},
             "default detail of the lines (a line's \"detail\" overrides): classify and "
             "intersect read value as topology, distance reads topology and certificate as value");
  batch->add_flag("--unordered", o.unordered,
                  "write each answer as soon as it is done (not in input order; key by \"id\")");
  batch->add_flag("--mpi", o.mpi,
                  "spread the lines over the ranks of an MPI job (mpirun/srun; rank 0 reads and "
                  "writes, the others compute; docs/cli.md)");
  batch
      ->add_option("--checkpoint", o.checkpoint,
                   "--mpi: append each answer to FILE; a run restarted with it skips the lines "
                   "answered there")
      ->type_name("FILE");
  batch
      ->add_option("--retry-undecided", o.retry_undecided,
                   "--mpi: run the lines undecided by their budget again, after the others, "
                   "with this budget in ms")
      ->check(not_nan())
      ->check(CLI::Range(1.0, 1e9))
      ->type_name("MS");
  batch
      ->add_option("--rank-timeout", o.rank_timeout,
                   "--mpi under mpirun --enable-recovery: a rank silent this long (heartbeats) "
                   "is dead and its lines go to the others")
      ->check(not_nan())
      ->check(CLI::Range(0.5, 1e6))
      ->each([&o](const std::string&) { o.rank_timeout_set = true; })
      ->type_name("S");
  batch->add_flag("--mpi-child", o.mpi_child, "")->group(""); // batch --mpi's compute child

  CLI::App* generate = cli.add_subcommand(
      "generate", "labelled test cases as batch lines (JSON lines on stdout; docs/cli.md)");
  generate
      ->add_option(
          "--case", o.gen.what,
          "1..35, all (the 35 + degenerate_pencil + coincident), degenerate_pencil, "
          "coincident, ellipsoid, natural (cylinders, cones, paraboloids, hyperboloids) or "
          "distance (default all)")
      ->type_name("N|all|degenerate_pencil|coincident|ellipsoid|natural|distance");
  generate->add_option("--count", o.gen.count, "random instances per case, 1 to 1000000")
      ->check(CLI::Range(1L, 1000000L));
  generate->add_option("--seed", o.gen.seed, "the seed (same seed, same lines)");
  generate->add_option("--encoding", o.encoding, "exact, double (binary64-exact) or shape")
      ->check(CLI::IsMember({"exact", "double", "shape"}))
      ->type_name("exact|double|shape");
  generate
      ->add_option("--family", o.gen.family,
                   "a path through a degeneracy instead of --case: tangency, node, acnode, cusp, "
                   "double_conic, touching, nested or all")
      ->check(CLI::IsMember(
          {"tangency", "node", "acnode", "cusp", "double_conic", "touching", "nested", "all"}));
  generate->add_option("--gaps", o.gaps, "the family's points at gap +-2^-k, 0 (default 10,20,40)")
      ->type_name("K,K,...");
  generate->add_option("--threads", o.threads, "labelling threads, 1 to 256")
      ->check(CLI::Range(1, 256));

  try {
    if (argc < 2) {
      std::cout << kUsage;
      rc = 2;
    } else {
      const std::string first = argv[1];
      if (!first.empty() && first[0] != '-' && first != "classify" && first != "intersect" &&
          first != "distance" && first != "verify" && first != "run" && first != "batch" &&
          first != "generate")
        throw UsageError("unknown command " + first);
      try {
        cli.parse(argc, argv);
      } catch (const CLI::CallForHelp&) {
        auto subs = cli.get_subcommands();
        std::cout << (subs.empty() ? kUsage : subs[0]->help());
        flint_cleanup();
        return 0;
      } catch (const CLI::CallForAllHelp&) {
        std::cout << cli.help("", CLI::AppFormatMode::All);
        flint_cleanup();
        return 0;
      } catch (const CLI::CallForVersion& e) {
        std::cout << e.what() << "\n";
        flint_cleanup();
        return 0;
      } catch (const CLI::ParseError& e) {
        throw UsageError(e.what());
      }
      for (CLI::App* sub : cli.get_subcommands())
        for (CLI::Option* opt : sub->get_options())
          if (opt->get_name() == "--mode" && opt->count() > 0) o.mode_given = true;
      if (classify->parsed())
        rc = cmd_classify(equations(*classify), o);
      else if (intersect->parsed())
        rc = cmd_intersect(equations(*intersect), o);
      else if (distance->parsed())
        rc = cmd_distance(equations(*distance), o);
      else if (verify->parsed())
        rc = cmd_verify(equations(*verify), o);
      else if (run->parsed())
        rc = cmd_run(o);
      else if (batch->parsed())
        rc = cmd_batch(o);
      else if (generate->parsed())
        rc = cmd_generate(o);
    }
  } catch (const InputError& e) {
    std::cerr << "surfcert: error: " << e.what() << "\n";
    rc = 2;
  } catch (const UsageError& e) {
    std::cerr << "surfcert: error: " << e.what() << "\n\n" << kUsage;
    rc = 2;
  } catch (const std::exception& e) {
    std::cerr << "surfcert: internal error: " << e.what() << "\n";
    rc = 1;
  }
  flint_cleanup();
  return rc;
}
