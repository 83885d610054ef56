// surfcert::certify::no_compact_component_in_box: a proof that no bounded component of the
// intersection curve of two quadrics (a loop, or an isolated point) lies wholly inside a box.
//
// Why: a box given by the caller may cut a loop of the curve. The traced picture then shows
// fewer closed branches than the affine topology has loops, and the box's exact crossings
// (box_exits.hpp) account only for the pieces that reach a face; a small loop lying wholly
// inside, missed by the tracer, would go unseen. This proves that there is none.
//
// The argument (exact in its premises, rigorous in its arithmetic): let K be a compact
// component of C = {f = g = 0} and d a direction. The linear function d.x attains its minimum
// on K at some point p. If p is a smooth point of C, d is normal to C there (Lagrange:
// d in span(grad f, grad g)); if p is singular, grad f and grad g are dependent. Either way
//   f(p) = g(p) = 0  and  h_d(p) = det[d; grad f(p); grad g(p)] = 0.
// So if K lay in the closed box B, the system f = g = h_d = 0 would have a solution in B. The
// proof covers B by cells (a subdivision, at most `budget` cells per direction) and shows on
// each cell that one of f, g, h_d has a CGAL interval enclosure (directed rounding, the exact
// rational coefficients enclosed) that misses 0. Directions are tried in turn (the axes, the
// face and the body diagonals); one direction that succeeds is a proof. Where a loop or an
// isolated point does lie in B, or a critical point of every direction is in B (on a cut loop,
// or on an unbounded branch), nothing is proved: `proven` is false, never a guess.
#pragma once

#include "surfcert/core/shape.hpp"

#include <array>
#include <string>

namespace surfcert::certify {

struct InnerLoopProof {
  bool proven = false;                   ///< no compact component of the curve lies in the box
  std::array<int, 3> direction{0, 0, 0}; ///< the direction d whose critical points B misses
  long cells = 0;                        ///< cells examined, over every direction tried
  std::string reason;                    ///< why not proven
};

/// The proof above for Q_A ∩ Q_B and the closed box [lo, hi] (lo <= hi coordinate-wise, finite
/// doubles, read exactly). `budget` bounds the cells examined per direction.
InnerLoopProof no_compact_component_in_box(const core::Mat4& a, const core::Mat4& b,
                                           const std::array<double, 3>& lo,
                                           const std::array<double, 3>& hi, long budget = 20000);

} // namespace surfcert::certify
