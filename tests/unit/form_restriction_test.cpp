// The exact sums over common denominators (core::over_common_denominator: integer sums, one
// canonicalisation per entry): algebra::restrict_form and algebra::bilinear over core::Rational
// against the plain rational sums written out here, and core::congruence against
// transpose(p) * m * p by core's rational matrix products, on random rationals with unrelated,
// shared and unit denominators, zeros, and the ~150-digit entries of a quadric posed in
// doubles; over double the template's own sums; core::integer_multiple (the positive lcm
// multiple the exact box crossings and plane sections work on).
#include "support/canonical.hpp"

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/shape.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <string>

using namespace surfcert;
using core::Integer;
using core::Rational;

namespace {

// A random rational: zero, an integer, a fraction with a small or a large denominator, or one
// over a denominator shared with others (`shared`), signs mixed.
Rational random_rational(std::mt19937_64& rng, const Rational& shared) {
  std::uniform_int_distribution<int> kind(0, 5);
  std::uniform_int_distribution<long> small(-40, 40);
  std::uniform_int_distribution<unsigned long> den(1, 1000);
  switch (kind(rng)) {
  case 0:
    return Rational(0);
  case 1:
    return Rational(small(rng));
  case 2:
    return Rational(small(rng), den(rng));
  case 3: { // a large numerator and denominator (~60 digits each)
    Rational x(1);
    for (int i = 0; i < 6; ++i)
      x = x * Rational(static_cast<long>(den(rng)) * 1000003 + 1, den(rng) * 999983 + 7);
    return small(rng) % 2 ? x : -x;
  }
  case 4:
    return shared * Rational(small(rng));
  default:
    return Rational::exact_from_double(std::ldexp(static_cast<double>(small(rng)), -60));
  }
}

template <size_t N, size_t M>
void expect_restriction_equals_plain_sums(const std::array<std::array<Rational, N>, N>& q,
                                          const std::array<std::array<Rational, N>, M>& cols) {
  const auto r = algebra::restrict_form(q, cols);
  for (size_t i = 0; i < M; ++i)
    for (size_t j = 0; j < M; ++j) {
      Rational s;
      for (size_t a = 0; a < N; ++a)
        for (size_t b = 0; b < N; ++b)
          s = s + cols[i][a] * q[a][b] * cols[j][b];
      EXPECT_EQ(r[i][j], s) << i << " " << j;
      // Canonical: denominator positive and coprime to the numerator.
      EXPECT_GT(fmpz_sgn(fmpq_denref(r[i][j].raw())), 0);
      EXPECT_TRUE(fmpq_is_canonical(r[i][j].raw()));
      const std::array<Rational, N>& u = cols[i];
      const std::array<Rational, N>& v = cols[j];
      EXPECT_EQ(algebra::bilinear(q, u, v), s);
    }
}

} // namespace

TEST(FormRestriction, RationalSumsOverCommonDenominatorsEqualThePlainSums) {
  std::mt19937_64 rng(surfcert::testing::test_seed());
  for (int trial = 0; trial < 200; ++trial) {
    const Rational shared(1, 3 * 7 * 11 * 13 * 1024 + static_cast<unsigned long>(trial));
    std::array<std::array<Rational, 4>, 4> q4;
    std::array<std::array<Rational, 3>, 3> q3;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j)
        q4[i][j] = q4[j][i] = random_rational(rng, shared);
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = i; j < 3; ++j)
        q3[i][j] = q3[j][i] = random_rational(rng, shared);
    std::array<std::array<Rational, 4>, 3> c43;
    std::array<std::array<Rational, 3>, 2> c32;
    for (auto& c : c43)
      for (auto& x : c)
        x = random_rational(rng, shared);
    for (auto& c : c32)
      for (auto& x : c)
        x = random_rational(rng, shared);
    expect_restriction_equals_plain_sums(q4, c43);
    expect_restriction_equals_plain_sums(q3, c32);
  }
}

TEST(FormRestriction, ZeroFormsAndVectorsGiveCanonicalZero) {
  std::array<std::array<Rational, 3>, 3> q{};
  const std::array<std::array<Rational, 3>, 2> cols{
      {{Rational(1, 3), Rational(2), Rational(0)}, {Rational(0), Rational(0), Rational(0)}}};
  const auto r = algebra::restrict_form(q, cols);
  for (const auto& row : r)
    for (const Rational& x : row) {
      EXPECT_TRUE(x.is_zero());
      EXPECT_TRUE(fmpz_is_one(fmpq_denref(x.raw())));
    }
  q[0][0] = Rational(5, 7);
  EXPECT_EQ(algebra::bilinear(q, cols[1], cols[0]), Rational(0));
  EXPECT_EQ(algebra::bilinear(q, cols[0], cols[0]), Rational(5, 63));
}

// A shape of the given type and radii posed in doubles (centre and quaternion doubles).
core::QuadricMatrix posed(core::ShapeType type, const std::array<double, 3>& radii) {
  core::ShapeSpec s;
  s.type = type;
  s.center = {0.123456789012345, -0.3141592653589793, 0.2718281828459045};
  s.radii = radii;
  s.rotated = true;
  s.quaternion = {0.4123105625617661, -0.8246211251235321, 0.2, 0.3316624790355400};
  return core::QuadricMatrix(s);
}

TEST(FormRestriction, PosedQuadricInDoublesAgainstPlainSums) {
  // A cylinder posed by a double quaternion: entries of ~150 digits over related denominators.
  const core::QuadricMatrix m =
      posed(core::ShapeType::Cylinder, {0.7071067811865476, 0.7071067811865476, 1});
  const auto& q = m.matrix();
  std::array<std::array<Rational, 4>, 3> cols{};
  cols[0] = {Rational(1), Rational(0), Rational(0), Rational(0)};
  cols[1] = {Rational(0), Rational(1), Rational(0), Rational::exact_from_double(0.1)};
  cols[2] = {Rational(0), Rational(0), Rational(1, 3), Rational(1)};
  expect_restriction_equals_plain_sums(q, cols);
}

TEST(FormRestriction, DoublesKeepTheTemplateSums) {
  const std::array<std::array<double, 3>, 3> q{{{1, 0.5, 0}, {0.5, 2, -1}, {0, -1, 3}}};
  const std::array<std::array<double, 3>, 2> cols{{{1, 2, 3}, {0, 1, -1}}};
  const auto r = algebra::restrict_form(q, cols);
  EXPECT_DOUBLE_EQ(r[0][0], 1 + 2 * 0.5 * 2 + 2 * 4 - 2 * 2 * 3 + 3 * 9);
  EXPECT_DOUBLE_EQ(r[0][1], algebra::bilinear(q, cols[0], cols[1]));
  EXPECT_DOUBLE_EQ(r[1][1], 2 + 2 + 3);
}

TEST(FormRestriction, CongruenceEqualsTheRationalMatrixProducts) {
  std::mt19937_64 rng(surfcert::testing::test_seed() + 1);
  for (int trial = 0; trial < 200; ++trial) {
    const Rational shared(1, 5 * 17 * 4096 + static_cast<unsigned long>(trial));
    core::Mat4 m, p;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j)
        m[i][j] = m[j][i] = random_rational(rng, shared);
    for (auto& row : p)
      for (auto& x : row)
        x = random_rational(rng, shared);
    const core::Mat4 want = core::transpose(p) * m * p;
    const core::Mat4 got = core::congruence(p, m);
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        EXPECT_EQ(got[i][j], want[i][j]) << trial << " " << i << " " << j;
        EXPECT_TRUE(fmpq_is_canonical(got[i][j].raw()));
      }
  }
  // A posed shape's exact matrix is formed by congruence: the same as the products.
  core::ShapeSpec s;
  s.type = core::ShapeType::Ellipsoid;
  s.center = {0.5, -0.25, 0.1};
  s.radii = {0.3, 0.7, 0.9};
  s.rotated = true;
  s.quaternion = {0.1, 0.2, -0.3, 0.9};
  const core::QuadricMatrix q(s), moved = q.translated({0.3, 0.0, -0.7});
  core::Mat4 t = core::identity4();
  t[0][3] = Rational::exact_from_double(0.3);
  t[2][3] = Rational::exact_from_double(-0.7);
  const core::Mat4 want = core::transpose(t) * q.matrix() * t;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      EXPECT_EQ(moved.matrix()[i][j], want[i][j]);
}

// core::integer_multiple: integer entries, every one L times the original for one L > 0 (the
// same form up to a positive factor: signs, zero set, inertia), L the least common
// denominator (the entries' gcd with L is 1 overall); random rationals and a posed quadric.
TEST(FormRestriction, IntegerMultipleIsThePositiveLcmMultiple) {
  auto check = [](const std::array<std::array<Rational, 4>, 4>& m, const std::string& ctx) {
    const auto r = core::integer_multiple(m);
    std::optional<Rational> factor;
    Integer lcm(1);
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        EXPECT_TRUE(r[i][j].den() == Integer(1)) << ctx;
        EXPECT_EQ(r[i][j].sign(), m[i][j].sign()) << ctx;
        fmpz_lcm(lcm.raw_mut(), lcm.raw(), m[i][j].den().raw());
        if (m[i][j].is_zero()) continue;
        const Rational f = r[i][j] / m[i][j];
        if (!factor) factor = f;
        EXPECT_TRUE(*factor == f) << ctx << ": not one factor";
      }
    if (factor) {
      EXPECT_TRUE(*factor == Rational(lcm)) << ctx << ": not the lcm";
    }
  };
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 200; ++trial) {
    const Rational shared(1, static_cast<long>(trial % 7 + 2));
    std::array<std::array<Rational, 4>, 4> m;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j)
        m[i][j] = m[j][i] = random_rational(rng, shared);
    check(m, "trial " + std::to_string(trial));
  }
  check(std::array<std::array<Rational, 4>, 4>{}, "zero");
  check(posed(core::ShapeType::Cone, {0.7071067811865476, 0.5, 1}).matrix(), "posed cone");
}
