// The interval filter against exact arithmetic: whenever it answers, every index it reports
// equals the exact inertia (LDL^T) of s*A - B at its separator, the separators alternate the
// exact sign of f, and the case equals the exact one. Pairs with a zero leading entry force
// the filter's Descartes branch (Jacobi's rule needs d1 != 0).
#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/pencil.hpp"
#include "surfcert/certify/pencil_filter.hpp"
#include "surfcert/certify/qsic.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

using namespace surfcert;
using core::Rational;

TEST(Filter, AgreesWithExactArithmeticWheneverItAnswers) {
  const char* env = std::getenv("SURFCERT_TEST_SEED");
  unsigned long seed = env ? std::strtoul(env, nullptr, 10) : 20261122UL;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<long> e(-9, 9), den(1, 5);
  int answered = 0, descartes_branch = 0;
  for (int it = 0; it < 600; ++it) {
    core::Mat4 a, b;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j) {
        a[i][j] = a[j][i] = Rational(e(rng), static_cast<unsigned long>(den(rng)));
        b[i][j] = b[j][i] = Rational(e(rng), static_cast<unsigned long>(den(rng)));
      }
    if (it % 2 == 0) a[0][0] = b[0][0] = Rational(0); // d1 = 0 at every sample
    auto fast = certify::analyze_pencil_filtered(core::QuadricMatrix(a), core::QuadricMatrix(b));
    if (!fast) continue;
    ++answered;
    descartes_branch += it % 2 == 0;
    std::string ctx = "seed " + std::to_string(seed) + " it " + std::to_string(it);
    ASSERT_EQ(fast->indices.size(), fast->samples.size()) << ctx;
    ASSERT_EQ(fast->samples.size(), fast->real_roots.size() + 1) << ctx;
    auto f = algebra::pencil_char_poly(a, b);
    for (size_t i = 0; i < fast->samples.size(); ++i) {
      const Rational& s = fast->samples[i];
      core::Mat4 m;
      for (size_t r = 0; r < 4; ++r)
        for (size_t c = 0; c < 4; ++c)
          m[r][c] = s * a[r][c] - b[r][c];
      EXPECT_EQ(fast->indices[i], algebra::inertia_ldlt(m).p) << ctx << " sample " << i;
      EXPECT_NE(f.evaluate(s).sign(), 0) << ctx;
      if (i > 0) {
        EXPECT_NE(f.evaluate(s).sign(), f.evaluate(fast->samples[i - 1]).sign()) << ctx;
      }
    }
    auto ex = algebra::analyze_pencil_exact(a, b);
    EXPECT_EQ(ex.real_roots.size(), fast->real_roots.size()) << ctx;
    EXPECT_EQ(
        certify::classify_qsic(core::QuadricMatrix(a), core::QuadricMatrix(b),
                               certify::Mode::Filtered)
            .tu_case,
        certify::classify_qsic(core::QuadricMatrix(a), core::QuadricMatrix(b), certify::Mode::Exact)
            .tu_case)
        << ctx;
  }
  EXPECT_GT(answered, 400);
  EXPECT_GT(descartes_branch, 150);
}
