// surfcert::core::Poly3: a polynomial in x, y, z with rational coefficients -- the one exact
// multivariate polynomial type of the project.
//
// What it is: RAII over FLINT's fmpq_mpoly in one shared three-variable context (x, y, z are
// variables 0, 1, 2; lexicographic order x > y > z, the order the resultant-based elimination
// of the distance code was measured with). Equation strings are read into it; quadrics, tori,
// implicit surfaces and the offset systems are built from it; algebra/poly_ops.hpp eliminates
// with it (resultants, gcd, square-free parts, ball evaluation).
// Contract: always a valid, canonical fmpq_mpoly of ctx(): FLINT stores content * zpoly with
// zpoly primitive with positive leading coefficient (both zero for the zero polynomial), so
// equality is exact and the integer-level algorithms may work on zpoly directly. Value
// semantics: copies are deep, moves are noexcept and leave the source zero. raw_mut() is for
// FLINT calls that keep that canonical form (every fmpq_mpoly_* function does).
// terms() builds an ordered map (exponents ascending, as the former map-based Poly3 stored
// them); for_each_term() visits the same terms without the map.
#pragma once

#include "surfcert/core/rational.hpp"

#include <flint/fmpq_mpoly.h>

#include <array>
#include <map>
#include <string>

namespace surfcert::core {

class Poly3 {
public:
  using Exponent = std::array<int, 3>;
  using Terms = std::map<Exponent, Rational>;

  Poly3();
  explicit Poly3(long c);
  explicit Poly3(const Integer& c);
  explicit Poly3(const Rational& c);
  /// The sum of the given terms (zero coefficients allowed and dropped).
  explicit Poly3(const Terms& t);
  Poly3(const Poly3& o);
  Poly3(Poly3&& o) noexcept;
  Poly3& operator=(const Poly3& o);
  Poly3& operator=(Poly3&& o) noexcept;
  ~Poly3();

  /// The variable x (var = 0), y (1) or z (2).
  static Poly3 variable(int var);
  /// The shared context every Poly3 lives in (read-only after initialisation: thread-safe).
  static const fmpq_mpoly_ctx_struct* ctx();
  const fmpq_mpoly_struct* raw() const { return v_; }
  fmpq_mpoly_struct* raw_mut() { return v_; }

  bool is_zero() const;
  bool is_constant() const; ///< true for the zero polynomial too
  /// -1 for the zero polynomial.
  int total_degree() const;
  /// Degree in one variable; -1 for the zero polynomial.
  int degree(int var) const;
  /// Number of nonzero terms.
  long length() const;
  /// Term i (0 <= i < length(), in FLINT's order: lex, largest exponent first).
  void term(long i, Exponent& e, Rational& c) const;
  /// f(e, c) for every nonzero term c x^e0 y^e1 z^e2, in FLINT's order.
  template <class F> void for_each_term(F&& f) const {
    Exponent e;
    Rational c;
    for (long i = 0, n = length(); i < n; ++i) {
      term(i, e, c);
      f(static_cast<const Exponent&>(e), static_cast<const Rational&>(c));
    }
  }
  /// The terms as a map from exponents to nonzero coefficients (built on each call).
  Terms terms() const;
  /// Coefficient of x^i y^j z^k (zero when absent).
  Rational coeff(int i, int j, int k) const;
  /// Adds c x^e (linear in length(): build long polynomials from a Terms map instead).
  void add_term(const Exponent& e, const Rational& c);
  Poly3 derivative(int var) const;

  friend Poly3 operator+(const Poly3& a, const Poly3& b);
  friend Poly3 operator-(const Poly3& a, const Poly3& b);
  friend Poly3 operator*(const Poly3& a, const Poly3& b);
  Poly3 operator-() const;
  Poly3 scaled(const Rational& c) const;
  /// a^n, n >= 0.
  Poly3 pow(unsigned n) const;
  friend bool operator==(const Poly3& a, const Poly3& b);
  friend bool operator!=(const Poly3& a, const Poly3& b) { return !(a == b); }

  Rational evaluate(const Rational& x, const Rational& y, const Rational& z) const;
  /// p(X(x), Y(x), Z(x)): the polynomial with x, y, z replaced by the three given ones (a
  /// change of coordinates when they are affine), exact.
  Poly3 substitute(const std::array<Poly3, 3>& xyz) const;
  /// Readable text such as "x^2 + 1/4*y^2 - 1" (exact coefficients; highest total degree
  /// first, then x before y before z).
  std::string to_string() const;

private:
  fmpq_mpoly_t v_;
};

/// Vectors of polynomials (gradients, offset directions) and their products.
Poly3 dot(const std::array<Poly3, 3>& a, const std::array<Poly3, 3>& b);
std::array<Poly3, 3> cross(const std::array<Poly3, 3>& a, const std::array<Poly3, 3>& b);

} // namespace surfcert::core
