// libFuzzer target of the JSON reader (surfcert::core::io::parse_json) and of the SURFACE reader
// behind it (read_surface). Built by -DSURFCERT_BUILD_FUZZ=ON with clang; run by scripts/fuzz.sh.
//
// Properties checked on every input:
//  * accepted text: every value has a position (line, column >= 1); dump(v) re-parses to a
//    value equal to v (same types, number texts, string bytes, member order), and so does the
//    pretty dump; dumping that value again gives the same text (dump is a fixed point);
//  * rejected text: an InputError located in the source (line >= 1, column >= 1), never
//    another exception type (the sanitizers catch crashes and undefined behaviour);
//  * read_surface on the document (and on the items of an array or of a "surfaces" array):
//    a surface or an InputError with a line and column, nothing else.
#include "surfcert/core/error.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

using surfcert::core::InputError;
using surfcert::core::io::dump;
using surfcert::core::io::Json;
using surfcert::core::io::parse_json;

namespace {

const char* const kSource = "fuzz.json";

[[noreturn]] void violation(const std::string& what, const std::string& input) {
  std::fprintf(stderr, "json_fuzz: property violated: %s\ninput (%zu bytes): %s\n", what.c_str(),
               input.size(), input.substr(0, 400).c_str());
  std::abort();
}

bool equal(const Json& a, const Json& b) {
  if (a.type() != b.type()) return false;
  switch (a.type()) {
  case Json::Type::Null:
    return true;
  case Json::Type::Bool:
    return a.as_bool() == b.as_bool();
  case Json::Type::Number:
  case Json::Type::String:
    return a.text() == b.text();
  case Json::Type::Array:
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!equal(a.items()[i], b.items()[i])) return false;
    return true;
  case Json::Type::Object:
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (a.members()[i].first != b.members()[i].first ||
          !equal(a.members()[i].second, b.members()[i].second))
        return false;
    return true;
  }
  return false;
}

bool positioned(const Json& v) {
  if (v.line() < 1 || v.column() < 1) return false;
  if (v.is_array())
    for (const Json& item : v.items())
      if (!positioned(item)) return false;
  if (v.is_object())
    for (const auto& m : v.members())
      if (!positioned(m.second)) return false;
  return true;
}

void check_located(const InputError& e, const std::string& input) {
  const auto& w = e.where();
  if (w.source != kSource || w.line < 1 || w.column < 1)
    violation("InputError without a location: " + std::string(e.what()), input);
}

Json reparse(const std::string& text, const std::string& input) {
  try {
    return parse_json(text, kSource);
  } catch (const InputError& e) {
    violation("dump output rejected: " + std::string(e.what()) + "\ndump: " + text.substr(0, 400),
              input);
  }
}

void read_surface_checked(const Json& v, const std::string& path, const std::string& input) {
  if (!v.is_string() && !v.is_object()) return;
  try {
    (void)surfcert::core::io::read_surface(v, kSource, path);
  } catch (const InputError& e) {
    check_located(e, input);
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  try {
    Json v;
    try {
      v = parse_json(input, kSource);
    } catch (const InputError& e) {
      check_located(e, input);
      return 0;
    }
    if (!positioned(v)) violation("a parsed value without a position", input);
    const std::string compact = dump(v);
    const Json v2 = reparse(compact, input);
    if (!equal(v, v2)) violation("parse(dump(v)) != v; dump: " + compact.substr(0, 400), input);
    if (dump(v2) != compact) violation("dump(parse(dump(v))) != dump(v)", input);
    const Json v3 = reparse(dump(v, 2), input);
    if (!equal(v, v3)) violation("parse(dump(v, 2)) != v", input);

    read_surface_checked(v, "$", input);
    if (v.is_array())
      for (std::size_t i = 0; i < v.size() && i < 8; ++i)
        read_surface_checked(v.items()[i], surfcert::core::io::json_path_index("$", i), input);
    if (v.is_object())
      if (const Json* s = v.find("surfaces"); s && s->is_array())
        for (std::size_t i = 0; i < s->size() && i < 8; ++i)
          read_surface_checked(s->items()[i], "$.surfaces[" + std::to_string(i) + "]", input);
  } catch (const InputError& e) {
    violation("InputError escaped the checks: " + std::string(e.what()), input);
  } catch (const std::exception& e) {
    violation("exception other than InputError: " + std::string(e.what()), input);
  }
  return 0;
}
