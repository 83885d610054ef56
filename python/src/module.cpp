// surfcert._surfcert: the compiled half of the Python module `surfcert` (python/surfcert/
// __init__.py is the other half and the one users call).
//
// What it represents: the embedding API (surfcert/surfcert.hpp) reduced to two calls that
// answer in the batch line's JSON: run (one query) and run_batch (many, on native threads
// with the interpreter lock released), plus generate (the lines of `surfcert generate`). A surface
// arrives as a "side":
//   ("text", str)                       an equation or a JSON surface (Surface::parse),
//   ("matrix", float64 array (4, 4))    doubles read exactly (Surface::from_matrix),
//   ("shape", type, float64 array (10,)) centre xyz, semi-axes abc, quaternion wxyz;
// run_batch takes ("texts", [str, ...]), ("matrices", (N, 4, 4)), ("shapes", type, (N, 10))
// or one of the single sides (the same surface for every item).
// Every answer is a tuple (ok, json_text, curves): ok false means json_text is the batch
// line's "error" object (kind "input" with source, line, column, json_path, or "internal");
// curves, for intersect, is ([(kind, closed, float64 array (n, 3)), ...], array (m, 3)) with
// the tracer's doubles as they are. Nothing here computes or decides anything.
#include "surfcert/app/scene.hpp"
#include "surfcert/certify/report.hpp"
#include "surfcert/surfcert.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;

namespace {

using surfcert::Json;
using surfcert::Options;
using surfcert::Surface;

// One surface as the worker threads need it: plain C++ data, read without the GIL.
struct Spec {
  enum class Kind { Text, Matrix, Shape } kind = Kind::Text;
  std::string text, type;
  std::array<double, 16> v{};
};

Surface make_surface(const Spec& s, const std::string& source, const std::string& path) {
  switch (s.kind) {
  case Spec::Kind::Text:
    return Surface::parse(s.text, source, path);
  case Spec::Kind::Matrix: {
    std::array<std::array<double, 4>, 4> m;
    for (int i = 0; i < 16; ++i)
      m[i / 4][i % 4] = s.v[i];
    return Surface::from_matrix(m, path);
  }
  case Spec::Kind::Shape:
    return Surface::from_shape(s.type, {s.v[0], s.v[1], s.v[2]}, {s.v[3], s.v[4], s.v[5]},
                               std::array<double, 4>{s.v[6], s.v[7], s.v[8], s.v[9]}, path);
  }
  throw std::logic_error("unknown surface kind");
}

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The specs of one side of a batch (n items; a single side is repeated); n = 0 asks the side
// for its own length.
std::vector<Spec> read_side(const py::tuple& side, std::size_t& n) {
  const std::string tag = side[0].cast<std::string>();
  std::vector<Spec> out;
  if (tag == "texts") {
    for (const auto& t : side[1].cast<py::list>()) {
      Spec s;
      s.text = t.cast<std::string>();
      out.push_back(std::move(s));
    }
  } else if (tag == "matrices" || tag == "matrix") {
    Rows a = side[1].cast<Rows>();
    const bool one = tag == "matrix";
    if ((one && (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)) ||
        (!one && (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4)))
      throw py::value_error(one ? "a matrix must have shape (4, 4)"
                                : "matrices must have shape (N, 4, 4)");
    const std::size_t count = one ? 1 : static_cast<std::size_t>(a.shape(0));
    const double* p = a.data();
    for (std::size_t i = 0; i < count; ++i) {
      Spec s;
      s.kind = Spec::Kind::Matrix;
      std::copy(p + 16 * i, p + 16 * (i + 1), s.v.begin());
      out.push_back(s);
    }
  } else if (tag == "shapes" || tag == "shape") {
    const std::string type = side[1].cast<std::string>();
    Rows a = side[2].cast<Rows>();
    const bool one = tag == "shape";
    if ((one && (a.ndim() != 1 || a.shape(0) != 10)) ||
        (!one && (a.ndim() != 2 || a.shape(1) != 10)))
      throw py::value_error(one ? "shape parameters must have shape (10,)"
                                : "shape parameters must have shape (N, 10)");
    const std::size_t count = one ? 1 : static_cast<std::size_t>(a.shape(0));
    const double* p = a.data();
    for (std::size_t i = 0; i < count; ++i) {
      Spec s;
      s.kind = Spec::Kind::Shape;
      s.type = type;
      std::copy(p + 10 * i, p + 10 * (i + 1), s.v.begin());
      out.push_back(s);
    }
  } else if (tag == "text") {
    Spec s;
    s.text = side[1].cast<std::string>();
    out.push_back(std::move(s));
  } else {
    throw py::value_error("unknown surface side " + tag);
  }
  const bool single = tag == "text" || tag == "matrix" || tag == "shape";
  if (!single) {
    if (n == 0) n = out.size();
    if (out.size() != n) throw py::value_error("the two sides of a batch differ in length");
  }
  return out;
}

Options read_options(const std::string& op, const std::string& mode, const std::string& detail,
                     long digits, bool solid, double tolerance, double budget_ms) {
  Options o;
  auto m = surfcert::certify::parse_mode(mode);
  if (!m)
    throw surfcert::InputError(surfcert::Location{"<options>", 0, 0, "$.mode"},
                               "a mode: \"exact\", \"filtered\" or \"float\"", "\"" + mode + "\"");
  o.mode = *m;
  auto d = surfcert::certify::parse_detail(detail);
  if (!d)
    throw surfcert::InputError(surfcert::Location{"<options>", 0, 0, "$.detail"},
                               std::string("a detail for ") + op + ": " +
                                   surfcert::certify::detail_spellings(op),
                               "\"" + detail + "\"");
  o.detail = *d;
  o.digits = digits;
  o.solid = solid;
  o.tolerance = tolerance;
  o.budget_ms = budget_ms;
  return o;
}

struct Out {
  bool ok = false;
  std::string json;
  bool has_curves = false;
  std::vector<surfcert::trace::Branch> branches;
  std::vector<surfcert::trace::Point3> isolated;
};

Json error_json(const std::string& message) {
  Json e = Json::object();
  e.set("kind", Json::string("internal"));
  e.set("message", Json::string(message));
  return e;
}

// One query, entirely in C++ (no Python object is touched: callable without the GIL).
Out answer(const std::string& op, const Spec& a, const Spec& b, const std::string& src_a,
           const std::string& src_b, const std::string& mode, const std::string& detail,
           long digits, bool solid, double tolerance, double budget_ms, const std::string& claims) {
  Out out;
  try {
    try {
      const Options o = read_options(op, mode, detail, digits, solid, tolerance, budget_ms);
      const Surface sa = make_surface(a, src_a, "$.a");
      const Surface sb = make_surface(b, src_b, "$.b");
      Json j;
      if (op == "classify") {
        j = surfcert::classify(sa, sb, o).to_json();
      } else if (op == "intersect") {
        surfcert::Intersection r = surfcert::intersect(sa, sb, o);
        j = r.to_json();
        out.has_curves = true;
        out.branches = std::move(r.curve.branches);
        out.isolated = std::move(r.curve.isolated_points);
      } else if (op == "distance") {
        j = surfcert::distance(sa, sb, o).to_json();
      } else if (op == "verify") {
        j = surfcert::verify(sa, sb, surfcert::core::io::parse_json(claims, "<claims>"), o)
                .to_json();
      } else {
        throw surfcert::InputError(surfcert::Location{"<options>", 0, 0, "$.op"},
                                   "an op: \"classify\", \"intersect\", \"distance\" or \"verify\"",
                                   "\"" + op + "\"");
      }
      out.json = surfcert::core::io::dump(j);
      out.ok = true;
    } catch (const surfcert::InputError& e) {
      out.json = surfcert::core::io::dump(surfcert::certify::input_error_json(e));
    }
  } catch (const std::exception& e) {
    out.json = surfcert::core::io::dump(error_json(e.what()));
  } catch (...) {
    out.json = surfcert::core::io::dump(error_json("unknown exception"));
  }
  return out;
}

py::array_t<double> points_array(const std::vector<surfcert::trace::Point3>& pts) {
  py::array_t<double> a({static_cast<py::ssize_t>(pts.size()), py::ssize_t{3}});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < 3; ++k)
      m(static_cast<py::ssize_t>(i), k) = pts[i][k];
  return a;
}

py::tuple to_python(const Out& o) {
  py::object curves = py::none();
  if (o.has_curves) {
    py::list bs;
    for (const auto& b : o.branches)
      bs.append(py::make_tuple(b.kind, b.closed, points_array(b.points)));
    curves = py::make_tuple(bs, points_array(o.isolated));
  }
  return py::make_tuple(o.ok, o.json, curves);
}

py::tuple run(const std::string& op, const py::tuple& a, const py::tuple& b,
              const std::string& mode, const std::string& detail, long digits, bool solid,
              double tolerance, double budget_ms, const std::string& claims) {
  std::size_t n = 0;
  const Spec sa = read_side(a, n).at(0), sb = read_side(b, n).at(0);
  Out o;
  {
    py::gil_scoped_release release;
    o = answer(op, sa, sb, "<a>", "<b>", mode, detail, digits, solid, tolerance, budget_ms, claims);
  }
  return to_python(o);
}

py::list run_batch(const std::string& op, const py::tuple& a, const py::tuple& b,
                   const std::string& mode, const std::string& detail, long digits, bool solid,
                   double tolerance, double budget_ms, const std::string& claims, int threads) {
  std::size_t n = 0;
  const std::vector<Spec> as = read_side(a, n), bs = read_side(b, n);
  if (n == 0 && (as.size() == 1 && bs.size() == 1)) {
    // two single sides: is either a list? (read_side set n for lists); here both single
    const std::string ta = a[0].cast<std::string>(), tb = b[0].cast<std::string>();
    const bool single_a = ta == "text" || ta == "matrix" || ta == "shape";
    const bool single_b = tb == "text" || tb == "matrix" || tb == "shape";
    if (single_a && single_b) n = 1;
  }
  std::vector<Out> outs(n);
  {
    py::gil_scoped_release release;
    surfcert::for_each_parallel(n, threads, [&](std::size_t i) {
      const Spec& sa = as.size() == 1 ? as[0] : as[i];
      const Spec& sb = bs.size() == 1 ? bs[0] : bs[i];
      outs[i] =
          answer(op, sa, sb, "<a[" + std::to_string(i) + "]>", "<b[" + std::to_string(i) + "]>",
                 mode, detail, digits, solid, tolerance, budget_ms, claims);
    });
  }
  py::list res;
  for (const auto& o : outs)
    res.append(to_python(o));
  return res;
}

// The lines of `surfcert generate` as JSON text (the GIL released while they are labelled).
// A bad request raises an InputError-carrying tuple (false, error JSON), as run does.
py::tuple generate(const std::string& cases, const std::string& family, std::vector<int> gaps,
                   long count, std::uint64_t seed, const std::string& encoding, int threads) {
  surfcert::GenerateOptions o;
  o.cases = cases;
  o.family = family;
  o.gaps = std::move(gaps);
  o.count = count;
  o.seed = seed;
  o.encoding = encoding;
  o.threads = threads;
  std::vector<std::string> lines;
  std::string error;
  bool ok = false;
  {
    py::gil_scoped_release release;
    try {
      try {
        for (const surfcert::GeneratedCase& c : surfcert::generate(o))
          lines.push_back(surfcert::core::io::dump(c.line));
        ok = true;
      } catch (const surfcert::InputError& e) {
        error = surfcert::core::io::dump(surfcert::certify::input_error_json(e));
      }
    } catch (const std::exception& e) {
      error = surfcert::core::io::dump(error_json(e.what()));
    }
  }
  if (!ok) return py::make_tuple(false, error);
  py::list out;
  for (const auto& l : lines)
    out.append(py::str(l));
  return py::make_tuple(true, out);
}

} // namespace

PYBIND11_MODULE(_surfcert, m) {
  m.doc() = "surfcert's compiled half: use the package `surfcert` (its __init__.py)";
  surfcert::app::install_flint_abort_handler(); // a FLINT abort is an error, not abort()
  m.attr("__version__") = surfcert::version();
  m.def("run", &run, py::arg("op"), py::arg("a"), py::arg("b"), py::arg("mode"), py::arg("detail"),
        py::arg("digits"), py::arg("solid"), py::arg("tolerance"), py::arg("budget_ms"),
        py::arg("claims"));
  m.def("run_batch", &run_batch, py::arg("op"), py::arg("a"), py::arg("b"), py::arg("mode"),
        py::arg("detail"), py::arg("digits"), py::arg("solid"), py::arg("tolerance"),
        py::arg("budget_ms"), py::arg("claims"), py::arg("threads"));
  m.def("generate", &generate, py::arg("cases"), py::arg("family"), py::arg("gaps"),
        py::arg("count"), py::arg("seed"), py::arg("encoding"), py::arg("threads"));
}
