// surfcert::certify::quadric_canal_distance: the certified minimum distance between a quadric
// S1 and a canal surface (the boundary of the union of the balls B(C(t), r(t)), t in
// [t0, t1]; seed 000 §4).
//
// With phi(t) = dist(C(t), S1) - r(t): S1 misses every ball iff min phi > 0, and then the
// distance is min phi (S1 outside the union, whether it encloses it or not). The minimum is
// at t0, t1, or an interior t where the foot p of C(t) on S1 satisfies the envelope condition
// (C - p).C' = r' |C - p| (seed 000 eq. 24-25). In the point-quadric parametrisation
// p(alpha, t) = (I + alpha Q3)^-1 (C(t) - alpha b), f(p) = 0 and that condition (squared when
// r is not constant) are two equations in (alpha, t) over Z; their real solutions are covered
// by boxes (Sylvester resultants, exact isolation), and each t-interval T gets the lower bound
// dist(C(t_c), S1) - max |C(T) - C(t_c)| - max r(T) (the exact point-quadric sextic at the
// rational centre t_c) and the upper bound phi(t_c); the ends t0, t1 are exact candidates.
// A plane is handled in closed form (phi is then a polynomial over |n|). min phi < 0: S1
// enters the solid, so it meets the canal surface when S1 is unbounded (it also has points
// outside); a bounded S1 possibly inside the solid is left undecided.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

namespace surfcert::certify {

/// Exact: r > 0 on the whole of [t0, t1] (r(t0) > 0 and no root of r in the interval). Where
/// r vanishes inside, a ball shrinks to a point and the solid may be pinched there (the
/// boundary of the union is then no surface that stays connected once a point is removed);
/// where r < 0 the union of balls is not what the routes compute.
bool canal_radius_positive(const core::CanalSurface& c);

DistanceResult quadric_canal_distance(const core::QuadricMatrix& q, const core::CanalSurface& c,
                                      long digits, bool quadric_first);

} // namespace surfcert::certify
