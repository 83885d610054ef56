// Times real-root isolation on polynomials with coefficients beyond kCgalMaxBits (the
// extreme_inputs_test cases and harder ones) and on small ones. Prints one line per case:
// name, coefficient bits, roots (fallback / isolate_real_roots), milliseconds (best of `reps`)
// of the fallback beyond kCgalMaxBits (isolate_real_roots_descartes, the loop isolator) and of
// isolate_real_roots (the float guess first, exact checks, the fallback when the guess fails). Run:
// build/bench/real_roots_bench [reps]
#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/real_roots.hpp"

#include <flint/fmpz.h>
#include <flint/fmpz_poly.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

using surfcert::algebra::RootSeparation;
using surfcert::algebra::UPolyZ;
using surfcert::core::Integer;

namespace {

Integer pow10(unsigned long e) {
  Integer r;
  fmpz_ui_pow_ui(r.raw_mut(), 10, e);
  return r;
}

Integer pow2(unsigned long e) {
  Integer r(1);
  fmpz_mul_2exp(r.raw_mut(), r.raw(), e);
  return r;
}

UPolyZ mul(const UPolyZ& a, const UPolyZ& b) {
  UPolyZ p;
  fmpz_poly_mul(p.raw_mut(), a.raw(), b.raw());
  return p;
}

// (x - 1)(r2 x^2 + (8 - r2) x + 1): the pencil of spheres of squared radius r2 and 1
// (extreme_inputs_test), and its reciprocal (r2 -> 1 / r2, scaled to integers).
UPolyZ sphere_pencil(const Integer& r2, bool reciprocal) {
  const UPolyZ lin = UPolyZ::from_coeffs({Integer(-1), Integer(1)});
  const UPolyZ quad = reciprocal
                          ? UPolyZ::from_coeffs({r2, Integer(8) * r2 - Integer(1), Integer(1)})
                          : UPolyZ::from_coeffs({Integer(1), Integer(8) - r2, r2});
  return mul(lin, quad);
}

// p(x / 2^s) * 2^(s deg p): the roots scaled by 2^s, the coefficients grown by s deg p bits.
UPolyZ scale_roots(const UPolyZ& p, unsigned long s) {
  UPolyZ q = p;
  const long n = p.degree();
  for (long i = 0; i <= n; ++i)
    fmpz_mul_2exp(q.raw_mut()->coeffs + i, p.raw()->coeffs + i,
                  static_cast<unsigned long>(s * static_cast<unsigned long>(n - i)));
  return q;
}

double best_ms(const std::function<RootSeparation()>& f, int reps, size_t& roots) {
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    roots = f().num_roots();
    best = std::min(
        best,
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

} // namespace

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::atoi(argv[1]) : 3;
  std::vector<std::pair<std::string, UPolyZ>> cases;
  for (unsigned long e : {700UL, 4000UL, 16000UL, 39000UL}) {
    cases.emplace_back("pencil 1e" + std::to_string(e), sphere_pencil(pow10(e), false));
    cases.emplace_back("pencil 1e-" + std::to_string(e), sphere_pencil(pow10(e), true));
  }
  // Irreducible cubics and quintics with three / five real roots, roots scaled by 2^5000.
  const UPolyZ cubic = UPolyZ::from_coeffs({Integer(1), Integer(-3), Integer(0), Integer(1)});
  const UPolyZ quintic = UPolyZ::from_coeffs({Integer(1), Integer(-10), Integer(0), Integer(20),
                                              Integer(0), Integer(-7), Integer(0), Integer(1)});
  cases.emplace_back("x^3-3x+1 roots*2^5000", scale_roots(cubic, 5000));
  cases.emplace_back("deg7 roots*2^5000", scale_roots(quintic, 5000));
  // Near-coincident roots of two irreducible quadratics: sqrt 2 and sqrt 2 + 2^-100, times
  // 2^5000 (10,000-bit coefficients): x^2 - 2 and (x - 2^-100)^2 - 2 scaled.
  {
    const UPolyZ a = UPolyZ::from_coeffs({Integer(-2), Integer(0), Integer(1)});
    const UPolyZ b = UPolyZ::from_coeffs({Integer(1) - pow2(201), -pow2(101), pow2(200)});
    cases.emplace_back("sqrt2 vs +2^-100, *2^5000", scale_roots(mul(a, b), 5000));
  }
  // Roots 10^5000, 10^-5000, 3 and an irreducible cubic's three roots near 1 (x^3 - 3x + 1
  // shifted), one factor each.
  {
    const UPolyZ big = UPolyZ::from_coeffs({-pow10(5000), Integer(1)});
    const UPolyZ tiny = UPolyZ::from_coeffs({Integer(-1), pow10(5000)});
    const UPolyZ three = UPolyZ::from_coeffs({Integer(-3), Integer(1)});
    cases.emplace_back("1e5000,1e-5000,3,cubic", mul(mul(mul(big, tiny), three), cubic));
  }
  // A product of (2^k x - (2^k + j)) with an irreducible quadratic 2^-2000 from one of them.
  {
    UPolyZ p = UPolyZ::from_coeffs({Integer(1)});
    for (int j = 1; j <= 3; ++j)
      p = mul(p, UPolyZ::from_coeffs({-(pow2(4000) + Integer(j)), pow2(4000)}));
    // x^2 - 2 x + 1 - 2^-4000 -> roots 1 +- 2^-2000: 2^4000 x^2 - 2^4001 x + 2^4000 - 1.
    p = mul(p, UPolyZ::from_coeffs({pow2(4000) - Integer(1), -pow2(4001), pow2(4000)}));
    cases.emplace_back("rationals + 1+-2^-2000", p);
  }
  // Small polynomials (the CGAL route is the production one here; for reference).
  cases.emplace_back("small (x-1)(x^2-2)",
                     mul(UPolyZ::from_coeffs({Integer(-1), Integer(1)}),
                         UPolyZ::from_coeffs({Integer(-2), Integer(0), Integer(1)})));
  cases.emplace_back("small deg7", quintic);

  std::printf("%-30s %7s %5s %12s %12s\n", "case", "bits", "roots", "fallback ms", "isolate ms");
  for (const auto& [name, p] : cases) {
    size_t r1 = 0, r2 = 0;
    const double fallback =
        best_ms([&] { return surfcert::algebra::isolate_real_roots_descartes(p); }, reps, r1);
    const double iso = best_ms([&] { return surfcert::algebra::isolate_real_roots(p); }, reps, r2);
    std::printf("%-30s %7ld %2zu/%zu %12.2f %12.2f\n", name.c_str(),
                surfcert::algebra::max_coefficient_bits(p), r1, r2, fallback, iso);
  }
}
