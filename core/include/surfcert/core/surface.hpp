// surfcert::core::Surface: any surface the distance queries accept: a quadric (planes
// included), a ring torus, or a canal surface. Quadric-only operations (classify, intersect)
// take the QuadricMatrix alternative and report an input error for the others.
//
// CanalSurface: the boundary of the union of the balls B(C(t), r(t)), t in [t0, t1] (seed 000
// §4's envelope of spheres, closed by the end spheres: a capsule is the segment case with a
// constant radius). C and r are polynomials with rational coefficients (constant term first).
// Invariants (checked by make_canal): t0 < t1; C not constant; r(t0) > 0 and r(t1) > 0
// (positivity on the whole interval is checked exactly where the distance is computed).
#pragma once

#include "surfcert/core/poly3.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/torus.hpp"

#include <array>
#include <string>
#include <variant>
#include <vector>

namespace surfcert::core {

struct CanalSurface {
  std::array<std::vector<Rational>, 3> spine; ///< C(t) coordinate polynomials
  std::vector<Rational> radius;               ///< r(t)
  Rational t0, t1;
};

/// Throws std::invalid_argument when an invariant fails (the reader reports an InputError).
CanalSurface make_canal(std::array<std::vector<Rational>, 3> spine, std::vector<Rational> radius,
                        const Rational& t0, const Rational& t1);

/// Value of a coefficient list (constant first) at t.
Rational eval_poly(const std::vector<Rational>& c, const Rational& t);

/// Highest total degree accepted for an implicit surface. The branch and bound serves any
/// degree; the exact offset systems are only attempted up to kMaxOffsetDegree (their
/// resultants grow like a power of the degree).
constexpr int kMaxImplicitDegree = 12;
constexpr int kMaxOffsetDegree = 6;

/// An implicit algebraic surface f(x, y, z) = 0 of total degree 3 to kMaxImplicitDegree
/// (quadrics are QuadricMatrix). Invariant: 3 <= total degree <= kMaxImplicitDegree, rational
/// coefficients.
struct ImplicitSurface {
  Poly3 f;
};

/// A rational parametric surface (X(u, v), Y(u, v), Z(u, v)) / W(u, v), u, v real; the
/// polynomials are stored as Poly3 in x (= u) and y (= v). Invariant: W is not the zero
/// polynomial and no polynomial involves z.
struct ParametricSurface {
  Poly3 X, Y, Z, W;
};

using Surface =
    std::variant<QuadricMatrix, Torus, CanalSurface, ImplicitSurface, ParametricSurface>;

/// "quadric", "torus", "canal", "implicit" or "parametric".
std::string surface_kind(const Surface& s);

/// What a surface is, as an input error's "found" says it where a quadric was needed: "total
/// degree N" for an implicit surface (as the equation reader words a degree it refuses), "a
/// torus", "a canal surface", "a parametric surface", "a quadric".
std::string surface_found(const Surface& s);

} // namespace surfcert::core
