// intersect_curve end to end on every ellipsoid case: the branches returned must reproduce the
// certified morphology (counts by kind), every point must lie on both surfaces, and a rational
// rigid motion must move the branches with the surfaces. The batch's direct text of an answer
// (append_curve_envelope) is byte for byte the document's (curve_envelope_json, dump), on every
// fixture pencil at every detail level (boxes, exits, conics, notes) and on awkward doubles
// against a reference builder (printf "%.17g"). On random double ellipsoid pairs (the
// benchmark's family) every point lies on both exact surfaces (first-order distance from the
// exact rational f, g) within 1e-12 of the scene, at most the reported max_residual, every
// chord's midpoint within the tolerance of both surfaces, and certified answers have the
// certified morphology's branches.
#include "support/fixtures.hpp"

#include "surfcert/core/error.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

using namespace surfcert;
using certify::Mode;
using core::Rational;

namespace {

struct Counts {
  int loops = 0, conics = 0, points = 0;
};

Counts count(const trace::CurveResult& r) {
  Counts c;
  for (const auto& b : r.branches) {
    if (b.kind == "loop" || b.kind == "figure_eight" || b.kind == "loop_with_cusp") ++c.loops;
    if (b.kind == "conic" || b.kind == "double_conic") ++c.conics;
  }
  c.points = static_cast<int>(r.isolated_points.size());
  return c;
}

// Independent check of the counts against the morphology table.
void expect_matches_morphology(const trace::CurveResult& r, const std::string& ctx) {
  ASSERT_NE(r.topology.morphology, nullptr) << ctx;
  const auto& m = *r.topology.morphology;
  Counts c = count(r);
  EXPECT_EQ(c.loops, m.loops) << ctx;
  EXPECT_EQ(c.conics, m.conics) << ctx;
  EXPECT_EQ(c.points, m.isolated_points) << ctx;
  EXPECT_EQ(r.status, certify::Status::Certified) << ctx << " note: " << r.note;
  EXPECT_LE(r.max_residual, 1e-12) << ctx;
  for (const auto& b : r.branches) {
    EXPECT_TRUE(b.closed) << ctx;
    EXPECT_GE(b.points.size(), 8u) << ctx << " " << b.kind;
  }
}

} // namespace

TEST(Intersect, AllEllipsoidFixtures) {
  auto doc = fixtures::load_json("fixtures/ellipsoid_fixtures.json");
  trace::TraceOptions opt;
  for (const auto& [key, e] : doc.members()) {
    core::QuadricMatrix a(fixtures::mat4_from_json(*e.find("E1"))),
        b(fixtures::mat4_from_json(*e.find("E2")));
    auto r = trace::intersect_curve(a, b, Mode::Filtered, opt);
    EXPECT_EQ(r.topology.tu_case, std::stoi(key));
    expect_matches_morphology(r, "ellipsoid fixture case " + key);
  }
}

TEST(Intersect, ReadableFixtures) {
  auto doc = fixtures::load_json("fixtures/nice_axis_aligned_fixtures.json");
  trace::TraceOptions opt;
  for (const auto& [key, e] : doc.members()) {
    auto fix = [](std::string s) {
      return std::regex_replace(s, std::regex("/([0-9]+)/([0-9]+)"), "/($1/$2)");
    };
    auto a = core::io::quadric_from_equation(fix(e.find("E1")->text()), {"t", 1, 1, ""});
    auto b = core::io::quadric_from_equation(fix(e.find("E2")->text()), {"t", 1, 1, ""});
    auto r = trace::intersect_curve(a, b, Mode::Filtered, opt);
    EXPECT_EQ(r.topology.tu_case, std::stoi(key));
    expect_matches_morphology(r, "readable fixture case " + key);
  }
}

TEST(Intersect, RigidMotionMovesTheBranches) {
  // Rotation from the integer quaternion (1, 2, 2, 1) (rational matrix), then a translation.
  const long w = 1, x = 2, y = 2, z = 1;
  Rational n(w * w + x * x + y * y + z * z);
  long R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                  {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                  {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  Rational t[3] = {Rational(1, 3), Rational(-2, 7), Rational(5, 4)};
  // New coordinates X' = R X + t, i.e. X = R^T (X' - t): quadric matrix P^T M P with P = that map.
  core::Mat4 p;
  for (size_t i = 0; i < 3; ++i) {
    Rational s;
    for (size_t j = 0; j < 3; ++j) {
      p[i][j] = Rational(R[j][i]) / n;
      s += p[i][j] * t[j];
    }
    p[i][3] = -s;
  }
  p[3][3] = Rational(1);
  const char* pairs[][2] = {{"x^2+y^2+4z^2/9=1", "x^2/4+(y-1)^2/4+z^2=1"}, // figure eight
                            {"x^2/4+y^2+z^2=1", "(x-1)^2+y^2+z^2/4=1"},    // loop + acnode
                            {"x^2+y^2/4+z^2=1", "x^2-2x+9y^2+9z^2/4=8"},   // two loops
                            {"x^2/4+y^2+z^2=1", "x^2+y^2/4+z^2=1"}};       // two conics
  trace::TraceOptions opt;
  for (const auto& pr : pairs) {
    auto a = core::io::quadric_from_equation(pr[0], {"t", 1, 1, ""});
    auto b = core::io::quadric_from_equation(pr[1], {"t", 1, 1, ""});
    auto r0 = trace::intersect_curve(a, b, Mode::Exact, opt);
    auto a1 = a.congruent(p), b1 = b.congruent(p);
    auto r1 = trace::intersect_curve(a1, b1, Mode::Exact, opt);
    EXPECT_EQ(r0.topology.tu_case, r1.topology.tu_case) << pr[0];
    auto c0 = count(r0), c1 = count(r1);
    EXPECT_EQ(c0.loops, c1.loops) << pr[0];
    EXPECT_EQ(c0.conics, c1.conics) << pr[0];
    EXPECT_EQ(c0.points, c1.points) << pr[0];
    EXPECT_EQ(r1.status, certify::Status::Certified) << pr[0] << " " << r1.note;
    // Moved branch points lie on the moved surfaces (residual check in the moved frame).
    EXPECT_LE(r1.max_residual, 1e-12) << pr[0];
    // The moved original points lie on the moved surfaces too (independent of the tracer run).
    trace::QuadricPair q1(a1, b1);
    for (const auto& br : r0.branches)
      for (size_t k = 0; k < br.points.size(); k += 7) {
        trace::Point3 m{};
        for (size_t i = 0; i < 3; ++i) {
          double s = t[i].to_double_approx();
          for (size_t j = 0; j < 3; ++j)
            s += (Rational(R[i][j]) / n).to_double_approx() * br.points[k][j];
          m[i] = s;
        }
        EXPECT_LE(std::max(std::abs(q1.f(m)), std::abs(q1.g(m))), 1e-9) << pr[0];
      }
  }
}

TEST(Intersect, DegenerateInputsAreNotCertifiedCurves) {
  trace::TraceOptions opt;
  auto cyl = core::io::quadric_from_equation("x^2+y^2=1", {"t", 1, 1, ""});
  auto cyl2 = core::io::quadric_from_equation("(x-1)^2+y^2=1", {"t", 1, 1, ""});
  // Equal parallel cylinders (a degenerate pencil): since issue 15 the two lines x = 1/2,
  // y = +-sqrt(3)/2 in closed form (degenerate_trace_test checks more such pairs).
  auto r = trace::intersect_curve(cyl, cyl2, Mode::Exact, opt);
  EXPECT_EQ(r.status, certify::Status::Certified) << r.note;
  ASSERT_EQ(r.branches.size(), 2u);
  for (const auto& br : r.branches)
    for (const auto& p : br.points) {
      EXPECT_NEAR(p[0], 0.5, 1e-12);
      EXPECT_NEAR(std::fabs(p[1]), std::sqrt(0.75), 1e-12);
    }
  auto hyp = core::io::quadric_from_equation("x^2+y^2-z^2=1", {"t", 1, 1, ""});
  // No ellipsoid (traced in a box since issue 15): z^2 = 0, the circle x^2 + y^2 = 1 counted
  // twice.
  auto r2 = trace::intersect_curve(hyp, cyl, Mode::Exact, opt);
  EXPECT_EQ(r2.status, certify::Status::Certified);
  ASSERT_EQ(r2.branches.size(), 1u);
  EXPECT_EQ(r2.branches[0].kind, "double_conic");
  for (const auto& p : r2.branches[0].points) {
    EXPECT_NEAR(p[2], 0, 1e-12);
    EXPECT_NEAR(p[0] * p[0] + p[1] * p[1], 1, 1e-12);
  }
}

namespace {

trace::CurveResult curve(const std::string& a, const std::string& b) {
  trace::TraceOptions opt;
  return trace::intersect_curve(core::io::quadric_from_equation(a, {"t", 1, 1, ""}),
                                core::io::quadric_from_equation(b, {"t", 1, 1, ""}), Mode::Filtered,
                                opt);
}

} // namespace

TEST(Intersect, SphereAndConeClosedForm) {
  // Cone x^2 + y^2 = (3z/4)^2; a sphere centred at (0, 0, 5) is 3 away from its generatrices,
  // so radius 3 touches it along a circle, a larger one cuts two circles, a smaller misses it.
  const std::string cone = "x^2 + y^2 - 9z^2/16";
  auto tangent = curve("x^2 + y^2 + (z-5)^2 = 9", cone);
  EXPECT_EQ(tangent.topology.tu_case, 21);
  expect_matches_morphology(tangent, "sphere tangent to cone");
  ASSERT_EQ(tangent.branches.size(), 1u);
  // The circle of tangency: the foot points of (0,0,5) on the generatrix rho = 3z/4, at
  // distance 3: rho = 12/5, z = 5 - 9/5 = 16/5.
  for (const auto& p : tangent.branches[0].points) {
    EXPECT_NEAR(std::hypot(p[0], p[1]), 12.0 / 5, 1e-9);
    EXPECT_NEAR(p[2], 16.0 / 5, 1e-9);
  }
  auto cut = curve("x^2 + y^2 + (z-5)^2 = 10", cone);
  EXPECT_EQ(cut.topology.tu_case, 14);
  expect_matches_morphology(cut, "sphere cutting the cone");
  auto miss = curve("x^2 + y^2 + (z-5)^2 = 8", cone);
  EXPECT_TRUE(miss.branches.empty());
  EXPECT_EQ(miss.topology.morphology->connected_components, 0);
  // Off the axis: a quartic; whatever its case, the branches match it.
  auto off = curve("(x-1)^2 + y^2 + (z-5)^2 = 10", cone);
  expect_matches_morphology(off, "sphere off the cone's axis");
}

TEST(Intersect, NearlyTangentPairsGap2pow30) {
  const std::string e = "1/1073741824"; // 2^-30
  // Unit spheres 2 -+ 2^-30 apart: a circle of radius ~2^-15.5, or nothing.
  auto close = curve("x^2+y^2+z^2=1", "(x-2+" + e + ")^2+y^2+z^2=1");
  EXPECT_EQ(close.topology.tu_case, 17);
  expect_matches_morphology(close, "spheres overlapping by 2^-30");
  auto apart = curve("x^2+y^2+z^2=1", "(x-2-" + e + ")^2+y^2+z^2=1");
  EXPECT_EQ(apart.topology.tu_case, 16);
  EXPECT_TRUE(apart.branches.empty());
  // Two ellipsoids almost touching from outside (touching pair of case 7 moved 2^-30 closer):
  // one small oval.
  auto oval = curve("x^2/4+y^2+z^2=1", "(x-3+" + e + ")^2+y^2+z^2/4=1");
  EXPECT_EQ(oval.topology.tu_case, 3);
  expect_matches_morphology(oval, "ellipsoids overlapping by 2^-30");
}

TEST(Intersect, EllipsoidAndCylinder) {
  // Generic: a cylinder through the sphere off its axis (a quartic); tangent: along a circle.
  auto generic = curve("x^2+y^2+z^2=1", "(x-3/10)^2+y^2=1/4");
  expect_matches_morphology(generic, "sphere and off-axis cylinder");
  auto viviani = curve("x^2+y^2+z^2=1", "(x-1/2)^2+y^2=1/4");
  EXPECT_EQ(viviani.topology.tu_case, 5);
  expect_matches_morphology(viviani, "Viviani's curve");
  auto tangent = curve("x^2+y^2/4+z^2=1", "x^2+z^2=1");
  EXPECT_EQ(tangent.topology.tu_case, 21);
  expect_matches_morphology(tangent, "ellipsoid tangent to a cylinder along a circle");
}

TEST(Intersect, DirectEnvelopeTextEqualsTheDocument) {
  int checked = 0, with_box = 0, with_exits = 0;
  for (const char* file :
       {"fixtures/canonical_examples.json", "fixtures/ellipsoid_fixtures.json"}) {
    const auto doc = fixtures::load_json(file);
    for (const auto& [key, e] : doc.members()) {
      const auto* A = e.find("A") ? e.find("A") : e.find("E1");
      const auto* B = e.find("B") ? e.find("B") : e.find("E2");
      core::QuadricMatrix a(fixtures::mat4_from_json(*A)), b(fixtures::mat4_from_json(*B));
      trace::TraceOptions opt;
      opt.tolerance = 1e-2;
      for (certify::Detail d :
           {certify::Detail::Topology, certify::Detail::Certificate, certify::Detail::Full}) {
        const auto r = trace::intersect_curve(a, b, Mode::Filtered, opt, d);
        std::string text = "prefix";
        trace::append_curve_envelope(text, r, a, b, d);
        ASSERT_EQ(text, "prefix" + core::io::dump(trace::curve_envelope_json(r, a, b, d)))
            << file << " " << key;
        ++checked;
        with_box += r.box ? 1 : 0;
        for (const auto& br : r.branches)
          with_exits += br.exits.empty() ? 0 : 1;
      }
    }
  }
  EXPECT_GE(checked, 3 * 35);
  EXPECT_GT(with_box, 0);
  EXPECT_GT(with_exits, 0);
}

TEST(Intersect, DirectEnvelopeAwkwardDoubles) {
  // A reference document of the branches built here: numbers by printf "%.17g".
  auto num = [](double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return core::io::Json::number_text(buf);
  };
  core::QuadricMatrix a(fixtures::mat4_from_json(
      *fixtures::load_json("fixtures/ellipsoid_fixtures.json").find("1")->find("E1")));
  core::QuadricMatrix b(fixtures::mat4_from_json(
      *fixtures::load_json("fixtures/ellipsoid_fixtures.json").find("1")->find("E2")));
  auto r = trace::intersect_curve(a, b, Mode::Filtered, trace::TraceOptions{});
  const double awkward[] = {0.0,
                            -0.0,
                            std::numeric_limits<double>::denorm_min(),
                            -std::numeric_limits<double>::min(),
                            1e300,
                            -1.7976931348623157e308,
                            0.1,
                            -1.0 / 3,
                            123456789012345678.0,
                            1e-7,
                            2.5};
  r.branches.clear();
  trace::Branch open;
  open.kind = "arc";
  open.closed = false;
  open.exits = {3, 0};
  for (size_t i = 0; i + 2 < std::size(awkward); ++i)
    open.points.push_back({awkward[i], awkward[i + 1], awkward[i + 2]});
  trace::Branch empty;
  empty.kind = "lo\"op\\";
  r.branches = {open, empty, open};
  r.note = "a \"note\"\n";
  core::io::Json ref = core::io::Json::array();
  for (const auto& br : r.branches) {
    auto o = core::io::Json::object();
    o.set("kind", core::io::Json::string(br.kind));
    o.set("closed", core::io::Json::boolean(br.closed));
    if (!br.exits.empty()) {
      auto ex = core::io::Json::array();
      for (int i : br.exits)
        ex.push_back(core::io::Json::number(i));
      o.set("exits", ex);
    }
    auto pts = core::io::Json::array();
    for (const auto& p : br.points) {
      auto a3 = core::io::Json::array();
      for (double x : p)
        a3.push_back(num(x));
      pts.push_back(a3);
    }
    o.set("points", pts);
    ref.push_back(o);
  }
  for (certify::Detail d : {certify::Detail::Topology, certify::Detail::Full}) {
    std::string text;
    trace::append_curve_envelope(text, r, a, b, d);
    ASSERT_EQ(text, core::io::dump(trace::curve_envelope_json(r, a, b, d)));
    const auto back = core::io::parse_json(text, "direct text");
    EXPECT_EQ(core::io::dump(*back.find("result")->find("branches")), core::io::dump(ref));
    EXPECT_EQ(back.find("note")->text(), r.note);
  }
  r.branches[0].points[1][2] = std::numeric_limits<double>::quiet_NaN();
  std::string text;
  EXPECT_THROW(trace::append_curve_envelope(text, r, a, b), core::InternalError);
}

namespace {

// max over the two surfaces of |f(p)| / |grad f(p)|: f exact (rationals from the exact matrix,
// independent of the tracer's double and double-double forms), the gradient in double.
double exact_distance(const core::QuadricMatrix& m, const trace::Point3& p) {
  const auto& e = m.matrix();
  const std::array<Rational, 4> x = {Rational::exact_from_double(p[0]),
                                     Rational::exact_from_double(p[1]),
                                     Rational::exact_from_double(p[2]), Rational(1)};
  Rational f;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      f += x[i] * e[i][j] * x[j];
  double g2 = 0;
  for (size_t i = 0; i < 3; ++i) {
    double gi = 0;
    for (size_t j = 0; j < 4; ++j)
      gi += 2 * e[i][j].to_double_approx() * (j < 3 ? p[j] : 1.0);
    g2 += gi * gi;
  }
  return std::fabs(f.to_double_approx()) / std::sqrt(g2);
}

// A random ellipsoid of seed 002 5.1.3 posed in doubles: centre in [-1/2, 1/2]^3, semi-axes in
// [1/10, 1], a random double quaternion (as the double_path benchmark draws them).
core::ShapeSpec random_posed_ellipsoid(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> c(-0.5, 0.5), r(0.1, 1.0);
  std::normal_distribution<double> g(0, 1);
  core::ShapeSpec s;
  s.type = core::ShapeType::Ellipsoid;
  s.center = {c(rng), c(rng), c(rng)};
  s.radii = {r(rng), r(rng), r(rng)};
  s.rotated = true;
  s.quaternion = {g(rng), g(rng), g(rng), g(rng)};
  return s;
}

} // namespace

TEST(Intersect, RandomDoubleEllipsoidPairsPointsAndChords) {
  std::mt19937_64 rng(1225);
  auto shape = [&] { return random_posed_ellipsoid(rng); };
  const double tol = 2e-4;
  int traced = 0, certified = 0;
  for (int i = 0; i < 40; ++i) {
    const core::QuadricMatrix a(shape()), b(shape());
    trace::TraceOptions opt;
    opt.tolerance = tol;
    const auto res = trace::intersect_curve(a, b, Mode::Filtered, opt, certify::Detail::Topology);
    ASSERT_EQ(res.status, certify::Status::Certified) << i << " " << res.note;
    ++certified;
    expect_matches_morphology(res, "random pair " + std::to_string(i));
    if (res.branches.empty()) continue;
    ++traced;
    // The scene: the branches' bounding box (the tracer's own is that of its start points).
    trace::Point3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const auto& br : res.branches)
      for (const auto& p : br.points)
        for (size_t k = 0; k < 3; ++k)
          lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    const double scene =
        std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                  (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double worst = 0, worst_mid = 0;
    for (const auto& br : res.branches) {
      const size_t n = br.points.size();
      for (size_t k = 0; k < n; ++k) {
        const auto& p = br.points[k];
        worst = std::max({worst, exact_distance(a, p), exact_distance(b, p)});
        const auto& q = br.points[(k + 1) % n];
        const trace::Point3 mid = {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
        worst_mid = std::max({worst_mid, exact_distance(a, mid), exact_distance(b, mid)});
      }
    }
    EXPECT_LE(worst, 1e-12 * scene) << i;
    EXPECT_LE(worst, 2 * res.max_residual + 1e-15 * scene) << i; // its own measure, ~ this one
    // A chord's midpoint lies within its sag (<= tol times the tracer's scene, at most ~2x
    // this one) of the curve: first order, so within that of each surface.
    EXPECT_LE(worst_mid, 2 * tol * scene) << i;
  }
  EXPECT_GE(traced, 20);
  EXPECT_EQ(certified, 40);
}

// Random unit-size posed pairs (seed 002 5.1.3, as the double_path benchmark draws them): a
// quarter of them count as far from the origin (far_centre: the least-squares centre more than
// 4 sizes out) and are translated by a centre clamped so that both shapes stay lazy (each
// centre minus the translation exact in double; in a coordinate without such a translation,
// none). The posed pair and the same exact surfaces given as rational matrices (translated
// there, when far, by the unclamped centre through the exact congruence) must give the same
// certified counts, every point on both exact surfaces.
TEST(Intersect, PosedPairsOffTheOriginMatchTheirExactMatrices) {
  std::mt19937_64 rng(20261202);
  auto shape = [&] { return random_posed_ellipsoid(rng); };
  int compared = 0, curves = 0;
  for (int i = 0; i < 60; ++i) {
    const core::QuadricMatrix pa(shape()), pb(shape());
    const core::QuadricMatrix ea(pa.matrix()), eb(pb.matrix()); // not lazy: no shape()
    ASSERT_EQ(ea.shape(), nullptr);
    trace::TraceOptions opt;
    opt.tolerance = 2e-4;
    const auto rp = trace::intersect_curve(pa, pb, Mode::Filtered, opt, certify::Detail::Topology);
    const auto re = trace::intersect_curve(ea, eb, Mode::Filtered, opt, certify::Detail::Topology);
    const std::string ctx = "pair " + std::to_string(i);
    ASSERT_EQ(rp.status, certify::Status::Certified) << ctx << " " << rp.note;
    ASSERT_EQ(re.status, certify::Status::Certified) << ctx << " " << re.note;
    expect_matches_morphology(rp, ctx + " posed");
    expect_matches_morphology(re, ctx + " exact");
    EXPECT_EQ(rp.topology.morphology, re.topology.morphology) << ctx;
    EXPECT_EQ(rp.branches.size(), re.branches.size()) << ctx;
    for (const auto& br : rp.branches)
      for (const auto& p : br.points) {
        EXPECT_LE(exact_distance(ea, p), 1e-12) << ctx;
        EXPECT_LE(exact_distance(eb, p), 1e-12) << ctx;
      }
    ++compared;
    curves += rp.branches.empty() ? 0 : 1;
  }
  EXPECT_EQ(compared, 60);
  EXPECT_GE(curves, 20);
}

// Pipes, cones, paraboloids and ellipsoids posed in doubles 1e6 .. 1e9 from the origin (CAD
// coordinates): certified with the counts of the same pair moved back near the origin (centres
// minus the offset, rounded: a generic pair keeps its topology), every point within 1e-9 of the
// box or the doubles' spacing out there of both exact surfaces. (Before, 4 of 36 certified.)
TEST(Intersect, PosedPairsFarFromTheOriginKeepTheirCounts) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::normal_distribution<double> g(0, 1);
  auto posed = [&](core::ShapeType t, std::array<double, 3> radii, std::array<double, 3> c) {
    core::ShapeSpec s;
    s.type = t;
    s.radii = radii;
    s.center = c;
    s.rotated = true;
    s.quaternion = {g(rng), g(rng), g(rng), g(rng)};
    return s;
  };
  using T = core::ShapeType;
  int compared = 0;
  for (const double off : {1e6, 123456789.123, 1e9})
    for (int i = 0; i < 8; ++i) {
      const std::array<double, 3> c{off + u(rng), 0.5 * off + u(rng), 0.5 * off + u(rng)};
      const std::array<double, 3> c2{c[0] + u(rng), c[1] + u(rng), c[2] + u(rng)};
      core::ShapeSpec sa, sb;
      switch (i % 4) {
      case 0:
        sa = posed(T::Cylinder, {1, 1, 1}, c), sb = posed(T::Cylinder, {0.7, 0.7, 1}, c2);
        break;
      case 1:
        sa = posed(T::Cone, {1, 1, 1}, c), sb = posed(T::Cylinder, {0.5, 0.5, 1}, c2);
        break;
      case 2:
        sa = posed(T::Ellipsoid, {1, 0.8, 0.6}, c), sb = posed(T::Cylinder, {0.5, 0.5, 1}, c2);
        break;
      default:
        sa = posed(T::EllipticParaboloid, {1, 0.8, 1}, c);
        sb = posed(T::Ellipsoid, {1, 0.9, 0.7}, c2);
      }
      core::ShapeSpec ha = sa, hb = sb;
      for (core::ShapeSpec* s : {&ha, &hb}) {
        s->center[0] -= off;
        s->center[1] -= 0.5 * off;
        s->center[2] -= 0.5 * off;
      }
      const core::QuadricMatrix a(sa), b(sb);
      const auto far = trace::intersect_curve(a, b, Mode::Filtered, {}, certify::Detail::Topology);
      const auto home = trace::intersect_curve(core::QuadricMatrix(ha), core::QuadricMatrix(hb),
                                               Mode::Filtered, {}, certify::Detail::Topology);
      const std::string ctx = "offset " + std::to_string(off) + " pair " + std::to_string(i);
      ASSERT_EQ(home.status, certify::Status::Certified) << ctx << " " << home.note;
      ASSERT_EQ(far.status, certify::Status::Certified) << ctx << " " << far.note;
      EXPECT_EQ(*far.affine.loops, *home.affine.loops) << ctx;
      EXPECT_EQ(*far.affine.unbounded_branches, *home.affine.unbounded_branches) << ctx;
      EXPECT_EQ(far.branches.size(), home.branches.size()) << ctx;
      // The scene: the box, or (an ellipsoid's bounded curve has none) the points' extent.
      double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      for (const auto& br : far.branches)
        for (const auto& p : br.points)
          for (size_t k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
      const double scene = far.box ? far.box->diagonal()
                           : far.branches.empty()
                               ? 1.0
                               : std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
      for (const auto& br : far.branches)
        for (const auto& p : br.points) {
          const double bound = 1e-9 * scene + 0x1p-52 * std::max({std::fabs(p[0]), std::fabs(p[1]),
                                                                  std::fabs(p[2])});
          EXPECT_LE(exact_distance(a, p), bound) << ctx;
          EXPECT_LE(exact_distance(b, p), bound) << ctx;
        }
      ++compared;
    }
  EXPECT_EQ(compared, 24);
}
