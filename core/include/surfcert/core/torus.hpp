// surfcert::core::Torus: a ring torus, the points at distance r from the circle K of radius R
// centred at `centre` in the plane through it orthogonal to `axis`.
//
// Invariants (checked by make_torus): axis != 0; R > r > 0 (a ring torus: its quartic
// (|x-c|^2 + R^2 - r^2)^2 - 4 R^2 (|x-c|^2 - ((x-c).a)^2/|a|^2) = 0 has exactly the tube as its
// real zero set; spindle and horn tori, whose quartic has a second sheet, are refused). All
// values exact rationals; the axis need not be a unit vector (only its direction counts).
#pragma once

#include "surfcert/core/rational.hpp"

#include <array>

namespace surfcert::core {

struct Torus {
  std::array<Rational, 3> centre;
  std::array<Rational, 3> axis;
  Rational R; ///< radius of the centre circle
  Rational r; ///< radius of the tube
};

/// Throws std::invalid_argument when an invariant fails (the reader reports an InputError).
Torus make_torus(const std::array<Rational, 3>& centre, const std::array<Rational, 3>& axis,
                 const Rational& R, const Rational& r);

/// An exact orthogonal (not unit) frame {u, v} of the plane orthogonal to a != 0:
/// u = a x e_k with k the index of a's smallest |component| (so u != 0, never nearly
/// parallel to a), v = a x u. Every torus route builds its circle parametrisation on this
/// one frame, so their points agree.
std::array<std::array<Rational, 3>, 2> plane_frame(const std::array<Rational, 3>& a);

} // namespace surfcert::core
