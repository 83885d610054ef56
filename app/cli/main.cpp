// The `surfcert` command line: classify, run, batch. Exit codes: 0 success, 2 bad input
// (message with location on stderr, nothing written), 3 finished with undecided results,
// 1 internal error.
#include "surfcert/app/scene.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/report.hpp"
#include "surfcert/core/io/expression.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/trace/export.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <flint/flint.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace surfcert;
using core::InputError;
using core::Location;
using core::io::Json;

namespace {

const char* kUsage =
    "surfcert 0.1.0: certified topology of the intersection of two quadrics\n"
    "\n"
    "usage:\n"
    "  surfcert classify 'EQ_A' 'EQ_B' [--mode exact|filtered|float] [--json]\n"
    "  surfcert intersect 'EQ_A' 'EQ_B' [--mode M] [--tol T] [--json] [--export F.obj|F.ply] "
    "[--svg F.svg]\n"
    "  surfcert distance 'SURF_A' 'SURF_B' [--digits N] [--solid] [--mode M] [--json]   "
    "(equations, or JSON "
    "surfaces incl. {\"type\":\"torus\",...})\n"
    "  surfcert run SCENE.json [-o REPORT.json] [--json] [--mode M]\n"
    "  surfcert batch [--mode M] [--threads N]     (JSON lines on stdin -> JSON lines on stdout)\n"
    "  surfcert --help | --version\n"
    "\n"
    "Equations are polynomials in x, y, z (e.g. 'x^2 + y^2/4 + z^2 = 1'); numbers are read\n"
    "exactly (0.1 = 1/10). Mode filtered (default) answers from interval arithmetic when it is\n"
    "provably right and falls back to exact arithmetic otherwise; float is uncertified.\n"
    "See README.md for the JSON contract.\n";

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

int cmd_classify(const std::vector<std::string>& args) {
  std::vector<std::string> eq;
  certify::Mode mode = certify::Mode::Filtered;
  bool json = false;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--json")
      json = true;
    else if (args[i] == "--mode" && i + 1 < args.size())
      mode = mode_arg(args[++i]);
    else if (args[i].rfind("--mode=", 0) == 0)
      mode = mode_arg(args[i].substr(7));
    else if (args[i].size() > 1 && args[i][0] == '-' && args[i][1] == '-')
      throw UsageError("unknown option " + args[i]);
    else
      eq.push_back(args[i]);
  }
  if (eq.size() != 2) throw UsageError("classify needs exactly two equations");
  auto a = core::io::quadric_from_equation(eq[0], Location{"<argument 1>", 1, 1, ""});
  auto b = core::io::quadric_from_equation(eq[1], Location{"<argument 2>", 1, 1, ""});
  certify::QsicResult r = certify::classify_qsic(a, b, mode);
  certify::complete_report_data(r, a, b);
  if (json)
    std::cout << core::io::dump(certify::qsic_envelope_json(r, a, b), 2) << "\n";
  else
    std::cout << certify::qsic_result_text(r, a, b);
  return r.status == certify::Status::Undecided ? 3 : 0;
}

std::string tol_text(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", t);
  return buf;
}

int cmd_intersect(const std::vector<std::string>& args) {
  std::vector<std::string> eq;
  certify::Mode mode = certify::Mode::Filtered;
  bool json = false;
  std::string export_path, svg_path;
  trace::TraceOptions opt;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--json")
      json = true;
    else if (args[i] == "--mode" && i + 1 < args.size())
      mode = mode_arg(args[++i]);
    else if (args[i] == "--export" && i + 1 < args.size())
      export_path = args[++i];
    else if (args[i] == "--svg" && i + 1 < args.size())
      svg_path = args[++i];
    else if (args[i] == "--tol" && i + 1 < args.size()) {
      auto t = core::Rational::from_string(args[++i]);
      double d = t ? t->to_double_approx() : 0;
      if (!(d >= 1e-12 && d <= 1))
        throw InputError(Location{"<command line>", 0, 0, ""}, "--tol between 1e-12 and 1",
                         "\"" + args[i] + "\"");
      opt.tolerance = d;
    } else if (args[i].size() > 1 && args[i][0] == '-' && args[i][1] == '-')
      throw UsageError("unknown option " + args[i]);
    else
      eq.push_back(args[i]);
  }
  if (eq.size() != 2) throw UsageError("intersect needs exactly two equations");
  auto ends_with = [](const std::string& s, const std::string& e) {
    return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
  };
  if (!export_path.empty() && !ends_with(export_path, ".obj") && !ends_with(export_path, ".ply"))
    throw InputError(Location{"<command line>", 0, 0, ""}, "--export FILE.obj or FILE.ply",
                     "\"" + export_path + "\"");
  auto a = core::io::quadric_from_equation(eq[0], Location{"<argument 1>", 1, 1, ""});
  auto b = core::io::quadric_from_equation(eq[1], Location{"<argument 2>", 1, 1, ""});
  trace::CurveResult c = trace::intersect_curve(a, b, mode, opt);
  std::vector<trace::Point3> special;
  for (const auto& p : c.topology.special_points)
    if (!p.at_infinity) special.push_back(p.approx);
  if (!export_path.empty())
    write_atomically(export_path, ends_with(export_path, ".obj")
                                      ? trace::to_obj(c.branches, c.isolated_points)
                                      : trace::to_ply(c.branches, c.isolated_points));
  if (!svg_path.empty()) {
    trace::Picture pic;
    pic.branches = c.branches;
    pic.special_points = special;
    pic.caption =
        c.topology.morphology
            ? "case " + std::to_string(c.topology.tu_case) + " " + c.topology.morphology->id +
                  ": " + c.topology.morphology->description + " (topology " +
                  certify::to_string(c.topology.status) + "; branches traced to tolerance " +
                  tol_text(opt.tolerance) +
                  (c.matches_topology ? ", matching it)" : ", NOT matching it: undecided)")
            : std::string("no curve: ") + c.note;
    write_atomically(svg_path, trace::to_svg(a, b, pic));
  }
  if (json) {
    std::cout << core::io::dump(trace::curve_envelope_json(c, a, b), 2) << "\n";
  } else {
    std::cout << certify::qsic_result_text(c.topology, a, b);
    std::cout << "curve: " << certify::to_string(c.status) << ", " << c.branches.size()
              << " branch(es):";
    for (const auto& br : c.branches)
      std::cout << " " << br.kind << "(" << br.points.size() << " points)";
    std::cout << ", " << c.isolated_points.size() << " isolated point(s), max residual "
              << c.max_residual << "\n";
    if (!c.note.empty()) std::cout << "note: " << c.note << "\n";
  }
  return c.status == certify::Status::Undecided ? 3 : 0;
}

int cmd_distance(const std::vector<std::string>& args) {
  std::vector<std::string> eq;
  long digits = 15;
  bool json = false, solid = false;
  certify::Mode mode = certify::Mode::Filtered;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--json")
      json = true;
    else if (args[i] == "--mode" && i + 1 < args.size())
      mode = mode_arg(args[++i]);
    else if (args[i].rfind("--mode=", 0) == 0)
      mode = mode_arg(args[i].substr(7));
    else if (args[i] == "--solid")
      solid = true;
    else if (args[i] == "--digits" && i + 1 < args.size()) {
      auto d = core::Integer::from_string(args[++i]);
      if (!d || *d < core::Integer(1) || core::Integer(1000) < *d)
        throw InputError(Location{"<command line>", 0, 0, ""}, "--digits from 1 to 1000",
                         "\"" + args[i] + "\"");
      digits = static_cast<long>(d->to_double_approx());
    } else if (args[i].size() > 1 && args[i][0] == '-' && args[i][1] == '-')
      throw UsageError("unknown option " + args[i]);
    else
      eq.push_back(args[i]);
  }
  if (eq.size() != 2) throw UsageError("distance needs exactly two surfaces");
  // An argument starting with '{' is a JSON surface (shapes, matrices, a torus), else an
  // equation.
  auto surface = [](const std::string& text, const std::string& src) -> core::Surface {
    if (!text.empty() && text[0] == '{')
      return core::io::read_surface(core::io::parse_json(text, src), src, "$");
    core::Poly3 p = core::io::parse_polynomial(text, Location{src, 1, 1, ""});
    if (p.total_degree() >= 3) { // an implicit surface of degree 3..kMaxImplicitDegree
      if (p.total_degree() > core::kMaxImplicitDegree)
        throw InputError(Location{src, 1, 1, ""},
                         "a surface of total degree at most " +
                             std::to_string(core::kMaxImplicitDegree),
                         "total degree " + std::to_string(p.total_degree()));
      return core::ImplicitSurface{std::move(p)};
    }
    return core::io::quadric_from_equation(text, Location{src, 1, 1, ""});
  };
  certify::DistanceResult d = certify::surface_distance(
      surface(eq[0], "<argument 1>"), surface(eq[1], "<argument 2>"), digits, solid, mode);
  if (json) {
    std::cout << core::io::dump(certify::distance_envelope_json(d, digits), 2) << "\n";
  } else {
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
    if (!d.method.empty()) std::cout << "method: " << d.method << "\n";
  }
  return d.status == certify::Status::Undecided ? 3 : 0;
}

int cmd_run(const std::vector<std::string>& args) {
  std::string scene_path, out_path;
  bool json = false;
  std::optional<certify::Mode> mode;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "-o" && i + 1 < args.size())
      out_path = args[++i];
    else if (args[i] == "--json")
      json = true;
    else if (args[i] == "--mode" && i + 1 < args.size())
      mode = mode_arg(args[++i]);
    else if (!args[i].empty() && args[i][0] == '-')
      throw UsageError("unknown option " + args[i]);
    else if (scene_path.empty())
      scene_path = args[i];
    else
      throw UsageError("run takes one scene file");
  }
  if (scene_path.empty()) throw UsageError("run needs a scene file");
  Json doc = core::io::parse_json(read_file(scene_path), scene_path);
  app::Scene scene =
      app::read_scene(doc, scene_path, mode.value_or(certify::Mode::Filtered));
  if (mode)
    for (auto& q : scene.queries)
      q.mode = *mode; // the command line wins over the scene
  Json report = Json::object();
  report.set("surfcert_version", Json::string("0.1.0"));
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

int cmd_batch(const std::vector<std::string>& args) {
  certify::Mode mode = certify::Mode::Filtered;
  int threads = 1;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--mode" && i + 1 < args.size())
      mode = mode_arg(args[++i]);
    else if (args[i] == "--threads" && i + 1 < args.size()) {
      try {
        threads = std::stoi(args[++i]);
      } catch (...) {
        threads = 0;
      }
      if (threads < 1 || threads > 256)
        throw InputError(Location{"<command line>", 0, 0, ""}, "--threads between 1 and 256",
                         "\"" + args[i] + "\"");
    } else
      throw UsageError("unknown batch argument " + args[i]);
  }
  std::ios::sync_with_stdio(false);
  auto st = app::process_batch(std::cin, std::cout, mode, threads);
  std::cerr << "surfcert batch: " << st.lines << " lines, " << st.errors << " errors, "
            << st.undecided << " undecided, " << st.fallbacks << " exact fallbacks\n";
  return st.undecided > 0 ? 3 : 0;
}

} // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  int rc = 1;
  try {
    if (args.empty() || args[0] == "--help" || args[0] == "-h") {
      std::cout << kUsage;
      rc = args.empty() ? 2 : 0;
    } else if (args[0] == "--version") {
      std::cout << "surfcert 0.1.0\n";
      rc = 0;
    } else {
      std::vector<std::string> rest(args.begin() + 1, args.end());
      if (args[0] == "classify")
        rc = cmd_classify(rest);
      else if (args[0] == "run")
        rc = cmd_run(rest);
      else if (args[0] == "intersect")
        rc = cmd_intersect(rest);
      else if (args[0] == "distance")
        rc = cmd_distance(rest);
      else if (args[0] == "batch")
        rc = cmd_batch(rest);
      else
        throw UsageError("unknown command " + args[0]);
    }
  } catch (const InputError& e) {
    std::cerr << "surfcert: error: " << e.what() << "\n";
    rc = 2;
  } catch (const UsageError& e) {
    std::cerr << "surfcert: " << e.what() << "\n\n" << kUsage;
    rc = 2;
  } catch (const std::exception& e) {
    std::cerr << "surfcert: internal error: " << e.what() << "\n";
    rc = 1;
  }
  flint_cleanup();
  return rc;
}
