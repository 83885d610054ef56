// Conic components whose planes come from the exact singular member (issue 15's degenerate
// inputs). The planes of a rank-2 member were the eigenvectors of the member rounded to
// doubles: two planes 2.8e-10 apart (a unit sphere in a cylinder of radius 1 - 1e-20) came
// out as noise (no conic: undecided; rotated: tilted by 4.5e-9), and the circle of radius
// 1e-20 where a sphere through a cone's apex meets the cone came out at radius 3.8e-11
// (certified: 1.9e-11 off the cone, within the picture check's 1e-9 of the curve's size, but
// far from the 1e-12 the issue asks). Now each plane coefficient is rounded once from exact
// rationals and one square root, and the conic is read from the better conditioned of the
// two quadrics in its plane (the cone's, next to its apex).
// Each pair is posed by rational rigid motions, in both orders; the circles are checked in the
// local coordinates R^T (p - t).
#include "support/posed_pairs.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace surfcert;
using certify::Mode;
using core::Rational;
using surfcert::testing::certified_or_undecided;
using surfcert::testing::Pose;
using surfcert::testing::q;

namespace {

struct Gap {
  std::string g;
  double value;
};

const std::vector<Gap>& gaps() {
  static const std::vector<Gap> g = {{"1/10000000000", 1e-10},
                                     {"1/1000000000000000", 1e-15},
                                     {"1/100000000000000000000", 1e-20},
                                     {"1/1152921504606846976", 0x1p-60},
                                     {"1/1267650600228229401496703205376", 0x1p-100}};
  return g;
}

} // namespace

TEST(ExactConicPlanes, SphereInACylinderJustNarrowerThanIt) {
  // x^2 + y^2 + z^2 = 1 and x^2 + y^2 = (1 - g)^2: the circles of radius 1 - g at
  // z = +-z0, z0 = sqrt(2g - g^2) (1.4e-10 at g = 1e-20, 1.3e-15 at 2^-100).
  int certified = 0, tried = 0;
  for (const auto& gap : gaps())
    for (const auto& ps : surfcert::testing::five_poses())
      for (bool swapped : {false, true}) {
        const std::string ctx = ps.name(gap.g, swapped);
        const auto [a, b] = surfcert::testing::posed_pair(
            "x^2 + y^2 + z^2 = 1", "x^2 + y^2 = (1 - (" + gap.g + "))^2", ps, swapped);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        ++tried;
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 2) << ctx;
        // Near the origin the doubles resolve the planes at every gap (z0 >= 1.3e-15); 2^20
        // out (spacing 2.3e-10) from 1e-15 down they may not.
        const bool must = ps.offset() < 10 || gap.value >= 1e-10;
        if (!certified_or_undecided(r, must, ctx)) continue;
        ++certified;
        ASSERT_EQ(r.branches.size(), 2u) << ctx;
        const double z0 = std::sqrt(2 * gap.value - gap.value * gap.value);
        const double slack = 0x1p-48 * (2 + ps.offset());
        int above = 0, below = 0;
        for (const auto& br : r.branches) {
          EXPECT_TRUE(br.closed) << ctx;
          int pos = 0, neg = 0;
          for (const auto& p : br.points) {
            const auto l = ps.local(p);
            EXPECT_NEAR(std::fabs(l[2]), z0, 1e-6 * z0 + slack) << ctx;
            EXPECT_NEAR(std::hypot(l[0], l[1]), 1.0, 1e-9 + slack) << ctx;
            pos += l[2] > 0 ? 1 : 0;
            neg += l[2] < 0 ? 1 : 0;
          }
          EXPECT_TRUE(pos == 0 || neg == 0) << ctx << ": a circle on both sides of z = 0";
          above += pos > 0 ? 1 : 0;
          below += neg > 0 ? 1 : 0;
        }
        EXPECT_EQ(above, 1) << ctx;
        EXPECT_EQ(below, 1) << ctx;
      }
  EXPECT_EQ(tried, 50);
  EXPECT_GE(certified, 42);
}

TEST(ExactConicPlanes, TinyCircleWhereASphereMeetsAConeNextToItsApex) {
  // x^2 + y^2 = z^2 and x^2 + y^2 + z^2 - 2z = c, c = 2g + g^2: 2z^2 - 2z - c = 0, so the
  // circles z = 1 + g (radius 1 + g) and z = -g (radius g, next to the apex). At the origin
  // (identity and rotations) the small one must be drawn at its size, to 1e-6 of it; where
  // the doubles cannot place it (1e-20 at (1/3, 0, -1): spacing 5.6e-17), undecided is allowed.
  int certified = 0, tried = 0;
  for (const auto& gap : gaps())
    for (size_t pi = 0; pi < 4; ++pi)
      for (bool swapped : {false, true}) {
        const Pose& ps = surfcert::testing::five_poses()[pi];
        const std::string ctx = ps.name(gap.g, swapped);
        const std::string g = "(" + gap.g + ")";
        const auto [a, b] = surfcert::testing::posed_pair(
            "x^2 + y^2 = z^2", "x^2 + y^2 + z^2 - 2*z = 2*" + g + " + " + g + "^2", ps, swapped);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        ++tried;
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 2) << ctx;
        const bool must = ps.offset() == 0;
        if (!certified_or_undecided(r, must, ctx)) continue;
        ++certified;
        ASSERT_EQ(r.branches.size(), 2u) << ctx;
        // At the origin each circle to 1e-6 of its own size; moved off it, every point within
        // ~1e-12 of the curve's size (2 + 2g) of its circle, as the issue asks (the small
        // circle's points 1/3 out are corrected on the rounded surfaces: 2e-13).
        auto tol = [&](double z) {
          return ps.offset() == 0 ? 1e-6 * std::fabs(z) : 4e-12 + 0x1p-50 * ps.offset();
        };
        int small = 0;
        for (const auto& br : r.branches) {
          EXPECT_TRUE(br.closed) << ctx;
          const bool tiny = std::fabs(ps.local(br.points[0])[2]) < 0.5;
          small += tiny ? 1 : 0;
          const double z = tiny ? -gap.value : 1 + gap.value;
          for (const auto& p : br.points) {
            const auto l = ps.local(p);
            EXPECT_NEAR(l[2], z, tol(z)) << ctx;
            EXPECT_NEAR(std::hypot(l[0], l[1]), std::fabs(z), tol(z)) << ctx;
          }
        }
        EXPECT_EQ(small, 1) << ctx;
      }
  EXPECT_EQ(tried, 40);
  EXPECT_GE(certified, 20); // every pair at the origin
}
