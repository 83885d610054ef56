// surfcert::certify::meet_by_sign_change: a certificate that two quadrics have a common affine
// point, for the cases the projective classification leaves open (a real intersection curve
// whose conics at infinity share a component may lie at infinity only: cylinder against a
// paraboloid of the same axis direction, two cones with one conic at infinity).
//
// If a quadric A (or one sheet of it) is connected and the other quadric's polynomial g takes
// both signs on it, then g vanishes somewhere on it (intermediate values along a path in A): the
// surfaces meet at an affine point. Points of A are certified balls (the root of f on the gradient
// line through a rational grid point, Arb) and the sign of g on each ball is certified;
// connectedness is decided exactly from the inertia of the quadratic block and of the 4x4 matrix
// (two-sheeted hyperboloids, hyperbolic cylinders and pairs of parallel planes are the disconnected
// real quadrics; for them both signs must be seen on one sheet, the sheet of a point told apart
// exactly by the sign of a linear function w^T (A x + b) that vanishes on no point of the
// quadric). The sampling grid (several scales around the origin) only chooses where to look:
// failure to find both signs proves nothing and returns false. The witness is approximate (a
// float bisection between the two certified points, projected on A).
#pragma once

#include "surfcert/core/quadric.hpp"
#include "surfcert/core/surface.hpp"

#include <array>
#include <vector>

namespace surfcert::certify {

/// True when a connected quadric among a, b is proven to have points on both sides of the
/// other; `witness` then holds an approximate common point.
/// `near`: suspected common points (approximate; e.g. boxes of an exact solution cover): probes
/// around them are tried too (they only choose where to look).
bool meet_by_sign_change(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                         std::array<double, 3>& witness,
                         const std::vector<std::array<double, 3>>& near = {});

/// Any two surfaces: the sampled (connected) surface is a quadric (gradient-line projections of
/// a rational grid), a ring torus (a grid of angles, rational multiples of pi) or a canal
/// surface (support points in a grid of rational unit directions: they lie on the boundary of
/// the unbounded complement of the solid, which is connected); the other
/// surface's side is certified by solid_relation.hpp's side_of (quadric, torus, canal,
/// implicit). Witness approximate: bisection along a path on the sampled surface, then a
/// float Gauss-Newton polish of both surfaces' distance-like functions; `residual` (when given)
/// receives the remaining float residual of the witness (how far it is from both surfaces).
/// `continuum` (when given) is true when both sides were seen on a piece that stays connected
/// once finitely many points are removed (a torus, a canal surface's outer boundary, a sheet
/// of a quadric, one nappe of a cone): the common points are then infinitely many. A cone
/// seen on either side on its two nappes only may meet the other surface at its apex alone.
bool surfaces_meet_by_sign_change(const core::Surface& a, const core::Surface& b,
                                  std::array<double, 3>& witness, double* residual = nullptr,
                                  bool* continuum = nullptr);

/// Exact: false for the disconnected real quadrics (two-sheeted hyperboloid, hyperbolic
/// cylinder, two parallel planes), true otherwise.
bool quadric_connected(const core::QuadricMatrix& q);

} // namespace surfcert::certify
