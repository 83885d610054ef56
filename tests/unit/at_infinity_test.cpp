// minimum_attained (at_infinity.hpp): the exact test that two unbounded quadrics share no real
// point at infinity, against the geometry of textbook pairs (axis directions), invariance under
// rational rigid motions, and end to end: a paraboloid beside a cone (disjoint: x^2 - x + 10 +
// 2y^2 = 0 has no real solution) is now certified, its lower bound never above the distance of
// sampled surface points, its pairs on both surfaces.
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
      {"x = y^2 + z^2 + 10", "x^2 + y^2 - z^2 = 0", true},     // axis x vs a cone around z
      {"z = x^2 + y^2", "z = x^2 + y^2 - 3", false},           // same axis direction
      {"z = x^2 + y^2", "(x - 5)^2 + y^2 = 1", false},         // cylinder parallel to the axis
      {"z = x^2 + y^2", "(x - 5)^2 + z^2 = 1", true},          // cylinder across
      {"z = x^2", "x = y^2 + z^2", true},                      // x^2 = z: line u_x = 0 vs axis x
      {"z = x^2", "z = x^2 + y^2 + 1", false},                 // both contain direction z
      {"x^2 + y^2 = 1", "y^2 + z^2 = 4", true},                // crossed cylinders
      {"x^2 + y^2 - z^2 = 1", "x^2 + y^2 - z^2 = -1", false}}; // two conics: not decided
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
  EXPECT_LT(best - r.approx, 0.1);
  for (const auto& pr : r.pairs) {
    EXPECT_NEAR(pr[0][1] * pr[0][1] + pr[0][2] * pr[0][2] + 10 - pr[0][0], 0, 1e-9);
    EXPECT_NEAR(pr[1][0] * pr[1][0] + pr[1][1] * pr[1][1] - pr[1][2] * pr[1][2], 0, 1e-9);
  }
}
