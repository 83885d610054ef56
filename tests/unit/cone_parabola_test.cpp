// A cone and a plane parallel to one of its generators, a gap g from the apex (issue 15's
// degenerate inputs): x^2 + y^2 = z^2 and z = x + g meet in the parabola y^2 = 2 g x + g^2
// (z = x + g), of focal length |g| / 2, which opens towards +x for g > 0 and towards -x for
// g < 0 from its vertex (-g/2, 0, g/2). Moved off the origin, the tracer's parabola was sampled
// out to a parameter equal to the box's reach, 1e11 out for g = 1e-6 in a box 256 wide, and
// none of its nine samples lay in the box (undecided at every pose but the origin's); and for
// g <= 1e-10 the plane's linear term fell below a threshold (1e-10 of the conic's size) and
// no conic was drawn. Closed-form check: one open conic, its two ends on the box's faces, every
// point on both exact surfaces (exact f over |grad f|) and on the parabola's side of the
// vertex; certified for |g| >= 1e-12 at every pose, and for 1e-15 where the apex is a double
// (the retry in the apex's frame traces the pair there at unit size: undecided before),
// certified or undecided below.
#include "support/posed_pairs.hpp"
#include "support/trace_boxes.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace surfcert;
using certify::Mode;
using core::Rational;
using surfcert::testing::certified_or_undecided;
using surfcert::testing::geometric_residual;
using surfcert::testing::Pose;
using surfcert::testing::q;

TEST(ConeParabola, OpensAwayFromTheApexOrUndecided) {
  const std::vector<Pose> poses = {{1, 0, 0, 0, {}},
                                   {1, 0, 0, 0, {Rational(1, 3), Rational(0), Rational(-1)}},
                                   {1, 1, 1, 1, {}},
                                   {1, 2, 3, 4, {Rational(1, 3), Rational(0), Rational(-1)}},
                                   {9, -1, 2, 3, {Rational(-1, 2), Rational(1), Rational(1, 4)}}};
  struct Gap {
    std::string g;
    double value;
    bool must_certify;
    bool must_certify_when_dyadic = false; // the apex a double: the retry there rescales
  };
  const std::vector<Gap> gaps = {{"1/1000000", 1e-6, true},
                                 {"-1/1000000", -1e-6, true},
                                 {"1/10000000000", 1e-10, true},
                                 {"-1/10000000000", -1e-10, true},
                                 {"1/1000000000000", 1e-12, true},
                                 {"-1/1000000000000", -1e-12, true},
                                 {"1/1000000000000000", 1e-15, false, true},
                                 {"-1/1000000000000000", -1e-15, false, true},
                                 {"1/100000000000000000000", 1e-20, false},
                                 {"-1/100000000000000000000", -1e-20, false},
                                 {"1/1267650600228229401496703205376", 0x1p-100, false},
                                 {"-1/1267650600228229401496703205376", -0x1p-100, false}};
  int certified = 0, tried = 0;
  for (const auto& gap : gaps)
    for (const auto& ps : poses)
      for (bool swapped : {false, true}) {
        const std::string ctx = ps.name(gap.g, swapped);
        auto a = q("x^2 + y^2 = z^2").congruent(ps.matrix());
        auto b = q("z = x + (" + gap.g + ")").congruent(ps.matrix());
        if (swapped) std::swap(a, b);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        ++tried;
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 0) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, 1) << ctx;
        bool dyadic = true;
        for (const auto& c : ps.t)
          dyadic = dyadic && c == Rational::exact_from_double(c.to_double_approx());
        const bool must = gap.must_certify || (gap.must_certify_when_dyadic && dyadic);
        if (!certified_or_undecided(r, must, ctx)) continue;
        ++certified;
        ASSERT_EQ(r.branches.size(), 1u) << ctx;
        const auto& br = r.branches[0];
        EXPECT_FALSE(br.closed) << ctx;
        EXPECT_EQ(br.kind, "conic") << ctx;
        ASSERT_TRUE(r.box.has_value()) << ctx;
        ASSERT_TRUE(r.box_exits.has_value()) << ctx;
        EXPECT_TRUE(r.box_exits->certified) << ctx;
        EXPECT_EQ(r.box_exits->points.size(), 2u) << ctx;
        const double diag = r.box->diagonal();
        const double slack = 1e-9 * diag + 0x1p-48 * (ps.offset() + diag);
        // The ends on the box's faces; the points on both surfaces and beyond the vertex
        // (x >= -g/2 for g > 0, x <= -g/2 for g < 0): a parabola opening the wrong way, or
        // a pair of its asymptotic lines, reaches the other side by the box's size.
        for (const auto* e : {&br.points.front(), &br.points.back()}) {
          double face = HUGE_VAL;
          for (size_t k = 0; k < 3; ++k)
            face = std::min(
                {face, std::abs((*e)[k] - r.box->min[k]), std::abs((*e)[k] - r.box->max[k])});
          EXPECT_LE(face, 1e-9 * diag) << ctx;
        }
        double behind = 0;
        for (const auto& p : br.points) {
          EXPECT_LE(geometric_residual(a, p), slack) << ctx;
          EXPECT_LE(geometric_residual(b, p), slack) << ctx;
          const double lx = ps.local(p)[0];
          behind = std::max(behind, gap.value > 0 ? -gap.value / 2 - lx : lx + gap.value / 2);
        }
        EXPECT_LE(behind, slack) << ctx << ": points behind the vertex";
      }
  EXPECT_EQ(tried, 120);
  EXPECT_GE(certified, 76); // every pair with |g| >= 1e-12, and 1e-15 where the apex is a double
}
