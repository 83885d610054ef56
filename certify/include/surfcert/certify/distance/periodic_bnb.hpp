// surfcert::certify::periodic_minimize: certified branch and bound for the minimum of a
// function f(t) on the circle t in [0, 2) (closed loops: a core circle, the generators of a
// cone), shared by the torus pair and the cone routes.
//
// The caller's bound(t_mid, T) returns a certified lower bound of f over the ball T and an
// upper bound that is a value of f (or of anything >= min f); intervals whose lower bound
// exceeds the best upper bound are dropped, the rest bisected (exact dyadic endpoints: 32
// starting intervals shifted by 1/64 so symmetric positions stay interior, together covering
// [0, 2) exactly) until the enclosure [min lower - shift, best upper - shift] has relative
// width <= 10^-digits. Surviving intervals are grouped (adjacent ones, across t = 0 too), one
// representative each: the minimizers. Fails (false) when the enclosure is not positive, when
// too many intervals survive (a continuum of minimizers, or a flat minimum) or when the round
// budget runs out.
#pragma once

#include "surfcert/certify/distance/ball.hpp"

#include <functional>
#include <vector>

namespace surfcert::certify {

struct PeriodicMinimum {
  Ball enclosure;               ///< [min f - shift, ...] with the requested relative width
  std::vector<Ball> minimizers; ///< one exact t (zero radius) per group of survivors
  /// Per group, a ball holding all its survivors (a group across t = 0 is written around 0):
  /// every minimizing t lies in one of them, modulo 2.
  std::vector<Ball> group_hulls;
};

using PeriodicBound =
    std::function<void(const arb_t t_mid, const arb_t T, arf_t lower, arf_t upper)>;

/// The lower bound of f over the ball T: the better of the interval extension f(T) and the
/// mean-value form f(t_m) + f'(T) (T - t_m) (used when finite).
void mean_value_lower(arf_t lower, const arb_t f_T, const arb_t df_T, const arb_t f_tm,
                      const arb_t T, long prec);

bool periodic_minimize(const PeriodicBound& bound, const arb_t shift, long digits, long prec,
                       PeriodicMinimum& out);

} // namespace surfcert::certify
