// Two elliptic cylinders (cylinder_pair.hpp), each result against an independent route:
// - circular cylinders, crossed: the distance of the two axis lines |(c2 - c1).(a x b)| /
//   |a x b| minus both radii (MPFR), random rational axes (fixed seed, printed on failure);
//   parallel: the planar centre distance minus the radii;
// - elliptic cylinders (crossed and parallel): a float sampling of both surfaces never goes
//   below the certified lower bound and comes close to it; the pair lies on both surfaces;
// - rigid motions, scaling by 10^6, swapping, digits 15/100; overlapping crossed cylinders
//   are left to the exact topology (distance 0);
// - cylinders of other kinds with parallel rulings (hyperbolic, parabolic): the hyperbola-circle
//   closed form under a rigid motion, parabolas opening apart (d = 1 at the vertices), crossing
//   sections (a witness on both), and the pairs whose infimum may lie at infinity (never
//   certified).
#include "surfcert/certify/distance/cylinder_pair.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <cmath>
#include <random>

using namespace surfcert;
using core::Rational;
using surfcert::testing::hi;
using surfcert::testing::lo;
using surfcert::testing::motion;
using surfcert::testing::overlap;
using surfcert::testing::q;

namespace {

std::string r(long v) {
  return "(" + std::to_string(v) + ")";
}

// (x - c) - ((x - c).a) a / |a|^2 has squared length rho^2: a circular cylinder as an equation.
std::string circular(const std::array<long, 3>& c, const std::array<long, 3>& a, long rho) {
  const std::string X = "(x-" + r(c[0]) + ")", Y = "(y-" + r(c[1]) + ")", Z = "(z-" + r(c[2]) + ")";
  const long aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  const std::string dot =
      "(" + r(a[0]) + "*" + X + "+" + r(a[1]) + "*" + Y + "+" + r(a[2]) + "*" + Z + ")";
  return X + "^2+" + Y + "^2+" + Z + "^2 - " + dot + "^2/" + r(aa) + " = " + r(rho * rho);
}

double eval(const core::QuadricMatrix& m, const std::array<double, 3>& x) {
  const double X[4] = {x[0], x[1], x[2], 1};
  double s = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      s += m(i, j).to_double_approx() * X[i] * X[j];
  return s;
}

certify::DistanceResult dist(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                             long digits = 15) {
  return certify::surface_distance(a, b, digits, false);
}

} // namespace

TEST(CylinderPair, CrossedCircularClosedForm) {
  std::mt19937 rng(4242);
  std::uniform_int_distribution<long> c(-9, 9), ax(-4, 4), rad(1, 3);
  int checked = 0;
  for (int k = 0; k < 30; ++k) {
    std::array<long, 3> c1{c(rng), c(rng), c(rng)}, c2{c(rng), c(rng), c(rng)},
        a{ax(rng), ax(rng), ax(rng)}, b{ax(rng), ax(rng), ax(rng)};
    const long r1 = rad(rng), r2 = rad(rng);
    const std::array<long, 3> n{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                a[0] * b[1] - a[1] * b[0]};
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
    const long num =
        std::labs(n[0] * (c2[0] - c1[0]) + n[1] * (c2[1] - c1[1]) + n[2] * (c2[2] - c1[2]));
    const long nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    // axis distance num / sqrt(nn); disjoint iff num^2 > (r1 + r2)^2 nn
    if (num * num <= (r1 + r2) * (r1 + r2) * nn) continue;
    const auto A = q(circular(c1, a, r1)), B = q(circular(c2, b, r2));
    for (long digits : {15L, 100L}) {
      const auto res = dist(A, B, digits);
      ASSERT_EQ(res.status, certify::Status::Certified) << "seed 4242 case " << k << res.note;
      EXPECT_EQ(res.method, certify::Method::CylinderClosedForm);
      EXPECT_EQ(res.minimizers, "1");
      mpfr_t d, l, u;
      mpfr_inits2(1000, d, l, u, static_cast<mpfr_ptr>(nullptr));
      mpfr_set_si(d, nn, MPFR_RNDN);
      mpfr_sqrt(d, d, MPFR_RNDN);
      mpfr_si_div(d, num, d, MPFR_RNDN);
      mpfr_sub_si(d, d, r1 + r2, MPFR_RNDN);
      mpfr_set_str(l, res.lower().c_str(), 10, MPFR_RNDD);
      mpfr_set_str(u, res.upper().c_str(), 10, MPFR_RNDU);
      EXPECT_TRUE(mpfr_cmp(l, d) <= 0 && mpfr_cmp(d, u) <= 0)
          << "seed 4242 case " << k << " digits " << digits << ": " << res.lower();
      mpfr_clears(d, l, u, static_cast<mpfr_ptr>(nullptr));
    }
    const auto res = dist(A, B);
    for (const auto& p : res.pairs) {
      EXPECT_NEAR(eval(A, p[0]), 0, 1e-9 * (1 + std::fabs(eval(A, {0, 0, 0}))));
      EXPECT_NEAR(eval(B, p[1]), 0, 1e-9 * (1 + std::fabs(eval(B, {0, 0, 0}))));
      EXPECT_NEAR(std::hypot(p[0][0] - p[1][0], p[0][1] - p[1][1], p[0][2] - p[1][2]), res.approx(),
                  1e-9);
    }
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

TEST(CylinderPair, ParallelCircularClosedForm) {
  // Axes along (1, 2, 2); centres differ by (6, 0, -3), orthogonal to the axis: 3 sqrt(5) - 3.
  const auto A = q(circular({0, 0, 0}, {1, 2, 2}, 1)), B = q(circular({6, 0, -3}, {1, 2, 2}, 2));
  const auto res = dist(A, B, 50);
  ASSERT_EQ(res.status, certify::Status::Certified) << res.note;
  EXPECT_EQ(res.minimizers, "infinite");
  EXPECT_NEAR(lo(res), 3 * std::sqrt(5.0) - 3, 1e-14);
  EXPECT_LE(lo(res), 3 * std::sqrt(5.0) - 3 + 1e-15);
}

TEST(CylinderPair, EllipticAgainstSampling) {
  // Crossed: x^2/4 + y^2 = 1 (axis z) and (y - 6)^2/9 + (x + z)^2/2 = 1 (axis (1, 0, -1));
  // parallel: both along z. Points of each surface sampled on a grid.
  struct Case {
    const char *a, *b;
  } cases[] = {{"x^2/4 + y^2 = 1", "(y - 6)^2/9 + (x + z)^2/2 = 1"},
               {"x^2/4 + y^2 = 1", "(x - 5)^2/9 + (y - 3)^2 + (x - 5)*(y - 3)/2 = 1"}};
  for (const auto& cs : cases) {
    const auto A = q(cs.a), B = q(cs.b);
    const auto res = dist(A, B);
    ASSERT_EQ(res.status, certify::Status::Certified) << cs.b << res.note;
    ASSERT_FALSE(res.pairs.empty());
    EXPECT_NEAR(eval(A, res.pairs[0][0]), 0, 1e-9);
    EXPECT_NEAR(eval(B, res.pairs[0][1]), 0, 1e-9);
    // Sample: A as (2 cos s, sin s, z); B by solving its equation along y-lines (grid).
    double best = 1e300;
    std::vector<std::array<double, 3>> pa, pb;
    for (int i = 0; i < 360; ++i)
      for (int j = -10; j <= 10; ++j) {
        const double s = 2 * M_PI * i / 360;
        pa.push_back({2 * std::cos(s), std::sin(s), j * 0.5});
      }
    // B points: project grid points of a box onto B along x by the quadratic in x.
    for (int i = -60; i <= 60; ++i)
      for (int j = -10; j <= 10; ++j) {
        const double y = 3 + i * 0.1, z = j * 0.5;
        // B(x) = a2 x^2 + a1 x + a0 along the line (x, y, z)
        const double f0 = eval(B, {0, y, z}), f1 = eval(B, {1, y, z}), fm = eval(B, {-1, y, z});
        const double a2 = (f1 + fm) / 2 - f0, a1 = (f1 - fm) / 2, disc = a1 * a1 - 4 * a2 * f0;
        if (a2 == 0 || disc < 0) continue;
        for (int sg : {-1, 1})
          pb.push_back({(-a1 + sg * std::sqrt(disc)) / (2 * a2), y, z});
      }
    for (const auto& x : pa)
      for (const auto& y : pb) {
        const double d = std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]);
        if (d < best) best = d;
      }
    EXPECT_GE(best, lo(res) - 1e-12) << cs.b;
    EXPECT_LT(best - res.approx(), 0.2) << cs.b;
  }
}

TEST(CylinderPair, MotionsScalingSwapsAndOverlap) {
  const auto A = q("x^2/4 + y^2 = 1"), B = q("(y - 6)^2/9 + (x + z)^2/2 = 1");
  const auto base = dist(A, B, 30);
  const auto m = motion(2, -1, 3, 1, {Rational(5), Rational(-7, 2), Rational(1, 3)});
  EXPECT_TRUE(overlap(base, dist(A.congruent(m), B.congruent(m), 30)));
  const auto sw = dist(B, A, 30);
  EXPECT_TRUE(overlap(base, sw));
  ASSERT_FALSE(sw.pairs.empty());
  EXPECT_NEAR(sw.pairs[0][0][1], base.pairs[0][1][1], 1e-9);
  const auto sc = surfcert::testing::scaling(Rational(1000000));
  const auto big = dist(A.congruent(sc), B.congruent(sc), 15);
  EXPECT_NEAR(big.approx() / 1e6, base.approx(), 1e-14 * base.approx());
  // Crossing cylinders meet: the exact topology answers 0.
  const auto x = dist(q("x^2 + y^2 = 1"), q("(x - 1)^2 + z^2 = 1"));
  EXPECT_EQ(x.upper(), "0");
}

TEST(CylinderPair, ParallelNonEllipticSections) {
  // Cylinders of any kind with a common ruling direction (degenerate pencil: the exact
  // topology is silent, the section plane decides contact and distance).
  // Hyperbola x^2 - y^2 = 1 against the circle of radius rho about (c, 0): the nearest point
  // of the hyperbola to (c, 0) has x = c / 2 (c >= 2), so d = sqrt(c^2 / 2 - 1) - rho, at two
  // mirror pairs (lines of pairs along z); moved by a rational rigid motion, the same.
  const auto m = motion(1, 2, -2, 3, {Rational(3), Rational(-1, 2), Rational(7)});
  for (long c : {3, 4, 7})
    for (long rho_den : {1, 2}) {
      const auto H = q("x^2 - y^2 = 1");
      const auto C =
          q("(x - " + std::to_string(c) + ")^2 + y^2 = 1/" + std::to_string(rho_den * rho_den));
      mpfr_t d;
      mpfr_init2(d, 300);
      mpfr_set_si(d, c * c, MPFR_RNDN);
      mpfr_div_ui(d, d, 2, MPFR_RNDN);
      mpfr_sub_ui(d, d, 1, MPFR_RNDN);
      mpfr_sqrt(d, d, MPFR_RNDN);
      mpfr_t r;
      mpfr_init2(r, 300);
      mpfr_set_ui(r, 1, MPFR_RNDN);
      mpfr_div_ui(r, r, static_cast<unsigned long>(rho_den), MPFR_RNDN);
      mpfr_sub(d, d, r, MPFR_RNDN);
      mpfr_clear(r);
      for (bool moved : {false, true}) {
        const auto res = moved ? dist(H.congruent(m), C.congruent(m), 30) : dist(H, C, 30);
        ASSERT_EQ(res.status, certify::Status::Certified) << c << " " << rho_den << res.note;
        EXPECT_TRUE(surfcert::testing::contains(res, d))
            << "c " << c << " rho 1/" << rho_den << ": " << res.lower() << " " << res.upper();
        EXPECT_EQ(res.minimizers, "infinite");
        EXPECT_EQ(res.pairs.size(), 2u);
        if (!moved && !res.pairs.empty()) {
          EXPECT_NEAR(res.pairs[0][0][0], c / 2.0, 1e-9);
        }
      }
      mpfr_clear(d);
    }
  // Parabolas opening away from each other: d = 1 at the vertices (y-gap >= 1 + x^2 + x'^2);
  // the same opening (y = x^2, y = x^2 + 1): the gap tends to 0 at infinity, never certified.
  const auto P = q("y = x^2");
  const auto away = dist(P, q("y = -x^2 - 1"), 20);
  ASSERT_EQ(away.status, certify::Status::Certified) << away.note;
  EXPECT_LE(lo(away), 1.0);
  EXPECT_GE(hi(away), 1.0);
  EXPECT_NE(dist(P, q("y = x^2 + 1")).status, certify::Status::Certified);
  // The same opening but different widths (y = x^2 and 4y = x^2 - 1): far out the half-widths
  // grow like sqrt(y) with different factors, the minimum is attained: 1/4 at the vertices
  // (a float sampling of both parabolas never goes below it and reaches it).
  const auto wide = dist(P, q("4y = x^2 - 1"), 20);
  ASSERT_EQ(wide.status, certify::Status::Certified) << wide.note;
  double best = 1e300;
  for (int i = -2000; i <= 2000; ++i)
    for (int j = -2000; j <= 2000; j += 4) {
      const double t = i / 400.0, u = j / 200.0;
      best = std::min(best, std::hypot(t - u, t * t - (u * u - 1) / 4));
    }
  EXPECT_GE(best, lo(wide) - 1e-12);
  EXPECT_LT(best - hi(wide), 1e-9);
  // Nested hyperbolas with the same asymptotes (x^2 - y^2 = 1 and = 4): the gap tends to 0
  // at infinity, the infimum 0 is not attained; never certified as a positive distance.
  const auto nested = dist(q("x^2 - y^2 = 1"), q("x^2 - y^2 = 4"));
  EXPECT_NE(nested.status, certify::Status::Certified);
  EXPECT_EQ(nested.lower().empty() ? "0" : nested.lower(), "0");
  // Shifted hyperbolas x^2 - y^2 = 1 and (x - 6)^2 - y^2 = 1 cross at (3, +-2 sqrt 2): a sign
  // change on one sheet proves it (distance 0).
  const auto crossing = dist(q("x^2 - y^2 = 1"), q("(x - 6)^2 - y^2 = 1"));
  ASSERT_EQ(crossing.status, certify::Status::Certified) << crossing.note;
  EXPECT_EQ(crossing.upper(), "0");
  // Crossing sections (y = x^2 and y = 1 - x^2 meet at x = +-1/sqrt 2): distance 0 with an
  // approximate common point on both; swapped, the same.
  for (bool swap : {false, true}) {
    const auto A = P, B = q("y = 1 - x^2");
    const auto x = swap ? dist(B, A) : dist(A, B);
    ASSERT_EQ(x.status, certify::Status::Certified) << x.note;
    EXPECT_EQ(x.upper(), "0");
    ASSERT_FALSE(x.pairs.empty());
    const auto& w = x.pairs[0][0];
    EXPECT_NEAR(w[1], w[0] * w[0], 1e-6);
    EXPECT_NEAR(w[1], 1 - w[0] * w[0], 1e-6);
  }
}

TEST(CylinderPair, ParallelSectionsAtExtremes) {
  // The cross-section route and the common apex at scalings 10^+-8 (exact congruences: the
  // distance scales by s) and 10^6 from the origin (unchanged).
  const std::pair<const char*, const char*> pairs[] = {{"x^2 - y^2 = 1", "(x - 3)^2 + y^2 = 1"},
                                                       {"y = x^2", "y = -x^2 - 1"}};
  for (const auto& [a, b] : pairs) {
    const auto base = dist(q(a), q(b), 20);
    ASSERT_EQ(base.status, certify::Status::Certified) << base.note;
    const std::pair<const char*, Rational> scales[] = {{"100000000", Rational(100000000)},
                                                       {"0.00000001", Rational(1, 100000000)}};
    for (const auto& [s, factor] : scales) {
      const auto sc = surfcert::testing::scaling(factor);
      const auto r = dist(q(a).congruent(sc), q(b).congruent(sc), 20);
      ASSERT_EQ(r.status, certify::Status::Certified) << a << " " << s << ": " << r.note;
      EXPECT_TRUE(surfcert::testing::overlap_scaled(base, s, r)) << a << " " << s;
      EXPECT_EQ(r.minimizers, "infinite");
    }
    const auto far = motion(1, 0, 0, 0, {Rational(1000000), Rational(-1000000), Rational(1000000)});
    const auto t = dist(q(a).congruent(far), q(b).congruent(far), 20);
    ASSERT_EQ(t.status, certify::Status::Certified) << a << ": " << t.note;
    EXPECT_TRUE(overlap(base, t)) << a << ": " << t.lower() << " vs " << base.lower();
  }
}

namespace {

// The gap e: "0", a decimal power "1/10^k", or "2^-100" (as an equation term and in MPFR).
struct Gap {
  const char* term; // appended to the centre distance 2 in an equation
  long neg_pow10;   // e = 10^-k (0: e = 2^-100; -1: e = 0)
};

void set_gap(mpfr_t e, const Gap& g) {
  if (g.neg_pow10 < 0) {
    mpfr_set_zero(e, 1);
  } else if (g.neg_pow10 == 0) {
    mpfr_set_ui_2exp(e, 1, -100, MPFR_RNDN);
  } else {
    mpfr_set_ui(e, 10, MPFR_RNDN);
    mpfr_pow_si(e, e, -g.neg_pow10, MPFR_RNDN);
  }
}

const Gap kGaps[] = {
    {"", -1}, {"1/10^10", 10}, {"1/10^20", 20}, {"1/10^30", 30}, {"1/2^64/2^36", 0}};

} // namespace

TEST(CylinderPair, ParallelSectionsThatTouchOrBarelyOverlap) {
  // Unit circular cylinders with parallel axes at centre distance 2 - e (they overlap: the
  // sections cross at two points 2 sqrt(e) apart, nearly tangent; e = 0: they touch along a
  // ruling) and 2 + e (apart by exactly e). Was undecided ("may meet or touch") for every
  // e <= 10^-10: the sign-change probes cannot see a lens 10^-30 thick. Also under a rational
  // rigid motion (the axes along an irrational unit direction).
  const auto mv = motion(1, 2, 3, 4, {Rational(1, 3), Rational(-2), Rational(5, 7)});
  for (const Gap& g : kGaps) {
    for (int side : {-1, 1}) {
      if (g.neg_pow10 < 0 && side > 0) continue;
      const std::string c =
          std::string("(2") + (side < 0 ? "-" : "+") + (*g.term ? g.term : "0") + ")";
      const auto A = q("x^2 + y^2 = 1"), B = q("(x - " + c + ")^2 + y^2 = 1");
      for (bool moved : {false, true}) {
        const auto a = moved ? A.congruent(mv) : A, b = moved ? B.congruent(mv) : B;
        for (bool swap : {false, true}) {
          const auto r = swap ? dist(b, a, 20) : dist(a, b, 20);
          const std::string what = c + (moved ? " moved" : "") + (swap ? " swapped" : "");
          ASSERT_EQ(r.status, certify::Status::Certified) << what << ": " << r.note;
          EXPECT_EQ(r.minimizers, "infinite") << what;
          mpfr_t e;
          mpfr_init2(e, 400);
          set_gap(e, g);
          if (side < 0) mpfr_set_zero(e, 1); // overlapping or touching: distance 0
          EXPECT_TRUE(surfcert::testing::contains(r, e))
              << what << ": [" << r.lower() << ", " << r.upper() << "]";
          if (side > 0) {
            EXPECT_GT(lo(r), 0) << what; // apart: never 0
          }
          mpfr_clear(e);
        }
      }
    }
  }
}

TEST(CylinderPair, CoaxialCylindersOfRevolution) {
  // x^2 + y^2 = R1 against x^2 + y^2 = R2: |sqrt R1 - sqrt R2| on every ray from the axis (was
  // undecided: the meridian system is a pair of parallel lines, a curve of solutions).
  for (const char* r2 : {"4", "1 + 1/10^10", "1 + 1/10^30", "1 + 1/2^64/2^36", "0"}) {
    const auto A = q("x^2 + y^2 = 1"), B = q(std::string("x^2 + y^2 = ") + r2);
    // MPFR: sqrt(R2) - 1 at 2000 bits, R2 from the same text.
    mpfr_t d, t;
    mpfr_inits2(2000, d, t, static_cast<mpfr_ptr>(nullptr));
    const std::string s = r2;
    if (s == "4") {
      mpfr_set_ui(d, 4, MPFR_RNDN);
    } else if (s == "0") {
      mpfr_set_zero(d, 1);
    } else if (s == "1 + 1/2^64/2^36") {
      mpfr_set_ui_2exp(d, 1, -100, MPFR_RNDN);
      mpfr_add_ui(d, d, 1, MPFR_RNDN);
    } else {
      mpfr_set_ui(d, 10, MPFR_RNDN);
      mpfr_pow_si(d, d, s.find("10^10") != std::string::npos ? -10 : -30, MPFR_RNDN);
      mpfr_add_ui(d, d, 1, MPFR_RNDN);
    }
    mpfr_sqrt(d, d, MPFR_RNDN);
    mpfr_sub_ui(d, d, 1, MPFR_RNDN);
    mpfr_abs(d, d, MPFR_RNDN);
    for (long digits : {15L, 60L})
      for (bool swap : {false, true}) {
        const auto r = swap ? dist(B, A, digits) : dist(A, B, digits);
        ASSERT_EQ(r.status, certify::Status::Certified) << r2 << ": " << r.note;
        EXPECT_EQ(r.minimizers, "infinite") << r2;
        EXPECT_TRUE(surfcert::testing::contains(r, d))
            << r2 << " digits " << digits << ": [" << r.lower() << ", " << r.upper() << "]";
      }
    mpfr_clears(d, t, static_cast<mpfr_ptr>(nullptr));
  }
  // About the axis (1, 1, 1) (|a| = sqrt 3 irrational), radii 1 and 2, moved rigidly: 1.
  const auto mv = motion(2, -1, 3, 1, {Rational(7), Rational(-1, 2), Rational(3)});
  const auto A = q(circular({0, 0, 0}, {1, 1, 1}, 1)).congruent(mv),
             B = q(circular({0, 0, 0}, {1, 1, 1}, 2)).congruent(mv);
  const auto r = dist(A, B, 30);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  EXPECT_EQ(r.minimizers, "infinite");
  EXPECT_EQ(r.lower(), "1");
  EXPECT_EQ(r.upper(), "1");
  for (const auto& p : r.pairs) { // the shown pair lies on both surfaces, 1 apart
    EXPECT_NEAR(eval(A, p[0]), 0, 1e-9);
    EXPECT_NEAR(eval(B, p[1]), 0, 1e-9);
    EXPECT_NEAR(std::hypot(p[0][0] - p[1][0], p[0][1] - p[1][1], p[0][2] - p[1][2]), 1, 1e-9);
  }
}

TEST(CylinderPair, SectionsTangentAtAnIrrationalPoint) {
  // The circle x^2 + (y - 1)^2 = 16/3 touches the ellipse x^2/4 + y^2 = 1 at (+-4 sqrt(2)/3,
  // -1/3) (substituting x^2 = 4 - 4 y^2 leaves -3 (y + 1/3)^2): as cylinders along z they
  // touch along two rulings (no rational point, no transversal crossing: was undecided). With
  // R^2 = 16/3 - e they cross (0); with 16/3 + e the circle holds the ellipse, and the distance
  // is sqrt(16/3 + e) - sqrt(16/3) (MPFR), probed at e = 10^-10, 10^-30, 2^-100; and in a
  // moved frame.
  const auto mv = motion(3, 1, -2, 1, {Rational(1, 2), Rational(5), Rational(-7, 3)});
  for (const Gap& g : kGaps) {
    for (int side : {-1, 1}) {
      if (g.neg_pow10 < 0 && side > 0) continue;
      const std::string r2 =
          std::string("16/3") + (side < 0 ? " - " : " + ") + (*g.term ? g.term : "0");
      const auto A = q("x^2/4 + y^2 = 1"), B = q("x^2 + (y - 1)^2 = " + r2);
      for (bool moved : {false, true}) {
        const auto a = moved ? A.congruent(mv) : A, b = moved ? B.congruent(mv) : B;
        const auto r = dist(a, b, 20);
        const std::string what = r2 + (moved ? " moved" : "");
        ASSERT_EQ(r.status, certify::Status::Certified) << what << ": " << r.note;
        mpfr_t e, d;
        mpfr_inits2(600, e, d, static_cast<mpfr_ptr>(nullptr));
        if (side < 0) {
          mpfr_set_zero(d, 1);
        } else {
          set_gap(e, g);
          mpfr_set_ui(d, 16, MPFR_RNDN);
          mpfr_div_ui(d, d, 3, MPFR_RNDN);
          mpfr_add(e, e, d, MPFR_RNDN);
          mpfr_sqrt(e, e, MPFR_RNDN);
          mpfr_sqrt(d, d, MPFR_RNDN);
          mpfr_sub(d, e, d, MPFR_RNDN);
          EXPECT_GT(lo(r), 0) << what;
        }
        EXPECT_TRUE(surfcert::testing::contains(r, d))
            << what << ": [" << r.lower() << ", " << r.upper() << "]";
        mpfr_clears(e, d, static_cast<mpfr_ptr>(nullptr));
      }
    }
  }
}
