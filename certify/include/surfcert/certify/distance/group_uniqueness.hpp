// surfcert::certify group uniqueness: the proof that a group of branch-and-bound survivors
// (a ball of the 1-parameter t holding every minimizing t near it) holds at most one
// minimizer, shared by the routes that minimise a distance over a circle of parameters (two
// tori, ellipsoid-torus, ellipsoid-cone).
//
// Adjacent survivors alone prove nothing: two minimizers closer than the survivors' width (a
// bump between them below 10^-digits) make one group. A group holds at most one minimizer
// when the function is strictly convex on its hull (f'' > 0 enclosed over the whole ball by
// Taylor arithmetic in Arb), or, for a maximum, strictly concave. Whether it holds one at all
// is the caller's (note_unproven_ties: a single group, or the ties' symmetry argument).
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

/// Encloses f'' over the ball T in d2; false when it cannot (not finite, a square root or a
/// division by a ball containing 0).
using SecondDerivative = std::function<bool(arb_t d2, const arb_t T)>;

/// For every hull: f'' enclosed and of the sign `sign` (+1 convex, -1 concave). At the first
/// hull that fails, res.count_unproven is set and the note says why (`what` names the arc);
/// true when every hull passed.
bool prove_one_per_group(DistanceResult& res, const std::vector<Ball>& hulls,
                         const SecondDerivative& second, int sign, const std::string& what);

/// D(t) = dist(y(t), E)^2 for the ellipsoid E = c + M^(1/2) B (support function n.c +
/// sqrt(n^T M n), M positive semidefinite, y taken relative to c and y(t) outside E): by
/// duality D = max over s > 0 of G(t, s) = s y^T (M + s I)^-1 y - s, strictly concave in s.
/// y and M are Taylor series of length >= 3 in t at the ball T (their value at every t in T
/// and derivatives). Brackets the maximiser s*(t) for every t in T by certified signs of
/// G_s, then encloses D'' = G_tt - G_ts^2 / G_ss over T x bracket (envelope: G_s = 0 along
/// s*). False when a sign is not decided.
bool ellipsoid_dist2_second(arb_t d2, const Series (&y)[3], const Series (&M)[3][3], long prec);

} // namespace surfcert::certify
