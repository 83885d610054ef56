// surfcert::algebra polynomial operations on core::Poly3 that belong above the core layer:
// elimination (resultants), gcd, square-free parts, the univariate view, ball enclosures over
// boxes of Arb balls, and the polynomial of a quadric matrix.
//
// What they are for: building the offset systems of the distance code and eliminating with
// FLINT's multivariate resultants (measured faster here than a Sylvester determinant). The
// integer algorithms run on the primitive integer part FLINT keeps inside every fmpq_mpoly
// (see poly3.hpp), so a rational polynomial costs no more than the integer one it is a
// multiple of.
// Contracts: every failure FLINT reports throws std::runtime_error (never a wrong zero); ball
// evaluation encloses the exact value of the rational polynomial.
#pragma once

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/upoly.hpp"
#include "surfcert/core/poly3.hpp"
#include "surfcert/core/rational.hpp"

#include <array>

namespace surfcert::algebra {

/// Resultant of a and b with respect to `var`, exact (including the contents' powers).
/// Throws std::runtime_error when FLINT reports failure (it returns 0 for that), and
/// core::BudgetExceeded when the thread's time budget runs out between two evaluation points of
/// a long (interpolated) resultant.
core::Poly3 resultant(const core::Poly3& a, const core::Poly3& b, int var);

/// Greatest common divisor of the integer parts: primitive, integer coefficients, positive
/// leading coefficient (FLINT).
core::Poly3 gcd(const core::Poly3& a, const core::Poly3& b);

/// Product of the distinct irreducible-up-to-multiplicity factors (FLINT's square-free
/// factorisation), primitive with integer coefficients. Zero and constants stay as they are.
core::Poly3 squarefree_part(const core::Poly3& a);

/// The primitive integer polynomial in `var` with positive leading coefficient that is a
/// rational multiple of a (same roots); precondition: no other variable occurs
/// (std::invalid_argument otherwise).
UPolyZ to_univariate(const core::Poly3& a, int var);

/// Ball enclosure of a(x, y, z) for every point of the box of balls b (term by term).
void evaluate(arb_t out, const core::Poly3& a, const std::array<const arb_struct*, 3>& b,
              long prec);

/// The quadric p^T M p (p = (x, y, z, 1)) of a symmetric rational 4x4 matrix, scaled by the
/// positive common denominator to integer coefficients (same zero set, same sign).
core::Poly3 quadric_poly(const std::array<std::array<core::Rational, 4>, 4>& m);

} // namespace surfcert::algebra
