// The plane-quadric route (plane_quadric.hpp), each result against an independent route:
// - random ellipsoids and planes against the support-function closed form used by
//   surface_distance for ellipsoids (a different derivation), and sphere-plane |n.c - delta| /
//   |n| - r (fixed seed, printed on failure);
// - closed forms for a paraboloid (tilted plane: tangency where the gradient is parallel to
//   n), a two-sheeted hyperboloid (a tie at 1, exactly), a hyperbolic cylinder (two lines at 1),
//   parallel planes, a double plane;
// - contact cases (cone, cylinder, hyperbolic paraboloid, pairs of planes): distance 0 and the
//   witness lies on both surfaces (double check); asymptotic pairs: infimum 0 not attained;
// - float upper-bound check: the plane distance of random points of the quadric is never below
//   the certified lower bound; the reported pair realises the distance;
// - rigid motions (integer quaternions), scalings, swapping, digits 15/100/1000 nested.
#include "surfcert/certify/distance/plane_quadric.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <cmath>
#include <random>

using namespace surfcert;
using core::Rational;
using surfcert::testing::contains;
using surfcert::testing::hi;
using surfcert::testing::lo;
using surfcert::testing::motion;
using surfcert::testing::overlap;
using surfcert::testing::q;

namespace {

certify::DistanceResult pq(const std::string& plane, const std::string& quadric, long digits = 15) {
  return certify::plane_quadric_distance(q(plane), q(quadric), digits, true);
}

double eval(const core::QuadricMatrix& m, const std::array<double, 3>& x) {
  const double X[4] = {x[0], x[1], x[2], 1};
  double s = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      s += m(i, j).to_double_approx() * X[i] * X[j];
  return s;
}

// The pair (plane point, quadric point) lies on both surfaces and is d apart (doubles).
void expect_pair_ok(const certify::DistanceResult& r, const core::QuadricMatrix& plane,
                    const core::QuadricMatrix& quad) {
  ASSERT_FALSE(r.pairs.empty());
  for (const auto& pr : r.pairs) {
    const double scale = 1 + std::hypot(pr[1][0], pr[1][1], pr[1][2]);
    EXPECT_NEAR(eval(plane, pr[0]), 0, 1e-9 * scale);
    EXPECT_NEAR(eval(quad, pr[1]), 0, 1e-9 * scale * scale);
    const double dd = std::hypot(pr[0][0] - pr[1][0], pr[0][1] - pr[1][1], pr[0][2] - pr[1][2]);
    EXPECT_NEAR(dd, r.approx(), 1e-9 * scale);
  }
}

std::string num(long v) {
  return "(" + std::to_string(v) + ")";
}

} // namespace

TEST(PlaneQuadric, RandomEllipsoidsAgainstTheSupportFormula) {
  std::mt19937 rng(777);
  std::uniform_int_distribution<long> c(-9, 9), r(1, 6);
  int compared = 0;
  for (int k = 0; k < 40; ++k) {
    const std::string e = "(x-" + num(c(rng)) + ")^2/" + num(r(rng)) + " + (y-" + num(c(rng)) +
                          ")^2/" + num(r(rng)) + " + (z-" + num(c(rng)) + ")^2/" + num(r(rng)) +
                          " + (x-" + num(c(rng)) + ")*(y-" + num(c(rng)) + ")/" + num(10 + r(rng)) +
                          " = 1";
    const std::string p =
        num(c(rng)) + "*x + " + num(c(rng)) + "*y + " + num(r(rng)) + "*z = " + num(c(rng));
    const auto E = q(e), P = q(p);
    if (E.kind() != core::QuadricKind::Ellipsoid || P.is_plane() == false) continue;
    const auto mine = certify::plane_quadric_distance(P, E, 15, true);
    const auto ref = certify::surface_distance(P, E, 15, false, certify::Mode::Exact);
    ASSERT_EQ(mine.status, certify::Status::Certified) << e << " | " << p;
    ASSERT_EQ(ref.status, certify::Status::Certified) << e << " | " << p;
    EXPECT_TRUE(overlap(mine, ref)) << "seed 777 case " << k << ": " << e << " | " << p << ": "
                                    << mine.lower() << " vs " << ref.lower();
    if (mine.approx() > 0) {
      EXPECT_EQ(mine.minimizers, "1");
      expect_pair_ok(mine, P, E);
    } else {
      EXPECT_EQ(mine.minimizers, "infinite"); // a curve of contact (or one point: measure 0)
    }
    ++compared;
  }
  EXPECT_GE(compared, 30);
}

TEST(PlaneQuadric, SpherePlaneClosedForm) {
  // x^2 + y^2 + z^2 = 1 and 3x + 4y + 12z = 39: |39| / 13 - 1 = 2.
  const auto r = pq("3x + 4y + 12z = 39", "(x-0)^2 + y^2 + z^2 = 1", 100);
  mpfr_t d;
  mpfr_init2(d, 4000);
  mpfr_set_ui(d, 2, MPFR_RNDN);
  EXPECT_TRUE(contains(r, d)) << r.lower();
  mpfr_clear(d);
  expect_pair_ok(r, q("3x + 4y + 12z = 39"), q("x^2 + y^2 + z^2 = 1"));
}

TEST(PlaneQuadric, ParaboloidTiltedPlane) {
  // z = x^2 + y^2 and 2x - z = 5: the tangency point (1, 0, 1), d = |2 - 1 - 5| / sqrt(5).
  for (long digits : {15L, 100L, 1000L}) {
    const auto r = pq("2x - z = 5", "x^2 + y^2 - z = 0", digits);
    ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
    mpfr_t d;
    mpfr_init2(d, 4000);
    mpfr_set_ui(d, 5, MPFR_RNDN);
    mpfr_sqrt(d, d, MPFR_RNDN);
    mpfr_ui_div(d, 4, d, MPFR_RNDN);
    EXPECT_TRUE(contains(r, d)) << digits << ": " << r.lower();
    mpfr_clear(d);
    EXPECT_EQ(r.minimizers, "1");
    EXPECT_NEAR(r.pairs[0][1][0], 1, 1e-12);
    EXPECT_NEAR(r.pairs[0][1][2], 1, 1e-12);
    // Relative width <= 10^-digits.
    EXPECT_LT(std::fabs(std::stod(r.upper()) - std::stod(r.lower())), 1e-14);
  }
}

TEST(PlaneQuadric, TiesLinesPlanesAndNonAttainment) {
  auto r = pq("z = 0", "x^2 + y^2 - z^2 = -1"); // between the sheets: 1, twice
  EXPECT_EQ(r.minimizers, "2");
  EXPECT_EQ(r.ties, certify::Ties::Proven);
  EXPECT_LE(lo(r), 1);
  EXPECT_GE(hi(r), 1);
  expect_pair_ok(r, q("z = 0"), q("x^2 + y^2 - z^2 = -1"));
  r = pq("x = 0", "x^2 - y^2 = 1"); // hyperbolic cylinder: the lines (+-1, 0, z)
  EXPECT_EQ(r.minimizers, "infinite");
  EXPECT_LE(lo(r), 1);
  EXPECT_GE(hi(r), 1);
  r = pq("z = 5", "z = 7");
  EXPECT_EQ(r.minimizers, "infinite");
  EXPECT_LE(lo(r), 2);
  EXPECT_GE(hi(r), 2);
  r = pq("z = 5", "(z - 1)^2 = 0"); // a double plane
  EXPECT_LE(lo(r), 4);
  EXPECT_GE(hi(r), 4);
  r = pq("x = 5", "x^2 + y^2 = 1"); // parallel to the cylinder's axis: a line of contact
  EXPECT_EQ(r.minimizers, "infinite");
  EXPECT_LE(lo(r), 4);
  EXPECT_GE(hi(r), 4);
  for (const char* asym : {"x*z - 1 = 0", "x^2 + z*y + 1 = 0"}) { // approach z = 0 at infinity
    r = pq("z = 0", asym);
    EXPECT_EQ(r.status, certify::Status::Certified) << asym;
    EXPECT_EQ(r.upper(), "0") << asym;
    EXPECT_EQ(r.minimizers, "0") << asym << ": " << r.note;
  }
  EXPECT_EQ(pq("z = 0", "x^2 + y^2 + z^2 + 1 = 0").status, certify::Status::Undecided);
}

TEST(PlaneQuadric, ContactWitnessesLieOnBoth) {
  const std::vector<std::pair<const char*, const char*>> cases = {
      {"z = 5", "x^2 + y^2 = 1"},
      {"x + y + z = 5", "x^2 + y^2 = 1"},
      {"z = 5", "x^2 + y^2 - z^2 = 0"},
      {"z = 0", "x^2 + y^2 - z^2 = 0"},
      {"x = 5", "x^2 - y^2 - z = 0"},
      {"z - 5 = 0", "x - 1 = 0"},
      {"x + 2y - 2z = 3", "y^2 - 4 = 0"},
      {"x - z = 5", "x^2 + y^2 - z^2 = 1"},
      {"y = 0", "x*y - z = 0"},
      {"2x + y = 1", "x^2 - 3y^2 + z^2 - 2 = 0"},
      {"z = 1", "x^2 + 4y^2 - z = 0"},
      // found by random testing: a rotated hyperbolic cylinder whose section form is positive
      // on both coordinate directions (the witness needs the vertex direction)
      {"z = 7", "(278/6727)*x*x + (-4080/6727)*x*y + (-1560/6727)*x*z + (25188/6727)*x + "
                "(12550/6727)*y*y + (5640/6727)*y*z + (-149020/6727)*y + (-1296/6727)*z*z + "
                "(-27696/6727)*z + (431301/6727) = 0"}};
  for (const auto& [p, s] : cases) {
    const auto r = pq(p, s);
    ASSERT_EQ(r.status, certify::Status::Certified) << p << " | " << s;
    EXPECT_EQ(r.upper(), "0") << p << " | " << s << ": " << r.note;
    ASSERT_EQ(r.pairs.size(), 1u) << p << " | " << s;
    const auto& w = r.pairs[0][0];
    const double scale = 1 + std::hypot(w[0], w[1], w[2]);
    EXPECT_NEAR(eval(q(p), w), 0, 1e-9 * scale) << p << " | " << s;
    EXPECT_NEAR(eval(q(s), w), 0, 1e-9 * scale * scale) << p << " | " << s;
  }
}

TEST(PlaneQuadric, FloatPointsNeverBelowTheLowerBound) {
  // Points of the paraboloid z = x^2 + 2y^2 + xy/3 sampled on a grid: their distance to the
  // plane x - y - 3z = 7 is >= the certified lower bound, and the minimum sample is close.
  const auto P = q("x - y - 3z = 7"), Q = q("x^2 + 2y^2 + x*y/3 - z = 0");
  const auto r = certify::plane_quadric_distance(P, Q, 15, true);
  ASSERT_EQ(r.status, certify::Status::Certified);
  double best = 1e300;
  for (int i = -200; i <= 200; ++i)
    for (int j = -200; j <= 200; ++j) {
      const double x = i / 100.0, y = j / 100.0, z = x * x + 2 * y * y + x * y / 3;
      const double d = std::fabs(x - y - 3 * z - 7) / std::sqrt(11.0);
      EXPECT_GE(d, lo(r) - 1e-15) << x << " " << y;
      best = std::min(best, d);
    }
  EXPECT_NEAR(best, r.approx(), 1e-3);
  expect_pair_ok(r, P, Q);
}

TEST(PlaneQuadric, MotionsScalingsSwaps) {
  const auto P = q("2x - z = 5"), Q = q("x^2 + y^2 - z = 0");
  const auto base = certify::plane_quadric_distance(P, Q, 30, true);
  const auto m = motion(3, 1, -2, 5, {Rational(7, 3), Rational(-2), Rational(1, 9)});
  const auto moved = certify::surface_distance(P.congruent(m), Q.congruent(m), 30, false);
  EXPECT_EQ(moved.method, certify::Method::PlaneClosedForm);
  EXPECT_TRUE(overlap(base, moved)) << base.lower() << " " << moved.lower();
  // Swapped: the same distance, the quadric's point first.
  const auto sw = certify::surface_distance(Q, P, 30, false);
  EXPECT_TRUE(overlap(base, sw));
  ASSERT_EQ(sw.pairs.size(), 1u);
  EXPECT_NEAR(sw.pairs[0][0][0], base.pairs[0][1][0], 1e-12);
  // Scaled by 10^8 and 10^-8.
  for (const Rational& s : {Rational(100000000), Rational(1, 100000000)}) {
    const auto sc = surfcert::testing::scaling(s);
    const auto r = certify::plane_quadric_distance(P.congruent(sc), Q.congruent(sc), 15, true);
    EXPECT_NEAR(r.approx() / s.to_double_approx(), base.approx(), 1e-14 * base.approx());
  }
}
