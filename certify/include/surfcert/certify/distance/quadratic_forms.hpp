// surfcert::certify quadratic forms over Q: the exact 3x3 and binary-form helpers the routes on
// points at infinity, ruling directions and common apices share.
// - quadratic_block: the quadratic part A of a quadric x^T A x + 2 b.x + c (its conic at
//   infinity, or the cone of directions about a singular point);
// - bilinear: u^T A v (algebra::bilinear, form_restriction.hpp);
// - restricted_resultant: the resultant of the two binary forms x^T A x, x^T B x restricted to
//   the plane span{u, v} (zero iff they share a root there, real or complex, counted on the
//   projective line: both forms may be evaluated at u and v themselves);
// - components_unbounded: every real component of q runs off to infinity (its quadratic block
//   is not definite);
// - common_kernel: an exact basis of the vectors (x, 0) or (x, w) annihilated by both 4x4
//   matrices (FLINT nullspace of the stacked 8 x n matrix of their first n columns): common
//   ruling directions (n = 3) or common singular points (n = 4).
// Invariants: everything exact; bases are integer vectors (FLINT's nullspace, as rationals).
#pragma once

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <vector>

namespace surfcert::certify {

using RVec3 = std::array<core::Rational, 3>;
using RMat3 = std::array<RVec3, 3>;

RMat3 quadratic_block(const core::QuadricMatrix& q);

/// Every real component of q is unbounded: its quadratic block is not definite (a definite
/// block gives an ellipsoid, a single point such as x^2 + y^2 + z^2 = 0, or no real point;
/// otherwise q is a cone, a hyperboloid, a paraboloid, a cylinder, planes or a line, each
/// component running off to infinity). QuadricKind::Other is no such test: it holds the
/// single points too.
bool components_unbounded(const core::QuadricMatrix& q);

using algebra::bilinear;

core::Rational restricted_resultant(const RMat3& a, const RMat3& b, const RVec3& u, const RVec3& v);

/// n = 3 or 4; each vector has n entries.
std::vector<std::vector<core::Rational>> common_kernel(const core::QuadricMatrix& a,
                                                       const core::QuadricMatrix& b, int n);

} // namespace surfcert::certify
