// surfcert::algebra::UPolyZ / UPolyQ: univariate polynomials over Z and Q (FLINT fmpz_poly /
// fmpq_poly), RAII value types.
//
// Invariant: the wrapped FLINT object is always initialised and normalised (FLINT keeps the
// leading coefficient nonzero). Coefficients are indexed from the constant term. These are the
// only types through which the algebra layer passes univariate polynomials around.
#pragma once

#include "surfcert/core/rational.hpp"

#include <flint/fmpq_poly.h>
#include <flint/fmpz_poly.h>

#include <string>
#include <vector>

namespace surfcert::algebra {

using core::Integer;
using core::Rational;

class UPolyZ {
public:
  UPolyZ() { fmpz_poly_init(v_); }
  UPolyZ(const UPolyZ& o) {
    fmpz_poly_init(v_);
    fmpz_poly_set(v_, o.v_);
  }
  UPolyZ(UPolyZ&& o) noexcept {
    fmpz_poly_init(v_);
    fmpz_poly_swap(v_, o.v_);
  }
  UPolyZ& operator=(UPolyZ o) noexcept {
    fmpz_poly_swap(v_, o.v_);
    return *this;
  }
  ~UPolyZ() { fmpz_poly_clear(v_); }
  /// From coefficients, constant term first.
  static UPolyZ from_coeffs(const std::vector<Integer>& c);

  const fmpz_poly_struct* raw() const { return v_; }
  fmpz_poly_struct* raw_mut() { return v_; }
  long degree() const { return fmpz_poly_degree(v_); } ///< -1 for zero
  bool is_zero() const { return fmpz_poly_is_zero(v_); }
  Integer coeff(long i) const;
  /// Exact sign of p(x) at a rational x.
  int sign_at(const Rational& x) const;
  /// Primitive part with positive leading coefficient (same roots).
  UPolyZ primitive_part() const;
  UPolyZ derivative() const;
  std::string to_string(const char* var = "t") const;
  friend bool operator==(const UPolyZ& a, const UPolyZ& b) { return fmpz_poly_equal(a.v_, b.v_); }

private:
  fmpz_poly_t v_;
};

class UPolyQ {
public:
  UPolyQ() { fmpq_poly_init(v_); }
  UPolyQ(long c) { // NOLINT: implicit constant, so generic closed forms can use T(3)
    fmpq_poly_init(v_);
    fmpq_poly_set_si(v_, c);
  }
  explicit UPolyQ(const Rational& c) {
    fmpq_poly_init(v_);
    fmpq_poly_set_fmpq(v_, c.raw());
  }
  /// a*l + b
  static UPolyQ linear(const Rational& a, const Rational& b);
  UPolyQ(const UPolyQ& o) {
    fmpq_poly_init(v_);
    fmpq_poly_set(v_, o.v_);
  }
  UPolyQ(UPolyQ&& o) noexcept {
    fmpq_poly_init(v_);
    fmpq_poly_swap(v_, o.v_);
  }
  UPolyQ& operator=(UPolyQ o) noexcept {
    fmpq_poly_swap(v_, o.v_);
    return *this;
  }
  ~UPolyQ() { fmpq_poly_clear(v_); }
  static UPolyQ from_coeffs(const std::vector<Rational>& c);

  const fmpq_poly_struct* raw() const { return v_; }
  fmpq_poly_struct* raw_mut() { return v_; }
  long degree() const { return fmpq_poly_degree(v_); }
  bool is_zero() const { return fmpq_poly_is_zero(v_); }
  Rational coeff(long i) const;
  Rational evaluate(const Rational& x) const;
  /// Integer polynomial with the same roots: denominators cleared, content removed,
  /// positive leading coefficient.
  UPolyZ primitive_integer() const;
  /// Readable text, e.g. "-1/4*l^4 + 189/16*l^3 - 729/4".
  std::string to_string(const char* var = "l") const;
  /// Remainder of the division by g (g nonzero).
  UPolyQ rem(const UPolyQ& g) const;

  friend UPolyQ operator+(const UPolyQ& a, const UPolyQ& b) {
    UPolyQ r;
    fmpq_poly_add(r.v_, a.v_, b.v_);
    return r;
  }
  friend UPolyQ operator-(const UPolyQ& a, const UPolyQ& b) {
    UPolyQ r;
    fmpq_poly_sub(r.v_, a.v_, b.v_);
    return r;
  }
  friend UPolyQ operator*(const UPolyQ& a, const UPolyQ& b) {
    UPolyQ r;
    fmpq_poly_mul(r.v_, a.v_, b.v_);
    return r;
  }
  friend bool operator==(const UPolyQ& a, const UPolyQ& b) { return fmpq_poly_equal(a.v_, b.v_); }

private:
  fmpq_poly_t v_;
};

/// The distinct rational roots of p (nonzero), in increasing order: the linear factors of its
/// FLINT factorisation over Z.
std::vector<Rational> rational_roots(const UPolyQ& p);

/// One irreducible factor over Z and its multiplicity.
struct IrreducibleFactor {
  UPolyZ poly; ///< primitive, irreducible over Q, degree >= 1
  int exponent = 1;
};
/// The factorisation of p (nonzero) over Z by FLINT (fmpz_poly_factor): its irreducible factors
/// with their exponents, in FLINT's order; the content (a constant) is left out. A p of degree
/// >= 2 with coefficients beyond 64 bits that factorisations modulo a few word-size primes prove
/// irreducible comes back as its primitive part (positive leading coefficient), exponent 1,
/// without FLINT's factorisation: the same answer.
std::vector<IrreducibleFactor> irreducible_factors(const UPolyZ& p);

} // namespace surfcert::algebra
