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
#include "support/trace_boxes.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

using namespace surfcert;

namespace {

core::QuadricMatrix from_rows(const std::array<std::array<const char*, 4>, 4>& rows) {
  core::Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = *core::Rational::from_string(rows[i][j]);
  return core::QuadricMatrix(m);
}

// The largest number of polyline arms leaving a finite special point of the given kind in the
// picture: a point of a closed branch or inside an open one counts 2, an end 1.
int most_arms_at(const trace::CurveResult& r, const std::string& kind) {
  int most = 0;
  for (const auto& sp : r.topology.special_points) {
    if (sp.at_infinity || sp.kind != kind) continue;
    int arms = 0;
    for (const auto& br : r.branches)
      for (size_t i = 0; i < br.points.size(); ++i)
        if (br.points[i] == sp.approx)
          arms += br.closed || (i > 0 && i + 1 < br.points.size()) ? 2 : 1;
    most = std::max(most, arms);
  }
  return most;
}

int most_arms_at_a_crunode(const trace::CurveResult& r) {
  return most_arms_at(r, "crunode");
}

// A pair in a given box and the singular point's kind that must keep its arms.
struct BoxCase {
  const char* id;
  std::array<std::array<const char*, 4>, 4> a, b;
  trace::Point3 lo, hi;
  const char* kind = "crunode";
};

// Each certified in its box (expect_matched_in_box: crossings certified, ends matched, points
// on both exact surfaces), with at most 4 arms at a crunode or 2 at a cusp.
void expect_certified_in_given_boxes(const std::vector<BoxCase>& cases) {
  for (const auto& c : cases) {
    const auto a = from_rows(c.a), b = from_rows(c.b);
    const auto r = trace::intersect_curve(a, b, certify::Mode::Filtered,
                                          surfcert::testing::given_box(c.lo, c.hi));
    surfcert::testing::expect_matched_in_box(r, a, b, c.id);
    EXPECT_LE(most_arms_at(r, c.kind), std::string(c.kind) == "cusp" ? 2 : 4) << c.id;
  }
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
      EXPECT_LE(most_arms_at_a_crunode(r), 4) << ctx;
    }
  // Measured 5 of 6 certified (pair 1 in the box of 10000 undecided).
  EXPECT_GE(certified, 4);
}

// Given boxes ~3e4 across around unit-size curves with a crunode (figure eights, Tu 5; a
// crunode on unbounded branches, Tu 8; `generate --case all --count 20 --seed 61`, boxes of
// `bench/boxed_pairs.py --boxes 2 --seed 61`): at the tolerance relative to the box (~7 units)
// and its two refinements by 8, walks on the other components still passed the crunode within
// a step and were glued to it (6 or 8 arms), or joined pieces a unit apart: undecided. The
// third refinement draws the chords 64 times finer with the same steps. Asserted: each is
// certified, at most 4 arms leave the crunode, every point lies on both surfaces to 1e-12 of
// the box's diagonal (exact substitution), and the ends match the exact crossings one to one.
TEST(CrunodeArms, LargeGivenBoxesAroundUnitCurves) {
  const std::vector<BoxCase> cases = {
      {"case05-0007-b1",
       {{{"-191/3", "217/3", "4", "-166/3"},
         {"217/3", "-191/3", "-26/3", "76/3"},
         {"4", "-26/3", "58/3", "28"},
         {"-166/3", "76/3", "28", "-23"}}},
       {{{"-82/3", "86/3", "8", "-74/3"},
         {"86/3", "-82/3", "-4/3", "38/3"},
         {"8", "-4/3", "11/3", "11"},
         {"-74/3", "38/3", "11", "-22"}}},
       {-13865.407500151641, -11288.658672893358, -8787.428028990003},
       {13271.889947092308, 11942.235474538691, 14900.377218896598}},
      {"case05-0016-b0",
       {{{"-8", "-2", "2", "2"},
         {"-2", "4", "6", "4"},
         {"2", "6", "-3", "4"},
         {"2", "4", "4", "11"}}},
       {{{"2", "17/2", "-2", "-1"},
         {"17/2", "-1", "0", "15/2"},
         {"-2", "0", "1/2", "-3"},
         {"-1", "15/2", "-3", "-7/2"}}},
       {-10443.255136602647, -7094.277362674218, -7406.7011298215975},
       {11104.512242688948, 14016.429001452603, 11538.90447888551}},
      {"case08-0007-b0",
       {{{"1", "12", "-20", "-7"},
         {"12", "-20", "22", "14"},
         {"-20", "22", "6", "-4"},
         {"-7", "14", "-4", "-9"}}},
       {{{"-4", "-8", "20", "8"},
         {"-8", "16", "-20", "-12"},
         {"20", "-20", "-6", "2"},
         {"8", "-12", "2", "6"}}},
       {-8176.64279728578, -12869.590581516086, -11227.808956069777},
       {14471.123270405365, 10113.887669907399, 13385.000203985413}},
      {"case08-0015-b0",
       {{{"20", "40", "-4", "-2"},
         {"40", "38", "-25", "18"},
         {"-4", "-25", "-13", "27"},
         {"-2", "18", "27", "-53"}}},
       {{{"40", "82", "-4", "-14"},
         {"82", "77", "-51", "34"},
         {"-4", "-51", "-31", "61"},
         {"-14", "34", "61", "-111"}}},
       {-6547.929173632108, -8498.451862451542, -14240.752157927267},
       {5225.721793525669, 6156.4236422648355, 5921.798880940436}}};
  expect_certified_in_given_boxes(cases);
}

// Figure eights whose crunode's two lines cross at a small angle, in given boxes ~2.5e4 across
// (`generate --case all --count 20 --seed 32 --encoding exact`, boxes of `bench/boxed_pairs.py
// --boxes 3 --seed 4`). A walk arriving at the crunode chose its way out by the chord from its
// last point: off the arm's tangent by ~kappa r / 2, nearer the other line there, so the walk
// turned onto the other branch; the pieces paired the arms inconsistently (one face point
// ended three pieces) and every refinement showed 6-10 arms at the crunode: undecided. Now the
// arm's tangent is read as 2 chord - t (second order) and the walk comes closer while the
// choice is not clear. Asserted as above: certified, at most 4 arms, points on both surfaces,
// ends matching the exact crossings.
TEST(CrunodeArms, LinesCrossingAtASmallAngle) {
  const std::vector<BoxCase> cases = {
      {"case05-0000-b0",
       {{{"101/3", "13/3", "-22/3", "1"},
         {"13/3", "14/3", "-23/3", "-7"},
         {"-22/3", "-23/3", "-43/3", "-22"},
         {"1", "-7", "-22", "-29"}}},
       {{{"265/3", "62/3", "-71/3", "2"},
         {"62/3", "28/3", "-64/3", "-17"},
         {"-71/3", "-64/3", "-95/3", "-53"},
         {"2", "-17", "-53", "-70"}}},
       {-13754.059775977059, -9479.735096358894, -7640.691119368489},
       {11288.091825676998, 9592.451558069179, 9097.021678418809}},
      {"case05-0010-b0",
       {{{"13/2", "12", "-29/2", "-7/2"},
         {"12", "-2", "-21", "-7"},
         {"-29/2", "-21", "53/2", "7"},
         {"-7/2", "-7", "7", "0"}}},
       {{{"-10", "-12", "20", "4"},
         {"-12", "-8", "24", "8"},
         {"20", "24", "-20", "-8"},
         {"4", "8", "-8", "0"}}},
       {-11588.208727157513, -7448.026511303315, -13739.4073251664},
       {12613.49317089043, 8081.22573705051, 10556.866098909193}},
      {"case05-0017-b0",
       {{{"44/3", "-47/3", "-65/3", "-47/3"},
         {"-47/3", "-4/3", "26/3", "41/3"},
         {"-65/3", "26/3", "59/3", "68/3"},
         {"-47/3", "41/3", "68/3", "41/3"}}},
       {{{"17/3", "94/3", "115/3", "-56/3"},
         {"94/3", "23/3", "38/3", "-172/3"},
         {"115/3", "38/3", "-73/3", "-76/3"},
         {"-56/3", "-172/3", "-76/3", "-22/3"}}},
       {-14256.3938602668, -14024.494536354034, -11103.050042533234},
       {13357.36553452411, 9808.856210206939, 12178.320196692786}},
      {"case05-0018-b0",
       {{{"-120", "30", "6", "-24"},
         {"30", "-36", "84", "72"},
         {"6", "84", "0", "-48"},
         {"-24", "72", "-48", "-72"}}},
       {{{"112", "-36", "2", "32"},
         {"-36", "40", "-78", "-72"},
         {"2", "-78", "1", "46"},
         {"32", "-72", "46", "72"}}},
       {-10049.58741560464, -5632.669957538179, -7367.685399832756},
       {14578.096170111228, 13996.151079461835, 12520.037903565782}}};
  expect_certified_in_given_boxes(cases);
}

// Another piece of curve passing a crunode (Tu 8) or a cusp (Tu 9) well within a step, in given
// boxes ~2e4 across around unit-size curves (`generate --case all --count 20 --encoding exact`,
// seed 32 with `boxed_pairs.py --boxes 3 --seed 4`, seed 61 with `--boxes 2 --seed 61`). A walk
// on that piece, heading at the singular point, was snapped onto it from ~19 away (the chord
// test passes for a straight piece passing at 0.5), and a walk leaving the crunode at ~12 landed
// on the piece passing 0.58 from it: two pieces ended on one face point, or 6-8 arms at the
// point, at every refinement. Now a walk comes to within h_free / 16 before stepping onto a
// singular point, leaves it at that distance, and keeps its steps below half its distance to it.
TEST(CrunodeArms, PiecesPassingCloseToTheSingularPoint) {
  const std::vector<BoxCase> cases = {
      {"seed 32 case08-0008-b0",
       {{{"10/3", "43/3", "-77/3", "-10"},
         {"43/3", "-3", "-23/3", "-7/3"},
         {"-77/3", "-23/3", "-11/3", "-9"},
         {"-10", "-7/3", "-9", "-22/3"}}},
       {{{"4/3", "49/3", "-59/3", "-8"},
         {"49/3", "-1", "-59/3", "-25/3"},
         {"-59/3", "-59/3", "-17/3", "-11"},
         {"-8", "-25/3", "-11", "-28/3"}}},
       {-7134.40243939752, -6600.003627888826, -13664.935808894123},
       {6625.247456884149, 9742.664730166249, 7992.33940023044}},
      {"seed 61 case09-0008-b1",
       {{{"-6", "10", "4", "4"},
         {"10", "4", "-6", "6"},
         {"4", "-6", "18", "-6"},
         {"4", "6", "-6", "6"}}},
       {{{"-35/2", "-1/2", "-8", "-2"},
         {"-1/2", "1/2", "-8", "1"},
         {"-8", "-8", "18", "-12"},
         {"-2", "1", "-12", "3"}}},
       {-11421.970943472461, -8599.785371006437, -9696.895960712549},
       {9984.988812720407, 8320.10685907702, 7894.400376829077},
       "cusp"}};
  expect_certified_in_given_boxes(cases);
}
