// The tracer's own check of a certified picture (trace/src/intersect_curve.cpp, check_picture):
// inputs of helper-14's audit (2026-12-02) that were certified with a wrong picture.
//  - A plane passing a cone's apex by g at |apex| ~ 1 (x = 1/3 + g against the cone with apex
//    (1/3, 0, -1)): the section is a hyperbola, one branch per nappe, but a float threshold drew
//    it as its two asymptotes, each crossing the apex (half on each nappe), matched to the exact
//    box exits and certified (160 of 1152 audited pairs). Closed form: two unbounded branches,
//    no line; each branch on one nappe (the sign of z + 1) beyond 1e-9 of the apex.
//  - A paraboloid near a cone's apex 1e9 out (audit id 6242): a circle 0.25 off the paraboloid,
//    certified because the residual test compared with the automatic box's diagonal (3.7e9).
//  - A loop of radius 2^-100 next to an apex (audit id 1703) drawn 4e-6 wide, certified with
//    max_residual 2.1e-6 (no residual test on the ellipsoid route).
// Each must be certified with a right picture or undecided with a reason.
#include "support/distance_checks.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace surfcert;
using certify::Mode;
using surfcert::testing::q;

namespace {

void expect_certified_or_undecided(const trace::CurveResult& r, const std::string& ctx) {
  if (r.status != certify::Status::Certified) {
    EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
    EXPECT_FALSE(r.note.empty()) << ctx;
  }
}

} // namespace

TEST(PictureCheck, HyperbolaNearTheApexIsNotItsAsymptotes) {
  struct Case {
    std::string o, g; // apex (o + 1/3, o, o - 1), plane x = o + 1/3 + g
    double gap;       // |g|
  };
  int certified = 0;
  for (const Case& c :
       {Case{"0", "1/10000000000", 1e-10}, Case{"0", "-1/10000000000", 1e-10},
        Case{"12345.678", "1/1000000", 1e-6}, Case{"12345.678", "-1/1000000", 1e-6}})
    for (bool swapped : {false, true}) {
      const std::string ctx = "offset " + c.o + ", gap " + c.g + (swapped ? " swapped" : "");
      auto a = q("(x - " + c.o + " - 1/3)^2 + (y - " + c.o + ")^2 = (z - " + c.o + " + 1)^2");
      auto b = q("x = " + c.o + " + 1/3 + (" + c.g + ")");
      if (swapped) std::swap(a, b);
      const auto r = trace::intersect_curve(a, b, Mode::Filtered, {});
      ASSERT_TRUE(r.affine.certified()) << ctx;
      EXPECT_EQ(*r.affine.unbounded_branches, 2) << ctx;
      EXPECT_EQ(*r.affine.lines, 0) << ctx;
      expect_certified_or_undecided(r, ctx);
      if (r.status != certify::Status::Certified) continue;
      ++certified;
      const double o = std::stod(c.o), ax = o + 1.0 / 3, az = o - 1;
      int upper = 0, lower = 0;
      for (const auto& br : r.branches) {
        EXPECT_NE(br.kind, "line") << ctx;
        int pos = 0, neg = 0;
        for (const auto& p : br.points) {
          const double d = std::sqrt((p[0] - ax) * (p[0] - ax) + (p[1] - o) * (p[1] - o) +
                                     (p[2] - az) * (p[2] - az));
          // On the hyperbola |z - az| >= gap (as (z - az)^2 = gap^2 + (y - o)^2): the nappe is
          // clear beyond half the gap from the apex (the automatic box frames the vertices,
          // ~gap from the apex, and may show nothing farther than 1e-9 from it).
          if (d <= 0.5 * c.gap) continue;
          (p[2] > az ? pos : neg) += 1;
        }
        EXPECT_TRUE(pos == 0 || neg == 0) << ctx << ": a branch on both nappes";
        upper += pos > 0 ? 1 : 0;
        lower += neg > 0 ? 1 : 0;
      }
      EXPECT_EQ(upper, 1) << ctx;
      EXPECT_EQ(lower, 1) << ctx;
    }
  EXPECT_GE(certified, 4); // at the origin the apex-frame retry draws the hyperbola
}

TEST(PictureCheck, ResidualAgainstTheCurvesSizeNotTheBox) {
  // audit id 6242 (cone and paraboloid near its apex, rotated, 1e9 out)
  const auto a = q("(-17/225)*x*x + (-88/45)*x*y + (-88/225)*x*z + (22480000000/9)*x + (1/9)*y*y + "
                   "(-16/45)*y*z + (18800000000/9)*y + (217/225)*z*z + (-10640000000/9)*z + "
                   "(-15320000000000000000/9)");
  const auto b =
      q("(-104/225)*x*x + (44/45)*x*y + (44/225)*x*z + (-11199999967/45)*x + (-5/9)*y*y + "
        "(8/45)*y*z + (-399999994/9)*y + (-221/225)*z*z + (71600000006/45)*z + "
        "(-584000001380000000000000000000000000009/900000000000000000000)");
  const auto r = trace::intersect_curve(a, b, Mode::Filtered, {});
  expect_certified_or_undecided(r, "6242");
  if (r.status == certify::Status::Certified) {
    EXPECT_LE(r.max_residual, 2e-6); // 16 ulps at 1e9
  }
}

TEST(PictureCheck, TinyLoopNextToAnApexIsNotDrawnWide) {
  // audit id 1703 (sphere against a cone, a loop of radius ~2^-100 at (1/3, 0, -1) rotated)
  const auto a =
      q("1*x*x + (-2/57)*x + 1*y*y + (12/19)*y + 1*z*z + (4/19)*z + (-12855504354071922204335696738"
        "752118530981732079489283340107785/14462442398330912479877658831070463422699826944045135517"
        "712384)");
  const auto b =
      q("(289/361)*x*x + (-144/361)*x*y + (408/361)*x*z + (34/57)*x + (289/361)*y*y + (408/361)*y*z"
        " + (24/19)*y + (-217/361)*z*z + (-30/19)*z + (-8/9)");
  const auto r = trace::intersect_curve(a, b, Mode::Filtered, {});
  expect_certified_or_undecided(r, "1703");
  if (r.status == certify::Status::Certified) {
    EXPECT_LE(r.max_residual, 1e-12);
  }
}

// A unit sphere in a cylinder of radius 1 - g, rotated by the integer quaternion (1, 2, 3, 4):
// two circles in the planes z' = +-sqrt(2g - g^2) of the cylinder's frame (2.8e-10 apart for
// g = 1e-20). The planes came from the eigenvectors of the rounded singular member, whose
// eigenvalue -(2g - g^2) sank into the rounding noise of its zero eigenvalues: circles drawn in
// planes tilted by 4.5e-9, half of each on either side, certified (helper-14: 32 answers).
// Certified with each circle on one side of z' = 0 beyond 1e-9 of the contact circle's plane,
// or undecided; g = 1e-10 (planes 2.8e-5 apart) must stay certified.
TEST(PictureCheck, NearDoubleConicPlanesAreNotNoise) {
  const long w = 1, x = 2, y = 3, z = 4, n = w * w + x * x + y * y + z * z;
  // The cylinder's axis R e_z (the rotation x -> R x of motion()).
  const double axis[3] = {2.0 * (x * z + w * y) / n, 2.0 * (y * z - w * x) / n,
                          static_cast<double>(w * w - x * x - y * y + z * z) / n};
  for (const std::string g :
       {"1/10000000000", "1/100000000000000000000", "1/1152921504606846976"}) {
    const auto m = surfcert::testing::motion(w, x, y, z, {});
    const auto a = q("x^2 + y^2 + z^2 = 1").congruent(m);
    const auto b = q("x^2 + y^2 = (1 - " + g + ")^2").congruent(m);
    const auto r = trace::intersect_curve(a, b, Mode::Filtered, {});
    const std::string ctx = "g = " + g;
    expect_certified_or_undecided(r, ctx);
    if (g == "1/10000000000") {
      EXPECT_EQ(r.status, certify::Status::Certified) << ctx;
    }
    if (r.status != certify::Status::Certified) continue;
    ASSERT_EQ(r.branches.size(), 2u) << ctx;
    int above = 0, below = 0;
    for (const auto& br : r.branches) {
      int pos = 0, neg = 0;
      for (const auto& p : br.points) {
        const double h = p[0] * axis[0] + p[1] * axis[1] + p[2] * axis[2];
        pos += h > 1e-15 ? 1 : 0;
        neg += h < -1e-15 ? 1 : 0;
      }
      EXPECT_TRUE(pos == 0 || neg == 0) << ctx << ": a circle on both sides";
      above += pos > 0 ? 1 : 0;
      below += neg > 0 ? 1 : 0;
    }
    EXPECT_EQ(above, 1) << ctx;
    EXPECT_EQ(below, 1) << ctx;
  }
}
