#include "surfcert/core/io/expression.hpp"

#include <flint/fmpq.h>
#include <flint/fmpz.h>

#include <algorithm>
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

long max_coefficient_bits(const Poly3& p) {
  long bits = 0;
  p.for_each_term([&](const Poly3::Exponent&, const Rational& c) {
    bits = std::max(bits, coefficient_bits(c));
  });
  return bits;
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
    long bits = max_coefficient_bits(p);
    if (bits > kMaxExpressionCoefficientBits) too_many_bits(at, bits);
  }
  [[noreturn]] void too_many_terms(std::size_t at, long terms) {
    fail(at, "a polynomial with at most " + std::to_string(kMaxExpressionTerms) + " terms",
         "a result with " + std::to_string(terms) + " terms");
  }
  [[noreturn]] void too_many_bits(std::size_t at, long bits) {
    fail(at, "coefficients of at most " + std::to_string(kMaxExpressionCoefficientBits) + " bits",
         "a coefficient of " + std::to_string(bits) + " bits");
  }

  // Counts `cost` term operations against max_work_; fails at `at` beyond it.
  void charge(long cost, std::size_t at) {
    if (cost > max_work_ - work_)
      fail(at,
           "an expression expanding with at most " + std::to_string(max_work_) + " term operations",
           "an expansion needing " + std::to_string(work_ + cost));
    work_ += cost;
  }

  // acc += t or acc -= t in place, on a term map: a Poly3 sum rewrites the whole accumulator,
  // which would make "big + 1 + 1 + ..." quadratic. Only the touched coefficients can have
  // grown; the degree cannot have.
  void add_into(Poly3::Terms& acc, const Poly3& t, bool subtract, std::size_t at) {
    t.for_each_term([&](const Poly3::Exponent& e, const Rational& c) {
      auto it = acc.try_emplace(e).first;
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
    long bits = max_coefficient_bits(a) + max_coefficient_bits(b) - 1;
    if (bits > kMaxExpressionCoefficientBits) too_many_bits(at, bits);
    // Degree <= 64 already bounds the terms (at most 47905 in three variables), but not the
    // work: two dense degree-32 factors would need 43 million coefficient products.
    charge(a.length() * b.length(), at);
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
        charge(acc.length(), at); // "big/1/1/1..." is not free
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
      long bits = max_coefficient_bits(base) * static_cast<long>(n);
      if (bits > kMaxExpressionCoefficientBits) too_many_bits(at, bits);
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
