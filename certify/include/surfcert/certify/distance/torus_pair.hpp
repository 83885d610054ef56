// surfcert::certify::torus_pair_distance: the certified distance between two ring tori whose
// solid tubes are disjoint, through their core circles.
//
// A solid tube is K + B(r) (core circle K, closed ball of radius r), so for disjoint tubes
//   dist(T1, T2) = dist(K1, K2) - r1 - r2,
// and dist(K1, K2) = min over the parameter t of f(t) = dist(K1(t), K2), where the distance from
// a point p to a circle is exact: sqrt((rho - R2)^2 + h^2) (h: height over K2's plane, rho:
// distance to K2's axis). f is minimised by branch and bound on t in [0, 2] (K1(t) =
// o1 + R1 (cos(pi t) u + sin(pi t) v), an orthonormal frame of Arb balls containing an exact
// frame): per interval a certified lower bound (the better of the interval extension and the
// mean-value form f(t_m) + f'(T) (T - t_m), derivatives by forward differentiation in Arb),
// f(t_m) as an upper bound (a value of f, hence >= the minimum), intervals above the best
// upper bound dropped, the rest bisected until the relative width of the distance is
// <= 10^-digits. The tubes are proven disjoint when min f > r1 + r2 is certain.
// Coaxial tori (one axis line): the distance of the two meridian circles in the half-plane, a
// closed form (apart, one tube inside the other, or meeting along circles), minimizers
// "infinite" (circles of pairs). Nested tubes (one torus inside the other's tube): d = min_t (r_out
// - r_in - dist(K_in(t), K_out)) when positive, by the same branch and bound (a maximisation of the
// circle distance); positivity proves the nesting. Returns nullopt (the caller tries a contact
// proof, else reports undecided) when the tubes may meet, or when the minimizers may form a
// continuum (coaxial tori: the surviving intervals cover the circle or exceed the budget). Ties:
// proven by symmetry where possible (symmetry.hpp), else reported as not proven.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/torus.hpp"

#include <optional>

namespace surfcert::certify {

std::optional<DistanceResult> torus_pair_distance(const core::Torus& a, const core::Torus& b,
                                                  long digits);

} // namespace surfcert::certify
