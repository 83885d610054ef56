// A curve whose affine part is isolated points only (certified: no loop, no unbounded branch)
// is drawn as those points, with nothing walked. The walks used to run anyway: seeded near an
// acnode, on the rounded pair, a walk circles a loop of rounding noise and ends off the box's
// faces, and the answer was undecided ("open branches do not end on the box's faces").
//  - Closed form: z = x^2 + y^2 against z = -x^2 - 2 y^2 (Tu 15: their difference 2x^2 + 3y^2
//    is two conjugate planes through the z-axis, which meets both paraboloids at the origin
//    and at (0 : 0 : 1 : 0)): the origin, and a point at infinity listed apart. Posed by the
//    five rational rigid motions, both orders: one isolated point, at the pose's translation.
//  - Regressions, generated (`surfcert generate --case all --count 20`, op intersect), each
//    undecided before: Tu 30 (two points) --seed 50 pair 1 and --seed 51 pair 9, Tu 25 (a point)
//    --seed 50 pair 8 (exact), Tu 7 (acnode) --seed 50 pair 18 (--encoding double). Certified,
//    no branch, each isolated point on both quadrics (exact substitution of its doubles: the
//    values within 1e-12 of the matrices' size).
#include "support/exact_points.hpp"
#include "support/posed_pairs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace surfcert;
using surfcert::testing::five_poses;
using surfcert::testing::from_ints;
using surfcert::testing::posed_pair;
using surfcert::testing::relative_value;

TEST(PointsOnly, ClosedFormParaboloidsTouchingAtAPoint) {
  int certified = 0;
  for (const auto& ps : five_poses())
    for (bool swapped : {false, true}) {
      const std::string ctx = ps.name("-", swapped);
      const auto [a, b] = posed_pair("z - x^2 - y^2 = 0", "z + x^2 + 2*y^2 = 0", ps, swapped);
      const auto r = trace::intersect_curve(a, b, certify::Mode::Filtered, {});
      ASSERT_TRUE(r.affine.certified()) << ctx << ": " << r.affine.reason;
      EXPECT_EQ(*r.affine.loops, 0) << ctx;
      EXPECT_EQ(*r.affine.unbounded_branches, 0) << ctx;
      EXPECT_EQ(*r.affine.isolated_points, 1) << ctx;
      ASSERT_EQ(r.affine.at_infinity_only.size(), 1u) << ctx;
      EXPECT_EQ(r.affine.at_infinity_only[0].kind, "point") << ctx;
      ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
      ++certified;
      EXPECT_TRUE(r.branches.empty()) << ctx;
      ASSERT_EQ(r.isolated_points.size(), 1u) << ctx;
      const auto l = ps.local(r.isolated_points[0]);
      EXPECT_LE(std::hypot(l[0], l[1], l[2]), 1e-9 * (1 + ps.offset())) << ctx;
      ASSERT_TRUE(r.box.has_value()) << ctx;
      for (size_t k = 0; k < 3; ++k) {
        EXPECT_LE(r.box->min[k], r.isolated_points[0][k]) << ctx;
        EXPECT_GE(r.box->max[k], r.isolated_points[0][k]) << ctx;
      }
    }
  EXPECT_EQ(certified, 10);
}

TEST(PointsOnly, GeneratedAcnodesAreNotWalked) {
  struct Case {
    const char* name;
    std::array<std::array<long, 4>, 4> a, b;
    size_t points;
  };
  const std::vector<Case> cases = {
      {"Tu 30, seed 50 pair 1",
       {{{-52, 48, 12, 48}, {48, -24, 8, -56}, {12, 8, -40, -36}, {48, -56, -36, -50}}},
       {{{66, -60, -18, -60}, {-60, 24, -12, 72}, {-18, -12, 48, 48}, {-60, 72, 48, 60}}},
       2},
      {"Tu 25, seed 50 pair 8",
       {{{-28, 18, 23, -13}, {18, 12, -15, -9}, {23, -15, -10, 8}, {-13, -9, 8, 32}}},
       {{{-16, 10, 13, -7}, {10, 4, -7, -5}, {13, -7, -7, 3}, {-7, -5, 3, 15}}},
       1},
      {"Tu 30, seed 51 pair 9",
       {{{-1, 6, -4, 1}, {6, 8, 4, -2}, {-4, 4, 4, -2}, {1, -2, -2, 5}}},
       {{{10, -24, 10, -7}, {-24, -8, -28, 26}, {10, -28, -4, 2}, {-7, 26, 2, -5}}},
       2},
      {"Tu 7, seed 50 pair 18 (double)",
       {{{-17, 17, 6, 9}, {17, -7, 22, -1}, {6, 22, 34, -4}, {9, -1, -4, 16}}},
       {{{12, -16, -9, -9}, {-16, 2, -22, 0}, {-9, -22, -36, 0}, {-9, 0, 0, -16}}},
       1},
  };
  for (const Case& c : cases)
    for (bool swapped : {false, true}) {
      const std::string ctx = std::string(c.name) + (swapped ? " swapped" : "");
      auto a = from_ints(c.a), b = from_ints(c.b);
      if (swapped) std::swap(a, b);
      const auto r = trace::intersect_curve(a, b, certify::Mode::Filtered, {});
      ASSERT_TRUE(r.affine.certified()) << ctx << ": " << r.affine.reason;
      EXPECT_EQ(*r.affine.loops, 0) << ctx;
      EXPECT_EQ(*r.affine.unbounded_branches, 0) << ctx;
      EXPECT_EQ(*r.affine.isolated_points, static_cast<int>(c.points)) << ctx;
      ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
      EXPECT_TRUE(r.branches.empty()) << ctx;
      ASSERT_EQ(r.isolated_points.size(), c.points) << ctx;
      for (const auto& p : r.isolated_points) {
        EXPECT_LE(relative_value(a, p), 1e-12) << ctx;
        EXPECT_LE(relative_value(b, p), 1e-12) << ctx;
      }
    }
}
