// Open double conics in a box (issue 15's degenerate inputs: surfaces tangent along a
// hyperbola or a parabola). Along a double conic f = g = 0 is singular on a face: every
// crossing is a double root of the face's crossing polynomial ("a multiple crossing", not
// certified) and Newton on f = g = 0 there does not converge (pieces ending inside the box),
// so all such pairs were undecided (33 of 33 answers of an audit of general quadric pairs).
// Now the exact crossings are those of the double plane (the rank-1 member, exact) with one
// surface, and the pieces are cut on {face, plane, surface}. Each pair is the closed form
// B = A + c (plane)^2, posed by five rational motions, both orders: certified near the origin,
// one open double conic per unbounded branch, every point on the double plane and on both
// exact surfaces, every exact crossing used once.
#include "support/posed_pairs.hpp"
#include "support/trace_boxes.hpp"

#include "surfcert/trace/intersect_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>

using namespace surfcert;
using certify::Mode;
using surfcert::testing::certified_or_undecided;
using surfcert::testing::geometric_residual;

TEST(DoubleConicBox, TangentAlongAHyperbolaOrAParabola) {
  struct Case {
    std::string a, b;
    int unbounded;
    std::function<double(const std::array<double, 3>&)> off_plane; // local coordinates
  };
  const std::vector<Case> cases = {
      // 9x^2 + 4y^2 - 36z^2 = 36 and B - A = 72 (x - 1)^2: the hyperbola 4y^2 - 36z^2 = 27, x = 1
      {"9*x^2 + 4*y^2 - 36*z^2 = 36", "81*x^2 + 4*y^2 - 36*z^2 - 144*x + 36 = 0", 2,
       [](const std::array<double, 3>& p) { return std::fabs(p[0] - 1); }},
      // 9x^2 - 4y^2 = 36z and B - A = 36 (z - 1)^2: the hyperbola 9x^2 - 4y^2 = 36, z = 1
      {"9*x^2 - 4*y^2 = 36*z", "9*x^2 - 4*y^2 + 36*z^2 - 108*z + 36 = 0", 2,
       [](const std::array<double, 3>& p) { return std::fabs(p[2] - 1); }},
      // 9x^2 - 4y^2 = 36z and B - A = 36 (x - 1)^2: the parabola 9 - 4y^2 = 36z, x = 1
      {"9*x^2 - 4*y^2 = 36*z", "45*x^2 - 4*y^2 - 72*x - 36*z + 36 = 0", 1,
       [](const std::array<double, 3>& p) { return std::fabs(p[0] - 1); }}};
  int certified = 0, tried = 0;
  for (const auto& cs : cases)
    for (const auto& ps : surfcert::testing::five_poses())
      for (bool swapped : {false, true}) {
        const std::string ctx = cs.a + " | " + cs.b + ", " + ps.name("-", swapped);
        const auto [a, b] = surfcert::testing::posed_pair(cs.a, cs.b, ps, swapped);
        const auto r = trace::intersect_curve(a, b, Mode::Exact, {});
        ++tried;
        ASSERT_TRUE(r.affine.certified()) << ctx;
        EXPECT_EQ(*r.affine.loops, 0) << ctx;
        EXPECT_EQ(*r.affine.unbounded_branches, cs.unbounded) << ctx;
        if (!certified_or_undecided(r, true, ctx)) continue;
        ++certified;
        ASSERT_EQ(static_cast<int>(r.branches.size()), cs.unbounded) << ctx;
        ASSERT_TRUE(r.box && r.box_exits && r.box_exits->certified) << ctx;
        ASSERT_EQ(static_cast<int>(r.box_exits->points.size()), 2 * cs.unbounded) << ctx;
        const double size = r.box->diagonal();
        std::set<int> used;
        for (const auto& br : r.branches) {
          EXPECT_EQ(br.kind, "double_conic") << ctx;
          EXPECT_FALSE(br.closed) << ctx;
          ASSERT_EQ(br.exits.size(), 2u) << ctx;
          used.insert(br.exits.begin(), br.exits.end());
          for (const auto& p : br.points) {
            const double ulps = 0x1p-46 * (std::fabs(p[0]) + std::fabs(p[1]) + std::fabs(p[2]));
            EXPECT_LE(cs.off_plane(ps.local(p)), 1e-12 * size + ulps) << ctx;
            EXPECT_LE(geometric_residual(a, p), 1e-12 * size + ulps) << ctx;
            EXPECT_LE(geometric_residual(b, p), 1e-12 * size + ulps) << ctx;
          }
        }
        EXPECT_EQ(static_cast<int>(used.size()), 2 * cs.unbounded) << ctx;
      }
  EXPECT_EQ(tried, 30);
  EXPECT_EQ(certified, 30);
}
