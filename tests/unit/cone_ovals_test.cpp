// Two cones crossing in two ovals (Tu case 1) with four points at infinity: the points alone
// allow "two unbounded ovals" (0 loops) and "one loop plus one oval through all four"; the
// cone's generators decide (certify/cone_ovals.hpp). Expected: both ovals reach infinity
// (0 loops, 4 unbounded branches), found independently by sampling the curve in floats along
// the generators of one cone, connecting the roots by continuity and reading the smallest |w|
// of each component on the unit sphere of R^4 (both ~1e-4 at 3000 samples: each component
// reaches w = 0; a loop would stay away from it). Pairs 16 and 37 of
// bench/natural_box_pairs.py --seed 1. Checked swapped, under a rational rigid motion, each
// cone as the one swept, and against the traced pieces and exact box exits.
#include "support/distance_checks.hpp"

#include "surfcert/certify/cone_ovals.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

using namespace surfcert;
using certify::Mode;
using core::Mat4;
using core::Rational;
using surfcert::testing::motion;

namespace {

Mat4 mat(const std::vector<std::vector<const char*>>& rows) {
  Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = *Rational::from_string(rows[i][j]);
  return m;
}

std::vector<std::pair<Mat4, Mat4>> pairs() {
  return {
      {mat({{"1", "0", "0", "2"},
            {"0", "1", "0", "0"},
            {"0", "0", "-4", "2"},
            {"2", "0", "2", "3"}}),
       mat({{"49/81", "64/81", "-8/81", "5/18"},
            {"64/81", "-47/81", "16/81", "-37/18"},
            {"-8/81", "16/81", "79/81", "4/9"},
            {"5/18", "-37/18", "4/9", "-7/2"}})},
      {mat({{"1", "0", "0", "0"},
            {"0", "1", "0", "-3/2"},
            {"0", "0", "-25/4", "25/2"},
            {"0", "-3/2", "25/2", "-91/4"}}),
       mat({{"1", "0", "0", "3/2"},
            {"0", "-1/4", "0", "-1/8"},
            {"0", "0", "1", "3/2"},
            {"3/2", "-1/8", "3/2", "71/16"}})},
  };
}

} // namespace

TEST(ConeOvals, BothOvalsReachInfinity) {
  const Mat4 m = motion(1, 2, 2, -1, {Rational(3, 2), Rational(-1), Rational(5, 4)});
  int idx = 0;
  for (const auto& [a0, b0] : pairs()) {
    ++idx;
    for (bool moved : {false, true})
      for (bool swapped : {false, true}) {
        const std::string ctx =
            "pair " + std::to_string(idx) + (moved ? " moved" : "") + (swapped ? " swapped" : "");
        core::QuadricMatrix a(a0), b(b0);
        if (moved) a = a.congruent(m), b = b.congruent(m);
        if (swapped) std::swap(a, b);
        for (bool first : {true, false}) {
          const auto lu = first ? certify::cone_oval_counts(a.matrix(), b.matrix(), 2, 4)
                                : certify::cone_oval_counts(b.matrix(), a.matrix(), 2, 4);
          ASSERT_TRUE(lu.has_value()) << ctx;
          EXPECT_EQ(*lu, (std::pair<int, int>{0, 4})) << ctx;
        }
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        ASSERT_EQ(r.topology.tu_case, 1) << ctx;
        ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
        EXPECT_EQ(*r.affine.loops, 0) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, 4) << ctx;
        int closed = 0;
        for (const auto& br : r.branches)
          closed += br.closed ? 1 : 0;
        EXPECT_EQ(closed, 0) << ctx;
        ASSERT_TRUE(r.box_exits && r.box_exits->certified) << ctx;
        EXPECT_EQ(r.box_exits->points.size(), 2 * r.branches.size()) << ctx;
      }
  }
}
