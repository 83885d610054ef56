// surfcert::algebra inertia of real symmetric 4x4 matrices, exactly.
//
// Inertia (p, n) = numbers of positive / negative eigenvalues; rank = p + n. Two independent
// exact routes: Descartes' rule of signs on the characteristic polynomial (all its roots are
// real, so sign variations count positive roots exactly) and a congruence diagonalisation
// (LDL^T with symmetric pivoting, Sylvester's law of inertia). Also exact numbers in Q(sqrt d)
// for the inertia at quadratic-irrational double roots of a pencil.
#pragma once

#include "surfcert/algebra/upoly.hpp"
#include "surfcert/core/quadric.hpp"

#include <flint/fmpz_mat.h>

#include <algorithm>
#include <string>

namespace surfcert::algebra {

struct Inertia {
  int p = 0;
  int n = 0;
  int rank() const { return p + n; }
  bool semidefinite() const { return std::min(p, n) == 0; }
  std::string to_string() const { return "(" + std::to_string(p) + "," + std::to_string(n) + ")"; }
  friend bool operator==(const Inertia& a, const Inertia& b) { return a.p == b.p && a.n == b.n; }
};

/// Descartes on mu^4 + c3 mu^3 + c2 mu^2 + c1 mu + c0 given the signs s[k] = sign(c_k).
Inertia inertia_from_charpoly_signs(const int s[4]);

/// Exact, by Descartes on the characteristic polynomial (FLINT's Berkowitz charpoly).
Inertia inertia_descartes(const core::Mat4& m);

/// Exact, by symmetric congruence elimination over Q (independent second route).
Inertia inertia_ldlt(const core::Mat4& m);

/// Writes into the initialised 4x4 `out` the integer matrix L*m, L = lcm of m's denominators
/// (a positive multiple: same inertia, rank and kernel).
void scaled_integer_matrix(fmpz_mat_t out, const core::Mat4& m);

/// Exact rank over Q (FLINT).
int rank_exact(const core::Mat4& m);

/// A number a + b*sqrt(d) with a, b rational and d a positive non-square integer (or b = 0).
struct QuadraticNumber {
  Rational a, b;
  core::Integer d;
  /// Exact sign (research §1.5 step 6).
  int sign() const;
  double to_double_approx() const;
  /// The same number with square factors moved out of d (trial division by small primes and
  /// a perfect-square test of the rest; d stays correct if a large square factor survives).
  QuadraticNumber normalized() const;
  /// d = square^2 * rest, the split normalized() makes (rest free of the squares of the primes
  /// below 2000; 1 when d is a perfect square). Numbers of one field share it: coordinates of
  /// one point, computed once (square_split) and applied to each (normalized(split)).
  struct SquareSplit {
    core::Integer square, rest;
  };
  /// normalized() with d's split given (split must be square_split(d)).
  QuadraticNumber normalized(const SquareSplit& split) const;
  /// "a + b*sqrt(d)" in exact text.
  std::string to_string() const;
};

/// Field operations in Q(sqrt d), exact, on numbers written over the same d (the result
/// carries d): x + s y (s = +-1), x y, x / y (y != 0).
QuadraticNumber quadratic_add(const QuadraticNumber& x, const QuadraticNumber& y, int s = 1);
/// The split of d > 0 that normalized() uses (QuadraticNumber::SquareSplit).
QuadraticNumber::SquareSplit square_split(const core::Integer& d);
QuadraticNumber quadratic_mul(const QuadraticNumber& x, const QuadraticNumber& y);
QuadraticNumber quadratic_div(const QuadraticNumber& x, const QuadraticNumber& y);

} // namespace surfcert::algebra
