// Building blocks against independent routes: root isolation (float-guess + exact check vs
// CGAL's Descartes isolator vs Arb's complex root enclosures vs a Sturm count), inertia
// (Descartes vs exact LDL^T vs Sylvester's law on P^T D P), the closed-form pencil
// determinant vs FLINT's fmpq_mat_det, D4 vs FLINT's discriminant, signs in Q(sqrt d).
#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/conic_isotropy.hpp"
#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/pencil.hpp"
#include "surfcert/algebra/pencil_poly.hpp"
#include "surfcert/algebra/real_roots.hpp"

#include <flint/fmpq_mat.h>
#include <gtest/gtest.h>
#include <mpfr.h>

#include <algorithm>

#include <cmath>
#include <cstdlib>
#include <random>
#include <set>

using namespace surfcert;
using algebra::UPolyZ;
using core::Integer;
using core::Rational;

namespace {

unsigned long test_seed() {
  const char* s = std::getenv("SURFCERT_TEST_SEED");
  return s ? std::strtoul(s, nullptr, 10) : 20261122UL;
}

UPolyZ squarefree_part(const UPolyZ& p) {
  UPolyZ d, g, q;
  fmpz_poly_derivative(d.raw_mut(), p.raw());
  fmpz_poly_gcd(g.raw_mut(), p.raw(), d.raw());
  fmpz_poly_div(q.raw_mut(), p.raw(), g.raw());
  return q.primitive_part();
}

// Checks the separators against Arb's certified complex roots: same number of real roots and
// each real root's ball lies strictly inside exactly one gap.
void check_against_arb(const UPolyZ& p, const algebra::RootSeparation& sep,
                       const std::string& ctx) {
  long n = p.degree();
  acb_ptr roots = _acb_vec_init(n);
  arb_fmpz_poly_complex_roots(roots, p.raw(), 0, 128);
  long real = 0;
  for (long i = 0; i < n; ++i) {
    if (!acb_is_real(roots + i)) continue;
    ++real;
    int inside = 0;
    for (size_t g = 0; g + 1 < sep.separators.size(); ++g) {
      arb_t lo, hi;
      arb_init(lo);
      arb_init(hi);
      arb_set_fmpq(lo, sep.separators[g].raw(), 256);
      arb_set_fmpq(hi, sep.separators[g + 1].raw(), 256);
      if (arb_lt(lo, acb_realref(roots + i)) && arb_lt(acb_realref(roots + i), hi)) ++inside;
      arb_clear(lo);
      arb_clear(hi);
    }
    EXPECT_EQ(inside, 1) << ctx;
  }
  EXPECT_EQ(real, static_cast<long>(sep.num_roots())) << ctx;
  _acb_vec_clear(roots, n);
}

} // namespace

TEST(RealRoots, RandomPolynomialsThreeIsolators) {
  std::mt19937_64 rng(test_seed());
  std::uniform_int_distribution<long> coef(-1000, 1000), deg(1, 12);
  int fallbacks = 0;
  for (int it = 0; it < 300; ++it) {
    std::vector<Integer> c;
    long d = deg(rng);
    for (long i = 0; i <= d; ++i)
      c.emplace_back(coef(rng));
    if (c.back().is_zero()) c.back() = Integer(1);
    UPolyZ p = squarefree_part(UPolyZ::from_coeffs(c));
    if (p.degree() < 1) continue;
    std::string ctx = "seed " + std::to_string(test_seed()) + " poly " + p.to_string();
    auto a = algebra::isolate_real_roots(p);
    auto b = algebra::isolate_real_roots_cgal(p);
    fallbacks += a.used_fallback;
    EXPECT_EQ(a.num_roots(), b.num_roots()) << ctx;
    EXPECT_EQ(static_cast<long>(a.num_roots()), algebra::count_real_roots(p)) << ctx;
    check_against_arb(p, a, ctx);
    check_against_arb(p, b, ctx);
  }
  EXPECT_LT(fallbacks, 30); // the float guess should do almost all of the work
}

// separate_rational_roots (an exact analysis whose square-free factors are all linear): the
// separators interleave the given roots strictly, also for roots 2^-100 apart, 10^40 apart and
// near 0, checked exactly; and on polynomials with those roots the same count as isolation,
// each separator gap holding exactly one root (sign change of the product of the factors).
TEST(RealRoots, SeparatorsOfKnownRationalRoots) {
  std::mt19937_64 rng(test_seed() + 5);
  std::uniform_int_distribution<long> num(-1000000, 1000000), den(1, 1000);
  const Rational tiny = core::pow2(-100);
  for (int it = 0; it < 300; ++it) {
    std::vector<Rational> roots;
    const int n = 1 + static_cast<int>(rng() % 4);
    for (int i = 0; i < n; ++i) {
      Rational r(num(rng), den(rng));
      if (it % 3 == 1 && i > 0) r = roots[0] + tiny * Rational(i);      // a cluster
      if (it % 3 == 2 && i > 0) r = roots[0] * core::pow2(130 * i) + r; // far apart
      if (std::find(roots.begin(), roots.end(), r) == roots.end()) roots.push_back(r);
    }
    const auto sep = algebra::separate_rational_roots(roots);
    std::vector<Rational> sorted = roots;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sep.separators.size(), sorted.size() + 1) << it;
    for (size_t i = 0; i < sorted.size(); ++i) {
      EXPECT_LT(sep.separators[i], sorted[i]) << it;
      EXPECT_GT(sep.separators[i + 1], sorted[i]) << it;
    }
    // The polynomial prod (den x - num): one sign change per gap, none beyond.
    algebra::UPolyQ prod(1);
    for (const Rational& r : roots)
      prod = prod * algebra::UPolyQ::linear(Rational(1), -r);
    const UPolyZ pz = prod.primitive_integer();
    for (size_t i = 0; i + 1 < sep.separators.size(); ++i)
      EXPECT_NE(pz.sign_at(sep.separators[i]), pz.sign_at(sep.separators[i + 1])) << it;
    EXPECT_EQ(algebra::count_real_roots(pz), static_cast<long>(roots.size())) << it;
  }
  EXPECT_EQ(algebra::separate_rational_roots({}).separators.size(), 1u);
}

// conic_has_rational_point against closed forms and an independent brute-force search: x^2 +
// y^2 = c z^2 has a point iff c is a sum of two squares (c = 2, 5, 13, 25: yes; 3, 7, 21: no);
// x^2 + y^2 + z^2 has no real point; random integer conics: every one with a point of height
// <= 12 found by search must answer true, and a false answer is checked by the search finding
// nothing (both directions counted, so that a test that always says "unknown" fails).
TEST(ConicIsotropy, HilbertSymbolsAgainstSearch) {
  auto diag = [](long a, long b, long c) {
    core::Mat4 m{};
    m[0][0] = Rational(a), m[1][1] = Rational(b), m[2][2] = Rational(c);
    return m;
  };
  for (long c : {2L, 5L, 13L, 25L, 1L})
    EXPECT_EQ(algebra::conic_has_rational_point(diag(1, 1, -c)), std::optional<bool>(true)) << c;
  for (long c : {3L, 7L, 21L, 6L, 11L})
    EXPECT_EQ(algebra::conic_has_rational_point(diag(1, 1, -c)), std::optional<bool>(false)) << c;
  EXPECT_EQ(algebra::conic_has_rational_point(diag(1, 1, 1)), std::optional<bool>(false));
  EXPECT_EQ(algebra::conic_has_rational_point(diag(3, 5, -1)),
            std::optional<bool>(false)); // mod 3, 5
  EXPECT_EQ(algebra::conic_has_rational_point(diag(2, 0, 1)), std::optional<bool>(true));
  // Beyond the factoring cap (default 62 bits): unknown; with the cap raised, the answer.
  {
    core::Mat4 big{};
    big[0][0] = Rational(1), big[1][1] = Rational(1), big[2][2] = -core::pow2(80) * Rational(3);
    EXPECT_FALSE(algebra::conic_has_rational_point(big).has_value());
    EXPECT_EQ(algebra::conic_has_rational_point(big, 200), std::optional<bool>(false));
    big[2][2] = -core::pow2(80) * Rational(2);
    EXPECT_EQ(algebra::conic_has_rational_point(big, 200), std::optional<bool>(true));
    big[2][2] = -core::pow2(40) * Rational(3); // 42 bits: below the cap
    EXPECT_EQ(algebra::conic_has_rational_point(big), std::optional<bool>(false));
  }
  // Scaled by rationals (the form up to a factor, an entry's denominator): the same answer.
  core::Mat4 m = diag(1, 1, -7);
  for (auto& row : m)
    for (auto& x : row)
      x *= Rational(-5, 12);
  EXPECT_EQ(algebra::conic_has_rational_point(m), std::optional<bool>(false));
  std::mt19937_64 rng(test_seed() + 9);
  std::uniform_int_distribution<long> e(-9, 9);
  int with_point = 0, without = 0;
  for (int it = 0; it < 400; ++it) {
    std::array<std::array<long, 3>, 3> q{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = i; j < 3; ++j)
        q[i][j] = q[j][i] = e(rng);
    core::Mat4 qm{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        qm[i][j] = Rational(q[i][j]);
    const auto ans = algebra::conic_has_rational_point(qm);
    if (!ans) continue; // degenerate
    bool found = false;
    for (long x = -12; x <= 12 && !found; ++x)
      for (long y = -12; y <= 12 && !found; ++y)
        for (long z = -12; z <= 12 && !found; ++z) {
          if (x == 0 && y == 0 && z == 0) continue;
          const std::array<long, 3> v{x, y, z};
          long s = 0;
          for (size_t i = 0; i < 3; ++i)
            for (size_t j = 0; j < 3; ++j)
              s += q[i][j] * v[i] * v[j];
          found = s == 0;
        }
    if (found) {
      EXPECT_TRUE(*ans) << it;
      ++with_point;
    }
    if (!*ans) {
      EXPECT_FALSE(found) << it;
      ++without;
    }
  }
  EXPECT_GE(with_point, 50);
  EXPECT_GE(without, 50);
}

// irreducible_factors (a modular irreducibility proof first, FLINT's factorisation otherwise)
// against FLINT's fmpz_poly_factor called directly: the same factors and exponents, on products
// of random factors (linear, quadratic, quartic; repeated ones too; coefficients of 10 and of
// 200 bits, as the points at infinity of cones posed in doubles have), and on random
// polynomials (mostly irreducible).
TEST(UPoly, IrreducibleFactorsMatchFlint) {
  std::mt19937_64 rng(test_seed() + 21);
  auto random_poly = [&](long deg, int bits) {
    UPolyZ p;
    for (long i = 0; i <= deg; ++i) {
      Integer c;
      fmpz_set_si(c.raw_mut(), static_cast<slong>(rng() % 2001) - 1000);
      if (bits > 10) {
        Integer big;
        fmpz_set_ui(big.raw_mut(), rng());
        fmpz_mul_2exp(big.raw_mut(), big.raw(), static_cast<ulong>(bits - 64));
        c = c * big + Integer(static_cast<long>(rng() % 1000));
      }
      if (i == deg && c.is_zero()) c = Integer(1);
      fmpz_poly_set_coeff_fmpz(p.raw_mut(), i, c.raw());
    }
    return p;
  };
  auto key = [](const std::vector<std::pair<std::string, int>>& v) {
    auto w = v;
    std::sort(w.begin(), w.end());
    return w;
  };
  for (int it = 0; it < 300; ++it) {
    const int bits = it % 2 ? 200 : 10;
    UPolyZ p;
    if (it % 3 == 0) {
      p = random_poly(4, bits);
    } else {
      fmpz_poly_set_si(p.raw_mut(), 1);
      const int parts = 1 + static_cast<int>(rng() % 3);
      for (int k = 0; k < parts; ++k) {
        const UPolyZ f = random_poly(static_cast<long>(1 + rng() % 4), bits);
        fmpz_poly_mul(p.raw_mut(), p.raw(), f.raw());
        if (rng() % 4 == 0) fmpz_poly_mul(p.raw_mut(), p.raw(), f.raw()); // a square
      }
    }
    std::vector<std::pair<std::string, int>> ours, flint;
    for (const auto& f : algebra::irreducible_factors(p))
      ours.emplace_back(f.poly.to_string(), f.exponent);
    fmpz_poly_factor_t fac;
    fmpz_poly_factor_init(fac);
    fmpz_poly_factor(fac, p.raw());
    for (slong i = 0; i < fac->num; ++i) {
      UPolyZ g;
      fmpz_poly_set(g.raw_mut(), fac->p + i);
      if (g.degree() >= 1) flint.emplace_back(g.to_string(), static_cast<int>(fac->exp[i]));
    }
    fmpz_poly_factor_clear(fac);
    EXPECT_EQ(key(ours), key(flint)) << "it " << it << ": " << p.to_string();
  }
}

TEST(RealRoots, ClusteredAndDyadicRoots) {
  // Mignotte-like x^8 - 2(2^20 x - 1)^2: two roots within 2^-40 of 2^-20 (forces the fallback).
  Integer a;
  fmpz_set_ui(a.raw_mut(), 1UL << 20);
  UPolyZ lin = UPolyZ::from_coeffs({Integer(-1), a});
  UPolyZ sq, p;
  fmpz_poly_mul(sq.raw_mut(), lin.raw(), lin.raw());
  fmpz_poly_scalar_mul_si(sq.raw_mut(), sq.raw(), -2);
  fmpz_poly_set_coeff_si(sq.raw_mut(), 8, 1);
  p = sq;
  auto s = algebra::isolate_real_roots(p);
  EXPECT_EQ(static_cast<long>(s.num_roots()), algebra::count_real_roots(p));
  check_against_arb(p, s, "mignotte");
  // Roots exactly at dyadic points where a midpoint separator could land: (2x-1)(4x-1)(4x+1)x.
  UPolyZ q = UPolyZ::from_coeffs({Integer(0), Integer(1)});
  for (auto [c0, c1] : {std::pair<long, long>{-1, 2}, {-1, 4}, {1, 4}}) {
    UPolyZ f = UPolyZ::from_coeffs({Integer(c0), Integer(c1)});
    fmpz_poly_mul(q.raw_mut(), q.raw(), f.raw());
  }
  auto t = algebra::isolate_real_roots(q);
  EXPECT_EQ(t.num_roots(), 4u);
  check_against_arb(q, t, "dyadic");
}

// The float-guess route proved by Descartes' rule (isolate_real_roots' first try below degree
// 12) on what makes it fail or succeed: quartics with coefficients of hundreds of bits (a
// rational root a of 150-bit numerator and denominator) times x^2 - e (two real roots 2 sqrt(e)
// apart) or x^2 + e (a complex pair sqrt(e) off the axis), e = 1e-10, 1e-20, 1e-30, 2^-100 and
// the pair moved onto a: the separators must always give exactly FLINT's Sturm count and put
// each of Arb's real roots in its own gap, whichever route answered.
TEST(RealRoots, CloseRootsAndNearRealPairsWithBigCoefficients) {
  Integer num, den;
  fmpz_set_str(num.raw_mut(), "1427247692705959881058285969449495136382746771", 10);
  fmpz_set_str(den.raw_mut(), "1298074214633706907132624082305024", 10); // 2^110, made odd:
  fmpz_add_ui(den.raw_mut(), den.raw(), 7);
  const UPolyZ lin = UPolyZ::from_coeffs({-num, den}); // den x - num
  const Rational e10(1, 10000000000UL);
  for (const Rational& e :
       {e10, e10 * e10, e10 * e10 * e10, Rational::exact_from_double(std::ldexp(1.0, -100))})
    for (int sign : {1, -1})
      for (bool at_a : {false, true}) {
        // x^2 -+ e around 0, or (x - a)^2 -+ e around a: over Z after clearing denominators.
        const Rational centre = at_a ? Rational(num, den) : Rational(0);
        const Rational c1 = -Rational(2) * centre, c0 = centre * centre - Rational(sign) * e;
        Integer l;
        fmpz_lcm(l.raw_mut(), fmpq_denref(c1.raw()), fmpq_denref(c0.raw()));
        const UPolyZ q =
            UPolyZ::from_coeffs({(c0 * Rational(l)).num(), (c1 * Rational(l)).num(), l});
        UPolyZ p;
        fmpz_poly_mul(p.raw_mut(), lin.raw(), q.raw());
        fmpz_poly_mul(p.raw_mut(), p.raw(), UPolyZ::from_coeffs({Integer(3), Integer(-5)}).raw());
        p = squarefree_part(p);
        const std::string ctx = "e " + e.to_string() + (sign > 0 ? " real pair" : " complex pair") +
                                (at_a ? " at a" : "");
        const auto sep = algebra::isolate_real_roots(p);
        EXPECT_EQ(static_cast<long>(sep.num_roots()), algebra::count_real_roots(p)) << ctx;
        for (size_t i = 0; i + 1 < sep.separators.size(); ++i)
          EXPECT_NE(p.sign_at(sep.separators[i]), p.sign_at(sep.separators[i + 1])) << ctx;
        check_against_arb(p, sep, ctx);
      }
}

// The float-guess route itself (no CGAL fallback) on what it used to hand over: two roots
// closer than doubles resolve, (x - c)^2 -+ e with e = 1e-10, 1e-20, 1e-30, 2^-100 (a real
// pair split exactly through the root of p' between them, or a complex pair proved rootless),
// at a short dyadic c and at c = 7/3; and a pencil-like quartic with real roots near 2^-58 and
// 3 * 2^56 and a complex pair 1/8 +- 0.484i, where a wide interval's Descartes count saw the
// pair. Checked against Sturm's count and Arb's roots, separators alternating in sign.
TEST(RealRoots, CloseRootPairsAndWideRangesDecidedByTheFloatGuess) {
  const Rational e10(1, 10000000000UL);
  const auto times = [](UPolyZ a, const UPolyZ& b) {
    fmpz_poly_mul(a.raw_mut(), a.raw(), b.raw());
    return a;
  };
  const auto check = [](const UPolyZ& p, const std::string& ctx) {
    const auto sep = algebra::isolate_real_roots(p);
    EXPECT_FALSE(sep.used_fallback) << ctx;
    EXPECT_EQ(static_cast<long>(sep.num_roots()), algebra::count_real_roots(p)) << ctx;
    for (size_t i = 0; i + 1 < sep.separators.size(); ++i)
      EXPECT_NE(p.sign_at(sep.separators[i]), p.sign_at(sep.separators[i + 1])) << ctx;
    check_against_arb(p, sep, ctx);
    return sep.num_roots();
  };
  for (const Rational& e :
       {e10, e10 * e10, e10 * e10 * e10, Rational::exact_from_double(std::ldexp(1.0, -100))})
    for (int sign : {1, -1})
      for (const Rational& c : {Rational(1), Rational(7, 3)}) {
        const Rational c1 = -Rational(2) * c, c0 = c * c - Rational(sign) * e;
        Integer l;
        fmpz_lcm(l.raw_mut(), fmpq_denref(c1.raw()), fmpq_denref(c0.raw()));
        UPolyZ p = UPolyZ::from_coeffs({(c0 * Rational(l)).num(), (c1 * Rational(l)).num(), l});
        p = times(p, UPolyZ::from_coeffs({Integer(3), Integer(-5)}));            // 3/5
        p = times(p, UPolyZ::from_coeffs({Integer(1), Integer(1), Integer(1)})); // complex
        const std::string ctx = "e " + e.to_string() + " c " + c.to_string() +
                                (sign > 0 ? " real pair" : " complex pair");
        EXPECT_EQ(check(p, ctx), sign > 0 ? 3u : 1u) << ctx;
      }
  // (2^58 x - 1)(x - 3 * 2^56)(x^2 - x / 4 + 1/64 + 0.484^2), over Z.
  Integer two58, far;
  fmpz_one(two58.raw_mut());
  fmpz_mul_2exp(two58.raw_mut(), two58.raw(), 58);
  fmpz_set_ui(far.raw_mut(), 3);
  fmpz_mul_2exp(far.raw_mut(), far.raw(), 56);
  UPolyZ wide = UPolyZ::from_coeffs({Integer(-1), two58});
  wide = times(wide, UPolyZ::from_coeffs({-far, Integer(1)}));
  // 1/64 + 0.2342560 = 15617/62500 (0.484^2 = 0.234256): 62500 x^2 - 15625 x + 15617.
  wide = times(wide, UPolyZ::from_coeffs({Integer(15617), Integer(-15625), Integer(62500)}));
  EXPECT_EQ(check(wide, "wide"), 2u);
}

// real_root_range (the range of the real roots, proved by Descartes' rule beyond the float
// roots) against the exact isolation and Sturm count, on degree-16 products with coefficients
// of hundreds of bits: the big-rational linear factor above, complex pairs (x - c)^2 + e and
// real pairs (x - c)^2 - e (e = 1e-10 ... 2^-100) placed at the ends of the real roots or
// alone, and a real root near 1.1e12 that the float roots misread as complex (declined, or
// inside the range). Whenever it answers: `any` false only when there is no real root (Sturm), and
// every real root strictly inside (lo, hi) (both bounds checked against the isolating intervals'
// roots, by exact signs); most of these it must answer (it is the fast path).
TEST(RealRoots, RangeOfTheRealRootsIsProvedOrDeclined) {
  Integer num, den;
  fmpz_set_str(num.raw_mut(), "1427247692705959881058285969449495136382746771", 10);
  fmpz_set_str(den.raw_mut(), "1298074214633706907132624082305031000000000001", 10);
  const UPolyZ lin = UPolyZ::from_coeffs({-num, den});
  Integer far_den;
  fmpz_set_str(far_den.raw_mut(), "1298074214633706907132624082305031", 10);
  const Rational e10(1, 10000000000UL);
  const auto pair = [](const Rational& c, const Rational& e, int sign) { // (x - c)^2 - sign e
    const Rational c1 = -Rational(2) * c, c0 = c * c - Rational(sign) * e;
    Integer l;
    fmpz_lcm(l.raw_mut(), fmpq_denref(c1.raw()), fmpq_denref(c0.raw()));
    return UPolyZ::from_coeffs({(c0 * Rational(l)).num(), (c1 * Rational(l)).num(), l});
  };
  const auto times = [](UPolyZ a, const UPolyZ& b) {
    fmpz_poly_mul(a.raw_mut(), a.raw(), b.raw());
    return a;
  };
  int answered = 0, cases = 0;
  for (const Rational& e :
       {e10, e10 * e10, e10 * e10 * e10, Rational::exact_from_double(std::ldexp(1.0, -100))})
    for (int sign : {1, -1})
      for (int where = 0; where < 3; ++where)
        for (int with_real : {1, 0, 2, 3}) {
          // Background: complex pairs off the axis (degree 10), then the real roots (or not),
          // then the probed pair: beyond the largest real root (where = 0), below the smallest
          // (1), or in between (2).
          UPolyZ p = UPolyZ::from_coeffs({Integer(1)});
          for (int k = 0; k < 5; ++k)
            p = times(p, pair(Rational(k - 2, 3), Rational(1, 50 + 7 * k), -1));
          if (with_real == 1 || with_real == 2) {
            p = times(p, lin);                                            // the root ~1.0995
            p = times(p, UPolyZ::from_coeffs({Integer(3), Integer(-5)})); // 3/5
          }
          // And one near 1.1e12 (2), or that one instead of ~1.0995 with 3/5 (3): there the
          // float roots (Aberth in doubles over 12 orders of magnitude) see no real root at all.
          if (with_real >= 2) p = times(p, UPolyZ::from_coeffs({-num, far_den}));
          if (with_real == 3) p = times(p, UPolyZ::from_coeffs({Integer(3), Integer(-5)}));
          const Rational c = where == 0 ? Rational(2) : where == 1 ? Rational(-1) : Rational(4, 5);
          p = times(p, pair(c, e, sign));
          p = times(p, pair(Rational(1, 7), Rational(1, 3), -1)); // degree 16 when with_real
          p = squarefree_part(p);
          const std::string ctx = "e " + e.to_string() +
                                  (sign > 0 ? " real pair" : " complex pair") + " at " +
                                  c.to_string() +
                                  (with_real == 0   ? ", no other root"
                                   : with_real >= 2 ? ", a far root"
                                                    : "");
          const auto r = algebra::real_root_range(p);
          const long count = algebra::count_real_roots(p);
          if (with_real <= 1) ++cases;
          if (!r) continue;
          if (with_real <= 1) ++answered;
          if (!r->any) {
            EXPECT_EQ(count, 0) << ctx;
            continue;
          }
          ASSERT_LT(r->lo, r->hi) << ctx;
          // Every real root inside: p's sign at lo and hi, and the isolating intervals' roots
          // (one sign change per gap) all strictly between lo and hi.
          const auto sep = algebra::isolate_real_roots(p);
          ASSERT_EQ(static_cast<long>(sep.num_roots()), count) << ctx;
          for (size_t i = 0; i + 1 < sep.separators.size(); ++i) {
            Rational a = sep.separators[i], b = sep.separators[i + 1];
            algebra::refine_root(p, a, b, (b - a) * Rational(1, 1L << 40));
            EXPECT_LT(r->lo, a) << ctx << " root " << i;
            EXPECT_LT(b, r->hi) << ctx << " root " << i;
          }
        }
  // It is the fast path: it must answer most of those without a far root (declining all would
  // pass the above; with a far root the float roots see no real root and it must decline).
  EXPECT_GE(answered, cases * 3 / 4) << answered << " of " << cases;
  std::printf("real_root_range answered %d of %d\n", answered, cases);
}

TEST(RealRoots, RootsOfHugeDynamicRange) {
  // (2^1000 x - 1)(x - 2^1000)(x + 3)(2^-... ) style products: roots 2^-1000, 2^1000, -3 and
  // a pair 2^-1000 apart near 1. Arb's complex root finder needs thousands of bits here (it
  // ran for minutes on the pencils of spheres at 1e150 and 1e-150); the exact isolation must
  // separate every root and agree with the exact count.
  Integer big;
  fmpz_one(big.raw_mut());
  fmpz_mul_2exp(big.raw_mut(), big.raw(), 1000);
  Integer negbig;
  fmpz_neg(negbig.raw_mut(), big.raw());
  Integer bigm1 = big, bigp1 = big; // 2^1000 x - (2^1000 -/+ 1): roots 1 -/+ 2^-1000
  fmpz_sub_ui(bigm1.raw_mut(), big.raw(), 1);
  fmpz_add_ui(bigp1.raw_mut(), big.raw(), 1);
  Integer nbm1, nbp1;
  fmpz_neg(nbm1.raw_mut(), bigm1.raw());
  fmpz_neg(nbp1.raw_mut(), bigp1.raw());
  const std::vector<std::pair<Integer, Integer>> factors = {
      {Integer(-1), big}, {negbig, Integer(1)}, {Integer(3), Integer(1)}, {nbm1, big}, {nbp1, big}};
  for (size_t n = 2; n <= factors.size(); ++n) {
    UPolyZ p = UPolyZ::from_coeffs({Integer(1)});
    for (size_t i = 0; i < n; ++i) {
      UPolyZ f = UPolyZ::from_coeffs({factors[i].first, factors[i].second});
      fmpz_poly_mul(p.raw_mut(), p.raw(), f.raw());
    }
    auto s = algebra::isolate_real_roots(p);
    const std::string ctx = "product of the first " + std::to_string(n) + " factors";
    EXPECT_EQ(static_cast<long>(s.num_roots()), static_cast<long>(n)) << ctx;
    EXPECT_EQ(static_cast<long>(s.num_roots()), algebra::count_real_roots(p)) << ctx;
    // Each factor's root lies in its own gap: exact signs of p at the separators alternate.
    for (size_t i = 0; i + 1 < s.separators.size(); ++i)
      EXPECT_EQ(p.sign_at(s.separators[i]) * p.sign_at(s.separators[i + 1]), -1) << ctx;
    // And the known roots -c0/c1, sorted, lie one per gap (degree <= 4 takes the exact
    // rational-root route, higher degrees the others).
    std::vector<Rational> roots;
    for (size_t i = 0; i < n; ++i)
      roots.push_back(-Rational(factors[i].first) / Rational(factors[i].second));
    std::sort(roots.begin(), roots.end());
    ASSERT_EQ(s.separators.size(), roots.size() + 1) << ctx;
    for (size_t i = 0; i < roots.size(); ++i) {
      EXPECT_LT(s.separators[i], roots[i]) << ctx << " root " << i;
      EXPECT_LT(roots[i], s.separators[i + 1]) << ctx << " root " << i;
    }
  }
}

// The allocation-free critical_point_separators (the interval filter's) against the exact
// roots: each point strictly between two consecutive roots (p changes sign across it), and the
// vector overload gives the same points. Quartics with 4 and with 2 real roots (then the
// cubic p' has 3 real roots, of which the one between the two roots is taken).
TEST(RealRoots, CriticalPointSeparatorsLieBetweenRoots) {
  struct Case {
    std::vector<double> roots; // real roots; a factor x^2 + 1 when only two
  };
  const Case cases[] = {{{-3, -1, 1, 2}}, {{-0.5, 0.25, 0.75, 4}}, {{-2, 3}}, {{0.125, 0.5}}};
  for (const Case& cs : cases) {
    std::vector<double> c = {1};            // constant term first
    auto times = [&c](double a, double b) { // c *= (x^2 + a x + b)
      std::vector<double> r(c.size() + 2, 0.0);
      for (size_t i = 0; i < c.size(); ++i) {
        r[i] += b * c[i];
        r[i + 1] += a * c[i];
        r[i + 2] += c[i];
      }
      c = r;
    };
    for (size_t i = 0; i + 1 < cs.roots.size(); i += 2)
      times(-(cs.roots[i] + cs.roots[i + 1]), cs.roots[i] * cs.roots[i + 1]);
    if (cs.roots.size() == 2) times(0, 1);
    ASSERT_EQ(c.size(), 5u);
    const size_t k = cs.roots.size();
    double out[3];
    const size_t n = algebra::critical_point_separators(c.data(), 4, k, out);
    ASSERT_EQ(n, k - 1);
    const std::vector<double> v = algebra::critical_point_separators(c, k);
    ASSERT_EQ(v.size(), n);
    for (size_t i = 0; i < n; ++i) {
      EXPECT_EQ(v[i], out[i]);
      EXPECT_GT(out[i], cs.roots[i]);
      EXPECT_LT(out[i], cs.roots[i + 1]);
    }
    EXPECT_EQ(algebra::critical_point_separators(c.data(), 4, 1, out), 0u); // k <= 1: none
  }
}

TEST(RealRoots, RefineNarrowsToTheRoot) {
  UPolyZ p = UPolyZ::from_coeffs({Integer(-2), Integer(0), Integer(1)}); // x^2 - 2
  auto s = algebra::isolate_real_roots(p);
  ASSERT_EQ(s.num_roots(), 2u);
  Rational lo = s.separators[1], hi = s.separators[2];
  algebra::refine_root(p, lo, hi, core::pow2(-100));
  EXPECT_LE(hi - lo, core::pow2(-100));
  // sqrt(2) squared is bracketed: lo^2 < 2 < hi^2.
  EXPECT_LT(lo * lo, Rational(2));
  EXPECT_GT(hi * hi, Rational(2));
}

// Exact signs from the homogenised integer Horner against FLINT's rational evaluation.
TEST(RealRoots, SignAtMatchesRationalEvaluation) {
  std::mt19937_64 rng(test_seed() + 7);
  std::uniform_int_distribution<long> c(-50, 50), num(-1000, 1000), den(1, 4096);
  for (int it = 0; it < 2000; ++it) {
    std::vector<Integer> co;
    const int deg = static_cast<int>(rng() % 6);
    for (int i = 0; i <= deg; ++i)
      co.emplace_back(c(rng));
    const UPolyZ p = UPolyZ::from_coeffs(co);
    const Rational x(num(rng), static_cast<unsigned long>(it % 3 == 0 ? 1 : den(rng)));
    Rational v;
    fmpz_poly_evaluate_fmpq(v.raw_mut(), p.raw(), x.raw());
    ASSERT_EQ(p.sign_at(x), v.sign()) << p.to_string() << " at " << x.to_string();
  }
}

// The proposed bracket is a claim: refine_root_near must keep only what exact signs prove.
// Wrong guesses (far off, the other root, just outside the width on either side, a root of
// another factor) must still give an interval that brackets sqrt(2) with the width met; a
// version that trusted the guess (bracket guess -+ width/4 without the two exact signs)
// returns intervals missing the root here.
TEST(RealRoots, RefineNearVerifiesTheProposedBracket) {
  const UPolyZ p = UPolyZ::from_coeffs({Integer(-2), Integer(0), Integer(1)}); // x^2 - 2
  // sqrt(2) to 2^-130 (lo^2 < 2 < hi^2 checked below), the independent route for "near".
  Rational rlo(1), rhi(2);
  while (rhi - rlo > core::pow2(-130)) {
    Rational m = (rlo + rhi) * Rational(1, 2);
    (m * m < Rational(2) ? rlo : rhi) = m;
  }
  for (long wbits : {10L, 30L, 60L, 100L}) {
    const Rational width = core::pow2(-wbits);
    std::vector<Rational> guesses = {Rational(0), Rational(5),       Rational(-3, 2),
                                     Rational(1), Rational(2),       Rational(19, 10),
                                     rlo,         Rational(141, 100)};
    for (long off : {-10L, 10L}) // the true root moved by 2^off widths, either side
      for (int sgn : {-1, 1})
        guesses.push_back(rlo + Rational(sgn) * width * core::pow2(off));
    for (double tiny : {1e-10, 1e-20, 1e-30}) // moved by less than the width, either side
      for (int sgn : {-1, 1})
        guesses.push_back(rlo + Rational(sgn) * Rational::exact_from_double(tiny));
    guesses.push_back(rlo + core::pow2(-100));
    guesses.push_back(rlo - core::pow2(-100));
    for (const Rational& g : guesses) {
      Rational lo(1), hi(2);
      algebra::refine_root_near(p, lo, hi, width, g);
      const std::string ctx = "width 2^-" + std::to_string(wbits) + " guess " + g.to_string();
      EXPECT_LE(hi - lo, width) << ctx;
      EXPECT_LT(lo * lo, Rational(2)) << ctx;
      EXPECT_GT(hi * hi, Rational(2)) << ctx;
      EXPECT_LE(Rational(1), lo) << ctx;
      EXPECT_LE(hi, Rational(2)) << ctx;
    }
  }
}

// refine_root (bisection), refine_root_newton (Newton proposal + exact check) and
// refine_root_near with random guesses on
// products of rational linear factors: every interval holds the known root, width met; an
// exact root hit gives lo == hi == that root.
TEST(RealRoots, RefineRootAgainstKnownRationalRoots) {
  std::mt19937_64 rng(test_seed() + 8);
  std::uniform_int_distribution<long> a(1, 40), b(-200, 200);
  for (int it = 0; it < 200; ++it) {
    const size_t n = 1 + rng() % 4;
    UPolyZ p = UPolyZ::from_coeffs({Integer(1)});
    std::vector<Rational> roots;
    for (size_t i = 0; i < n; ++i) {
      const long ai = a(rng), bi = b(rng);
      const Rational r(bi, static_cast<unsigned long>(ai));
      if (std::find(roots.begin(), roots.end(), r) != roots.end()) continue;
      roots.push_back(r);
      UPolyZ f = UPolyZ::from_coeffs({Integer(-bi), Integer(ai)});
      fmpz_poly_mul(p.raw_mut(), p.raw(), f.raw());
    }
    std::sort(roots.begin(), roots.end());
    const auto s = algebra::isolate_real_roots(p);
    ASSERT_EQ(s.num_roots(), roots.size());
    for (size_t r = 0; r < roots.size(); ++r)
      for (long wbits : {5L, 40L, 90L}) {
        const Rational width = core::pow2(-wbits);
        for (int variant = 0; variant < 4; ++variant) {
          Rational lo = s.separators[r], hi = s.separators[r + 1];
          if (variant == 0)
            algebra::refine_root(p, lo, hi, width);
          else if (variant == 3)
            algebra::refine_root_newton(p, lo, hi, width);
          else // a guess at another root, or a random point of the isolating interval
            algebra::refine_root_near(
                p, lo, hi, width,
                variant == 1 ? roots[(r + 1) % roots.size()]
                             : lo + (hi - lo) * Rational(static_cast<long>(rng() % 1000), 999));
          EXPECT_LE(hi - lo, width);
          EXPECT_LE(lo, roots[r]);
          EXPECT_LE(roots[r], hi);
          if (lo == hi) {
            EXPECT_EQ(lo, roots[r]);
          } else {
            EXPECT_NE(p.sign_at(lo), p.sign_at(hi));
          }
        }
      }
  }
}

// refine_root_newton where its double start cannot or can barely help: roots at 2^+-1500
// (ends beyond the double range), coefficients of 3,000 bits, a root at 2^-1070 (subnormal),
// 0 itself, and two roots 2^-200 apart. Every interval holds its known root (exact
// comparisons), is no wider than asked and has end signs that differ.
TEST(RealRoots, RefineRootNewtonBeyondTheDoubleRange) {
  auto linear = [](const Rational& r) { // den x - num
    return UPolyZ::from_coeffs({-r.num(), r.den()});
  };
  const std::vector<std::vector<Rational>> cases = {
      {core::pow2(1500), Rational(3), core::pow2(-1500)},
      {core::pow2(-1070), Rational(-1, 3), Rational(5)},
      {Rational(0), Rational(7, 2), Rational(-7, 2)},
      {Rational(1), Rational(1) + core::pow2(-200), Rational(-2)},
  };
  for (const auto& roots : cases) {
    UPolyZ p = UPolyZ::from_coeffs({Integer(1)});
    for (const auto& r : roots)
      fmpz_poly_mul(p.raw_mut(), p.raw(), linear(r).raw());
    UPolyZ big = p; // the same roots, every coefficient times 2^3000 + 1
    Integer k;
    fmpz_one(k.raw_mut());
    fmpz_mul_2exp(k.raw_mut(), k.raw(), 3000);
    fmpz_add_ui(k.raw_mut(), k.raw(), 1);
    fmpz_poly_scalar_mul_fmpz(big.raw_mut(), big.raw(), k.raw());
    std::vector<Rational> sorted = roots;
    std::sort(sorted.begin(), sorted.end());
    for (const UPolyZ* q : {&p, &big}) {
      const auto s = algebra::isolate_real_roots(*q);
      ASSERT_EQ(s.num_roots(), sorted.size());
      for (size_t r = 0; r < sorted.size(); ++r)
        for (long wbits : {10L, 80L, 300L}) {
          const Rational width = core::pow2(-wbits) * (core::abs(sorted[r]) + core::pow2(-1100));
          Rational lo = s.separators[r], hi = s.separators[r + 1];
          algebra::refine_root_newton(*q, lo, hi, width);
          const std::string ctx =
              sorted[r].to_string().substr(0, 40) + " at 2^-" + std::to_string(wbits);
          EXPECT_LE(hi - lo, width) << ctx;
          EXPECT_LE(lo, sorted[r]) << ctx;
          EXPECT_LE(sorted[r], hi) << ctx;
          if (lo == hi) {
            EXPECT_EQ(lo, sorted[r]) << ctx;
          } else {
            EXPECT_NE(q->sign_at(lo), q->sign_at(hi)) << ctx;
          }
        }
    }
  }
}

// Rational::to_double_approx (a machine-word quotient when numerator and denominator have at
// most 53 bits, MPFR otherwise) against mpfr_set_q at 53 bits, round to nearest: the same
// double for random sizes on both sides of 53 bits and at the boundaries 2^53 - 1, 2^53,
// 2^53 + 1, both signs.
TEST(Rationals, ToDoubleIsTheNearestDouble) {
  std::mt19937_64 rng(test_seed() + 21);
  auto check = [](const Integer& n, const Integer& d) {
    const Rational q = Rational(n) / Rational(d);
    mpq_t m;
    mpq_init(m);
    fmpq_get_mpq(m, q.raw());
    mpfr_t f;
    mpfr_init2(f, 53);
    mpfr_set_q(f, m, MPFR_RNDN);
    const double want = mpfr_get_d(f, MPFR_RNDN);
    mpfr_clear(f);
    mpq_clear(m);
    EXPECT_EQ(q.to_double_approx(), want) << q.to_string();
  };
  const Integer two53 = Integer(1L << 53);
  const std::vector<Integer> edges = {two53 - Integer(1), two53,      two53 + Integer(1),
                                      Integer(3),         Integer(1), Integer((1L << 52) + 1)};
  for (const auto& n : edges)
    for (const auto& d : edges) {
      check(n, d);
      check(Integer(0) - n, d);
    }
  for (int it = 0; it < 20000; ++it) {
    auto random = [&](int bits) {
      Integer x;
      fmpz_set_ui(x.raw_mut(), rng() >> (64 - bits));
      if (bits > 60) {
        fmpz_mul_2exp(x.raw_mut(), x.raw(), 40);
        fmpz_add_ui(x.raw_mut(), x.raw(), rng() >> 24);
      }
      return x;
    };
    Integer n = random(1 + static_cast<int>(rng() % 64)),
            d = random(1 + static_cast<int>(rng() % 64));
    if (d.is_zero()) d = Integer(1);
    check(rng() % 2 ? n : Integer(0) - n, d);
  }
}

TEST(Inertia, DescartesLdltAndSylvesterAgree) {
  std::mt19937_64 rng(test_seed() + 1);
  std::uniform_int_distribution<long> e(-3, 3), dsign(-1, 1), den(1, 7);
  for (int it = 0; it < 500; ++it) {
    // M = P^T D P with P invertible: inertia = signs of D (Sylvester's law of inertia).
    core::Mat4 p, d;
    do {
      for (auto& row : p)
        for (auto& v : row)
          v = Rational(e(rng), static_cast<unsigned long>(den(rng)));
    } while (core::det(p).is_zero());
    algebra::Inertia expect;
    for (size_t i = 0; i < 4; ++i) {
      long s = dsign(rng);
      d[i][i] = Rational(s * den(rng), static_cast<unsigned long>(den(rng)));
      if (s > 0) ++expect.p;
      if (s < 0) ++expect.n;
    }
    core::Mat4 m = core::transpose(p) * d * p;
    EXPECT_EQ(algebra::inertia_descartes(m), expect) << "seed " << test_seed() << " it " << it;
    EXPECT_EQ(algebra::inertia_ldlt(m), expect) << "seed " << test_seed() << " it " << it;
    EXPECT_EQ(algebra::rank_exact(m), expect.rank());
  }
}

TEST(Pencil, ClosedFormDeterminantMatchesFlint) {
  std::mt19937_64 rng(test_seed() + 2);
  std::uniform_int_distribution<long> e(-50, 50), den(1, 9);
  for (int it = 0; it < 200; ++it) {
    core::Mat4 a, b;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j) {
        a[i][j] = a[j][i] = Rational(e(rng), static_cast<unsigned long>(den(rng)));
        b[i][j] = b[j][i] = Rational(e(rng), static_cast<unsigned long>(den(rng)));
      }
    auto f = algebra::pencil_char_poly(a, b);
    for (long t : {-3L, 0L, 2L, 7L}) {
      core::Mat4 m;
      for (size_t i = 0; i < 4; ++i)
        for (size_t j = 0; j < 4; ++j)
          m[i][j] = Rational(t) * a[i][j] - b[i][j];
      EXPECT_EQ(f.evaluate(Rational(t)), core::det(m)); // core::det is fmpq_mat_det
    }
    // D4 equals the discriminant of f (FLINT), for an integer multiple of f.
    UPolyZ fz;
    fmpq_poly_get_numerator(fz.raw_mut(), f.raw());
    std::array<Integer, 5> c;
    for (size_t i = 0; i < 5; ++i)
      c[i] = fz.coeff(static_cast<long>(i));
    auto inv = algebra::quartic_invariants(c);
    Integer disc;
    fmpz_poly_discriminant(disc.raw_mut(), fz.raw());
    if (fz.degree() == 4) {
      EXPECT_EQ(inv.d4, disc);
    }
  }
}

TEST(QuadraticNumbers, ExactSigns) {
  using algebra::QuadraticNumber;
  // 3 - 2 sqrt(2) > 0, 2 - sqrt(5) < 0 , 1 - sqrt(1)... d must be a non-square, so use an
  // exact zero from b = 0; and a near-cancelling pair: 99 - 70 sqrt(2) = 1/(99 + 70 sqrt 2) > 0.
  EXPECT_EQ((QuadraticNumber{Rational(3), Rational(-2), Integer(2)}).sign(), 1);
  EXPECT_EQ((QuadraticNumber{Rational(2), Rational(-1), Integer(5)}).sign(), -1);
  EXPECT_EQ((QuadraticNumber{Rational(0), Rational(0), Integer(5)}).sign(), 0);
  EXPECT_EQ((QuadraticNumber{Rational(99), Rational(-70), Integer(2)}).sign(), 1);
  EXPECT_EQ((QuadraticNumber{Rational(-99), Rational(70), Integer(2)}).sign(), -1);
  auto n = QuadraticNumber{Rational(0), Rational(1), Integer(72)}.normalized();
  EXPECT_EQ(n.to_string(), "6*sqrt(2)");
}

// normalized() on multi-limb radicands: the same number (b^2 d unchanged, a unchanged), no
// square of a prime below 2000 left in d (1999, 1997 and 2 included, composites' squares
// through their primes), a large perfect-square rest folded into a.
TEST(QuadraticNumbers, NormalizedMovesSmallPrimeSquaresOut) {
  using algebra::QuadraticNumber;
  const Integer big = *Integer::from_string("100000000000000000039"); // prime, > 2^64
  auto check = [](const QuadraticNumber& in, const QuadraticNumber& out, const char* ctx) {
    EXPECT_EQ(out.b * out.b * Rational(out.d), in.b * in.b * Rational(in.d)) << ctx;
    if (out.d != Integer(1) && !out.b.is_zero()) {
      EXPECT_EQ(out.a, in.a) << ctx;
    }
    for (long p = 2; p < 2000; ++p) {
      const Integer p2(p * p);
      Integer r;
      fmpz_fdiv_r(r.raw_mut(), out.d.raw(), p2.raw());
      if (out.d != Integer(1)) {
        EXPECT_FALSE(r.is_zero()) << ctx << ": " << p << "^2 divides d";
      }
    }
  };
  const Integer d1 = Integer(32) * Integer(27) * Integer(1999 * 1999) * Integer(1997) *
                     Integer(1997 * 1997) * Integer(49 * 121) * big;
  const QuadraticNumber x{Rational(1, 3), Rational(-5, 7), d1};
  const auto n1 = x.normalized();
  check(x, n1, "2^5 3^3 1999^2 1997^3 7^2 11^2 p");
  EXPECT_EQ(n1.d, Integer(2) * Integer(3) * Integer(1997) * big);
  EXPECT_EQ(n1.b, Rational(-5, 7) * Rational(4L * 3 * 1999 * 1997 * 7 * 11));
  // A perfect square beyond the trial primes: sqrt(4 big^2) = 2 big, into a.
  const QuadraticNumber y{Rational(1), Rational(1, 2), Integer(4) * big * big};
  const auto n2 = y.normalized();
  EXPECT_TRUE(n2.b.is_zero());
  EXPECT_EQ(n2.a, Rational(1) + Rational(big));
  // Random radicands: products of primes below 2000 (drawn across the whole range, each to a
  // power 1..4) times 1, a large prime, or its square; the result known by construction (a
  // large prime's square stays in d unless it is all that is left: then d is a perfect square).
  std::mt19937_64 rng(20261204);
  std::vector<long> primes;
  for (long p = 2; p < 2000; ++p) {
    bool prime = true;
    for (long q = 2; q * q <= p && prime; ++q)
      prime = p % q != 0;
    if (prime) primes.push_back(p);
  }
  for (int trial = 0; trial < 300; ++trial) {
    Integer d(1), free(1), root(1);
    const int factors = static_cast<int>(rng() % 7);
    std::set<long> used;
    for (int f = 0; f < factors; ++f) {
      const long p = primes[rng() % primes.size()];
      if (!used.insert(p).second) continue;
      const int e = 1 + static_cast<int>(rng() % 4);
      for (int k = 0; k < e; ++k)
        d = d * Integer(p);
      for (int k = 0; k < e / 2; ++k)
        root = root * Integer(p);
      if (e % 2 == 1) free = free * Integer(p);
    }
    const int tail = static_cast<int>(rng() % 3); // 1, big, big^2
    if (tail >= 1) d = d * big, free = free * big;
    if (tail == 2) {
      d = d * big;
      if (free == big) {
        free = Integer(1), root = root * big;
      } else {
        free = free * big;
      }
    }
    const QuadraticNumber z{Rational(2), Rational(3, 5), d};
    const auto nz = z.normalized();
    const std::string ctx = "trial " + std::to_string(trial) + ", d = " + d.to_string();
    // The split found once and applied to several numbers of the field (special points'
    // coordinates): the same as each one's own normalized(), and the split's own identity.
    const auto split = algebra::square_split(d);
    EXPECT_EQ(split.square * split.square * split.rest, d) << ctx;
    for (const QuadraticNumber& w : {z, QuadraticNumber{Rational(-7, 3), Rational(11), d},
                                     QuadraticNumber{Rational(1), Rational(0), d}}) {
      const auto a = w.normalized(), b = w.normalized(split);
      EXPECT_EQ(a.a, b.a) << ctx;
      EXPECT_EQ(a.b, b.b) << ctx;
      EXPECT_EQ(a.d, b.d) << ctx;
    }
    if (free == Integer(1)) {
      EXPECT_TRUE(nz.b.is_zero()) << ctx;
      EXPECT_EQ(nz.a, Rational(2) + Rational(3, 5) * Rational(root)) << ctx;
    } else {
      check(z, nz, ctx.c_str());
      EXPECT_EQ(nz.d, free) << ctx;
      EXPECT_EQ(nz.b, Rational(3, 5) * Rational(root)) << ctx;
    }
  }
}

// square_split on radicands with a large power of 2 (sqrt(p / q) = sqrt(p q) / q with q = 2^k:
// a surface posed in doubles): d = 2^k * 9 * 5 * 7^3 for k = 0 .. 300, against the closed form
// square = 2^(k / 2) * 3 * 7, rest = 2^(k mod 2) * 35; also with a big square-free odd tail.
TEST(Pencil, SquareSplitTakesPowersOfTwoAtOnce) {
  const Integer odd_tail = Integer(1000003) * Integer(998244353); // two primes beyond 2000
  for (int tail = 0; tail < 2; ++tail)
    for (unsigned long k = 0; k <= 300; ++k) {
      Integer two_k(1);
      fmpz_mul_2exp(two_k.raw_mut(), two_k.raw(), k);
      const Integer t = tail ? odd_tail : Integer(1);
      const Integer d = two_k * Integer(9 * 5 * 343) * t;
      Integer sq(1);
      fmpz_mul_2exp(sq.raw_mut(), sq.raw(), k / 2);
      const auto s = algebra::square_split(d);
      EXPECT_EQ(s.square, sq * Integer(21)) << k;
      EXPECT_EQ(s.rest, Integer(k % 2 ? 2 : 1) * Integer(35) * t) << k;
      EXPECT_EQ(s.square * s.square * s.rest, d) << k;
    }
}

// simplest_root_form: a root of a square-free factor that still splits over Q is given by its
// own irreducible factor. f = (p1 l - q1)(p2 l - q2)(l^2 + c l + e) (random, known roots): the
// two rational roots come back as those rationals, the two others as a + b sqrt(d) with
// (x - a)^2 = b^2 d the quadratic's own roots, inside the isolating interval;
// (l^2 - 2)(l^2 - 3) gives four quadratic roots; an irreducible quartic is left as it is.
TEST(Pencil, SimplestRootFormSplitsReducibleFactors) {
  using algebra::QuadraticNumber;
  using algebra::RootFacts;
  auto poly = [](std::vector<long> c) { // constant first
    std::vector<Integer> v;
    for (long x : c)
      v.emplace_back(x);
    return UPolyZ::from_coeffs(v);
  };
  auto mul = [](const UPolyZ& a, const UPolyZ& b) {
    UPolyZ p;
    fmpz_poly_mul(p.raw_mut(), a.raw(), b.raw());
    return p;
  };
  auto roots_of = [](const UPolyZ& f) {
    std::vector<RootFacts> out;
    const auto s = algebra::isolate_real_roots(f);
    for (size_t i = 0; i + 1 < s.separators.size(); ++i) {
      RootFacts r;
      r.lo = s.separators[i];
      r.hi = s.separators[i + 1];
      r.factor = f.primitive_part();
      out.push_back(algebra::simplest_root_form(r));
    }
    return out;
  };
  auto inside = [](const QuadraticNumber& q, const RootFacts& r) {
    return QuadraticNumber{q.a - r.lo, q.b, q.d}.sign() > 0 &&
           QuadraticNumber{r.hi - q.a, -q.b, q.d}.sign() > 0;
  };
  std::mt19937_64 rng(test_seed());
  std::uniform_int_distribution<long> small(-9, 9), pos(1, 9);
  for (int trial = 0; trial < 200; ++trial) {
    const long p1 = pos(rng), q1 = small(rng), p2 = pos(rng), q2 = small(rng);
    const long c = small(rng), e = small(rng);
    const long disc = c * c - 4 * e;
    const long s = static_cast<long>(std::lround(std::sqrt(static_cast<double>(disc))));
    if (disc <= 0 || s * s == disc || Rational(q1, p1) == Rational(q2, p2)) continue;
    const UPolyZ f = mul(mul(poly({-q1, p1}), poly({-q2, p2})), poly({e, c, 1}));
    const std::string ctx = "f = " + f.to_string("l");
    const auto rs = roots_of(f);
    ASSERT_EQ(rs.size(), 4u) << ctx;
    int rational = 0, quadratic = 0;
    for (const RootFacts& r : rs) {
      if (r.rational_value) {
        ++rational;
        EXPECT_TRUE(*r.rational_value == Rational(q1, p1) || *r.rational_value == Rational(q2, p2))
            << ctx;
        EXPECT_TRUE(r.lo < *r.rational_value && *r.rational_value < r.hi) << ctx;
        EXPECT_EQ(r.factor.degree(), 1) << ctx;
      } else {
        ASSERT_TRUE(r.quadratic.has_value()) << ctx;
        ++quadratic;
        const QuadraticNumber& q = *r.quadratic;
        EXPECT_EQ(q.a, Rational(-c, 2)) << ctx;
        EXPECT_EQ(q.b * q.b * Rational(q.d), Rational(disc, 4)) << ctx;
        EXPECT_TRUE(inside(q, r)) << ctx;
      }
    }
    EXPECT_EQ(rational, 2) << ctx;
    EXPECT_EQ(quadratic, 2) << ctx;
  }
  const auto four = roots_of(mul(poly({-2, 0, 1}), poly({-3, 0, 1})));
  ASSERT_EQ(four.size(), 4u);
  for (const RootFacts& r : four) {
    ASSERT_TRUE(r.quadratic.has_value());
    EXPECT_TRUE(r.quadratic->a.is_zero());
    const Rational sq = r.quadratic->b * r.quadratic->b * Rational(r.quadratic->d);
    EXPECT_TRUE(sq == Rational(2) || sq == Rational(3));
    EXPECT_TRUE(inside(*r.quadratic, r));
  }
  const UPolyZ irreducible = poly({-2, 0, 0, 0, 1});
  for (const RootFacts& r : roots_of(irreducible)) {
    EXPECT_FALSE(r.rational_value || r.quadratic);
    EXPECT_EQ(r.factor, irreducible);
  }
}
