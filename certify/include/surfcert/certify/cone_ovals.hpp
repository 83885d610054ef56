// surfcert::certify::cone_oval_counts: which of the curve's ovals pass through infinity, when
// one quadric is a cone with an affine apex (e.g. two cones crossing in two ovals, Tu case 1,
// where the points at infinity alone allow "two unbounded ovals" and "one loop plus one oval
// with four points at infinity").
//
// What it computes (exact): the cone K with apex v (affine, not on the other quadric Q) is
// swept by its generators v + s d, d on K's conic at infinity, parametrised rationally as
// d(t), (t : 1) in P^1 (from a rational point of that conic, found by a bounded search). The
// curve is {(t, (s1 : s2)) : a s2^2 + 2 b(t) s1 s2 + c(t) s1^2 = 0}, a = Q(v), b = Q(v, d(t)),
// c = Q(d(t)) (a double cover of the conic where disc = b^2 - a c > 0). Each interval of P^1
// where disc > 0 between two roots of disc carries one oval; when disc > 0 everywhere the two
// roots s(t) = (-b +- sqrt(disc)) / c are two ovals, and the one through infinity at a root t0
// of c (s = infinity) is the '+' one iff b(t0) < 0. The roots of disc, c and b (pairwise
// coprime, else nothing is claimed) are ordered exactly (isolation of the square-free product,
// each root attributed by exact signs at the separators). Then loops = the ovals without a
// root of c, unbounded = the number of distinct real roots of c (the points at infinity).
// Preconditions (checked, nullopt otherwise): the curve is smooth and made of `ovals` ovals,
// with `points_at_infinity` distinct real points at infinity.
#pragma once

#include "surfcert/core/quadric.hpp"

#include <optional>
#include <utility>

namespace surfcert::certify {

/// (loops, unbounded branches), or nullopt when k is not a cone with an affine apex off q, no
/// rational point of its conic at infinity was found, or a check fails.
std::optional<std::pair<int, int>> cone_oval_counts(const core::Mat4& k, const core::Mat4& q,
                                                    int ovals, int points_at_infinity);

} // namespace surfcert::certify
