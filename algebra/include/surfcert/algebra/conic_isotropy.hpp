// surfcert::algebra::conic_has_rational_point: whether a regular conic x^T M x = 0 over Q
// (M the top-left 3x3 block of a rational symmetric matrix) has a rational point, exactly.
//
// The form is diagonalised over Q by completing squares (M00 q = y0^2 + T, S11 T = z1^2 +
// D z2^2, so q is isotropic iff <1, S11, D> is), and x^2 + S11 y^2 + D z^2 = 0 has a nonzero
// rational solution iff the Hilbert symbol (-S11, -D)_v is 1 at every place v (Hasse-Minkowski;
// Serre, A Course in Arithmetic, III.1-2): at infinity, at 2 and at each odd prime dividing
// S11 or D. A zero diagonal entry or a zero Schur pivot gives a rational point at once.
// Contract: true / false are proofs; nullopt when the conic is degenerate or the integers to
// factor exceed `max_bits` (factoring is the cost: word-size integers factor in microseconds,
// while the 70-110-bit ones of the bench's rotated cones took 20-50 us and up to 2 ms, more
// than the bounded search they would spare; the caller then searches as before).
#pragma once

#include "surfcert/core/shape.hpp"

#include <optional>

namespace surfcert::algebra {

std::optional<bool> conic_has_rational_point(const core::Mat4& m, long max_bits = 62);

} // namespace surfcert::algebra
