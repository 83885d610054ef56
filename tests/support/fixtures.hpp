// Test helpers: load JSON fixtures from data/, convert integer matrices, compare polynomials.
#pragma once

#include "surfcert/algebra/upoly.hpp"
#include "surfcert/core/io/expression.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/quadric.hpp"

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace surfcert::fixtures {

inline core::io::Json load_json(const std::string& rel) {
  std::string path = std::string(SURFCERT_DATA_DIR) + "/" + rel;
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return core::io::parse_json(ss.str(), path);
}

/// A 4x4 rational matrix from its entries' exact texts, row by row ("3/2", "-7").
inline core::Mat4 mat4_from_strings(const std::vector<std::vector<const char*>>& rows) {
  core::Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = *core::Rational::from_string(rows[i][j]);
  return m;
}

inline core::Mat4 mat4_from_json(const core::io::Json& m) {
  core::Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      r[i][j] = *core::Rational::from_string(m.items()[i].items()[j].text());
  return r;
}

/// A sympy polynomial in `lambda` (e.g. "-(4*lambda - 9)*(...)/576") read as an exact UPolyQ,
/// through our own expression reader with lambda renamed x.
inline algebra::UPolyQ sympy_univariate(const std::string& s) {
  std::string t = std::regex_replace(s, std::regex("lambda"), "x");
  core::Poly3 p = core::io::parse_polynomial(t, core::Location{"fixture", 1, 1, ""});
  std::vector<core::Rational> c(static_cast<size_t>(std::max(0, p.total_degree()) + 1));
  for (const auto& [e, v] : p.terms())
    c[static_cast<size_t>(e[0])] = v;
  return algebra::UPolyQ::from_coeffs(c);
}

inline std::string strip_spaces(std::string s) {
  s.erase(std::remove(s.begin(), s.end(), ' '), s.end());
  return s;
}

} // namespace surfcert::fixtures
