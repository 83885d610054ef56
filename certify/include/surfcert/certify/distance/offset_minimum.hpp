// surfcert::certify offset-minimum machinery shared by every "quadric source vs target"
// distance (quadric pairs, quadric vs torus):
// - SourceQuadric: the source surface S1 (f = 0, exact rational coefficients) with its gradient,
// and
//   a certified point of S1 near any rational point (on the gradient line, Arb);
// - MinimumTarget: what a target S2 contributes: a certified LOWER bound of the distance of
//   any closest pair whose S1 point lies in a box, and the distance of a GENUINE pair from a
//   certified point of S1 (an upper bound for the minimum);
// - minimize_over_cover: refines the boxes of a SolutionCover (which covers every closest
//   S1 point) until upper - lower <= 10^-digits lower, dropping boxes whose lower bound
//   exceeds the best upper bound, and fills a DistanceResult (enclosure, minimizer count,
//   approximate pairs).
// Invariants: every lower bound is <= the distance of every closest pair with its S1 point in
// the box (a NaN bound is read as 0); every upper bound is the distance of a pair of actual
// surface points (balls that contain the exact points), so [min lower, min upper] always
// encloses the minimum when the minimum is attained and the cover is complete. The minimizer
// count is the number of kept boxes, i.e. of closest S1 points (a box holds one solution at
// most; extra kept boxes only raise it, and a count above 1 is a tie, unproven until
// symmetry.hpp proves it). It would undercount only where one S1 point has two closest points
// on S2, which needs S2 on both sides of S1 along its normal (a plane between the sheets of a
// hyperboloid of two sheets): planes are answered by the closed form first.
#pragma once

#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/algebra/solution_cover.hpp"
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/poly3.hpp"

#include <array>
#include <optional>

namespace surfcert::certify {

using Balls3 = Ball[3];

/// The balls of a box as the pointer triple algebra::evaluate takes.
std::array<const arb_struct*, 3> ball_point(const Ball (&x)[3]);

/// |v| of a vector of balls.
void ball_norm(arb_t out, const Ball (&v)[3], long prec);

/// Real roots of a2 t^2 + a1 t + a0 = 0 (balls; a2 may be 0). Each of r[0 .. n) encloses a
/// real root of the exact equation. true with n = 0: no real root (proven); n = 1: r[0] (the
/// root of smallest magnitude when a1 != 0) - the only one when a2 = 0, and when a2's ball
/// contains 0 the other root, which may not exist, is not written; n = 2: both. false when
/// no root is certain at this precision (disc or the denominator not away from 0).
bool ball_quadratic_roots(const arb_t a2, const arb_t a1, const arb_t a0, Ball (&r)[2], int& n,
                          long prec);

struct SourceQuadric {
  explicit SourceQuadric(const core::QuadricMatrix& q);
  /// Any implicit source f = 0 (exact coefficients); degree > 2 projects through the exact
  /// real roots of the univariate f(c + t grad f(c)).
  explicit SourceQuadric(core::Poly3 f_any);
  const core::QuadricMatrix* quadric = nullptr; ///< null for a non-quadric source
  core::Poly3 f;
  std::array<core::Poly3, 3> N; ///< grad f
  std::array<std::array<core::Rational, 3>, 3> hess;
  /// A point of S1 on the gradient line through c (the root nearest c): balls that contain
  /// an exact point of S1; c itself when f(c) = 0 exactly and the line gives no certain root
  /// (a singular point). False when no real root is certain.
  bool project(const core::Rational (&c)[3], Ball (&p)[3], long prec) const;

private:
  bool project_on_normal(const core::Rational (&c)[3], Ball (&p)[3], long prec) const;
};

/// The sign of h (+1 or -1; 0 when not certain) at a certified point of the source near the
/// centre of a cover box (the contact tests: a point of S1 inside / outside the other
/// surface); the point, approximately, in `at`.
int certified_sign_near(const SourceQuadric& src, const core::Poly3& h,
                        const algebra::SolutionCover& c, const std::array<size_t, 3>& box,
                        long prec, std::array<double, 3>* at = nullptr);

struct CandidatePair {
  Ball d;                         ///< distance of a pair of actual surface points
  std::array<double, 3> p{}, q{}; ///< approximate points (on S1, on S2)
};

class MinimumTarget {
public:
  virtual ~MinimumTarget() = default;
  /// Lower bound for every closest pair with its S1 point in the box (+inf: none there).
  virtual void lower(arf_t out, const Ball (&box)[3], const core::Rational (&centre)[3],
                     long prec) const = 0;
  /// A genuine pair from the certified S1 point p (nullopt when not certain).
  virtual std::optional<CandidatePair> upper(const Ball (&p)[3], long prec) const = 0;
};

/// Refines `cover` to the minimum (see above). source_is_a: S1 is the first surface of the
/// query (pairs are reported in query order). compact: the minimum is attained (one surface
/// bounded); otherwise the status is undecided with lower = 0.
/// True (and out set to undecided, saying why) when the implicit source f is beyond the degree
/// the exact offset systems are attempted for (core::kMaxOffsetDegree).
bool refuse_beyond_offset_degree(const core::Poly3& f, DistanceResult& out);

void minimize_over_cover(algebra::SolutionCover& cover, const SourceQuadric& src,
                         const MinimumTarget& tgt, long digits, bool source_is_a, bool compact,
                         DistanceResult& out);

} // namespace surfcert::certify
