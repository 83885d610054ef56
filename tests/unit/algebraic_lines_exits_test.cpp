// Two cones with a common apex meeting in a double rational line and two lines conjugate over
// Q(sqrt D) (`generate --case degenerate_pencil --seed 83`, pairs 11 and 13). Their curve's
// crossings with a face are double on the double line, so box_exits could only answer "a
// multiple crossing", in every box, the automatic one too: undecided although the affine
// topology (3 lines) was certified. The lines' crossings are now read from the exact
// directions (lines_box_exits with algebraic directions: signs at the roots).
// Checked against closed forms: a box holding the apex inside is crossed twice by each line, so
// at 6 points, collinear in pairs with the apex; every crossing lies on both cones (exact
// substitution of the rounded point, geometric distance) and within its radius of the face;
// the same after a rational rigid motion and with the cones swapped; boxes not holding the
// apex give an even count; a box with the apex on a face is not certified (its reason given).
#include "support/distance_checks.hpp"
#include "support/trace_boxes.hpp"

#include "surfcert/certify/box_exits.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace surfcert;
using core::Rational;

namespace {

core::QuadricMatrix from_ints(const std::array<std::array<long, 4>, 4>& rows) {
  core::Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = Rational(rows[i][j]);
  return core::QuadricMatrix(m);
}

struct Pair {
  const char* id;
  core::QuadricMatrix a, b;
};

std::vector<Pair> pairs() {
  const auto a11 =
      from_ints({{{-18, 18, 6, -3}, {18, -12, -12, 6}, {6, -12, 4, -2}, {-3, 6, -2, 1}}});
  const auto b11 =
      from_ints({{{-9, -8, 20, -10}, {-8, 28, -20, 14}, {20, -20, -4, -2}, {-10, 14, -2, 3}}});
  const auto m =
      surfcert::testing::motion(3, -1, 2, 1, {Rational(2), Rational(-5, 3), Rational(1, 2)});
  const auto a13 =
      from_ints({{{12, 4, -10, 10}, {4, -1, -1, 1}, {-10, -1, 6, -6}, {10, 1, -6, 6}}});
  const auto b13 =
      from_ints({{{-24, -2, 14, -14}, {-2, 0, 4, -4}, {14, 4, -14, 14}, {-14, -4, 14, -14}}});
  std::vector<Pair> out = {{"pair 13", a13, b13},
                           {"pair 11", a11, b11},
                           {"pair 11 swapped", b11, a11},
                           {"pair 11 moved", a11.congruent(m), b11.congruent(m)}};
  return out;
}

// The apex, as doubles (the certified affine reading carries it exactly).
trace::Point3 apex_of(const trace::CurveResult& r) {
  trace::Point3 p{};
  for (size_t k = 0; k < 3; ++k)
    p[k] = (*r.affine.apex)[k].to_double_approx();
  return p;
}

void expect_crossings_on_the_lines(const trace::CurveResult& r, const core::QuadricMatrix& a,
                                   const core::QuadricMatrix& b, const std::string& ctx) {
  ASSERT_TRUE(r.box && r.box_exits) << ctx;
  const double diag = r.box->diagonal();
  for (const auto& c : r.box_exits->points) {
    // On the face, within its radius, and on both cones.
    const double face = c.at_max ? r.box->max[static_cast<size_t>(c.axis)]
                                 : r.box->min[static_cast<size_t>(c.axis)];
    EXPECT_EQ(c.approx[static_cast<size_t>(c.axis)], face) << ctx;
    const double size =
        diag + std::fabs(c.approx[0]) + std::fabs(c.approx[1]) + std::fabs(c.approx[2]);
    EXPECT_LE(c.radius, 1e-14 * size) << ctx;
    EXPECT_LE(surfcert::testing::geometric_residual(a, c.approx), 1e-13 * diag) << ctx;
    EXPECT_LE(surfcert::testing::geometric_residual(b, c.approx), 1e-13 * diag) << ctx;
  }
}

} // namespace

TEST(AlgebraicLinesExits, AutomaticBoxHoldsTheApex) {
  for (const auto& pr : pairs()) {
    const auto r = trace::intersect_curve(pr.a, pr.b, certify::Mode::Filtered, {});
    ASSERT_EQ(r.affine.route, "common_apex") << pr.id;
    ASSERT_EQ(r.affine.lines, 3) << pr.id;
    surfcert::testing::expect_matched_in_box(r, pr.a, pr.b, pr.id);
    ASSERT_TRUE(r.box_exits && r.affine.apex) << pr.id;
    EXPECT_EQ(r.box_exits->points.size(), 6u) << pr.id;
    expect_crossings_on_the_lines(r, pr.a, pr.b, pr.id);
    // Collinear in pairs with the apex: each crossing has exactly one partner on the opposite
    // side (the unit vectors from the apex opposite to 1e-9).
    const trace::Point3 p = apex_of(r);
    const auto& pts = r.box_exits->points;
    for (size_t i = 0; i < pts.size(); ++i) {
      int partners = 0;
      std::array<double, 3> u{};
      double nu = 0;
      for (size_t k = 0; k < 3; ++k) {
        u[k] = pts[i].approx[k] - p[k];
        nu += u[k] * u[k];
      }
      for (size_t j = 0; j < pts.size(); ++j) {
        if (j == i) continue;
        std::array<double, 3> v{};
        double nv = 0, dot = 0;
        for (size_t k = 0; k < 3; ++k) {
          v[k] = pts[j].approx[k] - p[k];
          nv += v[k] * v[k];
          dot += u[k] * v[k];
        }
        if (dot / std::sqrt(nu * nv) < -1 + 1e-9) ++partners;
      }
      EXPECT_EQ(partners, 1) << pr.id << " crossing " << i;
    }
  }
}

TEST(AlgebraicLinesExits, GivenBoxesAroundAndAwayFromTheApex) {
  for (const auto& pr : pairs()) {
    const auto auto_r = trace::intersect_curve(pr.a, pr.b, certify::Mode::Filtered, {});
    ASSERT_TRUE(auto_r.affine.apex) << pr.id;
    const trace::Point3 p = apex_of(auto_r);
    // Boxes around the apex at three scales and uneven offsets (the apex strictly inside):
    // 6 crossings. Boxes beside it (the apex outside): an even number.
    for (double w : {1e-3, 1.0, 1e3}) {
      const trace::Point3 lo{p[0] - w, p[1] - 0.7 * w, p[2] - 1.3 * w};
      const trace::Point3 hi{p[0] + 1.1 * w, p[1] + 0.9 * w, p[2] + 0.6 * w};
      const std::string ctx = std::string(pr.id) + " around, w " + std::to_string(w);
      const auto r = trace::intersect_curve(pr.a, pr.b, certify::Mode::Filtered,
                                            surfcert::testing::given_box(lo, hi));
      surfcert::testing::expect_matched_in_box(r, pr.a, pr.b, ctx);
      ASSERT_TRUE(r.box_exits) << ctx;
      EXPECT_EQ(r.box_exits->points.size(), 6u) << ctx;
      expect_crossings_on_the_lines(r, pr.a, pr.b, ctx);
      const trace::Point3 lo2{p[0] + 0.25 * w, p[1] - 0.8 * w, p[2] - 1.1 * w};
      const trace::Point3 hi2{p[0] + 2 * w, p[1] + 0.9 * w, p[2] + 1.2 * w};
      const auto r2 = trace::intersect_curve(pr.a, pr.b, certify::Mode::Filtered,
                                             surfcert::testing::given_box(lo2, hi2));
      surfcert::testing::expect_matched_in_box(r2, pr.a, pr.b, ctx + " beside");
      ASSERT_TRUE(r2.box_exits) << ctx;
      EXPECT_EQ(r2.box_exits->points.size() % 2, 0u) << ctx;
      expect_crossings_on_the_lines(r2, pr.a, pr.b, ctx + " beside");
    }
  }
}

TEST(AlgebraicLinesExits, ApexOnAFaceIsNotCertified) {
  const auto pr = pairs()[1];
  const auto r0 = trace::intersect_curve(pr.a, pr.b, certify::Mode::Filtered, {});
  ASSERT_TRUE(r0.affine.apex);
  const auto& ap = *r0.affine.apex;
  std::array<Rational, 3> lo, hi;
  for (size_t k = 0; k < 3; ++k) {
    lo[k] = ap[k] - Rational(1);
    hi[k] = ap[k] + Rational(1);
  }
  // The directions as the affine reading gives them.
  std::vector<std::array<Rational, 3>> rational;
  std::vector<certify::AlgebraicDirection> algebraic;
  for (const auto& pt : r0.affine.points_at_infinity) {
    if (pt.rational) {
      std::array<Rational, 3> d;
      for (size_t k = 0; k < 3; ++k)
        d[k] = *Rational::from_string(pt.direction[k]);
      rational.push_back(d);
    } else {
      algebraic.push_back({pt.polynomial, pt.lo, pt.hi, pt.dir_in_t});
    }
  }
  ASSERT_EQ(rational.size(), 1u);
  ASSERT_EQ(algebraic.size(), 2u);
  const auto inside = certify::lines_box_exits(ap, rational, algebraic, lo, hi);
  EXPECT_TRUE(inside.certified) << inside.reason;
  EXPECT_EQ(inside.points.size(), 6u);
  lo[0] = ap[0]; // the apex on the face x = lo
  const auto on_face = certify::lines_box_exits(ap, rational, algebraic, lo, hi);
  EXPECT_FALSE(on_face.certified);
  EXPECT_TRUE(on_face.points.empty());
}
