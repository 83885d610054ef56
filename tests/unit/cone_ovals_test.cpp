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
#include "support/fixtures.hpp"

#include "surfcert/certify/cone_ovals.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

using namespace surfcert;
using certify::Mode;
using core::Mat4;
using core::Rational;
using surfcert::fixtures::mat4_from_strings;
using surfcert::testing::motion;

namespace {

std::vector<std::pair<Mat4, Mat4>> pairs() {
  return {
      {mat4_from_strings({{"1", "0", "0", "2"},
                          {"0", "1", "0", "0"},
                          {"0", "0", "-4", "2"},
                          {"2", "0", "2", "3"}}),
       mat4_from_strings({{"49/81", "64/81", "-8/81", "5/18"},
                          {"64/81", "-47/81", "16/81", "-37/18"},
                          {"-8/81", "16/81", "79/81", "4/9"},
                          {"5/18", "-37/18", "4/9", "-7/2"}})},
      {mat4_from_strings({{"1", "0", "0", "0"},
                          {"0", "1", "0", "-3/2"},
                          {"0", "0", "-25/4", "25/2"},
                          {"0", "-3/2", "25/2", "-91/4"}}),
       mat4_from_strings({{"1", "0", "0", "3/2"},
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

// One loop and one oval through two points at infinity (1 loop, 2 unbounded branches): pair
// 139 of natural_box_pairs.py --seed 6, the cone (x + 1/2)^2 + (y - 3/2)^2 = 4 (z - 3/2)^2
// against a posed cone with apex (3/2, 2, 0). Ground truth, independent (floats, offline, in
// the manner of the header above): along b's generators v + s d(theta) (200000 samples of
// theta, d from b's eigenvectors), disc = b(v, d)^2 - b(v) b(d) > 0 everywhere (min 1.71), so
// the two roots are two ovals; the normalized s2 of the '+' root changes sign twice (it
// passes through infinity at the two real points at infinity), the '-' root's |s2| stays
// >= 0.0045 (a loop). This fails on readings that let an oval reach infinity without a root of
// c on it (e.g. both ovals counted through infinity whenever disc > 0 everywhere), which the
// two-unbounded-ovals pairs above cannot tell apart.
TEST(ConeOvals, OneLoopAndOneUnboundedOval) {
  const Mat4 a0 = mat4_from_strings({{"1", "0", "0", "1/2"},
                                     {"0", "1", "0", "-3/2"},
                                     {"0", "0", "-4", "6"},
                                     {"1/2", "-3/2", "6", "-13/2"}});
  const Mat4 b0 = mat4_from_strings({{"7/36", "-29/18", "-29/18", "211/72"},
                                     {"-29/18", "-20/9", "-29/9", "247/36"},
                                     {"-29/18", "-29/9", "-20/9", "319/36"},
                                     {"211/72", "247/36", "319/36", "-2609/144"}});
  const Mat4 m = motion(2, -1, 1, 1, {Rational(-1, 2), Rational(2), Rational(1, 4)});
  for (bool moved : {false, true})
    for (bool swapped : {false, true}) {
      const std::string ctx = std::string(moved ? "moved" : "") + (swapped ? " swapped" : "");
      core::QuadricMatrix a(a0), b(b0);
      if (moved) a = a.congruent(m), b = b.congruent(m);
      if (swapped) std::swap(a, b);
      for (bool first : {true, false}) {
        const auto lu = first ? certify::cone_oval_counts(a.matrix(), b.matrix(), 2, 2)
                              : certify::cone_oval_counts(b.matrix(), a.matrix(), 2, 2);
        ASSERT_TRUE(lu.has_value()) << ctx;
        EXPECT_EQ(*lu, (std::pair<int, int>{1, 2})) << ctx;
      }
      const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
      ASSERT_EQ(r.topology.tu_case, 1) << ctx;
      ASSERT_TRUE(r.affine.certified()) << ctx;
      EXPECT_EQ(*r.affine.loops, 1) << ctx;
      EXPECT_EQ(*r.affine.unbounded_branches, 2) << ctx;
      // The traced picture: certified with one loop and two open pieces. The automatic box
      // holds the whole loop, about 200 across (from the generators above: x in [-0.2, 98],
      // y in [1.8, 195], z in [-107, 0.8]), so the first trace's steps (200 times a tolerance
      // relative to the box) jumped from one arc of the oval to another, 0.9 apart; the
      // mismatch with the exact crossings now makes it trace again, finer.
      ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
      int closed = 0, open = 0;
      for (const auto& br : r.branches)
        (br.closed ? closed : open) += 1;
      EXPECT_EQ(closed, 1) << ctx;
      ASSERT_TRUE(r.box_exits && r.box_exits->certified) << ctx;
      EXPECT_EQ(r.box_exits->points.size(), static_cast<size_t>(2 * open)) << ctx;
    }
}

// Two ovals on two arcs of generators (disc < 0 between them: generators missing the other
// quadric), none through infinity: the cone x^2 + y^2 = z^2 against the sphere
// (x - 3)^2 + y^2 + z^2 = 25/4 (distance from its centre to the generator (cos t, sin t, 1)
// is sqrt(4.5 (1 + sin^2 t)), below 5/2 only for sin^2 t < 7/18: one oval near each of the
// generators t = 0 (upper nappe) and t = pi (lower nappe)) and against the cylinder
// y^2 + (z - 2)^2 = 1 (on the generator s (cos t, sin t, 1): s^2 (1 + sin^2 t) - 4 s + 3 = 0,
// real roots for sin^2 t < 1/3, both s > 0). Both second surfaces meet the cone's conic at
// infinity in no real point (the sphere has none; the cylinder's, (1 : 0 : 0 : 0), is off the
// cone), so every component is bounded: 2 loops, 0 unbounded (closed form). Fails when the
// reading of an arc lets an oval reach infinity without a root of c on it.
TEST(ConeOvals, OvalsOnArcsAreLoopsWithoutPointsAtInfinity) {
  const core::QuadricMatrix cone = surfcert::testing::q("x^2 + y^2 = z^2");
  const Mat4 m = motion(1, -2, 1, 3, {Rational(1, 3), Rational(-2), Rational(5, 2)});
  for (const char* other : {"(x - 3)^2 + y^2 + z^2 = 25/4", "y^2 + (z - 2)^2 = 1"})
    for (bool moved : {false, true}) {
      const std::string ctx = std::string(other) + (moved ? " moved" : "");
      core::QuadricMatrix k = cone, o = surfcert::testing::q(other);
      if (moved) k = k.congruent(m), o = o.congruent(m);
      const auto lu = certify::cone_oval_counts(k.matrix(), o.matrix(), 2, 0);
      ASSERT_TRUE(lu.has_value()) << ctx;
      EXPECT_EQ(*lu, (std::pair<int, int>{2, 0})) << ctx;
      const auto r = trace::intersect_curve(k, o, Mode::Exact, {});
      ASSERT_TRUE(r.affine.certified()) << ctx;
      EXPECT_EQ(*r.affine.loops, 2) << ctx;
      EXPECT_EQ(*r.affine.unbounded_branches, 0) << ctx;
    }
}
