// Extreme inputs (an audit of magnitudes near the readers' limits): numbers up to the
// 131072-bit coefficient limit, underflowing and overflowing literals, boxes at the double
// range. Each answer is exact, certified or honestly undecided, never a crash, a hang past its
// budget, an internal error or a non-finite JSON number. The CLI cases run the binary and check
// exit codes, statuses and JSON paths (never prose).
#include "support/distance_checks.hpp"

#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/budget.hpp"
#include "surfcert/core/io/json.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

using namespace surfcert;
using core::Integer;
using core::Rational;
using core::io::Json;
using surfcert::testing::q;

namespace {

struct Proc {
  int code;
  std::string out, err;
  double seconds;
};

std::string tmp_path(const std::string& name) {
  return (::testing::TempDir().empty() ? std::string("/tmp/") : ::testing::TempDir()) +
         "surfcert_extreme_" + std::to_string(getpid()) + "_" + name;
}

std::string slurp(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The binary with `args` (shell-quoted by the caller), stdin_text on its standard input, under
// `timeout` (a hang fails the test instead of stalling the suite: exit code 124).
Proc run(const std::string& args, const std::string& stdin_text = "", int timeout_s = 120) {
  const std::string in = tmp_path("stdin"), out = tmp_path("stdout"), err = tmp_path("stderr");
  std::ofstream(in) << stdin_text;
  const std::string cmd = "timeout " + std::to_string(timeout_s) + " " +
                          std::string(SURFCERT_BINARY) + " " + args + " <" + in + " >" + out +
                          " 2>" + err;
  const auto t0 = std::chrono::steady_clock::now();
  const int st = std::system(cmd.c_str());
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Proc r{WIFEXITED(st) ? WEXITSTATUS(st) : -1, slurp(out), slurp(err), s};
  std::remove(in.c_str());
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

std::vector<Json> lines_of(const std::string& out) {
  std::vector<Json> v;
  std::istringstream s(out);
  std::string line;
  while (std::getline(s, line))
    if (!line.empty()) v.push_back(core::io::parse_json(line, "stdout"));
  return v;
}

const Json& at(const Json& j, std::initializer_list<const char*> path) {
  const Json* p = &j;
  for (const char* k : path) {
    p = p->find(k);
    if (!p) throw std::runtime_error(std::string("missing field ") + k);
  }
  return *p;
}

// The square-free part of the pencil det(l A - B) of the spheres |x| = R and |x - (3,0,0)| = 1:
// (l - 1)(R^2 l^2 - (R^2 - 8) l + 1), roots 1, ~1 - 10/R^2 and ~1/R^2.
algebra::UPolyZ sphere_pencil(const Integer& r2) {
  const algebra::UPolyZ lin = algebra::UPolyZ::from_coeffs({Integer(-1), Integer(1)});
  const algebra::UPolyZ quad = algebra::UPolyZ::from_coeffs({Integer(1), Integer(8) - r2, r2});
  algebra::UPolyZ p;
  fmpz_poly_mul(p.raw_mut(), lin.raw(), quad.raw());
  return p;
}

Integer pow10(unsigned long e) {
  Integer r;
  fmpz_ui_pow_ui(r.raw_mut(), 10, e);
  return r;
}

} // namespace

// F2: CGAL's Descartes isolator recursed once per halving (40,000 frames for R = 1e10000, a
// stack overflow killing the process). Beyond kCgalMaxBits the loop isolator answers, up to the
// reader's 131072-bit limit (R^2 = 1e39000: 129,555 bits), exactly and quickly.
TEST(ExtremeInputs, HugeCoefficientsAreIsolatedWithoutRecursion) {
  for (unsigned long e : {700UL, 4000UL, 16000UL, 39000UL}) {
    const algebra::UPolyZ p = sphere_pencil(pow10(e));
    ASSERT_GT(algebra::max_coefficient_bits(p), algebra::kCgalMaxBits) << e;
    const auto t0 = std::chrono::steady_clock::now();
    const algebra::RootSeparation s = algebra::isolate_real_roots(p);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(s.num_roots(), 3u) << e;
    EXPECT_LT(secs, 20.0) << e;
    for (size_t i = 0; i + 1 < s.separators.size(); ++i) {
      EXPECT_LT(s.separators[i], s.separators[i + 1]) << e;
      EXPECT_NE(p.sign_at(s.separators[i]), p.sign_at(s.separators[i + 1])) << e;
    }
  }
}

namespace {

algebra::UPolyZ mul(const algebra::UPolyZ& a, const algebra::UPolyZ& b) {
  algebra::UPolyZ p;
  fmpz_poly_mul(p.raw_mut(), a.raw(), b.raw());
  return p;
}

Integer pow2(unsigned long e) {
  Integer r(1);
  fmpz_mul_2exp(r.raw_mut(), r.raw(), e);
  return r;
}

// p(x / s) * s^deg p for the integer s > 0: the roots times s.
algebra::UPolyZ scale_roots(const algebra::UPolyZ& p, const Integer& s) {
  algebra::UPolyZ q = p;
  Integer f(1);
  for (long i = p.degree(); i >= 0; --i) {
    fmpz_mul(q.raw_mut()->coeffs + i, p.raw()->coeffs + i, f.raw());
    fmpz_mul(f.raw_mut(), f.raw(), s.raw());
  }
  return q;
}

// The square-free part of p (the product of its square-free factors).
algebra::UPolyZ squarefree_part(const algebra::UPolyZ& p) {
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  fmpz_poly_factor_squarefree(fac, p.raw());
  algebra::UPolyZ sq = algebra::UPolyZ::from_coeffs({Integer(1)});
  for (slong i = 0; i < fac->num; ++i)
    fmpz_poly_mul(sq.raw_mut(), sq.raw(), fac->p + i);
  fmpz_poly_factor_clear(fac);
  return sq;
}

// The separators checked by an independent route: as many gaps as FLINT's Sturm count,
// increasing separators, exact nonzero signs of p at them (FLINT fmpq), alternating.
void expect_certified(const algebra::UPolyZ& p, const algebra::RootSeparation& s,
                      const std::string& what) {
  EXPECT_EQ(static_cast<long>(s.num_roots()), fmpz_poly_num_real_roots_sturm(p.raw())) << what;
  for (size_t i = 0; i < s.separators.size(); ++i) {
    EXPECT_NE(p.sign_at(s.separators[i]), 0) << what << " separator " << i;
    if (i == 0) continue;
    EXPECT_LT(s.separators[i - 1], s.separators[i]) << what << " separator " << i;
    EXPECT_EQ(p.sign_at(s.separators[i]), -p.sign_at(s.separators[i - 1]))
        << what << " separator " << i;
  }
}

// Coefficients of a random polynomial of degree 1..max_degree, entries in [-bound, bound],
// leading coefficient nonzero.
std::vector<Integer> random_coefficients(std::mt19937_64& rng, int bound, int max_degree) {
  std::uniform_int_distribution<int> coef(-bound, bound), deg(1, max_degree);
  std::vector<Integer> c;
  const int d = deg(rng);
  for (int i = 0; i <= d; ++i)
    c.emplace_back(coef(rng));
  if (c.back().is_zero()) c.back() = Integer(1);
  return c;
}

} // namespace

TEST(ExtremeInputs, LoopIsolatorAgreesWithCgalOnSmallPolynomials) {
  std::mt19937_64 rng(20);
  for (int it = 0; it < 300; ++it) {
    const std::vector<Integer> c = random_coefficients(rng, 40, 7);
    // Square-free part of a product with a rational root or two, so that factors meet.
    const algebra::UPolyZ sq =
        squarefree_part(mul(algebra::UPolyZ::from_coeffs(c),
                            algebra::UPolyZ::from_coeffs({Integer(it % 5 - 2), Integer(1)})));
    const auto a = algebra::isolate_real_roots_descartes(sq);
    const auto b = algebra::isolate_real_roots_cgal(sq);
    ASSERT_EQ(a.num_roots(), b.num_roots()) << sq.to_string();
    expect_certified(sq, a, sq.to_string());
  }
}

// Small polynomials scaled up: the roots times 2^3000 or 10^1000 (coefficients of thousands
// of bits). The count must be CGAL's on the small polynomial, and the separators scaled back
// must separate the small polynomial's roots (exact signs: p(s / t) has the sign of the scaled
// polynomial at s).
TEST(ExtremeInputs, LoopIsolatorOnScaledSmallPolynomials) {
  std::mt19937_64 rng(24);
  for (int it = 0; it < 60; ++it) {
    const std::vector<Integer> c = random_coefficients(rng, 20, 6);
    const algebra::UPolyZ p = squarefree_part(algebra::UPolyZ::from_coeffs(c));
    if (p.degree() < 1) continue;
    const size_t k = algebra::isolate_real_roots_cgal(p).num_roots();
    const Integer t = it % 2 ? pow2(3000) : pow10(1000);
    const algebra::UPolyZ big = scale_roots(p, t);
    const auto s = algebra::isolate_real_roots_descartes(big);
    ASSERT_EQ(s.num_roots(), k) << p.to_string();
    expect_certified(big, s, p.to_string());
    algebra::RootSeparation back;
    for (const Rational& x : s.separators)
      back.separators.push_back(x / Rational(t));
    expect_certified(p, back, "scaled back: " + p.to_string());
  }
}

// Known roots built exactly, 10^10000 orders apart, and near-coincident roots with 10,000-bit
// coefficients: every known rational root strictly inside its own gap, the count FLINT's, and
// the dispatcher (isolate_real_roots) certifying the same.
TEST(ExtremeInputs, LoopIsolatorSeparatesKnownAndNearCoincidentRoots) {
  using algebra::UPolyZ;
  const UPolyZ x2m2 = UPolyZ::from_coeffs({Integer(-2), Integer(0), Integer(1)}); // +-sqrt 2
  // (x - 10^5000)(10^5000 x - 1)(x - 3)(2x + 7)(x^2 - 2): roots -7/2, -sqrt 2, 10^-5000,
  // sqrt 2, 3, 10^5000.
  {
    const UPolyZ p = mul(mul(mul(UPolyZ::from_coeffs({-pow10(5000), Integer(1)}),
                                 UPolyZ::from_coeffs({Integer(-1), pow10(5000)})),
                             mul(UPolyZ::from_coeffs({Integer(-3), Integer(1)}),
                                 UPolyZ::from_coeffs({Integer(7), Integer(2)}))),
                         x2m2);
    const auto s = algebra::isolate_real_roots_descartes(p);
    ASSERT_EQ(s.num_roots(), 6u);
    expect_certified(p, s, "known roots");
    const std::vector<std::pair<size_t, Rational>> known = {{0, Rational(-7, 2)},
                                                            {2, Rational(Integer(1), pow10(5000))},
                                                            {4, Rational(3)},
                                                            {5, Rational(pow10(5000))}};
    for (const auto& [gap, r] : known) {
      EXPECT_LT(s.separators[gap], r) << gap;
      EXPECT_LT(r, s.separators[gap + 1]) << gap;
    }
  }
  // Roots 2^-100 (relative) apart with 10,000-bit coefficients, times 2^5000:
  // (a) sqrt 2 and sqrt 2 + 2^-100 (two irreducible quadratics);
  // (b) 1 and 1 +- sqrt 2 * 2^-100 (a linear factor between the roots of a quadratic);
  // (c) the pair 3 +- sqrt 2 * 2^-100 of one irreducible quadratic, and the cubic x^3 - 3x + 1
  //     against (x - 2^-100)^3 - 3(x - 2^-100) + 1 (three pairs of roots 2^-100 apart).
  const UPolyZ shifted = UPolyZ::from_coeffs({Integer(1) - pow2(201), -pow2(101), pow2(200)});
  const UPolyZ around1 = UPolyZ::from_coeffs({pow2(200) - Integer(2), -pow2(201), pow2(200)});
  const UPolyZ around3 = UPolyZ::from_coeffs(
      {Integer(9) * pow2(200) - Integer(2), -Integer(6) * pow2(200), pow2(200)});
  const UPolyZ cubic = UPolyZ::from_coeffs({Integer(1), Integer(-3), Integer(0), Integer(1)});
  // 2^300 (x - 2^-100)^3 - 3 * 2^300 (x - 2^-100) + 2^300, expanded exactly.
  const UPolyZ cubic_shifted = UPolyZ::from_coeffs({pow2(300) + Integer(3) * pow2(200) - Integer(1),
                                                    Integer(3) * pow2(100) - Integer(3) * pow2(300),
                                                    -Integer(3) * pow2(200), pow2(300)});
  const std::vector<std::tuple<const char*, UPolyZ, size_t>> cases = {
      {"sqrt2 vs sqrt2 + 2^-100", mul(x2m2, shifted), 4},
      {"1 between 1 +- sqrt2 2^-100", mul(UPolyZ::from_coeffs({Integer(-1), Integer(1)}), around1),
       3},
      {"3 +- sqrt2 2^-100", around3, 2},
      {"cubic vs cubic + 2^-100", mul(cubic, cubic_shifted), 6}};
  for (const auto& [what, small, k] : cases) {
    const UPolyZ p = scale_roots(small, pow2(5000));
    ASSERT_GE(algebra::max_coefficient_bits(p), 10000) << what;
    const auto t0 = std::chrono::steady_clock::now();
    const auto s = algebra::isolate_real_roots_descartes(p);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(s.num_roots(), k) << what;
    expect_certified(p, s, what);
    EXPECT_LT(secs, 5.0) << what;
    const auto d = algebra::isolate_real_roots(p);
    EXPECT_EQ(d.num_roots(), k) << what;
    expect_certified(p, d, std::string("dispatcher: ") + what);
  }
}

// 10^(2e) (x - 1)^2 - 2 (real roots 1 +- sqrt2 10^-e), or with (x - 1)^2 (x - 3) (a complex
// pair 10^-e from 1), each times x - 10^1000.
namespace {

algebra::UPolyZ cluster(unsigned long e, bool cubic) {
  using algebra::UPolyZ;
  const UPolyZ square = UPolyZ::from_coeffs({Integer(1), Integer(-2), Integer(1)}); // (x-1)^2
  const UPolyZ far = UPolyZ::from_coeffs({-pow10(1000), Integer(1)});               // x - 10^1000
  UPolyZ q = cubic ? mul(square, UPolyZ::from_coeffs({Integer(-3), Integer(1)})) : square;
  fmpz_poly_scalar_mul_fmpz(q.raw_mut(), q.raw(), pow10(2 * e).raw());
  fmpz_sub_ui(q.raw_mut()->coeffs, q.raw()->coeffs, 2);
  return mul(q, far);
}

} // namespace

// Inputs on which Arb's arb_fmpz_poly_complex_roots (tried in place of the loop in session 24)
// ran for seconds to minutes, uninterruptibly: two roots of one irreducible factor 10^-1000 or
// 10^-300 apart (real or complex), and well separated roots all near 10^1000. The loop: well
// under a second each.
TEST(ExtremeInputs, LoopIsolatorOnClustersAndHugeRootsOfOneFactor) {
  using algebra::UPolyZ;
  const std::vector<std::tuple<std::string, UPolyZ, size_t>> cases = {
      {"real pair 1e-1000", cluster(1000, false), 3},
      {"real pair 1e-300", cluster(300, false), 3},
      {"complex pair 1e-300 and 3", cluster(300, true), 2},
      {"17x^4 - 15x^3 - 17x^2 + 5x + 6, roots * 10^1000",
       scale_roots(
           UPolyZ::from_coeffs({Integer(6), Integer(5), Integer(-17), Integer(-15), Integer(17)}),
           pow10(1000)),
       2}};
  for (const auto& [what, p, k] : cases) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto s = algebra::isolate_real_roots_descartes(p);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(s.num_roots(), k) << what;
    expect_certified(p, s, what);
    EXPECT_LT(secs, 5.0) << what;
  }
}

// The same clusters and huge roots at degree >= 12, where isolate_real_roots asks Arb's complex
// root finder first: Arb's own driver (arb_fmpz_poly_complex_roots) doubled its precision
// without limit there; the dispatcher's capped rounds give up instead and the exact isolators
// answer. Each case times (x + 1)(x + 2)...(x + 10) (ten more real roots).
TEST(ExtremeInputs, DispatcherOnHighDegreeClustersAndHugeRoots) {
  using algebra::UPolyZ;
  UPolyZ ten = UPolyZ::from_coeffs({Integer(1)});
  for (long k = 1; k <= 10; ++k)
    ten = mul(ten, UPolyZ::from_coeffs({Integer(k), Integer(1)}));
  const std::vector<std::tuple<std::string, UPolyZ, size_t>> cases = {
      {"real pair 1e-1000", cluster(1000, false), 13},
      {"real pair 1e-300", cluster(300, false), 13},
      {"complex pair 1e-300 and 3", cluster(300, true), 12},
      {"quartic roots * 10^1000",
       scale_roots(
           UPolyZ::from_coeffs({Integer(6), Integer(5), Integer(-17), Integer(-15), Integer(17)}),
           pow10(1000)),
       12},
      {"ten small roots alone", ten, 10}};
  for (const auto& [what, p0, k] : cases) {
    const UPolyZ p = k == 10 ? mul(p0, UPolyZ::from_coeffs({Integer(1), Integer(0), Integer(1),
                                                            Integer(0), Integer(1)}))
                             : mul(p0, ten);
    ASSERT_GE(p.degree(), 12) << what;
    const auto t0 = std::chrono::steady_clock::now();
    const auto s = algebra::isolate_real_roots(p);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(s.num_roots(), k) << what;
    EXPECT_EQ(static_cast<long>(s.num_roots()), algebra::count_real_roots(p)) << what;
    expect_certified(p, s, what);
    EXPECT_LT(secs, 10.0) << what;
  }
}

TEST(ExtremeInputs, LoopIsolatorChecksTheBudget) {
  const algebra::UPolyZ p = sphere_pencil(pow10(16000));
  core::BudgetScope scope(1e-3);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_THROW(algebra::isolate_real_roots_descartes(p), core::BudgetExceeded);
}

TEST(ExtremeInputs, HugeAndTinySpherePencilsClassifyQuickly) {
  // 1e20000 crashed (stack overflow), 1e-20000 took more than 60 s (43.8 s in batch with a
  // budget of 2 s).
  for (const char* a : {"x^2+y^2+z^2=1e20000", "x^2+y^2+z^2=1e-20000"}) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = certify::classify_qsic(q(a), q("(x-3)^2+y^2+z^2=1"), certify::Mode::Filtered);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(r.status, certify::Status::Certified) << a;
    ASSERT_NE(r.morphology, nullptr) << a;
    EXPECT_EQ(std::string(r.morphology->id), "empty_imaginary_conics") << a;
    EXPECT_LT(secs, 20.0) << a;
  }
}

TEST(ExtremeInputs, BatchSurvivesHugeSpheres) {
  // The crash killed the batch process: every later line was lost.
  const std::string lines =
      R"({"id":1,"op":"distance","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1"})"
      "\n"
      R"({"id":2,"op":"classify","a":"x^2+y^2+z^2=1e20000","b":"(x-3)^2+y^2+z^2=1"})"
      "\n"
      R"({"id":3,"op":"distance","a":{"type":"sphere","radius":"1e10000"},"b":{"type":"sphere","center":[3,0,0],"radius":1}})"
      "\n"
      R"({"id":4,"op":"classify","a":"x^2+y^2+z^2=1e-20000","b":"(x-3)^2+y^2+z^2=1","budget_ms":2000})"
      "\n"
      R"({"id":5,"op":"distance","a":"x^2+y^2+z^2=1","b":"(x-4)^2+y^2+z^2=1"})"
      "\n";
  const Proc r = run("batch --threads 1", lines);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto out = lines_of(r.out);
  ASSERT_EQ(out.size(), 5u) << r.out;
  for (size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].find("id")->text(), std::to_string(i + 1));
    EXPECT_EQ(out[i].find("status")->text(), "certified") << i;
  }
  EXPECT_EQ(at(out[1], {"result", "ellipsoid_relation"}).text(), "nested");
  EXPECT_LT(r.seconds, 60.0);
}

// F3b: exact strings in JSON skipped the equation reader's 131072-bit limit ("1e999999" hung a
// distance, even with a budget): now the same input error, with its JSON path, at once.
TEST(ExtremeInputs, JsonStringsPastTheBitLimitAreInputErrors) {
  const std::string b = R"('{"type":"sphere","center":[3,0,0],"radius":1}')";
  for (const auto& [a, path] : std::vector<std::pair<std::string, std::string>>{
           {R"({"type":"sphere","radius":"1e999999"})", "$.radius"},
           {R"({"type":"sphere","radius":"1e99999"})", "$.radius"},
           {R"({"type":"sphere","radius":"1/1e1"})", "$.radius"}, // not a number: as before
           {R"({"matrix":[["1e99999",0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]]})", "$.matrix[0][0]"},
           {R"({"type":"sphere","radius":1,"center":[0,"-1e-50000",0]})", "$.center[1]"}}) {
    const Proc r = run("distance '" + a + "' " + b + " --json", "", 20);
    EXPECT_EQ(r.code, 2) << a << ": " << r.err;
    EXPECT_NE(r.err.find("(" + path + ")"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  // In batch: an error line with its JSON path, within the budget, and the next line answered.
  const Proc r = run("batch",
                     R"({"id":1,"op":"distance","a":{"type":"sphere","radius":"1e999999"},)"
                     R"("b":"(x-3)^2+y^2+z^2=1","budget_ms":2000})"
                     "\n"
                     R"({"id":2,"op":"distance","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1"})"
                     "\n",
                     20);
  const auto out = lines_of(r.out);
  ASSERT_EQ(out.size(), 2u) << r.out;
  EXPECT_EQ(out[0].find("status")->text(), "error");
  EXPECT_EQ(at(out[0], {"error", "kind"}).text(), "input");
  EXPECT_EQ(at(out[0], {"error", "json_path"}).text(), "$.a.radius");
  EXPECT_EQ(out[1].find("status")->text(), "certified");
  // Within the limit: read exactly (1e39000 is 129,555 bits).
  const Proc ok =
      run(R"(distance '{"type":"sphere","radius":"1e39000"}' )" + b + " --json", "", 60);
  EXPECT_EQ(ok.code, 0) << ok.err;
}

// F6: a nonzero number literal that underflows (1e-400, 2e-324) was read as 0 (a radius then
// "expected a positive length, found 0"; a centre silently moved) while 1e400 was refused: now
// refused the same way, at its location. Subnormal doubles and zeros written with an exponent
// are doubles.
TEST(ExtremeInputs, UnderflowingLiteralsAreRefusedLikeOverflowingOnes) {
  const std::string b = R"('{"type":"sphere","center":[3,0,0],"radius":1}')";
  for (const auto& [a, path] : std::vector<std::pair<std::string, std::string>>{
           {R"({"type":"sphere","radius":1e-400})", "$.radius"},
           {R"({"type":"sphere","radius":2e-324})", "$.radius"},
           {R"({"type":"sphere","radius":1,"center":[1e-400,0,0]})", "$.center[0]"},
           {R"({"type":"sphere","radius":1,"center":[0,-1e400,0]})", "$.center[1]"},
           {R"({"matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1e-999]]})", "$.matrix[3][3]"}}) {
    const Proc r = run("distance '" + a + "' " + b + " --json", "", 20);
    EXPECT_EQ(r.code, 2) << a << ": " << r.err;
    EXPECT_NE(r.err.find("(" + path + ")"), std::string::npos) << r.err;
  }
  for (const std::string a : {R"({"type":"sphere","radius":5e-324})",
                              R"({"type":"sphere","radius":1,"center":[0.0e-400,0,0]})",
                              R"({"type":"sphere","radius":"1e-400"})"}) {
    const Proc r = run("distance '" + a + "' " + b + " --json", "", 20);
    EXPECT_EQ(r.code, 0) << a << ": " << r.err;
  }
  // The batch's fast reader agrees (its underflows go to the exact reader).
  const Proc r = run("batch", R"({"id":1,"op":"classify","a":{"type":"sphere","radius":1,)"
                              R"("center":[1e-400,0,0]},"b":"x^2+y^2+z^2=4"})"
                              "\n");
  const auto out = lines_of(r.out);
  ASSERT_EQ(out.size(), 1u) << r.out;
  EXPECT_EQ(at(out[0], {"error", "json_path"}).text(), "$.a.center[0]");
}

TEST(ExtremeInputs, NanBudgetIsRefused) {
  const Proc r = run("batch --budget-ms nan", "");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(run("batch --budget-ms 100", "").code, 0);
}

// F6: the distance to a quadric with no real point was "undecided: no critical point found";
// now undecided with the machine-readable reason, proven exactly.
TEST(ExtremeInputs, DistanceToAQuadricWithNoRealPointSaysSo) {
  for (const char* a : {"x^2+y^2+z^2=-1", "x^2+y^2=-1", "-x^2-2y^2-(z-1)^2=3"}) {
    for (bool swap : {false, true}) {
      const std::string s = std::string("'") + a + "'", t = "'(x-3)^2+y^2+z^2=1'";
      const Proc r = run("distance " + (swap ? t + " " + s : s + " " + t) + " --json", "", 20);
      EXPECT_EQ(r.code, 3) << a;
      const Json j = core::io::parse_json(r.out, "stdout");
      EXPECT_EQ(j.find("status")->text(), "undecided") << a;
      ASSERT_NE(j.find("reason"), nullptr) << r.out;
      EXPECT_EQ(j.find("reason")->text(), "no_real_point") << a;
    }
  }
  // A real quadric (a cone's apex alone, a line) is not said empty.
  for (const char* a : {"x^2+y^2+z^2=0", "x^2+y^2=0"}) {
    const Proc r = run(std::string("distance '") + a + "' '(x-3)^2+y^2+z^2=1' --json", "", 20);
    const Json j = core::io::parse_json(r.out, "stdout");
    const Json* reason = j.find("reason");
    EXPECT_TRUE(reason == nullptr || reason->text() != "no_real_point") << a;
  }
}

namespace {

// A printed non-finite double ("inf", "-nan", ...) as a word of its own (not "infinite").
bool has_non_finite_token(const std::string& s) {
  static const std::regex word("(^|[^A-Za-z])-?(inf|nan|INF|NAN)([^A-Za-z]|$)");
  return std::regex_search(s, word);
}

} // namespace

// F3c: an ellipsoid with radii 1e-100, 1e100 and 1 against a turned copy never ended (no
// budget): the offset system is no longer attempted at such spreads (undecided at once).
TEST(ExtremeInputs, ExtremeAspectRatiosTerminate) {
  const std::string a = R"('{"type":"ellipsoid","radii":[1e-100,1e100,1]}')";
  const std::string b = R"('{"type":"ellipsoid","center":[3,0,0],"radii":[1,1e-100,1e100]}')";
  for (const char* mode : {"float", "filtered", "exact"}) {
    const Proc r = run("distance " + a + " " + b + " --json --mode " + mode, "", 60);
    EXPECT_TRUE(r.code == 0 || r.code == 3) << mode << ": " << r.code << " " << r.err;
    EXPECT_LT(r.seconds, 30.0) << mode;
    const Json j = core::io::parse_json(r.out, "stdout");
    EXPECT_NE(j.find("status")->text(), "certified") << mode; // nothing proven here yet
  }
}

// F3d: a given box from -1e308 to 1e308 (its diagonal past the doubles) hung the tracer, deaf to
// a batch budget; now undecided at once, its picture finite.
TEST(ExtremeInputs, BoxWithDiagonalBeyondTheDoublesIsUndecidedAtOnce) {
  const std::string svg = tmp_path("box.svg");
  const Proc r = run("intersect 'x^2-y^2=1' 'x^2+z^2=4' --box "
                     "-1e308,-1e308,-1e308,1e308,1e308,1e308 --json --svg " +
                         svg,
                     "", 60);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_LT(r.seconds, 30.0);
  const Json j = core::io::parse_json(r.out, "stdout");
  EXPECT_EQ(j.find("status")->text(), "undecided");
  const std::string pic = slurp(svg);
  EXPECT_FALSE(pic.empty());
  EXPECT_FALSE(has_non_finite_token(pic));
  std::remove(svg.c_str());
  const Proc bt = run("batch",
                      R"({"id":1,"op":"intersect","a":"x^2-y^2=1","b":"x^2+z^2=4",)"
                      R"("box":{"min":[-1.7e308,-1.7e308,-1.7e308],)"
                      R"("max":[1.7e308,1.7e308,1.7e308]},"budget_ms":2000})"
                      "\n",
                      60);
  const auto out = lines_of(bt.out);
  ASSERT_EQ(out.size(), 1u) << bt.out;
  EXPECT_EQ(out[0].find("status")->text(), "undecided");
  EXPECT_LT(bt.seconds, 30.0);
}

// F4 and F5: internal errors (exit 1) on valid input whose numbers leave the doubles: a
// non-finite double met exact arithmetic, or a box [-inf, inf] reached a JSON number; with
// --export and --svg the files were written anyway (the SVG with inf coordinates).
TEST(ExtremeInputs, BeyondTheDoublesAnswersWithFiniteNumbers) {
  const std::vector<std::string> cmds = {
      R"(distance '{"type":"ellipsoid","radii":[1.7e308,1.7e308,1.7e308]}' )"
      R"('{"type":"ellipsoid","center":[1.7e308,0,0],"radii":[1.7e308,1.7e308,1.7e308]}' --json)",
      R"(distance '{"matrix":[[1.7e308,0,0,0],[0,1.7e308,0,0],[0,0,-1.7e308,0],[0,0,0,0]]}' )"
      R"('x^2+y^2=1' --json)",
      "intersect 'x^2+y^2=1e700' 'x^2+z^2=1e700' --json",
      "intersect 'x^2+y^2-z^2=0' 'x=1e320' --json",
      "intersect 'x^2+y^2+z^2=1e700' '(x-2e350)^2+y^2+z^2=1e700' --json"};
  for (const std::string& c : cmds) {
    const Proc r = run(c, "", 60);
    EXPECT_TRUE(r.code == 0 || r.code == 3) << c << ": " << r.code << " " << r.err;
    const Json j = core::io::parse_json(r.out, "stdout"); // throws on a non-finite number
    EXPECT_NE(j.find("status"), nullptr) << c;
  }
  const std::string obj = tmp_path("c.obj"), svg = tmp_path("c.svg");
  const Proc r = run(
      "intersect 'x^2+y^2=1e700' 'x^2+z^2=1e700' --json --export " + obj + " --svg " + svg, "", 60);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_FALSE(has_non_finite_token(slurp(obj)));
  EXPECT_FALSE(has_non_finite_token(slurp(svg)));
  std::remove(obj.c_str());
  std::remove(svg.c_str());
}

// F7: "approx" went through a double: "inf" for a certified distance of ~1e400, "0" for one of
// 1e-1001. Now the midpoint's %.17g text at any exponent, inside [lower, upper].
TEST(ExtremeInputs, ApproxBeyondTheDoublesIsTheMidpoint) {
  const std::string tiny_centre = "2." + std::string(1000, '0') + "1"; // 2 + 1e-1001
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {R"({"type":"sphere","radius":"1e400"})",
            R"({"type":"sphere","center":[3,0,0],"radius":1})"},
           {R"({"type":"sphere","radius":1})",
            R"({"type":"sphere","center":[")" + tiny_centre + R"(",0,0],"radius":1})"}}) {
    const Proc r = run("distance '" + a + "' '" + b + "' --json", "", 60);
    ASSERT_EQ(r.code, 0) << r.err;
    const Json j = core::io::parse_json(r.out, "stdout");
    const Json& d = at(j, {"result", "distance"});
    const std::string lo = d.find("lower")->text(), hi = d.find("upper")->text(),
                      ap = d.find("approx")->text();
    mpfr_t l, h, m;
    mpfr_inits2(256, l, h, m, static_cast<mpfr_ptr>(nullptr));
    ASSERT_EQ(mpfr_set_str(l, lo.c_str(), 10, MPFR_RNDN), 0) << lo;
    ASSERT_EQ(mpfr_set_str(h, hi.c_str(), 10, MPFR_RNDN), 0) << hi;
    ASSERT_EQ(mpfr_set_str(m, ap.c_str(), 10, MPFR_RNDN), 0) << ap;
    EXPECT_TRUE(mpfr_number_p(m) && mpfr_sgn(m) > 0) << ap;
    EXPECT_LE(mpfr_cmp(l, m), 0) << lo << " " << ap;
    EXPECT_LE(mpfr_cmp(m, h), 0) << ap << " " << hi;
    mpfr_clears(l, h, m, static_cast<mpfr_ptr>(nullptr));
  }
}

// With F1: two spheres touching at (1e-350, 0, 0) are certified by classify (rightly); the
// special point's approx read "0" (a double underflowing), now the rational's decimal.
TEST(ExtremeInputs, SpecialPointApproxBeyondTheDoubles) {
  for (const auto& [a, b, sign] : std::vector<std::tuple<std::string, std::string, int>>{
           {"x^2+y^2+z^2=1e-700", "(x-2e-350)^2+y^2+z^2=1e-700", 1},
           {"x^2+y^2+z^2=1e700", "(x+2e350)^2+y^2+z^2=1e700", -1}}) {
    const Proc r = run("classify '" + a + "' '" + b + "' --json", "", 60);
    ASSERT_EQ(r.code, 0) << r.err;
    const Json j = core::io::parse_json(r.out, "stdout");
    const Json& sp = at(j, {"result", "special_points"});
    ASSERT_EQ(sp.size(), 1u);
    const std::string x = sp.items()[0].find("approx")->items()[0].text();
    mpfr_t m;
    mpfr_init2(m, 64);
    ASSERT_EQ(mpfr_set_str(m, x.c_str(), 10, MPFR_RNDN), 0) << x;
    EXPECT_TRUE(mpfr_number_p(m) && mpfr_sgn(m) == sign) << x;
    EXPECT_EQ(mpfr_get_exp(m), sign > 0 ? -1162 : 1163) << x; // 1e+-350 ~ 2^+-1162.7
    mpfr_clear(m);
  }
}
