// surfcert::certify quadrics of revolution: their axis, and their meridian conic.
//
// A quadric is invariant under the rotations about the line {point + t direction} iff its
// quadratic block is mu I + nu a a^T (a = direction) and Q3 point + b is parallel to a. Its
// meridian conic, in the half-plane of (X = distance to the axis, Z = signed height along a),
// is mu X^2 + lambda Z^2 + 2 beta |a| Z + f(point) = 0 (lambda the eigenvalue along a, beta
// from Q3 point + b = beta a). Exact rational arithmetic throughout; |a| must be rational
// (else nullopt: the meridian would have irrational coefficients).
#pragma once

#include "surfcert/core/quadric.hpp"

#include <array>
#include <optional>

namespace surfcert::certify {

struct Axis {
  std::array<core::Rational, 3> point, direction;
};

/// The axis of a quadric of revolution that is not a sphere (a double eigenvalue of the
/// quadratic block, the other one simple), or nullopt.
std::optional<Axis> revolution_axis(const core::QuadricMatrix& q);

/// The meridian conic of q about `ax` as a quadric in (x = X, height_var = Z) — height_var 1
/// (y) or 2 (z), Z measured in units of length along the axis — or nullopt when q is not
/// invariant about that axis, q is a plane, or |a| is irrational and the conic has a linear
/// term in Z (its coefficient is a multiple of |a|).
std::optional<core::QuadricMatrix> meridian_conic(const core::QuadricMatrix& q, const Axis& ax,
                                                  int height_var);

} // namespace surfcert::certify
