#include "surfcert/certify/distance/ball.hpp"

#include "surfcert/core/torus.hpp"

#include <flint/fmpz.h>
#include <mpfr.h>

#include <cmath>
#include <cstdlib>

namespace surfcert::certify {

void unit_plane_frame(Ball (&u)[3], Ball (&v)[3], const std::array<core::Rational, 3>& a,
                      long prec) {
  const auto fr = core::plane_frame(a);
  Ball(*out[2])[3] = {&u, &v};
  for (size_t j = 0; j < 2; ++j) {
    const auto& w = fr[j];
    Ball inv;
    const core::Rational ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    arb_set_fmpq(inv.v, ww.raw(), prec);
    arb_rsqrt(inv.v, inv.v, prec);
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq((*out[j])[i].v, w[i].raw(), prec);
      arb_mul((*out[j])[i].v, (*out[j])[i].v, inv.v, prec);
    }
  }
}

namespace {

// C's %.<digits>g layout of the positive number N * 10^(X - digits + 1), N a decimal integer
// of exactly `digits` digits: fixed notation when -4 <= X < digits, else d.ddde+XX; trailing
// zeros of the fraction (and a bare point) dropped.
std::string g_layout(const std::string& N, long X, long digits) {
  std::string out;
  if (X >= -4 && X < digits) {
    if (X >= 0) {
      out = N.substr(0, static_cast<size_t>(X + 1));
      std::string frac = N.substr(static_cast<size_t>(X + 1));
      while (!frac.empty() && frac.back() == '0')
        frac.pop_back();
      if (!frac.empty()) out += "." + frac;
    } else {
      std::string frac = std::string(static_cast<size_t>(-X - 1), '0') + N;
      while (!frac.empty() && frac.back() == '0')
        frac.pop_back();
      out = "0." + frac;
    }
    return out;
  }
  std::string frac = N.substr(1);
  while (!frac.empty() && frac.back() == '0')
    frac.pop_back();
  out = N.substr(0, 1);
  if (!frac.empty()) out += "." + frac;
  const long ax = X < 0 ? -X : X;
  out += X < 0 ? "e-" : "e+";
  if (ax < 10) out += "0";
  return out + std::to_string(ax);
}

// The positive finite x = man 2^exp printed as mpfr's "%.<digits>R{D,U}g" would, with exact
// integer arithmetic: N = floor or ceil of x 10^(digits - 1 - X) for the decimal exponent X of
// the rounded value (10^(digits-1) <= N < 10^digits). MPFR's formatted output is general and
// slow (a few microseconds per bound); this is what every certified answer prints.
std::string decimal_bound_exact(const arf_t x, bool upper, long digits) {
  fmpz_t man, exp, num, den, N, lo, hi;
  fmpz_init(man);
  fmpz_init(exp);
  fmpz_init(num);
  fmpz_init(den);
  fmpz_init(N);
  fmpz_init(lo);
  fmpz_init(hi);
  arf_get_fmpz_2exp(man, exp, x);
  const slong e2 = fmpz_get_si(exp);
  // log10 x in [(e2 + bits - 1) log10 2, (e2 + bits) log10 2): a first guess of X.
  long X = static_cast<long>(std::floor(
      static_cast<double>(e2 + static_cast<slong>(fmpz_bits(man)) - 1) * 0.30102999566398120));
  fmpz_ui_pow_ui(lo, 10, static_cast<ulong>(digits - 1));
  fmpz_mul_ui(hi, lo, 10);
  std::string out;
  for (int attempt = 0; attempt < 4; ++attempt) {
    const long k = digits - 1 - X; // N = round(x 10^k)
    fmpz_set(num, man);
    fmpz_one(den);
    if (k >= 0) {
      fmpz_ui_pow_ui(N, 10, static_cast<ulong>(k));
      fmpz_mul(num, num, N);
    } else {
      fmpz_ui_pow_ui(den, 10, static_cast<ulong>(-k));
    }
    if (e2 >= 0)
      fmpz_mul_2exp(num, num, static_cast<ulong>(e2));
    else
      fmpz_mul_2exp(den, den, static_cast<ulong>(-e2));
    if (upper)
      fmpz_cdiv_q(N, num, den);
    else
      fmpz_fdiv_q(N, num, den);
    if (fmpz_cmp(N, hi) >= 0) {
      ++X; // rounded up to 10^digits (or X guessed low): one more decimal place to the left
      continue;
    }
    if (fmpz_cmp(N, lo) < 0) {
      --X;
      continue;
    }
    char* str = fmpz_get_str(nullptr, 10, N);
    out = g_layout(str, X, digits);
    flint_free(str);
    break;
  }
  fmpz_clear(man);
  fmpz_clear(exp);
  fmpz_clear(num);
  fmpz_clear(den);
  fmpz_clear(N);
  fmpz_clear(lo);
  fmpz_clear(hi);
  return out;
}

} // namespace

std::string decimal_bound(const arf_t x, bool upper, long digits) {
  // Positive finite values with a moderate exponent: exact integer arithmetic (the same text).
  if (arf_sgn(x) > 0 && arf_is_finite(x) && digits >= 1 && digits <= 100000 &&
      fmpz_fits_si(ARF_EXPREF(x)) && std::labs(fmpz_get_si(ARF_EXPREF(x))) < 1000000) {
    std::string out = decimal_bound_exact(x, upper, digits);
    if (!out.empty()) return out;
  }
  mpfr_t m;
  mpfr_init2(m, static_cast<mpfr_prec_t>(arf_bits(x) + 2));
  arf_get_mpfr(m, x, MPFR_RNDN); // exact: enough bits
  std::string fmt = "%." + std::to_string(digits) + "R" + (upper ? "U" : "D") + "g";
  int n = mpfr_snprintf(nullptr, 0, fmt.c_str(), m);
  std::string out(static_cast<size_t>(n) + 1, '\0');
  mpfr_snprintf(out.data(), out.size(), fmt.c_str(), m);
  out.resize(static_cast<size_t>(n));
  mpfr_clear(m);
  return out;
}

bool relative_enclosure(arb_t d, const arb_t lo, const arb_t hi, long digits, long prec) {
  if (!arb_is_positive(lo) || !arb_is_finite(hi)) return false;
  arf_t l, h;
  arf_init(l);
  arf_init(h);
  arb_get_lbound_arf(l, lo, prec);
  arb_get_ubound_arf(h, hi, prec);
  Ball width, tol, lower;
  arb_set_arf(width.v, h);
  arb_set_arf(lower.v, l);
  arb_sub(width.v, width.v, lower.v, prec);
  arb_set_ui(tol.v, 10);
  arb_pow_ui(tol.v, tol.v, static_cast<ulong>(digits), prec);
  arb_div(tol.v, lower.v, tol.v, prec);
  const bool ok = arb_le(width.v, tol.v) != 0;
  if (ok) arb_set_interval_arf(d, l, h, prec);
  arf_clear(l);
  arf_clear(h);
  return ok;
}

std::array<double, 2> outward_interval(const arb_t x) {
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  arb_get_lbound_arf(lo, x, 64);
  arb_get_ubound_arf(hi, x, 64);
  const std::array<double, 2> out{arf_get_d(lo, ARF_RND_FLOOR), arf_get_d(hi, ARF_RND_CEIL)};
  arf_clear(lo);
  arf_clear(hi);
  return out;
}

} // namespace surfcert::certify
