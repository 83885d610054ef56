// surfcert::certify group uniqueness: the proof that a group of branch-and-bound survivors
// (a ball of the 1-parameter t holding every minimizing t near it) holds at most one
// minimizer, shared by the routes that minimise a distance over a circle of parameters (two
// tori, ellipsoid-torus, ellipsoid-cone).
//
// Adjacent survivors alone prove nothing: two minimizers closer than the survivors' width (a
// bump between them below 10^-digits) make one group. A group holds at most one minimizer
// when the function has at most one critical point on its hull: pieces where f' has a
// certified sign hold none, and a run of pieces where f'' > 0 (strictly convex; f'' and f'
// enclosed by Taylor arithmetic in Arb) at most one. For a maximum, the same with -f. Whether
// a group holds one at all is the caller's (note_unproven_ties: a single group, or the ties'
// symmetry argument).
#pragma once

#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/distance.hpp"

#include "surfcert/algebra/arb.hpp"

#include <functional>
#include <string>
#include <vector>

namespace surfcert::certify {

/// An arb_poly_t owned (Taylor series in the circle parameter).
struct Series {
  arb_poly_t p;
  Series() { arb_poly_init(p); }
  ~Series() { arb_poly_clear(p); }
  Series(const Series&) = delete;
  Series& operator=(const Series&) = delete;
};

/// Encloses f' in d1 and f'' in d2 over the ball T; either is left non-finite
/// (arb_indeterminate) when it cannot be enclosed (a square root or a division by a ball
/// containing 0, a sign not decided).
using Derivatives = std::function<void(arb_t d1, arb_t d2, const arb_t T)>;

/// For every hull: at most one critical point of f (so at most one minimizer, or for sign
/// -1 one maximizer) in it, proven by halving it into pieces, left to right, on each of which
/// sign f' is of one sign or sign f'' > 0; within a run of adjacent convex pieces sign f' is
/// strictly increasing (at most one zero, none when a piece with sign f' > 0 precedes the run
/// or one with sign f' < 0 follows it). f must be C^2 on the hull (every hull's extremum is a
/// critical point: the parameter runs over a circle). At the first hull that fails,
/// res.count_unproven is set and the note says why (`what` names the arc); true when every
/// hull passed.
bool prove_one_per_group(DistanceResult& res, const std::vector<Ball>& hulls,
                         const Derivatives& derivs, int sign, const std::string& what);

/// D(t) = dist(y(t), E)^2 for the ellipsoid E = c + M^(1/2) B (support function n.c +
/// sqrt(n^T M n), M positive semidefinite, y taken relative to c and y(t) outside E): by
/// duality D = max over s > 0 of G(t, s) = s y^T (M + s I)^-1 y - s, strictly concave in s.
/// y and M are Taylor series of length >= 3 in t at the ball T (their value at every t in T
/// and derivatives). Brackets the maximiser s*(t) for every t in T by certified signs of
/// G_s, then encloses D' = G_t and D'' = G_tt - G_ts^2 / G_ss over T x bracket (envelope:
/// G_s = 0 along s*) in d1 and d2; both are left non-finite when a sign is not decided, d2
/// alone when G_ss < 0 is not proven.
void ellipsoid_dist2_derivatives(arb_t d1, arb_t d2, const Series (&y)[3], const Series (&M)[3][3],
                                 long prec);

} // namespace surfcert::certify
