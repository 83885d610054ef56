// Point-quadric critical distances against closed forms: sphere, axis-aligned ellipsoid (on an
// axis and at the centre, with a brute-force check of the minimum), cylinder, cone (vertex
// candidate and the generatrix minimum 5/sqrt(2) at 50 digits), two precisions overlap, and a
// point on the axis of an ellipsoid of revolution (a continuum of foot points); at near ties
// front() still encloses the minimum (sorted by certified lower bounds).
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <cmath>

using namespace surfcert;
using core::Rational;

namespace {

core::QuadricMatrix q(const std::string& s) {
  return core::io::quadric_from_equation(s, {"t", 1, 1, ""});
}

std::array<Rational, 3> pt(long a, long b, long c) {
  return {Rational(a), Rational(b), Rational(c)};
}

// lower <= expect <= upper at 400 bits.
bool contains(const certify::CriticalDistance& c, const mpfr_t expect) {
  mpfr_t lo, hi;
  mpfr_inits2(400, lo, hi, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(lo, c.lower.c_str(), 10, MPFR_RNDD);
  mpfr_set_str(hi, c.upper.c_str(), 10, MPFR_RNDU);
  bool ok = mpfr_cmp(lo, expect) <= 0 && mpfr_cmp(hi, expect) >= 0;
  mpfr_clears(lo, hi, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

// (upper - lower) / expect
double rel_width(const certify::CriticalDistance& c, const mpfr_t expect) {
  mpfr_t lo, hi;
  mpfr_inits2(400, lo, hi, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(lo, c.lower.c_str(), 10, MPFR_RNDD);
  mpfr_set_str(hi, c.upper.c_str(), 10, MPFR_RNDU);
  mpfr_sub(hi, hi, lo, MPFR_RNDU);
  mpfr_div(hi, hi, expect, MPFR_RNDU);
  double w = mpfr_get_d(hi, MPFR_RNDU);
  mpfr_clears(lo, hi, static_cast<mpfr_ptr>(nullptr));
  return w;
}

void set_value(mpfr_t out, double num, double under_sqrt = 1.0) {
  mpfr_set_d(out, under_sqrt, MPFR_RNDN);
  mpfr_sqrt(out, out, MPFR_RNDN);
  mpfr_mul_d(out, out, num, MPFR_RNDN);
}

// Index of the critical whose enclosure holds num*sqrt(under_sqrt), or -1.
int find_value(const certify::PointQuadricResult& r, double num, double under_sqrt = 1.0) {
  mpfr_t e;
  mpfr_init2(e, 400);
  set_value(e, num, under_sqrt);
  int found = -1;
  for (size_t i = 0; i < r.criticals.size(); ++i)
    if (contains(r.criticals[i], e)) {
      found = static_cast<int>(i);
      break;
    }
  mpfr_clear(e);
  return found;
}

double lower_d(const certify::CriticalDistance& c) {
  mpfr_t lo;
  mpfr_init2(lo, 400);
  mpfr_set_str(lo, c.lower.c_str(), 10, MPFR_RNDD);
  double v = mpfr_get_d(lo, MPFR_RNDD);
  mpfr_clear(lo);
  return v;
}

} // namespace

TEST(PointQuadric, SphereOffCentre) {
  auto r = certify::point_quadric_critical(pt(4, 0, 0), q("(x-1)^2 + y^2 + z^2 - 4"), 15);
  ASSERT_TRUE(r.ok) << r.note;
  ASSERT_EQ(r.criticals.size(), 2u);
  mpfr_t e;
  mpfr_init2(e, 400);
  set_value(e, 1);
  EXPECT_TRUE(contains(r.criticals[0], e)) << r.criticals[0].lower << " " << r.criticals[0].upper;
  EXPECT_LE(rel_width(r.criticals[0], e), 1e-15);
  set_value(e, 5);
  EXPECT_TRUE(contains(r.criticals[1], e)) << r.criticals[1].lower << " " << r.criticals[1].upper;
  EXPECT_LE(rel_width(r.criticals[1], e), 1e-15);
  mpfr_clear(e);
  EXPECT_NEAR(r.criticals[0].foot[0], 3.0, 1e-12);
  EXPECT_NEAR(r.criticals[1].foot[0], -1.0, 1e-12);
  for (auto& c : r.criticals)
    EXPECT_FALSE(c.continuum);
}

TEST(PointQuadric, EllipsoidOnAxis) {
  auto r = certify::point_quadric_critical(pt(3, 0, 0), q("x^2/4 + y^2 + z^2/9 - 1"), 20);
  ASSERT_TRUE(r.ok) << r.note;
  int i1 = find_value(r, 1), i5 = find_value(r, 5);
  ASSERT_GE(i1, 0);
  ASSERT_GE(i5, 0);
  EXPECT_NEAR(r.criticals[static_cast<size_t>(i1)].foot[0], 2.0, 1e-12);
  EXPECT_NEAR(r.criticals[static_cast<size_t>(i5)].foot[0], -2.0, 1e-12);
  // minimum: the certified lower bound of the smallest critical is <= every sampled distance
  double lo = lower_d(r.criticals.front());
  double best = 1e300;
  const int n = 400;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      double th = M_PI * i / n, ph = M_PI * j / n;
      double px = 2 * std::sin(th) * std::cos(ph), py = std::sin(th) * std::sin(ph),
             pz = 3 * std::cos(th);
      double d = std::sqrt((px - 3) * (px - 3) + py * py + pz * pz);
      best = std::min(best, d);
    }
  EXPECT_LE(lo, best);
  EXPECT_NEAR(best, r.criticals.front().approx, 1e-3);
}

TEST(PointQuadric, EllipsoidCentre) {
  auto r = certify::point_quadric_critical(pt(0, 0, 0), q("x^2/4 + y^2 + z^2/9 - 1"), 20);
  ASSERT_TRUE(r.ok) << r.note;
  // two antipodal feet per semi-axis
  ASSERT_EQ(r.criticals.size(), 6u);
  const double expect[6] = {1, 1, 2, 2, 3, 3};
  for (size_t i = 0; i < 6; ++i) {
    mpfr_t e;
    mpfr_init2(e, 400);
    set_value(e, expect[i]);
    EXPECT_TRUE(contains(r.criticals[i], e)) << i << " " << r.criticals[i].lower;
    mpfr_clear(e);
    EXPECT_FALSE(r.criticals[i].continuum);
  }
  EXPECT_NEAR(std::fabs(r.criticals[0].foot[1]), 1.0, 1e-12);
  EXPECT_NEAR(std::fabs(r.criticals[1].foot[1]), 1.0, 1e-12);
  EXPECT_NEAR(r.criticals[0].foot[1] + r.criticals[1].foot[1], 0.0, 1e-12);
  EXPECT_NEAR(std::fabs(r.criticals[4].foot[2]), 3.0, 1e-12);
}

TEST(PointQuadric, Cylinder) {
  auto r = certify::point_quadric_critical(pt(3, 0, 0), q("x^2 + y^2 - 1"), 30);
  ASSERT_TRUE(r.ok) << r.note;
  ASSERT_FALSE(r.criticals.empty());
  mpfr_t e;
  mpfr_init2(e, 400);
  set_value(e, 2);
  EXPECT_TRUE(contains(r.criticals.front(), e)) << r.criticals.front().lower;
  set_value(e, 4);
  EXPECT_GE(find_value(r, 4), 0);
  mpfr_clear(e);
  // the foot of the minimum is (1,0,0)
  EXPECT_NEAR(r.criticals.front().foot[0], 1.0, 1e-12);
}

TEST(PointQuadric, ConeVertexAndGeneratrix) {
  auto r = certify::point_quadric_critical(pt(0, 0, -5), q("x^2 + y^2 - z^2"), 50);
  ASSERT_TRUE(r.ok) << r.note;
  bool vertex = false;
  mpfr_t e;
  mpfr_init2(e, 400);
  set_value(e, 5);
  for (auto& c : r.criticals)
    if (c.singular_point) {
      vertex = true;
      EXPECT_TRUE(contains(c, e)) << c.lower;
      EXPECT_EQ(c.foot[0], 0.0);
      EXPECT_EQ(c.foot[2], 0.0);
    }
  EXPECT_TRUE(vertex);
  // minimum 5/sqrt(2), to 50 digits
  mpfr_set_ui(e, 25, MPFR_RNDN);
  mpfr_div_ui(e, e, 2, MPFR_RNDN);
  mpfr_sqrt(e, e, MPFR_RNDN);
  const auto& m = r.criticals.front();
  EXPECT_TRUE(contains(m, e)) << m.lower << " " << m.upper;
  EXPECT_LE(rel_width(m, e), 1e-50);
  EXPECT_TRUE(m.continuum); // a circle of feet around the axis
  EXPECT_NEAR(m.foot[2], -2.5, 1e-12);
  mpfr_clear(e);
}

TEST(PointQuadric, TwoPrecisionsOverlap) {
  std::array<Rational, 3> x{Rational(1, 3), Rational(-2, 7), Rational(5, 4)};
  auto qq = q("x^2/4 + 2*y^2 + z^2/3 + x*y - y*z/5 - 1");
  auto a = certify::point_quadric_critical(x, qq, 15);
  auto b = certify::point_quadric_critical(x, qq, 60);
  ASSERT_TRUE(a.ok) << a.note;
  ASSERT_TRUE(b.ok) << b.note;
  ASSERT_EQ(a.criticals.size(), b.criticals.size());
  ASSERT_GE(a.criticals.size(), 2u);
  for (size_t i = 0; i < a.criticals.size(); ++i) {
    mpfr_t alo, ahi, blo, bhi;
    mpfr_inits2(400, alo, ahi, blo, bhi, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_str(alo, a.criticals[i].lower.c_str(), 10, MPFR_RNDD);
    mpfr_set_str(ahi, a.criticals[i].upper.c_str(), 10, MPFR_RNDU);
    mpfr_set_str(blo, b.criticals[i].lower.c_str(), 10, MPFR_RNDD);
    mpfr_set_str(bhi, b.criticals[i].upper.c_str(), 10, MPFR_RNDU);
    EXPECT_LE(mpfr_cmp(alo, bhi), 0) << i;
    EXPECT_LE(mpfr_cmp(blo, ahi), 0) << i;
    // the 60-digit one is nested-narrow
    mpfr_sub(bhi, bhi, blo, MPFR_RNDU);
    mpfr_div(bhi, bhi, blo, MPFR_RNDU);
    EXPECT_LE(mpfr_get_d(bhi, MPFR_RNDU), 1e-60) << i;
    mpfr_clears(alo, ahi, blo, bhi, static_cast<mpfr_ptr>(nullptr));
  }
  // each critical foot is on Q and x - p is normal to Q (float check of the foot points)
  for (auto& c : b.criticals) {
    double px = c.foot[0], py = c.foot[1], pz = c.foot[2];
    double val = px * px / 4 + 2 * py * py + pz * pz / 3 + px * py - py * pz / 5 - 1;
    EXPECT_NEAR(val, 0.0, 1e-9);
    double g[3] = {px / 2 + py, 4 * py + px - pz / 5, 2 * pz / 3 - py / 5};
    double v[3] = {1.0 / 3 - px, -2.0 / 7 - py, 1.25 - pz};
    double cr[3] = {g[1] * v[2] - g[2] * v[1], g[2] * v[0] - g[0] * v[2],
                    g[0] * v[1] - g[1] * v[0]};
    EXPECT_NEAR(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2], 0.0, 1e-9);
  }
}

TEST(PointQuadric, AxisOfRevolutionIsContinuum) {
  auto r = certify::point_quadric_critical(pt(0, 0, 0), q("x^2 + y^2 + z^2/4 - 1"), 20);
  ASSERT_TRUE(r.ok) << r.note;
  int i1 = find_value(r, 1), i2 = find_value(r, 2);
  ASSERT_GE(i1, 0);
  ASSERT_GE(i2, 0);
  EXPECT_TRUE(r.criticals[static_cast<size_t>(i1)].continuum);
  EXPECT_FALSE(r.criticals[static_cast<size_t>(i2)].continuum);
  const auto& f = r.criticals[static_cast<size_t>(i1)].foot;
  EXPECT_NEAR(f[0] * f[0] + f[1] * f[1], 1.0, 1e-12);
  EXPECT_NEAR(f[2], 0.0, 1e-12);
  // 1 (circle) + 2 poles at distance 2
  EXPECT_EQ(r.criticals.size(), 3u);
}

TEST(PointQuadric, SphereCentreIsContinuum) {
  auto r = certify::point_quadric_critical(pt(0, 0, 0), q("x^2 + y^2 + z^2 - 9"), 15);
  ASSERT_TRUE(r.ok) << r.note;
  ASSERT_EQ(r.criticals.size(), 1u);
  EXPECT_TRUE(r.criticals[0].continuum);
  EXPECT_EQ(find_value(r, 3), 0);
}

TEST(PointQuadric, PointOnSurface) {
  auto r = certify::point_quadric_critical(pt(2, 0, 0), q("x^2/4 + y^2 + z^2/9 - 1"), 15);
  ASSERT_TRUE(r.ok) << r.note;
  ASSERT_FALSE(r.criticals.empty());
  EXPECT_EQ(lower_d(r.criticals.front()), 0.0);
  EXPECT_GE(find_value(r, 4), 0);
}

TEST(PointQuadric, FrontEnclosesTheMinimumAtNearTies) {
  // x = (0, 0, +-eps) and the ellipsoid with shortest semi-axis 3/2 along z: two foot points
  // at 3/2 - eps and 3/2 + eps, too close to order at 15 digits for eps <= 1e-20; sorted by
  // the certified lower bounds, front() still encloses the minimum 3/2 - eps.
  for (const char* den :
       {"10000000000", "100000000000000000000", "1267650600228229401496703205376"})
    for (int sign : {-1, 1}) {
      Rational eps = Rational(sign) / *Rational::from_string(den);
      auto r = certify::point_quadric_critical({Rational(0), Rational(0), eps},
                                               q("x^2/9 + y^2/4 + 4*z^2/9 - 1"), 15);
      ASSERT_TRUE(r.ok) << r.note;
      mpfr_t e, t;
      mpfr_inits2(400, e, t, static_cast<mpfr_ptr>(nullptr));
      mpfr_set_str(t, den, 10, MPFR_RNDN);
      mpfr_ui_div(t, 1, t, MPFR_RNDN);
      mpfr_set_d(e, 1.5, MPFR_RNDN);
      mpfr_sub(e, e, t, MPFR_RNDN);
      EXPECT_TRUE(contains(r.criticals.front(), e))
          << den << " " << sign << ": " << r.criticals.front().lower << " "
          << r.criticals.front().upper;
      mpfr_clears(e, t, static_cast<mpfr_ptr>(nullptr));
    }
}
