#include "surfcert/certify/distance/ball.hpp"

#include "surfcert/core/torus.hpp"

#include <mpfr.h>

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

std::string decimal_bound(const arf_t x, bool upper, long digits) {
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
