// The printed bounds of every certified distance (decimal_bound, ball.hpp) and the width
// contract (Enclosure::meets_width), each against an independent route:
// - decimal_bound's text equals MPFR's "%.<digits>R{D,U}g" of the same number for random
//   binary numbers (1 to 300 bits, exponents -1100 ... 1100), digits 1 ... 120, both rounding
//   directions, and at the layout boundaries (10^-5, 10^-4, 10^(digits-1), 10^digits, 9.99...
//   rounding up to the next power of ten, exact decimals);
// - meets_width (which first tries a sufficient test without printing) equals the exact
//   check on the printed decimals (MPFR) for enclosures whose relative width straddles
//   10^-digits.
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/enclosure.hpp"

#include "support/canonical.hpp"

#include <gtest/gtest.h>

#include <flint/fmpz.h>
#include <mpfr.h>

#include <random>
#include <string>

using namespace surfcert;
using surfcert::testing::test_seed;

namespace {

std::string mpfr_reference(const arf_t x, bool upper, long digits) {
  mpfr_t m;
  mpfr_init2(m, static_cast<mpfr_prec_t>(arf_bits(x) + 2));
  arf_get_mpfr(m, x, MPFR_RNDN);
  const std::string fmt = "%." + std::to_string(digits) + "R" + (upper ? "U" : "D") + "g";
  char* s = nullptr;
  mpfr_asprintf(&s, fmt.c_str(), m);
  std::string out = s;
  mpfr_free_str(s);
  mpfr_clear(m);
  return out;
}

// A random positive binary number: an odd mantissa of 1 ... bits bits times 2^e.
void random_arf(std::mt19937_64& rng, arf_t x, int max_bits, long emin, long emax) {
  std::uniform_int_distribution<int> nb(1, max_bits);
  std::uniform_int_distribution<long> ex(emin, emax);
  fmpz_t m;
  fmpz_init(m);
  const int bits = nb(rng);
  for (int i = 0; i < bits; i += 32) {
    fmpz_mul_2exp(m, m, 32);
    fmpz_add_ui(m, m, rng() & 0xffffffffu);
  }
  fmpz_add_ui(m, m, 1);
  arf_set_fmpz(x, m);
  arf_mul_2exp_si(x, x, ex(rng) - static_cast<long>(fmpz_bits(m)));
  fmpz_clear(m);
}

// upper - lower <= 10^-digits lower on the printed text, in MPFR.
bool printed_width_ok(const certify::Enclosure& e, long digits) {
  mpfr_t l, u, w, t;
  mpfr_inits2(4000, l, u, w, t, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(l, e.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u, e.upper().c_str(), 10, MPFR_RNDU);
  mpfr_sub(w, u, l, MPFR_RNDU);
  mpfr_ui_pow_ui(t, 10, static_cast<unsigned long>(digits), MPFR_RNDD);
  mpfr_div(t, l, t, MPFR_RNDD);
  const bool ok = mpfr_cmp(w, t) <= 0;
  mpfr_clears(l, u, w, t, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

} // namespace

TEST(DecimalBound, EqualsMpfrFormattedOutput) {
  std::mt19937_64 rng(test_seed());
  const long digit_choices[] = {1, 2, 3, 5, 15, 17, 20, 32, 120};
  certify::Arf x;
  for (int t = 0; t < 20000; ++t) {
    const long digits = digit_choices[t % 9];
    random_arf(rng, x.v, t % 3 == 0 ? 300 : 60, t % 5 == 0 ? -1100 : -70, t % 5 == 0 ? 1100 : 70);
    for (bool upper : {false, true})
      ASSERT_EQ(certify::decimal_bound(x.v, upper, digits), mpfr_reference(x.v, upper, digits))
          << arf_get_str(x.v, 40) << " digits " << digits << " upper " << upper;
  }
}

TEST(DecimalBound, LayoutBoundaries) {
  certify::Arf x;
  certify::Ball b;
  // Powers of ten and their neighbours (one ulp at 200 bits either side), where the fixed /
  // exponent layout switches and 9.99... rounds up to the next power.
  for (long e = -8; e <= 25; ++e) {
    for (int side = -1; side <= 1; ++side) {
      arb_set_si(b.v, 10);
      arb_pow_ui(b.v, b.v, static_cast<ulong>(e < 0 ? -e : e), 200);
      if (e < 0) arb_inv(b.v, b.v, 200);
      arf_set(x.v, arb_midref(b.v));
      if (side != 0) {
        certify::Arf ulp;
        arf_set_ui(ulp.v, 1);
        arf_mul_2exp_si(ulp.v, ulp.v, arf_abs_bound_lt_2exp_si(x.v) - 200);
        if (side > 0)
          arf_add(x.v, x.v, ulp.v, ARF_PREC_EXACT, ARF_RND_DOWN);
        else
          arf_sub(x.v, x.v, ulp.v, ARF_PREC_EXACT, ARF_RND_DOWN);
      }
      for (long digits : {1L, 2L, 6L, 17L})
        for (bool upper : {false, true})
          ASSERT_EQ(certify::decimal_bound(x.v, upper, digits), mpfr_reference(x.v, upper, digits))
              << "10^" << e << " side " << side << " digits " << digits << " upper " << upper;
    }
  }
  // Exact decimals (printed without rounding) and 0.5, 0.75, 1, 3 at few digits.
  for (double d : {0.5, 0.75, 1.0, 3.0, 1000.0, 123456789.0, 0.0001, 0.00001, 1e17, 1e-300})
    for (long digits : {1L, 2L, 17L})
      for (bool upper : {false, true}) {
        arf_set_d(x.v, d);
        ASSERT_EQ(certify::decimal_bound(x.v, upper, digits), mpfr_reference(x.v, upper, digits))
            << d << " digits " << digits;
      }
}

TEST(DecimalBound, MeetsWidthEqualsTheCheckOnThePrintedText) {
  std::mt19937_64 rng(test_seed() + 1);
  std::uniform_real_distribution<double> f(0.2, 1.8);
  certify::Ball lo, w, hi;
  long met = 0, missed = 0;
  for (int t = 0; t < 4000; ++t) {
    const long digits = t % 2 ? 15 : 30;
    certify::Arf x;
    random_arf(rng, x.v, 200, t % 7 == 0 ? -900 : -40, t % 7 == 0 ? 900 : 40);
    // hi = lo (1 + f 10^-digits): relative widths from 0.2 to 1.8 times the contract.
    arb_set_arf(lo.v, x.v);
    arb_set_ui(w.v, 10);
    arb_pow_ui(w.v, w.v, static_cast<ulong>(digits), 300);
    arb_inv(w.v, w.v, 300);
    certify::Ball fb;
    arb_set_d(fb.v, f(rng));
    arb_mul(w.v, w.v, fb.v, 300);
    arb_mul(w.v, w.v, lo.v, 300);
    arb_add(hi.v, lo.v, w.v, 300);
    const auto e = certify::Enclosure::from_bounds(x.v, arb_midref(hi.v), digits);
    const bool expect = printed_width_ok(e, digits);
    ASSERT_EQ(e.meets_width(digits), expect) << e.lower() << " " << e.upper() << " " << digits;
    (expect ? met : missed)++;
  }
  EXPECT_GT(met, 500);
  EXPECT_GT(missed, 500);
}
