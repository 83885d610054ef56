// surfcert::certify::oval_chart: which of the curve's ovals meet the plane at infinity, decided
// in a projective chart where every oval is bounded.
//
// Why: two smooth ovals (Tu case 1, two_ovals) with four real points at infinity allow the
// affine readings {1 loop, 4 unbounded} (one oval carries every point at infinity) and
// {0 loops, 4 unbounded} (two each). A traced closed loop proves the first
// (proven_loops.hpp); the second needs every compact component ruled out, which the critical
// point bound (loops_upper_bound) fails to do when the unbounded arcs wind inside its box.
// Here both ovals are made bounded, and each is asked whether it holds a point at infinity.
//
// The argument, exact in every step:
//  1. A member M = l A - B (or A, or B) of the pencil with inertia (3,1) or (1,3) (exact, LDL^T;
//     l a short dyadic between the pencil's roots, proposed in floats) and a rational p with
//     p^T M p of the lone sign (exact). The plane H: p^T M x = 0 misses the real quadric
//     x^T M x = 0 (M restricted to p's M-orthogonal complement is definite), hence the curve
//     (every real point of it lies on every member).
//  2. The chart y = L x: y_0 = w (the old homogenising coordinate), y_1, y_2 two of x, y, z,
//     y_3 = h(x) (H's linear form, scaled to a unit coefficient on the coordinate left out),
//     the pair A' = L^-T A L^-1, B' likewise (a projective congruence: the same real
//     projective curve, every fact of the pencil kept). Its plane at infinity is H: in the
//     affine coordinates Y = (y_0, y_1, y_2) / y_3 the whole real curve is compact, its
//     components are the projective ones, and the old plane at infinity is the plane Y_0 = 0.
//     Each chart axis is then moved to the member's centre there and scaled by a power of two
//     to about its half-extent (Y_i = 2^k_i Z_i + c_i, c_i dyadic: exact), so the old plane at
//     infinity is Z_0 = infinity_at.
//  3. Boxes proven to hold a loop wholly inside (proven_loops on A', B', boxes proposed by the
//     tracer in the chart), pairwise disjoint and as many as the curve has components: each box
//     holds exactly one component, and every point of the curve lies in one of the boxes.
//  4. The curve's points on Z_0 = infinity_at inside a box (the old points at infinity on that
//     box's component): box_exits of the part of the box below it (its other faces lie on the
//     box's boundary, which the curve misses), certified, or none when the box lies on one side.
// A component with no such point is an affine loop of the original pair; one with some is split
// by them into unbounded branches. So loops = the number of boxes with no such crossing.
// Nothing here is a guess: a member of the wrong inertia, a plane section not certified, fewer
// proven boxes than components or crossings that do not add up to the real points at infinity
// leave the reading undecided.
#pragma once

#include "surfcert/certify/affine.hpp"
#include "surfcert/certify/proven_loops.hpp"
#include "surfcert/core/shape.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace surfcert::certify {

/// The pair in a chart whose plane at infinity misses the real curve (step 2 above).
struct OvalChart {
  core::Mat4 a, b;                     ///< A' = L^-T A L^-1, B' = L^-T B L^-1
  core::Mat4 from_chart;               ///< L^-1: x = L^-1 y (homogeneous coordinates)
  std::array<core::Rational, 4> plane; ///< h: the plane h . (x, y, z, w) = 0 sent to infinity
  core::Mat4 member;                   ///< the member of inertia (3,1) or (1,3) that H misses
  /// The old plane at infinity is the chart's coordinate plane Z_0 = infinity_at.
  core::Rational infinity_at;
};

/// Steps 1 and 2, or nullopt (with `why` set) when no member tried has inertia (3,1) or (1,3):
/// A, B, then l A - B at short dyadics between the float roots of det(l A - B) and beyond them
/// (the floats only propose; each member's inertia is decided exactly).
/// With `frame` (floats: the curve's centre and size, e.g. a traced picture's box), the pair is
/// first brought to about unit size around the origin by the exact congruence x = 2^k x0 + c
/// (2^k ~ size, c dyadic ~ centre): a pair scaled by 2^-20 or moved 2^30 away otherwise gives
/// a chart member of axis ratio ~3000 where nothing is traced. Every field of the result is
/// in the original coordinates (from_chart maps chart to original points).
struct ChartFrame {
  std::array<double, 3> centre{};
  double size = 0;
};
std::optional<OvalChart> oval_chart(const core::Mat4& a, const core::Mat4& b, std::string& why,
                                    const ChartFrame* frame = nullptr);

/// The same chart with its affine coordinates Y changed to Y' = R Y, R = rows (e_0, d, e_o):
/// Y'_0 = Y_0 stays the old plane at infinity's coordinate, Y'_1 = d . Y (a direction that
/// separates the ovals, proposed by the tracer, so that boxes around them are disjoint), Y'_2
/// the one of Y_1, Y_2 that keeps R invertible (o = 2 when |d_1| >= |d_2|, else 1). nullopt when
/// d_1 = d_2 = 0. `r` receives R.
std::optional<OvalChart> oval_chart_along(const OvalChart& c,
                                          const std::array<core::Rational, 3>& d,
                                          std::array<std::array<core::Rational, 3>, 3>& r);

/// Steps 3 and 4: the number of components (of `components`, the projective count) that meet
/// the old plane at infinity, from `proven` (proven_loops on chart.a, chart.b). `loops` is set
/// when every box's crossings are certified and the crossings add up to `points_at_infinity`
/// (the curve's distinct real points at infinity); `crossings` per box.
struct OvalsAtInfinity {
  std::optional<int> loops;
  std::vector<int> crossings;
  std::string reason;
};
OvalsAtInfinity ovals_at_infinity(const OvalChart& chart, const ProvenLoops& proven, int components,
                                  int points_at_infinity);

/// Keeps the readings of `t` with loops == *o.loops; when exactly one remains, the counts are
/// set from it, their undecided entries removed, and the route becomes "oval_chart"; returns
/// true then (t unchanged otherwise).
bool settle_by_oval_chart(AffineTopology& t, const OvalsAtInfinity& o);

} // namespace surfcert::certify
