// surfcert::algebra real-root isolation for square-free integer polynomials.
//
// What it represents: RootSeparation = rational separators s_0 < s_1 < ... < s_k such that
// the square-free polynomial p has no root outside (s_0, s_k), exactly one root in each gap
// (s_{i-1}, s_i), and p(s_i) != 0 with alternating signs. That is the certificate: with k the
// exact number of real roots (Sturm count) and k+1 points of alternating nonzero sign, every
// gap holds an odd number of roots, hence exactly one. With no real root, separators = {0}.
//
// How: from degree 12, Arb's complex root finder at 64, 128, ... bits, at most 8192 and no
// further after a slow round (its balls, validated by Arb, each hold one root; the real ones
// are proven real by conjugate symmetry); below degree 12 or when those rounds give up, a
// float guess first (Aberth iteration on the complex roots; cuts between the real-looking
// guesses and at the real part of each non-real pair, converted exactly to short dyadic
// rationals; each gap's count proved by Descartes' rule, 0 or 1; two guesses closer than
// doubles resolve, a double root split by rounded input, decided exactly through the root of
// p' between them: two real roots and a separator, or none), checked with exact signs;
// if the check fails (three close roots, a separator landing on a root), CGAL's Descartes
// isolator (Algebraic_kernel_d_1, one translation unit) supplies the separators instead, or,
// for coefficients beyond kCgalMaxBits bits, isolate_real_roots_descartes (a loop: CGAL's
// recursion overflowed the stack there).
#pragma once

#include "surfcert/algebra/upoly.hpp"

#include <complex>
#include <optional>
#include <vector>

namespace surfcert::algebra {

struct RootSeparation {
  std::vector<Rational> separators;
  bool used_fallback = false; ///< true when the float guess failed and CGAL was used
  size_t num_roots() const { return separators.size() - 1; }
};

/// Exact number of distinct real roots of a square-free polynomial (Sturm, FLINT).
long count_real_roots(const UPolyZ& squarefree);

/// Whether p (any nonzero polynomial, square-free or not) has a real root: the Sturm counts of
/// its square-free factors (FLINT), exact. Far cheaper than a full factorisation.
bool has_real_root(const UPolyZ& p);

/// Separators for a square-free, nonzero polynomial (degree >= 0). Exact.
RootSeparation isolate_real_roots(const UPolyZ& squarefree);

/// Separators for known distinct rational roots (any order): the integer floor(min) - 1 below,
/// ceil(max) + 1 above, and in each gap the dyadic with the fewest bits that the gap's lower
/// half holds (short numbers for the exact evaluations at the separators, where midpoints of
/// the ~200-bit roots of a pencil posed in doubles would be as long as the roots). Exact; no
/// polynomial involved. An empty list gives {0}.
RootSeparation separate_rational_roots(std::vector<Rational> roots);

/// The same from CGAL only (the fallback, and a second isolator for tests). Exact.
RootSeparation isolate_real_roots_cgal(const UPolyZ& squarefree);

/// The same from Descartes' rule of signs in a loop (no recursion: any coefficient size), the
/// intervals split at the geometric mean of their ends while they span more than a factor 4.
/// The fallback in place of CGAL for coefficients beyond kCgalMaxBits, whose Descartes
/// recursion (one frame per halving) overflowed the stack near 66,000 bits. Checks the
/// thread's time budget (core/budget.hpp) once per interval. Exact.
/// Not Arb (measured in its place, bench/real_roots_bench and the tests' cases): with the
/// factors apart, arb_fmpz_poly_complex_roots plus Arb's Newton steps matched the loop on the
/// sphere pencils, but Arb's root finder (Durand-Kerner at a fixed iteration count per
/// precision, which it then doubles, with no budget check) ran 3.9 s on two roots of one
/// quadratic 10^-300 apart and past 60 s at 10^-1000 or on a quartic's roots scaled by
/// 10^1000, where the loop takes under a millisecond.
RootSeparation isolate_real_roots_descartes(const UPolyZ& squarefree);

/// Where the real roots of p (nonzero, any degree, square-free or not) lie, without isolating
/// them: `any` false proves that p has no real root; `any` true says every real root lies in
/// the open interval (lo, hi) (it does not prove that one exists: the float guess saw one).
struct RootRange {
  bool any = false;
  Rational lo, hi;
};

/// The float roots propose a range a little wider than theirs; Descartes' rule proves it:
/// p(lo), p(hi) nonzero and no sign variation on (hi, B) nor on (-B, lo), B a root bound
/// (or none on (-B, B) when no root looks real). Exact; nullopt when the proposal does not
/// prove out (the caller isolates instead). Far cheaper than isolation for high degrees: a
/// critical-point eliminant of degree 16 with coefficients of hundreds of bits took Arb's
/// complex isolation ~10 ms, where only its range was wanted (proven_loops.cpp).
std::optional<RootRange> real_root_range(const UPolyZ& p);

/// Bits of the largest coefficient of p (absolute value).
long max_coefficient_bits(const UPolyZ& p);

/// Coefficient size beyond which isolate_real_roots does not call CGAL (see above).
constexpr long kCgalMaxBits = 2048;

/// Float guesses of all complex roots (Aberth iteration; no guarantee). coeffs: constant first,
/// leading coefficient nonzero.
std::vector<std::complex<double>> approx_complex_roots(const std::vector<double>& coeffs);

/// The `count` guesses closest to the real axis, real parts sorted increasingly (no guarantee).
std::vector<double> approx_real_roots(const std::vector<double>& coeffs, size_t count);

/// Float guesses (no guarantee) of real roots of c3 x^3 + ... + c0, increasing; returns their
/// number (0 when c3 == 0). Closed form plus two Newton steps.
int approx_cubic_real_roots(double c3, double c2, double c1, double c0, double* out);

/// For a polynomial of degree 2..4 with k real roots (k known exactly elsewhere): k - 1 float
/// points, one between each pair of consecutive roots, chosen among the critical points
/// (Rolle). Empty when it cannot pick them. A guess: callers check it exactly.
std::vector<double> critical_point_separators(const std::vector<double>& coeffs, size_t k);

/// The same for the n + 1 coefficients c[0..n] (constant first): writes the points to out
/// (room for 3) and returns their number (0 when it cannot pick them). No allocation: the
/// interval filter calls it once per pair.
size_t critical_point_separators(const double* c, size_t n, size_t k, double* out);

/// Narrows (lo, hi), which holds exactly one root of p with p(lo)p(hi) < 0, by exact
/// bisection until hi - lo <= width (or the root is hit exactly, then lo == hi).
/// With a placement other than Bisect set (set_root_placement, a testing hook) the interval
/// is another valid one: inside (lo, hi), of width <= width, p(lo)p(hi) < 0 (exact signs).
void refine_root(const UPolyZ& p, Rational& lo, Rational& hi, const Rational& width);

/// Where refine_root puts its interval among the valid ones. A testing hook: a certified route
/// must not depend on which valid interval it is handed (the same certified answer for every
/// placement). Bisect (nested halvings) is the default; Newton is refine_root_newton's bracket
/// (the root near its centre, on a dyadic grid); Centred the root within width / 2^16 of a
/// grid-snapped centre (mirror-symmetric roots get mirror-symmetric intervals); RootNearLo /
/// RootNearHi the root within width / 2^16 of an end; Tiny width / 2^20 (far narrower than asked).
enum class RootPlacement { Bisect, Newton, Centred, RootNearLo, RootNearHi, Tiny };
/// Process-wide (every thread; tests set it around a call and restore Bisect).
void set_root_placement(RootPlacement placement);
RootPlacement root_placement();

/// The same contract, faster far from the width: a float Newton estimate (Arb midpoints, no
/// guarantee) proposes a bracket of the width around the root; its ends are kept only as far
/// as exact signs at them confirm (refine_root_near), and exact bisection finishes whatever the
/// proposal did not settle. Certified by exact signs alone. The interval differs from
/// refine_root's (not nested halvings of the input): used by box_exits, where it halved the
/// instructions. The distance routes keep refine_root's bisection: there root refinement is
/// 0.1-5% of an exact-mode distance (15-1000 digits), nothing to gain. (A cone two-minima case
/// once gave up with this bracket: the offset route depended on interval placement, since
/// fixed; root_placement_test runs the routes under both and other placements.)
void refine_root_newton(const UPolyZ& p, Rational& lo, Rational& hi, const Rational& width);

/// refine_root_newton with the proposal given: `guess` (any rational; a claim, not trusted) is the
/// centre of a proposed bracket of about width / 2. Each of its ends inside (lo, hi) is
/// checked by an exact sign and narrows (lo, hi) on the side that sign proves; exact bisection
/// then brings hi - lo to at most `width`. A wrong guess costs two sign evaluations, never
/// a wrong interval.
void refine_root_near(const UPolyZ& p, Rational& lo, Rational& hi, const Rational& width,
                      const Rational& guess);

/// The sign of p at the root of the irreducible f isolated in (lo, hi) (lo == hi: the rational
/// root itself): Arb on the interval, narrowed (refine_root_newton) until the enclosure of p
/// excludes 0. A proof when nonzero; 0 when four narrowings (to 2^-2048 of the interval) never
/// excluded 0, which is certain when p vanishes at the root (f divides p) and otherwise means
/// undecided.
int sign_at_root(const UPolyQ& p, const UPolyZ& f, Rational lo, Rational hi);

} // namespace surfcert::algebra
