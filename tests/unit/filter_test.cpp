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

// PencilFacts::a, ::b (LazyMat4): unset, the basis reads as the zero matrix a default Mat4
// was; the filter leaves it unset and a report at Certificate copies the given matrices in;
// copies are deep.
TEST(Filter, PencilBasisIsSetOnlyWhenAReportNeedsIt) {
  const core::Mat4 zero{};
  algebra::PencilFacts unset;
  EXPECT_FALSE(unset.a.filled());
  EXPECT_EQ(unset.a, zero);
  EXPECT_EQ(unset.b[3][3], Rational(0));

  core::Mat4 a, b;
  for (size_t i = 0; i < 4; ++i) {
    a[i][i] = Rational(i == 3 ? -1 : static_cast<long>(i) + 1);         // diag(1, 2, 3, -1)
    b[i][i] = Rational(i == 3 ? -1 : static_cast<long>(i + 2) % 3 + 1); // diag(3, 1, 2, -1)
  }
  b[0][3] = b[3][0] = Rational(-1, 2);
  const core::QuadricMatrix qa(a), qb(b);
  certify::QsicResult r = certify::classify_qsic(qa, qb, certify::Mode::Filtered);
  ASSERT_EQ(r.status, certify::Status::Certified);
  ASSERT_FALSE(r.exact_fallback);
  EXPECT_FALSE(r.facts.a.filled());
  EXPECT_FALSE(r.facts.b.filled());
  certify::complete_report_data(r, qa, qb, certify::Detail::Topology);
  EXPECT_FALSE(r.facts.a.filled()); // topology needs no basis
  certify::complete_report_data(r, qa, qb, certify::Detail::Certificate);
  EXPECT_TRUE(r.facts.a.filled());
  EXPECT_EQ(r.facts.a, a);
  EXPECT_EQ(r.facts.b, b);
  const algebra::PencilFacts ex = algebra::analyze_pencil_exact(a, b);
  EXPECT_EQ(ex.a, a);
  EXPECT_EQ(ex.b, b);
  EXPECT_EQ(r.facts.f, ex.f); // the exact f from the copied basis
  algebra::PencilFacts inv = ex;
  algebra::fill_quartic_invariants(inv); // the exact analysis leaves D2..E to the report
  EXPECT_EQ(r.facts.d4, inv.d4);
  EXPECT_EQ(r.facts.e, inv.e);

  algebra::PencilFacts copy = ex;
  copy.a = core::scaled(a, Rational(2));
  EXPECT_EQ(ex.a, a); // deep
  EXPECT_NE(copy.a, a);
  EXPECT_EQ(copy.a[3][3], Rational(-2));
  copy.a = unset.a; // assigning an unset basis unsets it
  EXPECT_FALSE(copy.a.filled());
  EXPECT_EQ(copy.a, zero);
  const algebra::PencilFacts copy2 = unset;
  EXPECT_FALSE(copy2.b.filled());
}
