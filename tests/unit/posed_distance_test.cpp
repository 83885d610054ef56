// The separated-pair certificate straight from doubles (separated_posed_ellipsoids: ellipsoids
// and spheres posed with double centres, radii and quaternions; Arb balls from the exact
// doubles, no rationals), each result against an independent route:
// - random separated pairs: the same certificate on the exact rational description
//   (convex_quadric + separated_convex_distance: W = R D^2 R^T as exact rationals) - the
//   enclosures overlap and both meet the requested digits (15 and 30);
// - closed forms computed exactly from the doubles (MPFR at 2000 bits): two spheres (turned
//   by random quaternions, which must not matter) |c1 - c2| - r1 - r2; two ellipsoids turned
//   about the x axis and centred on it, whose gap X - a1 - a2 is exact (the slab between
//   their x-extremes separates them and the x-vertices realise it);
// - thresholds from both sides: relative gaps 2^-10, 2^-40, 2^-53 and absolute 2^-100 (at
//   scale 2^-60) certify or decline, never wrongly; tangent and overlapping pairs decline, and
//   surface_distance still answers them (0);
// - extremes: a sphere of radius 1e-300, 1e150 apart, 1e-300 apart at scale 1e-290;
// - swapping a and b gives the same enclosure with the pair swapped; nested pairs decline.
#include "surfcert/certify/distance/convex_distance.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "support/canonical.hpp"
#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace surfcert;
using surfcert::testing::overlap;
using surfcert::testing::test_seed;

namespace {

struct Posed {
  double r[3], c[3], q[4];
  bool sphere = false, rotated = true;
  std::string json() const {
    char buf[600];
    if (sphere)
      std::snprintf(buf, sizeof buf,
                    R"({"type":"sphere","radius":%.17g,"center":[%.17g,%.17g,%.17g])", r[0], c[0],
                    c[1], c[2]);
    else
      std::snprintf(
          buf, sizeof buf,
          R"({"type":"ellipsoid","radii":[%.17g,%.17g,%.17g],"center":[%.17g,%.17g,%.17g])", r[0],
          r[1], r[2], c[0], c[1], c[2]);
    std::string s = buf;
    if (rotated) {
      std::snprintf(buf, sizeof buf, R"(,"rotation":{"quaternion":[%.17g,%.17g,%.17g,%.17g]})",
                    q[0], q[1], q[2], q[3]);
      s += buf;
    }
    return s + "}";
  }
  core::QuadricMatrix read() const {
    return core::io::read_quadric(core::io::parse_json(json(), "t"), "t", "$");
  }
};

void random_quaternion(std::mt19937_64& rng, double (&q)[4]) {
  std::normal_distribution<double> g;
  double n = 0;
  for (double& x : q) {
    x = g(rng);
    n += x * x;
  }
  for (double& x : q)
    x /= std::sqrt(n);
}

// The bench's separated family: centres in [-1/2, 1/2]^3, semi-axes in [1/10, 1], the second
// pushed out along a random direction by the sum of the largest semi-axes + [0.01, 1].
std::pair<Posed, Posed> random_separated(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> cen(-0.5, 0.5), rad(0.1, 1.0), gap(0.01, 1.0);
  std::normal_distribution<double> g;
  Posed a, b;
  for (Posed* p : {&a, &b}) {
    for (int k = 0; k < 3; ++k) {
      p->c[k] = cen(rng);
      p->r[k] = rad(rng);
    }
    random_quaternion(rng, p->q);
  }
  double d[3] = {g(rng), g(rng), g(rng)};
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double push =
      std::max({a.r[0], a.r[1], a.r[2]}) + std::max({b.r[0], b.r[1], b.r[2]}) + gap(rng);
  for (int k = 0; k < 3; ++k)
    b.c[k] = a.c[k] + d[k] / len * push;
  return {a, b};
}

std::optional<certify::DistanceResult> fast(const core::QuadricMatrix& a,
                                            const core::QuadricMatrix& b, long digits) {
  if (a.shape() == nullptr || b.shape() == nullptr) return std::nullopt;
  return certify::separated_posed_ellipsoids(*a.shape(), *b.shape(), digits);
}

// upper - lower <= 10^-digits lower on the printed decimals, exactly (MPFR, 4000 bits).
bool width_ok(const certify::DistanceResult& r, long digits) {
  mpfr_t l, u, w, t;
  mpfr_inits2(4000, l, u, w, t, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(l, r.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u, r.upper().c_str(), 10, MPFR_RNDU);
  mpfr_sub(w, u, l, MPFR_RNDU);
  mpfr_ui_pow_ui(t, 10, static_cast<unsigned long>(digits), MPFR_RNDD);
  mpfr_div(t, l, t, MPFR_RNDD);
  const bool ok = mpfr_sgn(l) > 0 && mpfr_cmp(w, t) <= 0;
  mpfr_clears(l, u, w, t, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

// The exact value x (an MPFR number at 2000 bits, computed from the doubles) lies in r.
bool holds(const certify::DistanceResult& r, const mpfr_t x) {
  return surfcert::testing::contains(r, x);
}

// |c1 - c2| - r1 - r2 from the doubles, at 2000 bits (error far below any enclosure width).
void sphere_gap(mpfr_t out, const double (&c1)[3], double r1, const double (&c2)[3], double r2) {
  mpfr_t t, s;
  mpfr_inits2(2000, t, s, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_ui(s, 0, MPFR_RNDN);
  for (int k = 0; k < 3; ++k) {
    mpfr_set_d(t, c1[k], MPFR_RNDN);
    mpfr_sub_d(t, t, c2[k], MPFR_RNDN);
    mpfr_sqr(t, t, MPFR_RNDN);
    mpfr_add(s, s, t, MPFR_RNDN);
  }
  mpfr_sqrt(out, s, MPFR_RNDN);
  mpfr_sub_d(out, out, r1, MPFR_RNDN);
  mpfr_sub_d(out, out, r2, MPFR_RNDN);
  mpfr_clears(t, s, static_cast<mpfr_ptr>(nullptr));
}

Posed sphere(double r, double x, double y = 0, double z = 0) {
  Posed p;
  p.sphere = true;
  p.rotated = false;
  p.r[0] = p.r[1] = p.r[2] = r;
  p.c[0] = x;
  p.c[1] = y;
  p.c[2] = z;
  p.q[0] = 1;
  p.q[1] = p.q[2] = p.q[3] = 0;
  return p;
}

} // namespace

TEST(PosedDistance, RandomPairsAgainstTheExactRationalCertificate) {
  const auto seed = test_seed();
  std::mt19937_64 rng(seed);
  for (int t = 0; t < 300; ++t) {
    const auto [pa, pb] = random_separated(rng);
    const auto a = pa.read(), b = pb.read();
    const std::string ctx = "seed " + std::to_string(seed) + " pair " + std::to_string(t) + ": " +
                            pa.json() + " " + pb.json();
    for (long digits : {15L, 30L}) {
      if (digits == 30 && t % 10 != 0) continue;
      const auto r = fast(a, b, digits);
      ASSERT_TRUE(r.has_value()) << ctx;
      const auto ca = certify::convex_quadric(a), cb = certify::convex_quadric(b);
      ASSERT_TRUE(ca && cb);
      const auto e = certify::separated_convex_distance(*ca, *cb, digits);
      ASSERT_TRUE(e.has_value()) << ctx;
      EXPECT_TRUE(overlap(*r, *e)) << ctx << ": [" << r->lower() << ", " << r->upper() << "] vs ["
                                   << e->lower() << ", " << e->upper() << "]";
      EXPECT_TRUE(width_ok(*r, digits)) << ctx << " [" << r->lower() << ", " << r->upper() << "]";
      EXPECT_TRUE(width_ok(*e, digits)) << ctx;
      EXPECT_EQ(r->status, certify::Status::Certified);
      EXPECT_EQ(r->minimizers, e->minimizers);
      ASSERT_EQ(r->pairs.size(), 1u);
      for (int s = 0; s < 2; ++s)
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(r->pairs[0][s][k], e->pairs[0][s][k], 1e-9) << ctx;
    }
    // Through the public API: the same route, the same enclosure.
    if (t % 20 == 0) {
      const auto s = certify::surface_distance(a, b, 15, false);
      EXPECT_EQ(s.method, certify::Method::ConvexDuality) << ctx;
      EXPECT_TRUE(overlap(s, *fast(a, b, 15))) << ctx;
    }
  }
}

TEST(PosedDistance, ClosedForms) {
  std::mt19937_64 rng(test_seed() + 1);
  std::uniform_real_distribution<double> u(-1, 1), rad(0.05, 2);
  mpfr_t x;
  mpfr_init2(x, 2000);
  // Two spheres, turned by random quaternions (a sphere's rotation changes nothing).
  for (int t = 0; t < 50; ++t) {
    Posed a = sphere(rad(rng), u(rng), u(rng), u(rng)), b = sphere(rad(rng), 0, 0, 0);
    a.rotated = b.rotated = t % 2 == 0;
    random_quaternion(rng, a.q);
    random_quaternion(rng, b.q);
    double d[3] = {u(rng), u(rng), u(rng)};
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; ++k)
      b.c[k] = a.c[k] + d[k] / len * (a.r[0] + b.r[0] + 0.001 + std::fabs(u(rng)));
    const auto r = fast(a.read(), b.read(), 15);
    ASSERT_TRUE(r.has_value()) << a.json() << " " << b.json();
    sphere_gap(x, a.c, a.r[0], b.c, b.r[0]);
    EXPECT_TRUE(holds(*r, x)) << a.json() << " " << b.json() << " [" << r->lower() << ", "
                              << r->upper() << "]";
    EXPECT_TRUE(width_ok(*r, 15));
  }
  // Two ellipsoids centred on the x axis and turned about it: the gap is X - a1 - a2 exactly.
  for (int t = 0; t < 50; ++t) {
    Posed a, b;
    for (Posed* p : {&a, &b}) {
      for (int k = 0; k < 3; ++k) {
        p->r[k] = rad(rng);
        p->c[k] = 0;
      }
      const double th = 3 * u(rng);
      p->q[0] = std::cos(th);
      p->q[1] = std::sin(th);
      p->q[2] = p->q[3] = 0;
    }
    b.c[0] = a.r[0] + b.r[0] + 0.01 + std::fabs(u(rng));
    const auto r = fast(a.read(), b.read(), 15);
    ASSERT_TRUE(r.has_value()) << a.json() << " " << b.json();
    mpfr_set_d(x, b.c[0], MPFR_RNDN);
    mpfr_sub_d(x, x, a.r[0], MPFR_RNDN);
    mpfr_sub_d(x, x, b.r[0], MPFR_RNDN); // exact at 2000 bits
    EXPECT_TRUE(holds(*r, x)) << a.json() << " " << b.json() << " [" << r->lower() << ", "
                              << r->upper() << "]";
    EXPECT_TRUE(width_ok(*r, 15));
  }
  mpfr_clear(x);
}

TEST(PosedDistance, ThresholdsFromBothSides) {
  mpfr_t x;
  mpfr_init2(x, 2000);
  // Unit sphere at 0 against a sphere whose surface is g away (relative gaps 2^-10, 2^-40,
  // 2^-53: radius 1 - 2^-53 at 2 gives 2^-53) and, at scale 2^-60, an absolute 2^-100.
  struct Case {
    double r1, r2, cx;
  };
  const Case cases[] = {
      {1, 1, 2 + std::ldexp(1.0, -10)},
      {1, 1, 2 + std::ldexp(1.0, -40)},
      {1, 1 - std::ldexp(1.0, -53), 2},
      {std::ldexp(1.0, -60), std::ldexp(1.0, -60), std::ldexp(1.0, -59) + std::ldexp(1.0, -100)}};
  for (const Case& c : cases) {
    for (bool swap : {false, true}) {
      const Posed a = sphere(c.r1, 0), b = sphere(c.r2, c.cx);
      const auto qa = a.read(), qb = b.read();
      const double ca[3] = {0, 0, 0}, cb[3] = {c.cx, 0, 0};
      sphere_gap(x, ca, c.r1, cb, c.r2);
      ASSERT_GT(mpfr_sgn(x), 0);
      // The fast certificate may decline a tiny relative gap; what it answers holds.
      const auto r = swap ? fast(qb, qa, 15) : fast(qa, qb, 15);
      if (r) {
        EXPECT_TRUE(holds(*r, x)) << b.json() << " [" << r->lower() << ", " << r->upper() << "]";
        EXPECT_TRUE(width_ok(*r, 15)) << b.json();
      }
      // The public answer is certified and right either way.
      const auto s = swap ? certify::surface_distance(qb, qa, 15, false)
                          : certify::surface_distance(qa, qb, 15, false);
      ASSERT_EQ(s.status, certify::Status::Certified) << b.json() << " " << s.note;
      EXPECT_TRUE(holds(s, x)) << b.json() << " [" << s.lower() << ", " << s.upper() << "]";
      EXPECT_TRUE(width_ok(s, 15)) << b.json();
    }
  }
  // The relative gap 2^-10 is well inside what doubles resolve: the fast path certifies it.
  EXPECT_TRUE(fast(sphere(1, 0).read(), sphere(1, 2 + std::ldexp(1.0, -10)).read(), 15));
  // Tangent (exactly: 2 = 1 + 1) and overlapping by 2^-40: declined; the answer is 0.
  for (double cx : {2.0, 2 - std::ldexp(1.0, -40)}) {
    const auto qa = sphere(1, 0).read(), qb = sphere(1, cx).read();
    EXPECT_FALSE(fast(qa, qb, 15).has_value()) << cx;
    EXPECT_FALSE(fast(qb, qa, 15).has_value()) << cx;
    const auto s = certify::surface_distance(qa, qb, 15, false);
    ASSERT_EQ(s.status, certify::Status::Certified) << s.note;
    EXPECT_EQ(s.upper(), "0") << cx;
  }
  // Nested: declined (the nested route answers those).
  EXPECT_FALSE(fast(sphere(1, 0).read(), sphere(3, 0.5).read(), 15).has_value());
  mpfr_clear(x);
}

TEST(PosedDistance, Extremes) {
  mpfr_t x;
  mpfr_init2(x, 2000);
  struct Case {
    double r1, c1, r2, c2;
  };
  const Case cases[] = {
      {1, 0, 1e-300, 2},          // a sphere of radius 1e-300 at distance ~1
      {1, 0, 1, 1e150},           // 1e150 apart
      {1e-150, 1e150, 1, 0},      // the issue's: radius 1e-150 at 1e150
      {1e-290, 0, 1e-290, 3e-290} // everything tiny: gap 1e-290
  };
  for (const Case& c : cases) {
    Posed a = sphere(c.r1, c.c1), b = sphere(c.r2, c.c2);
    // An ellipsoid form too (rotated by a fixed quaternion): the same solid.
    for (bool ellipsoid : {false, true}) {
      if (ellipsoid) {
        a.sphere = false;
        a.rotated = true;
        a.q[0] = 0.6;
        a.q[1] = 0.8;
        a.q[2] = a.q[3] = 0;
      }
      const double ca[3] = {c.c1, 0, 0}, cb[3] = {c.c2, 0, 0};
      sphere_gap(x, ca, c.r1, cb, c.r2);
      for (bool swap : {false, true}) {
        const auto qa = a.read(), qb = b.read();
        const auto r = swap ? fast(qb, qa, 15) : fast(qa, qb, 15);
        ASSERT_TRUE(r.has_value()) << a.json() << " " << b.json();
        EXPECT_TRUE(holds(*r, x)) << a.json() << " " << b.json() << " [" << r->lower() << ", "
                                  << r->upper() << "]";
        EXPECT_TRUE(width_ok(*r, 15)) << a.json();
      }
    }
  }
  mpfr_clear(x);
}

TEST(PosedDistance, SwappingGivesTheSameEnclosure) {
  std::mt19937_64 rng(test_seed() + 2);
  for (int t = 0; t < 100; ++t) {
    const auto [pa, pb] = random_separated(rng);
    const auto a = pa.read(), b = pb.read();
    const auto r = fast(a, b, 15), s = fast(b, a, 15);
    ASSERT_TRUE(r && s) << pa.json() << " " << pb.json();
    EXPECT_TRUE(overlap(*r, *s));
    EXPECT_TRUE(width_ok(*s, 15));
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(r->pairs[0][0][k], s->pairs[0][1][k], 1e-12);
      EXPECT_NEAR(r->pairs[0][1][k], s->pairs[0][0][k], 1e-12);
    }
  }
}
