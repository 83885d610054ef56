// surfcert::core::io::Json: a small JSON document model, used to read input and write reports.
//
// What it represents: one JSON value (RFC 8259) as a tree. Numbers are kept as their literal
// text exactly as written, never converted to a machine type, so that big integers and decimals
// reach the exact readers (Rational::from_string) unrounded, and writers put them out verbatim.
// Objects keep their members in insertion order (a vector of pairs, so reports are written in
// a stable, readable order); a parsed object never has two members with the same key, and set()
// keeps it that way. Every parsed value remembers the 1-based line and column (counted in
// Unicode code points) of its first character; values built in code have line() == 0.
// Strings hold UTF-8; parse_json() rejects text that is not valid UTF-8.
// Misusing an accessor (as_bool() on a string, items() on an object, ...) is a programming
// error and throws InternalError: readers check the type first and report an InputError.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace surfcert::core::io {

namespace detail {
class JsonParser;
} // namespace detail

class Json {
public:
  enum class Type { Null, Bool, Number, String, Array, Object };
  using Member = std::pair<std::string, Json>;

  /// The null value.
  Json() = default;

  static Json null() { return Json(); }
  static Json boolean(bool b);
  /// Precondition: `text` is a valid JSON number (checked: throws InternalError otherwise).
  static Json number_text(std::string text);
  static Json number(long n);
  /// A double as the text printf("%.17g") gives (it reads back as the same double), written
  /// by append_json_double (the same characters, far faster than printf). Precondition: x
  /// finite (checked: throws InternalError).
  static Json number_double(double x);
  static Json string(std::string s);
  static Json array();
  static Json object();

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::Null; }
  bool is_bool() const { return type_ == Type::Bool; }
  bool is_number() const { return type_ == Type::Number; }
  bool is_string() const { return type_ == Type::String; }
  bool is_array() const { return type_ == Type::Array; }
  bool is_object() const { return type_ == Type::Object; }

  bool as_bool() const;
  /// A number's literal text or a string's (unescaped, UTF-8) value.
  const std::string& text() const;
  const std::vector<Json>& items() const;
  const std::vector<Member>& members() const;
  /// Moves an object's members out (the object is left with none): for a writer that merges
  /// one built envelope into another without copying its tree (an answer's branches).
  std::vector<Member> take_members();
  /// The member named `key` of an object, or nullptr when there is none.
  const Json* find(const std::string& key) const;
  /// Number of items of an array or members of an object.
  std::size_t size() const;

  /// Appends to an array.
  void push_back(Json v);
  /// Reserves room for n items of an array (writers that know the count: one allocation).
  void reserve(std::size_t n);
  /// Sets a member of an object: replaces the value if `key` exists (keeping its place),
  /// otherwise appends.
  void set(const std::string& key, Json v);

  /// 1-based position of the value's first character in the parsed text; 0 when built in code.
  int line() const { return line_; }
  int column() const { return column_; }
  void set_position(int line, int column) {
    line_ = line;
    column_ = column;
  }

private:
  // The parser checks key uniqueness itself (in O(log n)) and appends without set()'s search.
  friend class detail::JsonParser;

  Type type_ = Type::Null;
  bool bool_ = false;
  std::string text_;
  std::vector<Json> items_;
  std::vector<Member> members_;
  int line_ = 0;
  int column_ = 0;
};

/// "null", "a boolean", "a number", "a string", "an array", "an object": for error messages.
const char* type_name(Json::Type t);

/// Parses exactly one JSON value (surrounding whitespace allowed; a leading UTF-8 byte order
/// mark is skipped). Strict RFC 8259: no comments, trailing commas, NaN/Infinity, leading zeros
/// or unescaped control characters; duplicate object keys and nesting deeper than 256 are
/// rejected. Throws InputError with Location{source_name, line, column, ""}.
Json parse_json(const std::string& text, const std::string& source_name);

/// Serialises `v`. indent < 0: compact, one line, no spaces (for JSONL). indent >= 0: one item
/// per line, nested levels indented by `indent` spaces, no trailing newline. Numbers are written
/// as their text; strings escape '"', '\\' and control characters and keep UTF-8 as is (bytes
/// that are not valid UTF-8 are written as U+FFFD so that the output is always valid JSON).
std::string dump(const Json& v, int indent = -1);

/// Appends the string `s` as dump() writes a string value (quoted and escaped, see above): for
/// writers that put out JSON text directly and must match dump() byte for byte.
void append_json_string(std::string& out, std::string_view s);

/// Appends x as Json::number_double's text (printf "%.17g"; std::to_chars' characters): for
/// writers that put out JSON text directly. Most doubles (1e-4 <= |x| < 2^53) take an exact
/// integer route ~10x faster than std::to_chars. Precondition: x finite (checked: throws
/// InternalError).
void append_json_double(std::string& out, double x);

/// JSON path of a member: parent + ".key", or parent + "[\"key\"]" when key is not an
/// identifier ([A-Za-z_][A-Za-z0-9_]*). The root path is "$".
std::string json_path_child(const std::string& parent, const std::string& key);
/// JSON path of an array item: parent + "[i]".
std::string json_path_index(const std::string& parent, std::size_t i);

} // namespace surfcert::core::io
