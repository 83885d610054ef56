// surfcert::certify::cone_oval_counts: which of the curve's ovals pass through infinity, when
// a member of the pencil is a real cone or cylinder (e.g. two cones crossing in two ovals, Tu
// case 1, where the points at infinity alone allow "two unbounded ovals" and "one loop plus
// one oval with four points at infinity"; a hyperbolic or parabolic cylinder against any
// quadric, two ovals with two or four points at infinity).
//
// What it computes (exact): the cone K (rank 3) with apex v (its kernel, rational; affine or at
// infinity, not on the other quadric Q) is swept by its generators (s2 v + s1 d(t)), d on K's
// conic in a base plane Pi not through v (the plane at infinity for an affine apex, a
// coordinate plane x_j = 0 with v_j != 0 for a cylinder), parametrised rationally as d(t),
// (t : 1) in P^1, from a rational point of that conic found by a bounded search. The curve is
// {(t, (s1 : s2)) : a s2^2 + 2 b(t) s1 s2 + c(t) s1^2 = 0}, a = Q(v), b = Q(v, d(t)),
// c = Q(d(t)) (a double cover of the conic where disc = b^2 - a c > 0). Each interval of P^1
// where disc > 0 between two roots of disc carries one oval; when disc > 0 everywhere the two
// roots are two ovals. The points at infinity:
//  - affine apex: the curve's point s2 = 0 of the generator t0 lies at infinity iff c(t0) = 0;
//    with disc > 0 everywhere, the oval through it is the '+' root s(t) = (-b +- sqrt(disc))/c
//    iff b(t0) < 0;
//  - apex at infinity: a generator meets the plane at infinity at v only, unless it lies in it
//    (d_w(t0) = 0); both of its curve points then lie at infinity (two distinct real ones where
//    disc(t0) > 0), one on each sheet.
// The roots of disc and of the marker (c, with b, for an affine apex; d_w for a cylinder;
// pairwise coprime, else nothing is claimed) are ordered exactly (isolation of the square-free
// product, each root attributed by exact signs at the separators; signs of disc read on disc
// itself). Then loops = the ovals without a root of the marker, unbounded = the number of
// distinct real points at infinity.
// Preconditions (checked, nullopt otherwise): the curve is smooth and made of `ovals` ovals,
// with `points_at_infinity` distinct real points at infinity.
#pragma once

#include "surfcert/core/quadric.hpp"

#include <optional>
#include <utility>

namespace surfcert::certify {

/// (loops, unbounded branches), or nullopt when k is not a cone (rank 3) with its apex off q,
/// no rational point of its base conic was found, or a check fails.
std::optional<std::pair<int, int>> cone_oval_counts(const core::Mat4& k, const core::Mat4& q,
                                                    int ovals, int points_at_infinity);

} // namespace surfcert::certify
