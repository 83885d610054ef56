// common_apex_contact (common_apex.hpp): quadrics sharing a real singular point, whose pencil
// is degenerate. Expected answers derived by hand for each pair (comments), checked also after
// a rational rigid motion (the witness must be the moved apex, the minimizer verdict the same)
// and with the surfaces swapped; a pair without a common singular point is left to the other
// routes (parallel cylinders: their common singular point is at infinity).
#include "surfcert/certify/distance/common_apex.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <tuple>

using namespace surfcert;
using core::Rational;
using surfcert::testing::motion;
using surfcert::testing::q;

TEST(CommonApex, TextbookPairs) {
  const std::tuple<const char*, const char*, const char*, std::array<double, 3>> table[] = {
      // 3x^2 = 0: x = 0, y = +-z (tangent along two lines: the double line x^2 of B - A)
      {"x^2 + y^2 - z^2", "4x^2 + y^2 - z^2", "infinite", {0, 0, 0}},
      // z^2 = 100 (x^2 + y^2) and x^2 = 100 (y^2 + z^2) force x = y = z = 0
      {"x^2 + y^2 - z^2/100", "y^2 + z^2 - x^2/100", "1", {0, 0, 0}},
      // coaxial cones of different angles: z^2 = 4 z^2 only at the apex
      {"x^2 + y^2 - z^2", "x^2 + y^2 - 4z^2", "1", {0, 0, 0}},
      // a plane pair through the apex: x = 0 gives y = +-z (transversal: a sign change)
      {"x*y", "x^2 + y^2 - z^2", "infinite", {0, 0, 0}},
      // cones about z and about x with apex (1, 2, -1), crossing along real lines (below)
      {"(x-1)^2 + (y-2)^2 - 2(z+1)^2", "(y-2)^2 + (z+1)^2 - 2(x-1)^2", "infinite", {1, 2, -1}},
  };
  // The last pair: with u = x-1, v = y-2, w = z+1: u^2 + v^2 = 2 w^2 and v^2 + w^2 = 2 u^2;
  // subtracting, u^2 - w^2 = 2 w^2 - 2 u^2, so u^2 = w^2 and then v^2 = w^2: (1, 1, 1) is a
  // common real direction.
  const auto m = motion(3, -1, 2, 1, {Rational(2), Rational(-5, 3), Rational(1, 2)});
  for (const auto& [sa, sb, mins, apex] : table) {
    for (bool moved : {false, true})
      for (bool swap : {false, true}) {
        auto A = q(sa), B = q(sb);
        if (moved) {
          A = A.congruent(m);
          B = B.congruent(m);
        }
        const auto r =
            swap ? certify::common_apex_contact(B, A) : certify::common_apex_contact(A, B);
        ASSERT_TRUE(r) << sa << " | " << sb;
        ASSERT_EQ(r->status, certify::Status::Certified) << sa << " | " << sb << ": " << r->note;
        EXPECT_EQ(r->upper(), "0");
        EXPECT_EQ(r->minimizers, mins) << sa << " | " << sb << (moved ? " moved" : "");
        ASSERT_EQ(r->pairs.size(), 1u);
        // The witness is a singular point of both (moved or not): the gradient of each
        // quadric vanishes there (checked with the exact matrices at the double point, to
        // double accuracy) and, unmoved, it is the apex given above.
        const auto& w = r->pairs[0][0];
        if (!moved) {
          for (size_t i = 0; i < 3; ++i)
            EXPECT_NEAR(w[i], apex[i], 1e-12);
        }
        for (const auto* Q : {&A, &B})
          for (int i = 0; i < 4; ++i) {
            double g = (*Q)(i, 3).to_double_approx();
            for (int j = 0; j < 3; ++j)
              g += (*Q)(i, j).to_double_approx() * w[static_cast<size_t>(j)];
            EXPECT_NEAR(g, 0, 1e-9) << sa << " | " << sb;
          }
      }
  }
  // Parallel cylinders share only a singular point at infinity: not this route's case.
  EXPECT_FALSE(certify::common_apex_contact(q("x^2 - y^2 = 1"), q("(x - 5)^2 + y^2 = 1")));
  // End to end: the distance query answers through this route.
  const auto e = certify::surface_distance(q("x^2 + y^2 - z^2/100 = 0"),
                                           q("y^2 + z^2 - x^2/100 = 0"), 15, false);
  ASSERT_EQ(e.status, certify::Status::Certified) << e.note;
  EXPECT_EQ(e.method, certify::Method::CommonApex);
  EXPECT_EQ(e.minimizers, "1");
}
