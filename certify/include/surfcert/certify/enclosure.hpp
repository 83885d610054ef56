// surfcert::certify enclosures of a quadric's exact matrix in interval arithmetic.
//
// What it represents: for a QuadricMatrix q, a symmetric 4x4 matrix of CGAL intervals that
// contains every entry of q's exact matrix. For a quadric built from a shape posed in doubles
// (core/shape.hpp) it is computed straight from the doubles (1/r^2, the quaternion's rotation
// divided by |q|^2, T^T L T) without forming the exact rationals, which is what lets the
// filtered decision run at float speed on double input; for a quadric built from a matrix of
// doubles, its symmetric part in intervals (core/quadric.hpp); otherwise each exact entry is
// enclosed by its directed roundings. approx() gives the midpoints (float mode's input).
// Contract: enclose() must run with the FPU rounding upwards (inside a
// CGAL::Protect_FPU_rounding<true> scope); overflow or underflow only widens an entry (up to
// infinite bounds), so a caller that cannot decide from it falls back to matrix().
#pragma once

#include "surfcert/algebra/pencil_poly.hpp"
#include "surfcert/core/quadric.hpp"

#include <CGAL/Interval_nt.h>

namespace surfcert::certify {

using Interval = CGAL::Interval_nt<false>; ///< needs rounding towards +infinity
using IMat4 = algebra::Mat4T<Interval>;

/// Interval enclosure of the exact matrix (see above; rounding upwards required).
IMat4 enclose(const core::QuadricMatrix& q);

/// An interval enclosing an exact rational (rounding upwards required).
Interval enclose(const core::Rational& x);

/// Doubles near the exact matrix entries (midpoints of the enclosure; no rounding mode needed).
algebra::Mat4T<double> approx(const core::QuadricMatrix& q);

/// True when approx(q) equals the exact matrix entry for entry: a matrix posed in doubles (or
/// in any rationals that doubles represent); never for a shape (its exact matrix is not formed).
bool approx_is_exact(const core::QuadricMatrix& q);

} // namespace surfcert::certify
