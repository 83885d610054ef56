// Certified distance between two ring tori (core circles, torus_pair.hpp), against
// independent routes:
// - coplanar core circles side by side: d = D - R1 - R2 - r1 - r2 in closed form, also after a
//   rational rigid motion of both tori (integer quaternion) and at 100 digits;
// - perpendicular and linked (chain-link) tori, and random pairs: a float search over both
//   circles (dense grid + Newton on the squared distance) - the certified lower bound never
//   exceeds it and the enclosure comes within 1e-9 of it;
// - swapping the tori keeps the enclosure and swaps the points;
// - refusals: coaxial tori (a circle of minimizers) and crossing tubes stay undecided.
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>

using namespace surfcert;
using surfcert::testing::hi;
using surfcert::testing::lo;
using surfcert::testing::overlap;

namespace {

struct T {
  double c[3], a[3], R, r;
  std::string json() const {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  R"({"type":"torus","center":[%.17g,%.17g,%.17g],"axis":[%.17g,%.17g,%.17g],)"
                  R"("major_radius":%.17g,"minor_radius":%.17g})",
                  c[0], c[1], c[2], a[0], a[1], a[2], R, r);
    return buf;
  }
};

core::Surface torus(const T& t) {
  return core::io::read_surface(core::io::parse_json(t.json(), "t"), "t", "$");
}

// A point of circle (c, a, R) at angle s (frame from a x e_k, as doubles).
std::array<double, 3> on(const T& t, double s) {
  double n = std::sqrt(t.a[0] * t.a[0] + t.a[1] * t.a[1] + t.a[2] * t.a[2]);
  double ax[3] = {t.a[0] / n, t.a[1] / n, t.a[2] / n};
  double e[3] = {0, 0, 0};
  e[std::fabs(ax[0]) < 0.5 ? 0 : (std::fabs(ax[1]) < 0.5 ? 1 : 2)] = 1;
  double u[3] = {ax[1] * e[2] - ax[2] * e[1], ax[2] * e[0] - ax[0] * e[2],
                 ax[0] * e[1] - ax[1] * e[0]};
  double un = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (double& x : u)
    x /= un;
  double v[3] = {ax[1] * u[2] - ax[2] * u[1], ax[2] * u[0] - ax[0] * u[2],
                 ax[0] * u[1] - ax[1] * u[0]};
  return {t.c[0] + t.R * (std::cos(s) * u[0] + std::sin(s) * v[0]),
          t.c[1] + t.R * (std::cos(s) * u[1] + std::sin(s) * v[1]),
          t.c[2] + t.R * (std::cos(s) * u[2] + std::sin(s) * v[2])};
}

// Float circle-circle distance: grid, then Newton on the squared distance (finite differences).
double float_circles(const T& a, const T& b) {
  auto D = [&](double s, double t) {
    auto p = on(a, s), q = on(b, t);
    return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
           (p[2] - q[2]) * (p[2] - q[2]);
  };
  double best = 1e300, bs = 0, bt = 0;
  const int n = 400;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double s = 2 * M_PI * i / n, t = 2 * M_PI * j / n, d = D(s, t);
      if (d < best) best = d, bs = s, bt = t;
    }
  for (int it = 0; it < 50; ++it) {
    const double h = 1e-5;
    double gs = (D(bs + h, bt) - D(bs - h, bt)) / (2 * h),
           gt = (D(bs, bt + h) - D(bs, bt - h)) / (2 * h),
           hss = (D(bs + h, bt) - 2 * D(bs, bt) + D(bs - h, bt)) / (h * h),
           htt = (D(bs, bt + h) - 2 * D(bs, bt) + D(bs, bt - h)) / (h * h),
           hst = (D(bs + h, bt + h) - D(bs + h, bt - h) - D(bs - h, bt + h) + D(bs - h, bt - h)) /
                 (4 * h * h);
    double det = hss * htt - hst * hst;
    if (!(std::fabs(det) > 1e-300)) break;
    double ns = bs - (htt * gs - hst * gt) / det, nt = bt - (hss * gt - hst * gs) / det;
    if (D(ns, nt) > D(bs, bt)) break;
    bs = ns, bt = nt;
  }
  return std::sqrt(D(bs, bt));
}

void expect_float_agrees(const T& a, const T& b, const std::string& ctx) {
  auto r = certify::surface_distance(torus(a), torus(b), 15, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << ctx << " " << r.note;
  EXPECT_EQ(r.method, certify::Method::TorusCirclePair) << ctx;
  const double f = float_circles(a, b) - a.r - b.r;
  EXPECT_LE(lo(r), f + 1e-12 * (1 + f)) << ctx; // never above a float pair distance
  EXPECT_NEAR(hi(r), f, 1e-9 * (1 + f)) << ctx;
  EXPECT_LE((hi(r) - lo(r)) / lo(r), 1e-14) << ctx;
}

} // namespace

TEST(TorusPair, CoplanarCirclesClosedForm) {
  // centres 10 apart in the common plane z = 0: d = 10 - 3 - 2 - 1 - 1/2 = 7/2.
  const char* a = R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,)"
                  R"("minor_radius":1})";
  const char* b = R"({"type":"torus","center":[10,0,0],"axis":[0,0,1],"major_radius":2,)"
                  R"("minor_radius":"1/2"})";
  auto sa = core::io::read_surface(core::io::parse_json(a, "a"), "a", "$");
  auto sb = core::io::read_surface(core::io::parse_json(b, "b"), "b", "$");
  for (long digits : {15L, 100L}) {
    auto r = certify::surface_distance(sa, sb, digits, false);
    ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
    surfcert::testing::Bounds ref;
    ref.lower = ref.upper = "3.5";
    EXPECT_TRUE(overlap(r, ref)) << r.lower() << " " << r.upper();
    EXPECT_EQ(r.minimizers, "1");
    ASSERT_EQ(r.pairs.size(), 1u);
    EXPECT_NEAR(r.pairs[0][0][0], 4, 1e-7);
    EXPECT_NEAR(r.pairs[0][1][0], 7.5, 1e-7);
  }
  // The same pair turned by the rotation of the integer quaternion (1, 2, 2, 0) (matrix
  // [[1, 8, 4], [8, 1, -4], [-4, 4, -7]] / 9): centres and
  // axes rotated exactly (entries over 9), d unchanged.
  const char* ra = R"({"type":"torus","center":[0,0,0],"axis":["-4/9","4/9","7/9"],)"
                   R"("major_radius":3,"minor_radius":1})";
  const char* rb = R"({"type":"torus","center":["10/9","80/9","-40/9"],)"
                   R"("axis":["-4/9","4/9","7/9"],"major_radius":2,"minor_radius":"1/2"})";
  auto r = certify::surface_distance(
      core::io::read_surface(core::io::parse_json(ra, "a"), "a", "$"),
      core::io::read_surface(core::io::parse_json(rb, "b"), "b", "$"), 30, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  surfcert::testing::Bounds ref;
  ref.lower = ref.upper = "3.5";
  EXPECT_TRUE(overlap(r, ref)) << r.lower() << " " << r.upper();
}

TEST(TorusPair, PerpendicularLinkedAndRandomAgainstAFloatSearch) {
  expect_float_agrees({{0, 0, 0}, {0, 0, 1}, 3, 0.5}, {{9, 0, 0}, {1, 0, 0}, 2, 0.25}, "perp");
  // chain links: K2 passes through the hole of K1 (disjoint tubes)
  expect_float_agrees({{0, 0, 0}, {0, 0, 1}, 3, 0.5}, {{3.5, 0, 0}, {0, 1, 0}, 3, 0.5}, "linked");
  const unsigned seed = std::getenv("SURFCERT_TEST_SEED")
                            ? static_cast<unsigned>(std::atoi(std::getenv("SURFCERT_TEST_SEED")))
                            : 4242u;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> ax(-9, 9), cen(-40, 40), rad(10, 30);
  int checked = 0;
  for (int i = 0; i < 40 && checked < 6; ++i) {
    T a{{0, 0, 0}, {double(ax(rng)), double(ax(rng)), double(ax(rng))}, rad(rng) / 10.0, 0.25};
    T b{{cen(rng) / 4.0, cen(rng) / 4.0, cen(rng) / 4.0},
        {double(ax(rng)), double(ax(rng)), double(ax(rng))},
        rad(rng) / 10.0,
        0.125};
    if ((a.a[0] == 0 && a.a[1] == 0 && a.a[2] == 0) || (b.a[0] == 0 && b.a[1] == 0 && b.a[2] == 0))
      continue;
    if (float_circles(a, b) < 0.5) continue; // tubes too close to be sure they are disjoint
    expect_float_agrees(a, b, "seed " + std::to_string(seed) + " pair " + std::to_string(i));
    ++checked;
  }
  EXPECT_GE(checked, 4) << "seed " << seed;
}

TEST(TorusPair, SwapKeepsTheEnclosure) {
  T a{{0, 0, 0}, {1, 2, 2}, 3, 0.5}, b{{9, 1, 2}, {2, -1, 0}, 2, 0.5};
  auto r = certify::surface_distance(torus(a), torus(b), 40, false);
  auto s = certify::surface_distance(torus(b), torus(a), 40, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  ASSERT_EQ(s.status, certify::Status::Certified) << s.note;
  EXPECT_TRUE(overlap(r, s)) << r.lower() << " vs " << s.lower();
  ASSERT_FALSE(r.pairs.empty());
  ASSERT_FALSE(s.pairs.empty());
  for (size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(r.pairs[0][0][k], s.pairs[0][1][k], 1e-6);
}

TEST(TorusPair, ContinuaAndCrossingTubesStayUndecided) {
  // coaxial tori one above the other: a circle of minimizers, certified (meridian circles
  // (3, 0) and (2, 5), radii 1/2: sqrt(26) - 1)
  auto c = certify::surface_distance(torus({{0, 0, 0}, {0, 0, 1}, 3, 0.5}),
                                     torus({{0, 0, 5}, {0, 0, 1}, 2, 0.5}), 15, false);
  EXPECT_EQ(c.status, certify::Status::Certified) << c.note;
  EXPECT_EQ(c.minimizers, "infinite");
  EXPECT_NEAR(c.approx(), std::sqrt(26.0) - 1, 1e-15);
  // crossing tubes (radial ranges [2.5, 3.5] and, along the x-axis, [3, 4]): not the circle
  // route's case; the branch and bound on the two quartics proves a common point (2-D
  // Krawczyk), which must lie on both tubes (closed-form distance to each core circle)
  auto x = certify::surface_distance(torus({{0, 0, 0}, {0, 0, 1}, 3, 0.5}),
                                     torus({{5.5, 0, 0}, {0, 0, 1}, 2, 0.5}), 15, false);
  EXPECT_EQ(x.status, certify::Status::Certified) << x.note;
  EXPECT_EQ(x.upper(), "0");
  EXPECT_EQ(x.method, certify::Method::ImplicitBnb);
  ASSERT_FALSE(x.pairs.empty());
  const auto& w = x.pairs[0][0];
  EXPECT_NEAR(std::hypot(std::hypot(w[0], w[1]) - 3, w[2]), 0.5, 1e-9);
  EXPECT_NEAR(std::hypot(std::hypot(w[0] - 5.5, w[1]) - 2, w[2]), 0.5, 1e-9);
  // linked circles each through the other's centre: (3, 0, 0) on K1 is at distance 3 from
  // every point of K2, a continuum of minimizers
  auto l = certify::surface_distance(torus({{0, 0, 0}, {0, 0, 1}, 3, 0.5}),
                                     torus({{3, 0, 0}, {0, 1, 0}, 3, 0.5}), 15, false);
  EXPECT_EQ(l.status, certify::Status::Undecided) << l.lower();
}

TEST(TorusPair, NestedTubes) {
  // A small torus inside the tube of a big one: d = r_out - r_in - max_s dist(K_in(s), K_out),
  // with dist(p, K_out) = sqrt((rho - R)^2 + h^2) in closed form; the maximum over s by a fine
  // float sampling plus golden refinement (independent of the Arb branch and bound).
  const T out{{0, 0, 0}, {0, 0, 1}, 10, 3}, in{{10, 0, 0.5}, {1, 1, 1}, 1, 0.5};
  auto dist_out = [&](const std::array<double, 3>& p) {
    return std::hypot(std::hypot(p[0], p[1]) - 10, p[2]);
  };
  double best = -1, bs = 0;
  for (int i = 0; i < 20000; ++i) {
    const double s = 2 * M_PI * i / 20000, v = dist_out(on(in, s));
    if (v > best) best = v, bs = s;
  }
  for (double h = 1e-3; h > 1e-13; h *= 0.5)
    for (double ds : {-h, h})
      if (dist_out(on(in, bs + ds)) > best) best = dist_out(on(in, bs + ds)), bs += ds;
  for (bool swap : {false, true}) {
    const auto r = swap ? certify::surface_distance(torus(in), torus(out), 15, false)
                        : certify::surface_distance(torus(out), torus(in), 15, false);
    ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
    EXPECT_NEAR(r.approx(), 3 - 0.5 - best, 1e-12);
    EXPECT_NE(r.note.find("nested tubes"), std::string::npos) << r.note;
    ASSERT_EQ(r.pairs.size(), 1u);
    const auto& inner_pt = r.pairs[0][swap ? 0 : 1];
    const auto& outer_pt = r.pairs[0][swap ? 1 : 0];
    EXPECT_NEAR(dist_out(outer_pt), 3, 1e-9); // on the outer torus
    EXPECT_NEAR(
        std::hypot(inner_pt[0] - outer_pt[0], inner_pt[1] - outer_pt[1], inner_pt[2] - outer_pt[2]),
        r.approx(), 1e-9);
  }
  // Solid distance: one tube contains the other.
  const auto s = certify::surface_distance(torus(out), torus(in), 15, true);
  EXPECT_EQ(s.upper(), "0") << s.note;
}

namespace {

// Points of a torus on an angle grid (doubles).
std::vector<std::array<double, 3>> torus_points(const T& t, int n, int m) {
  std::vector<std::array<double, 3>> out;
  const double an = std::sqrt(t.a[0] * t.a[0] + t.a[1] * t.a[1] + t.a[2] * t.a[2]);
  for (int i = 0; i < n; ++i) {
    const auto k = on(t, 2 * M_PI * i / n);
    double w[3] = {k[0] - t.c[0], k[1] - t.c[1], k[2] - t.c[2]};
    const double wn = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int j = 0; j < m; ++j) {
      const double ph = 2 * M_PI * j / m;
      std::array<double, 3> p{};
      for (size_t l = 0; l < 3; ++l)
        p[l] = k[l] + t.r * (std::cos(ph) * w[l] / wn + std::sin(ph) * t.a[l] / an);
      out.push_back(p);
    }
  }
  return out;
}

} // namespace

TEST(TorusPair, CoaxialToriAgainstSampling) {
  // Apart, nested (a thin tube inside a thick one, shifted), and meeting; the sampled distance
  // of both surfaces never goes below the certified lower bound and comes close to it.
  const T a{{0, 0, 0}, {1, 2, 2}, 3, 0.5};
  const T cases[] = {{{0.5, 1, 1}, {-2, -4, -4}, 2, 0.25},      // apart (h = 1.5 along the axis)
                     {{0.01, 0.02, 0.02}, {1, 2, 2}, 3.1, 0.2}, // inside the tube
                     {{0.1, 0.2, 0.2}, {1, 2, 2}, 3, 0.5}};     // meeting
  const auto pa = torus_points(a, 120, 40);
  for (const T& b : cases) {
    const auto r = certify::surface_distance(torus(a), torus(b), 15, false);
    ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
    EXPECT_EQ(r.minimizers, "infinite");
    EXPECT_EQ(r.method, certify::Method::TorusCoaxialClosedForm);
    const auto pb = torus_points(b, 120, 40);
    double best = 1e300;
    for (const auto& p : pa)
      for (const auto& q : pb)
        best = std::min(best, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
    EXPECT_GE(best, lo(r) - 1e-12) << r.note;
    EXPECT_LT(best - r.approx(), 0.15) << r.note;
  }
}

TEST(TorusPair, TwoMinimaInOneArcAreNotCountedAsOne) {
  // Core circles K1 (centre (2, 0, 1), radius 1, plane z = 1) and K2 (centre 0, radius R2 =
  // 3 - e, plane z = 0): over K1, dist(K1(s), K2) = sqrt((rho(s) - R2)^2 + 1) with rho(s) in
  // [1, 3], so for e > 0 the minimum 1 is attained exactly twice (rho = R2, s = +-s*, mirror
  // images in y = 0), d = 1 - 1/4 - 1/4 = 1/2, and the bump between them at s = 0 is only
  // e^2 / 2: for e = 1e-10 and below the two minimizers lie in one arc of survivors. Before
  // the fix the route counted that arc as one minimizer ("1", certified).
  auto ta = core::io::read_surface(
      core::io::parse_json(
          R"({"type":"torus","center":[2,0,1],"axis":[0,0,1],"major_radius":1,"minor_radius":"1/4"})",
          "a"),
      "a", "$");
  const std::string two100 = "1267650600228229401496703205376"; // 2^100
  for (const std::string& R2 :
       {std::string("2999/1000"), std::string("29999999999/10000000000"),
        std::string("299999999999999999999/100000000000000000000"),
        std::string("3802951800684688204490109616127/") + two100}) { // 3 - 2^-100
    auto tb = core::io::read_surface(
        core::io::parse_json(R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":")" +
                                 R2 + R"(","minor_radius":"1/4"})",
                             "b"),
        "b", "$");
    for (bool swap : {false, true}) {
      const auto r = swap ? certify::surface_distance(tb, ta, 15, false)
                          : certify::surface_distance(ta, tb, 15, false);
      ASSERT_EQ(r.status, certify::Status::Certified) << R2 << ": " << r.note;
      surfcert::testing::Bounds ref;
      ref.lower = ref.upper = "0.5";
      EXPECT_TRUE(overlap(r, ref)) << R2 << ": " << r.lower() << " " << r.upper();
      // "2" (proven) or "undecided"; never a certified single minimizer.
      EXPECT_NE(r.minimizers, "1") << R2 << " swap " << swap << ": " << r.note;
    }
  }
}

TEST(TorusPair, StrictlyConvexMinimaKeepTheirCount) {
  // The one-arc check must not lose well separated single minimizers: side by side (the
  // closed form of CoplanarCirclesClosedForm), and a small torus in a big one's tube.
  const auto r = certify::surface_distance(torus({{0, 0, 0}, {0, 0, 1}, 3, 1}),
                                           torus({{10, 0, 0}, {0, 0, 1}, 2, 0.5}), 15, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  EXPECT_EQ(r.minimizers, "1") << r.note;
  const auto n = certify::surface_distance(torus({{0, 0, 0}, {0, 0, 1}, 10, 3}),
                                           torus({{10, 0, 0.5}, {1, 1, 1}, 1, 0.5}), 15, false);
  ASSERT_EQ(n.status, certify::Status::Certified) << n.note;
  EXPECT_EQ(n.minimizers, "1") << n.note;
}
