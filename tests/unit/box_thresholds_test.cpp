// The box-exit triggers probed from both sides (issue 15): a face offset by +-delta from a
// non-generic position (tangent to the curve, through an edge crossing, through a singular
// point), delta in {1e-10, 1e-20, 1e-30, 2^-100}, and offset pipes at tangency +-2^-30,
// +-2^-60. The right answers are closed forms: the parabola z = x^2, y = 0 meets the face
// z = delta at x = +-sqrt(delta) (two pieces, four exits, for delta > 0; one piece through the
// vertex for delta < 0); a crossing moved off the edge x = 1, z = 1 leaves one piece, two
// exits; the cone's lines z = +-x (y = 0) cut by a face z = +-delta near the apex give two
// pieces, four exits; a pipe of radius 1/2 at offset 1/2 + e inside a pipe of radius 1 meets
// it in two loops when e < 0, one loop when e > 0. Each answer is certified with that count or
// undecided with a reason: never a certified wrong count. (Boxes x in [-1.5, 1.5]: the top
// face z = 1 meets the curves at x = +-1, inside the face.)
#include "support/distance_checks.hpp"
#include "support/trace_boxes.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace surfcert;
using certify::Mode;
using surfcert::testing::given_box;
using surfcert::testing::q;

namespace {

const std::vector<double>& deltas() {
  static const std::vector<double> d = {1e-10, 1e-20, 1e-30, std::ldexp(1.0, -100)};
  return d;
}

// Certified with `pieces` open pieces and 2 * pieces exits, or undecided with a reason.
// Returns whether it was certified.
bool expect_count(const trace::CurveResult& r, int pieces, const std::string& ctx) {
  if (r.status != certify::Status::Certified) {
    EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
    EXPECT_FALSE(r.note.empty()) << ctx;
    return false;
  }
  int open = 0;
  for (const auto& br : r.branches)
    open += br.closed ? 0 : 1;
  EXPECT_EQ(open, pieces) << ctx;
  EXPECT_TRUE(r.box_exits && r.box_exits->certified) << ctx;
  if (r.box_exits) {
    EXPECT_EQ(static_cast<int>(r.box_exits->points.size()), 2 * pieces) << ctx;
  }
  return true;
}

} // namespace

TEST(BoxThresholds, FaceNearATangency) {
  int certified = 0;
  for (double d : deltas())
    for (double side : {1.0, -1.0}) {
      const std::string ctx = "face z = " + std::to_string(side) + " * " + std::to_string(d);
      auto r = trace::intersect_curve(q("z = x^2 + y^2"), q("y = 0"), Mode::Exact,
                                      given_box({-1.5, -1, side * d}, {1.5, 1, 1}));
      certified += expect_count(r, side > 0 ? 2 : 1, ctx) ? 1 : 0;
    }
  EXPECT_GE(certified, 4); // the face below the vertex at least
}

TEST(BoxThresholds, CrossingNearAnEdge) {
  int certified = 0;
  for (double d : deltas())
    for (double side : {1.0, -1.0}) {
      const std::string ctx = "edge x = 1 + " + std::to_string(side) + " * " + std::to_string(d);
      auto r = trace::intersect_curve(q("z = x^2 + y^2"), q("y = 0"), Mode::Exact,
                                      given_box({-0.5, -1, -1}, {1 + side * d, 1, 1}));
      certified += expect_count(r, 1, ctx) ? 1 : 0;
    }
  EXPECT_GE(certified, 2);
}

TEST(BoxThresholds, FaceNearASingularPoint) {
  for (double d : deltas())
    for (double side : {1.0, -1.0}) {
      const std::string ctx = "face z = " + std::to_string(side) + " * " + std::to_string(d);
      auto r = trace::intersect_curve(q("x^2 + y^2 = z^2"), q("y = 0"), Mode::Exact,
                                      given_box({-1.5, -1, side * d}, {1.5, 1, 1}));
      expect_count(r, 2, ctx);
    }
  // Today all undecided: the two lines' ends on the face z = +-delta lie 2 delta apart, closer
  // than the tolerance matching traced ends with exact crossings (1e-7 of the box).
}

// Offset pipes: x^2 + y^2 = 1 and (y - 1/2 - e)^2 + z^2 = 1/4, tangent at e = 0.
TEST(BoxThresholds, OffsetPipesNearTangency) {
  for (int k : {30, 60})
    for (int side : {1, -1}) {
      const std::string e = std::string(side > 0 ? "+" : "-") + "1/2^" + std::to_string(k);
      const std::string ctx = "offset 1/2 " + e;
      const std::string pow = "(1/" + std::to_string(1LL << 30) + ")" + (k == 60 ? "^2" : "");
      const std::string b =
          "(y - 1/2 " + std::string(side > 0 ? "- " : "+ ") + pow + ")^2 + z^2 = 1/4";
      auto r = trace::intersect_curve(q("x^2 + y^2 = 1"), q(b), Mode::Exact, {});
      if (r.status != certify::Status::Certified) {
        EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
        EXPECT_FALSE(r.note.empty()) << ctx;
        continue;
      }
      int closed = 0;
      for (const auto& br : r.branches)
        closed += br.closed ? 1 : 0;
      EXPECT_EQ(closed, side > 0 ? 1 : 2) << ctx;
      EXPECT_EQ(static_cast<int>(r.branches.size()), closed) << ctx;
      ASSERT_TRUE(r.affine.loops.has_value()) << ctx;
      EXPECT_EQ(*r.affine.loops, side > 0 ? 1 : 2) << ctx;
    }
}

// A face near a cone's apex where the curve has its node: the cylinder (x - 1)^2 + y^2 = 1
// through the apex of x^2 + y^2 = z^2 cuts it in the figure eight z^2 = 2x (one component,
// 1 loop, node at the apex). Closed forms: the face z = s delta (box [-1, 3] x [-2, 2] x
// [s delta, 3]) meets it at the 2 points (delta^2 / 2, +-delta sqrt(1 - delta^2 / 4), s delta),
// on either side (s = +-1: the upper lobe cut off near the node, or the lower one cut just
// below it); the face x = delta (box [delta, 3] x [-2, 2] x [-3, 3]) at the 4 points
// (delta, +-sqrt(2 delta - delta^2), +-sqrt(2 delta)), the face x = -delta at none (the box
// holds the whole curve). The exits are certified with these counts at every delta (the exact
// crossings); the answer is certified with them or undecided with a reason.
TEST(BoxThresholds, FaceNearTheNodeAtAConeApex) {
  const auto cone = q("x^2 + y^2 = z^2"), cyl = q("(x - 1)^2 + y^2 = 1");
  for (double d : deltas())
    for (double side : {1.0, -1.0})
      for (int axis : {2, 0}) {
        const std::string ctx = std::string(axis == 2 ? "face z = " : "face x = ") +
                                std::to_string(side) + " * " + std::to_string(d);
        const trace::Point3 lo =
            axis == 2 ? trace::Point3{-1, -2, side * d} : trace::Point3{side * d, -2, -3};
        auto r = trace::intersect_curve(cone, cyl, Mode::Exact, given_box(lo, {3, 2, 3}));
        ASSERT_TRUE(r.box_exits && r.box_exits->certified) << ctx << ": " << r.box_exits->reason;
        const size_t exits = axis == 2 ? 2 : (side > 0 ? 4 : 0);
        ASSERT_EQ(r.box_exits->points.size(), exits) << ctx;
        for (const auto& e : r.box_exits->points) {
          const auto& p = e.approx;
          if (axis == 2) {
            EXPECT_NEAR(p[0], d * d / 2, e.radius + 1e-9 * d * d) << ctx;
            EXPECT_NEAR(std::fabs(p[1]), d * std::sqrt(1 - d * d / 4), e.radius + 1e-9 * d) << ctx;
            EXPECT_EQ(p[2], side * d) << ctx;
          } else {
            EXPECT_EQ(p[0], d) << ctx;
            EXPECT_NEAR(std::fabs(p[1]), std::sqrt(2 * d - d * d), e.radius + 1e-9 * std::sqrt(d))
                << ctx;
            EXPECT_NEAR(std::fabs(p[2]), std::sqrt(2 * d), e.radius + 1e-9 * std::sqrt(d)) << ctx;
          }
        }
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 1) << ctx;
        if (r.status != certify::Status::Certified) {
          EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
          EXPECT_FALSE(r.note.empty()) << ctx;
          continue;
        }
        int closed = 0, open = 0;
        for (const auto& br : r.branches)
          (br.closed ? closed : open) += 1;
        EXPECT_EQ(2 * open, static_cast<int>(exits)) << ctx;
        EXPECT_EQ(closed, exits == 0 ? 1 : 0) << ctx;
      }
}
