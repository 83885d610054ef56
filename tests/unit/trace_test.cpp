// surfcert::trace (extreme_points + march) against independent routes:
//  * Viviani's curve against its closed-form parameterisation (both Hausdorff directions);
//  * readable fixtures of cases 1, 3, 5, 6, 9 and seed 002 Example 4.1: number and kinds of
//    branches equal the certified morphology (classify_qsic, exact), every point on both
//    surfaces (residual evaluated exactly, in rationals, from the exact matrices);
//  * small features built from touching / nodal / nearly tangent pairs with a closed-form size
//    (ovals of diameter 2^-10 and 2^-20; two loops 2^-20 apart side by side, in parallel and
//    nested; one loop with a 2^-20 neck), the size measured on the traced polylines;
//  * the start points are the extreme points of every loop in one direction, and include the
//    singular points (march finds them without being told);
//  * invariance under an exact rational rigid motion (also of the 2^-20 features).
#include "surfcert/certify/morphology.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/trace/curve.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace surfcert;
using certify::Mode;
using core::Mat4;
using core::QuadricMatrix;
using core::Rational;
using trace::Branch;
using trace::Point3;

namespace {

QuadricMatrix q(const std::string& s) {
  return core::io::quadric_from_equation(s, {"trace_test", 1, 1, ""});
}

struct Traced {
  certify::QsicResult cert;
  std::vector<Point3> starts;
  std::vector<Point3> singular;
  std::vector<Branch> branches;
};

Traced run(const QuadricMatrix& a, const QuadricMatrix& b, double tol = 2e-4) {
  Traced t;
  t.cert = certify::classify_qsic(a, b, Mode::Exact);
  certify::complete_report_data(t.cert, a, b);
  for (const auto& s : t.cert.special_points)
    if (!s.at_infinity) t.singular.push_back(s.approx);
  const trace::QuadricPair pair(a, b);
  t.starts = trace::extreme_points(a, b);
  trace::TraceOptions opt;
  opt.tolerance = tol;
  t.branches = trace::march(pair, t.starts, t.singular, opt);
  return t;
}

double dist(const Point3& a, const Point3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

double seg_dist(const Point3& x, const Point3& a, const Point3& b) {
  double ab[3], ax[3], l2 = 0, t = 0;
  for (size_t i = 0; i < 3; ++i) {
    ab[i] = b[i] - a[i];
    ax[i] = x[i] - a[i];
    l2 += ab[i] * ab[i];
    t += ax[i] * ab[i];
  }
  t = l2 > 0 ? std::clamp(t / l2, 0.0, 1.0) : 0.0;
  return dist(x, {a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]});
}

// Distance from x to a polyline (closed: last point joined to the first).
double poly_dist(const Point3& x, const std::vector<Point3>& pts, bool closed) {
  double d = pts.empty() ? INFINITY : dist(x, pts[0]);
  const size_t n = pts.size();
  for (size_t i = 0; i + 1 < n + (closed ? 1 : 0); ++i)
    d = std::min(d, seg_dist(x, pts[i], pts[(i + 1) % n]));
  return d;
}

// |X^T Q X| / max|Q| with X = (p, 1), evaluated exactly from the exact matrix (independent of
// QuadricPair).
double exact_residual(const QuadricMatrix& m, const Point3& p) {
  std::array<Rational, 4> x = {Rational::exact_from_double(p[0]), Rational::exact_from_double(p[1]),
                               Rational::exact_from_double(p[2]), Rational(1)};
  Rational s, mx;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      s += x[i] * m.matrix()[i][j] * x[j];
      mx = std::max(mx, core::abs(m.matrix()[i][j]));
    }
  return std::abs((s / mx).to_double_approx());
}

void expect_on_both(const QuadricMatrix& a, const QuadricMatrix& b, const Traced& t) {
  double worst = 0;
  for (const auto& br : t.branches)
    for (const auto& p : br.points) {
      const double s = 1 + p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
      worst = std::max({worst, exact_residual(a, p) / s, exact_residual(b, p) / s});
    }
  EXPECT_LE(worst, 1e-12);
}

std::vector<std::string> kinds(const Traced& t) {
  std::vector<std::string> k;
  for (const auto& b : t.branches)
    k.push_back(b.kind);
  std::sort(k.begin(), k.end());
  return k;
}

// Branch kinds the certified morphology implies (ellipsoid cases: every curve component is
// a closed quartic branch; a figure eight in case 5, a cuspidal loop in case 9).
std::vector<std::string> expected_kinds(const certify::QsicResult& r) {
  std::string kind = r.tu_case == 5 ? "figure_eight" : r.tu_case == 9 ? "loop_with_cusp" : "loop";
  return std::vector<std::string>(static_cast<size_t>(r.morphology->loops), kind);
}

void expect_matches_certified(const QuadricMatrix& a, const QuadricMatrix& b, const Traced& t,
                              int expected_case) {
  ASSERT_EQ(t.cert.status, certify::Status::Certified);
  ASSERT_EQ(t.cert.tu_case, expected_case);
  ASSERT_NE(t.cert.morphology, nullptr);
  EXPECT_EQ(kinds(t), expected_kinds(t.cert));
  for (const auto& br : t.branches) {
    EXPECT_TRUE(br.closed) << br.kind;
    EXPECT_GE(br.points.size(), 8u);
  }
  expect_on_both(a, b, t);
}

// Largest distance between two points of a branch.
double diameter(const Branch& b) {
  double d = 0;
  for (size_t i = 0; i < b.points.size(); ++i)
    for (size_t j = i + 1; j < b.points.size(); ++j)
      d = std::max(d, dist(b.points[i], b.points[j]));
  return d;
}

// Smallest distance from the vertices of one branch to the polyline of the other (through
// the segments next to the nearest vertex: enough when the steps are small against the
// curvature, as they are here).
double gap_one_way(const Branch& a, const Branch& b) {
  const auto& q = b.points;
  const size_t n = q.size();
  double d = INFINITY;
  for (const auto& p : a.points) {
    size_t best = 0;
    double bd = INFINITY;
    for (size_t j = 0; j < n; ++j) {
      const double dx = p[0] - q[j][0], dy = p[1] - q[j][1], dz = p[2] - q[j][2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < bd) {
        bd = d2;
        best = j;
      }
    }
    double e = std::sqrt(bd);
    if (n > 1) {
      e = std::min(e, seg_dist(p, q[best], q[(best + 1) % n]));
      e = std::min(e, seg_dist(p, q[(best + n - 1) % n], q[best]));
    }
    d = std::min(d, e);
  }
  return d;
}

double gap(const Branch& a, const Branch& b) {
  return std::min(gap_one_way(a, b), gap_one_way(b, a));
}

size_t count_near(const Branch& b, const Point3& p, double eps) {
  size_t n = 0;
  for (const auto& x : b.points)
    if (dist(x, p) <= eps) ++n;
  return n;
}

} // namespace

TEST(Trace, QuadricPairNormalisesAndProjects) {
  auto a = q("x^2 + y^2 + z^2 = 4"), b = q("(x - 1)^2 + y^2 = 1");
  trace::QuadricPair p(a, b);
  double ma = 0;
  for (const auto& row : p.a)
    for (double v : row)
      ma = std::max(ma, std::abs(v));
  // Scaled by a power of two (rounding nothing): diag(1, 1, 1, -4) / 8.
  EXPECT_EQ(ma, 0.5);
  EXPECT_EQ(p.f({2, 0, 0}), 0.0);
  EXPECT_EQ(p.f({0, 0, 0}), -0.5);
  EXPECT_EQ(p.a[0][0], 0.125);
  // Exact coefficients: only the evaluation perturbs f; a third is rounded.
  EXPECT_LT(p.noise_unit, 0x1p-58);
  EXPECT_GE(trace::QuadricPair(q("x^2 + y^2 + z^2 = 1/3"), b).noise_unit, 0x1p-53);
  // The edge of the doubles: 2^53 + 1 needs 54 bits, 2^53 and 2^-100 do not.
  EXPECT_GE(trace::QuadricPair(q("x^2 + y^2 + z^2 = 9007199254740993"), b).noise_unit, 0x1p-53);
  EXPECT_LT(trace::QuadricPair(q("x^2 + y^2 + z^2 = 9007199254740992"), b).noise_unit, 0x1p-58);
  EXPECT_LT(
      trace::QuadricPair(q("x^2 + y^2 + z^2 = 1/1267650600228229401496703205376"), b).noise_unit,
      0x1p-58);
  // A matrix of doubles that is not symmetric: its symmetric part (1 + 2^-52) / 2 ... needs
  // 54 bits, carried exactly as hi + lo.
  core::DoubleMat4 d{};
  d[0][0] = d[1][1] = d[2][2] = 1, d[3][3] = -1;
  d[0][1] = 1, d[1][0] = 1 + 0x1p-52;
  const trace::QuadricPair s(core::QuadricMatrix::from_double_matrix(d), b);
  EXPECT_TRUE(s.split);
  EXPECT_LT(s.noise_unit, 0x1p-58);
  EXPECT_EQ(static_cast<long double>(s.a[0][1]) + s.a_lo[0][1],
            (2 + 0x1p-52L) / 2 / 2); // scaled by 2^-1 (largest entry ~1)
  EXPECT_NE(s.a_lo[0][1], 0.0);
  Point3 x{1.2, 0.9, 1.1};
  ASSERT_TRUE(trace::project_onto_curve(p, x));
  // On the sphere of radius 2 and the cylinder: checked without QuadricPair.
  EXPECT_NEAR(x[0] * x[0] + x[1] * x[1] + x[2] * x[2], 4.0, 1e-13);
  EXPECT_NEAR((x[0] - 1) * (x[0] - 1) + x[1] * x[1], 1.0, 1e-13);
  // Minimum norm: the correction is short (the start was close to the curve).
  EXPECT_LT(dist(x, {1.2, 0.9, 1.1}), 0.3);
  // No real point nearby: disjoint spheres.
  trace::QuadricPair far(q("x^2 + y^2 + z^2 = 1"), q("(x - 5)^2 + y^2 + z^2 = 1"));
  Point3 y{2.5, 0.1, 0};
  EXPECT_FALSE(trace::project_onto_curve(far, y));
}

TEST(Trace, VivianiFigureEightAgainstClosedForm) {
  auto a = q("x^2 + y^2 + z^2 = 1"), b = q("(x - 1/2)^2 + y^2 = 1/4");
  const double tol = 2e-4;
  Traced t = run(a, b, tol);
  ASSERT_EQ(t.branches.size(), 1u);
  const Branch& br = t.branches[0];
  EXPECT_EQ(br.kind, "figure_eight");
  EXPECT_TRUE(br.closed);
  EXPECT_EQ(count_near(br, {1, 0, 0}, 1e-12), 2u); // through the crunode twice
  // Dense closed-form sampling: (x, y, z) = ((1 + cos s)/2, sin s / 2, sin(s/2)), s in [0, 4pi).
  const int n = 40000;
  std::vector<Point3> ref;
  for (int i = 0; i < n; ++i) {
    const double s = 4 * M_PI * i / n;
    ref.push_back({(1 + std::cos(s)) / 2, std::sin(s) / 2, std::sin(s / 2)});
  }
  double worst_pt = 0;
  for (const auto& p : br.points)
    worst_pt = std::max(worst_pt, poly_dist(p, ref, true));
  EXPECT_LE(worst_pt, 1e-6); // the traced points are on the curve, not just near it
  double worst_ref = 0;
  for (const auto& r : ref)
    worst_ref = std::max(worst_ref, poly_dist(r, br.points, true));
  // The tolerance is relative to the scene size; the curve's bounding box diagonal bounds it.
  EXPECT_LE(worst_ref, tol * std::sqrt(1.0 + 1.0 + 4.0));
  EXPECT_GT(worst_ref, 0.0);
  expect_on_both(a, b, t);
}

TEST(Trace, FixtureCase1TwoLoops) {
  auto a = q("4x^2 + y^2/9 + z^2 = 1"), b = q("4x^2 + (y - 1)^2 + z^2/9 = 1");
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 1);
  ASSERT_EQ(t.branches.size(), 2u);
  EXPECT_GT(gap(t.branches[0], t.branches[1]), 1e-2);
}

TEST(Trace, FixtureCase3OneLoop) {
  auto a = q("4x^2 + y^2/4 + 4z^2/9 = 1"), b = q("(x - 2)^2/4 + (y - 1/2)^2 + z^2 = 1");
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 3);
}

TEST(Trace, FixtureCase5FigureEight) {
  auto a = q("x^2 + y^2 + 4z^2/9 = 1"), b = q("x^2/4 + (y - 1)^2/4 + z^2 = 1");
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 5);
  ASSERT_EQ(t.branches.size(), 1u);
  EXPECT_EQ(count_near(t.branches[0], {0, -1, 0}, 1e-12), 2u);
}

TEST(Trace, FixtureCase6LoopAndAcnode) {
  auto a = q("x^2/4 + y^2 + z^2 = 1"), b = q("(x - 1)^2 + y^2 + z^2/4 = 1");
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 6);
  ASSERT_EQ(t.branches.size(), 1u);
  // The acnode (2, 0, 0) is not on the loop.
  EXPECT_GT(poly_dist({2, 0, 0}, t.branches[0].points, true), 1e-2);
}

TEST(Trace, FixtureCase9CuspidalLoop) {
  auto a = q("x^2 + y^2 + (z - 1)^2 = 1"), b = q("2x^2 + y^2 + z^2 - y z - 2z = 0");
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 9);
  ASSERT_EQ(t.branches.size(), 1u);
  EXPECT_EQ(count_near(t.branches[0], {0, 0, 0}, 1e-12), 1u);
}

TEST(Trace, Seed002Example41TwoLoops) {
  auto a = q("x^2 + y^2/4 + z^2 = 1"), b = q("x^2 - 2x + 9y^2 + 9z^2/4 = 8");
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 1);
  ASSERT_EQ(t.branches.size(), 2u);
  // The paper's start points (-0.54, 0.77, 0.75) and (-0.62, -0.77, 0.69) are on different
  // loops (2 decimals: within 0.02 of the curve).
  const Point3 p1{-0.54, 0.77, 0.75}, p2{-0.62, -0.77, 0.69};
  auto which = [&](const Point3& p) {
    return poly_dist(p, t.branches[0].points, true) < poly_dist(p, t.branches[1].points, true) ? 0
                                                                                               : 1;
  };
  EXPECT_LT(std::min(poly_dist(p1, t.branches[0].points, true),
                     poly_dist(p1, t.branches[1].points, true)),
            0.02);
  EXPECT_NE(which(p1), which(p2));
}

// Gradient of X^T M X at (p, 1), from the exact matrix (not through QuadricPair).
Point3 gradient(const QuadricMatrix& m, const Point3& p) {
  const double x[4] = {p[0], p[1], p[2], 1};
  Point3 g{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 4; ++j)
      g[i] += 2 * m.matrix()[i][j].to_double_approx() * x[j];
  return g;
}

Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Point3 unit(const Point3& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

// The start points are the extreme points of every loop in one direction d: at the smooth
// ones the curve's tangent is orthogonal to d (d is recovered from the starts themselves),
// and on every traced loop the vertices where d.x is smallest and largest are next to a start.
void expect_starts_are_extremes(const std::string& sa, const std::string& sb) {
  SCOPED_TRACE(sa + " & " + sb);
  auto a = q(sa), b = q(sb);
  Traced t = run(a, b);
  ASSERT_FALSE(t.branches.empty());
  std::vector<Point3> tangents;
  for (const auto& p : t.starts) {
    const Point3 c = cross(gradient(a, p), gradient(b, p));
    const double n = std::sqrt(dot(c, c));
    const double ga = std::sqrt(dot(gradient(a, p), gradient(a, p)));
    const double gb = std::sqrt(dot(gradient(b, p), gradient(b, p)));
    if (n > 1e-6 * ga * gb) tangents.push_back(unit(c)); // skip singular points of the curve
  }
  ASSERT_GE(tangents.size(), 2u);
  Point3 d{};
  double best = 0;
  for (size_t i = 0; i < tangents.size(); ++i)
    for (size_t j = i + 1; j < tangents.size(); ++j) {
      const Point3 c = cross(tangents[i], tangents[j]);
      if (dot(c, c) > best) {
        best = dot(c, c);
        d = unit(c);
      }
    }
  ASSERT_GT(best, 1e-4);
  for (const auto& tg : tangents)
    EXPECT_LT(std::abs(dot(tg, d)), 1e-8);
  for (const auto& br : t.branches) {
    size_t lo = 0, hi = 0;
    double step = 0;
    for (size_t i = 0; i < br.points.size(); ++i) {
      if (dot(br.points[i], d) < dot(br.points[lo], d)) lo = i;
      if (dot(br.points[i], d) > dot(br.points[hi], d)) hi = i;
      step = std::max(step, dist(br.points[i], br.points[(i + 1) % br.points.size()]));
    }
    for (size_t k : {lo, hi}) {
      double near = INFINITY;
      for (const auto& s : t.starts)
        near = std::min(near, dist(s, br.points[k]));
      EXPECT_LE(near, step);
    }
  }
}

// x^2/4 + y^2 + z^2 = 1 and (x - (3 - d))^2 + y^2 + z^2/4 = 1 touch at (2, 0, 0) for d = 0;
// for small d > 0 they meet in an oval (3/2) y^2 + (9/8) z^2 ~= d around it, of diameter
// 2 sqrt(8d/9). d = 9/32 D^2 gives diameter D.
void small_oval(int log2_diameter) {
  const Rational d = Rational(9, 32) * core::pow2(-2 * log2_diameter);
  const std::string c = (Rational(3) - d).to_string();
  auto a = q("x^2/4 + y^2 + z^2 = 1"), b = q("(x - " + c + ")^2 + y^2 + z^2/4 = 1");
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 3);
  ASSERT_EQ(t.branches.size(), 1u);
  const double expect = std::ldexp(1.0, -log2_diameter);
  EXPECT_NEAR(diameter(t.branches[0]), expect, 0.02 * expect);
  EXPECT_GE(t.branches[0].points.size(), 16u);
}

TEST(Trace, StartPointsAreExtremesOfEveryLoop) {
  expect_starts_are_extremes("4x^2 + y^2/9 + z^2 = 1", "4x^2 + (y - 1)^2 + z^2/9 = 1");
  expect_starts_are_extremes("x^2 + y^2/4 + z^2 = 1", "x^2 - 2x + 9y^2 + 9z^2/4 = 8");
  expect_starts_are_extremes("x^2 + y^2 + 4z^2/9 = 1", "x^2/4 + (y - 1)^2/4 + z^2 = 1");
  expect_starts_are_extremes("x^2 + y^2 + (z - 1)^2 = 1", "2x^2 + y^2 + z^2 - y z - 2z = 0");
}

// extreme_points also returns the singular points of the curve (they are critical for every
// direction), so march finds and passes them without being told.
TEST(Trace, SingularPointsFoundWithoutBeingPassed) {
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"x^2 + y^2 + z^2 = 1", "(x - 1/2)^2 + y^2 = 1/4"},
      {"x^2/4 + y^2 + z^2 = 1", "(x - 1)^2 + y^2 + z^2/4 = 1"},
      {"x^2 + y^2 + (z - 1)^2 = 1", "2x^2 + y^2 + z^2 - y z - 2z = 0"}};
  for (const auto& [sa, sb] : pairs) {
    SCOPED_TRACE(sa + " & " + sb);
    auto a = q(sa), b = q(sb);
    Traced t = run(a, b);
    const trace::QuadricPair pair(a, b);
    auto alone = trace::march(pair, t.starts, {}, trace::TraceOptions{});
    ASSERT_EQ(alone.size(), t.branches.size());
    EXPECT_EQ(kinds(Traced{t.cert, {}, {}, alone}), expected_kinds(t.cert));
  }
}

TEST(Trace, SmallOvalDiameter2pow10) {
  small_oval(10);
}
TEST(Trace, SmallOvalDiameter2pow20) {
  small_oval(20);
}

// The case 5 pair with the second ellipsoid grown or shrunk by e: near the crunode (0,-1,0)
// the curve becomes -x^2/4 + 7 z^2/9 = e on the tangent plane y = -1. For e = 7/36 * 2^-40
// the branches z >= 3 sqrt(e/7), z <= -3 sqrt(e/7) are 6 sqrt(e/7) = 2^-20 apart and the
// figure eight splits into two loops (case 1); for e = -2^-44 the branches are x >= 2 sqrt|e|,
// x <= -2 sqrt|e| (4 sqrt|e| = 2^-20 apart) and the lobes join into one loop with a narrow
// neck (case 3).
TEST(Trace, TwoLoops2pow20Apart) {
  const Rational e = Rational(7, 36) * core::pow2(-40);
  auto a = q("x^2 + y^2 + 4z^2/9 = 1");
  auto b = q("x^2/4 + (y - 1)^2/4 + z^2 = " + (Rational(1) + e).to_string());
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 1);
  ASSERT_EQ(t.branches.size(), 2u);
  const double expect = std::ldexp(1.0, -20);
  const double g = gap(t.branches[0], t.branches[1]);
  EXPECT_GT(g, 0.9 * expect);
  EXPECT_LT(g, 1.2 * expect);
}

// The unit sphere and x^2/4 + y^2 + (1 + 2^-20) z^2 = 1 - 3 * 2^-44: the curve lies on the
// sphere and on 3/4 x^2 = 2^-20 z^2 + 3 * 2^-44, two sheets x = +-sqrt(4/3 (3 * 2^-44 +
// 2^-20 z^2)): two loops, nearly parallel great circles of low curvature, 2^-20 apart at z = 0
// over a long stretch (not a neck: the gap grows only like z * 2^-9).
TEST(Trace, TwoParallelLoops2pow20Apart) {
  auto a = q("x^2 + y^2 + z^2 = 1");
  auto b = q("x^2/4 + y^2 + " + (Rational(1) + core::pow2(-20)).to_string() +
             " z^2 = " + (Rational(1) - Rational(3) * core::pow2(-44)).to_string());
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 1);
  ASSERT_EQ(t.branches.size(), 2u);
  for (const auto& br : t.branches) { // each loop stays on its own sheet
    size_t pos = 0;
    for (const auto& p : br.points)
      if (p[0] > 0) ++pos;
    EXPECT_TRUE(pos == 0 || pos == br.points.size()) << pos << " of " << br.points.size();
  }
  const double expect = std::ldexp(1.0, -20);
  const double g = gap(t.branches[0], t.branches[1]);
  EXPECT_GT(g, 0.9 * expect);
  EXPECT_LT(g, 1.2 * expect);
}

// Nested rather than side by side: the unit sphere and the paraboloid
// (1 + 2^-40) x^2 + y^2 + (1 + 2^-20) z = 1 + (1/2)(1/2 + 2^-20) meet where
// (z - 1/2)(z - 1/2 - 2^-20) = 2^-40 x^2, two latitude-like loops z <= 1/2 and
// z >= 1/2 + 2^-20, 2^-20 apart at x = 0, both bending the same way (the predictor of the
// upper one errs towards the lower one).
TEST(Trace, NestedLoops2pow20Apart) {
  auto a = q("x^2 + y^2 + z^2 = 1");
  const Rational c2 = Rational(1, 2) + core::pow2(-20);
  auto b = q((Rational(1) + core::pow2(-40)).to_string() + " x^2 + y^2 + " +
             (Rational(1, 2) + c2).to_string() +
             " z = " + (Rational(1) + Rational(1, 2) * c2).to_string());
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 1);
  ASSERT_EQ(t.branches.size(), 2u);
  const double mid = 0.5 + std::ldexp(1.0, -21);
  for (const auto& br : t.branches) { // each loop stays on its own side of z = 1/2 + 2^-21
    size_t up = 0;
    for (const auto& p : br.points)
      if (p[2] > mid) ++up;
    EXPECT_TRUE(up == 0 || up == br.points.size()) << up << " of " << br.points.size();
  }
  const double expect = std::ldexp(1.0, -20);
  const double g = gap(t.branches[0], t.branches[1]);
  EXPECT_GT(g, 0.9 * expect);
  EXPECT_LT(g, 1.2 * expect);
}

TEST(Trace, OneLoopWithNeck2pow20) {
  const Rational e = -core::pow2(-44);
  auto a = q("x^2 + y^2 + 4z^2/9 = 1");
  auto b = q("x^2/4 + (y - 1)^2/4 + z^2 = " + (Rational(1) + e).to_string());
  Traced t = run(a, b);
  expect_matches_certified(a, b, t, 3);
  ASSERT_EQ(t.branches.size(), 1u);
  // Both sides of the neck, x = +-2 sqrt|e| = +-2^-21 on y = -1, z = 0, are on the one loop.
  const double s = std::ldexp(1.0, -21);
  EXPECT_LT(poly_dist({s, -1, 0}, t.branches[0].points, true), 0.05 * s);
  EXPECT_LT(poly_dist({-s, -1, 0}, t.branches[0].points, true), 0.05 * s);
}

// X = P X' with P = [[R^T, -R^T t], [0, 1]]: the moved quadric of the point set R x + t.
Mat4 rigid_motion_inverse(long qa, long qb, long qc, long qd, const std::array<Rational, 3>& tr,
                          std::array<std::array<double, 3>, 3>& rot) {
  const long n = qa * qa + qb * qb + qc * qc + qd * qd;
  const long m[3][3] = {
      {qa * qa + qb * qb - qc * qc - qd * qd, 2 * (qb * qc - qa * qd), 2 * (qb * qd + qa * qc)},
      {2 * (qb * qc + qa * qd), qa * qa - qb * qb + qc * qc - qd * qd, 2 * (qc * qd - qa * qb)},
      {2 * (qb * qd - qa * qc), 2 * (qc * qd + qa * qb), qa * qa - qb * qb - qc * qc + qd * qd}};
  Mat4 p = core::identity4();
  for (size_t i = 0; i < 3; ++i) {
    Rational s;
    for (size_t j = 0; j < 3; ++j) {
      Rational rji(m[j][i], static_cast<unsigned long>(n)); // (R^T)_{ij}
      p[i][j] = rji;
      s += rji * tr[j];
      rot[i][j] = static_cast<double>(m[i][j]) / static_cast<double>(n);
    }
    p[i][3] = -s;
  }
  return p;
}

TEST(Trace, InvariantUnderRationalRigidMotion) {
  const std::array<Rational, 3> tr = {Rational(1, 3), Rational(-2, 7), Rational(5, 4)};
  std::array<std::array<double, 3>, 3> rot{};
  const Mat4 p = rigid_motion_inverse(4, 1, -2, 3, tr, rot);
  const double td[3] = {1.0 / 3, -2.0 / 7, 5.0 / 4};
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"x^2 + y^2 + z^2 = 1", "(x - 1/2)^2 + y^2 = 1/4"},               // Viviani
      {"4x^2 + y^2/9 + z^2 = 1", "4x^2 + (y - 1)^2 + z^2/9 = 1"},       // case 1
      {"x^2/4 + y^2 + z^2 = 1", "(x - 1)^2 + y^2 + z^2/4 = 1"},         // case 6
      {"x^2 + y^2 + (z - 1)^2 = 1", "2x^2 + y^2 + z^2 - y z - 2z = 0"}, // case 9
      // the oval of diameter 2^-20 and the two loops 2^-20 apart (see below)
      {"x^2/4 + y^2 + z^2 = 1", "(x - " +
                                    (Rational(3) - Rational(9, 32) * core::pow2(-40)).to_string() +
                                    ")^2 + y^2 + z^2/4 = 1"},
      {"x^2 + y^2 + 4z^2/9 = 1",
       "x^2/4 + (y - 1)^2/4 + z^2 = " +
           (Rational(1) + Rational(7, 36) * core::pow2(-40)).to_string()}};
  for (const auto& [sa, sb] : pairs) {
    SCOPED_TRACE(sa + " & " + sb);
    auto a = q(sa), b = q(sb);
    auto ma = a.congruent(p), mb = b.congruent(p);
    Traced t0 = run(a, b), t1 = run(ma, mb);
    EXPECT_EQ(t1.cert.tu_case, t0.cert.tu_case);
    EXPECT_EQ(kinds(t1), kinds(t0));
    ASSERT_FALSE(t1.branches.empty());
    expect_on_both(ma, mb, t1);
    // The moved curve, moved back, lies on the original polylines (within the tolerance,
    // relative to the size of the curve).
    Point3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const auto& b0 : t0.branches)
      for (const auto& x : b0.points)
        for (size_t i = 0; i < 3; ++i) {
          lo[i] = std::min(lo[i], x[i]);
          hi[i] = std::max(hi[i], x[i]);
        }
    const double size = dist(lo, hi);
    double worst = 0;
    for (const auto& br : t1.branches)
      for (const auto& x : br.points) {
        Point3 y{};
        for (size_t i = 0; i < 3; ++i)
          for (size_t j = 0; j < 3; ++j)
            y[i] += rot[j][i] * (x[j] - td[j]);
        double d = INFINITY;
        for (const auto& b0 : t0.branches)
          d = std::min(d, poly_dist(y, b0.points, b0.closed));
        worst = std::max(worst, d);
      }
    // For the 2^-20 features the bound is looser: QuadricPair rounds the moved coefficients
    // (entries up to ~|t|^2) to doubles, which moves a curve on nearly tangent surfaces
    // sideways by ~1e-16 |t|^2 / sin(angle) ~ 1e-9, about 1e-3 of its size.
    EXPECT_LE(worst, (size > 1e-3 ? 2e-4 : 3e-3) * size);
  }
}

TEST(Trace, MaxPointsStopsTheWalk) {
  auto a = q("4x^2 + y^2/4 + 4z^2/9 = 1"), b = q("(x - 2)^2/4 + (y - 1/2)^2 + z^2 = 1");
  const trace::QuadricPair pair(a, b);
  trace::TraceOptions opt;
  opt.max_points_per_branch = 20;
  auto br = trace::march(pair, trace::extreme_points(a, b), {}, opt);
  ASSERT_FALSE(br.empty());
  for (const auto& x : br) {
    EXPECT_LE(x.points.size(), 20u);
    EXPECT_FALSE(x.closed);
  }
}

// A sphere poking into a cylinder by e (touching it at the origin for e = 0): one loop of
// diameter ~2 sqrt(2 e) around the origin, between surfaces at an angle ~sqrt(2 e). Below
// e ~ 1e-15 Newton between such nearly tangent surfaces does not converge from longer steps, and
// once the step floor fell to 2^-40 |p| a walk crawled on at ~1e-14 per step: 290,000 points
// and 9 s for e = 1e-16. A walk whose steps stay far below their target ends: bounded point
// counts, and every point near the loop (each closed branch within 4 sqrt(e) of the origin).
TEST(Trace, NearTangentTinyLoopDoesNotCrawl) {
  for (const Rational& e : {Rational(1, 10000000000000000), Rational(1, 1000000000000000000),
                            core::pow2(-60), core::pow2(-20)}) {
    SCOPED_TRACE("e = " + e.to_string());
    auto a = q("(x + 1)^2 + y^2 = 1");
    auto b = q("(x - 1 + " + e.to_string() + ")^2 + y^2 + z^2 = 1");
    Traced t = run(a, b);
    const double reach = 4 * std::sqrt(e.to_double_approx());
    for (const auto& br : t.branches) {
      EXPECT_LE(br.points.size(), 20000u);
      if (!br.closed) continue;
      for (const auto& p : br.points)
        EXPECT_LE(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), reach);
    }
    if (e == core::pow2(-20)) { // resolvable: the loop itself
      ASSERT_EQ(t.branches.size(), 1u);
      EXPECT_TRUE(t.branches[0].closed);
    }
  }
}
