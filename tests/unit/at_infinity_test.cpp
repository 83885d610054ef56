// minimum_attained (at_infinity.hpp): the exact test that two unbounded quadrics share no real
// point at infinity, against the geometry of textbook pairs (axis directions), invariance under
// rational rigid motions, and end to end: a paraboloid beside a cone (disjoint: x^2 - x + 10 +
// 2y^2 = 0 has no real solution) and a two-sheeted hyperboloid beside a cone (two proper conics
// at infinity, disjoint) are certified, their lower bounds never above the distance of
// sampled surface points, their pairs on both surfaces.
#include "surfcert/certify/distance/at_infinity.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace surfcert;
using core::Rational;
using surfcert::testing::motion;
using surfcert::testing::q;

TEST(AtInfinity, TextbookPairs) {
  const std::tuple<const char*, const char*, bool> table[] = {
      {"x = y^2 + z^2 + 10", "x^2 + y^2 - z^2 = 0", true},    // axis x vs a cone around z
      {"z = x^2 + y^2", "z = x^2 + y^2 - 3", false},          // same axis direction
      {"z = x^2 + y^2", "(x - 5)^2 + y^2 = 1", false},        // cylinder parallel to the axis
      {"z = x^2 + y^2", "(x - 5)^2 + z^2 = 1", true},         // cylinder across
      {"z = x^2", "x = y^2 + z^2", true},                     // x^2 = z: line u_x = 0 vs axis x
      {"z = x^2", "z = x^2 + y^2 + 1", false},                // both contain direction z
      {"x^2 + y^2 = 1", "y^2 + z^2 = 4", true},               // crossed cylinders
      {"x^2 + y^2 - z^2 = 1", "x^2 + y^2 - z^2 = -1", false}, // one conic at infinity
      // Two proper conics / a line pair (chart + exact solution cover): x^2 + y^2 = z^2 and
      // y^2 + z^2 = x^2 share (1 : 0 : +-1); a narrow cone about z and one about x share
      // nothing (z^2 = 100 (x^2 + y^2), x^2 = 100 (y^2 + z^2) force x = y = z = 0); the lines
      // x = +-y against y^2 + z^2 = x^2 / 100 neither.
      {"x^2 + y^2 - z^2 = -1", "y^2 + z^2 - x^2 = 0", false},
      {"x^2 + y^2 - z^2/100 = -1", "y^2 + z^2 - x^2/100 = 0", true},
      {"x^2 - y^2 = 1", "y^2 + z^2 - x^2/100 = 0", true}};
  const auto m = motion(2, 1, -1, 3, {Rational(1, 3), Rational(4), Rational(-2, 7)});
  for (const auto& [a, b, expect] : table) {
    EXPECT_EQ(certify::minimum_attained(q(a), q(b)), expect) << a << " | " << b;
    EXPECT_EQ(certify::minimum_attained(q(b), q(a)), expect) << b << " | " << a;
    EXPECT_EQ(certify::minimum_attained(q(a).congruent(m), q(b).congruent(m)), expect) << a;
  }
}

TEST(AtInfinity, ParaboloidBesideACone) {
  const auto A = q("x = y^2 + z^2 + 10"), B = q("x^2 + y^2 - z^2 = 0");
  const auto r = certify::surface_distance(A, B, 20, false, certify::Mode::Exact);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  const double lo = surfcert::testing::lo(r);
  // Sampled points: paraboloid (y^2 + z^2 + 10, y, z), cone (rho cos t, rho sin t, +-rho).
  double best = 1e300;
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) {
      const double y = i * 0.05, z = j * 0.05, x = y * y + z * z + 10;
      for (int k = 0; k < 200; ++k)
        for (int sg : {-1, 1}) {
          const double rho = k * 0.05, t = 0;
          const double cx = rho * std::cos(t), cy = rho * std::sin(t), cz = sg * rho;
          best = std::min(best, std::hypot(x - cx, y - cy, z - cz));
        }
    }
  EXPECT_GE(best, lo - 1e-12);
  EXPECT_LT(best - r.approx(), 0.1);
  for (const auto& pr : r.pairs) {
    EXPECT_NEAR(pr[0][1] * pr[0][1] + pr[0][2] * pr[0][2] + 10 - pr[0][0], 0, 1e-9);
    EXPECT_NEAR(pr[1][0] * pr[1][0] + pr[1][1] * pr[1][1] - pr[1][2] * pr[1][2], 0, 1e-9);
  }
}

TEST(AtInfinity, HyperboloidBesideACone) {
  // A two-sheeted hyperboloid about z against a cone about x: their conics at infinity are
  // disjoint (the table above), so the minimum over the critical pairs is the distance; both
  // modes agree and the pairs lie on both surfaces.
  const auto A = q("x^2 + y^2 - z^2/100 = -1"), B = q("y^2 + (z - 3)^2 - (x - 4)^2/100 = 0");
  const auto r = certify::surface_distance(A, B, 20, false, certify::Mode::Exact);
  const auto f = certify::surface_distance(A, B, 20, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  ASSERT_EQ(f.status, certify::Status::Certified) << f.note;
  EXPECT_TRUE(surfcert::testing::overlap(r, f)) << r.lower() << " " << f.lower();
  ASSERT_FALSE(r.pairs.empty());
  for (const auto& pr : r.pairs) {
    const auto& p = pr[0];
    const auto& c = pr[1];
    EXPECT_NEAR(p[0] * p[0] + p[1] * p[1] - p[2] * p[2] / 100 + 1, 0, 1e-8);
    EXPECT_NEAR(c[1] * c[1] + (c[2] - 3) * (c[2] - 3) - (c[0] - 4) * (c[0] - 4) / 100, 0, 1e-8);
    EXPECT_NEAR(std::hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]), r.approx(), 1e-8);
  }
  // Sampled points of the upper and lower sheets never come closer than the lower bound.
  double best = 1e300;
  for (int i = -30; i <= 30; ++i)
    for (int j = -30; j <= 30; ++j) {
      const double x = i * 0.2, y = j * 0.2;
      for (int sg : {-1, 1}) {
        const double z = sg * 10 * std::sqrt(1 + x * x + y * y);
        // distance to the cone, bounded above by the distance to sampled cone points
        for (int k = -40; k <= 40; ++k)
          for (int t = 0; t < 24; ++t) {
            const double u = k * 1.0, rho = std::fabs(u) / 10, th = t * M_PI / 12;
            best = std::min(best, std::hypot(x - (4 + u), y - rho * std::cos(th),
                                             z - (3 + rho * std::sin(th))));
          }
      }
    }
  EXPECT_GE(best, surfcert::testing::lo(r) - 1e-12);
  EXPECT_LT(best - r.approx(), 1.0) << best << " vs " << r.approx(); // the samples come near
}
