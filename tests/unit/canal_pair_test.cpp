// Canal surfaces against canal surfaces and tori as unions of balls (canal_pair.hpp), each
// result against an independent route:
// - random capsule pairs against the exact segment-segment closed form (capsule_pair.hpp),
//   both orders (fixed seed, printed on failure);
// - a capsule above a torus (3 by hand) and a parabolic canal whose end balls are nearest a
//   torus: sqrt(26) - 3/2 at two pairs (MPFR, 15/100 digits), a proven tie;
// - a canal with a growing radius against a torus: points sampled in the canal's balls and on
//   the torus are never closer than the certified lower bound (the solids are disjoint) and
//   come close to it; the pairs lie on the torus / within the canal's balls;
// - rational rigid motions of both surfaces, swapping; overlapping solids are refused.
#include "surfcert/certify/distance/canal_pair.hpp"
#include "surfcert/certify/distance/capsule_pair.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <cmath>
#include <random>

using namespace surfcert;
using core::Rational;
using surfcert::testing::lo;
using surfcert::testing::overlap;

namespace {

using V3 = std::array<Rational, 3>;

core::CanalSurface capsule(const V3& a, const V3& b, const Rational& r) {
  std::array<std::vector<Rational>, 3> sp;
  for (size_t i = 0; i < 3; ++i)
    sp[i] = {a[i], b[i] - a[i]};
  return core::make_canal(sp, {r}, Rational(0), Rational(1));
}

// The rotation of the integer quaternion (2, 1, -2, 1) / 10 applied to a point.
V3 rot(const V3& x) {
  const long w = 2, a = 1, b = -2, c = 1;
  const long R[3][3] = {{w * w + a * a - b * b - c * c, 2 * (a * b - w * c), 2 * (a * c + w * b)},
                        {2 * (a * b + w * c), w * w - a * a + b * b - c * c, 2 * (b * c - w * a)},
                        {2 * (a * c - w * b), 2 * (b * c + w * a), w * w - a * a - b * b + c * c}};
  V3 y{Rational(0), Rational(0), Rational(0)};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      y[i] += Rational(R[i][j], 10) * x[j];
  return y;
}

// The canal moved by x -> rot(x) + shift (the spine's coefficient vectors rotate; the constant
// term also shifts).
core::CanalSurface moved(const core::CanalSurface& c, const V3& shift) {
  std::array<std::vector<Rational>, 3> sp;
  size_t n = 0;
  for (const auto& p : c.spine)
    n = std::max(n, p.size());
  for (auto& p : sp)
    p.assign(n, Rational(0));
  for (size_t k = 0; k < n; ++k) {
    V3 v;
    for (size_t i = 0; i < 3; ++i)
      v[i] = k < c.spine[i].size() ? c.spine[i][k] : Rational(0);
    const V3 w = rot(v);
    for (size_t i = 0; i < 3; ++i)
      sp[i][k] = w[i] + (k == 0 ? shift[i] : Rational(0));
  }
  return core::make_canal(sp, c.radius, c.t0, c.t1);
}

core::Torus torus_z() {
  return core::make_torus({0, 0, 0}, {0, 0, 1}, 3, 1);
}

} // namespace

TEST(CanalPair, RandomCapsulesAgainstTheClosedForm) {
  std::mt19937 rng(515);
  std::uniform_int_distribution<long> c(-8, 8), r(1, 4);
  int compared = 0;
  for (int k = 0; k < 25; ++k) {
    const auto A =
        capsule({c(rng), c(rng), c(rng)}, {c(rng), c(rng), c(rng) + 1}, Rational(r(rng), 4));
    const auto B =
        capsule({c(rng), c(rng), c(rng)}, {c(rng) + 1, c(rng), c(rng)}, Rational(r(rng), 4));
    const auto ref = certify::capsule_pair_distance(A, B, 15);
    if (!ref || ref->minimizers == "infinite") continue; // solids meet, or parallel continuum
    const auto mine = certify::canal_pair_distance(core::Surface(A), core::Surface(B), 15);
    ASSERT_TRUE(mine.has_value()) << "seed 515 case " << k;
    EXPECT_TRUE(overlap(*mine, *ref))
        << "seed 515 case " << k << ": " << mine->lower << " vs " << ref->lower;
    const auto back = certify::canal_pair_distance(core::Surface(B), core::Surface(A), 15);
    ASSERT_TRUE(back.has_value());
    EXPECT_TRUE(overlap(*back, *ref));
    ++compared;
  }
  EXPECT_GE(compared, 10);
}

TEST(CanalPair, TorusClosedForms) {
  // A capsule from (0, 0, 5) to (4, 0, 5), radius 1, above the torus R = 3, r = 1: 5 - 1 - 1.
  auto r = certify::canal_pair_distance(core::Surface(torus_z()),
                                        core::Surface(capsule({0, 0, 5}, {4, 0, 5}, 1)), 15);
  ASSERT_TRUE(r.has_value());
  EXPECT_LE(lo(*r), 3);
  EXPECT_GE(std::stod(r->upper), 3);
  // Spine (t, 0, 9 - t^2), t in [-2, 2], radius 1/2: nearest at the end balls (+-2, 0, 5),
  // |(2, 0, 5) - (3, 0, 0)| = sqrt(26): d = sqrt(26) - 3/2, twice.
  const auto K =
      core::make_canal({std::vector<Rational>{0, 1}, {0}, {9, 0, -1}}, {Rational(1, 2)}, -2, 2);
  for (long digits : {15L, 100L}) {
    r = certify::canal_pair_distance(core::Surface(torus_z()), core::Surface(K), digits);
    ASSERT_TRUE(r.has_value()) << digits;
    mpfr_t d, l, u;
    mpfr_inits2(800, d, l, u, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_ui(d, 26, MPFR_RNDN);
    mpfr_sqrt(d, d, MPFR_RNDN);
    mpfr_sub_d(d, d, 1.5, MPFR_RNDN);
    mpfr_set_str(l, r->lower.c_str(), 10, MPFR_RNDD);
    mpfr_set_str(u, r->upper.c_str(), 10, MPFR_RNDU);
    EXPECT_TRUE(mpfr_cmp(l, d) <= 0 && mpfr_cmp(d, u) <= 0) << digits << ": " << r->lower;
    mpfr_clears(d, l, u, static_cast<mpfr_ptr>(nullptr));
    EXPECT_EQ(r->minimizers, "2");
  }
  const auto full =
      certify::surface_distance(core::Surface(torus_z()), core::Surface(K), 15, false);
  EXPECT_EQ(full.method, "sphere_family_bnb");
  EXPECT_EQ(full.ties, "proven") << full.note;
}

TEST(CanalPair, GrowingRadiusAgainstSampling) {
  // Spine (t, t^2/2, 4 + t/3), radius 1/4 + t^2/8, t in [-1, 2], against the torus.
  const auto K =
      core::make_canal({std::vector<Rational>{0, 1}, {0, 0, Rational(1, 2)}, {4, Rational(1, 3)}},
                       {Rational(1, 4), 0, Rational(1, 8)}, -1, 2);
  const auto r = certify::canal_pair_distance(core::Surface(K), core::Surface(torus_z()), 15);
  ASSERT_TRUE(r.has_value());
  double best = 1e300;
  for (int i = 0; i <= 300; ++i) {
    const double t = -1 + 3.0 * i / 300, rad = 0.25 + t * t / 8;
    const double c[3] = {t, t * t / 2, 4 + t / 3};
    for (int a = 0; a < 24; ++a)
      for (int b = 0; b < 12; ++b) { // points of the ball (its sphere)
        const double th = 2 * M_PI * a / 24, ph = M_PI * (b + 0.5) / 12;
        const double p[3] = {c[0] + rad * std::sin(ph) * std::cos(th),
                             c[1] + rad * std::sin(ph) * std::sin(th), c[2] + rad * std::cos(ph)};
        // distance from p to the torus surface in closed form
        const double rho = std::hypot(p[0], p[1]);
        best = std::min(best, std::fabs(std::hypot(rho - 3, p[2]) - 1));
      }
  }
  EXPECT_GE(best, lo(*r) - 1e-12);
  EXPECT_LT(best - r->approx, 0.05);
  for (const auto& pr : r->pairs) // the torus point lies on the torus
    EXPECT_NEAR(std::hypot(std::hypot(pr[1][0], pr[1][1]) - 3, pr[1][2]), 1, 1e-9);
  // Rigid motion of both (the torus axis and centre moved the same way), swapped order.
  const V3 shift{Rational(7, 3), Rational(-2), Rational(1, 5)};
  const auto Km = moved(K, shift);
  const auto Tm = core::make_torus(shift, rot({0, 0, 1}), 3, 1);
  const auto m = certify::canal_pair_distance(core::Surface(Tm), core::Surface(Km), 15);
  ASSERT_TRUE(m.has_value());
  EXPECT_TRUE(overlap(*m, *r)) << m->lower << " vs " << r->lower;
}

TEST(CanalPair, OverlappingSolidsAreRefused) {
  const auto K =
      core::make_canal({std::vector<Rational>{0, 1}, {0}, {9, 0, -1}}, {Rational(1, 2)}, -2, 2);
  EXPECT_FALSE(certify::canal_pair_distance(core::Surface(K),
                                            core::Surface(capsule({0, 0, 5}, {4, 0, 5}, 1)), 15));
  EXPECT_FALSE(certify::canal_pair_distance(core::Surface(torus_z()),
                                            core::Surface(capsule({0, 0, 0}, {5, 0, 0}, 1)), 15));
}
