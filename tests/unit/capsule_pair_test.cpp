// Two capsules in closed form (capsule_pair.hpp), against independent routes:
// - axis-aligned configurations whose distance is read off by hand (perpendicular: 3/2;
//   parallel overlapping: 7/2 with a continuum of minimizers; parallel end to end: 1);
// - random capsules: a dense float sampling of both segments never beats the certified lower
//   bound and comes within 1e-3 of it (grid step); swapping keeps the enclosure;
// - 100 digits nest inside 15; crossing capsules and curved canals are not answered here.
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

core::Surface surf(const std::string& j) {
  return core::io::read_surface(core::io::parse_json(j, "t"), "t", "$");
}

std::string capsule(const std::array<int, 3>& a, const std::array<int, 3>& b, int r_num,
                    int r_den) {
  char buf[300];
  std::snprintf(buf, sizeof buf,
                R"({"type":"capsule","from":[%d,%d,%d],"to":[%d,%d,%d],"radius":"%d/%d"})", a[0],
                a[1], a[2], b[0], b[1], b[2], r_num, r_den);
  return buf;
}

surfcert::testing::Bounds exact_value(const char* v) {
  surfcert::testing::Bounds r;
  r.lower = r.upper = v;
  return r;
}

} // namespace

TEST(CapsulePair, HandComputedConfigurations) {
  const std::string c1 = capsule({0, 0, 0}, {4, 0, 0}, 1, 1);
  auto perp =
      certify::surface_distance(surf(c1), surf(capsule({1, 3, 0}, {1, 5, 1}, 1, 2)), 30, false);
  ASSERT_EQ(perp.status, certify::Status::Certified) << perp.note;
  EXPECT_TRUE(overlap(perp, exact_value("1.5"))) << perp.lower(); // 3 - 1 - 1/2
  EXPECT_EQ(perp.minimizers, "1");
  EXPECT_EQ(perp.method, certify::Method::CapsuleClosedForm);
  auto par =
      certify::surface_distance(surf(c1), surf(capsule({-2, 5, 0}, {2, 5, 0}, 1, 2)), 15, false);
  ASSERT_EQ(par.status, certify::Status::Certified);
  EXPECT_TRUE(overlap(par, exact_value("3.5")));
  EXPECT_EQ(par.minimizers, "infinite");
  auto end =
      certify::surface_distance(surf(c1), surf(capsule({7, 0, 0}, {9, 0, 0}, 1, 1)), 15, false);
  ASSERT_EQ(end.status, certify::Status::Certified);
  EXPECT_TRUE(overlap(end, exact_value("1")));
  EXPECT_EQ(end.minimizers, "1");
  ASSERT_EQ(end.pairs.size(), 1u);
  EXPECT_NEAR(end.pairs[0][0][0], 5, 1e-12);
  EXPECT_NEAR(end.pairs[0][1][0], 6, 1e-12);
}

TEST(CapsulePair, RandomAgainstAFloatSampling) {
  const unsigned seed = std::getenv("SURFCERT_TEST_SEED")
                            ? static_cast<unsigned>(std::atoi(std::getenv("SURFCERT_TEST_SEED")))
                            : 99u;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> co(-20, 20), rad(1, 8);
  int checked = 0;
  for (int i = 0; i < 60 && checked < 10; ++i) {
    std::array<int, 3> a{co(rng), co(rng), co(rng)}, b{co(rng), co(rng), co(rng)},
        c{co(rng), co(rng), co(rng)}, d{co(rng), co(rng), co(rng)};
    const int ra = rad(rng), rb = rad(rng);
    auto r = certify::surface_distance(surf(capsule(a, b, ra, 4)), surf(capsule(c, d, rb, 4)), 100,
                                       false);
    if (r.status != certify::Status::Certified) continue; // solids meet: not this route
    double f = 1e300;
    const int n = 2000;
    for (int s = 0; s <= n; ++s)
      for (int t = 0; t <= n; t += 1) {
        double ss = double(s) / n, tt = double(t) / n, d2 = 0;
        for (size_t k = 0; k < 3; ++k) {
          double x = a[k] + ss * (b[k] - a[k]) - c[k] - tt * (d[k] - c[k]);
          d2 += x * x;
        }
        f = std::min(f, d2);
      }
    f = std::sqrt(f) - (ra + rb) / 4.0;
    const std::string ctx = "seed " + std::to_string(seed) + " case " + std::to_string(i);
    EXPECT_LE(lo(r), f + 1e-12) << ctx;
    EXPECT_NEAR(hi(r), f, 1e-3 * (1 + f)) << ctx; // the grid step bounds the float error
    auto s = certify::surface_distance(surf(capsule(c, d, rb, 4)), surf(capsule(a, b, ra, 4)), 15,
                                       false);
    EXPECT_TRUE(overlap(r, s)) << ctx;
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

TEST(CapsulePair, CrossingAndCurvedCanalsAreNotAnsweredHere) {
  auto x = certify::surface_distance(surf(capsule({0, 0, 0}, {4, 0, 0}, 1, 1)),
                                     surf(capsule({2, -3, 0}, {2, 3, 0}, 1, 1)), 15, false);
  EXPECT_NE(x.method, certify::Method::CapsuleClosedForm);
  EXPECT_NE(x.status, certify::Status::Certified);
  auto c = certify::surface_distance(
      surf(capsule({0, 0, 0}, {4, 0, 0}, 1, 1)),
      surf(R"({"type":"canal","spine":[["10","1","0"],["0","0","1"],["0","0","0"]],)"
           R"("radius":["1/2"],"interval":[0,1]})"),
      15, false);
  EXPECT_NE(c.method, certify::Method::CapsuleClosedForm);
}
