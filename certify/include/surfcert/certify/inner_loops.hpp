// surfcert::certify::inner_component_bound: a proven upper bound on the number of bounded
// components of the intersection curve of two quadrics (loops, isolated points) that lie
// wholly inside a box.
//
// Why: a box given by the caller may cut loops of the curve. The traced picture then shows
// fewer closed branches than the affine topology has loops, and the box's exact crossings
// (box_exits.hpp) account only for the pieces that reach a face; a loop lying wholly inside,
// missed by the tracer, would go unseen. A bound equal to the number of closed branches traced
// inside rules that out.
//
// The argument (exact in its premises, rigorous in its arithmetic). C = {f = g = 0}, d a
// direction, h_d = det[d; grad f; grad g] = d . tau with tau = grad f x grad g the tangent
// (zero exactly at the singular points). Along a smooth arc of C, d.x is critical exactly where
// h_d = 0. The system S_d: f = g = h_d = 0 is solved in the closed box B by a cover of cells,
// each either cleared (one of f, g, h_d has a CGAL interval enclosure, directed rounding, that
// misses 0) or holding exactly one solution, where the interval Newton (Krawczyk) operator maps
// the cell into its interior (so the Jacobian is nonsingular there: a smooth point, where h_d
// changes sign along C). This gives K_d, the exact number of solutions in B, all of that kind
// (a singular point of C in B, or a positive-dimensional solution set, blocks the cover).
//  - A compact component wholly in B has its d-minimum and d-maximum in B: two solutions, at
//    least, of its own.
//  - With the crossings certified (transversal, complete: the curve in B is closed loops plus
//    arcs between crossings), each crossing e gets sigma_e, the sign of d . tau oriented into
//    the box (decided on an interval enclosure of the crossing). An arc whose two ends have the
//    same sigma turns back in d: it holds an odd number, so at least one, of the solutions.
//    Whatever the pairing of the crossings into arcs, at least |n+ - n-| / 2 arcs do that
//    (n+, n- the crossings with sigma = +, -).
// So the number of compact components wholly in B is at most (K_d - |n+ - n-| / 2) / 2
// (K_d = 0 needs no crossing). Directions are tried in turn (the axes, the face and the body
// diagonals, then the 36 other primitive integer directions with entries in -2..2, up to sign:
// the cells that hold critical points of unbounded arcs differ with the direction) until one
// gives a bound <= `wanted`; the least bound found is returned. Nothing is
// a guess: where no direction's cover completes (within `budget` cells each), no bound.
#pragma once

#include "surfcert/certify/box_exits.hpp"
#include "surfcert/core/shape.hpp"

#include <array>
#include <optional>
#include <string>

namespace surfcert::certify {

struct InnerComponentBound {
  std::optional<int> bound;              ///< proven: at most this many compact components in B
  std::array<int, 3> direction{0, 0, 0}; ///< the direction d giving it
  int critical_points = 0;               ///< K_d for that direction
  long cells = 0;                        ///< cells examined, over every direction tried
  std::string reason;                    ///< why no bound
};

/// The bound above for Q_A ∩ Q_B and the closed box [lo, hi] (lo <= hi coordinate-wise, finite
/// doubles, read exactly). `exits`, when given and certified, must be box_exits of that pair
/// and box; without it only directions with no solution in B (bound 0) count. `budget` bounds
/// the cells examined per direction.
InnerComponentBound inner_component_bound(const core::Mat4& a, const core::Mat4& b,
                                          const std::array<double, 3>& lo,
                                          const std::array<double, 3>& hi, const BoxExits* exits,
                                          int wanted, long budget = 20000);

} // namespace surfcert::certify
