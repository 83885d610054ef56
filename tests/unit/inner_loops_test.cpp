// A given box that cuts a loop (issue 15): the tracer then shows fewer closed branches than the
// affine topology has loops, and certify::no_compact_component_in_box must prove that no loop
// lies wholly inside the box before the picture is certified.
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
// z > 0 and one in z < 0 (z^2 = 1 + (x - 1/2)^2 + y^2/4 in [1, 13/4] on the cylinder, so
// |z| in [1, 1.81]). A box that holds the lower loop wholly must not be proven empty of loops
// (else a tracer that missed that loop would be certified): no_compact_component_in_box says
// "not proven" for it, with and without the upper loop cut; the box between the loops (no
// curve at all) and boxes below or beside everything are proven.
#include "support/distance_checks.hpp"
#include "support/fixtures.hpp"
#include "support/trace_boxes.hpp"

#include "surfcert/certify/inner_loops.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

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
        const auto proof = certify::no_compact_component_in_box(a.matrix(), b.matrix(), lo, hi);
        EXPECT_TRUE(proof.proven) << ctx << ": " << proof.reason;
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

TEST(InnerLoops, LoopWhollyInsideIsNeverProvenAway) {
  const core::QuadricMatrix a = q("x^2 + y^2 = 1"), b = q("z^2 - (x - 1/2)^2 - y^2/4 = 1");
  struct Case {
    std::array<double, 3> lo, hi;
    bool empty_of_loops;
    int inside; ///< loops wholly inside the box
    const char* what;
  };
  const Case cases[] = {
      {{-2, -2, -2}, {2, 2, 1.2}, false, 1, "lower loop inside, upper loop cut by z = 1.2"},
      {{-2, -2, -2}, {2, 2, 0}, false, 1, "lower loop inside, upper loop outside"},
      {{-1.5, -1.5, -1.9}, {1.5, 1.5, -0.9}, false, 1, "lower loop inside, tight"},
      {{-2, -2, -2}, {2, 2, 2}, false, 2, "both loops inside"},
      {{-2, -2, -0.9}, {2, 2, 0.9}, true, 0, "between the loops: no curve"},
      {{1.5, -2, -2}, {3, 2, 2}, true, 0, "beside the cylinder: no curve"},
  };
  for (const auto& c : cases) {
    for (bool swapped : {false, true}) {
      const std::string ctx = std::string(c.what) + (swapped ? " swapped" : "");
      const auto p = swapped
                         ? certify::no_compact_component_in_box(b.matrix(), a.matrix(), c.lo, c.hi)
                         : certify::no_compact_component_in_box(a.matrix(), b.matrix(), c.lo, c.hi);
      EXPECT_EQ(p.proven, c.empty_of_loops) << ctx << ": " << p.reason;
      if (!p.proven) {
        EXPECT_FALSE(p.reason.empty()) << ctx;
      }
      // The whole answer: certified only with every loop inside the box traced closed.
      const auto r = swapped ? trace::intersect_curve(b, a, Mode::Exact, given_box(c.lo, c.hi))
                             : trace::intersect_curve(a, b, Mode::Exact, given_box(c.lo, c.hi));
      if (r.status != certify::Status::Certified) {
        EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
        continue;
      }
      int closed = 0;
      for (const auto& br : r.branches)
        closed += br.closed ? 1 : 0;
      EXPECT_EQ(closed, c.inside) << ctx;
    }
  }
}
