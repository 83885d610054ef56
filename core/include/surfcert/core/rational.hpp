// surfcert::core::Integer and Rational: value types over FLINT's fmpz and fmpq.
//
// What they represent: an arbitrary-precision integer, and a rational number kept in
// canonical form (denominator > 0, gcd(num, den) = 1) by every operation, as FLINT does.
// Invariants: the wrapped C object is always initialised; moves are O(1) swaps and leave the
// source equal to zero. Conversions that lose information say so in their name
// (to_double_approx); exact_from_double reads a binary double exactly as a dyadic rational.
// Thread safety: distinct objects may be used from distinct threads (FLINT is built with TLS).
#pragma once

#include <flint/fmpq.h>
#include <flint/fmpz.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

namespace surfcert::core {

class Integer {
public:
  Integer() { fmpz_init(v_); }
  Integer(long x) { fmpz_init_set_si(v_, x); } // NOLINT: implicit from machine integers
  Integer(const Integer& o) { fmpz_init_set(v_, o.v_); }
  Integer(Integer&& o) noexcept {
    fmpz_init(v_);
    fmpz_swap(v_, o.v_);
  }
  Integer& operator=(Integer o) noexcept {
    fmpz_swap(v_, o.v_);
    return *this;
  }
  ~Integer() { fmpz_clear(v_); }

  /// Parses an optionally signed decimal integer; nullopt when the text is not one.
  static std::optional<Integer> from_string(const std::string& s);

  const fmpz* raw() const { return v_; }
  fmpz* raw_mut() { return v_; }

  int sign() const { return fmpz_sgn(v_); }
  bool is_zero() const { return fmpz_is_zero(v_); }
  std::string to_string() const;
  double to_double_approx() const { return fmpz_get_d(v_); }
  long bits() const { return static_cast<long>(fmpz_bits(v_)); }

  friend Integer operator+(const Integer& a, const Integer& b) {
    Integer r;
    fmpz_add(r.v_, a.v_, b.v_);
    return r;
  }
  friend Integer operator-(const Integer& a, const Integer& b) {
    Integer r;
    fmpz_sub(r.v_, a.v_, b.v_);
    return r;
  }
  friend Integer operator*(const Integer& a, const Integer& b) {
    Integer r;
    fmpz_mul(r.v_, a.v_, b.v_);
    return r;
  }
  Integer operator-() const {
    Integer r;
    fmpz_neg(r.v_, v_);
    return r;
  }
  friend bool operator==(const Integer& a, const Integer& b) { return fmpz_equal(a.v_, b.v_); }
  friend bool operator!=(const Integer& a, const Integer& b) { return !(a == b); }
  friend bool operator<(const Integer& a, const Integer& b) { return fmpz_cmp(a.v_, b.v_) < 0; }

private:
  fmpz_t v_;
};

class Rational {
public:
  Rational() { fmpq_init(v_); }
  Rational(long x) { // NOLINT: implicit from machine integers
    fmpq_init(v_);
    fmpq_set_si(v_, x, 1);
  }
  Rational(long num, unsigned long den) {
    fmpq_init(v_);
    fmpq_set_si(v_, num, den);
  }
  explicit Rational(const Integer& x) {
    fmpq_init(v_);
    fmpq_set_fmpz_frac(v_, x.raw(), Integer(1).raw());
  }
  Rational(const Integer& num, const Integer& den); // den != 0 (checked)
  Rational(const Rational& o) {
    fmpq_init(v_);
    fmpq_set(v_, o.v_);
  }
  Rational(Rational&& o) noexcept {
    fmpq_init(v_);
    fmpq_swap(v_, o.v_);
  }
  Rational& operator=(Rational o) noexcept {
    fmpq_swap(v_, o.v_);
    return *this;
  }
  ~Rational() { fmpq_clear(v_); }

  /// Exact value of a finite binary double (a dyadic rational). Precondition: std::isfinite(d).
  static Rational exact_from_double(double d);
  /// Reads "12", "-3/4", "0.1" (= 1/10 exactly), "1.5e-3", "2E+10" exactly.
  /// nullopt when the text is not such a number or has a zero denominator.
  static std::optional<Rational> from_string(const std::string& s);

  const fmpq* raw() const { return v_; }
  fmpq* raw_mut() { return v_; }

  Integer num() const;
  Integer den() const;
  int sign() const { return fmpq_sgn(v_); }
  bool is_zero() const { return fmpq_is_zero(v_); }
  bool is_integer() const { return fmpz_is_one(fmpq_denref(v_)); }
  /// Canonical exact text: "n" or "n/d".
  std::string to_string() const;
  /// Nearest-ish double (FLINT rounding; not certified). Inexact: the name says so.
  double to_double_approx() const;
  /// Decimal text with `digits` significant digits, correctly rounded (MPFR). Inexact.
  std::string to_decimal_approx(int digits = 17) const;

  friend Rational operator+(const Rational& a, const Rational& b) {
    Rational r;
    fmpq_add(r.v_, a.v_, b.v_);
    return r;
  }
  friend Rational operator-(const Rational& a, const Rational& b) {
    Rational r;
    fmpq_sub(r.v_, a.v_, b.v_);
    return r;
  }
  friend Rational operator*(const Rational& a, const Rational& b) {
    Rational r;
    fmpq_mul(r.v_, a.v_, b.v_);
    return r;
  }
  /// Division; precondition b != 0 (checked: throws std::domain_error).
  friend Rational operator/(const Rational& a, const Rational& b);
  Rational operator-() const {
    Rational r;
    fmpq_neg(r.v_, v_);
    return r;
  }
  Rational& operator+=(const Rational& b) {
    fmpq_add(v_, v_, b.v_);
    return *this;
  }
  Rational& operator-=(const Rational& b) {
    fmpq_sub(v_, v_, b.v_);
    return *this;
  }
  Rational& operator*=(const Rational& b) {
    fmpq_mul(v_, v_, b.v_);
    return *this;
  }
  friend bool operator==(const Rational& a, const Rational& b) { return fmpq_equal(a.v_, b.v_); }
  friend bool operator!=(const Rational& a, const Rational& b) { return !(a == b); }
  friend bool operator<(const Rational& a, const Rational& b) { return fmpq_cmp(a.v_, b.v_) < 0; }
  friend bool operator>(const Rational& a, const Rational& b) { return b < a; }
  friend bool operator<=(const Rational& a, const Rational& b) { return !(b < a); }
  friend bool operator>=(const Rational& a, const Rational& b) { return !(a < b); }

private:
  fmpq_t v_;
};

/// 2^e as a rational (e may be negative).
Rational pow2(long e);
Rational abs(const Rational& x);
/// Writes x[k] = nums[k] / den (k < n) with den > 0 the least common denominator of the x[k]:
/// sums of products of rationals then run on integers, canonicalised once per result (exact
/// linear algebra on the ~150-digit rationals of surfaces posed in doubles spent most of its
/// time in the gcd that reduces every rational product and sum).
void over_common_denominator(const Rational* const* x, size_t n, Integer* nums, Integer& den);

/// L * m with L > 0 the least common denominator of the square matrix m's entries: integer
/// entries, the same zero set, signs, inertia and kernel. For exact work that needs a form
/// only up to a positive factor: products and sums of integers skip the gcd that reduces every
/// rational one (the ~150-digit denominators of a surface posed in doubles made it most of the
/// cost of box crossings and plane sections).
template <size_t N>
std::array<std::array<Rational, N>, N>
integer_multiple(const std::array<std::array<Rational, N>, N>& m) {
  std::array<const Rational*, N * N> x;
  for (size_t i = 0; i < N; ++i)
    for (size_t j = 0; j < N; ++j)
      x[N * i + j] = &m[i][j];
  std::array<Integer, N * N> nums;
  Integer den;
  over_common_denominator(x.data(), x.size(), nums.data(), den);
  std::array<std::array<Rational, N>, N> r;
  for (size_t i = 0; i < N; ++i)
    for (size_t j = 0; j < N; ++j)
      r[i][j] = Rational(nums[N * i + j]);
  return r;
}

inline std::ostream& operator<<(std::ostream& os, const Integer& x) {
  return os << x.to_string();
}
inline std::ostream& operator<<(std::ostream& os, const Rational& x) {
  return os << x.to_string();
}

} // namespace surfcert::core
