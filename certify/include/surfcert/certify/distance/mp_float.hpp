// surfcert::certify::Mp: Boost's MPFR float for the float searches that steer the certified
// fast paths beyond double precision (they only choose where Arb certifies), with exact
// conversions from rationals and into Arb balls.
//
// Boost gives every new value (temporaries included) the *default* precision: MpPrecision sets
// it for a scope and restores it, and every conversion that must keep the working precision
// has to happen inside that scope.
#pragma once

#include "surfcert/algebra/arb.hpp"
#include "surfcert/core/rational.hpp"

#include <boost/multiprecision/mpfr.hpp>
#include <flint/fmpq.h>

namespace surfcert::certify {

using Mp = boost::multiprecision::mpfr_float;

struct MpPrecision {
  explicit MpPrecision(long bits) : saved(Mp::default_precision()) {
    Mp::default_precision(static_cast<unsigned>(static_cast<double>(bits) / 3.3) + 5);
  }
  ~MpPrecision() { Mp::default_precision(saved); }
  MpPrecision(const MpPrecision&) = delete;
  MpPrecision& operator=(const MpPrecision&) = delete;
  unsigned saved;
};

/// The rational rounded to the current default precision.
inline Mp mp_from(const core::Rational& r) {
  Mp x;
  fmpq_get_mpfr(x.backend().data(), r.raw(), MPFR_RNDN);
  return x;
}

/// The exact value of x as a ball of radius 0.
inline void mp_to_ball(arb_t b, const Mp& x) {
  arf_set_mpfr(arb_midref(b), x.backend().data());
  mag_zero(arb_radref(b));
}

} // namespace surfcert::certify
