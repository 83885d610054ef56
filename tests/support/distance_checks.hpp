// Helpers shared by the distance tests: decimal enclosures compared exactly (MPFR reads the
// decimal strings with outward rounding), and rational rigid motions / scalings as 4x4
// congruences (Q' = P^T Q P describes the moved surface), so invariance checks stay exact.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/core/quadric.hpp"

#include <gmp.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <string>

namespace surfcert::testing {

/// A quadric from an equation (test input, location "t").
inline core::QuadricMatrix q(const std::string& s) {
  return core::io::quadric_from_equation(s, {"t", 1, 1, ""});
}

inline double lo(const certify::DistanceResult& r) {
  return std::stod(r.lower());
}
inline double hi(const certify::DistanceResult& r) {
  return std::stod(r.upper());
}

/// [lower, upper] of two results overlap (decimal strings read exactly at 3000 bits).
inline bool overlap(const certify::DistanceResult& a, const certify::DistanceResult& b) {
  mpfr_t la, ua, lb, ub;
  mpfr_inits2(3000, la, ua, lb, ub, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(la, a.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(ua, a.upper().c_str(), 10, MPFR_RNDU);
  mpfr_set_str(lb, b.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(ub, b.upper().c_str(), 10, MPFR_RNDU);
  bool ok = mpfr_cmp(la, ub) <= 0 && mpfr_cmp(lb, ua) <= 0;
  mpfr_clears(la, ua, lb, ub, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

/// r's enclosure meets the decimal interval [lo, hi] (read exactly at 3000 bits).
inline bool overlap_bounds(const certify::DistanceResult& r, const std::string& lo,
                           const std::string& hi) {
  mpfr_t la, ua, lb, ub;
  mpfr_inits2(3000, la, ua, lb, ub, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(la, r.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(ua, r.upper().c_str(), 10, MPFR_RNDU);
  mpfr_set_str(lb, lo.c_str(), 10, MPFR_RNDD);
  mpfr_set_str(ub, hi.c_str(), 10, MPFR_RNDU);
  bool ok = mpfr_cmp(la, ub) <= 0 && mpfr_cmp(lb, ua) <= 0;
  mpfr_clears(la, ua, lb, ub, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

/// A reference interval from an independent route (decimal bounds, read with outward rounding).
struct Bounds {
  std::string lower, upper;
};

inline bool overlap(const certify::DistanceResult& r, const Bounds& b) {
  return overlap_bounds(r, b.lower, b.upper);
}

/// x lies in [lower, upper] (the decimal strings read with outward rounding, at least 4000
/// bits or x's precision + 64).
inline bool contains(const certify::DistanceResult& r, const mpfr_t x) {
  const mpfr_prec_t bits = std::max<mpfr_prec_t>(4000, mpfr_get_prec(x) + 64);
  mpfr_t l, u;
  mpfr_inits2(bits, l, u, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(l, r.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u, r.upper().c_str(), 10, MPFR_RNDU);
  const bool ok = mpfr_cmp(l, x) <= 0 && mpfr_cmp(x, u) <= 0;
  mpfr_clears(l, u, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

/// log10 of the relative width (upper - lower) / lower, computed in MPFR (at 1000 digits the
/// width itself underflows a double).
inline double log10_rel_width(const certify::DistanceResult& r) {
  mpfr_t l, u;
  mpfr_inits2(4000, l, u, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(l, r.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u, r.upper().c_str(), 10, MPFR_RNDU);
  mpfr_sub(u, u, l, MPFR_RNDU);
  mpfr_div(u, u, l, MPFR_RNDU);
  mpfr_log10(u, u, MPFR_RNDU);
  const double w = mpfr_get_d(u, MPFR_RNDU);
  mpfr_clears(l, u, static_cast<mpfr_ptr>(nullptr));
  return w;
}

/// [lower, upper] of r times the decimal factor s (e.g. "1e8", "0.00000001"), rounded
/// outward at 2000 bits with a relative slack of 1e-300 (the factor's own rounding is about
/// 2^-2000), overlaps the enclosure e: the scaling law d(s A, s B) = s d(A, B).
inline bool overlap_scaled(const certify::DistanceResult& r, const std::string& s,
                           const certify::DistanceResult& e) {
  mpfr_t l, u, k, el, eu;
  mpfr_inits2(2000, l, u, k, el, eu, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(l, r.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(u, r.upper().c_str(), 10, MPFR_RNDU);
  mpfr_set_str(k, s.c_str(), 10, MPFR_RNDN);
  mpfr_mul(l, l, k, MPFR_RNDD);
  mpfr_mul(u, u, k, MPFR_RNDU);
  mpfr_mul_d(l, l, 1 - 1e-300, MPFR_RNDD);
  mpfr_mul_d(u, u, 1 + 1e-300, MPFR_RNDU);
  mpfr_set_str(el, e.lower().c_str(), 10, MPFR_RNDD);
  mpfr_set_str(eu, e.upper().c_str(), 10, MPFR_RNDU);
  const bool ok = mpfr_cmp(l, eu) <= 0 && mpfr_cmp(el, u) <= 0;
  mpfr_clears(l, u, k, el, eu, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

/// Rigid motion x -> R x + t with R from the integer quaternion (w, x, y, z), as the 4x4
/// congruence P with Q' = P^T Q P describing the moved surface.
inline core::Mat4 motion(long w, long x, long y, long z, const std::array<core::Rational, 3>& t) {
  core::Rational n(w * w + x * x + y * y + z * z);
  long R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                  {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                  {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  core::Mat4 p;
  for (size_t i = 0; i < 3; ++i) {
    core::Rational s;
    for (size_t j = 0; j < 3; ++j) {
      p[i][j] = core::Rational(R[j][i]) / n; // inverse rotation R^T
      s += p[i][j] * t[j];
    }
    p[i][3] = -s;
  }
  p[3][3] = core::Rational(1);
  return p;
}

/// Scaling x -> s x as a congruence (Q'(x) = Q(x / s)).
inline core::Mat4 scaling(const core::Rational& s) {
  core::Mat4 p;
  for (size_t i = 0; i < 3; ++i)
    p[i][i] = core::Rational(1) / s;
  p[3][3] = core::Rational(1);
  return p;
}

/// out = (sqrt(s) - t) / u for rationals s >= 0, t, u != 0 given as "p/q" text, at 1200 bits
/// (a closed-form distance to compare an enclosure with).
inline void closed_form(mpfr_t out, const char* s, const char* t, const char* u) {
  mpq_t a;
  mpq_init(a);
  mpfr_t x;
  mpfr_init2(x, 1200);
  mpq_set_str(a, s, 10);
  mpq_canonicalize(a);
  mpfr_set_q(out, a, MPFR_RNDN);
  mpfr_sqrt(out, out, MPFR_RNDN);
  mpq_set_str(a, t, 10);
  mpq_canonicalize(a);
  mpfr_set_q(x, a, MPFR_RNDN);
  mpfr_sub(out, out, x, MPFR_RNDN);
  mpq_set_str(a, u, 10);
  mpq_canonicalize(a);
  mpfr_set_q(x, a, MPFR_RNDN);
  mpfr_div(out, out, x, MPFR_RNDN);
  mpfr_clear(x);
  mpq_clear(a);
}

} // namespace surfcert::testing
