// The fast path for disjoint convex solids (support-function duality), each result against an
// independent route:
// - closed forms: sphere-sphere |c1 - c2| - r1 - r2 (MPFR), sphere-cylinder
//   dist(c, axis) - r - rho, gaps of exactly 2^-40 and 2^-100;
// - sphere-ellipsoid against the point-ellipsoid sextic (point_quadric_critical: exact roots);
// - random separated ellipsoid pairs and ellipsoid-cylinder pairs against the exact offset
//   method (quadric_pair_distance: resultants, exact isolation) - the enclosures must overlap;
// - rigid motions (integer quaternions), swapping, scaling by 10^+-8, translation by 10^6,
//   eccentricity 10^6, digits 15 / 100 / 1000 nested;
// - it answers only what it proves: overlapping, touching and nested pairs give nullopt.
#include "surfcert/certify/distance/convex_distance.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/certify/distance/quadric_pair.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <cstdlib>
#include <random>

using namespace surfcert;
using surfcert::testing::hi;
using surfcert::testing::lo;
using surfcert::testing::motion;
using surfcert::testing::overlap;
using surfcert::testing::q;
using surfcert::testing::scaling;

namespace {

std::optional<certify::DistanceResult> fast(const core::QuadricMatrix& a,
                                            const core::QuadricMatrix& b, long digits) {
  auto ca = certify::convex_quadric(a), cb = certify::convex_quadric(b);
  if (!ca || !cb) return std::nullopt;
  return certify::separated_convex_distance(*ca, *cb, digits);
}

// A reference enclosure [lo, hi] written as a result (for overlap()), rounded outward.
surfcert::testing::Bounds ref_interval(const mpfr_t l, const mpfr_t u) {
  surfcert::testing::Bounds r;
  char* s = nullptr;
  mpfr_asprintf(&s, "%.60RDe", l);
  r.lower = s;
  mpfr_free_str(s);
  mpfr_asprintf(&s, "%.60RUe", u);
  r.upper = s;
  mpfr_free_str(s);
  return r;
}

double rel_width(const certify::DistanceResult& r) {
  return (hi(r) - lo(r)) / lo(r);
}

std::string sphere(long cx, long cy, long cz, const std::string& r) {
  return "(x-(" + std::to_string(cx) + "))^2 + (y-(" + std::to_string(cy) + "))^2 + (z-(" +
         std::to_string(cz) + "))^2 = (" + r + ")^2";
}

// A random ellipsoid: semi-axes in [1/5, 2], a random integer-quaternion rotation, centre `c`.
core::QuadricMatrix random_ellipsoid(std::mt19937_64& rng, const std::array<core::Rational, 3>& c) {
  std::uniform_int_distribution<long> ax(20, 200), qd(-5, 5);
  core::Mat4 m;
  for (size_t i = 0; i < 3; ++i) {
    core::Rational a(ax(rng), 100);
    m[i][i] = core::Rational(1) / (a * a);
  }
  m[3][3] = core::Rational(-1);
  long w = 0, x = 0, y = 0, z = 0;
  while (w == 0 && x == 0 && y == 0 && z == 0)
    w = qd(rng), x = qd(rng), y = qd(rng), z = qd(rng);
  return core::QuadricMatrix(m).congruent(motion(w, x, y, z, c));
}

} // namespace

TEST(ConvexDistance, SphereSphereClosedForm) {
  // |(0,0,0) - (3,4,1)| - 1 - 1 = sqrt(26) - 2, at 15 and 300 digits.
  for (long digits : {15L, 300L}) {
    auto r = fast(q(sphere(0, 0, 0, "1")), q(sphere(3, 4, 1, "1")), digits);
    ASSERT_TRUE(r);
    mpfr_t v; // the closed form to 4000 bits (an error of 2^-3990 is far below any enclosure)
    mpfr_init2(v, 4000);
    mpfr_set_ui(v, 26, MPFR_RNDN);
    mpfr_sqrt(v, v, MPFR_RNDN);
    mpfr_sub_ui(v, v, 2, MPFR_RNDN);
    EXPECT_TRUE(overlap(*r, ref_interval(v, v))) << r->lower();
    mpfr_clear(v);
    EXPECT_LE(rel_width(*r), std::pow(10.0, -std::min(digits, 15L)));
    EXPECT_EQ(r->minimizers, "1");
    ASSERT_EQ(r->pairs.size(), 1u);
    // the closest points are on the segment of the centres
    EXPECT_NEAR(r->pairs[0][0][0], 3 / std::sqrt(26.0), 1e-12);
    EXPECT_NEAR(r->pairs[0][1][1], 4 - 4 / std::sqrt(26.0), 1e-12);
  }
}

TEST(ConvexDistance, ExactGapsOf2ToTheMinus40And100) {
  // Unit spheres at distance exactly 2 + 2^-k between centres: d = 2^-k, a dyadic rational.
  for (int k : {40, 100}) {
    core::Rational gap = core::pow2(-k);
    core::Mat4 m;
    for (size_t i = 0; i < 3; ++i)
      m[i][i] = core::Rational(1);
    m[3][3] = core::Rational(-1);
    core::QuadricMatrix a(m);
    core::QuadricMatrix b = a.congruent(motion(1, 0, 0, 0, {core::Rational(2) + gap, 0, 0}));
    auto r = fast(a, b, 20);
    ASSERT_TRUE(r) << k;
    EXPECT_LE(lo(r.value()), std::ldexp(1.0, -k) * (1 + 1e-18));
    EXPECT_GE(hi(r.value()), std::ldexp(1.0, -k) * (1 - 1e-18));
    EXPECT_LE(rel_width(*r), 1e-19) << k;
  }
}

TEST(ConvexDistance, SphereEllipsoidAgainstThePointEllipsoidSextic) {
  // d = (min distance from the centre to the ellipsoid) - rho, the minimum from the exact roots
  // of the point-quadric sextic (another code path: no support functions).
  const auto e = q("x^2/4 + y^2 + (z-1)^2/9 = 1");
  struct Case {
    long cx, cy, cz, rho_num, rho_den;
  };
  for (const Case& c : {Case{5, 1, 2, 1, 2}, Case{-3, 4, -6, 2, 1}, Case{0, 0, 11, 3, 7}}) {
    const std::string rho = std::to_string(c.rho_num) + "/" + std::to_string(c.rho_den);
    auto r = fast(q(sphere(c.cx, c.cy, c.cz, rho)), e, 20);
    ASSERT_TRUE(r) << rho;
    auto pq = certify::point_quadric_critical(
        {core::Rational(c.cx), core::Rational(c.cy), core::Rational(c.cz)}, e, 30);
    ASSERT_TRUE(pq.ok);
    mpfr_t l, u, rr;
    mpfr_inits2(4000, l, u, rr, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_str(l, pq.criticals.front().lower.c_str(), 10, MPFR_RNDD);
    mpfr_set_str(u, pq.criticals.front().upper.c_str(), 10, MPFR_RNDU);
    mpfr_set_si(rr, c.rho_num, MPFR_RNDN);
    mpfr_div_si(rr, rr, c.rho_den, MPFR_RNDU);
    mpfr_sub(l, l, rr, MPFR_RNDD);
    mpfr_set_si(rr, c.rho_num, MPFR_RNDN);
    mpfr_div_si(rr, rr, c.rho_den, MPFR_RNDD);
    mpfr_sub(u, u, rr, MPFR_RNDU);
    EXPECT_TRUE(overlap(*r, ref_interval(l, u)))
        << r->lower() << " vs " << pq.criticals.front().lower;
    mpfr_clears(l, u, rr, static_cast<mpfr_ptr>(nullptr));
  }
}

TEST(ConvexDistance, SphereCylinderClosedForm) {
  // Cylinder y^2 + z^2 = 1 (axis x); sphere of radius rho at c: d = sqrt(cy^2 + cz^2) - 1 - rho.
  struct Case {
    long cx, cy, cz;
  };
  for (const Case& c : {Case{0, 5, 0}, Case{3, 4, 4}, Case{-7, -2, 6}})
    for (long digits : {25L, 100L}) {
      // At 100 digits both are turned by a rational rotation (tilted axis): the MPFR
      // refinement must then stay exactly on the plane orthogonal to the axis.
      const core::Mat4 m = motion(digits > 25 ? 3 : 1, digits > 25 ? 1 : 0, digits > 25 ? -2 : 0,
                                  digits > 25 ? 1 : 0, {0, 0, 0});
      auto r = fast(q("y^2 + z^2 = 1").congruent(m),
                    q(sphere(c.cx, c.cy, c.cz, "1/3")).congruent(m), digits);
      ASSERT_TRUE(r) << c.cy << " " << digits;
      EXPECT_LE(rel_width(*r), 1e-25);
      mpfr_t v, t;
      mpfr_inits2(4000, v, t, static_cast<mpfr_ptr>(nullptr));
      mpfr_set_si(v, c.cy * c.cy + c.cz * c.cz, MPFR_RNDN);
      mpfr_sqrt(v, v, MPFR_RNDN);
      mpfr_set_ui(t, 4, MPFR_RNDN);
      mpfr_div_ui(t, t, 3, MPFR_RNDN);
      mpfr_sub(v, v, t, MPFR_RNDN);
      EXPECT_TRUE(overlap(*r, ref_interval(v, v))) << r->lower();
      mpfr_clears(v, t, static_cast<mpfr_ptr>(nullptr));
      if (digits == 25) { // the cylinder's point sits at the sphere centre's abscissa
        EXPECT_NEAR(r->pairs[0][0][0], static_cast<double>(c.cx), 1e-9);
      }
      EXPECT_EQ(r->minimizers, "1");
    }
}

TEST(ConvexDistance, RandomSeparatedPairsAgainstTheOffsetMethod) {
  // Independent route: the exact offset system (resultants + exact isolation), same pairs.
  const unsigned seed = std::getenv("SURFCERT_TEST_SEED")
                            ? static_cast<unsigned>(std::atoi(std::getenv("SURFCERT_TEST_SEED")))
                            : 20261122u;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<long> off(-60, 60);
  int checked = 0;
  for (int i = 0; i < 12 && checked < 5; ++i) {
    auto a = random_ellipsoid(rng, {core::Rational(0), core::Rational(0), core::Rational(0)});
    auto b = random_ellipsoid(rng, {core::Rational(off(rng), 10), core::Rational(off(rng), 10),
                                    core::Rational(off(rng), 10)});
    auto r = fast(a, b, 15);
    if (!r) continue; // overlapping or nested draws: not this path's business
    auto x = certify::quadric_pair_distance(a, b, 15);
    ASSERT_EQ(x.status, certify::Status::Certified) << "seed " << seed << " pair " << i;
    EXPECT_TRUE(overlap(*r, x)) << "seed " << seed << " pair " << i << ": " << r->lower() << " vs "
                                << x.lower();
    EXPECT_EQ(x.minimizers, "1") << "seed " << seed << " pair " << i;
    ASSERT_FALSE(x.pairs.empty());
    for (size_t k = 0; k < 3; ++k) { // the same closest points
      EXPECT_NEAR(r->pairs[0][0][k], x.pairs[0][0][k], 1e-6) << "seed " << seed << " pair " << i;
      EXPECT_NEAR(r->pairs[0][1][k], x.pairs[0][1][k], 1e-6) << "seed " << seed << " pair " << i;
    }
    ++checked;
  }
  EXPECT_GE(checked, 3) << "seed " << seed;
}

TEST(ConvexDistance, EllipsoidCylinderAgainstTheOffsetMethod) {
  // A tilted elliptic cylinder (rational rotation) and rotated ellipsoids beside it.
  const auto cyl = q("x^2/4 + y^2 = 1").congruent(motion(3, 1, -2, 1, {0, 0, 0}));
  const unsigned seed = 7;
  std::mt19937_64 rng(seed);
  int checked = 0;
  for (const auto& c : {std::array<long, 3>{5, 1, 0}, std::array<long, 3>{-2, 6, 3},
                        std::array<long, 3>{1, -5, -4}}) {
    auto e =
        random_ellipsoid(rng, {core::Rational(c[0]), core::Rational(c[1]), core::Rational(c[2])});
    auto r = fast(e, cyl, 15);
    if (!r) continue;
    auto x = certify::quadric_pair_distance(e, cyl, 15);
    ASSERT_EQ(x.status, certify::Status::Certified) << x.note;
    EXPECT_TRUE(overlap(*r, x)) << r->lower() << " vs " << x.lower();
    ++checked;
  }
  EXPECT_GE(checked, 2);
}

TEST(ConvexDistance, SphereParaboloidAgainstThePointQuadricSextic) {
  // Paraboloids (axis-aligned and turned by a rational rotation) against spheres outside their
  // convex side; the reference is (point-paraboloid distance from the sextic) - rho.
  const core::Mat4 turn = motion(2, 1, -1, 3, {core::Rational(1, 2), 0, 0});
  struct Case {
    const char* par;
    long cx, cy, cz;
  };
  for (const Case& c :
       {Case{"x^2 + y^2 - z = 0", 3, 0, 0}, Case{"x^2 + y^2 - z = 0", 0, 0, -5},
        Case{"x^2/4 + y^2 - z + x/3 = 1", 4, -3, 1}, Case{"z^2 + 3y^2 + x - 2 = 0", 5, 1, 1}})
    for (bool turned : {false, true}) {
      core::QuadricMatrix par = q(c.par), sph = q(sphere(c.cx, c.cy, c.cz, "1/2"));
      if (turned) par = par.congruent(turn), sph = sph.congruent(turn);
      auto r = fast(sph, par, 20);
      ASSERT_TRUE(r) << c.par << " " << turned;
      // centre of the (possibly moved) sphere: -Q(i,3)/Q(0,0)
      std::array<core::Rational, 3> cen;
      for (int i = 0; i < 3; ++i)
        cen[static_cast<size_t>(i)] = -sph(i, 3) / sph(0, 0);
      auto pq = certify::point_quadric_critical(cen, par, 30);
      ASSERT_TRUE(pq.ok);
      mpfr_t l, u;
      mpfr_inits2(4000, l, u, static_cast<mpfr_ptr>(nullptr));
      mpfr_set_str(l, pq.criticals.front().lower.c_str(), 10, MPFR_RNDD);
      mpfr_set_str(u, pq.criticals.front().upper.c_str(), 10, MPFR_RNDU);
      mpfr_sub_d(l, l, 0.5, MPFR_RNDD);
      mpfr_sub_d(u, u, 0.5, MPFR_RNDU);
      EXPECT_TRUE(overlap(*r, ref_interval(l, u)))
          << c.par << " " << turned << ": " << r->lower() << " vs " << pq.criticals.front().lower;
      mpfr_clears(l, u, static_cast<mpfr_ptr>(nullptr));
    }
  // A sphere inside the convex side is not separated: no answer here.
  EXPECT_FALSE(fast(q(sphere(0, 0, 5, "1/2")), q("x^2 + y^2 - z = 0"), 15));
  EXPECT_FALSE(fast(q("x^2 + y^2 - z = 0"), q("x^2 + y^2 - z + 1 = 0"), 15)); // no ellipsoid
}

TEST(ConvexDistance, EllipsoidParaboloidAgainstTheOffsetMethod) {
  const auto par = q("x^2/4 + y^2 - z = 0").congruent(motion(1, 2, 0, -1, {0, 0, 1}));
  std::mt19937_64 rng(11);
  int checked = 0;
  for (const auto& c : {std::array<long, 3>{4, 0, -2}, std::array<long, 3>{-3, 3, -4},
                        std::array<long, 3>{0, -5, 0}}) {
    auto e =
        random_ellipsoid(rng, {core::Rational(c[0]), core::Rational(c[1]), core::Rational(c[2])});
    auto r = fast(e, par, 15);
    if (!r) continue;
    auto x = certify::quadric_pair_distance(e, par, 15);
    ASSERT_EQ(x.status, certify::Status::Certified) << x.note;
    EXPECT_TRUE(overlap(*r, x)) << r->lower() << " vs " << x.lower();
    ++checked;
  }
  EXPECT_GE(checked, 2);
}

TEST(ConvexDistance, InvarianceSwapScalingTranslation) {
  const auto a = q("x^2/4 + y^2 + z^2/9 = 1"), b = q("(x-5)^2/9 + (y-1)^2/4 + (z-2)^2 = 1");
  auto r = fast(a, b, 30);
  ASSERT_TRUE(r);
  // swapping swaps the points
  auto s = fast(b, a, 30);
  ASSERT_TRUE(s);
  EXPECT_TRUE(overlap(*r, *s));
  for (size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(r->pairs[0][0][k], s->pairs[0][1][k], 1e-12);
  // rigid motions (integer quaternions) and a translation by 10^6
  for (auto m : {motion(1, 2, 3, 4, {0, 0, 0}), motion(5, -1, 0, 2, {1000000, -1000000, 3}),
                 motion(2, 7, -1, 1, {core::Rational(1, 3), 0, 0})}) {
    auto t = fast(a.congruent(m), b.congruent(m), 30);
    ASSERT_TRUE(t);
    EXPECT_TRUE(overlap(*r, *t)) << t->lower();
  }
  // scaling by 10^8 and 10^-8 scales d
  for (int e : {8, -8}) {
    core::Rational sc = e > 0 ? core::Rational(100000000) : core::Rational(1, 100000000);
    auto t = fast(a.congruent(scaling(sc)), b.congruent(scaling(sc)), 30);
    ASSERT_TRUE(t);
    EXPECT_NEAR(lo(*t) / lo(*r), std::pow(10.0, e), 1e-13 * std::pow(10.0, e));
    EXPECT_LE(rel_width(*t), 1e-29);
  }
}

TEST(ConvexDistance, DigitsNestAndEccentricityOneMillion) {
  // A needle (semi-axes 1, 10^-6, 10^-6) beside a pancake; 15, 100 and 1000 digits nest.
  const auto a = q("x^2 + 1000000000000 y^2 + 1000000000000 z^2 = 1"),
             b = q("(x-1)^2/4 + (y-3)^2 + 1000000000000 (z-1/2)^2 = 1");
  auto r15 = fast(a, b, 15), r100 = fast(a, b, 100), r1000 = fast(a, b, 1000);
  ASSERT_TRUE(r15 && r100 && r1000);
  EXPECT_TRUE(overlap(*r15, *r100));
  EXPECT_TRUE(overlap(*r100, *r1000));
  EXPECT_LE(rel_width(*r15), 1e-15);
  EXPECT_GE(r1000->lower().size(), 1000u);
  // A float search over both surfaces never beats the certified lower bound.
  double best = 1e300;
  for (int i = 0; i <= 200; i += 10)
    for (int j = 0; j < 200; ++j) {
      const double th = M_PI * i / 200, ph = 2 * M_PI * j / 200;
      const double px = std::sin(th) * std::cos(ph), py = 1e-6 * std::sin(th) * std::sin(ph),
                   pz = 1e-6 * std::cos(th);
      for (int k = 0; k <= 40; ++k)
        for (int l = 0; l < 40; ++l) {
          const double t2 = M_PI * k / 40, p2 = 2 * M_PI * l / 40;
          const double qx = 1 + 2 * std::sin(t2) * std::cos(p2),
                       qy = 3 + std::sin(t2) * std::sin(p2), qz = 0.5 + 1e-6 * std::cos(t2);
          best = std::min(best, std::hypot(px - qx, py - qy, pz - qz));
        }
    }
  EXPECT_LE(lo(*r15), best);
}

TEST(ConvexDistance, FloatModeSaysItIsUncertifiedAndAgrees) {
  const auto a = q("x^2/4 + y^2 + z^2/9 = 1"), b = q("(x-5)^2/9 + (y-1)^2/4 + (z-2)^2 = 1");
  auto ca = certify::convex_quadric(a), cb = certify::convex_quadric(b);
  auto f = certify::separated_convex_distance_float(*ca, *cb);
  auto r = certify::separated_convex_distance(*ca, *cb, 15);
  ASSERT_TRUE(f && r);
  EXPECT_EQ(f->status, certify::Status::Uncertified);
  EXPECT_NE(f->note.find("NOT certified"), std::string::npos);
  EXPECT_NEAR(f->approx(), r->approx(), 1e-12 * r->approx());
  EXPECT_FALSE(certify::separated_convex_distance_float(
      *certify::convex_quadric(q(sphere(0, 0, 0, "1"))),
      *certify::convex_quadric(q(sphere(1, 0, 0, "1"))))); // overlapping: no separation
}

TEST(ConvexDistance, ModesThroughThePublicApi) {
  // filtered = the duality certificate; exact = the offset method only (an independent route:
  // resultants and exact isolation); float = uncertified double answer. Same pair, same value.
  const auto a = q("x^2/4 + y^2 + z^2/9 = 1").congruent(motion(1, 1, 2, 0, {0, 0, 0})),
             b = q("(x-5)^2/9 + (y-1)^2/4 + (z-2)^2 = 1");
  auto fil = certify::surface_distance(a, b, 20, false);
  auto ex = certify::surface_distance(a, b, 20, false, certify::Mode::Exact);
  auto fl = certify::surface_distance(a, b, 20, false, certify::Mode::Float);
  ASSERT_EQ(fil.status, certify::Status::Certified);
  ASSERT_EQ(ex.status, certify::Status::Certified) << ex.note;
  EXPECT_EQ(fil.method, certify::Method::ConvexDuality);
  EXPECT_EQ(ex.method, certify::Method::OffsetSystem);
  EXPECT_FALSE(ex.univariate_degrees.empty());
  EXPECT_TRUE(overlap(fil, ex)) << fil.lower() << " vs " << ex.lower();
  EXPECT_EQ(fl.status, certify::Status::Uncertified);
  EXPECT_EQ(fl.mode, certify::Mode::Float);
  EXPECT_NEAR(fl.approx(), fil.approx(), 1e-12 * fil.approx());
  auto j = certify::distance_envelope_json(ex, 20);
  EXPECT_EQ(j.find("result")->find("mode")->text(), "exact");
  EXPECT_EQ(j.find("result")->find("method")->text(), "offset_system");
}

TEST(ConvexDistance, AnswersOnlyWhatItProves) {
  // overlapping, touching (d = 0 exactly) and nested pairs: no certificate of separation.
  EXPECT_FALSE(fast(q(sphere(0, 0, 0, "1")), q(sphere(1, 0, 0, "1")), 15));
  EXPECT_FALSE(fast(q(sphere(0, 0, 0, "1")), q(sphere(2, 0, 0, "1")), 15));
  EXPECT_FALSE(fast(q("x^2 + y^2/4 + (z+3)^2/9 = 1"), q("x^2/4 + y^2/9 + z^2/49 = 1"), 15));
  EXPECT_FALSE(fast(q(sphere(0, 0, 0, "1/2")), q("y^2 + z^2 = 1"), 15)); // inside the cylinder
  EXPECT_FALSE(fast(q("y^2 + z^2 = 1"), q("x^2 + z^2 = 1"), 15));        // two cylinders
  // Not convex quadrics at all: no description.
  EXPECT_FALSE(certify::convex_quadric(q("x^2 + y^2 - z^2 = 1")));
  EXPECT_FALSE(certify::convex_quadric(q("x^2 - y^2 - z = 0")));   // hyperbolic paraboloid
  EXPECT_FALSE(certify::convex_quadric(q("x^2 + y^2 - z^2 = 0"))); // cone
  EXPECT_TRUE(certify::convex_quadric(q("x^2 + y^2 - z = 0")));    // elliptic paraboloid
  EXPECT_FALSE(certify::convex_quadric(q("x^2 + y^2 + z^2 = -1")));
  EXPECT_FALSE(certify::convex_quadric(q("x^2 + y^2 = 0")));
  EXPECT_TRUE(certify::convex_quadric(q("-x^2 - y^2 + 1 = 0"))); // orientation does not matter
}

TEST(ConvexDistance, UnboundedStrictlyConvexPairs) {
  // Two elliptic paraboloids opening away from each other: closed form 3 at the vertices;
  // a paraboloid above an elliptic cylinder (axis x): 4 at (0, 0, 0) - (0, 0, -4). Tilted:
  // a sampled grid of both surfaces never goes below the certified lower bound.
  auto r = fast(q("x^2 + y^2 - z = 0"), q("x^2 + y^2 + z + 3 = 0"), 30);
  ASSERT_TRUE(r);
  EXPECT_LE(lo(*r), 3);
  EXPECT_GE(hi(*r), 3);
  EXPECT_EQ(r->minimizers, "1");
  r = fast(q("x^2 + y^2 - z = 0"), q("y^2 + (z + 5)^2 = 1"), 15);
  ASSERT_TRUE(r);
  EXPECT_LE(lo(*r), 4);
  EXPECT_GE(hi(*r), 4);
  r = fast(q("x^2 + 2y^2 - z = 0"), q("(x - 5)^2 + y^2 + z + x*y/4 = 0"), 15);
  ASSERT_TRUE(r);
  double best = 1e300;
  for (int i = -60; i <= 60; ++i)
    for (int j = -30; j <= 30; ++j) {
      const double x1 = i * 0.05, y1 = j * 0.05, z1 = x1 * x1 + 2 * y1 * y1;
      for (int k = -60; k <= 60; k += 2)
        for (int l = -30; l <= 30; l += 2) {
          const double x2 = 5 + k * 0.05, y2 = l * 0.05,
                       z2 = -((x2 - 5) * (x2 - 5) + y2 * y2 + x2 * y2 / 4);
          best = std::min(best, std::hypot(x1 - x2, y1 - y2, z1 - z2));
        }
    }
  EXPECT_GE(best, lo(*r) - 1e-12);
  EXPECT_LT(best - r->approx(), 0.1);
  // Same-direction paraboloids only approach each other: never certified here.
  EXPECT_FALSE(fast(q("x^2 + y^2 - z = 0"), q("x^2 + y^2 - z + 3 = 0"), 15));
}
