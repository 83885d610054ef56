// algebra::SolutionCover on systems whose equations miss a variable, where a Sylvester
// resultant of two polynomials free of the eliminated variable is the constant 1 and would
// drop every solution: the cover must still hold each known solution (checked by evaluating
// the exact solutions' coordinates against the box intervals), and on random systems with
// known rational solutions (fixed seed) every planted solution lies in a box.
#include "surfcert/algebra/solution_cover.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace surfcert;
using core::Poly3;
using core::Rational;

namespace {

Poly3 X() {
  return Poly3::variable(0);
}
Poly3 Y() {
  return Poly3::variable(1);
}
Poly3 Z() {
  return Poly3::variable(2);
}
Poly3 C(long c) {
  return Poly3(core::Integer(c));
}

// Some box of the cover holds the rational point p.
bool covered(const algebra::SolutionCover& c, const std::array<Rational, 3>& p) {
  for (const auto& b : c.boxes) {
    bool in = true;
    for (size_t k = 0; k < 3 && in; ++k) {
      const auto& r = c.roots[k][b[k]];
      in = r.lo <= p[k] && p[k] <= r.hi;
    }
    if (in) return true;
  }
  return false;
}

} // namespace

TEST(SolutionCover, EquationsFreeOfTheEliminatedVariable) {
  // (x - 10)^2 + y^2 = 1, y = 0, z^2 ((x - 10)^2 + y^2) = 0: solutions (9, 0, 0), (11, 0, 0).
  // The first two do not involve z (a cylinder's offset system against a coaxial torus).
  const Poly3 f = (X() - C(10)) * (X() - C(10)) + Y() * Y() - C(1);
  const Poly3 g = C(-10) * Y();
  const Poly3 h = Z() * Z() * ((X() - C(10)) * (X() - C(10)) + Y() * Y());
  const auto c = algebra::cover_real_solutions({f, g, h}, Rational(1, 1024));
  ASSERT_TRUE(c.ok) << c.note;
  EXPECT_TRUE(covered(c, {Rational(9), Rational(0), Rational(0)}));
  EXPECT_TRUE(covered(c, {Rational(11), Rational(0), Rational(0)}));
  EXPECT_EQ(c.boxes.size(), 2u);
  // Same with x missing from two equations (the other elimination order).
  const Poly3 f2 = (Y() - C(10)) * (Y() - C(10)) + Z() * Z() - C(1), g2 = C(3) * Z();
  const Poly3 h2 = X() * X() * ((Y() - C(10)) * (Y() - C(10)) + Z() * Z());
  const auto c2 = algebra::cover_real_solutions({f2, g2, h2}, Rational(1, 1024));
  ASSERT_TRUE(c2.ok) << c2.note;
  EXPECT_TRUE(covered(c2, {Rational(0), Rational(9), Rational(0)}));
  EXPECT_TRUE(covered(c2, {Rational(0), Rational(11), Rational(0)}));
}

TEST(SolutionCover, PlantedRationalSolutions) {
  // (x - a)(x - b) = 0, (y - c) + k (x - a) = 0 ... products of linear forms vanishing at the
  // planted points p1, p2; every planted point must be covered (seed 31).
  std::mt19937 rng(31);
  std::uniform_int_distribution<long> d(-6, 6);
  for (int t = 0; t < 20; ++t) {
    std::array<long, 3> p{d(rng), d(rng), d(rng)}, q{d(rng), d(rng), d(rng)};
    if (p[0] == q[0]) q[0] += 1;
    const Poly3 f = (X() - C(p[0])) * (X() - C(q[0]));
    // y and z as affine functions of x through both points (exact rationals scaled to Z)
    const long dx = q[0] - p[0];
    const Poly3 g = C(dx) * (Y() - C(p[1])) - C(q[1] - p[1]) * (X() - C(p[0]));
    const Poly3 h = C(dx) * (Z() - C(p[2])) - C(q[2] - p[2]) * (X() - C(p[0]));
    const auto c = algebra::cover_real_solutions({f, g, h}, Rational(1, 64));
    ASSERT_TRUE(c.ok) << "seed 31, t " << t << ": " << c.note;
    EXPECT_TRUE(covered(c, {Rational(p[0]), Rational(p[1]), Rational(p[2])})) << "seed 31 t " << t;
    EXPECT_TRUE(covered(c, {Rational(q[0]), Rational(q[1]), Rational(q[2])})) << "seed 31 t " << t;
  }
}
