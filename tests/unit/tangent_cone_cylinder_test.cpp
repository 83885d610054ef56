// A cone and a cylinder tangent to it (issue 15; Open CASCADE emits two overlapping curves for
// such pairs). Two kinds, each posed by rational rigid motions:
//  - the cylinder (x - 1)^2 + y^2 = 1 through the apex of x^2 + y^2 = z^2, tangent there: the
//    curve is z^2 = 2x on the cylinder, a figure eight with its node at the apex, one
//    connected bounded component (closed form: 1 loop, 0 unbounded branches, no box exit in a
//    box holding it: its points have norm <= 3, the motions below add <= 2.3, so [-6, 6]^3);
//  - a cylinder tangent to the cone along the ruling (t, 0, t): axis (s, 0, -s) + t (1, 0, 1),
//    radius^2 = 2 s^2, s = +-1. By hand, cylinder - cone = -(u / 2)(x + 3z + 4 s) with
//    u = x - z: the curve is that ruling counted twice plus the ellipse 8 (z + 3s/2)^2 + y^2 = 2
//    in the plane x + 3z = -4s, touching the ruling at (-s, 0, -s). Certified only with one
//    line and one conic; otherwise undecided with a reason.
// Never a wrong certified count.
#include "support/distance_checks.hpp"
#include "support/trace_boxes.hpp"

#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

using namespace surfcert;
using certify::Mode;
using core::Rational;
using surfcert::testing::given_box;
using surfcert::testing::motion;
using surfcert::testing::q;

namespace {

std::vector<core::Mat4> poses() {
  return {motion(1, 0, 0, 0, {}),
          motion(1, 2, 2, -1, {Rational(3, 2), Rational(-1), Rational(5, 4)}),
          motion(2, -1, 1, 1, {Rational(-1, 2), Rational(1), Rational(1, 4)}),
          motion(1, 1, 1, 1, {Rational(1, 3), Rational(0), Rational(-1)}),
          motion(3, 0, 4, 0, {Rational(0), Rational(1, 2), Rational(0)}),
          motion(0, 1, 2, 2, {Rational(1), Rational(1), Rational(1)})};
}

} // namespace

TEST(TangentConeCylinder, CylinderThroughTheApex) {
  const auto cone = q("x^2 + y^2 = z^2"), cyl = q("(x - 1)^2 + y^2 = 1");
  int pose = 0, certified = 0;
  for (const auto& m : poses()) {
    ++pose;
    for (bool swapped : {false, true})
      for (bool automatic : {true, false}) {
        const std::string ctx = "pose " + std::to_string(pose) + (swapped ? " swapped" : "") +
                                (automatic ? " automatic box" : " box [-6, 6]^3");
        auto a = cone.congruent(m), b = cyl.congruent(m);
        if (swapped) std::swap(a, b);
        const auto r = trace::intersect_curve(a, b, Mode::Exact,
                                              automatic ? trace::TraceOptions{}
                                                        : given_box({-6, -6, -6}, {6, 6, 6}));
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 1) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, 0) << ctx;
        EXPECT_EQ(*r.affine.isolated_points, 0) << ctx;
        if (r.status != certify::Status::Certified) {
          EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
          EXPECT_FALSE(r.note.empty()) << ctx;
          continue;
        }
        ++certified;
        int closed = 0;
        for (const auto& br : r.branches)
          closed += br.closed ? 1 : 0;
        EXPECT_EQ(closed, 1) << ctx;
        EXPECT_EQ(r.branches.size(), 1u) << ctx;
        ASSERT_TRUE(r.box_exits && r.box_exits->certified) << ctx;
        EXPECT_TRUE(r.box_exits->points.empty()) << ctx;
      }
  }
  EXPECT_GE(certified, 1); // the canonical pose at least
}

TEST(TangentConeCylinder, TangentAlongARuling) {
  const auto cone = q("x^2 + y^2 = z^2");
  const std::vector<std::string> cylinders = {"(x - 1)^2 + y^2 + (z + 1)^2 - (x + z)^2/2 = 2",
                                              "(x + 1)^2 + y^2 + (z - 1)^2 - (x + z)^2/2 = 2"};
  int pose = 0;
  for (const auto& m : poses()) {
    ++pose;
    for (const auto& c : cylinders)
      for (bool swapped : {false, true}) {
        const std::string ctx =
            "pose " + std::to_string(pose) + ", " + c + (swapped ? " swapped" : "");
        auto a = cone.congruent(m), b = q(c).congruent(m);
        if (swapped) std::swap(a, b);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        if (r.status == certify::Status::Certified) {
          ASSERT_TRUE(r.affine.certified()) << ctx;
          EXPECT_EQ(*r.affine.lines, 1) << ctx;
          EXPECT_EQ(*r.affine.conics, 1) << ctx;
        } else {
          EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
          EXPECT_FALSE(r.note.empty()) << ctx;
        }
        // A certified affine reading, when given, has the line and the conic.
        if (r.affine.certified()) {
          EXPECT_EQ(*r.affine.lines, 1) << ctx;
          EXPECT_EQ(*r.affine.conics, 1) << ctx;
        }
      }
  }
}

// The cylinder (x - 1 - g)^2 + y^2 = 1 passing the apex of x^2 + y^2 = z^2 at a gap g of either
// sign: two loops, one on each nappe (for g > 0 they come within about g of each other near the
// apex, where each turns by 90 degrees within a length of about g; for g < 0 the apex is inside
// the cylinder and the loops span |z| in [|g|, 2 - |g|]). The walks must step down to the gap's
// scale to pass there: with a step floor of 1e-11 of the scene every such pair was undecided
// (two open arcs), posed at the origin or 2^20 out alike. Checked against the closed form: two
// closed loops, each wholly on one nappe (the sign of (p - apex) . axis), each reaching the
// apex within the tolerance. Rotations about the apex keep the neck at the origin, where
// doubles are dense; after a translation the tracer retries in the frame of the apex (at
// |c| ~ 1 the rounded cone is a hyperboloid with a waist ~1e-8, and a walk there followed it
// from one nappe to the other: two "loops" each made of halves of both, certified before):
// every gap down to 2^-100 must be certified when the apex is a double; the apex (1/3, 0, -1)
// is not, and a neck below ~1e-30 next to its rounding may stay undecided (with a reason),
// never a wrong loop.
TEST(TangentConeCylinder, CylinderPassingTheApexByAGap) {
  const auto cone = q("x^2 + y^2 = z^2");
  struct Pose {
    long w, x, y, z;
    std::array<Rational, 3> t;
    bool must_certify;
  };
  const std::vector<Pose> poses = {
      {1, 0, 0, 0, {}, true},
      {1, 2, 2, -1, {}, true},
      {3, 0, 4, 0, {}, true},
      {1, 1, 1, 1, {Rational(1, 3), Rational(0), Rational(-1)}, false},
      {2, -1, 1, 1, {Rational(-1, 2), Rational(1), Rational(1, 4)}, true}};
  const std::vector<std::string> gaps = {
      "1/10000000000",           "-1/10000000000",
      "1/100000000000000000000", "-1/100000000000000000000",
      "1/1152921504606846976",                                         // 2^-60
      "-1/1152921504606846976",  "1/1267650600228229401496703205376"}; // 2^-100
  int certified = 0, tried = 0;
  for (const auto& g : gaps)
    for (const auto& ps : poses)
      for (bool swapped : {false, true}) {
        const std::string ctx = "gap " + g + ", pose (" + std::to_string(ps.w) + "," +
                                std::to_string(ps.x) + "," + std::to_string(ps.y) + "," +
                                std::to_string(ps.z) + ")" + (swapped ? " swapped" : "");
        const auto m = motion(ps.w, ps.x, ps.y, ps.z, ps.t);
        auto a = cone.congruent(m), b = q("(x - 1 - (" + g + "))^2 + y^2 = 1").congruent(m);
        if (swapped) std::swap(a, b);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        ++tried;
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 2) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, 0) << ctx;
        if (r.status != certify::Status::Certified) {
          EXPECT_FALSE(ps.must_certify) << ctx << ": " << r.note;
          EXPECT_EQ(r.status, certify::Status::Undecided) << ctx;
          EXPECT_FALSE(r.note.empty()) << ctx;
          continue;
        }
        ++certified;
        ASSERT_EQ(r.branches.size(), 2u) << ctx;
        // The moved axis R e_z and apex t (doubles: enough for the signs checked here).
        const double n = static_cast<double>(ps.w * ps.w + ps.x * ps.x + ps.y * ps.y + ps.z * ps.z);
        const double axis[3] = {2.0 * (ps.x * ps.z + ps.w * ps.y) / n,
                                2.0 * (ps.y * ps.z - ps.w * ps.x) / n,
                                (ps.w * ps.w - ps.x * ps.x - ps.y * ps.y + ps.z * ps.z) / n};
        const double apex[3] = {ps.t[0].to_double_approx(), ps.t[1].to_double_approx(),
                                ps.t[2].to_double_approx()};
        // Points within the doubles' reach of the apex's plane count for either nappe.
        const double slack = ps.must_certify ? 0.0 : 1e-12;
        int upper = 0, lower = 0;
        for (const auto& br : r.branches) {
          EXPECT_TRUE(br.closed) << ctx;
          int pos = 0, neg = 0;
          double nearest = 1e300;
          for (const auto& p : br.points) {
            double h = 0, d2 = 0;
            for (size_t k = 0; k < 3; ++k) {
              h += (p[k] - apex[k]) * axis[k];
              d2 += (p[k] - apex[k]) * (p[k] - apex[k]);
            }
            pos += h > slack ? 1 : 0;
            neg += h < -slack ? 1 : 0;
            nearest = std::min(nearest, std::sqrt(d2));
          }
          EXPECT_TRUE(pos == 0 || neg == 0) << ctx << ": a loop on both nappes";
          upper += pos > 0 ? 1 : 0;
          lower += neg > 0 ? 1 : 0;
          // The loop reaches the apex (|g| away) within the tolerance 2e-4 of its size (~3).
          EXPECT_LE(nearest, 1e-3) << ctx;
        }
        EXPECT_EQ(upper, 1) << ctx;
        EXPECT_EQ(lower, 1) << ctx;
        EXPECT_LE(r.max_residual, 1e-12) << ctx;
      }
  EXPECT_EQ(tried, 70);
  EXPECT_GE(certified, 56); // every pose with a double apex, both orders, every gap
}

// The same pair far out: x - o, y - o, z - o for o = 2^20 (dyadic) and 12345.678 (not a double:
// the apex is translated to its rounding, ~1e-12 off). The tracer reaches the apex's frame
// through the far-pair translation and the retry; certified with one loop per nappe (slack:
// four ulps of o), max_residual within the doubles' spacing out there.
TEST(TangentConeCylinder, FarCylinderPassingTheApexByAGap) {
  for (const std::string o : {"1048576", "12345.678"})
    for (const std::string g : {"1/10000000000", "-1/10000000000", "1/100000000000000000000"})
      for (bool swapped : {false, true}) {
        const std::string ctx = "offset " + o + ", gap " + g + (swapped ? " swapped" : "");
        auto a = q("(x - " + o + ")^2 + (y - " + o + ")^2 = (z - " + o + ")^2");
        auto b = q("(x - " + o + " - 1 - (" + g + "))^2 + (y - " + o + ")^2 = 1");
        if (swapped) std::swap(a, b);
        const auto r = trace::intersect_curve(a, b, Mode::Filtered, {});
        ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
        ASSERT_EQ(r.branches.size(), 2u) << ctx;
        const double oz = std::stod(o), slack = 4 * std::ldexp(1.0, std::ilogb(oz) - 52);
        int upper = 0, lower = 0;
        for (const auto& br : r.branches) {
          EXPECT_TRUE(br.closed) << ctx;
          int pos = 0, neg = 0;
          for (const auto& p : br.points) {
            pos += p[2] - oz > slack ? 1 : 0;
            neg += p[2] - oz < -slack ? 1 : 0;
          }
          EXPECT_TRUE(pos == 0 || neg == 0) << ctx << ": a loop on both nappes";
          upper += pos > 0 ? 1 : 0;
          lower += neg > 0 ? 1 : 0;
        }
        EXPECT_EQ(upper, 1) << ctx;
        EXPECT_EQ(lower, 1) << ctx;
        EXPECT_LE(r.max_residual, 2 * slack) << ctx;
      }
}

// The user's path: a cone and a cylinder given as shapes posed in doubles (a random double unit
// quaternion, the apex c in [-1, 1]^3 or 1000.25 + [-1, 1]^3, the cylinder's axis parallel to
// the cone's, its centre c + R (1 + g, 0, 0) in doubles): the exact reading passes the apex by
// about g. 7 of 40 such pairs (g = 1e-9, 1e-12) were certified with loops made of both nappes
// (the walk crossed in the rounded cone's waist, ~1e-8 wide at |c| ~ 1), 22 more were
// undecided; the retry in the apex's frame needs the exact translation (not the one that keeps
// double-posed shapes lazy, which left the apex up to ~1 off the origin). Certified, each loop
// on one nappe: no point farther than 1e-9 from the apex on the other side ((p - c) . axis,
// axis = R e_z in doubles: the walk may cut the neck within the tolerance).
TEST(TangentConeCylinder, DoublePosedShapesPassingTheApex) {
  std::mt19937_64 rng(20261202);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(-1, 1);
  int pairs = 0;
  for (double offset : {0.0, 1000.25})
    for (double g : {1e-9, 1e-12})
      for (int k = 0; k < 10; ++k) {
        double qv[4];
        double n = 0;
        for (double& v : qv)
          v = gauss(rng), n += v * v;
        n = std::sqrt(n);
        for (double& v : qv)
          v /= n;
        const double w = qv[0], x = qv[1], y = qv[2], z = qv[3];
        const double r[3][3] = {
            {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
        double c[3], cc[3], axis[3];
        for (size_t i = 0; i < 3; ++i) {
          c[i] = offset + unit(rng);
          cc[i] = c[i] + r[i][0] * (1 + g);
          axis[i] = r[i][2];
        }
        char buf[1024];
        std::snprintf(buf, sizeof buf,
                      "{\"type\": \"%s\", \"center\": [%.17g, %.17g, %.17g], %s, "
                      "\"rotation\": {\"quaternion\": [%.17g, %.17g, %.17g, %.17g]}}",
                      "cone", c[0], c[1], c[2], "\"radii\": [1, 1, 1]", w, x, y, z);
        const std::string cone_json = buf;
        std::snprintf(buf, sizeof buf,
                      "{\"type\": \"%s\", \"center\": [%.17g, %.17g, %.17g], %s, "
                      "\"rotation\": {\"quaternion\": [%.17g, %.17g, %.17g, %.17g]}}",
                      "cylinder", cc[0], cc[1], cc[2], "\"radius\": 1", w, x, y, z);
        const std::string cyl_json = buf;
        auto read = [](const std::string& j) {
          return core::io::read_quadric(core::io::parse_json(j, "t"), "t", "$");
        };
        const std::string ctx = cone_json + " & " + cyl_json;
        const auto r2 = trace::intersect_curve(read(cone_json), read(cyl_json), Mode::Filtered, {});
        ++pairs;
        ASSERT_EQ(r2.status, certify::Status::Certified) << ctx << ": " << r2.note;
        ASSERT_EQ(r2.branches.size(), 2u) << ctx;
        int upper = 0, lower = 0;
        for (const auto& br : r2.branches) {
          EXPECT_TRUE(br.closed) << ctx;
          int pos = 0, neg = 0;
          for (const auto& p : br.points) {
            double h = 0, d2 = 0;
            for (size_t i = 0; i < 3; ++i) {
              h += (p[i] - c[i]) * axis[i];
              d2 += (p[i] - c[i]) * (p[i] - c[i]);
            }
            if (std::sqrt(d2) <= 1e-9) continue; // the neck, cut within the tolerance
            (h > 0 ? pos : neg) += 1;
          }
          EXPECT_TRUE(pos == 0 || neg == 0) << ctx << ": a loop on both nappes";
          upper += pos > 0 ? 1 : 0;
          lower += neg > 0 ? 1 : 0;
        }
        EXPECT_EQ(upper, 1) << ctx;
        EXPECT_EQ(lower, 1) << ctx;
      }
  EXPECT_EQ(pairs, 40);
}
