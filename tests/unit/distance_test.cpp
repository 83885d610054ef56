// Certified distance (first capability: a sphere against any quadric) against closed forms:
// sphere-sphere (separated, nested, concentric, touching, intersecting), sphere-plane,
// sphere-ellipsoid along an axis, cylinder-sphere, cone-sphere; rigid-motion invariance; two
// precisions overlap; unsupported pairs stay undecided (never guessed). The sphere route at
// small gaps (the width contract against cancellation in d - r) and at near ties (two foot
// points whose distances differ by 2 eps: the nearer one must be certified, on both sides,
// in both modes), checked against closed forms computed in MPFR at 2000 bits.
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

using namespace surfcert;

namespace {

core::QuadricMatrix q(const std::string& s) {
  return core::io::quadric_from_equation(s, {"t", 1, 1, ""});
}

// lower <= expect <= upper, compared in MPFR at 400 bits (expect given as a decimal string or
// computed by the caller with mpfr).
void expect_contains(const certify::DistanceResult& r, const mpfr_t expect,
                     const std::string& ctx) {
  ASSERT_EQ(r.status, certify::Status::Certified) << ctx << " " << r.note;
  mpfr_t lo, hi;
  mpfr_inits2(400, lo, hi, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(lo, r.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(hi, r.upper().c_str(), 10, MPFR_RNDU);
  EXPECT_LE(mpfr_cmp(lo, expect), 0) << ctx << " lower " << r.lower();
  EXPECT_GE(mpfr_cmp(hi, expect), 0) << ctx << " upper " << r.upper();
  mpfr_clears(lo, hi, static_cast<mpfr_ptr>(nullptr));
}

// sqrt(p/q) - (u/v) at 400 bits.
void closed_form(mpfr_t out, const core::Rational& under_sqrt, const core::Rational& minus) {
  mpfr_t t;
  mpfr_init2(t, 400);
  mpfr_set_str(out, under_sqrt.num().to_string().c_str(), 10, MPFR_RNDN);
  mpfr_set_str(t, under_sqrt.den().to_string().c_str(), 10, MPFR_RNDN);
  mpfr_div(out, out, t, MPFR_RNDN);
  mpfr_sqrt(out, out, MPFR_RNDN);
  mpfr_set_str(t, minus.num().to_string().c_str(), 10, MPFR_RNDN);
  mpfr_div_ui(t, t, 1, MPFR_RNDN);
  mpfr_t u;
  mpfr_init2(u, 400);
  mpfr_set_str(u, minus.den().to_string().c_str(), 10, MPFR_RNDN);
  mpfr_div(t, t, u, MPFR_RNDN);
  mpfr_sub(out, out, t, MPFR_RNDN);
  mpfr_clears(t, u, static_cast<mpfr_ptr>(nullptr));
}

void check(const std::string& a, const std::string& b, const core::Rational& under_sqrt,
           const core::Rational& minus, const std::string& ctx, long digits = 15) {
  mpfr_t e;
  mpfr_init2(e, 400);
  closed_form(e, under_sqrt, minus);
  auto r = certify::surface_distance(q(a), q(b), digits, false);
  expect_contains(r, e, ctx);
  auto s = certify::surface_distance(q(b), q(a), digits, false); // swapping swaps the points
  expect_contains(s, e, ctx + " (swapped)");
  if (!r.pairs.empty() && !s.pairs.empty()) {
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_NEAR(r.pairs[0][0][i], s.pairs[0][1][i], 1e-9) << ctx;
      EXPECT_NEAR(r.pairs[0][1][i], s.pairs[0][0][i], 1e-9) << ctx;
    }
  }
  mpfr_clear(e);
}

} // namespace

TEST(Distance, SphereSphereClosedForms) {
  using core::Rational;
  check("x^2+y^2+z^2=1", "(x-3)^2+y^2+z^2=1", Rational(9), Rational(2), "separated: 3 - 2");
  check("x^2+y^2+z^2=9", "(x-1)^2+y^2+z^2=1", Rational(9), Rational(2), "nested: 3 - (1 + 1)");
  auto conc = certify::surface_distance(q("x^2+y^2+z^2=9"), q("x^2+y^2+z^2=1"), 15, false);
  EXPECT_EQ(conc.minimizers, "infinite");
  mpfr_t two;
  mpfr_init2(two, 400);
  mpfr_set_ui(two, 2, MPFR_RNDN);
  expect_contains(conc, two, "concentric: 3 - 1");
  mpfr_clear(two);
  for (const char* b : {"(x-2)^2+y^2+z^2=1", "(x-1)^2+y^2+z^2=1"}) {
    auto r = certify::surface_distance(q("x^2+y^2+z^2=1"), q(b), 15, false);
    EXPECT_EQ(r.status, certify::Status::Certified) << b;
    EXPECT_EQ(r.upper(), "0") << b;
    ASSERT_FALSE(r.pairs.empty()) << b;
    auto w = r.pairs[0][0]; // witness on both spheres
    EXPECT_NEAR(w[0] * w[0] + w[1] * w[1] + w[2] * w[2], 1.0, 1e-9) << b;
  }
}

TEST(Distance, SpherePlaneEllipsoidCylinderCone) {
  using core::Rational;
  check("(x-1)^2+y^2+(z-5)^2=4", "z=1", Rational(16), Rational(2), "sphere-plane: 4 - 2");
  check("(x-3)^2+y^2+z^2=1/4", "x^2/4+y^2+z^2/9=1", Rational(1), Rational(1, 2),
        "sphere-ellipsoid on the axis: 1 - 1/2");
  check("(x-3)^2+y^2+z^2=1/4", "x^2+y^2=1", Rational(4), Rational(1, 2), "cylinder: 2 - 1/2");
  check("x^2+y^2+(z+5)^2=1", "x^2+y^2-z^2", Rational(25, 2), Rational(1), "cone: 5/sqrt2 - 1");
}

TEST(Distance, EllipsoidPlaneClosedForm) {
  using core::Rational;
  // x^2/4 + y^2 + z^2/9 = 1: support in direction n is sqrt(4 n1^2 + n2^2 + 9 n3^2).
  check("x^2/4+y^2+z^2/9=1", "x=5", Rational(9), Rational(0), "plane x = 5: 5 - 2");
  // Plane x + y = 10: (10 - sqrt 5) / sqrt 2 = sqrt(50) - sqrt(5/2); check as a bracket.
  auto r = certify::surface_distance(q("x^2/4+y^2+z^2/9=1"), q("x+y=10"), 40, false);
  mpfr_t e, t;
  mpfr_inits2(400, e, t, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_ui(e, 50, MPFR_RNDN);
  mpfr_sqrt(e, e, MPFR_RNDN);
  mpfr_set_d(t, 2.5, MPFR_RNDN);
  mpfr_sqrt(t, t, MPFR_RNDN);
  mpfr_sub(e, e, t, MPFR_RNDN);
  expect_contains(r, e, "plane x + y = 10");
  mpfr_clears(e, t, static_cast<mpfr_ptr>(nullptr));
  // The plane x = 1 cuts the ellipsoid, z = 3 touches it at a pole: distance 0.
  auto cut = certify::surface_distance(q("x^2/4+y^2+z^2/9=1"), q("x=1"), 15, false);
  EXPECT_EQ(cut.upper(), "0");
  EXPECT_EQ(cut.minimizers, "infinite");
  auto touch = certify::surface_distance(q("x^2/4+y^2+z^2/9=1"), q("z=3"), 15, false);
  EXPECT_EQ(touch.upper(), "0");
  EXPECT_EQ(touch.minimizers, "1");
}

TEST(Distance, RigidMotionAndPrecision) {
  // Sphere around (3, 1/2, 0) radius 1/4 vs the ellipsoid x^2/4 + y^2 + z^2/9 = 1, and the
  // same pair rotated by the integer quaternion (1,2,2,1) and translated: same enclosures.
  auto a = q("(x-3)^2+(y-1/2)^2+z^2=1/16"), b = q("x^2/4+y^2+z^2/9=1");
  const long w = 1, x = 2, y = 2, z = 1;
  core::Rational n(w * w + x * x + y * y + z * z);
  long R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                  {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                  {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  core::Rational t[3] = {core::Rational(1, 3), core::Rational(-2, 7), core::Rational(5, 4)};
  core::Mat4 p;
  for (size_t i = 0; i < 3; ++i) {
    core::Rational s;
    for (size_t j = 0; j < 3; ++j) {
      p[i][j] = core::Rational(R[j][i]) / n;
      s += p[i][j] * t[j];
    }
    p[i][3] = -s;
  }
  p[3][3] = core::Rational(1);
  auto r0 = certify::surface_distance(a, b, 30, false);
  auto r1 = certify::surface_distance(a.congruent(p), b.congruent(p), 30, false);
  auto r2 = certify::surface_distance(a, b, 60, false);
  ASSERT_EQ(r0.status, certify::Status::Certified) << r0.note;
  ASSERT_EQ(r1.status, certify::Status::Certified) << r1.note;
  ASSERT_EQ(r2.status, certify::Status::Certified) << r2.note;
  mpfr_t l0, u0, l1, u1, l2, u2;
  mpfr_inits2(600, l0, u0, l1, u1, l2, u2, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(l0, r0.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u0, r0.upper().c_str(), 10, MPFR_RNDU);
  mpfr_set_str(l1, r1.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u1, r1.upper().c_str(), 10, MPFR_RNDU);
  mpfr_set_str(l2, r2.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u2, r2.upper().c_str(), 10, MPFR_RNDU);
  EXPECT_TRUE(mpfr_cmp(l0, u1) <= 0 && mpfr_cmp(l1, u0) <= 0) << r0.lower() << " " << r1.lower();
  EXPECT_TRUE(mpfr_cmp(l0, u2) <= 0 && mpfr_cmp(l2, u0) <= 0) << "30 vs 60 digits";
  // 60 digits: relative width <= 1e-60.
  mpfr_sub(u2, u2, l2, MPFR_RNDU);
  mpfr_div(u2, u2, l2, MPFR_RNDU);
  EXPECT_LE(mpfr_get_d(u2, MPFR_RNDU), 1e-59);
  // The enclosure contains the distance of no pair of surface points below it: a float search
  // over the ellipsoid gives an upper bound >= lower.
  double best = 1e300;
  for (int i = 0; i <= 400; ++i)
    for (int j = 0; j <= 400; ++j) {
      double th = M_PI * i / 400, ph = 2 * M_PI * j / 400;
      double ex = 2 * std::sin(th) * std::cos(ph), ey = std::sin(th) * std::sin(ph),
             ez = 3 * std::cos(th);
      double d = std::sqrt((ex - 3) * (ex - 3) + (ey - 0.5) * (ey - 0.5) + ez * ez) - 0.25;
      best = std::min(best, d);
    }
  EXPECT_LE(mpfr_get_d(l0, MPFR_RNDD), best);
  EXPECT_LT(best - mpfr_get_d(u0, MPFR_RNDU), 1e-3); // and the grid comes close
  mpfr_clears(l0, u0, l1, u1, l2, u2, static_cast<mpfr_ptr>(nullptr));
}

TEST(Distance, UnsupportedPairsAreNotGuessed) {
  // Two coaxial paraboloids of revolution: every tried offset system has a curve of solutions
  // (revolution symmetry); the answer must be undecided, not a guess.
  auto r = certify::surface_distance(q("z = x^2 + y^2"), q("z = x^2 + y^2 + 1"), 15, false);
  EXPECT_NE(r.status, certify::Status::Certified) << r.lower();
}

namespace {

// Decimal digits of 2^-100 and of the offsets used below, as rational text.
const char* const kTwoPow100 = "1267650600228229401496703205376";
const char* const kTwoPow60 = "1152921504606846976";
const char* const kTwoPow93 = "9903520314283042199192993792";

// 1/den in MPFR at 2000 bits (den an integer in decimal).
void inverse(mpfr_t out, const std::string& den) {
  mpfr_set_str(out, den.c_str(), 10, MPFR_RNDN); // exact: an integer below 2^2000
  mpfr_ui_div(out, 1, out, MPFR_RNDN);
}

// Certified, relative width <= 10^-digits, and the enclosure holds `truth` (lower AND upper).
void expect_certified_around(const certify::DistanceResult& r, const mpfr_t truth, long digits,
                             const std::string& ctx) {
  ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
  EXPECT_TRUE(surfcert::testing::contains(r, truth))
      << ctx << ": [" << r.lower() << ", " << r.upper() << "]";
  EXPECT_LE(surfcert::testing::log10_rel_width(r), -static_cast<double>(digits))
      << ctx << ": [" << r.lower() << ", " << r.upper() << "]";
}

// upper < x (read with outward rounding at 4000 bits): the enclosure excludes x from above.
bool upper_below(const certify::DistanceResult& r, const mpfr_t x) {
  mpfr_t u;
  mpfr_init2(u, 4000);
  mpfr_set_str(u, r.upper().c_str(), 10, MPFR_RNDU);
  const bool ok = mpfr_cmp(u, x) < 0;
  mpfr_clear(u);
  return ok;
}

} // namespace

TEST(Distance, SphereRouteSmallGapMeetsWidth) {
  mpfr_t e;
  mpfr_init2(e, 2000);
  // Cone x^2 + y^2 = z^2 (half-angle 45 deg) and the sphere about (0,0,2) of radius
  // (2 - t)/sqrt 2: the centre is 2 sin 45 = sqrt 2 from the cone, so d = t / sqrt 2.
  for (long digits : {15L, 20L}) {
    inverse(e, kTwoPow60);
    mpfr_t s2;
    mpfr_init2(s2, 2000);
    mpfr_sqrt_ui(s2, 2, MPFR_RNDN);
    mpfr_div(e, e, s2, MPFR_RNDN); // 2^-60 / sqrt 2
    mpfr_clear(s2);
    auto r = certify::surface_distance(
        q("x^2+y^2=z^2"), q(std::string("x^2+y^2+(z-2)^2=(2-1/") + kTwoPow60 + ")^2/2"), digits,
        false);
    expect_certified_around(r, e, digits,
                            "cone, gap 2^-60/sqrt2, digits " + std::to_string(digits));
    EXPECT_EQ(r.minimizers, "infinite"); // a circle of feet around the axis
  }
  // The ellipsoid 4(x - 1/2 + delta)^2 + 25y^2/9 + 9z^2/4 = 1 inside the unit ball: on it
  // |p|^2 <= x^2 + (4/9)(1 - 4(x - h)^2) (h = 1/2 - delta), increasing in x up to the vertex
  // x = 1 - delta, so the farthest point is the vertex and d = 1 - (1 - delta) = delta.
  for (long digits : {15L, 20L, 40L}) {
    inverse(e, kTwoPow93);
    auto r = certify::surface_distance(
        q("x^2+y^2+z^2=1"), q(std::string("4(x-1/2+1/") + kTwoPow93 + ")^2+25y^2/9+9z^2/4=1"),
        digits, false);
    expect_certified_around(r, e, digits,
                            "ellipsoid inside, gap 2^-93, digits " + std::to_string(digits));
    EXPECT_EQ(r.minimizers, "1");
  }
  mpfr_clear(e);
}

TEST(Distance, SphereRouteWidthThresholdProbes) {
  // Gaps 1e-10, 1e-20, 1e-30, 2^-100, on both sides: the quadric outside the ball (cone,
  // d = t / sqrt 2), inside it (the ellipsoid above, d = delta), and a plane (d = t).
  const std::string dens[] = {"10000000000", "100000000000000000000",
                              "1000000000000000000000000000000", kTwoPow100};
  mpfr_t e, s2;
  mpfr_inits2(2000, e, s2, static_cast<mpfr_ptr>(nullptr));
  mpfr_sqrt_ui(s2, 2, MPFR_RNDN);
  for (const auto& den : dens)
    for (bool exact : {false, true}) {
      const auto mode = exact ? certify::Mode::Exact : certify::Mode::Filtered;
      const std::string ctx = "gap 1/" + den + (exact ? " exact" : " filtered");
      inverse(e, den);
      mpfr_div(e, e, s2, MPFR_RNDN);
      auto cone = certify::surface_distance(
          q("x^2+y^2=z^2"), q("x^2+y^2+(z-2)^2=(2-1/" + den + ")^2/2"), 15, false, mode);
      expect_certified_around(cone, e, 15, "cone, " + ctx);
      inverse(e, den);
      auto ell = certify::surface_distance(
          q("x^2+y^2+z^2=1"), q("4(x-1/2+1/" + den + ")^2+25y^2/9+9z^2/4=1"), 15, false, mode);
      expect_certified_around(ell, e, 15, "ellipsoid inside, " + ctx);
      auto plane =
          certify::surface_distance(q("x^2+y^2+z^2=1"), q("z=1+1/" + den), 15, false, mode);
      expect_certified_around(plane, e, 15, "plane, " + ctx);
    }
  // A plane at 2^-200: the closed form d = (q - r^2) / (dc + r) does not cancel.
  mpfr_set_ui(e, 1, MPFR_RNDN);
  mpfr_div_2ui(e, e, 200, MPFR_RNDN);
  auto plane = certify::surface_distance(
      q("x^2+y^2+z^2=1"), q("z=1+1/1606938044258990275541962092341162602522202993782792835301376"),
      15, false, certify::Mode::Exact);
  expect_certified_around(plane, e, 15, "plane, gap 2^-200");
  mpfr_clears(e, s2, static_cast<mpfr_ptr>(nullptr));
}

TEST(Distance, SphereRouteNearTies) {
  // Two foot points at 3/2 - eps and 3/2 + eps from the centre of a unit sphere: the ellipsoid
  // x^2/9 + y^2/4 + z^2/(9/4) = 1 (shortest semi-axis 3/2 along z, centre shifted along z)
  // and the throat of the one-sheeted hyperboloid x^2/4 + y^2/(9/4) - z^2 = 1 (on it
  // x^2 + y^2 + z^2 >= 9/4 (1 + z^2) + z^2, so the throat's short axis is nearest; centre
  // shifted along y). Truth 1/2 - eps; the farther candidate gives 1/2 + eps.
  const std::string dens[] = {"10000000000", "100000000000000000000",
                              "1000000000000000000000000000000", kTwoPow100};
  mpfr_t truth, far, e;
  mpfr_inits2(2000, truth, far, e, static_cast<mpfr_ptr>(nullptr));
  for (const auto& den : dens)
    for (const char* sign : {"-", "+"})
      for (bool exact : {true, false})
        for (bool hyperboloid : {false, true}) {
          const auto mode = exact ? certify::Mode::Exact : certify::Mode::Filtered;
          const std::string off = std::string(sign) + "1/" + den;
          const std::string ctx = std::string(hyperboloid ? "hyperboloid" : "ellipsoid") +
                                  " offset " + off + (exact ? " exact" : " filtered");
          inverse(e, den);
          mpfr_set_ui(truth, 1, MPFR_RNDN);
          mpfr_div_2ui(truth, truth, 1, MPFR_RNDN);
          mpfr_add(far, truth, e, MPFR_RNDN); // exact at 2000 bits
          mpfr_sub(truth, truth, e, MPFR_RNDN);
          const std::string quad = hyperboloid ? "x^2/4+4y^2/9-z^2=1" : "x^2/9+y^2/4+4z^2/9=1";
          const std::string sph =
              hyperboloid ? "x^2+(y" + off + ")^2+z^2=1" : "x^2+y^2+(z" + off + ")^2=1";
          auto r = certify::surface_distance(q(sph), q(quad), 15, false, mode);
          expect_certified_around(r, truth, 15, ctx);
          // 2 eps >= 1e-10 relative is far above 10^-15: the farther candidate is excluded.
          if (den == "10000000000") {
            EXPECT_TRUE(upper_below(r, far)) << ctx << " " << r.upper();
          }
          // The sphere route separates the two within its budget (2 digits + 40): one
          // minimizer. (Filtered mode answers the ellipsoid by convex duality.)
          if (exact || hyperboloid) {
            EXPECT_EQ(r.minimizers, "1") << ctx;
            EXPECT_EQ(r.ties, certify::Ties::None) << ctx;
            EXPECT_EQ(r.pairs.size(), 1u) << ctx;
          }
        }
  mpfr_clears(truth, far, e, static_cast<mpfr_ptr>(nullptr));
}

TEST(Distance, SphereRouteExactTieIsProven) {
  // Centre exactly at the centre: two foot points at the same rational squared distance.
  mpfr_t h;
  mpfr_init2(h, 2000);
  mpfr_set_d(h, 0.5, MPFR_RNDN);
  for (const char* quad : {"x^2/9+y^2/4+4z^2/9=1", "x^2/4+4y^2/9-z^2=1"}) {
    auto r =
        certify::surface_distance(q("x^2+y^2+z^2=1"), q(quad), 15, false, certify::Mode::Exact);
    expect_certified_around(r, h, 15, quad);
    EXPECT_EQ(r.minimizers, "2") << quad;
    EXPECT_EQ(r.ties, certify::Ties::Proven) << quad << " " << r.note;
    EXPECT_EQ(r.pairs.size(), 2u) << quad;
  }
  mpfr_clear(h);
}

TEST(Distance, SphereRouteNearTiesInsideAndUnseparated) {
  // Inside the ball (r - d_max): the ellipsoid x^2 + 4y^2/9 + z^2/9 = 1 (longest semi-axis 3
  // along z) in the ball of radius 4 about (0, 0, eps): the farthest points are the poles at
  // 3 + |eps| and 3 - |eps|; truth 1 - |eps|, the wrong pole gives 1 + |eps|.
  const std::string dens[] = {"10000000000", "100000000000000000000", kTwoPow100};
  mpfr_t truth, far, e;
  mpfr_inits2(2000, truth, far, e, static_cast<mpfr_ptr>(nullptr));
  for (const auto& den : dens)
    for (const char* sign : {"-", "+"})
      for (bool exact : {true, false}) {
        const std::string off = std::string(sign) + "1/" + den;
        const std::string ctx = "inside, offset " + off + (exact ? " exact" : " filtered");
        inverse(e, den);
        mpfr_set_ui(truth, 1, MPFR_RNDN);
        mpfr_add(far, truth, e, MPFR_RNDN);
        mpfr_sub(truth, truth, e, MPFR_RNDN);
        auto r = certify::surface_distance(q("x^2+y^2+(z" + off + ")^2=16"),
                                           q("x^2+4y^2/9+z^2/9=1"), 15, false,
                                           exact ? certify::Mode::Exact : certify::Mode::Filtered);
        expect_certified_around(r, truth, 15, ctx);
        if (den == "10000000000") {
          EXPECT_TRUE(upper_below(r, far)) << ctx << " " << r.upper();
        }
        if (exact) {
          EXPECT_EQ(r.minimizers, "1") << ctx;
        }
      }
  // Beyond the separation budget (offset 1e-200 at 15 digits): both candidates are listed and
  // the tie is reported unproven; the enclosure [min lower, min upper] - r still holds the
  // truth 1/2 - 1e-200.
  const std::string tiny = "1" + std::string(200, '0');
  inverse(e, tiny);
  mpfr_set_d(truth, 0.5, MPFR_RNDN);
  mpfr_sub(truth, truth, e, MPFR_RNDN);
  for (bool hyperboloid : {false, true}) {
    auto r = certify::surface_distance(
        q(hyperboloid ? "x^2+(y-1/" + tiny + ")^2+z^2=1" : "x^2+y^2+(z-1/" + tiny + ")^2=1"),
        q(hyperboloid ? "x^2/4+4y^2/9-z^2=1" : "x^2/9+y^2/4+4z^2/9=1"), 15, false,
        certify::Mode::Exact);
    expect_certified_around(r, truth, 15, hyperboloid ? "hyperboloid 1e-200" : "ellipsoid 1e-200");
    // Not separated within the budget and not proven equal: the true minimizer is unique, so
    // the count must not read "2" — it is "undecided" with both candidates kept.
    EXPECT_EQ(r.minimizers, "undecided");
    EXPECT_EQ(r.minimizer_candidates(), 2);
    EXPECT_EQ(r.ties, certify::Ties::Unproven) << r.note;
  }
  mpfr_clears(truth, far, e, static_cast<mpfr_ptr>(nullptr));
}
