// Invariance of the exact QSIC classification (research qsic-classification §1.1, §1.4): the
// Tu case of a pencil does not depend on (i) a congruence P^T A P, P^T B P (small and 40-bit
// integer P), (ii) swapping A and B, (iii) negating A or B, (iv) another basis (pA + qB,
// rA + sB), (v) exact scaling by 10^30 / 10^-30. Inputs: 200 random integer symmetric pairs
// with entries in [-5, 5] and scrambled canonical pencils of all 35 cases (expected case from
// the §4.5 table). Also: filtered == exact; the exact pencil facts are checked against
// independent routes (core::det for f, LDL^T inertia at the sample points and rational roots,
// sign changes of f, Segre by invariant factors, the §2.1 lookup of (Segre, normalised
// signature sequence) -> case). Degenerate pencils (f == 0) are skipped and counted.
// SURFCERT_TEST_SEED overrides the fixed seed; it is printed with every failure.
#include "support/canonical.hpp"

#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/pencil.hpp"
#include "surfcert/algebra/segre.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/quadric.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace st = surfcert::testing;
using surfcert::algebra::analyze_pencil_exact;
using surfcert::algebra::Inertia;
using surfcert::algebra::inertia_ldlt;
using surfcert::algebra::PencilFacts;
using surfcert::algebra::PencilKind;
using surfcert::algebra::rank_exact;
using surfcert::algebra::segre_by_invariant_factors;
using surfcert::algebra::segre_from_facts;
using surfcert::certify::classify_qsic;
using surfcert::certify::Mode;
using surfcert::certify::QsicResult;
using surfcert::certify::Status;
using surfcert::core::det;
using surfcert::core::Mat4;
using surfcert::core::QuadricMatrix;
using surfcert::core::Rational;
using surfcert::core::scaled;

namespace {

constexpr int kRandomPairs = 200;
constexpr int kBigCongruencePairs = 20;
constexpr int kMaxDegenerate = 10; // of 200; random [-5,5] pairs are almost never degenerate
constexpr int kCanonicalDraws = 5;
constexpr int kSmallEntryPairs = 400;

std::string seed_text() {
  return "seed " + std::to_string(st::test_seed()) + " (set SURFCERT_TEST_SEED to replay)";
}

// Library exceptions become test failures that name the input (a SCOPED_TRACE is not shown
// for an exception that escapes the test body).
QsicResult classify(const Mat4& a, const Mat4& b, Mode m) {
  try {
    return classify_qsic(QuadricMatrix(a), QuadricMatrix(b), m);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "classify_qsic (" << surfcert::certify::to_string(m) << ") threw: " << e.what()
                  << "\n"
                  << st::pencil_to_string(a, b);
    QsicResult r;
    r.status = Status::Error;
    r.tu_case = -1;
    return r;
  }
}

std::optional<PencilFacts> analyze(const Mat4& a, const Mat4& b) {
  try {
    return analyze_pencil_exact(a, b);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "analyze_pencil_exact threw: " << e.what() << "\n"
                  << st::pencil_to_string(a, b);
    return std::nullopt;
  }
}

std::string segre_if(const Mat4& a, const Mat4& b) {
  try {
    return segre_by_invariant_factors(a, b);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "segre_by_invariant_factors threw: " << e.what() << "\n"
                  << st::pencil_to_string(a, b);
    return "?";
  }
}

Rational pow10(int e) {
  Rational r(1);
  for (int k = 0; k < (e < 0 ? -e : e); ++k)
    r *= Rational(10);
  return e < 0 ? Rational(1) / r : r;
}

Mat4 pencil_member(const Mat4& a, const Mat4& b, const Rational& s) {
  return scaled(a, s) + scaled(b, Rational(-1));
}

int sgn(const Rational& x) {
  return x.sign();
}

std::string expected_root_pattern(const PencilFacts& f) {
  std::vector<int> m;
  for (const auto& r : f.real_roots)
    m.push_back(r.multiplicity);
  std::sort(m.rbegin(), m.rend());
  using V = std::vector<int>;
  if (m == V{1, 1, 1, 1}) return "R1";
  if (m.empty()) return f.complex_double_pair ? "R8" : "R2";
  if (m == V{1, 1}) return "R3";
  if (m == V{2, 1, 1}) return "R4";
  if (m == V{2}) return "R5";
  if (m == V{2, 2}) return "R6";
  if (m == V{3, 1}) return "R7";
  if (m == V{4}) return "R9";
  return "?";
}

// Exact pencil facts of (A, B) checked against routes that do not use the library's pencil
// analysis. Precondition: regular pencil.
void check_facts(const PencilFacts& f, const Mat4& A, const Mat4& B) {
  ASSERT_EQ(f.kind, PencilKind::Regular);
  // Re-basing (§1.1): exactly when det A = 0, to (tA - B, -A).
  EXPECT_EQ(f.rebased, det(A).is_zero());
  if (f.rebased) {
    EXPECT_EQ(f.a, pencil_member(A, B, Rational(f.rebase_t)));
    EXPECT_EQ(f.b, scaled(A, Rational(-1)));
  } else {
    EXPECT_EQ(f.a, A);
    EXPECT_EQ(f.b, B);
  }
  ASSERT_FALSE(det(f.a).is_zero());
  ASSERT_EQ(f.f.degree(), 4);
  // f(s) = det(s a - b) by the closed-form determinant of core.
  for (long s = -3; s <= 3; ++s)
    EXPECT_EQ(f.f.evaluate(Rational(s)), det(pencil_member(f.a, f.b, Rational(s)))) << "s=" << s;

  const size_t k = f.real_roots.size();
  ASSERT_EQ(f.samples.size(), k + 1);
  ASSERT_EQ(f.indices.size(), k + 1);
  bool definite = false;
  for (size_t j = 0; j <= k; ++j) {
    if (j > 0) {
      EXPECT_LT(f.samples[j - 1], f.samples[j]);
    }
    const Mat4 m = pencil_member(f.a, f.b, f.samples[j]);
    EXPECT_EQ(f.f.evaluate(f.samples[j]), det(m));
    EXPECT_FALSE(det(m).is_zero()) << "sample " << f.samples[j] << " is a root";
    const Inertia in = inertia_ldlt(m); // LDL^T route; the library uses Descartes
    EXPECT_EQ(in.p, f.indices[j]) << "index at sample " << f.samples[j];
    EXPECT_EQ(in.rank(), 4);
    definite = definite || f.indices[j] == 0 || f.indices[j] == 4;
  }
  EXPECT_EQ(f.definite_member, definite);

  int total = f.complex_roots;
  EXPECT_EQ(f.complex_roots % 2, 0);
  for (size_t i = 0; i < k; ++i) {
    const auto& r = f.real_roots[i];
    SCOPED_TRACE("root " + std::to_string(i) + " in [" + r.lo.to_string() + ", " +
                 r.hi.to_string() + "]");
    total += r.multiplicity;
    EXPECT_LE(f.samples[i], r.lo);
    EXPECT_LE(r.lo, r.hi);
    EXPECT_LE(r.hi, f.samples[i + 1]);
    EXPECT_EQ(r.index_left, f.indices[i]);
    EXPECT_EQ(r.index_right, f.indices[i + 1]);
    // f changes sign across a root of odd multiplicity only.
    const bool change = sgn(f.f.evaluate(f.samples[i])) != sgn(f.f.evaluate(f.samples[i + 1]));
    EXPECT_EQ(change, r.multiplicity % 2 == 1);
    // rank = 4 - number of Jordan blocks, so 4 - m <= rank <= 3.
    EXPECT_EQ(r.rank, r.sigma.rank());
    EXPECT_LE(r.rank, 3);
    EXPECT_GE(r.rank, 4 - r.multiplicity);
    // The index jump is the sum of the signs of the odd-sized blocks (§1.3): parity of m.
    const int jump = r.index_right - r.index_left;
    EXPECT_EQ(((jump - r.multiplicity) % 2 + 2) % 2, 0);
    EXPECT_LE(std::abs(jump), r.multiplicity);
    // Semicontinuity: eigenvalues of one sign at theta keep that sign nearby.
    EXPECT_LE(r.sigma.p, std::min(r.index_left, r.index_right));
    EXPECT_LE(r.sigma.n, 4 - std::max(r.index_left, r.index_right));
    if (r.multiplicity == 1) {
      EXPECT_EQ(r.sigma.p, std::min(r.index_left, r.index_right));
      EXPECT_EQ(r.sigma.n, 4 - std::max(r.index_left, r.index_right));
    } else {
      EXPECT_TRUE(r.rational_value.has_value() || r.quadratic.has_value());
    }
    if (r.rational_value) {
      const Rational& t = *r.rational_value;
      EXPECT_TRUE(f.f.evaluate(t).is_zero());
      EXPECT_LE(r.lo, t);
      EXPECT_LE(t, r.hi);
      const Mat4 m = pencil_member(f.a, f.b, t);
      EXPECT_EQ(rank_exact(m), r.rank);
      EXPECT_EQ(inertia_ldlt(m), r.sigma);
    }
  }
  EXPECT_EQ(total, 4);
  if (f.complex_double_pair) {
    EXPECT_EQ(k, 0u);
  }
  EXPECT_EQ(f.root_pattern, expected_root_pattern(f));
}

struct Reference {
  int tu_case = 0;
  std::string segre;
  std::string sequence;
};

// Exact classification of (A, B) plus every cross-check; expected_case = 0: not known in
// advance (random pair), then the §2.1 table lookup is the reference.
Reference reference_of(const Mat4& A, const Mat4& B, int expected_case) {
  Reference ref;
  const QsicResult r = classify(A, B, Mode::Exact);
  EXPECT_EQ(r.status, Status::Certified) << r.note;
  EXPECT_EQ(r.pencil, PencilKind::Regular);
  const std::optional<PencilFacts> got = analyze(A, B);
  if (!got) return ref;
  const PencilFacts& facts = *got;
  {
    SCOPED_TRACE("pencil facts");
    check_facts(facts, A, B);
  }
  ref.segre = segre_if(A, B);
  EXPECT_EQ(segre_from_facts(facts), ref.segre);
  EXPECT_EQ(r.segre, ref.segre);
  ref.sequence = st::signature_normal_form(facts);
  const int table = st::case_from_table(ref.segre, ref.sequence);
  EXPECT_NE(table, 0) << "no §2.1 row for " << ref.segre << " " << ref.sequence;
  EXPECT_EQ(r.tu_case, table) << "exact rules vs §2.1 lookup of " << ref.segre << " "
                              << ref.sequence;
  if (expected_case != 0) {
    EXPECT_EQ(r.tu_case, expected_case);
  }
  ref.tu_case = expected_case != 0 ? expected_case : table;
  const QsicResult fr = classify(A, B, Mode::Filtered);
  EXPECT_EQ(fr.status, Status::Certified) << fr.note;
  EXPECT_EQ(fr.tu_case, ref.tu_case) << "filtered vs exact";
  EXPECT_EQ(fr.segre, ref.segre) << "filtered vs exact";
  return ref;
}

void expect_same(const Reference& ref, const Mat4& a, const Mat4& b, const std::string& how) {
  SCOPED_TRACE(how + "\n" + st::pencil_to_string(a, b));
  const QsicResult r = classify(a, b, Mode::Exact);
  if (r.status == Status::Error && r.tu_case == -1) return; // exception, already reported
  EXPECT_EQ(r.status, Status::Certified) << r.note;
  EXPECT_EQ(r.pencil, PencilKind::Regular);
  EXPECT_EQ(r.tu_case, ref.tu_case);
  EXPECT_EQ(r.segre, ref.segre);
  EXPECT_EQ(st::signature_normal_form(r.facts), ref.sequence);
}

// The whole battery of invariances for one regular pencil.
void invariance_battery(const Mat4& A, const Mat4& B, int expected_case, st::Rng& rng,
                        bool big_congruence) {
  const Reference ref = reference_of(A, B, expected_case);
  // (i) congruence, small and (optionally) 40-bit entries.
  {
    const Mat4 p = st::random_invertible(rng, -2, 2);
    const st::PencilPair c = st::congruence({A, B}, p);
    expect_same(ref, c.a, c.b, "congruence P = " + st::mat_to_string(p));
    const QsicResult fr = classify(c.a, c.b, Mode::Filtered);
    EXPECT_EQ(fr.tu_case, ref.tu_case) << "filtered after congruence\n" << st::pencil_to_string(c);
  }
  if (big_congruence) {
    const long big = 1L << 40;
    const Mat4 p = st::random_invertible(rng, -big, big);
    const st::PencilPair c = st::congruence({A, B}, p);
    expect_same(ref, c.a, c.b, "40-bit congruence P = " + st::mat_to_string(p));
    const QsicResult fr = classify(c.a, c.b, Mode::Filtered);
    EXPECT_EQ(fr.tu_case, ref.tu_case)
        << "filtered after 40-bit congruence, P = " << st::mat_to_string(p);
  }
  // (ii) swap, (iii) negations.
  expect_same(ref, B, A, "swap A and B");
  expect_same(ref, scaled(A, Rational(-1)), B, "-A, B");
  expect_same(ref, A, scaled(B, Rational(-1)), "A, -B");
  expect_same(ref, scaled(A, Rational(-1)), scaled(B, Rational(-1)), "-A, -B");
  // (iv) another basis of the pencil.
  {
    const st::PencilPair c = st::random_basis_change({A, B}, rng);
    expect_same(ref, c.a, c.b, "basis change");
  }
  // (v) exact scalings.
  expect_same(ref, scaled(A, pow10(30)), scaled(B, pow10(30)), "A, B * 10^30");
  expect_same(ref, scaled(A, pow10(-30)), scaled(B, pow10(-30)), "A, B * 10^-30");
  expect_same(ref, scaled(A, pow10(30)), scaled(B, pow10(-30)), "A * 10^30, B * 10^-30");
}

} // namespace

TEST(Invariance, RandomIntegerPairs) {
  st::Rng rng(st::test_seed());
  int degenerate = 0;
  std::map<int, int> histogram;
  for (int k = 0; k < kRandomPairs; ++k) {
    const Mat4 A = st::random_symmetric(rng, -5, 5);
    const Mat4 B = st::random_symmetric(rng, -5, 5);
    SCOPED_TRACE("random pair " + std::to_string(k) + ", " + seed_text() + "\n" +
                 st::pencil_to_string(A, B));
    if (surfcert::algebra::pencil_char_poly(A, B).is_zero() ||
        surfcert::algebra::proportional(A, B)) {
      ++degenerate;
      continue;
    }
    invariance_battery(A, B, 0, rng, k < kBigCongruencePairs);
    ++histogram[classify(A, B, Mode::Exact).tu_case];
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_LE(degenerate, kMaxDegenerate);
  std::string h;
  for (const auto& [c, n] : histogram)
    h += " case" + std::to_string(c) + ":" + std::to_string(n);
  std::cout << "[ info     ] degenerate skipped: " << degenerate << "; cases:" << h << "\n";
  // A [-5, 5] pencil is generic: all four [1111] cases show up.
  EXPECT_GE(histogram.size(), 3u) << h;
}

TEST(Invariance, ScrambledCanonicalPencils) {
  st::Rng rng(st::test_seed() ^ 0x5eedULL);
  for (const st::CaseRecipe& cr : st::case_recipes()) {
    const st::Recipe base = st::parse_recipe(cr.recipe);
    for (int k = 0; k < kCanonicalDraws; ++k) {
      const st::PencilPair ab = st::scrambled_pencil(base, rng);
      SCOPED_TRACE("case " + std::to_string(cr.tu_case) + " (" + cr.recipe + "), draw " +
                   std::to_string(k) + ", " + seed_text() + "\n" + st::pencil_to_string(ab));
      invariance_battery(ab.a, ab.b, cr.tu_case, rng, k == 0);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
}

// Entries in [-1, 1]: many non-generic pencils (multiple roots, det A = 0, degenerate ones).
TEST(Invariance, SmallEntryPairs) {
  st::Rng rng(st::test_seed() + 17);
  int degenerate = 0;
  std::map<int, int> histogram;
  for (int k = 0; k < kSmallEntryPairs; ++k) {
    const Mat4 A = st::random_symmetric(rng, -1, 1);
    const Mat4 B = st::random_symmetric(rng, -1, 1);
    SCOPED_TRACE("small pair " + std::to_string(k) + ", " + seed_text() + "\n" +
                 st::pencil_to_string(A, B));
    if (surfcert::algebra::pencil_char_poly(A, B).is_zero() ||
        surfcert::algebra::proportional(A, B)) {
      ++degenerate;
      continue;
    }
    invariance_battery(A, B, 0, rng, false);
    ++histogram[classify(A, B, Mode::Exact).tu_case];
    if (::testing::Test::HasFatalFailure()) return;
  }
  std::string h;
  for (const auto& [c, n] : histogram)
    h += " case" + std::to_string(c) + ":" + std::to_string(n);
  std::cout << "[ info     ] degenerate/coincident skipped: " << degenerate << "; cases:" << h
            << "\n";
  EXPECT_LE(degenerate, kSmallEntryPairs / 2);
}

// A pencil with f == 0 is reported as degenerate (not a case), also after the transformations.
TEST(Invariance, DegeneratePencilStaysDegenerate) {
  // Two cones with a common apex at the origin of the (x, y, z) block, w free: every member
  // is singular.
  Mat4 a, b;
  a[0][0] = 1;
  a[1][1] = 1;
  a[2][2] = -1;
  b[0][0] = 1;
  b[1][1] = -2;
  b[0][2] = 1;
  b[2][0] = 1;
  ASSERT_TRUE(surfcert::algebra::pencil_char_poly(a, b).is_zero());
  st::Rng rng(st::test_seed());
  const st::PencilPair c = st::congruence({a, b}, st::random_invertible(rng, -2, 2));
  for (const auto& [x, y] : {std::pair<Mat4, Mat4>{a, b}, std::pair<Mat4, Mat4>{c.a, c.b},
                             std::pair<Mat4, Mat4>{b, a}}) {
    SCOPED_TRACE(st::pencil_to_string(x, y));
    const QsicResult r = classify(x, y, Mode::Exact);
    EXPECT_EQ(r.pencil, PencilKind::Degenerate);
    EXPECT_EQ(r.status, Status::Certified);
    EXPECT_EQ(r.tu_case, 0);
    EXPECT_EQ(classify(x, y, Mode::Filtered).pencil, PencilKind::Degenerate);
  }
}

// certify::translated_classification (what the tracer uses for a far pair moved towards the
// origin) against classifying the moved pair afresh: the same decisions and root facts, in
// filtered and exact mode, for every canonical case scrambled (exact fallbacks included) and for
// the same pencils posed in doubles; and after complete_special_points, the same special points
// in the moved coordinates (the basis matrices were replaced, not carried over).
TEST(Invariance, TranslatedClassificationEqualsClassifyingTheMovedPair) {
  st::Rng rng(st::test_seed() ^ 0x7a11ULL);
  const std::array<double, 3> c{0.75, -2.5, 0.875};
  int compared = 0, with_points = 0;
  for (const st::CaseRecipe& cr : st::case_recipes()) {
    const st::Recipe base = st::parse_recipe(cr.recipe);
    for (int k = 0; k < 2; ++k) {
      const st::PencilPair ab = st::scrambled_pencil(base, rng);
      for (bool doubles : {false, true}) {
        auto pose = [doubles](const Mat4& m) {
          if (!doubles) return QuadricMatrix(m);
          surfcert::core::DoubleMat4 d{};
          for (size_t i = 0; i < 4; ++i)
            for (size_t j = 0; j < 4; ++j)
              d[i][j] = m[i][j].to_double_approx();
          return QuadricMatrix::from_double_matrix(d);
        };
        const QuadricMatrix a = pose(ab.a), b = pose(ab.b);
        const QuadricMatrix a2 = a.translated(c), b2 = b.translated(c);
        for (Mode mode : {Mode::Filtered, Mode::Exact}) {
          SCOPED_TRACE("case " + std::to_string(cr.tu_case) + " draw " + std::to_string(k) +
                       (doubles ? " doubles" : " exact") +
                       (mode == Mode::Exact ? " exact mode" : " filtered") + ", " + seed_text());
          const auto r = classify_qsic(a, b, mode);
          auto moved = surfcert::certify::translated_classification(r, a2, b2);
          auto fresh = classify_qsic(a2, b2, mode);
          ASSERT_EQ(moved.status, fresh.status);
          ASSERT_EQ(moved.pencil, fresh.pencil);
          EXPECT_EQ(moved.tu_case, fresh.tu_case);
          EXPECT_EQ(moved.segre, fresh.segre);
          ASSERT_EQ(moved.facts.real_roots.size(), fresh.facts.real_roots.size());
          for (size_t i = 0; i < moved.facts.real_roots.size(); ++i) {
            const auto &x = moved.facts.real_roots[i], &y = fresh.facts.real_roots[i];
            EXPECT_EQ(x.multiplicity, y.multiplicity);
            EXPECT_EQ(x.rank, y.rank);
            EXPECT_EQ(x.sigma.p, y.sigma.p);
            EXPECT_EQ(x.sigma.n, y.sigma.n);
            EXPECT_EQ(x.rational_value, y.rational_value);
          }
          if (fresh.status != surfcert::certify::Status::Certified) continue;
          ++compared;
          surfcert::certify::complete_special_points(moved, a2, b2);
          surfcert::certify::complete_special_points(fresh, a2, b2);
          auto texts = [](const surfcert::certify::QsicResult& q) {
            std::vector<std::string> v;
            for (const auto& p : q.special_points)
              v.push_back(p.kind + " " + p.coords[0] + " " + p.coords[1] + " " + p.coords[2]);
            std::sort(v.begin(), v.end());
            return v;
          };
          EXPECT_EQ(texts(moved), texts(fresh));
          EXPECT_EQ(moved.special_points_complete, fresh.special_points_complete);
          with_points += moved.special_points.empty() ? 0 : 1;
        }
      }
    }
  }
  EXPECT_GE(compared, 200);
  EXPECT_GE(with_points, 60); // the multiple-root cases, moved off the origin
}
