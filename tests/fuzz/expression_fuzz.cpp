// libFuzzer target of the expression parser (surfcert::core::io::parse_polynomial) and of
// quadric_from_equation. Built by -DSURFCERT_BUILD_FUZZ=ON with clang; run by scripts/fuzz.sh.
//
// Properties checked on every input:
//  * accepted text (within a smaller work budget, kFuzzWork): the polynomial p printed by
//    Poly3::to_string re-parses to exactly p (and that text is a fixed point); an equation of
//    degree 1 or 2 gives a quadric whose to_poly() is exactly p (quadric_from_equation), any
//    other degree an InputError;
//  * rejected text: an InputError on line kWhere.line, at a column >= kWhere.column (the
//    offending character), with the JSON path kept; never another exception type (the
//    sanitizers catch crashes and undefined behaviour).
// The input is also parsed with an unknown location (line 0, column 0): columns are then 1-based
// offsets, >= 1.
#include "surfcert/core/error.hpp"
#include "surfcert/core/io/expression.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/core/poly3.hpp"
#include "surfcert/core/quadric.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>

using surfcert::core::InputError;
using surfcert::core::Location;
using surfcert::core::Poly3;
using surfcert::core::io::parse_polynomial;

namespace {

const Location kWhere{"fuzz", 3, 7, "$.equation"};
const Location kNowhere{"fuzz", 0, 0, ""};
// A fortieth of kMaxExpressionWork: the sanitizers and the coverage instrumentation make a
// term operation about 20 times slower, and -timeout=10 must only catch real hangs. Inputs over
// this budget still exercise the refusal (an InputError at the operator).
constexpr long kFuzzWork = surfcert::core::io::kMaxExpressionWork / 40;

[[noreturn]] void violation(const std::string& what, const std::string& input) {
  std::fprintf(stderr, "expression_fuzz: property violated: %s\ninput (%zu bytes): %s\n",
               what.c_str(), input.size(), input.substr(0, 400).c_str());
  std::abort();
}

void check_located(const InputError& e, const Location& where, const std::string& input) {
  const Location& w = e.where();
  bool ok = w.source == where.source && w.json_path == where.json_path && w.line == where.line &&
            w.column >= (where.column == 0 ? 1 : where.column) &&
            static_cast<std::size_t>(w.column) <=
                input.size() + 1 + static_cast<std::size_t>(where.column);
  if (!ok) violation("InputError badly located: " + std::string(e.what()), input);
}

std::optional<Poly3> parse_checked(const std::string& text, const Location& where) {
  try {
    return parse_polynomial(text, where, kFuzzWork);
  } catch (const InputError& e) {
    check_located(e, where, text);
    return std::nullopt;
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  try {
    std::optional<Poly3> p = parse_checked(input, kWhere);
    std::optional<Poly3> p0 = parse_checked(input, kNowhere);
    if (p.has_value() != p0.has_value() || (p && !(*p == *p0)))
      violation("the result depends on the location", input);
    if (!p) return 0;

    const std::string printed = p->to_string();
    Poly3 q;
    try {
      q = parse_polynomial(printed, kWhere);
    } catch (const InputError& e) {
      violation("to_string output rejected: " + std::string(e.what()) +
                    "\nprinted: " + printed.substr(0, 400),
                input);
    }
    if (!(q == *p))
      violation("parse(to_string(p)) != p; printed: " + printed.substr(0, 400), input);
    if (q.to_string() != printed) violation("to_string is not a fixed point", input);

    const int d = p->total_degree();
    try {
      auto m = surfcert::core::io::quadric_from_equation(input, kWhere);
      if (d < 1 || d > 2) violation("a quadric from degree " + std::to_string(d), input);
      if (!(m.to_poly() == *p)) violation("quadric_from_equation(p).to_poly() != p", input);
    } catch (const InputError& e) {
      if (d >= 1 && d <= 2) violation("quadric refused: " + std::string(e.what()), input);
      if (e.where().line != kWhere.line || e.where().column < 1)
        violation("quadric error badly located: " + std::string(e.what()), input);
    }
  } catch (const std::exception& e) {
    violation("exception other than InputError: " + std::string(e.what()), input);
  }
  return 0;
}
