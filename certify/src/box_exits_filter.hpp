// Internal to certify/box_exits: the interval filter on one face. On a face x_k = c both quadrics
// restrict to conics in the face's coordinates (u, v) = (x_i, x_j); their common points in the
// face rectangle are the curve's crossings with that face.
//
// What it proves, in interval arithmetic with directed rounding (CGAL intervals, rounding
// upwards; every conic entry an enclosure of the exact one):
//   - no_common_point: the two conics have no common point in the closed rectangle (each cell
//     of a subdivision excluded because one form's enclosure misses 0);
//   - face_crossings: the complete list of their common points in the closed rectangle, each
//     inside the open rectangle, each a simple root of the 2x2 system: the curve crosses the
//     face transversally there, at a smooth point. Every cell of a subdivision is either
//     excluded as above or lies inside a box X where the Krawczyk test K(X) ⊂ int X proves
//     exactly one root (and every Jacobian in X nonsingular); each root's tight enclosure (a
//     second Krawczyk box around the converged Newton point, inside X) decides whether it lies
//     in the open rectangle, outside the closed one, or too near an edge to tell.
// Either returns "not proved" (false, nullopt) when its cell budget runs out, a Krawczyk test
// fails (a tangency, a singular point, two crossings closer than the cells, a common component)
// or an edge is too close: the exact route (box_exits.cpp) then decides, as without the filter.
// Like the exact route's own filter, a face it clears says nothing about a component of the
// curve lying in the face's plane wholly outside the rectangle (the exact route reports that
// as not certified).
#pragma once

#include "box_exits_line_conic.hpp"

#include "surfcert/certify/enclosure.hpp"

#include <optional>
#include <vector>

namespace surfcert::certify::detail {

/// A face conic c00 u^2 + 2 c01 u v + c11 v^2 + 2 c02 u + 2 c12 v + c22 in interval arithmetic
/// (entries enclosing the exact ones).
struct IConic {
  Interval c00, c01, c11, c02, c12, c22;
  /// The exact face form's entries enclosed (rounding upwards required).
  explicit IConic(const FaceForm& m);
  /// The face form of the matrix m on x_k = c (u along axis i, v along axis j), from
  /// enclosures of m's entries and of c (rounding upwards required).
  IConic(const IMat4& m, size_t i, size_t j, size_t k, const Interval& c);
  /// An enclosure of the form over the cell mu + du, mv + dv (centred form: the exact Taylor
  /// expansion at the midpoint, tight on small cells). Rounding upwards required.
  Interval over(double mu, double mv, const Interval& du, const Interval& dv) const;
};

/// True when the conics provably have no common point in [u_lo, u_hi] x [v_lo, v_hi] (closed),
/// within `budget` cells (sets the rounding mode itself).
bool no_common_point(const IConic& a, const IConic& b, const core::Rational& u_lo,
                     const core::Rational& u_hi, const core::Rational& v_lo,
                     const core::Rational& v_hi, int budget);

/// Every common point of the conics in the closed rectangle, proved as described above (sets
/// the rounding mode itself); each FacePoint the midpoint of its root's enclosure and that
/// enclosure's larger radius. Nullopt when not proved.
std::optional<std::vector<FacePoint>>
face_crossings(const IConic& a, const IConic& b, const core::Rational& u_lo,
               const core::Rational& u_hi, const core::Rational& v_lo, const core::Rational& v_hi);

/// The same for a face where one quadric restricts to a line (`line`: no quadratic part, its
/// entries c00 = c01 = c11 = 0 exactly) and the other to `conic`: the conic along the line is
/// a quadratic A t^2 + 2 B t + C with enclosed coefficients; proved when B^2 - A C < 0 (no
/// common point) or > 0 with A != 0 (two simple roots: transversal crossings at smooth points,
/// as line_conic_crossings' Complete), each root's face point enclosed within 2^-46 of the
/// face's scale and placed inside or outside the rectangle. Listed in line_conic_crossings'
/// order. Nullopt (the exact line_conic_crossings then) for anything else: a double or nearly
/// double root, the line nearly parallel to an asymptote (A near 0), a point near an edge, the
/// line's coefficients not proved nonzero.
std::optional<std::vector<FacePoint>> line_face_crossings(const IConic& line, const IConic& conic,
                                                          const core::Rational& u_lo,
                                                          const core::Rational& u_hi,
                                                          const core::Rational& v_lo,
                                                          const core::Rational& v_hi);

} // namespace surfcert::certify::detail
