#include "surfcert/certify/distance/enclosure.hpp"
#include "surfcert/certify/distance/ball.hpp"

#include <CGAL/Interval_nt.h>
#include <mpfr.h>

#include <cmath>
#include <cstdio>

namespace surfcert::certify {

Enclosure Enclosure::from_ball(const arb_t d, long digits) {
  Enclosure e;
  e.digits_ = digits;
  arb_get_lbound_arf(e.lo_.v, d, bits_for(digits));
  arb_get_ubound_arf(e.hi_.v, d, bits_for(digits));
  if (arf_sgn(e.lo_.v) < 0) arf_zero(e.lo_.v);
  return e;
}

Enclosure Enclosure::from_bounds(const arf_t lo, const arf_t hi, long digits) {
  Enclosure e;
  e.digits_ = digits;
  arf_set(e.lo_.v, lo);
  arf_set(e.hi_.v, hi);
  if (arf_sgn(e.lo_.v) < 0 || arf_is_nan(e.lo_.v)) arf_zero(e.lo_.v);
  if (arf_is_nan(e.hi_.v)) arf_pos_inf(e.hi_.v);
  return e;
}

Enclosure Enclosure::exact(const core::Rational& v, long digits) {
  Ball b;
  arb_set_fmpq(b.v, v.raw(), bits_for(digits) + 64);
  return from_ball(b.v, digits);
}

Enclosure Enclosure::zero() {
  return Enclosure();
}

Enclosure Enclosure::up_to(const arf_t hi, long digits) {
  Enclosure e;
  e.digits_ = digits;
  arf_set(e.hi_.v, hi);
  return e;
}

Enclosure Enclosure::scaled_2exp(long k) const {
  Enclosure e(*this);
  arf_mul_2exp_si(e.lo_.v, e.lo_.v, k);
  arf_mul_2exp_si(e.hi_.v, e.hi_.v, k);
  return e;
}

Enclosure Enclosure::min_of(const Enclosure& a, const Enclosure& b) {
  Enclosure e(a);
  if (arf_cmp(b.lo_.v, e.lo_.v) < 0) arf_set(e.lo_.v, b.lo_.v);
  if (arf_cmp(b.hi_.v, e.hi_.v) < 0) arf_set(e.hi_.v, b.hi_.v);
  e.digits_ = std::max(a.digits_, b.digits_);
  return e;
}

const std::string Enclosure::lower() const {
  if (arf_is_zero(lo_.v)) return "0";
  return decimal_bound(lo_.v, false, digits_ + 2);
}

const std::string Enclosure::upper() const {
  if (arf_is_zero(hi_.v)) return "0";
  if (!arf_is_finite(hi_.v)) return "inf";
  return decimal_bound(hi_.v, true, digits_ + 2);
}

double Enclosure::approx() const {
  if (!arf_is_finite(hi_.v)) return arf_get_d(lo_.v, ARF_RND_NEAR);
  Arf m;
  arf_add(m.v, lo_.v, hi_.v, ARF_PREC_EXACT, ARF_RND_NEAR);
  arf_mul_2exp_si(m.v, m.v, -1);
  return arf_get_d(m.v, ARF_RND_NEAR);
}

std::string Enclosure::approx_text() const {
  const double d = approx();
  char buf[64];
  const bool tiny = d == 0 && !arf_is_zero(arf_is_finite(hi_.v) ? hi_.v : lo_.v);
  if (!tiny && (std::isfinite(d) || !arf_is_finite(hi_.v))) {
    // As printf's "%.17g" writes the double (the text every answer had).
    std::snprintf(buf, sizeof buf, "%.17g", d);
    return buf;
  }
  // The midpoint beyond the doubles (a sphere of radius 1e400: "inf"; a lower bound 1e-1001:
  // "0"): the same format from MPFR, whose exponent has no such limit.
  Arf m;
  arf_add(m.v, lo_.v, hi_.v, ARF_PREC_EXACT, ARF_RND_NEAR);
  arf_mul_2exp_si(m.v, m.v, -1);
  mpfr_t x;
  mpfr_init2(x, 64);
  arf_get_mpfr(x, m.v, MPFR_RNDN);
  char* text = nullptr;
  mpfr_asprintf(&text, "%.17Rg", x);
  std::string out = text ? text : "0";
  mpfr_free_str(text);
  mpfr_clear(x);
  return out;
}

void Enclosure::to_ball(arb_t out, long prec) const {
  arb_set_interval_arf(out, lo_.v, hi_.v, prec);
}

bool Enclosure::meets_width(long digits) const {
  if (!arf_is_finite(hi_.v)) return false;
  // A sufficient test without printing: each bound is printed with digits_ + 2 significant
  // digits rounded outward, so it moves by less than one unit of its last digit, at most
  // eps = 10^-(digits_ + 1) times itself. If hi (1 + eps) - lo (1 - eps) <= 10^-digits
  // lo (1 - eps), the printed decimals meet the width (Arb decides, rigorously). Otherwise
  // the exact check on the printed text below.
  if (arf_sgn(lo_.v) > 0 && digits >= 0 && digits_ >= 0 && digits <= 250 && digits_ <= 250) {
    // The same test first in outward-rounded double intervals (CGAL::Interval_nt): lo and hi
    // rounded down and up to doubles (which only widens w and lowers tol), 10^-k as an
    // interval; directed rounding keeps every bound valid (an underflow only weakens tol).
    // Not decided there (a width at the edge, extreme magnitudes): the Arb test below.
    const double ld = arf_get_d(lo_.v, ARF_RND_FLOOR), hd = arf_get_d(hi_.v, ARF_RND_CEIL);
    if (ld > 0x1p-600 && hd < 0x1p600) {
      using DI = CGAL::Interval_nt<false>;
      CGAL::Protect_FPU_rounding<true> guard;
      auto pow10_inv = [](long k) {
        DI r(1), tenth = DI(1) / DI(10);
        for (; k > 0; --k)
          r *= tenth;
        return r;
      };
      const DI L(ld), H(hd), eps = pow10_inv(digits_ + 1);
      const DI w = (H - L) + eps * (H + L), tol = L * pow10_inv(digits) * (DI(1) - eps);
      if (w.sup() <= tol.inf()) return true;
    }
    const long prec = 64;
    Ball eps, l, h, w, t, tol;
    arb_ui_pow_ui(eps.v, 10, static_cast<ulong>(digits_ + 1), prec);
    arb_inv(eps.v, eps.v, prec);
    arb_set_arf(l.v, lo_.v);
    arb_set_arf(h.v, hi_.v);
    arb_sub(w.v, h.v, l.v, prec);
    arb_add(t.v, h.v, l.v, prec);
    arb_addmul(w.v, eps.v, t.v, prec);
    arb_ui_pow_ui(tol.v, 10, static_cast<ulong>(digits), prec);
    arb_div(tol.v, l.v, tol.v, prec);
    arb_submul(tol.v, tol.v, eps.v, prec);
    if (arb_le(w.v, tol.v)) return true;
  }
  const std::string l = lower(), u = upper();
  mpfr_t ml, mu, w, tol;
  const mpfr_prec_t bits = static_cast<mpfr_prec_t>(64 + 4 * (l.size() + u.size()) + 4 * digits);
  mpfr_inits2(bits, ml, mu, w, tol, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(ml, l.c_str(), 10, MPFR_RNDD);
  mpfr_set_str(mu, u.c_str(), 10, MPFR_RNDU);
  mpfr_sub(w, mu, ml, MPFR_RNDU);
  mpfr_set_ui(tol, 10, MPFR_RNDN);
  mpfr_pow_si(tol, tol, -digits, MPFR_RNDD);
  mpfr_mul(tol, tol, ml, MPFR_RNDD);
  const bool ok = mpfr_cmp(w, tol) <= 0;
  mpfr_clears(ml, mu, w, tol, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

} // namespace surfcert::certify
