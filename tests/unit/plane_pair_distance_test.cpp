// Distance to a rational plane pair (plane_pair_distance.hpp) in closed form: an ellipsoid
// between the planes z = +-1 (or x = 3 and y = -5) is at the distance to the nearer plane,
// axis-aligned so the plane distances are exact (d = offset - semi-axis); a symmetric position
// is a tie (value certified, count not proven; a sphere's is proven by its own route, which
// runs first); contact with both parallel planes counts both
// points; a plane cutting the sphere is a continuum. Swapped and translated alike. (These were
// undecided with no bounds: a plane pair is a degenerate quadric the offset system cannot
// solve.)
#include "surfcert/certify/distance/distance.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

using namespace surfcert;
using surfcert::testing::hi;
using surfcert::testing::lo;
using surfcert::testing::q;

namespace {

struct Case {
  const char* pair;
  const char* other;
  double d;
  const char* minimizers;
};

const Case kCases[] = {
    {"z^2 = 1", "x^2 + y^2 + (z - 1/4)^2 = 1/4", 0.25, "1"},
    {"z^2 = 1", "x^2/4 + y^2/9 + (z + 1/8)^2*4 = 1", 0.375, "1"},
    {"(x - 3)*(y + 5) = 0", "x^2 + y^2/4 + z^2/9 = 1", 2, "1"},
    {"(x - 3)*(y + 5) = 0", "x^2 + y^2/4 + z^2/9 = 1/4", 2.5, "1"},
    {"z^2 = 1", "x^2 + y^2 + z^2 = 1", 0, "2"},               // touches both planes
    {"z*(z - 10) = 0", "x^2 + y^2 + z^2 = 1", 0, "infinite"}, // z = 0 cuts it
    {"z^2 = 1", "x^2 + y^2 + z^2 = 1/4", 0.5, "2"}, // midway: the sphere route proves the tie
    {"z^2 = 1", "x^2/4 + y^2/9 + 4*z^2 = 1", 0.5, "undecided"}, // midway: a tie, not proven
};

} // namespace

TEST(PlanePairDistance, TheNearerPlaneInClosedForm) {
  for (const Case& c : kCases)
    for (bool swap : {false, true})
      for (int moved = 0; moved < 2; ++moved) {
        // A rational translation keeps the planes axis-aligned and the values exact.
        const std::string t = moved ? "(x - 7/3)" : "x", u = moved ? "(y + 5/4)" : "y",
                          v = moved ? "(z - 2/7)" : "z";
        auto sub = [&](std::string e) {
          std::string out;
          for (char ch : e)
            out += ch == 'x' ? t : ch == 'y' ? u : ch == 'z' ? v : std::string(1, ch);
          return out;
        };
        const auto p = q(sub(c.pair)), o = q(sub(c.other));
        const auto r = swap ? certify::surface_distance(o, p, 15, false)
                            : certify::surface_distance(p, o, 15, false);
        const std::string tag = std::string(c.pair) + " | " + c.other + (swap ? " swapped" : "") +
                                (moved ? " moved" : "");
        ASSERT_EQ(r.status, certify::Status::Certified) << tag << ": " << r.note;
        EXPECT_LE(lo(r), c.d) << tag;
        EXPECT_GE(hi(r), c.d) << tag;
        EXPECT_LE(hi(r) - lo(r), 1e-14 * (1 + c.d)) << tag;
        EXPECT_EQ(r.minimizers.str(), c.minimizers) << tag << ": " << r.note;
      }
}

TEST(PlanePairDistance, ExactModeAndUnmodelledSolids) {
  const auto p = q("z^2 = 1"), o = q("x^2/4 + y^2/9 + (z + 1/8)^2*4 = 1");
  const auto r = certify::surface_distance(p, o, 30, false, certify::Mode::Exact);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  EXPECT_LE(lo(r), 0.375);
  EXPECT_GE(hi(r), 0.375);
  EXPECT_EQ(r.method, certify::Method::PlanePairMin);
  // A slab is a solid this route does not model: --solid never certifies the surface value.
  const auto s = certify::surface_distance(p, o, 15, true);
  if (s.status == certify::Status::Certified) {
    EXPECT_NE(s.method, certify::Method::PlanePairMin);
  }
}
