// surfcert::core::Poly3: a polynomial in x, y, z with rational coefficients.
//
// Sparse: a map from exponent triples (i, j, k), meaning x^i y^j z^k, to nonzero rational
// coefficients. Invariant: no stored coefficient is zero (the zero polynomial is the empty
// map), so equality of maps is equality of polynomials and total_degree() is exact.
// This is the form in which equation strings are read; quadrics are built from it.
#pragma once

#include "surfcert/core/rational.hpp"

#include <array>
#include <map>
#include <string>

namespace surfcert::core {

class Poly3 {
public:
  using Exponent = std::array<int, 3>;
  using Terms = std::map<Exponent, Rational>;

  Poly3() = default;
  explicit Poly3(const Rational& c);
  /// The variable x (var = 0), y (1) or z (2).
  static Poly3 variable(int var);

  const Terms& terms() const { return terms_; }
  bool is_zero() const { return terms_.empty(); }
  /// -1 for the zero polynomial.
  int total_degree() const;
  /// Coefficient of x^i y^j z^k (zero when absent).
  Rational coeff(int i, int j, int k) const;
  void add_term(const Exponent& e, const Rational& c);

  friend Poly3 operator+(const Poly3& a, const Poly3& b);
  friend Poly3 operator-(const Poly3& a, const Poly3& b);
  friend Poly3 operator*(const Poly3& a, const Poly3& b);
  Poly3 operator-() const;
  Poly3 scaled(const Rational& c) const;
  /// a^n, n >= 0.
  Poly3 pow(unsigned n) const;
  friend bool operator==(const Poly3& a, const Poly3& b) { return a.terms_ == b.terms_; }

  Rational evaluate(const Rational& x, const Rational& y, const Rational& z) const;
  /// p(X(x), Y(x), Z(x)): the polynomial with x, y, z replaced by the three given ones (a
  /// change of coordinates when they are affine), exact.
  Poly3 substitute(const std::array<Poly3, 3>& xyz) const;
  /// Readable text such as "x^2 + 1/4*y^2 - 1" (exact coefficients).
  std::string to_string() const;

private:
  Terms terms_;
};

} // namespace surfcert::core
