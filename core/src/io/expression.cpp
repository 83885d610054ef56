#include "surfcert/core/io/expression.hpp"

#include <flint/fmpq.h>
#include <flint/fmpz.h>
#include <flint/fmpz_mpoly.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace surfcert::core::io {

namespace {

const char* const kPrimary = "a number, x, y, z or '('";

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_ident_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool is_ident_char(char c) {
  return is_ident_start(c) || is_digit(c);
}
bool is_ws(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}
int variable_index(char c) {
  switch (c) {
  case 'x':
  case 'X':
    return 0;
  case 'y':
  case 'Y':
    return 1;
  case 'z':
  case 'Z':
    return 2;
  default:
    return -1;
  }
}

long coefficient_bits(const Rational& c) {
  const fmpq* q = c.raw();
  return static_cast<long>(std::max(fmpz_bits(fmpq_numref(q)), fmpz_bits(fmpq_denref(q))));
}

// The sizes the header limits: the largest coefficient_bits over p's terms, and the sum over
// its terms of numerator plus denominator bits (what printing p writes, in binary).
struct CoefficientSizes {
  long max = 0, total = 0;
};

CoefficientSizes coefficient_sizes(const Poly3& p) {
  CoefficientSizes s;
  p.for_each_term([&](const Poly3::Exponent&, const Rational& c) {
    s.max = std::max(s.max, coefficient_bits(c));
    s.total += static_cast<long>(fmpz_bits(fmpq_numref(c.raw())) + fmpz_bits(fmpq_denref(c.raw())));
  });
  return s;
}

// Sizes of the integer coefficients FLINT multiplies (an fmpq_mpoly is content * zpoly), by
// powers of two of 64-bit limbs: bucket k holds the coefficients of 2^k to 2^(k+1) - 1 limbs,
// with their count, the sum of their sizes L and the sum of L^0.6 (what product_work needs).
struct LimbBucket {
  double count = 0, sum = 0, sum_06 = 0;
};
using LimbHistogram = std::array<LimbBucket, 24>;

long limbs_of(const fmpz_t x) {
  return std::max(1L, (static_cast<long>(fmpz_bits(x)) + 63) / 64);
}

LimbHistogram limb_histogram(const Poly3& p) {
  LimbHistogram h{};
  const fmpz_mpoly_struct* z = p.raw()->zpoly;
  for (slong i = 0; i < z->length; ++i) {
    const long limbs = limbs_of(z->coeffs + i);
    std::size_t k = 0;
    while (k + 1 < h.size() && (2L << k) <= limbs)
      ++k;
    h[k].count += 1;
    h[k].sum += static_cast<double>(limbs);
    h[k].sum_06 += std::pow(static_cast<double>(limbs), 0.6);
  }
  return h;
}

// Term operations for the product a * b, in units of one product of machine-sized integers
// with its addition into the result (16 ns measured: FLINT fmpz_mul + fmpz_add, Release, one
// core). A product of integers of la >= lb limbs costs about (la / lb) * M(lb) with
// M(n) ~ 2.9 ns * n^1.58 (GMP's Karatsuba/Toom range; measured 680 ns at 32 x 32 limbs, 342 us
// at 2048 x 2048), so each pair is charged 1 + la * lb^0.6 / 5. Summed by buckets: when all of
// one bucket's sizes exceed the other's the sums give it exactly; within one bucket both orders
// are charged (at most twice the truth). Saturates at `cap` (the caller refuses beyond it).
long product_work(const Poly3& a, const Poly3& b, long cap) {
  const LimbHistogram ha = limb_histogram(a), hb = limb_histogram(b);
  double work = 0;
  for (std::size_t i = 0; i < ha.size(); ++i) {
    if (ha[i].count == 0) continue;
    for (std::size_t j = 0; j < hb.size(); ++j) {
      if (hb[j].count == 0) continue;
      double big = 0;
      if (i >= j) big += ha[i].sum * hb[j].sum_06;
      if (i <= j) big += ha[i].sum_06 * hb[j].sum;
      work += ha[i].count * hb[j].count + big / 5.0; // multiply_work, summed
    }
  }
  return work >= static_cast<double>(cap) ? cap : static_cast<long>(std::ceil(work));
}

// Term operations (units of product_work) for a multiplication of integers of la and lb limbs
// (the per-pair weight of product_work, without its floor of 1).
double multiply_work(double la, double lb) {
  return std::max(la, lb) * std::pow(std::min(la, lb), 0.6) / 5.0;
}

// Term operations for a gcd of integers of la >= lb limbs: one division (like a product), then a
// gcd of lb-limb numbers, about ten products of that size. Measured (FLINT fmpz_gcd, Release, one
// core): 120 ns for one limb each, 0.8 us at 1024 x 1 limbs, 2.9 us at 16 x 16, 16.6 us at
// 64 x 64, 1.6 ms at 1024 x 1024; charged 8 units (128 ns) at least.
double gcd_work(double la, double lb) {
  return 8.0 + multiply_work(la, lb) + 10.0 * multiply_work(std::min(la, lb), std::min(la, lb));
}

// Term operations for the rational sum a + b (GMP's mpq_add: a gcd of the denominators, three
// products, a gcd with the small common factor; 1.8 ms measured for 65536-bit numerators and
// denominators; 12000 such sums took 9 s before sums were charged). A sum into a zero
// coefficient is a copy.
long sum_work(const Rational& a, const Rational& b) {
  const auto limbs = [](const Rational& q) {
    return static_cast<double>(limbs_of(fmpq_numref(q.raw())) + limbs_of(fmpq_denref(q.raw())));
  };
  const double la = limbs(a), lb = limbs(b);
  if (a.is_zero() || b.is_zero()) return 1 + static_cast<long>((la + lb) / 16.0);
  return static_cast<long>(std::ceil(gcd_work(la, lb) + 3.0 * (1.0 + multiply_work(la, lb))));
}

// Upper bounds on coefficient_sizes(p), without forming the terms. A term is content * z_i in
// lowest terms: its numerator has at most bits(content num) + bits(z_i) bits, its denominator
// at most bits(content den). Forming every term costs a gcd each, 5 s for the 2145 terms of
// (1 + y + 8e-320 z)^64, more than expanding it; these bounds cost nothing. They are exact
// when the content is an integer; with a common denominator a term's own may be smaller.
CoefficientSizes coefficient_sizes_bound(const Poly3& p) {
  const fmpq* content = p.raw()->content;
  const fmpz_mpoly_struct* z = p.raw()->zpoly;
  const long num = static_cast<long>(fmpz_bits(fmpq_numref(content)));
  const long den = static_cast<long>(fmpz_bits(fmpq_denref(content)));
  CoefficientSizes s;
  for (slong i = 0; i < z->length; ++i) {
    const long zbits = static_cast<long>(fmpz_bits(z->coeffs + i));
    s.max = std::max({s.max, num + zbits, den});
    s.total += num + zbits + den;
  }
  return s;
}

// Long literals are shortened in messages; the column already says where they are.
std::string quote(const std::string& text) {
  if (text.size() <= 40) return "'" + text + "'";
  return "'" + text.substr(0, 37) + "...'";
}

class ExpressionParser {
public:
  ExpressionParser(const std::string& text, const Location& where, long max_work)
      : s_(text), where_(where), max_work_(max_work) {}

  Poly3 parse() {
    skip_ws();
    Poly3 result = parse_expr();
    skip_ws();
    if (peek() == '=') {
      std::size_t eq = pos_;
      ++pos_;
      Poly3 rhs = parse_expr();
      skip_ws();
      if (peek() == '=') fail(pos_, "at most one '='", "'='");
      Poly3::Terms acc = result.terms();
      add_into(acc, rhs, true, eq);
      result = Poly3(acc);
    }
    if (!at_end()) fail(pos_, "end of expression", describe(pos_));
    return result;
  }

private:
  [[noreturn]] void fail(std::size_t at, const std::string& expected, const std::string& found) {
    // Columns count code points, so UTF-8 continuation bytes before `at` do not count.
    int offset = 0;
    for (std::size_t i = 0; i < at && i < s_.size(); ++i)
      if ((static_cast<unsigned char>(s_[i]) & 0xC0) != 0x80) ++offset;
    Location loc = where_;
    loc.column = where_.column == 0 ? offset + 1 : where_.column + offset;
    throw InputError(loc, expected, found);
  }

  bool at_end() const { return pos_ >= s_.size(); }
  char peek(std::size_t ahead = 0) const {
    return pos_ + ahead < s_.size() ? s_[pos_ + ahead] : '\0';
  }
  char char_at(std::size_t i) const { return i < s_.size() ? s_[i] : '\0'; }
  void skip_ws() {
    while (!at_end() && is_ws(s_[pos_]))
      ++pos_;
  }

  // Extent of the number starting at i: digits [. digits] [e [sign] digits], stopping before a
  // '.' or 'e' that does not continue it.
  std::size_t scan_number(std::size_t i) const {
    std::size_t p = i;
    while (is_digit(char_at(p)))
      ++p;
    if (char_at(p) == '.' && is_digit(char_at(p + 1))) {
      ++p;
      while (is_digit(char_at(p)))
        ++p;
    }
    char e = char_at(p);
    if (e == 'e' || e == 'E') {
      char n = char_at(p + 1);
      if (is_digit(n) || ((n == '+' || n == '-') && is_digit(char_at(p + 2)))) {
        p += 2;
        while (is_digit(char_at(p)))
          ++p;
      }
    }
    return p;
  }

  // The token at i as named in "found": the whole identifier or number, else one character.
  std::string describe(std::size_t i) const {
    if (i >= s_.size()) return "end of input";
    char c = s_[i];
    if (is_ident_start(c)) {
      std::size_t end = i;
      while (is_ident_char(char_at(end)))
        ++end;
      return quote(s_.substr(i, end - i));
    }
    if (is_digit(c) || (c == '.' && is_digit(char_at(i + 1)))) {
      std::size_t end = scan_number(i);
      return quote(s_.substr(i, end - i));
    }
    auto b = static_cast<unsigned char>(c);
    if (b == '\n') return "newline";
    if (b == '\r') return "carriage return";
    if (b == '\t') return "tab";
    if (b < 0x20 || b == 0x7F) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "control character U+%04X", static_cast<unsigned>(b));
      return buf;
    }
    if (b < 0x80) return std::string("'") + c + "'";
    // A non-ASCII character ("²", "−", "·"): quote its whole UTF-8 sequence.
    std::size_t end = i + 1;
    while (end < s_.size() && end - i < 4 && (static_cast<unsigned char>(s_[end]) & 0xC0) == 0x80)
      ++end;
    return "'" + s_.substr(i, end - i) + "'";
  }

  // The limits of the header, checked on every intermediate result. `at` is the operator.
  void check(const Poly3& p, std::size_t at) {
    int degree = p.total_degree();
    if (degree > kMaxExpressionDegree)
      fail(at, "a polynomial of total degree at most " + std::to_string(kMaxExpressionDegree),
           "a result of total degree " + std::to_string(degree));
    if (p.length() > kMaxExpressionTerms) too_many_terms(at, p.length());
    const CoefficientSizes bound = coefficient_sizes_bound(p);
    // The total is a resource limit (what printing p may write), checked on its free bound.
    const long total_limit = max_total_bits();
    if (bound.total > total_limit)
      fail(at, "coefficients of at most " + std::to_string(total_limit) + " bits in all",
           "a result whose coefficients need up to " + std::to_string(bound.total) + " bits");
    if (bound.max <= kMaxExpressionCoefficientBits) return;
    const long bits = exact_max_coefficient_bits(p, at);
    if (bits > kMaxExpressionCoefficientBits) too_many_bits(at, bits);
  }

  // kMaxExpressionTotalBits, scaled down with a smaller work budget: what a caller does with the
  // result (printing it, reading it back) must stay within the same time.
  long max_total_bits() const {
    return static_cast<long>(static_cast<double>(kMaxExpressionTotalBits) *
                             (static_cast<double>(max_work_) / kMaxExpressionWork));
  }

  // coefficient_sizes(p).max, charged: only called where the free bound is over the limit.
  long exact_max_coefficient_bits(const Poly3& p, std::size_t at) {
    // Forming a term takes a gcd of its integer and the content's denominator.
    const fmpz_mpoly_struct* z = p.raw()->zpoly;
    const double lc = static_cast<double>(limbs_of(fmpq_denref(p.raw()->content)));
    double cost = 0;
    for (slong i = 0; i < z->length; ++i)
      cost += gcd_work(static_cast<double>(limbs_of(z->coeffs + i)), lc);
    charge(cost > static_cast<double>(max_work_) ? max_work_ + 1 : static_cast<long>(cost), at);
    return coefficient_sizes(p).max;
  }
  [[noreturn]] void too_many_terms(std::size_t at, long terms) {
    fail(at, "a polynomial with at most " + std::to_string(kMaxExpressionTerms) + " terms",
         "a result with " + std::to_string(terms) + " terms");
  }
  [[noreturn]] void too_many_bits(std::size_t at, long bits) {
    fail(at, "coefficients of at most " + std::to_string(kMaxExpressionCoefficientBits) + " bits",
         "a coefficient of " + std::to_string(bits) + " bits");
  }

  // Counts `cost` term operations against max_work_; fails at `at` beyond it (a cost above
  // max_work_ may be saturated: product_work stops counting there).
  void charge(long cost, std::size_t at) {
    if (cost > max_work_ - work_)
      fail(at,
           "an expression expanding with at most " + std::to_string(max_work_) + " term operations",
           cost > max_work_ ? "an expansion needing more than " + std::to_string(max_work_)
                            : "an expansion needing " + std::to_string(work_ + cost));
    work_ += cost;
  }

  // acc += t or acc -= t in place, on a term map: a Poly3 sum rewrites the whole accumulator,
  // which would make "big + 1 + 1 + ..." quadratic. Only the touched coefficients can have
  // grown; the degree cannot have.
  void add_into(Poly3::Terms& acc, const Poly3& t, bool subtract, std::size_t at) {
    t.for_each_term([&](const Poly3::Exponent& e, const Rational& c) {
      auto it = acc.try_emplace(e).first;
      charge(sum_work(it->second, c), at);
      if (subtract)
        it->second -= c;
      else
        it->second += c;
      if (it->second.is_zero()) {
        acc.erase(it);
        return;
      }
      const long bits = coefficient_bits(it->second);
      if (bits > kMaxExpressionCoefficientBits) too_many_bits(at, bits);
    });
    if (static_cast<long>(acc.size()) > kMaxExpressionTerms)
      too_many_terms(at, static_cast<long>(acc.size()));
  }

  // a * b, refusing before the work when the degree or coefficient size would exceed the limits.
  Poly3 multiply(const Poly3& a, const Poly3& b, std::size_t at) {
    if (a.is_zero() || b.is_zero()) return Poly3();
    long degree = static_cast<long>(a.total_degree()) + b.total_degree();
    if (degree > kMaxExpressionDegree)
      fail(at, "a polynomial of total degree at most " + std::to_string(kMaxExpressionDegree),
           "a result of total degree " + std::to_string(degree));
    // A product of integers of b1 and b2 bits has b1 + b2 - 1 bits at least: refuse only then
    // (b1 + b2 refused "N*x" for a coefficient N of exactly the limit, so that the printed form
    // "1/N*x" of an accepted "x/N" did not read back). check() below is exact.
    long bits = coefficient_sizes_bound(a).max + coefficient_sizes_bound(b).max - 1;
    if (bits > kMaxExpressionCoefficientBits) {
      bits = exact_max_coefficient_bits(a, at) + exact_max_coefficient_bits(b, at) - 1;
      if (bits > kMaxExpressionCoefficientBits) too_many_bits(at, bits);
    }
    // Degree <= 64 already bounds the terms (at most 47905 in three variables), but not the
    // work: two dense degree-32 factors would need 43 million coefficient products, and
    // (1 + y + 8e-320 z)^64 only 137 thousand, but of up to 68000-bit integers (5 s unweighted).
    charge(product_work(a, b, max_work_ + 1), at);
    Poly3 r = a * b;
    check(r, at);
    return r;
  }

  Poly3 parse_expr() {
    Poly3 first = parse_signed_term();
    skip_ws();
    if (peek() != '+' && peek() != '-') return first;
    Poly3::Terms acc = first.terms();
    for (;;) {
      skip_ws();
      char op = peek();
      if (op != '+' && op != '-') return Poly3(acc);
      std::size_t at = pos_;
      ++pos_;
      Poly3 t = parse_signed_term();
      add_into(acc, t, op == '-', at);
    }
  }

  // One optional sign; "x + -1" is accepted (generated text often looks like that), "--x" not.
  Poly3 parse_signed_term() {
    skip_ws();
    char sign = peek();
    if (sign != '+' && sign != '-') return parse_term();
    ++pos_;
    Poly3 t = parse_term();
    return sign == '-' ? -t : t;
  }

  Poly3 parse_signed_power() {
    skip_ws();
    char sign = peek();
    if (sign != '+' && sign != '-') return parse_power();
    ++pos_;
    Poly3 p = parse_power();
    return sign == '-' ? -p : p;
  }

  Poly3 parse_term() {
    Poly3 acc = parse_power();
    for (;;) {
      skip_ws();
      char c = peek();
      std::size_t at = pos_;
      if (c == '*' && peek(1) != '*') {
        ++pos_;
        Poly3 rhs = parse_signed_power();
        acc = multiply(acc, rhs, at);
      } else if (c == '/') {
        ++pos_;
        skip_ws();
        std::size_t start = pos_;
        Poly3 divisor = parse_signed_power();
        if (divisor.is_zero() || divisor.total_degree() > 0) {
          std::size_t end = pos_;
          while (end > start && is_ws(s_[end - 1]))
            --end;
          fail(start, "a constant nonzero divisor", quote(s_.substr(start, end - start)));
        }
        charge(product_work(acc, divisor, max_work_ + 1), at); // "big/1/1/1..." is not free
        acc = acc.scaled(Rational(1) / divisor.coeff(0, 0, 0));
        check(acc, at);
      } else if (is_digit(c) || (c == '.' && is_digit(peek(1))) || is_ident_start(c) || c == '(') {
        // Juxtaposition: "2x", "2(x+1)", "x y", "3x^2y".
        Poly3 rhs = parse_power();
        acc = multiply(acc, rhs, at);
      } else {
        return acc;
      }
    }
  }

  Poly3 parse_power() {
    Poly3 base = parse_primary();
    skip_ws();
    bool caret = peek() == '^';
    if (!caret && !(peek() == '*' && peek(1) == '*')) return base;
    std::size_t at = pos_;
    pos_ += caret ? 1 : 2;
    unsigned n = parse_exponent();
    if (!base.is_zero()) {
      long degree = static_cast<long>(base.total_degree()) * n;
      if (degree > kMaxExpressionDegree)
        fail(at, "a polynomial of total degree at most " + std::to_string(kMaxExpressionDegree),
             "a result of total degree " + std::to_string(degree));
      long bits = coefficient_sizes_bound(base).max * static_cast<long>(n);
      if (bits > kMaxExpressionCoefficientBits) {
        bits = exact_max_coefficient_bits(base, at) * static_cast<long>(n);
        if (bits > kMaxExpressionCoefficientBits) too_many_bits(at, bits);
      }
    }
    // Repeated multiplication, not binary powering: for the dense polynomials of three
    // variables met here, squaring a^(n/2) costs far more than n small products (measured:
    // (1+x+y+z)^64 takes 3 million term products this way, 43 million by squaring).
    Poly3 r(Rational(1));
    for (unsigned k = 0; k < n; ++k)
      r = multiply(r, base, at);
    skip_ws();
    if (peek() == '^' || (peek() == '*' && peek(1) == '*'))
      fail(pos_, "parentheses around a power that is raised again", peek() == '^' ? "'^'" : "'**'");
    return r;
  }

  unsigned parse_exponent() {
    const char* expected = "a non-negative integer exponent";
    skip_ws();
    bool parenthesised = peek() == '(';
    if (parenthesised) {
      ++pos_;
      skip_ws();
    }
    std::size_t start = pos_;
    if (!is_digit(peek())) fail(pos_, expected, describe(pos_));
    std::size_t end = scan_number(start);
    std::string text = s_.substr(start, end - start);
    if (text.find_first_not_of("0123456789") != std::string::npos) // "2.5", "1e3"
      fail(start, expected, describe(start));
    pos_ = end;
    std::size_t first = std::min(text.find_first_not_of('0'), text.size() - 1);
    std::string digits = text.substr(first);
    if (digits.size() > 2 || std::stoi(digits) > kMaxExpressionDegree)
      fail(start, "an exponent at most " + std::to_string(kMaxExpressionDegree), quote(text));
    if (parenthesised) {
      skip_ws();
      if (peek() != ')') fail(pos_, "')'", describe(pos_));
      ++pos_;
    }
    return static_cast<unsigned>(std::stoi(digits));
  }

  Poly3 parse_number() {
    std::size_t start = pos_;
    std::size_t end = scan_number(start);
    std::string text = s_.substr(start, end - start);
    if (char_at(end) == '.') {
      if (text.find_first_of(".eE") == std::string::npos)
        fail(end + 1, "a digit after '.'", describe(end + 1));
      fail(end, "an operator after the number " + quote(text), "'.'");
    }
    // Refuse huge decimal exponents before Rational::from_string computes 10^e, and drop the
    // exponent's leading zeros, which from_string counts against its own length limit.
    std::string normalized = text;
    std::size_t e = text.find_first_of("eE");
    if (e != std::string::npos) {
      std::size_t d = text.find_first_not_of("+-0", e + 1);
      if (d != std::string::npos && text.size() - d > 5)
        fail(start,
             "coefficients of at most " + std::to_string(kMaxExpressionCoefficientBits) + " bits",
             quote(text));
      std::string sign = text[e + 1] == '-' ? "-" : "";
      normalized = text.substr(0, e) + "e" + sign + (d == std::string::npos ? "0" : text.substr(d));
    }
    auto value = Rational::from_string(normalized);
    if (!value) fail(start, "a number", quote(text)); // not reached: scan_number's grammar
    Poly3 p(*value);
    check(p, start);
    pos_ = end;
    return p;
  }

  Poly3 parse_primary() {
    skip_ws();
    char c = peek();
    if (at_end()) fail(pos_, kPrimary, "end of input");
    if (is_digit(c) || (c == '.' && is_digit(peek(1)))) return parse_number();
    if (is_ident_start(c)) {
      std::size_t end = pos_;
      while (is_ident_char(char_at(end)))
        ++end;
      for (std::size_t i = pos_; i < end; ++i)
        if (variable_index(s_[i]) < 0)
          fail(pos_, kPrimary, "unknown identifier " + quote(s_.substr(pos_, end - pos_)));
      // A run of variable letters ("xy") is their product: take one letter at a time.
      return Poly3::variable(variable_index(s_[pos_++]));
    }
    if (c == '(') {
      if (depth_ >= kMaxExpressionNesting)
        fail(pos_, "at most " + std::to_string(kMaxExpressionNesting) + " nested parentheses",
             "'('");
      ++depth_;
      ++pos_;
      Poly3 inner = parse_expr();
      skip_ws();
      if (peek() != ')') fail(pos_, "')'", describe(pos_));
      ++pos_;
      --depth_;
      return inner;
    }
    fail(pos_, kPrimary, describe(pos_));
  }

  const std::string& s_;
  const Location& where_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  long max_work_; // kMaxExpressionWork unless a caller asks for less
  long work_ = 0; // term operations spent so far, bounded by max_work_
};

} // namespace

Poly3 parse_polynomial(const std::string& text, const Location& where) {
  return ExpressionParser(text, where, kMaxExpressionWork).parse();
}

Poly3 parse_polynomial(const std::string& text, const Location& where, long max_work) {
  if (max_work < 1 || max_work > kMaxExpressionWork)
    throw InternalError("parse_polynomial: work budget " + std::to_string(max_work) +
                        " outside [1, " + std::to_string(kMaxExpressionWork) + "]");
  return ExpressionParser(text, where, max_work).parse();
}

} // namespace surfcert::core::io
