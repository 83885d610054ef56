// surfcert::certify::Enclosure and Estimate: the two kinds of numeric distance answer, kept
// apart by their types.
//
// An Enclosure is a proven interval [lower, upper] that contains the exact distance. It can
// only be built from a proof: an Arb ball (the exact value lies in it), rigorous arf bounds
// (each computed with outward rounding), an exact rational, or another Enclosure (hull,
// exact scaling by 2^k). There is no constructor from a double or from decimal text, so a
// float judgement cannot fill a certified field. The bounds are stored exactly (binary
// floating point, arf) and printed as decimals with digits + 2 significant digits, rounded
// outward, so the printed interval still contains the exact value.
//
// An Estimate is a floating-point answer (float mode, an uncertified search): a double and
// nothing else; it never converts to an Enclosure.
//
// The width contract of a certified distance is upper - lower <= 10^-digits * lower on the
// printed decimals (meets_width checks it exactly, in MPFR).
#pragma once

#include "surfcert/algebra/arb.hpp"
#include "surfcert/core/rational.hpp"

#include <string>

namespace surfcert::certify {

using algebra::Arf;

class Enclosure {
public:
  /// The ball's bounds, lower clamped at 0 (a distance is never negative).
  static Enclosure from_ball(const arb_t d, long digits);
  /// [lo, hi] from rigorous bounds (lo clamped at 0; hi may be +inf for an undecided answer
  /// that established a lower bound only).
  static Enclosure from_bounds(const arf_t lo, const arf_t hi, long digits);
  /// The exact rational value v >= 0.
  static Enclosure exact(const core::Rational& v, long digits);
  /// Exactly 0 (the surfaces meet).
  static Enclosure zero();
  /// [0, hi]: what an answer that only found a genuine pair (an upper bound) established.
  static Enclosure up_to(const arf_t hi, long digits);

  /// This enclosure times 2^k (exact: a change of scale).
  Enclosure scaled_2exp(long k) const;
  /// The hull with another enclosure (the minimum of two candidate values lies in
  /// [min lower, min upper]: use min_of for that).
  static Enclosure min_of(const Enclosure& a, const Enclosure& b);

  /// Decimal bounds rounded outward ("0" for an exact 0; upper "inf" when unbounded).
  const std::string lower() const;
  const std::string upper() const;
  /// The midpoint as a double (an approximation, for display).
  double approx() const;
  /// The midpoint as "%.17g" text (the JSON "approx"), also beyond the double range, where
  /// approx() is inf or 0: then from MPFR ("1e+400", "1.0000000000000001e-1001").
  std::string approx_text() const;
  bool is_zero() const { return arf_is_zero(lo_.v) && arf_is_zero(hi_.v); }
  bool upper_finite() const { return arf_is_finite(hi_.v) != 0; }
  const arf_struct* lower_arf() const { return lo_.v; }
  const arf_struct* upper_arf() const { return hi_.v; }
  /// The ball [lower, upper] at precision prec.
  void to_ball(arb_t out, long prec) const;
  /// upper - lower <= 10^-digits * lower, on the printed decimals, exactly (0 meets it when
  /// upper is 0 too).
  bool meets_width(long digits) const;
  long digits() const { return digits_; }

private:
  Enclosure() = default;
  Arf lo_, hi_;
  long digits_ = 15;
};

/// A floating-point answer: never certified, never an enclosure.
struct Estimate {
  double value = 0;
};

} // namespace surfcert::certify
