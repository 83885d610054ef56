// Unit tests of surfcert::core::io::parse_polynomial: exact values of accepted expressions
// (compared with polynomials built by arithmetic) and every error class with its column.
#include "surfcert/core/error.hpp"
#include "surfcert/core/io/expression.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/core/poly3.hpp"
#include "surfcert/core/rational.hpp"

#include <flint/fmpz.h>

#include <gtest/gtest.h>

#include <string>

using surfcert::core::InputError;
using surfcert::core::Integer;
using surfcert::core::Location;
using surfcert::core::Poly3;
using surfcert::core::Rational;
using surfcert::core::io::parse_polynomial;

namespace {

const Location kWhere{"in.json", 3, 10, "$.surfaces[0].equation"};
const char* const kPrimary = "a number, x, y, z or '('";

Poly3 parse(const std::string& s) {
  return parse_polynomial(s, kWhere);
}

const Poly3 X = Poly3::variable(0);
const Poly3 Y = Poly3::variable(1);
const Poly3 Z = Poly3::variable(2);
Poly3 c(long n) {
  return Poly3(Rational(n));
}
Poly3 c(long n, unsigned long d) {
  return Poly3(Rational(n, d));
}

// `text` must fail at 0-based `offset` (reported at column kWhere.column + offset, line and JSON
// path kept) with exactly these expected/found parts.
void expect_error(const std::string& text, int offset, const std::string& expected,
                  const std::string& found) {
  SCOPED_TRACE("input: " + (text.size() <= 80 ? text : text.substr(0, 80) + "..."));
  try {
    Poly3 p = parse(text);
    ADD_FAILURE() << "no error; parsed as " << p.to_string();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().source, "in.json");
    EXPECT_EQ(e.where().line, 3);
    EXPECT_EQ(e.where().column, 10 + offset);
    EXPECT_EQ(e.where().json_path, "$.surfaces[0].equation");
    EXPECT_EQ(e.expected(), expected);
    EXPECT_EQ(e.found(), found);
  }
}

} // namespace

TEST(Expression, DecimalsAreExact) {
  Poly3 p = parse("0.1x^2");
  ASSERT_EQ(p.terms().size(), 1u);
  EXPECT_EQ(p.coeff(2, 0, 0), Rational(1, 10));
  EXPECT_EQ(parse("0.1 + 0.2"), c(3, 10)); // not 0.30000000000000004
  EXPECT_EQ(parse(".5"), c(1, 2));
  EXPECT_EQ(parse("1.5e-3"), c(3, 2000));
  EXPECT_EQ(parse("2E4"), c(20000));
  EXPECT_EQ(parse("2e+3x"), X.scaled(Rational(2000)));
  EXPECT_EQ(parse("1e-0000003"), c(1, 1000));
  EXPECT_EQ(parse("007"), c(7));
}

TEST(Expression, BigIntegersAreExact) {
  Poly3 p = parse("123456789012345678901234567890123456789 x - 1/98765432109876543210");
  Rational big(*Integer::from_string("123456789012345678901234567890123456789"));
  Rational small(Integer(1), *Integer::from_string("98765432109876543210"));
  EXPECT_EQ(p.coeff(1, 0, 0), big);
  EXPECT_EQ(p.coeff(0, 0, 0), -small);
  EXPECT_EQ(p.terms().size(), 2u);
}

TEST(Expression, PowersAndProducts) {
  EXPECT_EQ(parse("(x+y)^2"), (X + Y) * (X + Y));
  EXPECT_EQ(parse("(x+y)^2").coeff(1, 1, 0), Rational(2));
  EXPECT_EQ(parse("x**3"), X * X * X);
  EXPECT_EQ(parse("x^(3)"), X * X * X);
  EXPECT_EQ(parse("x ^ ( 2 )"), X * X);
  EXPECT_EQ(parse("x^0"), c(1));
  EXPECT_EQ(parse("(x - 1)^3"), (X - c(1)) * (X - c(1)) * (X - c(1)));
  EXPECT_EQ(parse("x^64"), X.pow(64));
  EXPECT_EQ(parse("x^064"), X.pow(64)); // leading zeros in the exponent
  EXPECT_EQ(parse("2*3*x*y*z"), (X * Y * Z).scaled(Rational(6)));
}

TEST(Expression, ImplicitMultiplication) {
  EXPECT_EQ(parse("2x"), X.scaled(Rational(2)));
  EXPECT_EQ(parse("2(x+1)"), X.scaled(Rational(2)) + c(2));
  EXPECT_EQ(parse("x y"), X * Y);
  EXPECT_EQ(parse("xy"), X * Y);
  EXPECT_EQ(parse("xyz"), X * Y * Z);
  EXPECT_EQ(parse("3x^2y"), (X * X * Y).scaled(Rational(3)));
  EXPECT_EQ(parse("xy^2"), X * Y * Y); // the exponent binds to y only
  EXPECT_EQ(parse("(x+1)(x-1)"), X * X - c(1));
  EXPECT_EQ(parse("x(y)z"), X * Y * Z);
  EXPECT_EQ(parse("X Y Z"), X * Y * Z);
  EXPECT_EQ(parse("0.5x 0.5y"), (X * Y).scaled(Rational(1, 4)));
}

TEST(Expression, UnaryMinus) {
  EXPECT_EQ(parse("-x^2"), -(X * X));
  EXPECT_EQ(parse("-x^2").coeff(2, 0, 0), Rational(-1));
  EXPECT_EQ(parse("-2^2"), c(-4));
  EXPECT_EQ(parse("(-2)^2"), c(4));
  EXPECT_EQ(parse("+x"), X);
  EXPECT_EQ(parse("2*-x"), X.scaled(Rational(-2)));
  EXPECT_EQ(parse("2*-x^2"), (X * X).scaled(Rational(-2)));
  EXPECT_EQ(parse("x/-2"), X.scaled(Rational(-1, 2)));
  EXPECT_EQ(parse("x + -1"), X - c(1));
  EXPECT_EQ(parse("x - -1"), X + c(1));
  EXPECT_EQ(parse("-(x - y)"), Y - X);
}

TEST(Expression, Division) {
  EXPECT_EQ(parse("x^2/1/4"), (X * X).scaled(Rational(1, 4)));
  EXPECT_EQ(parse("x^2/4"), (X * X).scaled(Rational(1, 4)));
  EXPECT_EQ(parse("1/2x"), X.scaled(Rational(1, 2))); // left to right: (1/2)*x
  EXPECT_EQ(parse("6/3/2"), c(1));
  EXPECT_EQ(parse("x/(1+1)"), X.scaled(Rational(1, 2)));
  EXPECT_EQ(parse("(x+y)/0.5"), (X + Y).scaled(Rational(2)));
  EXPECT_EQ(parse("x^2/9 + y^2/4 + z^2 = 1"),
            (X * X).scaled(Rational(1, 9)) + (Y * Y).scaled(Rational(1, 4)) + Z * Z - c(1));
}

TEST(Expression, Equations) {
  EXPECT_EQ(parse("x^2 + y^2 = 1"), X * X + Y * Y - c(1));
  EXPECT_EQ(parse("z = x y"), Z - X * Y);
  EXPECT_EQ(parse("x = x"), Poly3());
  EXPECT_TRUE(parse("x - x").is_zero());
  EXPECT_EQ(parse(" \t x ^ 2 *\n3 = 0 "), (X * X).scaled(Rational(3)));
}

TEST(Expression, LargestAllowedDensePower) {
  Poly3 p = parse("(1 + x + y + z)^64");
  EXPECT_EQ(p.total_degree(), 64);
  EXPECT_EQ(p.terms().size(), 47905u); // all monomials of degree <= 64 in 3 variables
  EXPECT_EQ(p.coeff(0, 0, 64), Rational(1));
  EXPECT_EQ(p.coeff(1, 0, 0), Rational(64));
}

TEST(ExpressionErrors, Primaries) {
  expect_error("", 0, kPrimary, "end of input");
  expect_error("   ", 3, kPrimary, "end of input");
  expect_error("x + @", 4, kPrimary, "'@'");
  expect_error("x +", 3, kPrimary, "end of input");
  expect_error("x = ", 4, kPrimary, "end of input");
  expect_error("= 1", 0, kPrimary, "'='");
  expect_error("--x", 1, kPrimary, "'-'");
  expect_error("2**-x", 3, "a non-negative integer exponent", "'-'");
  expect_error("x * * y", 4, kPrimary, "'*'");
  expect_error("x\xC2\xB2", 1, "end of expression", "'\xC2\xB2'");
  expect_error("2 \xE2\x88\x92 x", 2, "end of expression", "'\xE2\x88\x92'"); // U+2212
}

TEST(ExpressionErrors, UnknownIdentifiers) {
  expect_error("w + 1", 0, kPrimary, "unknown identifier 'w'");
  expect_error("x + sin(y)", 4, kPrimary, "unknown identifier 'sin'");
  expect_error("2e", 1, kPrimary, "unknown identifier 'e'");
  expect_error("2e+x", 1, kPrimary, "unknown identifier 'e'");
  expect_error("3 x2", 2, kPrimary, "unknown identifier 'x2'");
  expect_error("2 pi", 2, kPrimary, "unknown identifier 'pi'");
}

TEST(ExpressionErrors, Parentheses) {
  expect_error("(x+1", 4, "')'", "end of input");
  expect_error("(x+1 = 2)", 5, "')'", "'='");
  expect_error("x y )", 4, "end of expression", "')'");
  expect_error("()", 1, kPrimary, "')'");
  std::string ok = std::string(256, '(') + "x" + std::string(256, ')');
  EXPECT_EQ(parse(ok), X);
  std::string deep = std::string(257, '(') + "x" + std::string(257, ')');
  expect_error(deep, 256, "at most 256 nested parentheses", "'('");
}

TEST(ExpressionErrors, Exponents) {
  expect_error("x^-2", 2, "a non-negative integer exponent", "'-'");
  expect_error("x^2.5", 2, "a non-negative integer exponent", "'2.5'");
  expect_error("x^1e2", 2, "a non-negative integer exponent", "'1e2'");
  expect_error("x^y", 2, "a non-negative integer exponent", "'y'");
  expect_error("x^", 2, "a non-negative integer exponent", "end of input");
  expect_error("x^(2", 4, "')'", "end of input");
  expect_error("x^(1+1)", 4, "')'", "'+'");
  expect_error("x^65", 2, "an exponent at most 64", "'65'");
  expect_error("x^123456789012345678901234567890", 2, "an exponent at most 64",
               "'123456789012345678901234567890'");
  expect_error("x^2^3", 3, "parentheses around a power that is raised again", "'^'");
  expect_error("x**2**3", 4, "parentheses around a power that is raised again", "'**'");
}

TEST(ExpressionErrors, Numbers) {
  expect_error("2.", 2, "a digit after '.'", "end of input");
  expect_error("2.x", 2, "a digit after '.'", "'x'");
  expect_error("1.2.3", 3, "an operator after the number '1.2'", "'.'");
  expect_error("x . 5", 2, "end of expression", "'.'");
}

TEST(ExpressionErrors, Division) {
  expect_error("1/x", 2, "a constant nonzero divisor", "'x'");
  expect_error("y / (x + 1) + 2", 4, "a constant nonzero divisor", "'(x + 1)'");
  expect_error("x/0", 2, "a constant nonzero divisor", "'0'");
  expect_error("x/0.0", 2, "a constant nonzero divisor", "'0.0'");
  expect_error("x / (1 - 1)", 4, "a constant nonzero divisor", "'(1 - 1)'");
  expect_error("x/-y^2", 2, "a constant nonzero divisor", "'-y^2'");
}

TEST(ExpressionErrors, Equations) {
  expect_error("x = y = z", 6, "at most one '='", "'='");
  expect_error("x == y", 3, kPrimary, "'='");
}

TEST(ExpressionErrors, SizeGuards) {
  const std::string degree = "a polynomial of total degree at most 64";
  expect_error("x^64*x", 4, degree, "a result of total degree 65");
  expect_error("x^64 y", 5, degree, "a result of total degree 65"); // implicit product
  expect_error("(x^2)^33", 5, degree, "a result of total degree 66");
  expect_error("(x+1)^40*(y+1)^40", 8, degree, "a result of total degree 80");
  const std::string bits = "coefficients of at most 131072 bits";
  expect_error("2 + (1e4000 x)^64", 14, bits, "a coefficient of 850432 bits");
  expect_error("1e999999", 0, bits, "'1e999999'");
  expect_error("x + 1" + std::string(40000, '0'), 4, bits, "a coefficient of 132878 bits");
  EXPECT_EQ(parse("1" + std::string(39000, '0')).coeff(0, 0, 0).num().bits(), 129556);
}

TEST(ExpressionErrors, WorkGuard) {
  // Each factor is cheap; expanding their product would need 6545^2 term products.
  const std::string text = "(1+x+y+z)^32 * (1+x+y+z)^32";
  try {
    parse(text);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().column, 10 + 13);
    EXPECT_EQ(e.expected(), "an expression expanding with at most 10000000 term operations");
    EXPECT_EQ(e.found().rfind("an expansion needing ", 0), 0u) << e.found();
  }
}

TEST(ExpressionErrors, RepeatedDivisionOfALargePolynomialIsCharged) {
  std::string text = "(1+x+y+z)^32";
  for (int i = 0; i < 2000; ++i)
    text += "/1";
  try {
    parse(text);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.expected(), "an expression expanding with at most 10000000 term operations");
  }
}

TEST(Expression, LongSumAfterALargePolynomialStaysLinear) {
  // Copying the 6545-term accumulator for each "+ 1" would take minutes; in place it is fast.
  std::string text = "(1+x+y+z)^32";
  for (int i = 0; i < 200000; ++i)
    text += " + 1";
  Poly3 p = parse(text);
  EXPECT_EQ(p.terms().size(), 6545u);
  EXPECT_EQ(p.coeff(0, 0, 0), Rational(200001));
}

TEST(ExpressionErrors, ColumnWhenLocationHasNone) {
  try {
    parse_polynomial("x+@", Location{"<argument 1>", 0, 0, ""});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().source, "<argument 1>");
    EXPECT_EQ(e.where().line, 0);
    EXPECT_EQ(e.where().column, 3);
    EXPECT_EQ(e.found(), "'@'");
  }
}

// Found with the fuzz target's round-trip property (tests/fuzz/expression_fuzz.cpp; the input
// is longer than the fuzzer's): a coefficient of exactly the bit limit times a variable was
// refused ("N*x": the size guard counted b1 + b2 bits for a product that has b1), so the printed
// form "1/N*x" of the accepted "x/N" did not read back.
TEST(ExpressionRegressions, CoefficientAtTheBitLimitTimesAVariable) {
  Integer n;
  fmpz_one_2exp(n.raw_mut(), 131071); // 2^131071: 131072 bits
  const std::string ns = n.to_string();
  Poly3 scaled = parse("x/" + ns);
  EXPECT_EQ(parse(scaled.to_string()), scaled);
  EXPECT_EQ(parse(ns + "*x"), X.scaled(Rational(n)));
  EXPECT_EQ(parse("x " + ns), X.scaled(Rational(n)));
  // One bit more is refused.
  expect_error("2x*" + ns, 2, "coefficients of at most 131072 bits",
               "a coefficient of 131073 bits");
}

// Found while writing tests/fuzz/json_fuzz.cpp: read_surface located equation errors at the
// opening quote, one column before the offending character (read_quadric counted the quote;
// the implicit-surface and parametric paths did not).
TEST(ExpressionRegressions, SurfaceEquationErrorsPointAtTheCharacter) {
  using surfcert::core::io::parse_json;
  using surfcert::core::io::read_surface;
  auto column = [](const std::string& json) {
    try {
      (void)read_surface(parse_json(json, "t"), "t", "$");
    } catch (const InputError& e) {
      return e.where().column;
    }
    return -1;
  };
  //                   1234567890123456789012
  EXPECT_EQ(column(R"("x^2 + $")"), 8);
  EXPECT_EQ(column(R"({"equation": "x^3 + $"})"), 21);
  EXPECT_EQ(column(R"({"type": "parametric", "x": "u + $", "y": "v", "z": "1"})"), 34);
}

// Found by the fuzz target under CI's sanitizers (libFuzzer timeout, 14 s): the work budget
// counted coefficient products, not their size, and the size guards formed every term of every
// intermediate result (a gcd each). (1 + y + 8e-320 z)^64 has only 2145 terms but coefficients
// of up to 68000 bits: 5 s in Release before, now refused by the work budget before the
// expansion ends; at the fuzz target's budget it is refused by the total-size limit.
TEST(ExpressionRegressions, LargeCoefficientsWeighTheWorkBudget) {
  const std::string work = "an expression expanding with at most 10000000 term operations";
  for (const std::string text : {"(1 +  y +8e-320 z)^64", "(1+x+y+8e-320 z)^40"}) {
    try {
      parse(text);
      ADD_FAILURE() << "accepted " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.expected(), work) << text;
    }
  }
  // A smaller power of the same base is accepted, and exact: the coefficient of y^a z^b is
  // 40! / (a! b! (40 - a - b)!) * (8e-320)^b.
  const Poly3 p = parse("(1 + y + 8e-320 z)^40");
  EXPECT_EQ(p.length(), 861);
  const Rational t(8, 1); // 8e-320 = 8 / 10^320
  Integer ten320(10);
  fmpz_pow_ui(ten320.raw_mut(), ten320.raw(), 320);
  const Rational small = t / Rational(ten320);
  Rational power(1);
  for (int b = 0; b < 17; ++b)
    power *= small;
  Integer multinomial; // 40! / (13! 17! 10!)
  fmpz_fac_ui(multinomial.raw_mut(), 40);
  Integer f13, f17, f10;
  fmpz_fac_ui(f13.raw_mut(), 13);
  fmpz_fac_ui(f17.raw_mut(), 17);
  fmpz_fac_ui(f10.raw_mut(), 10);
  EXPECT_EQ(p.coeff(0, 13, 17),
            Rational(multinomial) / (Rational(f13) * Rational(f17) * Rational(f10)) * power);
}

// Sums were not charged: 12000 decimal literals of 63000 to 103000 bits ("1e-19000 + 1e-19001
// + ...") took 9 s. Now each rational sum is weighted by its operands' sizes.
TEST(ExpressionRegressions, SumsOfLargeLiteralsAreCharged) {
  std::string text = "1e-19000";
  for (int i = 1; i < 12000; ++i)
    text += "+1e-" + std::to_string(19000 + i);
  try {
    parse(text);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.expected(), "an expression expanding with at most 10000000 term operations");
    EXPECT_GT(e.where().column, 10 + 8); // past the first sum
  }
  // Few such sums are accepted, exactly.
  EXPECT_EQ(parse("1e-19000 + 1e-19001 + 1e-19002"),
            Poly3(Rational::from_string("111e-19002").value()));
}

// A division by a long constant is cheap (FLINT scales the common content), but printing the
// result writes the long denominator once per term: (1+x+y+z)^30 / 1e30000 prints 165 MB. The
// coefficients' total size is limited (2^27 bits, from the stored form), on both sides.
TEST(ExpressionRegressions, TotalCoefficientSizeIsLimited) {
  try {
    parse("(1+x+y+z)^30/1e30000");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.expected(), "coefficients of at most 134217728 bits in all");
    EXPECT_EQ(e.where().column, 10 + 12); // the '/'
  }
  // 5456 terms of about 10^3000 each: 54 million bits, accepted and read back from its print.
  const Poly3 p = parse("(1+x+y+z)^30/1e3000");
  EXPECT_EQ(p.length(), 5456);
  EXPECT_EQ(p.coeff(0, 0, 30), Rational::from_string("1e-3000").value());
  EXPECT_EQ(parse(p.to_string()), p);
  // A smaller budget scales the limit down (the fuzz target's budget: a fortieth).
  try {
    parse_polynomial("(1+x+y+z)^30/1e300", kWhere, surfcert::core::io::kMaxExpressionWork / 40);
    ADD_FAILURE() << "accepted at a fortieth of the budget";
  } catch (const InputError& e) {
    EXPECT_EQ(e.expected(), "coefficients of at most 3355443 bits in all");
  }
  EXPECT_EQ(parse("(1+x+y+z)^30/1e300").length(), 5456);
}

// The coefficient-size guards first use free bounds from FLINT's stored form (content times
// integers), which over-estimate a term whose own denominator is smaller than the common one;
// only then the exact sizes decide. Probed on both sides of the 131072-bit limit.
TEST(ExpressionRegressions, CoefficientGuardsDecideOnExactSizes) {
  Integer three(3);
  fmpz_pow_ui(three.raw_mut(), three.raw(), 25000); // 39625 bits
  const std::string t = three.to_string();
  // Stored as (3^25000 x + 10^20000 y) / (10^20000 3^25000): a bound of 106064 bits per term,
  // exactly 66439 and 39625.
  const std::string a = "(x*1e-20000 + y/" + t + ")";
  const Poly3 pa = parse(a);
  EXPECT_EQ(pa.coeff(1, 0, 0), Rational::from_string("1e-20000").value());
  // A product whose bounds exceed the limit but whose exact sizes do not: 66439 + 64446 - 1.
  const Poly3 ok = parse(a + "*x*1e-19400");
  EXPECT_EQ(ok.coeff(2, 0, 0), Rational::from_string("1e-39400").value());
  // One whose exact sizes exceed it: 66439 + 64778 - 1 = 131216 bits.
  try {
    parse(a + "*x*1e-19500");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.expected(), "coefficients of at most 131072 bits");
    EXPECT_EQ(e.found(), "a coefficient of 131216 bits");
  }
  // Sums whose common denominator exceeds the limit while every term's own does not.
  const Poly3 sum = parse("x*1e-39000 + y/" + t + "/" + t + "/" + t);
  EXPECT_EQ(sum.coeff(1, 0, 0), Rational::from_string("1e-39000").value());
  EXPECT_EQ(parse(sum.to_string()), sum);
}
