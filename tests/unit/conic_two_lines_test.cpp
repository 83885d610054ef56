// A conic and two lines crossing on it at infinity (Tu case 26), closed forms: A: x^2 - 1 + yz = 0
// against A + y (x - c) = 0. The member y (x - c) is a rational plane pair: the plane y = 0 cuts A
// in the parallel lines x = +-1 (direction (0, 0, 1)), the plane x = c in the hyperbola
// yz = 1 - c^2, whose asymptotic directions are (0, 1, 0) and (0, 0, 1): the lines cross on the
// conic at the point at infinity (0, 0, 1), where the curve meets the plane at infinity with
// multiplicity 3. By hand: no loop, 4 unbounded branches (the hyperbola's two, one per line),
// 2 lines, 1 conic. The points at infinity alone allow other assignments (the triple point shared
// among the three components in several ways): before, undecided; now the two plane sections
// are read exactly (plane_pair_route on the rational member of rank 2). Posed by the five rational
// motions, both orders, for c = 2 and c = 1/2: that reading certified, and the picture traced in a
// box of half-width 8 around the origin (it holds the hyperbola's vertices and crosses both
// lines) shows four open branches.
#include "support/exact_points.hpp"
#include "support/posed_pairs.hpp"

#include <gtest/gtest.h>

using namespace surfcert;
using surfcert::testing::five_poses;
using surfcert::testing::posed_pair;

TEST(ConicAndTwoLines, CrossingAtInfinityReadFromThePlanePair) {
  for (const char* b_eq : {"x^2 - 1 + y*z + y*(x - 2) = 0", "x^2 - 1 + y*z + y*(x - 1/2) = 0"}) {
    int certified = 0;
    for (const auto& ps : five_poses())
      for (bool swapped : {false, true}) {
        const std::string ctx = std::string(b_eq) + " " + ps.name("0", swapped);
        const auto [a, b] = posed_pair("x^2 - 1 + y*z = 0", b_eq, ps, swapped);
        const trace::TraceOptions opt = surfcert::testing::box_around_pose(ps, 8);
        const auto r = trace::intersect_curve(a, b, certify::Mode::Exact, opt);
        ASSERT_NE(r.topology.morphology, nullptr) << ctx;
        EXPECT_EQ(std::string(r.topology.morphology->id), "conic_and_two_lines_crossing_on_it")
            << ctx;
        ASSERT_TRUE(r.affine.certified()) << ctx << ": " << r.affine.reason;
        EXPECT_EQ(*r.affine.loops, 0) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, 4) << ctx;
        EXPECT_EQ(r.affine.points_at_infinity.size(), 2u) << ctx;
        ASSERT_TRUE(r.affine.lines && r.affine.conics) << ctx;
        EXPECT_EQ(*r.affine.lines, 2) << ctx;
        EXPECT_EQ(*r.affine.conics, 1) << ctx;
        if (r.status != certify::Status::Certified) {
          EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
          continue;
        }
        ++certified;
        EXPECT_EQ(r.branches.size(), 4u) << ctx;
        for (const auto& br : r.branches)
          EXPECT_FALSE(br.closed) << ctx;
      }
    // Measured 10 of 10 each.
    EXPECT_GE(certified, 9) << b_eq;
  }
}

// A conic and two imaginary lines crossing on it at infinity (Tu case 27): x^2 + 1 - yz = 0
// against the same plus z x or z (x - 2). The plane z = 0 cuts A in the conjugate parallel lines
// x = +-i (direction (0, 1, 0)); the plane x = c in the hyperbola yz = 1 + c^2, whose asymptotic
// directions are (0, 1, 0) and (0, 0, 1): the imaginary lines meet it at (0, 1, 0), a special
// point at infinity where the points alone cannot tell what meets (before: undecided). By hand:
// the real curve is the hyperbola, 0 loops and 2 unbounded branches. Five poses, both orders.
TEST(ConicAndTwoLines, ImaginaryLinesMeetingOnTheConicAtInfinity) {
  for (const char* b_eq : {"x^2 + 1 - y*z + z*x = 0", "x^2 + 1 - y*z + z*(x - 2) = 0"}) {
    int certified = 0;
    for (const auto& ps : five_poses())
      for (bool swapped : {false, true}) {
        const std::string ctx = std::string(b_eq) + " " + ps.name("0", swapped);
        const auto [a, b] = posed_pair("x^2 + 1 - y*z = 0", b_eq, ps, swapped);
        const auto r = trace::intersect_curve(a, b, certify::Mode::Exact, {});
        ASSERT_NE(r.topology.morphology, nullptr) << ctx;
        EXPECT_EQ(std::string(r.topology.morphology->id), "conic_with_tangency_point") << ctx;
        ASSERT_TRUE(r.affine.certified()) << ctx << ": " << r.affine.reason;
        EXPECT_EQ(*r.affine.loops, 0) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, 2) << ctx;
        if (r.status != certify::Status::Certified) {
          EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
          continue;
        }
        ++certified;
        EXPECT_EQ(r.branches.size(), 2u) << ctx;
      }
    // Measured 10 of 10 each.
    EXPECT_GE(certified, 9) << b_eq;
  }
}

// Tu 27 with the pencil's plane pair being one of the given quadrics, the four-fold root at
// infinity of the given basis (generate --case 27 --count 20 --seed 32, pair 1: A is the plane
// pair 4 (x + 2y + z)(x - y - 2z) = 0). By hand (sympy, exact): the plane x = -2y - z cuts B in
// -2 (3 (y + z) + 1)^2 - 2 = 0, two imaginary parallel lines; the plane x = y + 2z in a
// hyperbola (its quadratic part -9 y^2 + 9 z^2). So: no loop, two unbounded branches. Was
// undecided ("a singular point at infinity where imaginary components may meet": the plane pair
// was looked for at the re-based pencil's root but built from the given matrices, and A itself
// was not tried); now read two ways, the Tu 27 rule (the conic's own points at infinity) and
// the plane pair, which agree on all 120 case-27 pairs of seeds 32, 50, 51 (exact and double).
TEST(ConicAndTwoLines, PlanePairGivenAsOneOfTheQuadrics) {
  const auto a = surfcert::testing::from_ints(
      {{{4, 2, -2, 0}, {2, -8, -10, 0}, {-2, -10, -8, 0}, {0, 0, 0, 0}}});
  const auto b = surfcert::testing::from_ints(
      {{{3, 3, 3, 5}, {3, -18, -15, 4}, {3, -15, -15, -1}, {5, 4, -1, -4}}});
  for (bool swapped : {false, true}) {
    const auto r = swapped ? trace::intersect_curve(b, a, certify::Mode::Filtered, {})
                           : trace::intersect_curve(a, b, certify::Mode::Filtered, {});
    ASSERT_NE(r.topology.morphology, nullptr);
    EXPECT_EQ(std::string(r.topology.morphology->id), "conic_with_tangency_point");
    ASSERT_TRUE(r.affine.certified()) << r.affine.reason;
    EXPECT_EQ(*r.affine.loops, 0);
    EXPECT_EQ(*r.affine.unbounded_branches, 2);
    ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
    int open = 0;
    for (const auto& br : r.branches)
      open += br.closed ? 0 : 1;
    EXPECT_EQ(open, 2);
  }
}
