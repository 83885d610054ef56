// A walk that dies next to a cusp is not a piece of the curve. generate --case 9 --count 20
// --seed 32, pair 18 (a cuspidal loop, its cusp at (-3, 4, -3); exact integer matrices): one of
// the float start points lies 6e-6 from the cusp; the walk from it died both ways after 8
// points (the rounded pair's gradients are noise there), and the loop through the cusp was
// traced from another start. The 8-point arc beside it ended off the box's faces: undecided.
// Now a walk that ends off the faces at both ends and lies wholly on another traced piece is
// dropped (march). Asserted, in both orders: certified, one closed branch, every point on both
// quadrics (exact substitution of its doubles), passing the cusp within 1e-6 of the curve's
// size, and nothing else drawn.
#include "support/exact_points.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

using namespace surfcert;
using surfcert::testing::from_ints;
using surfcert::testing::relative_value;

TEST(CuspWalk, DeadArcBesideTheCuspIsDropped) {
  const auto a0 = from_ints({{{-8, 4, 32, 40}, {4, 0, 8, 52}, {32, 8, -16, 48}, {40, 52, 48, 40}}});
  const auto b0 = from_ints(
      {{{-6, -10, -14, -20}, {-10, -14, -14, -16}, {-14, -14, -10, -16}, {-20, -16, -16, -44}}});
  const trace::Point3 cusp{-3, 4, -3};
  for (bool swapped : {false, true}) {
    const std::string ctx = swapped ? "swapped" : "as generated";
    const auto& a = swapped ? b0 : a0;
    const auto& b = swapped ? a0 : b0;
    const auto r = trace::intersect_curve(a, b, certify::Mode::Filtered, {});
    ASSERT_NE(r.topology.morphology, nullptr) << ctx;
    EXPECT_EQ(std::string(r.topology.morphology->id), "cuspidal_loop") << ctx;
    ASSERT_TRUE(r.affine.certified()) << ctx;
    EXPECT_EQ(*r.affine.loops, 1) << ctx;
    EXPECT_EQ(*r.affine.unbounded_branches, 0) << ctx;
    ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
    ASSERT_EQ(r.branches.size(), 1u) << ctx;
    const auto& br = r.branches[0];
    EXPECT_TRUE(br.closed) << ctx;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double to_cusp = HUGE_VAL;
    for (const auto& p : br.points) {
      EXPECT_LE(relative_value(a, p), 1e-12) << ctx;
      EXPECT_LE(relative_value(b, p), 1e-12) << ctx;
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
      to_cusp = std::min(to_cusp, std::hypot(p[0] - cusp[0], p[1] - cusp[1], p[2] - cusp[2]));
    }
    const double size = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    EXPECT_LE(to_cusp, 1e-6 * size) << ctx;
  }
}
