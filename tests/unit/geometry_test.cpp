// Readable pairs with a known geometric meaning (research qsic-classification §4.2-4.3):
// case, ellipsoid relation, and exact special points checked independently (each point lies
// on both surfaces and the gradients there are parallel: a singular point of the curve).
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <gtest/gtest.h>

using namespace surfcert;
using certify::Mode;
using core::Rational;

namespace {

core::QuadricMatrix q(const std::string& s) {
  return core::io::quadric_from_equation(s, {"test", 1, 1, ""});
}

certify::QsicResult run(const std::string& a, const std::string& b, Mode m = Mode::Exact) {
  auto qa = q(a), qb = q(b);
  auto r = certify::classify_qsic(qa, qb, m);
  certify::complete_report_data(r, qa, qb);
  return r;
}

// Exact checks for a rational special point: on both quadrics, gradients parallel.
void expect_singular_on_both(const std::string& a, const std::string& b,
                             const certify::SpecialPoint& p) {
  ASSERT_TRUE(p.exact);
  std::array<Rational, 3> x;
  for (size_t i = 0; i < 3; ++i) {
    auto v = Rational::from_string(p.coords[i]);
    ASSERT_TRUE(v.has_value()) << "not rational: " << p.coords[i];
    x[i] = *v;
  }
  auto pa = q(a).to_poly(), pb = q(b).to_poly();
  EXPECT_TRUE(pa.evaluate(x[0], x[1], x[2]).is_zero()) << p.kind;
  EXPECT_TRUE(pb.evaluate(x[0], x[1], x[2]).is_zero()) << p.kind;
  auto grad = [&](const core::Poly3& f) {
    std::array<Rational, 3> g;
    for (const auto& [e, c] : f.terms())
      for (int v = 0; v < 3; ++v) {
        if (e[static_cast<size_t>(v)] == 0) continue;
        Rational t = c * Rational(e[static_cast<size_t>(v)]);
        for (int w = 0; w < 3; ++w)
          for (int k = 0; k < e[static_cast<size_t>(w)] - (w == v ? 1 : 0); ++k)
            t *= x[static_cast<size_t>(w)];
        g[static_cast<size_t>(v)] += t;
      }
    return g;
  };
  auto ga = grad(pa), gb = grad(pb);
  EXPECT_TRUE((ga[1] * gb[2] - ga[2] * gb[1]).is_zero());
  EXPECT_TRUE((ga[2] * gb[0] - ga[0] * gb[2]).is_zero());
  EXPECT_TRUE((ga[0] * gb[1] - ga[1] * gb[0]).is_zero());
}

bool has_point(const certify::QsicResult& r, const std::array<double, 3>& p) {
  for (const auto& s : r.special_points)
    if (std::abs(s.approx[0] - p[0]) < 1e-12 && std::abs(s.approx[1] - p[1]) < 1e-12 &&
        std::abs(s.approx[2] - p[2]) < 1e-12)
      return true;
  return false;
}

struct Case {
  const char* a;
  const char* b;
  int tu_case;
  const char* relation;
};

} // namespace

TEST(Geometry, SpheresAndEllipsoidsWithKnownRelations) {
  const Case cases[] = {
      {"x^2+y^2+z^2=1", "(x-3)^2+y^2+z^2=1", 16, "separated"},
      {"x^2+y^2+z^2=1", "(x-2)^2+y^2+z^2=1", 25, "externally_touching"},
      {"x^2+y^2+z^2=1", "(x-1)^2+y^2+z^2=1", 17, "overlapping"},
      {"x^2+y^2+z^2=9", "x^2+y^2+z^2=1", 22, "nested"},
      {"x^2+y^2+z^2=9", "(x-1)^2+y^2+z^2=1", 16, "nested"},
      {"x^2+y^2+z^2=9", "(x-2)^2+y^2+z^2=1", 25, "internally_touching"},
      {"x^2+y^2+z^2=1", "x^2/4+y^2+z^2=1", 21, "internally_touching"},
      {"x^2+y^2+z^2=1", "x^2/4+y^2/9+z^2=1", 15, "internally_touching"},
      {"x^2+y^2+z^2=1", "x^2/4+y^2/4+z^2=1", 30, "internally_touching"},
      {"x^2/4+y^2+z^2=1", "x^2+y^2/4+z^2=1", 13, "overlapping"},
      {"x^2/4+y^2+z^2=1", "(x-1)^2+y^2+z^2/4=1", 6, "overlapping"},
      {"x^2/4+y^2+z^2=1", "(x-2)^2+y^2+z^2/4=1", 3, "overlapping"},
      {"x^2/4+y^2+z^2=1", "(x-3)^2+y^2+z^2/4=1", 7, "externally_touching"},
      {"4x^2+y^2+z^2=1", "(x+5/2)^2/4+y^2/4+z^2/9=1", 7, "externally_touching"},
      {"4x^2+y^2+z^2=1", "(x-3/2)^2/4+y^2/4+z^2/9=1", 20, "internally_touching"},
      {"x^2+y^2+(z-1)^2=1", "x^2+y^2+2z^2+2z=0", 25, "externally_touching"},
      {"x^2+y^2+(z-1)^2=1", "2x^2+y^2+z^2-yz-2z=0", 9, "overlapping"},
      {"x^2+y^2+(z-1)^2=1", "x^2+y^2+z^2+xz-2z=0", 27, "overlapping"},
      {"x^2+y^2+(z-1)^2=1", "x^2+y^2+2z^2-2z=0", 33, "internally_touching"},
  };
  for (const auto& c : cases)
    for (Mode m : {Mode::Exact, Mode::Filtered}) {
      auto r = run(c.a, c.b, m);
      ASSERT_EQ(r.status, certify::Status::Certified);
      EXPECT_EQ(r.tu_case, c.tu_case) << c.a << " | " << c.b;
      EXPECT_EQ(r.ellipsoid_relation, c.relation) << c.a << " | " << c.b;
      // Swapping the surfaces changes neither the case nor the relation.
      auto s = run(c.b, c.a, m);
      EXPECT_EQ(s.tu_case, c.tu_case) << "swapped " << c.a << " | " << c.b;
      EXPECT_EQ(s.ellipsoid_relation, c.relation) << "swapped " << c.a << " | " << c.b;
      for (const auto& p : r.special_points)
        expect_singular_on_both(c.a, c.b, p);
    }
}

TEST(Geometry, NestedContainment) {
  EXPECT_EQ(run("x^2+y^2+z^2=9", "(x-1)^2+y^2+z^2=1").containment, "b_inside_a");
  EXPECT_EQ(run("(x-1)^2+y^2+z^2=1", "x^2+y^2+z^2=9").containment, "a_inside_b");
}

TEST(Geometry, SpecialPointsOfReadableFixtures) {
  // research §4.3: case 5 crunode (0,-1,0); case 6 acnode (2,0,0); case 7 contact (2,0,0);
  // case 13 crossings (0,0,+-1); case 15 points (0,0,+-1); case 25 touching point (1,0,0).
  auto r5 = run("x^2+y^2+4z^2/9=1", "x^2/4+(y-1)^2/4+z^2=1");
  EXPECT_EQ(r5.tu_case, 5);
  ASSERT_EQ(r5.special_points.size(), 1u);
  EXPECT_EQ(r5.special_points[0].kind, "crunode");
  EXPECT_TRUE(has_point(r5, {0, -1, 0}));
  auto r6 = run("x^2/4+y^2+z^2=1", "(x-1)^2+y^2+z^2/4=1");
  ASSERT_EQ(r6.special_points.size(), 1u);
  EXPECT_EQ(r6.special_points[0].kind, "acnode");
  EXPECT_TRUE(has_point(r6, {2, 0, 0}));
  auto r7 = run("x^2/4+y^2+z^2=1", "(x-3)^2+y^2+z^2/4=1");
  ASSERT_EQ(r7.special_points.size(), 1u);
  EXPECT_TRUE(has_point(r7, {2, 0, 0}));
  auto r13 = run("x^2/4+y^2+z^2=1", "x^2+y^2/4+z^2=1");
  ASSERT_EQ(r13.special_points.size(), 2u);
  EXPECT_TRUE(has_point(r13, {0, 0, 1}));
  EXPECT_TRUE(has_point(r13, {0, 0, -1}));
  auto r15 = run("x^2+y^2+z^2=1", "x^2/4+y^2/9+z^2=1");
  ASSERT_EQ(r15.special_points.size(), 2u);
  EXPECT_TRUE(has_point(r15, {0, 0, 1}));
  EXPECT_TRUE(has_point(r15, {0, 0, -1}));
  auto r25 = run("x^2+y^2+z^2=1", "(x-2)^2+y^2+z^2=1");
  ASSERT_EQ(r25.special_points.size(), 1u);
  EXPECT_TRUE(has_point(r25, {1, 0, 0}));
}

TEST(Geometry, IrrationalSpecialPoints) {
  // Case 13 stretched along z: the conics cross at (0, 0, +-c) for the semi-axis c.
  auto r = run("x^2/4+y^2+z^2/4=1", "x^2+y^2/4+z^2/4=1");
  EXPECT_EQ(r.tu_case, 13);
  EXPECT_TRUE(has_point(r, {0, 0, 2}));
  // Crossings at z = +-sqrt(2): irrational coordinates in Q(sqrt 2).
  auto s = run("x^2/4+y^2+z^2/2=1", "x^2+y^2/4+z^2/2=1");
  EXPECT_EQ(s.tu_case, 13);
  ASSERT_EQ(s.special_points.size(), 2u);
  for (const auto& p : s.special_points) {
    EXPECT_NE(p.coords[2].find("sqrt(2)"), std::string::npos) << p.coords[2];
    EXPECT_NEAR(std::abs(p.approx[2]), std::sqrt(2.0), 1e-15);
  }
}

TEST(Geometry, TuWorkedExampleCase17) {
  auto r = run("20x^2 - 12xy + 48xz + 76x + 16y^2 - 16yz - 12y + 42z^2 + 72z + 58",
               "28x^2 + 16xy + 80xz + 56x + 2y^2 + 24yz + 20y + 56z^2 + 72z + 14");
  EXPECT_EQ(r.tu_case, 17);
  EXPECT_EQ(r.segre, "[(11)11]");
}

TEST(Geometry, DegenerateAndCoincidentPencils) {
  auto d = run("x^2+y^2=1", "(x-1)^2+y^2=1"); // parallel cylinders: det(lA - B) == 0
  EXPECT_EQ(d.pencil, algebra::PencilKind::Degenerate);
  EXPECT_EQ(d.status, certify::Status::Certified);
  auto c = run("x^2+y^2+z^2=1", "2x^2+2y^2+2z^2-2=0");
  EXPECT_EQ(c.pencil, algebra::PencilKind::Coincident);
  auto cones = run("x^2+y^2-z^2", "x^2-y^2+z^2"); // cones with a common apex
  EXPECT_EQ(cones.pencil, algebra::PencilKind::Degenerate);
}

TEST(Geometry, SingularFirstQuadricIsRebased) {
  // A is a cylinder (det A = 0): the pencil is re-based, the case is unchanged by swapping.
  auto r = run("x^2+y^2=1", "x^2/4+y^2/4+z^2=1");
  auto s = run("x^2/4+y^2/4+z^2=1", "x^2+y^2=1");
  EXPECT_TRUE(r.facts.rebased);
  EXPECT_FALSE(s.facts.rebased);
  EXPECT_EQ(r.tu_case, s.tu_case);
  EXPECT_EQ(r.tu_case, 14); // closed form: two disjoint circles x^2+y^2=1 at z = +-sqrt(3)/2
}

// kind() against the inertia known by construction: P^T diag(d) P with P an affine map (the
// last row (0, 0, 0, 1): the 3x3 block and its definiteness are carried along) and a nonzero
// rational factor of either sign. Every sign pattern of the four diagonal entries, zeros too,
// so each leading minor of the posed block is met positive, negative and zero.
TEST(Geometry, QuadricKindFromTheInertiaByConstruction) {
  unsigned long long seed = 88172645463325252ull;
  auto next = [&seed](int lo, int hi) {
    seed ^= seed << 13;
    seed ^= seed >> 7;
    seed ^= seed << 17;
    return lo + static_cast<int>(seed % static_cast<unsigned long long>(hi - lo + 1));
  };
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::array<int, 4> d{};
    for (int& x : d)
      x = next(-1, 1) * next(1, 5);
    core::Mat4 p{}, m{};
    Rational det3(0);
    while (det3.is_zero()) {
      for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j)
          p[i][j] = Rational(next(-4, 4));
      det3 = p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
             p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
             p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
    }
    for (size_t i = 0; i < 3; ++i)
      p[i][3] = Rational(next(-9, 9), next(1, 7));
    p[3][3] = Rational(1);
    for (size_t i = 0; i < 4; ++i)
      m[i][i] = Rational(d[i]);
    if (d == std::array<int, 4>{}) continue;
    const Rational factor(next(1, 9) * (next(0, 1) ? 1 : -1), next(1, 5));
    core::Mat4 posed = core::congruence(p, m);
    for (auto& row : posed)
      for (auto& x : row)
        x = x * factor;
    // Expected: the block diag(d0, d1, d2) definite and d3 of the opposite sign: a real
    // ellipsoid; of the same sign: no real point; anything else (d3 = 0 included): other.
    const int s0 = (d[0] > 0) - (d[0] < 0), s1 = (d[1] > 0) - (d[1] < 0),
              s2 = (d[2] > 0) - (d[2] < 0), s3 = (d[3] > 0) - (d[3] < 0);
    core::QuadricKind want = core::QuadricKind::Other;
    if (s0 != 0 && s0 == s1 && s1 == s2 && s3 != 0)
      want = s3 == -s0 ? core::QuadricKind::Ellipsoid : core::QuadricKind::ImaginaryEllipsoid;
    EXPECT_EQ(core::QuadricMatrix(posed).kind(), want)
        << "trial " << trial << " d " << d[0] << " " << d[1] << " " << d[2] << " " << d[3];
    ++checked;
  }
  EXPECT_GT(checked, 350);
}
