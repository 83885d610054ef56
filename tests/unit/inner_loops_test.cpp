// A given box that cuts loops (issue 15): the tracer then shows fewer closed branches than the
// affine topology has loops, and certify::inner_component_bound must prove that no more loops
// than those traced closed lie wholly inside the box before the picture is certified.
//
// Pair 139 of bench/natural_box_pairs.py --seed 6 (two cones: one loop about 200 across, x in
// [-0.2, 98], y in [1.8, 195], z in [-107, 0.8], and two unbounded branches; cone_ovals_test
// reads the same pair with the automatic box) in the boxes [-r, r]^3, r = 8, 20, 50: each cuts
// the loop; the curve crosses the faces at 6 points in each (sympy: natural_box_pairs.py's
// sympy_count, the face conics solved in radicals and evaluated to 40 digits, run offline), so
// the certified picture is 3 open pieces, no closed one. Checked swapped and translated
// (pair and box moved by the same rational vector).
//
// The other side: x^2 + y^2 = 1 against z^2 - (x - 1/2)^2 - y^2/4 = 1 is two loops, one in
// z > 0 and one in z < 0: on the cylinder (cos t, sin t, z), z^2 = 3/2 - cos t + 3/4 cos^2 t, in
// [1, 13/4] (|z| in [1, 1.81]; critical at t = 0, pi and cos t = 2/3). For each box, the number
// of loops wholly inside it (closed form) is a lower bound for any proven bound: the lower loop
// inside must never be proven away (else a tracer that missed it would be certified). Where
// the bound equals that number the answer is certified with it:
//  - [-2, 0.3] x [-2, 2]^2 cuts both loops at x = 0.3 (4 crossings, (3/10, +-sqrt(91)/10,
//    +-sqrt(1 + 1/25 + 91/400))): x is critical on the loops at t = 0, pi only, so 2 critical
//    points in the box (t = pi) and 4 crossings where x decreases into the box: no loop inside;
//  - [-2, 2]^2 x [-2, 6/5] holds the lower loop and cuts the upper one at z = 6/5, where
//    cos t = (1 - sqrt(41/50)) / 1.5: 3 x-critical points (2 on the lower loop, t = 0 on the
//    upper one) and 2 crossings where x increases into the box: at most 1 loop inside.
// With the tracer mutated to drop its closed loops, these boxes must be undecided.
#include "support/distance_checks.hpp"
#include "support/fixtures.hpp"
#include "support/trace_boxes.hpp"

#include "surfcert/certify/inner_loops.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace surfcert;
using certify::Mode;
using core::Mat4;
using core::Rational;
using surfcert::fixtures::mat4_from_strings;
using surfcert::testing::given_box;
using surfcert::testing::motion;
using surfcert::testing::q;

namespace {

const Mat4& cone_a() {
  static const Mat4 m = mat4_from_strings({{"1", "0", "0", "1/2"},
                                           {"0", "1", "0", "-3/2"},
                                           {"0", "0", "-4", "6"},
                                           {"1/2", "-3/2", "6", "-13/2"}});
  return m;
}

const Mat4& cone_b() {
  static const Mat4 m = mat4_from_strings({{"7/36", "-29/18", "-29/18", "211/72"},
                                           {"-29/18", "-20/9", "-29/9", "247/36"},
                                           {"-29/18", "-29/9", "-20/9", "319/36"},
                                           {"211/72", "247/36", "319/36", "-2609/144"}});
  return m;
}

} // namespace

TEST(InnerLoops, CutLoopOfSeed6Pair139) {
  for (double r : {8.0, 20.0, 50.0})
    for (bool moved : {false, true})
      for (bool swapped : {false, true}) {
        const std::string ctx = "box [-" + std::to_string(r) + ", " + std::to_string(r) + "]^3" +
                                (moved ? " moved" : "") + (swapped ? " swapped" : "");
        // The translation x -> x + (3, -5, 1/2): pair and box alike.
        const std::array<double, 3> t =
            moved ? std::array<double, 3>{3, -5, 0.5} : std::array<double, 3>{0, 0, 0};
        const Mat4 m = motion(1, 0, 0, 0,
                              {Rational::exact_from_double(t[0]), Rational::exact_from_double(t[1]),
                               Rational::exact_from_double(t[2])});
        core::QuadricMatrix a(cone_a()), b(cone_b());
        a = a.congruent(m), b = b.congruent(m);
        if (swapped) std::swap(a, b);
        const std::array<double, 3> lo{t[0] - r, t[1] - r, t[2] - r},
            hi{t[0] + r, t[1] + r, t[2] + r};
        const auto bound =
            certify::inner_component_bound(a.matrix(), b.matrix(), lo, hi, nullptr, 0);
        ASSERT_TRUE(bound.bound.has_value()) << ctx << ": " << bound.reason;
        EXPECT_EQ(*bound.bound, 0) << ctx;
        const auto res = trace::intersect_curve(a, b, Mode::Exact, given_box(lo, hi));
        ASSERT_TRUE(res.affine.certified()) << ctx;
        EXPECT_EQ(*res.affine.loops, 1) << ctx;
        EXPECT_EQ(*res.affine.unbounded_branches, 2) << ctx;
        ASSERT_EQ(res.status, certify::Status::Certified) << ctx << ": " << res.note;
        int closed = 0, open = 0;
        for (const auto& br : res.branches)
          (br.closed ? closed : open) += 1;
        EXPECT_EQ(closed, 0) << ctx;
        EXPECT_EQ(open, 3) << ctx;
        ASSERT_TRUE(res.box_exits && res.box_exits->certified) << ctx;
        EXPECT_EQ(res.box_exits->points.size(), 6u) << ctx;
      }
}

namespace {

struct LoopBox {
  std::array<double, 3> lo, hi;
  int inside; ///< loops wholly inside (closed form)
  int exits;  ///< crossings with the faces (closed form)
  bool exact; ///< the bound is expected to be exactly `inside` (the cases above)
  const char* what;
};

} // namespace

TEST(InnerLoops, LoopsInsideAreCountedNeverProvenAway) {
  const core::QuadricMatrix a = q("x^2 + y^2 = 1"), b = q("z^2 - (x - 1/2)^2 - y^2/4 = 1");
  const LoopBox cases[] = {
      {{-2, -2, -2}, {0.3, 2, 2}, 0, 4, true, "both loops cut by x = 0.3"},
      {{-2, -2, -2}, {2, 2, 1.2}, 1, 2, true, "lower loop inside, upper loop cut by z = 1.2"},
      {{-2, -2, -2}, {2, 2, 0}, 1, 0, false, "lower loop inside, upper loop outside"},
      {{-1.5, -1.5, -1.9}, {1.5, 1.5, -0.9}, 1, 0, false, "lower loop inside, tight"},
      {{-2, -2, -2}, {2, 2, 2}, 2, 0, false, "both loops inside"},
      {{-2, -2, -0.9}, {2, 2, 0.9}, 0, 0, true, "between the loops: no curve"},
      {{1.5, -2, -2}, {3, 2, 2}, 0, 0, true, "beside the cylinder: no curve"},
  };
  for (const auto& c : cases)
    for (bool swapped : {false, true}) {
      const std::string ctx = std::string(c.what) + (swapped ? " swapped" : "");
      const core::QuadricMatrix& x = swapped ? b : a;
      const core::QuadricMatrix& y = swapped ? a : b;
      const certify::BoxExits ex = certify::box_exits(
          x.matrix(), y.matrix(),
          {Rational::exact_from_double(c.lo[0]), Rational::exact_from_double(c.lo[1]),
           Rational::exact_from_double(c.lo[2])},
          {Rational::exact_from_double(c.hi[0]), Rational::exact_from_double(c.hi[1]),
           Rational::exact_from_double(c.hi[2])});
      ASSERT_TRUE(ex.certified) << ctx << ": " << ex.reason;
      ASSERT_EQ(static_cast<int>(ex.points.size()), c.exits) << ctx;
      // Never below the true count, whatever number is wanted.
      for (int wanted : {0, 1, 2}) {
        const auto p =
            certify::inner_component_bound(x.matrix(), y.matrix(), c.lo, c.hi, &ex, wanted);
        if (p.bound) {
          EXPECT_GE(*p.bound, c.inside) << ctx << ", wanted " << wanted;
        } else {
          EXPECT_FALSE(p.reason.empty()) << ctx;
        }
        if (c.exact && wanted == c.inside) {
          ASSERT_TRUE(p.bound.has_value()) << ctx << ": " << p.reason;
          EXPECT_EQ(*p.bound, c.inside) << ctx;
        }
      }
      // The whole answer: certified only with every loop inside the box traced closed.
      const auto r = trace::intersect_curve(x, y, Mode::Exact, given_box(c.lo, c.hi));
      if (!c.exact && r.status != certify::Status::Certified) {
        EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
        EXPECT_FALSE(r.note.empty()) << ctx;
        continue;
      }
      ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
      int closed = 0, open = 0;
      for (const auto& br : r.branches)
        (br.closed ? closed : open) += 1;
      EXPECT_EQ(closed, c.inside) << ctx;
      EXPECT_EQ(2 * open, c.exits) << ctx;
      if (c.exits == 4) {
        for (const auto& e : r.box_exits->points) {
          EXPECT_NEAR(e.approx[0], 0.3, 1e-12) << ctx;
          EXPECT_NEAR(std::fabs(e.approx[1]), std::sqrt(0.91), 1e-12) << ctx;
          EXPECT_NEAR(std::fabs(e.approx[2]), std::sqrt(1 + 0.04 + 0.91 / 4), 1e-12) << ctx;
        }
      } else if (c.exits == 2) {
        const double ct = (1 - std::sqrt(0.82)) / 1.5;
        for (const auto& e : r.box_exits->points) {
          EXPECT_NEAR(e.approx[0], ct, 1e-12) << ctx;
          EXPECT_NEAR(std::fabs(e.approx[1]), std::sqrt(1 - ct * ct), 1e-12) << ctx;
          EXPECT_NEAR(e.approx[2], 1.2, 1e-12) << ctx;
        }
      }
    }
}
