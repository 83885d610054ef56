// surfcert::core::io::parse_polynomial: reads an equation string such as "x^2 + y^2 = 1".
//
// What it represents: the reader of the human-written form of a surface, turning text into an
// exact Poly3. Decimals are read exactly ("0.1" is 1/10, never the binary double near it), so
// the polynomial is exactly the one written. An equation "lhs = rhs" becomes lhs - rhs.
//
// Grammar (whitespace allowed between tokens):
//   input        = expr [ '=' expr ]
//   expr         = signed_term { ('+' | '-') signed_term }
//   signed_term  = [ '+' | '-' ] term
//   term         = power { ('*' | '/') signed_power | power }   (juxtaposition multiplies:
//                  "2x", "2(x+1)", "x y", "3x^2y"; a run of x/y/z letters such as "xy" is x*y)
//   signed_power = [ '+' | '-' ] power
//   power        = primary [ ('^' | '**') exponent ]   ("-x^2" is -(x^2); "x^2^3" is rejected)
//   exponent     = integer | '(' integer ')'            (0 <= exponent <= 64)
//   primary      = number | 'x' | 'y' | 'z' | 'X' | 'Y' | 'Z' | '(' expr ')'
//   number       = digits [ '.' digits ] [ exponent part ] | '.' digits [ exponent part ]
// where an 'e'/'E' after a number is an exponent part only when a digit, or a sign and a digit,
// follows. '*' and '/' (and juxtaposition) associate left to right: "x^2/1/4" is x^2/4 and
// "1/2x" is x/2. Division is only by a nonzero constant.
//
// Invariants of the result: exactly the polynomial written; total degree <= 64, at most 100000
// terms, coefficients of at most 131072 bits (numerator and denominator) and 2^27 bits in all
// at every intermediate step, and a bounded amount of coefficient arithmetic (weighted by the
// operands' sizes), so hostile input cannot exhaust time or memory, in the parser or in
// printing its result.
#pragma once

#include "surfcert/core/error.hpp"
#include "surfcert/core/poly3.hpp"

#include <string>

namespace surfcert::core::io {

/// Limits on every intermediate result of parse_polynomial.
constexpr int kMaxExpressionDegree = 64;
constexpr long kMaxExpressionTerms = 100000;
constexpr long kMaxExpressionCoefficientBits = 131072;
/// Limit on the bits of all coefficients of a result together (numerators and denominators, as
/// bounded from FLINT's storage: content times integers; about 40 MB of decimal digits once
/// printed), scaled down in proportion with a smaller work budget.
constexpr long kMaxExpressionTotalBits = 1L << 27;
/// Limit on the term operations spent expanding one expression: a product of two
/// machine-sized coefficients (with its addition into the result) is one; larger ones are
/// weighted by their measured cost relative to that (about la * lb^0.6 / 5 for integers of
/// la >= lb 64-bit limbs), and so are rational sums. The whole budget is about 0.2 s of work
/// (Release, one core); (1+x+y+z)^64 needs 5 million, (1 + y + 8e-320 z)^64 is refused.
constexpr long kMaxExpressionWork = 10000000;
/// Limit on nested parentheses (the reader is recursive).
constexpr int kMaxExpressionNesting = 256;

/// Parses `text` (grammar above). `where` locates the text: its column is that of the text's
/// first character. Errors throw InputError at `where` with the column moved to the offending
/// character (where.column + its 0-based offset in code points, or offset + 1 when where.column
/// is 0); the line is kept. Empty input is an error.
Poly3 parse_polynomial(const std::string& text, const Location& where);

/// The same with a smaller budget of term operations, 1 <= max_work <= kMaxExpressionWork
/// (checked: InternalError otherwise). For the fuzz target (tests/fuzz): under its sanitizers a
/// term operation is about 20 times slower, and a full budget would exceed its time limit.
Poly3 parse_polynomial(const std::string& text, const Location& where, long max_work);

} // namespace surfcert::core::io
