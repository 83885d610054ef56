// Helpers shared by the tracer's box tests: trace options with a given box (the curve is
// clipped to [lo, hi], its exits on the box's faces counted), instead of the automatic one;
// the geometric residual of a traced point against an exact quadric; the checks of a
// certified picture made only of open pieces (expect_open_pieces) and of any certified picture
// in a given box (expect_matched_in_box).
#pragma once

#include "surfcert/core/rational.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace surfcert::testing {

/// Default trace options but for the box [lo, hi] (componentwise lo <= hi).
inline trace::TraceOptions given_box(trace::Point3 lo, trace::Point3 hi) {
  trace::TraceOptions opt;
  trace::Box box;
  box.min = lo;
  box.max = hi;
  opt.box = box;
  return opt;
}

// |f(p)| / |grad f(p)|, with f(p) exact (the double point read exactly): the first-order
// distance from p to the surface. Exact f matters at a cone's apex, where the gradient
// vanishes and the rounding error of a float f would dominate the quotient.
inline double geometric_residual(const core::QuadricMatrix& m, const trace::Point3& p) {
  const core::Rational x[4] = {core::Rational::exact_from_double(p[0]),
                               core::Rational::exact_from_double(p[1]),
                               core::Rational::exact_from_double(p[2]), core::Rational(1)};
  core::Rational f;
  double g[3] = {0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      f += x[i] * m(i, j) * x[j];
      if (i < 3) g[i] += 2 * (m(i, j) * x[j]).to_double_approx();
    }
  const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  const double fa = std::fabs(f.to_double_approx());
  return gn > 0 ? fa / gn : fa;
}

/// The checks of a certified picture made of `pieces` open pieces of kind `kind` (lines,
/// double conics: closed-form components): that many branches, the box's exact crossings
/// certified and twice as many, each piece open with two exits, every crossing used once,
/// every point within 1e-12 of the box's diagonal (plus a few ulps of its coordinates) of
/// both exact surfaces, and within `off_tol` of the closed form when `off` is given (a
/// distance from it). Lines are also checked straight and drawn once each: two lines are
/// distinct when one's ends are off the other by more than `line_gap` (default 1e-6 of the
/// box's diagonal; the closed form's least distance between lines, less rounding, when the
/// lines are closer than that).
inline void expect_open_pieces(const trace::CurveResult& r, const core::QuadricMatrix& a,
                               const core::QuadricMatrix& b, int pieces, const std::string& kind,
                               const std::string& ctx,
                               const std::function<double(const trace::Point3&)>& off = nullptr,
                               double off_tol = 0, double line_gap = -1) {
  ASSERT_EQ(static_cast<int>(r.branches.size()), pieces) << ctx;
  ASSERT_TRUE(r.box && r.box_exits && r.box_exits->certified) << ctx;
  ASSERT_EQ(static_cast<int>(r.box_exits->points.size()), 2 * pieces) << ctx;
  const double size = r.box->diagonal();
  auto tol = [&](const trace::Point3& p) {
    return 1e-12 * size + 0x1p-46 * (std::fabs(p[0]) + std::fabs(p[1]) + std::fabs(p[2]));
  };
  auto sub = [](const trace::Point3& x, const trace::Point3& y) {
    return trace::Point3{x[0] - y[0], x[1] - y[1], x[2] - y[2]};
  };
  auto len = [](const trace::Point3& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  };
  // Distance of x from the line through p0 and p1.
  auto off_chord = [&](const trace::Point3& x, const trace::Point3& p0, const trace::Point3& p1) {
    const trace::Point3 d = sub(p1, p0), v = sub(x, p0);
    const double t = (v[0] * d[0] + v[1] * d[1] + v[2] * d[2]) / (len(d) * len(d));
    return len({v[0] - t * d[0], v[1] - t * d[1], v[2] - t * d[2]});
  };
  std::set<int> used;
  std::vector<std::array<trace::Point3, 2>> seen; // each line's ends
  for (const auto& br : r.branches) {
    EXPECT_EQ(br.kind, kind) << ctx;
    EXPECT_FALSE(br.closed) << ctx;
    ASSERT_GE(br.points.size(), 2u) << ctx;
    ASSERT_EQ(br.exits.size(), 2u) << ctx;
    used.insert(br.exits.begin(), br.exits.end());
    const trace::Point3 p0 = br.points.front(), p1 = br.points.back();
    if (kind == "line") {
      ASSERT_GT(len(sub(p1, p0)), 1e-3 * size) << ctx;
    }
    for (const auto& p : br.points) {
      EXPECT_LE(geometric_residual(a, p), tol(p)) << ctx;
      EXPECT_LE(geometric_residual(b, p), tol(p)) << ctx;
      if (off) {
        EXPECT_LE(off(p), off_tol) << ctx;
      }
      if (kind == "line") {
        EXPECT_LE(off_chord(p, p0, p1), tol(p)) << ctx << ": not straight";
      }
    }
    if (kind == "line") {
      for (const auto& e : seen) // distinct: the other line's ends are not both on this one
        EXPECT_GT(std::max(off_chord(e[0], p0, p1), off_chord(e[1], p0, p1)),
                  line_gap >= 0 ? line_gap : 1e-6 * size)
            << ctx << ": a line twice";
      seen.push_back({p0, p1});
    }
  }
  EXPECT_EQ(static_cast<int>(used.size()), 2 * pieces) << ctx;
}

/// A picture in a given box, certified: its crossings with the faces certified, each open
/// piece's two ends matched to exact crossings (as many ends as crossings), every point within
/// 1e-12 of the box's diagonal of both surfaces (exact substitution). Returns the number of ends.
inline size_t expect_matched_in_box(const trace::CurveResult& r, const core::QuadricMatrix& a,
                                    const core::QuadricMatrix& b, const std::string& ctx) {
  EXPECT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
  if (!r.box || !r.box_exits || !r.box_exits->certified) {
    ADD_FAILURE() << ctx << ": no certified crossings";
    return 0;
  }
  const double diag = r.box->diagonal();
  size_t ends = 0;
  for (const auto& br : r.branches) {
    if (!br.closed) {
      ends += 2;
      EXPECT_EQ(br.exits.size(), 2u) << ctx;
    }
    for (const auto& p : br.points) {
      EXPECT_LE(geometric_residual(a, p), 1e-12 * diag) << ctx;
      EXPECT_LE(geometric_residual(b, p), 1e-12 * diag) << ctx;
    }
  }
  EXPECT_EQ(ends, r.box_exits->points.size()) << ctx;
  return ends;
}

} // namespace surfcert::testing
