// The interval filter against exact arithmetic: whenever it answers, every index it reports
// equals the exact inertia (LDL^T) of s*A - B at its separator, the separators alternate the
// exact sign of f, and the case equals the exact one. Pairs with a zero leading entry force
// the filter's Descartes branch (Jacobi's rule needs d1 != 0).
#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/pencil.hpp"
#include "surfcert/certify/pencil_filter.hpp"
#include "surfcert/certify/qsic.hpp"

#include <gtest/gtest.h>

#include <cstdio>
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

namespace {

// P^T diag(d) P for an integer P: symmetric, of the rank of d (P invertible).
core::Mat4 congruent_diag(const std::array<long, 4>& d,
                          const std::array<std::array<long, 4>, 4>& p) {
  core::Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      long s = 0;
      for (size_t k = 0; k < 4; ++k)
        s += p[k][i] * d[k] * p[k][j];
      m[i][j] = Rational(s);
    }
  return m;
}

// The filter's facts on a pencil re-based because det A = 0, checked against the exact path's
// and against independent exact arithmetic: the same basis (rebased, t), the same root count
// and index sequence, every index the exact inertia (LDL^T) of the re-based member at the
// filter's separator, l = 0 an exact root; after complete_report_data the basis and f are the
// exact path's (f from the basis the filter's caller fills in).
void expect_rebased_like_exact(const core::Mat4& a, const core::Mat4& b, const std::string& ctx) {
  const core::QuadricMatrix qa(a), qb(b);
  const algebra::PencilFacts ex = algebra::analyze_pencil_exact(a, b);
  ASSERT_TRUE(ex.rebased) << ctx;
  certify::QsicResult r = certify::classify_qsic(qa, qb, certify::Mode::Filtered);
  ASSERT_EQ(r.status, certify::Status::Certified) << ctx;
  const certify::QsicResult rx = certify::classify_qsic(qa, qb, certify::Mode::Exact);
  EXPECT_EQ(r.tu_case, rx.tu_case) << ctx;
  EXPECT_EQ(r.segre, rx.segre) << ctx;
  EXPECT_TRUE(r.facts.rebased) << ctx;
  EXPECT_EQ(r.facts.rebase_t, ex.rebase_t) << ctx;
  if (r.exact_fallback) return; // a multiple root: nothing more of the filter's to check
  EXPECT_EQ(r.facts.indices, ex.indices) << ctx;
  ASSERT_EQ(r.facts.real_roots.size(), ex.real_roots.size()) << ctx;
  int zero_roots = 0;
  for (const auto& rt : r.facts.real_roots)
    if (rt.rational_value) {
      EXPECT_TRUE(rt.rational_value->is_zero()) << ctx;
      ++zero_roots;
    }
  EXPECT_EQ(zero_roots, 1) << ctx;
  const core::Mat4 ra = ex.a, rb = ex.b; // t A - B, -A
  auto f = algebra::pencil_char_poly(ra, rb);
  for (size_t i = 0; i < r.facts.samples.size(); ++i) {
    const Rational& s = r.facts.samples[i];
    core::Mat4 m;
    for (size_t p = 0; p < 4; ++p)
      for (size_t q = 0; q < 4; ++q)
        m[p][q] = s * ra[p][q] - rb[p][q];
    EXPECT_EQ(r.facts.indices[i], algebra::inertia_ldlt(m).p) << ctx << " sample " << i;
    EXPECT_NE(f.evaluate(s).sign(), 0) << ctx;
  }
  certify::complete_report_data(r, qa, qb, certify::Detail::Certificate);
  EXPECT_EQ(r.facts.a, ex.a) << ctx;
  EXPECT_EQ(r.facts.b, ex.b) << ctx;
  EXPECT_EQ(r.facts.f, ex.f) << ctx;
}

} // namespace

// A singular first quadric (a cone, a cylinder, a plane: most natural quadrics) sent every
// pencil to the exact path; the filter now re-bases it as that path does. Random A of rank 3,
// 2 or 1 against random B (every third one singular too: then t = 0 is skipped, f(0) = det B
// = 0 proven exactly): the filter must answer most of those with simple roots, and agree.
TEST(Filter, SingularFirstQuadricIsRebasedAsTheExactPathDoes) {
  std::mt19937_64 rng(20261203UL);
  std::uniform_int_distribution<long> e(-4, 4), dv(-3, 3);
  int simple = 0, answered = 0, skipped_zero = 0;
  for (int it = 0; it < 300; ++it) {
    std::array<std::array<long, 4>, 4> p{}, pb{};
    for (auto& row : p)
      for (long& x : row)
        x = e(rng);
    for (auto& row : pb)
      for (long& x : row)
        x = e(rng);
    const int rank = 3 - it % 3;
    std::array<long, 4> d{}, db{};
    for (int k = 0; k < 4; ++k) {
      d[static_cast<size_t>(k)] = k < rank ? (dv(rng) | 1) : 0; // odd: nonzero
      db[static_cast<size_t>(k)] = dv(rng) | 1;
    }
    if (it % 6 == 0) db[3] = 0; // B singular too, A of rank 3 (when P is invertible)
    const core::Mat4 a = congruent_diag(d, p), b = congruent_diag(db, pb);
    if (!core::det(a).is_zero()) continue; // (always: rank <= 3)
    bool zero = true;
    for (const auto& row : a)
      for (const auto& x : row)
        zero = zero && x.is_zero();
    if (zero) continue;
    const algebra::PencilFacts ex = algebra::analyze_pencil_exact(a, b);
    if (ex.kind != algebra::PencilKind::Regular) continue;
    const std::string ctx = "it " + std::to_string(it);
    expect_rebased_like_exact(a, b, ctx);
    bool all_simple = true;
    for (const auto& rt : ex.real_roots)
      all_simple = all_simple && rt.multiplicity == 1;
    all_simple = all_simple && ex.complex_roots % 2 == 0 && !ex.complex_double_pair;
    if (!all_simple) continue;
    ++simple;
    const bool fast = !certify::classify_qsic(core::QuadricMatrix(a), core::QuadricMatrix(b),
                                              certify::Mode::Filtered)
                           .exact_fallback;
    answered += fast;
    skipped_zero += fast && ex.rebase_t != 0;
  }
  EXPECT_GT(simple, 60);
  EXPECT_GT(answered, simple * 9 / 10); // before the re-basing: 0
  EXPECT_GT(skipped_zero, 10);
  std::printf("simple %d, answered %d, re-based past t = 0 %d\n", simple, answered, skipped_zero);
}

// The t the filter picks is the exact path's when an f(t) after t = 0 is zero too: a cone A
// and a singular B with det(-A - B) = 0 (a zero row) re-base at t = 1. And a first quadric
// that is NOT singular but nearly (det A = +-eps with eps = 1e-10, 1e-20, 1e-30, 2^-100): the
// filter must not re-base (the exact path does not); whatever path answers, the same case.
TEST(Filter, RebaseChoosesTheExactPathsTAndNeverRebasesANonsingularA) {
  core::Mat4 a{}, b{};
  a[0][0] = 1, a[1][1] = 1, a[2][2] = -1; // the cone x^2 + y^2 = z^2
  b[0][0] = -1, b[1][1] = 2, b[1][3] = b[3][1] = 1, b[2][2] = 1, b[3][3] = Rational(1, 2);
  ASSERT_TRUE(core::det(b).is_zero());
  const algebra::PencilFacts ex = algebra::analyze_pencil_exact(a, b);
  ASSERT_EQ(ex.rebase_t, 1);
  expect_rebased_like_exact(a, b, "zero row");

  // A cone with generic B: certified by the filter, re-based at t = 0.
  core::Mat4 g{};
  g[0][0] = 2, g[1][1] = 3, g[2][2] = 1, g[3][3] = -5, g[0][1] = g[1][0] = 1,
  g[1][2] = g[2][1] = -1, g[0][3] = g[3][0] = Rational(1, 3), g[2][3] = g[3][2] = 2;
  auto tenth = [](int k) { // 10^-k
    Rational r(1);
    for (int i = 0; i < k; ++i)
      r = r / Rational(10);
    return r;
  };
  for (const Rational& eps : {Rational(0), tenth(10), -tenth(10), tenth(20), -tenth(20), tenth(30),
                              -tenth(30), core::pow2(-100), -core::pow2(-100)}) {
    core::Mat4 ae = a;
    ae[3][3] = eps; // det = -eps
    const std::string ctx = "eps " + eps.to_string();
    const core::QuadricMatrix qa(ae), qg(g);
    EXPECT_EQ(qa.singular(), eps.is_zero()) << ctx;
    const certify::QsicResult f = certify::classify_qsic(qa, qg, certify::Mode::Filtered);
    const certify::QsicResult x = certify::classify_qsic(qa, qg, certify::Mode::Exact);
    ASSERT_EQ(f.status, certify::Status::Certified) << ctx;
    EXPECT_EQ(f.tu_case, x.tu_case) << ctx;
    EXPECT_EQ(f.facts.rebased, x.facts.rebased) << ctx;
    EXPECT_EQ(f.facts.rebased, eps.is_zero()) << ctx;
    if (eps.is_zero()) {
      EXPECT_FALSE(f.exact_fallback) << ctx; // the point of the re-basing
      expect_rebased_like_exact(ae, g, ctx);
    }
  }
}
