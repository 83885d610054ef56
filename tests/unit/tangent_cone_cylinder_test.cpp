// A cone and a cylinder tangent to it (issue 15; Open CASCADE emits two overlapping curves for
// such pairs). Two kinds, each posed by rational rigid motions:
//  - the cylinder (x - 1)^2 + y^2 = 1 through the apex of x^2 + y^2 = z^2, tangent there: the
//    curve is z^2 = 2x on the cylinder, a figure eight with its node at the apex, one
//    connected bounded component (closed form: 1 loop, 0 unbounded branches, no box exit in a
//    box holding it: its points have norm <= 3, the motions below add <= 2.3, so [-6, 6]^3);
//  - a cylinder tangent to the cone along the ruling (t, 0, t): axis (s, 0, -s) + t (1, 0, 1),
//    radius^2 = 2 s^2, s = +-1. By hand, cylinder - cone = -(u / 2)(x + 3z + 4 s) with
//    u = x - z: the curve is that ruling counted twice plus the ellipse 8 (z + 3s/2)^2 + y^2 = 2
//    in the plane x + 3z = -4s, touching the ruling at (-s, 0, -s). Certified only with one
//    line and one conic; otherwise undecided with a reason.
// Never a wrong certified count.
#include "support/distance_checks.hpp"
#include "support/trace_boxes.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

using namespace surfcert;
using certify::Mode;
using core::Rational;
using surfcert::testing::given_box;
using surfcert::testing::motion;
using surfcert::testing::q;

namespace {

std::vector<core::Mat4> poses() {
  return {motion(1, 0, 0, 0, {}),
          motion(1, 2, 2, -1, {Rational(3, 2), Rational(-1), Rational(5, 4)}),
          motion(2, -1, 1, 1, {Rational(-1, 2), Rational(1), Rational(1, 4)}),
          motion(1, 1, 1, 1, {Rational(1, 3), Rational(0), Rational(-1)}),
          motion(3, 0, 4, 0, {Rational(0), Rational(1, 2), Rational(0)}),
          motion(0, 1, 2, 2, {Rational(1), Rational(1), Rational(1)})};
}

} // namespace

TEST(TangentConeCylinder, CylinderThroughTheApex) {
  const auto cone = q("x^2 + y^2 = z^2"), cyl = q("(x - 1)^2 + y^2 = 1");
  int pose = 0, certified = 0;
  for (const auto& m : poses()) {
    ++pose;
    for (bool swapped : {false, true})
      for (bool automatic : {true, false}) {
        const std::string ctx = "pose " + std::to_string(pose) + (swapped ? " swapped" : "") +
                                (automatic ? " automatic box" : " box [-6, 6]^3");
        auto a = cone.congruent(m), b = cyl.congruent(m);
        if (swapped) std::swap(a, b);
        const auto r = trace::intersect_curve(a, b, Mode::Exact,
                                              automatic ? trace::TraceOptions{}
                                                        : given_box({-6, -6, -6}, {6, 6, 6}));
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 1) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, 0) << ctx;
        EXPECT_EQ(*r.affine.isolated_points, 0) << ctx;
        if (r.status != certify::Status::Certified) {
          EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
          EXPECT_FALSE(r.note.empty()) << ctx;
          continue;
        }
        ++certified;
        int closed = 0;
        for (const auto& br : r.branches)
          closed += br.closed ? 1 : 0;
        EXPECT_EQ(closed, 1) << ctx;
        EXPECT_EQ(r.branches.size(), 1u) << ctx;
        ASSERT_TRUE(r.box_exits && r.box_exits->certified) << ctx;
        EXPECT_TRUE(r.box_exits->points.empty()) << ctx;
      }
  }
  EXPECT_GE(certified, 1); // the canonical pose at least
}

TEST(TangentConeCylinder, TangentAlongARuling) {
  const auto cone = q("x^2 + y^2 = z^2");
  const std::vector<std::string> cylinders = {"(x - 1)^2 + y^2 + (z + 1)^2 - (x + z)^2/2 = 2",
                                              "(x + 1)^2 + y^2 + (z - 1)^2 - (x + z)^2/2 = 2"};
  int pose = 0;
  for (const auto& m : poses()) {
    ++pose;
    for (const auto& c : cylinders)
      for (bool swapped : {false, true}) {
        const std::string ctx =
            "pose " + std::to_string(pose) + ", " + c + (swapped ? " swapped" : "");
        auto a = cone.congruent(m), b = q(c).congruent(m);
        if (swapped) std::swap(a, b);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        if (r.status == certify::Status::Certified) {
          ASSERT_TRUE(r.affine.certified()) << ctx;
          EXPECT_EQ(*r.affine.lines, 1) << ctx;
          EXPECT_EQ(*r.affine.conics, 1) << ctx;
        } else {
          EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
          EXPECT_FALSE(r.note.empty()) << ctx;
        }
        // A certified affine reading, when given, has the line and the conic.
        if (r.affine.certified()) {
          EXPECT_EQ(*r.affine.lines, 1) << ctx;
          EXPECT_EQ(*r.affine.conics, 1) << ctx;
        }
      }
  }
}
