#include "surfcert/certify/distance/ball.hpp"

#include <mpfr.h>

namespace surfcert::certify {

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

} // namespace surfcert::certify
