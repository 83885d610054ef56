// surfcert::algebra::SolutionCover: finitely many boxes whose union contains every real
// solution of a square polynomial system F1 = F2 = F3 = 0 over Q[x, y, z] (core::Poly3).
//
// How: Sylvester resultants (FLINT) eliminate z from two pairs of equations, then y (or x)
// from the two bivariate resultants, giving for each coordinate a univariate eliminant that
// vanishes at that coordinate of every solution (resultants lie in the ideal, so this holds
// in every position, generic or not). The real roots of each square-free eliminant are
// isolated exactly; a box is a choice of one isolating interval per coordinate. A box is
// discarded only when a ball evaluation proves that some equation (or an (x, y) resultant)
// has no zero in it, so the kept boxes always cover all real solutions. Refinement narrows
// the kept boxes' intervals (refine_root: exact signs) and discards again.
// Invariants: each interval holds exactly one root of its factor of the eliminant (intervals
// of different factors may overlap); eliminants are nonzero when ok. ok == false (eliminant
// identically zero in every tried combination: the system has a curve of solutions, or the
// elimination met one) is reported with a note, never papered over.
// Time budget (core/budget.hpp): every resultant, factorisation, isolation and refinement is a
// step; past the thread's deadline cover_real_solutions / refine_cover throw
// core::BudgetExceeded (no partial cover is returned). A factorisation is not interruptible:
// it starts only when its modelled cost fits the remaining time (check_budget_for).
// What a box is NOT: a certificate that a solution exists in it, or that it holds only one.
#pragma once

#include "surfcert/algebra/poly_ops.hpp"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace surfcert::algebra {

/// An interval (lo, hi) holding exactly one root of the irreducible factor `factor` of an
/// eliminant, or lo == hi equal to that root.
struct RootInterval {
  core::Rational lo, hi;
  size_t factor = 0;
};

struct SolutionCover {
  bool ok = false;
  int dims = 3; ///< 2 for cover_real_solutions_2d (z unused)
  std::string note;
  std::array<core::Poly3, 3> system;
  std::vector<core::Poly3> xy_resultants; ///< nonzero resultants in (x, y), used to discard
  /// Distinct irreducible factors (FLINT) of the projections onto x, y, z: isolating roots
  /// factor by factor is much cheaper than on their product (degree 66 -> 36 + 24 + 6 for two
  /// generic ellipsoids: 20 ms instead of 170 ms).
  std::array<std::vector<UPolyZ>, 3> factors;
  std::array<long, 3> eliminant_degree{};  ///< degrees of the projections
  std::array<long, 3> squarefree_degree{}; ///< sums of the degrees of their distinct factors
  std::array<long, 2> bivariate_degree{};  ///< total degrees of the two resultants in (x, y)
  std::array<std::vector<RootInterval>, 3> roots;
  std::vector<std::array<size_t, 3>> boxes; ///< indices into roots[0], roots[1], roots[2]
};

/// The cover of the real solutions of F (see above), intervals refined to width <= width0.
SolutionCover cover_real_solutions(const std::array<core::Poly3, 3>& F,
                                   const core::Rational& width0);

/// The same for two equations F(x, y) = G(x, y) = 0 in the plane (z unused: its single
/// "interval" is [0, 0]).
SolutionCover cover_real_solutions_2d(const core::Poly3& F, const core::Poly3& G,
                                      const core::Rational& width0);

/// Narrows every kept box's intervals to width <= width and discards boxes proved empty.
void refine_cover(SolutionCover& c, const core::Rational& width);

/// The box as three balls (exact interval hulls), at precision prec.
void box_balls(const SolutionCover& c, const std::array<size_t, 3>& box, arb_t x, arb_t y, arb_t z,
               long prec);

/// Working precision (bits) suited to intervals of the given width.
long precision_for_width(const core::Rational& width);

} // namespace surfcert::algebra
