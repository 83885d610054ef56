// The generic branch-and-bound route for two bounded implicit surfaces (implicit_bnb), each
// result against an independent route:
// - spheres given as generic degree-2 polynomials: closed forms |c1 - c2| - r1 - r2 (apart) and
//   r2 - |c1 - c2| - r1 (nested), MPFR, random rational data (fixed seed, printed);
// - ellipsoid pairs against the exact offset route surface_distance(QuadricMatrix, ..., Exact);
// - a ring torus (its quartic) against a sphere centred off the axis at height h:
//   sqrt((rho - R)^2 + h^2) - r - s (rho: distance of the centre to the axis), and against the
//   existing torus-quadric route; centred on the axis (a circle of minimizers): never a guess;
// - two tori with disjoint tubes against torus_pair_distance; linked tori: 0 with a witness;
// - x^4 + y^4 + z^4 = 1 and a sextic against ellipsoids via implicit_quadric_distance;
// - rational rigid motions of both surfaces, swapping (points swap), scaling by s (d scales);
//   15 and 100 digits overlap, the 100-digit enclosure is 10^-100 narrow;
// - what it must refuse: an unbounded surface (undecided).
#include "surfcert/certify/distance/implicit_bnb.hpp"
#include "surfcert/certify/distance/quadric_pair.hpp"
#include "surfcert/certify/distance/torus_pair.hpp"
#include "surfcert/core/io/expression.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <flint/fmpq.h>
#include <mpfr.h>

#include <chrono>
#include <cmath>
#include <random>

using namespace surfcert;
using surfcert::testing::contains;
using surfcert::testing::hi;
using surfcert::testing::lo;
using surfcert::testing::log10_rel_width;
using surfcert::testing::motion;
using surfcert::testing::overlap;

namespace {

using R3 = std::array<core::Rational, 3>;

core::Poly3 P(const std::string& s) {
  return core::io::parse_polynomial(s, {"t", 1, 1, ""});
}

// f(P (x, 1)): the surface moved by the congruence P (distance_checks.hpp convention).
core::Poly3 moved(const core::Poly3& f, const core::Mat4& p) {
  std::array<core::Poly3, 3> l;
  for (size_t i = 0; i < 3; ++i) {
    l[i] = core::Poly3(p[i][3]);
    for (size_t j = 0; j < 3; ++j)
      l[i] = l[i] + core::Poly3::variable(static_cast<int>(j)).scaled(p[i][j]);
  }
  return f.substitute(l);
}

core::Poly3 sphere(const R3& c, const core::Rational& r) {
  core::Poly3 s(-(r * r));
  for (size_t i = 0; i < 3; ++i) {
    const core::Poly3 u = core::Poly3::variable(static_cast<int>(i)) - core::Poly3(c[i]);
    s = s + u * u;
  }
  return s;
}

certify::DistanceResult run(const core::Poly3& f, const core::Poly3& g, long digits) {
  const auto t0 = std::chrono::steady_clock::now();
  auto r = certify::implicit_pair_distance(f, g, digits);
  const auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0);
  std::printf("  [implicit_bnb] deg %d/%d digits %ld: %.1f ms, status %d, [%.17s, %.17s] %s\n",
              f.total_degree(), g.total_degree(), digits, ms.count(), static_cast<int>(r.status),
              r.lower().c_str(), r.upper().c_str(), r.note.c_str());
  return r;
}

void expect_certified(const certify::DistanceResult& r, long digits) {
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  EXPECT_EQ(r.method, certify::Method::ImplicitBnb);
  EXPECT_LE(log10_rel_width(r), -static_cast<double>(digits) + 1e-9);
  EXPECT_GE(r.critical_candidates, 1);
  ASSERT_FALSE(r.pairs.empty());
}

void set_q(mpfr_t out, const core::Rational& q) {
  mpq_t m;
  mpq_init(m);
  fmpq_get_mpq(m, q.raw());
  mpfr_set_q(out, m, MPFR_RNDN);
  mpq_clear(m);
}

} // namespace

TEST(ImplicitBnb, SpheresAgainstClosedForms) {
  const unsigned seed = 20261122;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coord(-40, 40), rad(4, 20);
  for (int k = 0; k < 4; ++k) {
    R3 c1{core::Rational(coord(rng), 8), core::Rational(coord(rng), 8),
          core::Rational(coord(rng), 8)};
    R3 c2{core::Rational(coord(rng), 8), core::Rational(coord(rng), 8),
          core::Rational(coord(rng), 8)};
    core::Rational r1(rad(rng), 8), r2(rad(rng), 8);
    const bool nested = k % 2 == 1;
    if (nested) { // sphere 1 small, well inside sphere 2
      c1 = {c2[0] + core::Rational(1, 4), c2[1] - core::Rational(1, 8), c2[2]};
      r1 = core::Rational(1, 2);
      r2 = core::Rational(3) + core::Rational(rad(rng), 16);
    } else { // push sphere 2 away
      c2[0] = c1[0] + core::Rational(6) + core::Rational(coord(rng) + 40, 16);
    }
    for (long digits : {15L, 100L, 1000L}) {
      if (digits == 1000 && k != 0) continue;
      auto r = run(sphere(c1, r1), sphere(c2, r2), digits);
      SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(k));
      expect_certified(r, digits);
      // closed form: D = |c1 - c2| (exact square), apart D - r1 - r2, nested r2 - D - r1
      core::Rational D2;
      for (size_t i = 0; i < 3; ++i)
        D2 += (c1[i] - c2[i]) * (c1[i] - c2[i]);
      mpfr_t x, t;
      mpfr_inits2(4000, x, t, static_cast<mpfr_ptr>(nullptr));
      set_q(x, D2);
      mpfr_sqrt(x, x, MPFR_RNDN);
      set_q(t, nested ? r2 - r1 : r1 + r2);
      mpfr_sub(x, x, t, MPFR_RNDN);          // apart: D - r1 - r2
      if (nested) mpfr_neg(x, x, MPFR_RNDN); // nested: r2 - r1 - D
      EXPECT_TRUE(contains(r, x)) << r.lower() << " " << r.upper();
      mpfr_clears(x, t, static_cast<mpfr_ptr>(nullptr));
      EXPECT_EQ(r.minimizers, "1");
    }
  }
}

TEST(ImplicitBnb, EllipsoidsAgainstTheOffsetRoute) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"x^2 + 2 y^2 + 3 z^2 - 1", "(x - 4)^2 / 4 + (y - 1)^2 + (z + 1/2)^2 / 2 - 1"},
      {"2 x^2 + y^2 + z^2 + x y - 1", "(x - 1/2)^2 + (y + 3)^2 / 3 + 4 (z - 1)^2 - 1"},
      // nested: a small ellipsoid inside a large one
      {"4 (x - 1/3)^2 + 9 y^2 + 16 (z + 1/5)^2 - 1", "x^2 / 9 + y^2 / 4 + z^2 / 5 - 1"},
  };
  for (const auto& [a, b] : cases) {
    SCOPED_TRACE(a + " | " + b);
    const auto r = run(P(a), P(b), 15);
    expect_certified(r, 15);
    const auto e = certify::surface_distance(core::QuadricMatrix::from_poly(P(a)),
                                             core::QuadricMatrix::from_poly(P(b)), 15, false,
                                             certify::Mode::Exact);
    ASSERT_EQ(e.status, certify::Status::Certified) << e.note;
    EXPECT_TRUE(overlap(r, e)) << r.lower() << " " << r.upper() << " vs " << e.lower() << " "
                               << e.upper();
    // the reported points lie on their surfaces and realise the distance
    const auto& pq = r.pairs[0];
    const double d = std::hypot(pq[0][0] - pq[1][0], pq[0][1] - pq[1][1], pq[0][2] - pq[1][2]);
    EXPECT_NEAR(d, r.approx(), 1e-9);
  }
}

TEST(ImplicitBnb, TorusAgainstSpheres) {
  const core::Torus t = core::make_torus({0, 0, 0}, {0, 0, 1}, 3, 1);
  const core::Poly3 tq = certify::torus_polynomial(t);
  // the quartic vanishes on the tube: (R + r, 0, 0) and (R, 0, r)
  EXPECT_TRUE(tq.evaluate(4, 0, 0).is_zero());
  EXPECT_TRUE(tq.evaluate(3, 0, 1).is_zero());
  // sphere centre (a, 0, h), radius s: sqrt((a - R)^2 + h^2) - r - s (apart from the tube)
  for (auto [a, hh, s] : {std::array<long, 3>{8, 0, 1}, {7, 3, 2}, {0, 9, 2}}) {
    SCOPED_TRACE("centre " + std::to_string(a) + ", 0, " + std::to_string(hh));
    const core::Poly3 sp = sphere({a, 0, hh}, s);
    const auto r = run(tq, sp, 15);
    if (a == 0) { // on the axis: a circle of minimizers, never a single guessed pair
      EXPECT_FALSE(r.status == certify::Status::Certified && r.minimizers != "infinite")
          << r.lower() << " " << r.upper();
      continue;
    }
    expect_certified(r, 15);
    mpfr_t x;
    mpfr_init2(x, 256);
    mpfr_set_si(x, (a - 3) * (a - 3) + hh * hh, MPFR_RNDN);
    mpfr_sqrt(x, x, MPFR_RNDN);
    mpfr_sub_si(x, x, 1 + s, MPFR_RNDN);
    EXPECT_TRUE(contains(r, x)) << r.lower() << " " << r.upper();
    mpfr_clear(x);
    const auto e = certify::surface_distance(
        core::Surface(t), core::Surface(core::QuadricMatrix::from_poly(sp)), 15, false);
    ASSERT_EQ(e.status, certify::Status::Certified) << e.note;
    EXPECT_TRUE(overlap(r, e));
  }
}

TEST(ImplicitBnb, TwoToriAgainstTorusPair) {
  const core::Torus t1 = core::make_torus({0, 0, 0}, {0, 0, 1}, 3, 1);
  const core::Torus t2 = core::make_torus({7, 1, 4}, {1, 1, 1}, 2, core::Rational(1, 2));
  const auto r = run(certify::torus_polynomial(t1), certify::torus_polynomial(t2), 15);
  expect_certified(r, 15);
  const auto e = certify::torus_pair_distance(t1, t2, 15);
  ASSERT_TRUE(e.has_value());
  ASSERT_EQ(e->status, certify::Status::Certified) << e->note;
  EXPECT_TRUE(overlap(r, *e)) << r.lower() << " vs " << e->lower();
  // linked tori: the second ring passes through the first one's hole and crosses its tube
  const core::Torus t3 = core::make_torus({3, 0, 0}, {0, 1, 0}, 3, 1);
  const auto m = run(certify::torus_polynomial(t1), certify::torus_polynomial(t3), 15);
  if (m.status == certify::Status::Certified) {
    EXPECT_EQ(m.upper(), "0");
    ASSERT_FALSE(m.pairs.empty());
    const auto& w = m.pairs[0][0];
    const double f1 =
        std::pow(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] + 8, 2) - 36 * (w[0] * w[0] + w[1] * w[1]);
    EXPECT_NEAR(f1, 0, 1e-6);
  } else {
    EXPECT_EQ(m.status, certify::Status::Undecided);
  }
}

// min (sign = 1) or max (sign = -1) of |p - c| over the surface x^k + y^k + z^k = 1 (k even):
// p(u) = u / |u|_k over directions u (dense grid on the cube faces, then a local descent).
double float_super(int k, const std::array<double, 3>& c, int sign) {
  auto val = [&](std::array<double, 3> u) {
    double n = 0;
    for (double v : u)
      n += std::pow(std::fabs(v), k);
    n = std::pow(n, 1.0 / k);
    double d = 0;
    for (size_t i = 0; i < 3; ++i)
      d += (u[i] / n - c[i]) * (u[i] / n - c[i]);
    return sign * std::sqrt(d);
  };
  double best = 1e300;
  std::array<double, 3> bu{};
  const int N = 120;
  for (size_t a = 0; a < 3; ++a)
    for (double s : {-1.0, 1.0})
      for (int i = 0; i <= N; ++i)
        for (int j = 0; j <= N; ++j) {
          std::array<double, 3> u{};
          u[a] = s;
          u[(a + 1) % 3] = -1 + 2.0 * i / N;
          u[(a + 2) % 3] = -1 + 2.0 * j / N;
          const double v = val(u);
          if (v < best) best = v, bu = u;
        }
  for (double st = 0.02; st > 1e-14; st /= 1.5)
    for (int it = 0; it < 6; ++it)
      for (size_t i = 0; i < 3; ++i)
        for (double sg : {-1.0, 1.0}) {
          auto u = bu;
          u[i] += sg * st;
          const double v = val(u);
          if (v < best) best = v, bu = u;
        }
  return sign * best;
}

TEST(ImplicitBnb, QuarticAndSexticAgainstSpheres) {
  // sphere centre c, radius rho; apart: min |p - c| - rho; around: rho - max |p - c|
  struct Case {
    int k;
    std::array<long, 3> c; // centre in 1/4 units
    long rho4;             // radius in 1/4 units
    bool around;
  };
  for (const Case& cs : {Case{4, {12, 2, 4}, 2, false}, Case{6, {3, 9, -5}, 3, false},
                         Case{4, {1, -1, 0}, 14, true}}) {
    const std::string e = "x^" + std::to_string(cs.k) + " + y^" + std::to_string(cs.k) + " + z^" +
                          std::to_string(cs.k) + " - 1";
    SCOPED_TRACE(e);
    const R3 c{core::Rational(cs.c[0], 4), core::Rational(cs.c[1], 4), core::Rational(cs.c[2], 4)};
    const auto r = run(P(e), sphere(c, core::Rational(cs.rho4, 4)), 15);
    expect_certified(r, 15);
    const std::array<double, 3> cd{cs.c[0] / 4.0, cs.c[1] / 4.0, cs.c[2] / 4.0};
    const double fl = cs.around ? cs.rho4 / 4.0 - float_super(cs.k, cd, -1)
                                : float_super(cs.k, cd, 1) - cs.rho4 / 4.0;
    EXPECT_LE(lo(r), fl + 1e-12); // a float pair of surface points never beats the lower bound
    EXPECT_LT(fl - hi(r), 1e-8);  // and the search gets close to it
    const auto& pq = r.pairs[0];
    const double d = std::hypot(pq[0][0] - pq[1][0], pq[0][1] - pq[1][1], pq[0][2] - pq[1][2]);
    EXPECT_NEAR(d, r.approx(), 1e-9);
  }
}

TEST(ImplicitBnb, MotionsSwapScalingDigits) {
  const core::Poly3 f = P("x^4 + y^4 + z^4 - 1 + x y");
  const core::Poly3 g = P("(x - 3)^2 + 2 (y - 1/2)^2 + (z - 1)^2 - 1/4");
  const auto r15 = run(f, g, 15);
  expect_certified(r15, 15);
  const auto r100 = run(f, g, 100);
  expect_certified(r100, 100);
  EXPECT_TRUE(overlap(r15, r100));
  // swap: same enclosure, points swapped
  const auto s = run(g, f, 15);
  expect_certified(s, 15);
  EXPECT_TRUE(overlap(r15, s));
  EXPECT_NEAR(s.pairs[0][1][0], r15.pairs[0][0][0], 1e-9);
  EXPECT_NEAR(s.pairs[0][0][2], r15.pairs[0][1][2], 1e-9);
  // rational rigid motions (integer quaternions), fixed: quarter turns for the quartic (its
  // interval extension stays sharp), generic rotations for an ellipsoid pair
  const core::Poly3 e1 = P("x^2 + 2 y^2 + 3 z^2 - 1");
  const core::Poly3 e2 = P("(x - 4)^2 / 4 + (y - 1)^2 + (z + 1/2)^2 / 2 - 1");
  const auto re = run(e1, e2, 15);
  expect_certified(re, 15);
  struct Move {
    std::array<long, 4> q;
    bool quartic;
  };
  for (const Move& mv : {Move{{1, 1, 0, 0}, true}, Move{{1, 0, 0, -1}, true},
                         Move{{1, 2, -1, 3}, false}, Move{{3, 0, 1, -2}, false}}) {
    const auto& qt = mv.q;
    const core::Mat4 m = motion(qt[0], qt[1], qt[2], qt[3], {core::Rational(1, 3), -2, 5});
    SCOPED_TRACE("quaternion " + std::to_string(qt[0]) + " " + std::to_string(qt[1]) + " " +
                 std::to_string(qt[2]) + " " + std::to_string(qt[3]));
    const auto& ref = mv.quartic ? r15 : re;
    const auto rm =
        mv.quartic ? run(moved(f, m), moved(g, m), 15) : run(moved(e1, m), moved(e2, m), 15);
    expect_certified(rm, 15);
    EXPECT_TRUE(overlap(ref, rm)) << ref.lower() << " vs " << rm.lower();
  }
  // scaling by 3: distance times 3
  const core::Mat4 sc = surfcert::testing::scaling(3);
  const auto r3 = run(moved(f, sc), moved(g, sc), 15);
  expect_certified(r3, 15);
  EXPECT_NEAR(lo(r3), 3 * lo(r15), 1e-12 * lo(r3));
}

TEST(ImplicitBnb, RefusesWhatItCannotProve) {
  // unbounded (hyperboloid): no guess
  const auto r = run(P("x^2 + y^2 - z^2 - 1"), P("(x - 5)^2 + y^2 + z^2 - 1"), 15);
  EXPECT_EQ(r.status, certify::Status::Undecided);
  // odd degree
  const auto c = run(P("x^3 + y^2 + z^2 - 1"), P("(x - 5)^2 + y^2 + z^2 - 1"), 15);
  EXPECT_EQ(c.status, certify::Status::Undecided);
  // crossing spheres: distance 0 with a witness on both
  const auto m = run(P("x^2 + y^2 + z^2 - 1"), P("(x - 3/2)^2 + y^2 + z^2 - 1"), 15);
  ASSERT_EQ(m.status, certify::Status::Certified) << m.note;
  EXPECT_EQ(m.upper(), "0");
  ASSERT_FALSE(m.pairs.empty());
  const auto& w = m.pairs[0][0];
  EXPECT_NEAR(w[0], 0.75, 1e-9);
  EXPECT_NEAR(w[1] * w[1] + w[2] * w[2], 1 - 0.5625, 1e-9);
}
