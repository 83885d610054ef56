// Walks must not be drawn through a crossing they do not lie on. Two figure eights (Tu case 5,
// generate --case 5 --count 30 --encoding exact: --seed 32 pair 17, --seed 35 pair 5) traced in
// boxes of
// half-width 100, 1000 and 10000 around the origin: at those scales the steps reach ~10-100
// units, and the curve's other two components pass a few units from the crunode. The walk on
// such a component used to snap onto the crossing (it lay within a step, ahead) and leave along
// one of its branches: each component glued to the crossing, 8 polyline arms leaving a point
// where the curve has 4, while the counts and the box crossings still matched: certified
// (6 of 6 such pictures certified before). Now a walk snaps only when the chord to the crossing
// runs along the curve (its midpoint within r/50 of it), and settle_box refuses a picture with
// more arms at a crunode than 4 (retraced finer, or undecided). Asserted: every certified picture
// has at most 4 arms at the crunode, and its affine reading is the one checked independently
// (3 unbounded pieces: 50-digit sweep of the singular member's generators).
#include "support/distance_checks.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

using namespace surfcert;

namespace {

core::QuadricMatrix from_rows(const std::array<std::array<const char*, 4>, 4>& rows) {
  core::Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = *core::Rational::from_string(rows[i][j]);
  return core::QuadricMatrix(m);
}

} // namespace

TEST(CrunodeArms, OtherComponentsAreNotGluedToTheCrossing) {
  const std::array<std::pair<core::QuadricMatrix, core::QuadricMatrix>, 2> pairs = {
      std::make_pair(from_rows({{{"44/3", "-47/3", "-65/3", "-47/3"},
                                 {"-47/3", "-4/3", "26/3", "41/3"},
                                 {"-65/3", "26/3", "59/3", "68/3"},
                                 {"-47/3", "41/3", "68/3", "41/3"}}}),
                     from_rows({{{"17/3", "94/3", "115/3", "-56/3"},
                                 {"94/3", "23/3", "38/3", "-172/3"},
                                 {"115/3", "38/3", "-73/3", "-76/3"},
                                 {"-56/3", "-172/3", "-76/3", "-22/3"}}})),
      std::make_pair(from_rows({{{"-29/4", "-87/2", "163/4", "61/2"},
                                 {"-87/2", "7", "-9/2", "9"},
                                 {"163/4", "-9/2", "31/4", "-17/2"},
                                 {"61/2", "9", "-17/2", "-8"}}}),
                     from_rows({{{"147/4", "-55/2", "115/4", "45/2"},
                                 {"-55/2", "23", "-65/2", "-31"},
                                 {"115/4", "-65/2", "143/4", "55/2"},
                                 {"45/2", "-31", "55/2", "-4"}}}))};
  int certified = 0;
  for (size_t pi = 0; pi < pairs.size(); ++pi)
    for (double w : {100.0, 1000.0, 10000.0}) {
      const std::string ctx = "pair " + std::to_string(pi) + " box " + std::to_string(w);
      trace::TraceOptions opt;
      trace::Box box;
      for (size_t k = 0; k < 3; ++k) {
        box.min[k] = -w;
        box.max[k] = w;
      }
      opt.box = box;
      const auto r =
          trace::intersect_curve(pairs[pi].first, pairs[pi].second, certify::Mode::Exact, opt);
      ASSERT_NE(r.topology.morphology, nullptr) << ctx;
      EXPECT_EQ(std::string(r.topology.morphology->id), "figure_eight") << ctx;
      ASSERT_TRUE(r.affine.certified()) << ctx;
      EXPECT_EQ(*r.affine.loops, 0) << ctx;
      EXPECT_EQ(*r.affine.unbounded_branches, 3) << ctx;
      if (r.status != certify::Status::Certified) continue;
      ++certified;
      for (const auto& sp : r.topology.special_points) {
        if (sp.at_infinity || sp.kind != "crunode") continue;
        int arms = 0;
        for (const auto& br : r.branches)
          for (size_t i = 0; i < br.points.size(); ++i)
            if (br.points[i] == sp.approx)
              arms += br.closed || (i > 0 && i + 1 < br.points.size()) ? 2 : 1;
        EXPECT_LE(arms, 4) << ctx;
      }
    }
  // Measured 5 of 6 certified (pair 1 in the box of 10000 undecided).
  EXPECT_GE(certified, 4);
}
