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
