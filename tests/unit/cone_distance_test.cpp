// Ellipsoid against a quadratic cone through the generator lines (cone_distance.hpp), against
// independent routes:
// - sphere vs cone: (critical distance from the centre by the point-quadric sextic) - rho, for
//   a right circular cone (two symmetric minimizers) and a tilted elliptic cone;
// - random ellipsoids vs a rotated elliptic cone: the exact offset method (Mode::Exact) gives
//   overlapping enclosures;
// - it answers only what it proves: crossing, a sphere on the axis (a circle of minimizers) and
//   more than 25 digits go to the exact route.
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <random>

using namespace surfcert;
using surfcert::testing::motion;
using surfcert::testing::overlap;
using surfcert::testing::q;

namespace {

// [lower - rho, upper - rho] of the smallest critical distance from c, outward rounded.
surfcert::testing::Bounds sextic_minus(const std::array<core::Rational, 3>& c,
                                       const core::QuadricMatrix& cone, long rho_num,
                                       long rho_den) {
  auto pq = certify::point_quadric_critical(c, cone, 30);
  EXPECT_TRUE(pq.ok);
  surfcert::testing::Bounds r;
  mpfr_t l, u, t;
  mpfr_inits2(4000, l, u, t, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(l, pq.criticals.front().lower.c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u, pq.criticals.front().upper.c_str(), 10, MPFR_RNDU);
  mpfr_set_si(t, rho_num, MPFR_RNDN);
  mpfr_div_si(t, t, rho_den, MPFR_RNDU);
  mpfr_sub(l, l, t, MPFR_RNDD);
  mpfr_set_si(t, rho_num, MPFR_RNDN);
  mpfr_div_si(t, t, rho_den, MPFR_RNDD);
  mpfr_sub(u, u, t, MPFR_RNDU);
  char* s = nullptr;
  mpfr_asprintf(&s, "%.40RDe", l);
  r.lower = s;
  mpfr_free_str(s);
  mpfr_asprintf(&s, "%.40RUe", u);
  r.upper = s;
  mpfr_free_str(s);
  mpfr_clears(l, u, t, static_cast<mpfr_ptr>(nullptr));
  return r;
}

} // namespace

TEST(ConeDistance, SphereAgainstThePointQuadricSextic) {
  const auto round = q("x^2 + y^2 - z^2 = 0");
  auto r = certify::surface_distance(q("(x-4)^2 + y^2 + z^2 = 1"), round, 15, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  EXPECT_EQ(r.method, certify::Method::ConeGeneratorBound);
  // the generators x = z and x = -z, one per arc (the squared distance is proven strictly
  // convex over each arc of survivors)
  EXPECT_EQ(r.minimizers, "2") << r.note;
  EXPECT_TRUE(overlap(r, sextic_minus({4, 0, 0}, round, 1, 1))) << r.lower();
  // a tilted elliptic cone with its vertex at (1/2, -1, 0)
  const auto tilted = q("x^2 + 2y^2 - z^2/3 + x*y/7 + y*z/5 = 0")
                          .congruent(motion(1, 0, 0, 0, {core::Rational(1, 2), -1, 0}));
  auto t = certify::surface_distance(q("(x-5)^2 + (y-1)^2 + (z-1)^2 = 1/4"), tilted, 20, false);
  ASSERT_EQ(t.status, certify::Status::Certified) << t.note;
  EXPECT_EQ(t.method, certify::Method::ConeGeneratorBound);
  EXPECT_TRUE(overlap(t, sextic_minus({5, 1, 1}, tilted, 1, 2))) << t.lower();
}

TEST(ConeDistance, RandomEllipsoidsAgainstTheOffsetMethod) {
  const auto cone =
      q("x^2/4 + y^2 - z^2 = 0").congruent(motion(2, 1, -1, 1, {1, core::Rational(1, 3), -2}));
  std::mt19937_64 rng(31);
  std::uniform_int_distribution<int> ax(30, 100), qd(-4, 4), off(-6, 6);
  int checked = 0;
  for (int i = 0; i < 10 && checked < 3; ++i) {
    core::Mat4 m;
    for (size_t k = 0; k < 3; ++k) {
      core::Rational a(ax(rng), 100);
      m[k][k] = core::Rational(1) / (a * a);
    }
    m[3][3] = core::Rational(-1);
    long w = 0, x = 0, y = 0, z = 0;
    while (w == 0 && x == 0 && y == 0 && z == 0)
      w = qd(rng), x = qd(rng), y = qd(rng), z = qd(rng);
    auto e = core::QuadricMatrix(m).congruent(motion(w, x, y, z, {off(rng), off(rng), off(rng)}));
    auto r = certify::surface_distance(e, cone, 15, false);
    if (r.method != certify::Method::ConeGeneratorBound)
      continue; // crossing draws: the exact route
    auto ex = certify::surface_distance(e, cone, 15, false, certify::Mode::Exact);
    ASSERT_EQ(ex.status, certify::Status::Certified) << ex.note;
    EXPECT_TRUE(overlap(r, ex)) << "case " << i << ": " << r.lower() << " vs " << ex.lower();
    // Every arc of surviving generators holds one minimizing line (strict convexity of the
    // squared distance over the arc): the count equals the exact route's.
    ASSERT_TRUE(ex.minimizers.is_count()) << "case " << i;
    EXPECT_EQ(r.minimizers, ex.minimizers) << "case " << i << ": " << r.note;
    ++checked;
  }
  EXPECT_GE(checked, 2);
}

TEST(ConeDistance, AnswersOnlyWhatItProves) {
  const auto round = q("x^2 + y^2 - z^2 = 0");
  auto cross = certify::surface_distance(q("(x-1)^2 + y^2 + (z-1)^2 = 1/4"), round, 15, false);
  EXPECT_NE(cross.method, certify::Method::ConeGeneratorBound);
  EXPECT_EQ(cross.status, certify::Status::Certified); // the exact route: they meet
  EXPECT_EQ(cross.upper(), "0");
  auto axis = certify::surface_distance(q("x^2 + y^2 + (z-5)^2 = 1"), round, 15, false);
  EXPECT_NE(axis.method, certify::Method::ConeGeneratorBound); // a circle of minimizers
  auto many = certify::surface_distance(q("(x-4)^2 + y^2 + z^2 = 1"), round, 40, false);
  EXPECT_NE(many.method, certify::Method::ConeGeneratorBound);
  EXPECT_EQ(many.status, certify::Status::Certified);
}

// The round cone x^2 + y^2 = z^2 and the ellipsoid centred at (2, 0, 4) with semi-axes 1/2, b,
// 1/2 (inside the upper nappe). The mirror y -> -y makes D(phi) = dist(line(phi), E)^2 even
// in the generator angle phi (line(phi) through the vertex along (cos phi, sin phi, 1)), and
// at phi = 0 the nearest points lie in the plane y = 0: D(0) = (sqrt(2) - 1/2)^2 whatever b.
// At b* = 1.29004401567275798467585054385318245260684251930365172072037218251070532960245...
// D''(0) = 0 (D''''(0) = 29.698... > 0); for b = b* + delta, phi = 0 is a local maximum
// between two minimizers +-phi1, for b = b* - delta the one minimizer phi = 0 (d = sqrt(2) -
// 1/2). mpmath at 160 digits (dual formula D = max_s s y^T (M + s I)^-1 y - s in the plane
// normal to the line, D'' and b* by findroot): delta = 3e-7, 3e-21, 3e-41, 2e-61 put the two
// minimizers 1.069e-3, 1.069e-10, 1.069e-20, 7.889e-31 (about 2^-100) apart, the bump between
// them 1.0e-13, 1.0e-41, 1.0e-81, 4.3e-122. Checked independently for delta = 3e-7 by the
// primal distance (point-ellipsoid secular equation minimised along the line, mpmath at 50
// digits): the same bump 1.0116e-13 and d.
TEST(ConeDistance, TwoMinimaInOneArcAreNotCountedAsOne) {
  const auto round = q("x^2 + y^2 - z^2 = 0");
  struct Case {
    const char* b; // b* +- delta, 100 digits
    const char* d; // the distance (mpmath)
    bool two;      // two minimizers (b > b*), else one
  };
  const Case cases[] = {
      // 1e-3 apart: the bump 1e-13 is above 10^-15 d (two arcs)
      {"1.29004431567275798467585054385318245260684251930365172072037218251070532960245362656403"
       "2616104368355",
       "0.91421356237303972066520418109359638371169817543307", true},
      {"1.29004371567275798467585054385318245260684251930365172072037218251070532960245362656403"
       "2616104368355",
       "0.91421356237309504880168872420969807856967187537695", false},
      // 1e-10, 1e-20, 2^-100 apart: one arc of survivors at 15 digits
      {"1.29004401567275798467885054385318245260684251930365172072037218251070532960245362656403"
       "2616104368355",
       "0.91421356237309504880168872420969807856966634256156", true},
      {"1.29004401567275798467285054385318245260684251930365172072037218251070532960245362656403"
       "2616104368355",
       "0.91421356237309504880168872420969807856967187537695", false},
      {"1.29004401567275798467585054385318245260687251930365172072037218251070532960245362656403"
       "2616104368355",
       "0.91421356237309504880168872420969807856967187537695", true},
      {"1.29004401567275798467585054385318245260681251930365172072037218251070532960245362656403"
       "2616104368355",
       "0.91421356237309504880168872420969807856967187537695", false},
      {"1.29004401567275798467585054385318245260684251930365172072037238251070532960245362656403"
       "2616104368355",
       "0.91421356237309504880168872420969807856967187537695", true},
      {"1.29004401567275798467585054385318245260684251930365172072037198251070532960245362656403"
       "2616104368355",
       "0.91421356237309504880168872420969807856967187537695", false},
  };
  // At 15 digits the cone route gives up on these flat minima (too many survivors) and the
  // exact route answers; at 3 digits the cone route answers with one arc of survivors.
  int cone_route = 0;
  for (const Case& c : cases) {
    const std::string b(c.b);
    const auto e = q("4*(x-2)^2 + y^2/(" + b + ")^2 + 4*(z-4)^2 = 1");
    for (long digits : {3L, 15L})
      for (bool swap : {false, true}) {
        if (swap && digits == 15) continue; // the exact route (slow): once
        const auto r = swap ? certify::surface_distance(round, e, digits, false)
                            : certify::surface_distance(e, round, digits, false);
        ASSERT_EQ(r.status, certify::Status::Certified) << b << ": " << r.note;
        if (r.method == certify::Method::ConeGeneratorBound) ++cone_route;
        mpfr_t d;
        mpfr_init2(d, 200);
        mpfr_set_str(d, c.d, 10, MPFR_RNDN);
        EXPECT_TRUE(surfcert::testing::contains(r, d))
            << b << ": " << r.lower() << " " << r.upper();
        mpfr_clear(d);
        // two (b > b*) or one, else undecided: never the other count
        if (r.minimizers.is_count())
          EXPECT_EQ(r.minimizers.value(), c.two ? 2 : 1) << b << " at " << digits << ": " << r.note;
        else
          EXPECT_TRUE(r.minimizers.is_undecided()) << b << ": " << r.minimizers;
      }
  }
  // the point: the generator route met every case (at 3 digits)
  EXPECT_GE(cone_route, 16);
}
