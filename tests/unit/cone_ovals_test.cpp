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

// Cylinders (apex at infinity) and pencil members. Two ovals on a cylinder K over a conic,
// with the other quadric Q = z^2 + c(x, y): on the ruling over the conic's point (x, y),
// z^2 = -c(x, y), so disc = -c restricted to the conic decides (closed forms, by hand):
//  - K: x^2 - y^2 = 1 (x = +-cosh u, y = sinh u), Q: z^2 - x^2 + 9x + 2y - 9 = 0: disc =
//    cosh^2 u -+ 9 cosh u - 2 sinh u + 9, on the right branch > 0 for u in (-0.96, 0.32) (a
//    loop: x in [1, 1.5]) and beyond u = -2.36 and 3.00, on the left branch > 0 everywhere
//    (> 9): the other oval runs through both points at infinity of the hyperbola, where the
//    ruling at infinity meets Q at two points each (z^2 = x^2 there): 1 loop, 4 unbounded.
//  - the same K against z^2 - x^2 - y + 9 = 0: disc = cosh^2 u + sinh u - 9 on both branches,
//    > 0 only on each branch's two tails: two ovals, each through one point at infinity of
//    the hyperbola (two points of Q each): 0 loops, 4 unbounded.
//  - K: y = x^2 (a parabolic cylinder; its ruling at infinity is tangent to the plane at
//    infinity), Q: z^2 - y^2 + 5y - 4 = 0: disc = (x^2 - 1)(x^2 - 4) > 0 for |x| < 1 (a loop)
//    and |x| > 2 (one oval through the point at infinity of the parabola, where the curve
//    touches the plane at infinity at (0 : 1 : +-1 : 0)): 1 loop, 2 unbounded.
// The points at infinity alone allow both 0 and 1 loop in each (undecided before). The same
// curves again as A = Q, B = Q + K (or Q + 2K): neither is a cone or a cylinder, the member
// at the rational root of det(l A - B) is, and reads the same. Posed by a rational rigid motion
// and swapped; the traced picture must agree.
TEST(ConeOvals, CylindersAndPencilMembers) {
  struct Case {
    const char *k, *q;
    int k_multiple; // B = Q + k_multiple K (0: the pair is K, Q itself)
    int loops, unbounded, points;
  };
  const Case cases[] = {
      {"x^2 - y^2 = 1", "z^2 - x^2 + 9*x + 2*y - 9 = 0", 0, 1, 4, 4},
      {"x^2 - y^2 = 1", "z^2 - x^2 - y + 9 = 0", 0, 0, 4, 4},
      {"y = x^2", "z^2 - y^2 + 5*y - 4 = 0", 0, 1, 2, 2},
      {"x^2 - y^2 = 1", "z^2 - x^2 + 9*x + 2*y - 9 = 0", 1, 1, 4, 4},
      {"x^2 - y^2 = 1", "z^2 - x^2 - y + 9 = 0", 2, 0, 4, 4},
  };
  const Mat4 m = motion(2, 1, -1, 3, {Rational(-3, 4), Rational(1, 2), Rational(2)});
  for (const Case& c : cases)
    for (bool moved : {false, true})
      for (bool swapped : {false, true}) {
        const std::string ctx = std::string(c.k) + " / " + c.q + " x" +
                                std::to_string(c.k_multiple) + (moved ? " moved" : "") +
                                (swapped ? " swapped" : "");
        core::QuadricMatrix k = surfcert::testing::q(c.k), o = surfcert::testing::q(c.q);
        if (moved) k = k.congruent(m), o = o.congruent(m);
        if (c.k_multiple == 0) {
          const auto lu = certify::cone_oval_counts(k.matrix(), o.matrix(), 2, c.points);
          ASSERT_TRUE(lu.has_value()) << ctx;
          EXPECT_EQ(*lu, (std::pair<int, int>{c.loops, c.unbounded})) << ctx;
          // Q read as the cone (a cylinder in the third case): the same answer, or none.
          if (const auto lq = certify::cone_oval_counts(o.matrix(), k.matrix(), 2, c.points)) {
            EXPECT_EQ(*lq, (std::pair<int, int>{c.loops, c.unbounded})) << ctx;
          }
        }
        core::QuadricMatrix a = o, b = k;
        if (c.k_multiple > 0) {
          Mat4 s = o.matrix();
          for (size_t i = 0; i < 4; ++i)
            for (size_t j = 0; j < 4; ++j)
              s[i][j] += Rational(c.k_multiple) * k.matrix()[i][j];
          b = core::QuadricMatrix(s);
          ASSERT_FALSE(certify::cone_oval_counts(a.matrix(), b.matrix(), 2, c.points)) << ctx;
          ASSERT_FALSE(certify::cone_oval_counts(b.matrix(), a.matrix(), 2, c.points)) << ctx;
        }
        if (swapped) std::swap(a, b);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        ASSERT_EQ(r.topology.morphology->id, std::string("two_ovals")) << ctx;
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, c.loops) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, c.unbounded) << ctx;
        EXPECT_EQ(r.affine.points_at_infinity.size(), static_cast<size_t>(c.points)) << ctx;
        ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
        int closed = 0;
        for (const auto& br : r.branches)
          closed += br.closed ? 1 : 0;
        EXPECT_EQ(closed, c.loops) << ctx;
      }
}
