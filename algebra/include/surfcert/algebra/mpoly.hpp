// surfcert::algebra::MPoly: a polynomial in x, y, z (variables 0, 1, 2) with integer
// coefficients, RAII over FLINT's fmpz_mpoly in one shared lexicographic context.
//
// What it is for: building the offset systems of the distance code over Z and eliminating
// with FLINT's multivariate resultants (measured faster here than a Sylvester determinant).
// Invariants: always a valid fmpz_mpoly of the shared context (x > y > z, lex); value
// semantics (copies are deep). Ball evaluation encloses the value over a box of balls.
#pragma once

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/upoly.hpp"
#include "surfcert/core/rational.hpp"

#include <flint/fmpz_mpoly.h>

#include <array>

namespace surfcert::algebra {

class MPoly {
public:
  MPoly();
  explicit MPoly(long c);
  explicit MPoly(const core::Integer& c);
  MPoly(const MPoly& o);
  MPoly(MPoly&& o) noexcept;
  MPoly& operator=(MPoly o) noexcept;
  ~MPoly();

  static MPoly var(int i); ///< x (0), y (1) or z (2)
  static const fmpz_mpoly_ctx_struct* ctx();

  const fmpz_mpoly_struct* raw() const { return v_; }
  fmpz_mpoly_struct* raw_mut() { return v_; }

  bool is_zero() const;
  bool is_constant() const;
  long total_degree() const; ///< -1 for the zero polynomial
  long degree(int var) const;
  long terms() const;
  MPoly derivative(int var) const;

  friend MPoly operator+(const MPoly& a, const MPoly& b);
  friend MPoly operator-(const MPoly& a, const MPoly& b);
  friend MPoly operator*(const MPoly& a, const MPoly& b);
  friend MPoly operator-(const MPoly& a);
  friend bool operator==(const MPoly& a, const MPoly& b);

private:
  fmpz_mpoly_t v_;
};

/// Vectors of polynomials (gradients, offset directions) and their products.
using MVec3 = std::array<MPoly, 3>;
MPoly dot(const MVec3& a, const MVec3& b);
MVec3 cross(const MVec3& a, const MVec3& b);

/// Resultant of a and b with respect to `var` (FLINT). Throws std::runtime_error when FLINT
/// reports failure (it returns 0 for that), never returns a wrong zero silently.
MPoly resultant(const MPoly& a, const MPoly& b, int var);

/// Greatest common divisor (FLINT; positive leading coefficient).
MPoly gcd(const MPoly& a, const MPoly& b);

/// Product of the distinct irreducible-up-to-multiplicity factors (FLINT's square-free
/// factorisation), primitive. Zero stays zero.
MPoly squarefree_part(const MPoly& a);

/// a as a univariate polynomial in `var`; precondition: no other variable occurs.
UPolyZ to_univariate(const MPoly& a, int var);

/// Ball enclosure of a(x, y, z) for every point of the box of balls b (term by term).
void evaluate(arb_t out, const MPoly& a, const std::array<const arb_struct*, 3>& b, long prec);

/// The quadric p^T M p (p = (x, y, z, 1)) of a symmetric rational 4x4 matrix, scaled by the
/// positive common denominator to integer coefficients (same zero set, same sign).
MPoly quadric_poly(const std::array<std::array<core::Rational, 4>, 4>& m);

} // namespace surfcert::algebra
