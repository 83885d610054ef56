#include "surfcert/core/rational.hpp"

#include <mpfr.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace surfcert::core {

std::optional<Integer> Integer::from_string(const std::string& s) {
  size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  if (i == s.size()) return std::nullopt;
  for (size_t j = i; j < s.size(); ++j)
    if (!std::isdigit(static_cast<unsigned char>(s[j]))) return std::nullopt;
  Integer r;
  // fmpz_set_str accepts a leading '-' but not '+'.
  std::string t = s[0] == '+' ? s.substr(1) : s;
  if (fmpz_set_str(r.raw_mut(), t.c_str(), 10) != 0) return std::nullopt;
  return r;
}

std::string Integer::to_string() const {
  char* c = fmpz_get_str(nullptr, 10, v_);
  std::string s(c);
  flint_free(c);
  return s;
}

Rational::Rational(const Integer& num, const Integer& den) {
  fmpq_init(v_);
  if (den.is_zero()) {
    fmpq_clear(v_);
    throw std::domain_error("rational with zero denominator");
  }
  fmpq_set_fmpz_frac(v_, num.raw(), den.raw());
}

Rational Rational::exact_from_double(double d) {
  if (!std::isfinite(d)) throw std::domain_error("exact_from_double: non-finite double");
  Rational r;
  if (d == 0) return r;
  // d = +-m * 2^e from its IEEE 754 fields (no libm calls: this runs for every sample point of
  // the filtered decision): a normal number is (2^52 + fraction) * 2^(biased - 1075), a
  // subnormal fraction * 2^-1074. Stripping m's trailing zero bits leaves num / 2^k in lowest
  // terms.
  uint64_t bits = 0;
  std::memcpy(&bits, &d, sizeof bits);
  const auto biased = static_cast<long>((bits >> 52) & 0x7ff);
  uint64_t m = bits & ((uint64_t(1) << 52) - 1);
  long exp2 = -1074;
  if (biased != 0) {
    m |= uint64_t(1) << 52;
    exp2 = biased - 1075;
  }
  const int tz = __builtin_ctzll(m); // m != 0 since d != 0
  m >>= tz;
  exp2 += tz;
  const auto mi = static_cast<slong>(m); // < 2^53
  fmpz_set_si(fmpq_numref(r.v_), (bits >> 63) ? -mi : mi);
  if (exp2 >= 0)
    fmpz_mul_2exp(fmpq_numref(r.v_), fmpq_numref(r.v_), static_cast<ulong>(exp2));
  else
    fmpz_one_2exp(fmpq_denref(r.v_), static_cast<ulong>(-exp2));
  return r;
}

std::optional<Rational> Rational::from_string(const std::string& s) {
  if (s.empty()) return std::nullopt;
  auto slash = s.find('/');
  if (slash != std::string::npos) {
    auto n = Integer::from_string(s.substr(0, slash));
    std::string ds = s.substr(slash + 1);
    if (!ds.empty() && (ds[0] == '+' || ds[0] == '-')) return std::nullopt;
    auto d = Integer::from_string(ds);
    if (!n || !d || d->is_zero()) return std::nullopt;
    return Rational(*n, *d);
  }
  // Decimal: [sign] digits [. digits] [e|E [sign] digits]
  size_t i = 0;
  bool neg = false;
  if (s[i] == '+' || s[i] == '-') neg = s[i++] == '-';
  std::string digits;
  long frac_len = 0;
  bool any = false;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) {
    digits += s[i++];
    any = true;
  }
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) {
      digits += s[i++];
      ++frac_len;
      any = true;
    }
  }
  if (!any) return std::nullopt;
  long exp10 = 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    std::string es;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) es += s[i++];
    size_t start = i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
      es += s[i++];
    if (i == start || es.size() > 7) return std::nullopt; // |exponent| < 10^6: bounded work
    exp10 = std::stol(es);
  }
  if (i != s.size()) return std::nullopt;
  auto mant = Integer::from_string(digits);
  if (!mant) return std::nullopt;
  long e = exp10 - frac_len;
  Integer p;
  fmpz_set_ui(p.raw_mut(), 10);
  fmpz_pow_ui(p.raw_mut(), p.raw(), static_cast<unsigned long>(e < 0 ? -e : e));
  Rational r = e < 0 ? Rational(*mant, p) : Rational(*mant * p);
  return neg ? -r : r;
}

Integer Rational::num() const {
  Integer r;
  fmpz_set(r.raw_mut(), fmpq_numref(v_));
  return r;
}

Integer Rational::den() const {
  Integer r;
  fmpz_set(r.raw_mut(), fmpq_denref(v_));
  return r;
}

std::string Rational::to_string() const {
  char* c = fmpq_get_str(nullptr, 10, v_);
  std::string s(c);
  flint_free(c);
  return s;
}

double Rational::to_double_approx() const {
  // Numerator and denominator of at most 53 bits are exact doubles, and IEEE division rounds
  // their quotient to nearest (ties to even) as MPFR's RNDN does below: the same double,
  // without an MPFR number per call (7% of a plane section's instructions).
  if (fmpz_bits(fmpq_numref(v_)) <= 53 && fmpz_bits(fmpq_denref(v_)) <= 53)
    return static_cast<double>(fmpz_get_si(fmpq_numref(v_))) /
           static_cast<double>(fmpz_get_si(fmpq_denref(v_)));
  mpfr_t t;
  mpfr_init2(t, 53);
  fmpq_get_mpfr(t, v_, MPFR_RNDN);
  double d = mpfr_get_d(t, MPFR_RNDN);
  mpfr_clear(t);
  return d;
}

std::string Rational::to_decimal_approx(int digits) const {
  if (digits < 1) digits = 1;
  mpfr_t t;
  mpfr_init2(t, static_cast<mpfr_prec_t>(digits * 3.33 + 16));
  fmpq_get_mpfr(t, v_, MPFR_RNDN);
  std::string fmt = "%." + std::to_string(digits) + "Rg";
  // One formatting pass when the text fits a small buffer (the common case), else measure.
  char small[96];
  int n = mpfr_snprintf(small, sizeof small, fmt.c_str(), t);
  std::string out;
  if (n >= 0 && static_cast<size_t>(n) < sizeof small) {
    out.assign(small, static_cast<size_t>(n));
  } else {
    out.assign(static_cast<size_t>(n) + 1, '\0');
    mpfr_snprintf(out.data(), out.size(), fmt.c_str(), t);
    out.resize(static_cast<size_t>(n));
  }
  mpfr_clear(t);
  return out;
}

Rational operator/(const Rational& a, const Rational& b) {
  if (b.is_zero()) throw std::domain_error("rational division by zero");
  Rational r;
  fmpq_div(r.v_, a.v_, b.v_);
  return r;
}

Rational pow2(long e) {
  Rational r(1);
  if (e >= 0)
    fmpq_mul_2exp(r.raw_mut(), r.raw(), static_cast<ulong>(e));
  else
    fmpq_div_2exp(r.raw_mut(), r.raw(), static_cast<ulong>(-e));
  return r;
}

Rational abs(const Rational& x) {
  return x.sign() < 0 ? -x : x;
}

void over_common_denominator(const Rational* const* x, size_t n, Integer* nums, Integer& den) {
  fmpz_one(den.raw_mut());
  for (size_t k = 0; k < n; ++k) {
    const fmpz* d = fmpq_denref(x[k]->raw());
    // Equal denominators (a posed shape's entries share theirs) cost no gcd.
    if (!fmpz_is_one(d) && !fmpz_equal(d, den.raw())) fmpz_lcm(den.raw_mut(), den.raw(), d);
  }
  Integer t;
  for (size_t k = 0; k < n; ++k) {
    const fmpz* d = fmpq_denref(x[k]->raw());
    if (fmpz_equal(d, den.raw())) {
      fmpz_set(nums[k].raw_mut(), fmpq_numref(x[k]->raw()));
    } else {
      fmpz_divexact(t.raw_mut(), den.raw(), d);
      fmpz_mul(nums[k].raw_mut(), t.raw(), fmpq_numref(x[k]->raw()));
    }
  }
}

} // namespace surfcert::core
