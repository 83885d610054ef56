// The sphere-family route (sphere_family.hpp): canal surfaces and tori as unions of balls,
// each result against an independent route:
// - random capsule pairs against the exact segment-segment closed form (capsule_pair.hpp), both
//   orders (fixed seed, printed on failure);
// - a cone frustum (linear spine, linear radius) against a capsule pointing away from it: the
//   closed form p sqrt(1 - k^2) - k a - r0 - rho of min_s |C(s) - P| - r(s) (MPFR, 15 and 100
//   digits; an edge minimum of the capsule);
// - a parabolic arc of constant radius against a skew capsule: sqrt(5) - r1 - r2 (an interior
//   minimum), a torus against a capsule parallel to its axis: sqrt((R - a)^2 + h^2) - r - rho;
// - a capsule on the torus axis: a circle of minimizers, never certified as one answer;
// - rational rigid motions, scaling by 10^3 and 10^-3, swapping a and b (the pairs swap);
// - touching and overlapping solids are never certified with a positive distance.
#include "surfcert/certify/distance/capsule_pair.hpp"
#include "surfcert/certify/distance/sphere_family.hpp"
#include "surfcert/certify/distance/symmetry.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <cmath>
#include <random>
#include <string>

using namespace surfcert;
using core::Rational;
using surfcert::testing::overlap;

namespace {

using V3 = std::array<Rational, 3>;
using Result = std::optional<certify::DistanceResult>;

core::CanalSurface capsule(const V3& a, const V3& b, const Rational& r) {
  std::array<std::vector<Rational>, 3> sp;
  for (size_t i = 0; i < 3; ++i)
    sp[i] = {a[i], b[i] - a[i]};
  return core::make_canal(sp, {r}, Rational(0), Rational(1));
}

// x -> R x with R the rotation of the integer quaternion (w, x, y, z) (exact rationals).
struct Rotation {
  long q[4];
  V3 operator()(const V3& v) const {
    const long w = q[0], a = q[1], b = q[2], c = q[3];
    const long n = w * w + a * a + b * b + c * c;
    const long R[3][3] = {
        {w * w + a * a - b * b - c * c, 2 * (a * b - w * c), 2 * (a * c + w * b)},
        {2 * (a * b + w * c), w * w - a * a + b * b - c * c, 2 * (b * c - w * a)},
        {2 * (a * c - w * b), 2 * (b * c + w * a), w * w - a * a - b * b + c * c}};
    V3 y{Rational(0), Rational(0), Rational(0)};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        y[i] += Rational(R[i][j], n) * v[j];
    return y;
  }
};

// x -> s R x + shift applied to a canal surface / a torus.
core::CanalSurface moved(const core::CanalSurface& c, const Rotation& rot, const Rational& s,
                         const V3& shift) {
  std::array<std::vector<Rational>, 3> sp;
  size_t n = 0;
  for (const auto& p : c.spine)
    n = std::max(n, p.size());
  for (auto& p : sp)
    p.assign(n, Rational(0));
  for (size_t k = 0; k < n; ++k) {
    V3 v;
    for (size_t i = 0; i < 3; ++i)
      v[i] = k < c.spine[i].size() ? c.spine[i][k] * s : Rational(0);
    const V3 w = rot(v);
    for (size_t i = 0; i < 3; ++i)
      sp[i][k] = w[i] + (k == 0 ? shift[i] : Rational(0));
  }
  std::vector<Rational> r = c.radius;
  for (auto& x : r)
    x *= s;
  return core::make_canal(sp, r, c.t0, c.t1);
}
core::Torus moved(const core::Torus& t, const Rotation& rot, const Rational& s, const V3& shift) {
  V3 c = rot(t.centre);
  for (size_t i = 0; i < 3; ++i)
    c[i] = c[i] * s + shift[i];
  return core::make_torus(c, rot(t.axis), t.R * s, t.r * s);
}

// The closed form `ref` (an MPFR value) lies in [lower, upper].
bool encloses(const certify::DistanceResult& r, const mpfr_t ref) {
  mpfr_t l, u;
  mpfr_inits2(3000, l, u, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(l, r.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u, r.upper().c_str(), 10, MPFR_RNDU);
  const bool ok = mpfr_cmp(l, ref) <= 0 && mpfr_cmp(ref, u) <= 0;
  mpfr_clears(l, u, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

// [lower, upper] of a times num/den overlaps [lower, upper] of b.
bool overlap_scaled(const certify::DistanceResult& a, unsigned long num, unsigned long den,
                    const certify::DistanceResult& b) {
  mpfr_t la, ua, lb, ub;
  mpfr_inits2(3000, la, ua, lb, ub, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(la, a.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(ua, a.upper().c_str(), 10, MPFR_RNDU);
  mpfr_mul_ui(la, la, num, MPFR_RNDD);
  mpfr_div_ui(la, la, den, MPFR_RNDD);
  mpfr_mul_ui(ua, ua, num, MPFR_RNDU);
  mpfr_div_ui(ua, ua, den, MPFR_RNDU);
  mpfr_set_str(lb, b.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(ub, b.upper().c_str(), 10, MPFR_RNDU);
  const bool ok = mpfr_cmp(la, ub) <= 0 && mpfr_cmp(lb, ua) <= 0;
  mpfr_clears(la, ua, lb, ub, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

double pair_length(const std::array<std::array<double, 3>, 2>& p) {
  return std::hypot(p[0][0] - p[1][0], p[0][1] - p[1][1], p[0][2] - p[1][2]);
}

bool certified_positive(const Result& r) {
  return r && r->status == certify::Status::Certified && std::stod(r->lower()) > 0;
}

} // namespace

namespace {

unsigned seed_or(unsigned fallback) {
  const char* s = std::getenv("SURFCERT_TEST_SEED");
  return s ? static_cast<unsigned>(std::stoul(s)) : fallback;
}

core::Torus torus_z() {
  return core::make_torus({0, 0, 0}, {0, 0, 1}, 3, 1);
}

// mpfr value sqrt(q) * a + b (q, a, b rational given as num/den pairs in doubles is enough:
// all are small integers over small denominators).
void closed_form(mpfr_t out, long q, long a_num, long a_den, long b_num, long b_den) {
  mpfr_t t;
  mpfr_init2(t, 3000);
  mpfr_set_si(out, q, MPFR_RNDN);
  mpfr_sqrt(out, out, MPFR_RNDN);
  mpfr_mul_si(out, out, a_num, MPFR_RNDN);
  mpfr_div_si(out, out, a_den, MPFR_RNDN);
  mpfr_set_si(t, b_num, MPFR_RNDN);
  mpfr_div_si(t, t, b_den, MPFR_RNDN);
  mpfr_add(out, out, t, MPFR_RNDN);
  mpfr_clear(t);
}

void expect_closed_form(const core::Surface& a, const core::Surface& b, long q, long a_num,
                        long a_den, long b_num, long b_den, const std::string& what) {
  mpfr_t ref;
  mpfr_init2(ref, 3000);
  closed_form(ref, q, a_num, a_den, b_num, b_den);
  Result prev;
  for (long digits : {15L, 100L}) {
    const Result r = certify::sphere_family_distance(a, b, digits);
    ASSERT_TRUE(r.has_value()) << what << " digits " << digits;
    EXPECT_EQ(r->status, certify::Status::Certified) << what;
    EXPECT_TRUE(encloses(*r, ref))
        << what << " digits " << digits << ": [" << r->lower() << ", " << r->upper() << "]";
    EXPECT_EQ(r->minimizers, "1") << what << ": " << r->note;
    EXPECT_EQ(r->method, certify::Method::SphereFamilyBnb);
    ASSERT_EQ(r->pairs.size(), 1u) << what;
    EXPECT_NEAR(pair_length(r->pairs[0]), r->approx(), 1e-9) << what;
    if (prev) {
      EXPECT_TRUE(overlap(*prev, *r)) << what;
    }
    prev = r;
  }
  // swapped: the same enclosure, the pair swapped
  const Result s = certify::sphere_family_distance(b, a, 15);
  ASSERT_TRUE(s.has_value()) << what << " swapped";
  EXPECT_TRUE(encloses(*s, ref)) << what << " swapped";
  ASSERT_EQ(s->pairs.size(), 1u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(s->pairs[0][0][i], prev->pairs[0][1][i], 1e-9) << what;
    EXPECT_NEAR(s->pairs[0][1][i], prev->pairs[0][0][i], 1e-9) << what;
  }
  mpfr_clear(ref);
}

} // namespace

TEST(SphereFamily, RandomCapsulesAgainstTheClosedForm) {
  const unsigned seed = seed_or(20261122);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<long> c(-8, 8), r(1, 4);
  int compared = 0;
  for (int k = 0; k < 20; ++k) {
    const auto A =
        capsule({c(rng), c(rng), c(rng)}, {c(rng), c(rng), c(rng) + 1}, Rational(r(rng), 4));
    const auto B =
        capsule({c(rng), c(rng), c(rng)}, {c(rng) + 1, c(rng), c(rng)}, Rational(r(rng), 4));
    const auto ref = certify::capsule_pair_distance(A, B, 15);
    const Result mine = certify::sphere_family_distance(core::Surface(A), core::Surface(B), 15);
    if (!ref) { // the solids meet: never a positive certified distance here
      EXPECT_FALSE(certified_positive(mine)) << "seed " << seed << " case " << k;
      continue;
    }
    if (ref->minimizers == "infinite") continue; // parallel: a continuum
    ASSERT_TRUE(mine.has_value()) << "seed " << seed << " case " << k;
    EXPECT_TRUE(overlap(*mine, *ref))
        << "seed " << seed << " case " << k << ": " << mine->lower() << " vs " << ref->lower();
    EXPECT_EQ(mine->minimizers, "1") << "seed " << seed << " case " << k;
    ASSERT_FALSE(mine->pairs.empty());
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 2; ++j)
        EXPECT_NEAR(mine->pairs[0][j][i], ref->pairs[0][j][i], 1e-7)
            << "seed " << seed << " case " << k;
    const Result back = certify::sphere_family_distance(core::Surface(B), core::Surface(A), 15);
    ASSERT_TRUE(back.has_value()) << "seed " << seed << " case " << k;
    EXPECT_TRUE(overlap(*back, *ref)) << "seed " << seed << " case " << k;
    ++compared;
  }
  EXPECT_GE(compared, 8) << "seed " << seed;
}

TEST(SphereFamily, ConeFrustumAgainstAnEndBall) {
  // C(s) = (s, 0, 0), r(s) = 1/2 + s/4 on [0, 4]; the capsule from P = (1, 3, 0) to (1, 5, 0)
  // (radius 1/4) points away from the spine, so its end ball at P is nearest, and
  // min_s |C(s) - P| - r(s) = 3 sqrt(1 - 1/16) - 1/4 - 1/2: d = 3 sqrt(15)/4 - 1.
  const auto cone = core::make_canal({std::vector<Rational>{0, 1}, {0}, {0}},
                                     {Rational(1, 2), Rational(1, 4)}, 0, 4);
  const auto cap = capsule({1, 3, 0}, {1, 5, 0}, Rational(1, 4));
  expect_closed_form(core::Surface(cone), core::Surface(cap), 15, 3, 4, -1, 1, "cone");
  const Rotation rot{{2, 1, -2, 1}};
  const V3 shift{Rational(7, 3), Rational(-2), Rational(1, 5)};
  expect_closed_form(core::Surface(moved(cone, rot, 1, shift)),
                     core::Surface(moved(cap, rot, 1, shift)), 15, 3, 4, -1, 1, "cone moved");
}

TEST(SphereFamily, ParabolicArcAgainstASkewCapsule) {
  // Spine (t, t^2, 0), t in [-1, 1], radius 1/4; the segment y = -2, z = 1, x in [-3, 3],
  // radius 1/3: |(t - x, t^2 + 2, -1)| is least at t = x = 0, d = sqrt(5) - 7/12.
  const auto arc =
      core::make_canal({std::vector<Rational>{0, 1}, {0, 0, 1}, {0}}, {Rational(1, 4)}, -1, 1);
  const auto cap = capsule({-3, -2, 1}, {3, -2, 1}, Rational(1, 3));
  expect_closed_form(core::Surface(arc), core::Surface(cap), 5, 1, 1, -7, 12, "arc");
}

TEST(SphereFamily, TorusAgainstACapsuleParallelToItsAxis) {
  // Torus R = 3, r = 1 around the z axis; the segment x = 1, y = 0, z in [2, 5], radius 1/2:
  // the nearest core point is (3, 0, 0) (at the seam of the circle's parameter), the nearest
  // segment point its lower end: d = sqrt(4 + 4) - 1 - 1/2.
  const auto cap = capsule({1, 0, 2}, {1, 0, 5}, Rational(1, 2));
  expect_closed_form(core::Surface(torus_z()), core::Surface(cap), 8, 1, 1, -3, 2, "torus");
  const Result r = certify::sphere_family_distance(torus_z(), cap, 15);
  ASSERT_TRUE(r.has_value());
  for (const auto& pr : r->pairs)
    EXPECT_NEAR(std::hypot(std::hypot(pr[0][0], pr[0][1]) - 3, pr[0][2]), 1, 1e-9);
}

TEST(SphereFamily, CapsuleOnTheTorusAxisIsAContinuum) {
  // On the axis every core point is equally near (sqrt(13) - 3/2 at a circle of pairs): never
  // reported as one certified minimizer.
  const auto cap = capsule({0, 0, 2}, {0, 0, 5}, Rational(1, 2));
  const Result r = certify::sphere_family_distance(torus_z(), cap, 15);
  if (r) {
    EXPECT_NE(r->minimizers, "1");
    mpfr_t ref;
    mpfr_init2(ref, 3000);
    closed_form(ref, 13, 1, 1, -3, 2);
    EXPECT_TRUE(encloses(*r, ref));
    mpfr_clear(ref);
  }
}

TEST(SphereFamily, RigidMotionScalingSwapAndDigits) {
  // A canal with a curved spine and a growing radius against the torus and against a capsule.
  const auto K =
      core::make_canal({std::vector<Rational>{0, 1}, {0, 0, Rational(1, 2)}, {4, Rational(1, 3)}},
                       {Rational(1, 4), 0, Rational(1, 8)}, -1, 2);
  const auto cap = capsule({-2, 3, -1}, {4, 2, 1}, Rational(1, 3));
  const Rotation rot{{1, 2, 3, -1}};
  const V3 shift{Rational(-5, 2), Rational(1, 7), Rational(3)};
  for (int which = 0; which < 2; ++which) {
    const core::Surface other = which == 0 ? core::Surface(torus_z()) : core::Surface(cap);
    auto move = [&](const core::Surface& s, const Rational& f) -> core::Surface {
      if (const auto* c = std::get_if<core::CanalSurface>(&s)) return moved(*c, rot, f, shift);
      return moved(std::get<core::Torus>(s), rot, f, shift);
    };
    const Result r = certify::sphere_family_distance(core::Surface(K), other, 15);
    ASSERT_TRUE(r.has_value()) << which;
    EXPECT_GT(std::stod(r->lower()), 0);
    const Result r100 = certify::sphere_family_distance(core::Surface(K), other, 100);
    ASSERT_TRUE(r100.has_value()) << which;
    EXPECT_TRUE(overlap(*r, *r100)) << which;
    const Result m = certify::sphere_family_distance(move(K, 1), move(other, 1), 15);
    ASSERT_TRUE(m.has_value()) << which;
    EXPECT_TRUE(overlap(*r, *m)) << which << ": " << r->lower() << " vs " << m->lower();
    for (const auto& [num, den] : {std::pair<unsigned long, unsigned long>{1000, 1}, {1, 1000}}) {
      const Rational f(static_cast<long>(num), static_cast<long>(den));
      const Result sc = certify::sphere_family_distance(move(K, f), move(other, f), 15);
      ASSERT_TRUE(sc.has_value()) << which << " scale " << num << "/" << den;
      EXPECT_TRUE(overlap_scaled(*r, num, den, *sc))
          << which << " scale " << num << "/" << den << ": " << sc->lower();
    }
    const Result s = certify::sphere_family_distance(other, core::Surface(K), 15);
    ASSERT_TRUE(s.has_value()) << which;
    EXPECT_TRUE(overlap(*r, *s)) << which;
    ASSERT_EQ(s->pairs.size(), r->pairs.size());
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_NEAR(s->pairs[0][0][i], r->pairs[0][1][i], 1e-9);
      EXPECT_NEAR(s->pairs[0][1][i], r->pairs[0][0][i], 1e-9);
    }
  }
}

TEST(SphereFamily, TouchingAndOverlappingSolidsAreNotCertified) {
  const Rational h(1, 2);
  const std::vector<std::pair<core::Surface, core::Surface>> cases = {
      // crossed capsules touching at (1, 1/2, 0)
      {capsule({0, 0, 0}, {2, 0, 0}, h), capsule({1, 1, -1}, {1, 1, 1}, h)},
      // parallel capsules touching along a segment
      {capsule({0, 0, 0}, {1, 0, 0}, h), capsule({0, 1, 0}, {1, 1, 0}, h)},
      // crossed capsules overlapping
      {capsule({0, 0, 0}, {2, 0, 0}, Rational(3, 4)), capsule({1, 1, -1}, {1, 1, 1}, h)},
      // a capsule through the tube of the torus, one resting on its top circle, one inside
      {torus_z(), capsule({0, 0, 0}, {5, 0, 0}, 1)},
      {torus_z(), capsule({3, -1, 2}, {3, 1, 2}, 1)},
      {capsule({3, Rational(-1, 10), 0}, {3, Rational(1, 10), 0}, Rational(1, 10)), torus_z()},
  };
  for (size_t k = 0; k < cases.size(); ++k)
    for (long digits : {15L, 40L}) {
      const Result r = certify::sphere_family_distance(cases[k].first, cases[k].second, digits);
      EXPECT_FALSE(certified_positive(r)) << "case " << k << ": " << (r ? r->lower() : "");
    }
}

TEST(SphereFamily, TwoEndBallMinimaAreReportedAsTies) {
  // Spine (t, 0, 9 - t^2), t in [-2, 2], radius 1/2, above the torus: the end balls at
  // (+-2, 0, 5) are nearest, |(2, 0, 5) - (3, 0, 0)| = sqrt(26): d = sqrt(26) - 3/2, twice
  // (mirror images; this route does not prove the tie itself).
  const auto K =
      core::make_canal({std::vector<Rational>{0, 1}, {0}, {9, 0, -1}}, {Rational(1, 2)}, -2, 2);
  mpfr_t ref;
  mpfr_init2(ref, 3000);
  closed_form(ref, 26, 1, 1, -3, 2);
  for (long digits : {15L, 100L}) {
    const Result r = certify::sphere_family_distance(torus_z(), K, digits);
    ASSERT_TRUE(r.has_value()) << digits;
    EXPECT_TRUE(encloses(*r, ref)) << digits << ": " << r->lower();
    EXPECT_EQ(r->minimizers, "2") << r->note;
    EXPECT_EQ(r->ties, certify::Ties::Unproven);
    ASSERT_EQ(r->pairs.size(), 2u);
    EXPECT_NEAR(r->pairs[0][1][0], -r->pairs[1][1][0], 1e-9); // mirror images in x
    // the regions let the exact symmetry x -> -x of both surfaces prove the tie
    certify::DistanceResult t = *r;
    certify::prove_ties(t, core::Surface(torus_z()), core::Surface(K));
    EXPECT_EQ(t.ties, certify::Ties::Proven) << t.note;
  }
  mpfr_clear(ref);
}

TEST(SphereFamily, ParallelContinuumAndVanishingRadiusAreRefused) {
  // Parallel capsules with overlapping projections: a segment of closest pairs (the closed form
  // reports "infinite"); never one certified minimizer.
  const auto A = capsule({0, 0, 0}, {4, 0, 0}, Rational(1, 2));
  const auto B = capsule({1, 3, 0}, {6, 3, 0}, Rational(1, 4));
  const auto ref = certify::capsule_pair_distance(A, B, 15);
  ASSERT_TRUE(ref.has_value());
  ASSERT_EQ(ref->minimizers, "infinite");
  const Result r = certify::sphere_family_distance(core::Surface(A), core::Surface(B), 15);
  if (r) {
    EXPECT_NE(r->minimizers, "1");
    EXPECT_TRUE(overlap(*r, *ref));
  }
  // r(t) = (t - 1/2)^2 + 0 vanishes inside [0, 1]: the solid is not a union of proper balls.
  const auto V = core::make_canal({std::vector<Rational>{0, 1}, {0}, {0}},
                                  {Rational(1, 4), Rational(-1), Rational(1)}, 0, 1);
  EXPECT_FALSE(certify::sphere_family_distance(core::Surface(V), core::Surface(B), 15));
}

TEST(SphereFamily, GrowingRadiusAgainstSampledBalls) {
  // Spine (t, t^2/2, 4 + t/3), radius 1/4 + t^2/8, t in [-1, 2], against the torus R = 3, r = 1
  // about z: points sampled on the canal's balls (inside its solid) and the closed-form distance
  // of each to the torus surface are never below the certified lower bound (the solids are
  // disjoint) and come close to it; the torus-side pair point lies on the torus.
  const auto K =
      core::make_canal({std::vector<Rational>{0, 1}, {0, 0, Rational(1, 2)}, {4, Rational(1, 3)}},
                       {Rational(1, 4), 0, Rational(1, 8)}, -1, 2);
  const auto T = core::make_torus({0, 0, 0}, {0, 0, 1}, 3, 1);
  const auto r = certify::sphere_family_distance(core::Surface(K), core::Surface(T), 15);
  ASSERT_TRUE(r.has_value());
  double best = 1e300;
  for (int i = 0; i <= 300; ++i) {
    const double t = -1 + 3.0 * i / 300, rad = 0.25 + t * t / 8;
    const double c[3] = {t, t * t / 2, 4 + t / 3};
    for (int a = 0; a < 24; ++a)
      for (int b = 0; b < 12; ++b) {
        const double th = 2 * M_PI * a / 24, ph = M_PI * (b + 0.5) / 12;
        const double p[3] = {c[0] + rad * std::sin(ph) * std::cos(th),
                             c[1] + rad * std::sin(ph) * std::sin(th), c[2] + rad * std::cos(ph)};
        best = std::min(best, std::fabs(std::hypot(std::hypot(p[0], p[1]) - 3, p[2]) - 1));
      }
  }
  EXPECT_GE(best, surfcert::testing::lo(*r) - 1e-12);
  EXPECT_LT(best - r->approx(), 0.05);
  for (const auto& pr : r->pairs)
    EXPECT_NEAR(std::hypot(std::hypot(pr[1][0], pr[1][1]) - 3, pr[1][2]), 1, 1e-9);
}
