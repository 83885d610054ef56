// Helpers shared by the near-degenerate curve tests (a closed-form pair at a gap g, posed by
// rational rigid motions, in both orders): a pose, its name for failure messages, the local
// coordinates R^T (p - t) of a traced point, and the verdict check every such test makes
// (certified, or undecided with a reason where that is allowed).
#pragma once

#include "support/distance_checks.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace surfcert::testing {

/// x -> R x + t with R from the integer quaternion (w, x, y, z) (see motion()).
struct Pose {
  long w = 1, x = 0, y = 0, z = 0;
  std::array<core::Rational, 3> t{};
  core::Mat4 matrix() const { return motion(w, x, y, z, t); }
  /// "gap G, pose (w,x,y,z) + (tx,ty,tz)[ swapped]": the context of a failure message.
  std::string name(const std::string& gap, bool swapped) const {
    return "gap " + gap + ", pose (" + std::to_string(w) + "," + std::to_string(x) + "," +
           std::to_string(y) + "," + std::to_string(z) + ") + (" + t[0].to_string() + "," +
           t[1].to_string() + "," + t[2].to_string() + ")" + (swapped ? " swapped" : "");
  }
  /// R^T (p - t), in doubles (exact to a few ulps of |p|).
  std::array<double, 3> local(const trace::Point3& p) const {
    const double W = static_cast<double>(w), X = static_cast<double>(x), Y = static_cast<double>(y),
                 Z = static_cast<double>(z);
    const double n = W * W + X * X + Y * Y + Z * Z;
    const double R[3][3] = {
        {W * W + X * X - Y * Y - Z * Z, 2 * (X * Y - W * Z), 2 * (X * Z + W * Y)},
        {2 * (X * Y + W * Z), W * W - X * X + Y * Y - Z * Z, 2 * (Y * Z - W * X)},
        {2 * (X * Z - W * Y), 2 * (Y * Z + W * X), W * W - X * X - Y * Y + Z * Z}};
    std::array<double, 3> out{};
    for (size_t j = 0; j < 3; ++j)
      for (size_t k = 0; k < 3; ++k)
        out[j] += R[k][j] * (p[k] - t[k].to_double_approx()) / n;
    return out;
  }
  /// |t|_1: the scale of the coordinates' rounding.
  double offset() const {
    double s = 0;
    for (const auto& c : t)
      s += std::abs(c.to_double_approx());
    return s;
  }
};

/// The five rational poses of the near-degenerate curve tests: the identity, a rotation, two
/// rotations with small rational translations ((1/3, 0, -1) is not a double), and 2^20 out.
inline const std::vector<Pose>& five_poses() {
  static const std::vector<Pose> p = {
      {1, 0, 0, 0, {}},
      {1, 1, 1, 1, {}},
      {1, 2, 3, 4, {core::Rational(1, 3), core::Rational(0), core::Rational(-1)}},
      {9, -1, 2, 3, {core::Rational(-1, 2), core::Rational(1), core::Rational(1, 4)}},
      {1, 0, 0, 0, {core::Rational(1048576), core::Rational(0), core::Rational(0)}}};
  return p;
}

/// Trace options with the box of half-width h around the pose's origin (its translation).
inline trace::TraceOptions box_around_pose(const Pose& ps, double h) {
  trace::TraceOptions opt;
  trace::Box box;
  for (size_t k = 0; k < 3; ++k) {
    box.min[k] = ps.t[k].to_double_approx() - h;
    box.max[k] = ps.t[k].to_double_approx() + h;
  }
  opt.box = box;
  return opt;
}

/// The quadrics of the equations a and b posed by ps, in the order (b, a) when swapped.
inline std::pair<core::QuadricMatrix, core::QuadricMatrix>
posed_pair(const std::string& a, const std::string& b, const Pose& ps, bool swapped) {
  auto qa = q(a).congruent(ps.matrix()), qb = q(b).congruent(ps.matrix());
  if (swapped) std::swap(qa, qb);
  return {qa, qb};
}

/// True when r is certified; otherwise checks it is undecided with a reason, and not a pair
/// that must be certified.
inline bool certified_or_undecided(const trace::CurveResult& r, bool must_certify,
                                   const std::string& ctx) {
  if (r.status == certify::Status::Certified) return true;
  EXPECT_FALSE(must_certify) << ctx << ": " << r.note;
  EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
  EXPECT_FALSE(r.note.empty()) << ctx;
  return false;
}

/// A closed-form line in a pose's local coordinates: true when the point lies on it (to eps).
using OnLocalLine = std::function<bool(const std::array<double, 3>&, double)>;

/// The picture of a curve made of lines: every branch an open "line" whose points all lie on
/// exactly one of `lines` (the pose's local coordinates, to 1e-9 (1 + |t|)), each line drawn
/// once, both ends of each on the box's faces, and two exact crossings per line.
inline void expect_each_line_drawn_once(const trace::CurveResult& r, const Pose& ps,
                                        const std::vector<OnLocalLine>& lines,
                                        const std::string& ctx) {
  const size_t n = lines.size();
  ASSERT_TRUE(r.box.has_value()) << ctx;
  ASSERT_TRUE(r.box_exits.has_value()) << ctx;
  EXPECT_TRUE(r.box_exits->certified) << ctx;
  EXPECT_EQ(r.box_exits->points.size(), 2 * n) << ctx;
  ASSERT_EQ(r.branches.size(), n) << ctx;
  const double eps = 1e-9 * (1 + ps.offset());
  std::vector<int> drawn(n, 0);
  for (const auto& br : r.branches) {
    EXPECT_EQ(br.kind, "line") << ctx;
    EXPECT_FALSE(br.closed) << ctx;
    ASSERT_GE(br.points.size(), 2u) << ctx;
    int which = -1, holders = 0;
    for (size_t i = 0; i < n; ++i) {
      bool all = true;
      for (const auto& p : br.points)
        all = all && lines[i](ps.local(p), eps);
      if (all) {
        which = static_cast<int>(i);
        ++holders;
      }
    }
    ASSERT_EQ(holders, 1) << ctx << ": a branch off every closed-form line";
    ++drawn[static_cast<size_t>(which)];
    for (const auto* e : {&br.points.front(), &br.points.back()}) {
      bool on_face = false;
      for (size_t k = 0; k < 3; ++k)
        on_face = on_face || (*e)[k] == r.box->min[k] || (*e)[k] == r.box->max[k];
      EXPECT_TRUE(on_face) << ctx << ": an end off the box's faces";
    }
  }
  for (size_t i = 0; i < n; ++i)
    EXPECT_EQ(drawn[i], 1) << ctx << ": closed-form line " << i;
}

/// The pair (sa, sb) in each of the five poses and both orders: f(pose, ctx, a, b, r) with r
/// its exact intersect_curve answer and ctx the pair's and pose's name. Returns the number of
/// answers (10). (An ASSERT in f ends that pose's check only.)
template <class F> int each_posed_curve(const std::string& sa, const std::string& sb, F&& f) {
  int n = 0;
  for (const auto& ps : five_poses())
    for (bool swapped : {false, true}) {
      const std::string ctx = sa + " | " + sb + ", " + ps.name("-", swapped);
      const auto [a, b] = posed_pair(sa, sb, ps, swapped);
      f(ps, ctx, a, b, trace::intersect_curve(a, b, certify::Mode::Exact, {}));
      ++n;
    }
  return n;
}

} // namespace surfcert::testing
