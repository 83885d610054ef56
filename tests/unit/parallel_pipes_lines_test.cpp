// Two parallel unit pipes overlapping by g (issue 15's degenerate inputs): x^2 + y^2 = 1 and
// (x - 2 + g)^2 + y^2 = 1 meet in the two lines x = 1 - g/2, y = +-y0, y0 = sqrt(g - g^2/4)
// (y0 ~ 1e-10 at g = 1e-20, ~9e-16 at g = 2^-100). Their four crossings with the automatic
// box's faces lie 2 y0 apart in pairs, and the traced ends (the lines' exact points rounded)
// were matched with a tolerance of 1e-7 box diagonals: two crossings within it made every
// such pair undecided from g = 1e-15 down (176 answers of an audit of near-degenerate pairs).
// Now each crossing takes its nearest end when the next nearest is 8 times farther; every
// line must still lie on its side of y = 0 at the distance y0, end on two distinct crossings,
// and the four crossings must be used once each.
// Each pair is posed by rational rigid motions, in both orders; the lines are checked in the
// local coordinates R^T (p - t).
#include "support/posed_pairs.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace surfcert;
using certify::Mode;
using core::Rational;
using surfcert::testing::certified_or_undecided;
using surfcert::testing::Pose;
using surfcert::testing::q;

TEST(ParallelPipes, TwoLinesCloseTogetherAreCertifiedOnTheirSides) {
  const std::vector<Pose>& poses = surfcert::testing::five_poses();
  struct Gap {
    std::string g;
    double y0;             // sqrt(g - g^2/4)
    bool must_certify;     // at every pose
    bool must_near_origin; // at the poses near the origin (y0 above the doubles' spacing there)
  };
  const std::vector<Gap> gaps = {
      {"1/10000000000", 1e-5, true, true},
      {"1/1000000000000000", 3.1622776601683794e-8, true, true},
      {"1/100000000000000000000", 1e-10, false, true}, // 2^20 out the spacing is 2.3e-10
      {"1/1152921504606846976", 9.313225746154785e-10, false, false},              // 2^-60
      {"1/1267650600228229401496703205376", 8.881784197001252e-16, false, false}}; // 2^-100
  int certified = 0, tried = 0;
  for (const auto& gap : gaps)
    for (const auto& ps : poses)
      for (bool swapped : {false, true}) {
        const std::string ctx = ps.name(gap.g, swapped);
        const auto [a, b] = surfcert::testing::posed_pair(
            "x^2 + y^2 = 1", "(x - 2 + (" + gap.g + "))^2 + y^2 = 1", ps, swapped);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        ++tried;
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 0) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, 2) << ctx;
        EXPECT_EQ(*r.affine.lines, 2) << ctx;
        const bool near_origin = ps.offset() < 10;
        if (!certified_or_undecided(r, gap.must_certify || (near_origin && gap.must_near_origin),
                                    ctx))
          continue;
        ++certified;
        ASSERT_EQ(r.branches.size(), 2u) << ctx;
        ASSERT_TRUE(r.box_exits && r.box_exits->certified) << ctx;
        ASSERT_EQ(r.box_exits->points.size(), 4u) << ctx;
        // Local coordinates to a few ulps of |p|: the slack is far below y0 wherever the
        // lines are certified (the doubles cannot place them closer).
        const double slack = 0x1p-48 * (2 + ps.offset());
        std::set<int> used;
        int above = 0, below = 0;
        for (const auto& br : r.branches) {
          EXPECT_FALSE(br.closed) << ctx;
          EXPECT_EQ(br.kind, "line") << ctx;
          ASSERT_EQ(br.exits.size(), 2u) << ctx;
          EXPECT_NE(br.exits[0], br.exits[1]) << ctx;
          used.insert(br.exits.begin(), br.exits.end());
          int pos = 0, neg = 0;
          for (const auto& p : br.points) {
            const auto l = ps.local(p);
            EXPECT_NEAR(l[0], 1.0, 1e-9 + slack) << ctx; // x = 1 - g/2, g <= 1e-10
            EXPECT_NEAR(std::fabs(l[1]), gap.y0, 1e-3 * gap.y0 + slack) << ctx;
            pos += l[1] > 0 ? 1 : 0;
            neg += l[1] < 0 ? 1 : 0;
          }
          EXPECT_TRUE(pos == 0 || neg == 0) << ctx << ": a line on both sides of y = 0";
          above += pos > 0 ? 1 : 0;
          below += neg > 0 ? 1 : 0;
        }
        EXPECT_EQ(used.size(), 4u) << ctx << ": every crossing with the box ends one line";
        EXPECT_EQ(above, 1) << ctx;
        EXPECT_EQ(below, 1) << ctx;
      }
  EXPECT_EQ(tried, 50);
  EXPECT_GE(certified, 26); // 1e-10, 1e-15 everywhere; 1e-20 near the origin
}
