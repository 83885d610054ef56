// The contract of a certified distance, checked where issue 11 found it broken:
// - a minimizer count is reported only when proven ("undecided" with the number of candidates
//   otherwise), never a count of unseparated candidates (x^4+y^4+z^4 = 1 vs a cylinder said
//   "3" with one pair; the minimizer (1,0,0)-(2,0,0) is unique);
// - a float-mode answer travels as an estimate, never in the enclosure fields;
// - the width contract upper - lower <= 10^-digits lower holds on every certified answer
//   (Enclosure::meets_width, checked exactly on the printed decimals) at 15, 30 and 60 digits;
// - an Enclosure cannot be built from text or doubles (compile-time: see enclosure.hpp), and
//   an exact rational encloses itself at any digits;
// - the interval filter encloses integers beyond the double range rigorously (it used
//   fmpz_get_d + 2 ulps, undefined past 2^1024): scaling a pencil by 2^1100 changes nothing.
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/pencil_filter.hpp"
#include "surfcert/certify/qsic.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

using namespace surfcert;
using surfcert::testing::q;

TEST(CertifiedContract, UnprovenCountIsUndecidedNotACount) {
  // The seed pair with a 10^-30 asymmetry: the two candidate minimizers are not proven equal
  // (the true minimizer is unique), so the count must not read "2".
  const auto a = q("x^2 + y^2/4 + (z+3)^2/9 = 1");
  const auto b = q("x^2/4 + (y - 1/10^30)^2/9 + z^2/49 = 1");
  const auto r = certify::surface_distance(a, b, 15, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  EXPECT_NE(r.minimizers, "2") << r.note;
  if (r.minimizers == "undecided") {
    EXPECT_GE(r.minimizer_candidates(), 2);
  }
  // The symmetric pair: the tie is proven, the count "2" is proven.
  const auto s = certify::surface_distance(a, q("x^2/4 + y^2/9 + z^2/49 = 1"), 15, false);
  ASSERT_EQ(s.status, certify::Status::Certified) << s.note;
  EXPECT_EQ(s.minimizers, "2");
  EXPECT_EQ(s.ties, certify::Ties::Proven);
}

TEST(CertifiedContract, FlatQuarticAgainstCylinderNeverCountsThree) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the offset system of a quartic takes minutes under the sanitizers";
#endif
  const auto r = certify::surface_distance(
      core::io::read_surface(core::io::Json::string("x^4+y^4+z^4=1"), "t", "$"),
      core::Surface(q("(x-3)^2+y^2=1")), 15, false);
  if (r.status != certify::Status::Certified) GTEST_SKIP() << "undecided: " << r.note;
  mpfr_t one;
  mpfr_init2(one, 64);
  mpfr_set_ui(one, 1, MPFR_RNDN);
  EXPECT_TRUE(surfcert::testing::contains(r, one)) << r.lower() << " " << r.upper();
  mpfr_clear(one);
  EXPECT_TRUE(r.minimizers == "1" || r.minimizers == "undecided") << r.minimizers;
  EXPECT_NE(r.minimizers, "3");
}

TEST(CertifiedContract, FloatModeIsAnEstimate) {
  const auto r = certify::surface_distance(q("x^2+y^2+z^2=1"), q("(x-5)^2/4+y^2+z^2=1"), 15, false,
                                           certify::Mode::Float);
  ASSERT_EQ(r.status, certify::Status::Uncertified) << r.note;
  EXPECT_FALSE(r.distance.has_value());
  ASSERT_TRUE(r.estimate.has_value());
  EXPECT_NEAR(r.estimate->value, 2.0, 1e-9);
  const auto j = certify::distance_envelope_json(r, 15);
  const core::io::Json* res = j.find("result");
  ASSERT_NE(res, nullptr);
  EXPECT_EQ(res->find("distance"), nullptr);
  EXPECT_NE(res->find("estimate"), nullptr);
  // A float search proves no count either (it said "1", proof "exact"): the pair is a
  // candidate.
  EXPECT_TRUE(r.minimizers.is_undecided()) << r.minimizers;
  EXPECT_EQ(r.minimizers.proof(), certify::Minimizers::Proof::None);
  EXPECT_EQ(r.minimizer_candidates(), 1);
}

TEST(CertifiedContract, OnlyACertifiedAnswerCarriesAProvenCount) {
  // z = x^2 against z = x^2 + c: the critical pair at x = 0 is at distance c, but the
  // infimum is 0 at infinity (not attained). The answer is undecided [0, c] and said
  // "minimizers 1" (proof "interval"), a false proven field.
  for (const char* c : {"1", "1/10^10", "1/10^30", "1/2^64"}) {
    const auto r =
        certify::surface_distance(q("z = x^2"), q(std::string("z = x^2 + ") + c), 15, false);
    ASSERT_NE(r.status, certify::Status::Certified) << c << ": " << r.note;
    EXPECT_FALSE(r.minimizers.is_count()) << c << ": " << r.minimizers;
    EXPECT_EQ(r.minimizers.proof(), certify::Minimizers::Proof::None) << c;
  }
  // The same route with an attained minimum stays a proven answer: parallel circular
  // cylinders at centre distance 5, radii 1 and 2 (distance 2, a line of pairs).
  const auto s = certify::surface_distance(q("x^2+y^2=1"), q("(x-5)^2+y^2=4"), 15, false);
  if (s.status == certify::Status::Certified) {
    EXPECT_EQ(s.minimizers, "infinite");
  }
}

TEST(CertifiedContract, WidthContractAtSeveralDigits) {
  const std::pair<const char*, const char*> pairs[] = {
      {"x^2+y^2+z^2=1", "(x-5)^2/4+y^2/9+z^2=1"},                    // separated ellipsoids
      {"x^2 + y^2/4 + (z+3)^2/9 = 1", "x^2/4 + y^2/9 + z^2/49 = 1"}, // nested (seed 000)
      {"x^2+y^2-z=0", "(x^2+y^2)/4+(z-5)^2=1"},                      // coaxial paraboloid-spheroid
      {"z=0", "x^2+y^2-(z-3)^2=1/100"},                              // plane and hyperboloid
  };
  for (const auto& [sa, sb] : pairs)
    for (long digits : {15L, 30L, 60L}) {
      SCOPED_TRACE(std::string(sa) + " | " + sb + " @" + std::to_string(digits));
      const auto r = certify::surface_distance(q(sa), q(sb), digits, false);
      ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
      ASSERT_TRUE(r.distance.has_value());
      EXPECT_TRUE(r.distance->is_zero() || r.distance->meets_width(digits))
          << r.lower() << " " << r.upper();
    }
}

TEST(CertifiedContract, ExactEnclosures) {
  for (long digits : {15L, 100L}) {
    const auto e = certify::Enclosure::exact(core::Rational(1, 3), digits);
    EXPECT_TRUE(e.meets_width(digits));
    mpfr_t l, u, third;
    mpfr_inits2(4000, l, u, third, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_str(l, e.lower().c_str(), 10, MPFR_RNDD);
    mpfr_set_str(u, e.upper().c_str(), 10, MPFR_RNDU);
    mpfr_set_ui(third, 1, MPFR_RNDN);
    mpfr_div_ui(third, third, 3, MPFR_RNDN);
    EXPECT_LT(mpfr_cmp(l, third), 0);
    EXPECT_GT(mpfr_cmp(u, third), 0);
    mpfr_clears(l, u, third, static_cast<mpfr_ptr>(nullptr));
  }
  EXPECT_EQ(certify::Enclosure::zero().lower(), "0");
  EXPECT_EQ(certify::Enclosure::zero().upper(), "0");
}

TEST(CertifiedContract, FilterEnclosesHugeIntegers) {
  // Two ellipsoids (separated), then the same pencil scaled by 2^1100 / 2^1200: every entry
  // beyond the double range. The filter either declines or agrees with the exact answer.
  core::Mat4 a{}, b{};
  a[0][0] = a[1][1] = a[2][2] = core::Rational(1);
  a[3][3] = core::Rational(-1);
  b[0][0] = core::Rational(1, 4);
  b[1][1] = b[2][2] = core::Rational(1);
  b[0][3] = b[3][0] = core::Rational(-5, 4);
  b[3][3] = core::Rational(25, 4) - core::Rational(1);
  const auto base =
      certify::classify_qsic(core::QuadricMatrix(a), core::QuadricMatrix(b), certify::Mode::Exact);
  ASSERT_EQ(base.status, certify::Status::Certified);
  for (long k : {1100L, 1200L}) {
    core::Rational s(1);
    for (long i = 0; i < k; ++i)
      s = s * core::Rational(2);
    const core::Mat4 as = core::scaled(a, s), bs = core::scaled(b, s * s);
    const auto filt =
        certify::analyze_pencil_filtered(core::QuadricMatrix(as), core::QuadricMatrix(bs));
    const auto exact = certify::classify_qsic(core::QuadricMatrix(as), core::QuadricMatrix(bs),
                                              certify::Mode::Exact);
    ASSERT_EQ(exact.status, certify::Status::Certified);
    EXPECT_EQ(exact.tu_case, base.tu_case);
    const auto fr = certify::classify_qsic(core::QuadricMatrix(as), core::QuadricMatrix(bs),
                                           certify::Mode::Filtered);
    ASSERT_EQ(fr.status, certify::Status::Certified);
    EXPECT_EQ(fr.tu_case, base.tu_case) << "2^" << k << (filt ? " (filter answered)" : "");
  }
}
