#include "surfcert/core/io/json.hpp"

#include "surfcert/core/error.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <set>
#include <string_view>
#include <system_error>

namespace surfcert::core::io {

namespace {

constexpr int kMaxDepth = 256;

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// Length of the well-formed UTF-8 sequence starting at s[i] (1..4), or 0 when the bytes there
// are not one (overlong forms, surrogates and code points above U+10FFFF are ill-formed).
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t len = 0;
  unsigned char lo = 0x80, hi = 0xBF; // allowed range of the second byte
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    len = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    len = 3;
    if (b0 == 0xE0) lo = 0xA0;
    if (b0 == 0xED) hi = 0x9F;
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    len = 4;
    if (b0 == 0xF0) lo = 0x90;
    if (b0 == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + len > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < len; ++k)
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  return len;
}

void append_utf8(std::string& out, unsigned long cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

std::string hex_byte(unsigned char b) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%02X", static_cast<unsigned>(b));
  return buf;
}

// How the character at s[i] is named in an error's "found" part.
std::string describe_char(const std::string& s, std::size_t i) {
  if (i >= s.size()) return "end of input";
  auto b = static_cast<unsigned char>(s[i]);
  if (b == '\n') return "newline";
  if (b == '\r') return "carriage return";
  if (b == '\t') return "tab";
  if (b < 0x20 || b == 0x7F) return "control character U+00" + hex_byte(b);
  if (b < 0x80) return std::string("'") + static_cast<char>(b) + "'";
  std::size_t len = utf8_sequence_length(s, i);
  if (len == 0) return "byte 0x" + hex_byte(b) + " (not UTF-8)";
  return "'" + s.substr(i, len) + "'";
}

// Length of the JSON number starting at s[i], 0 when there is none. Grammar (RFC 8259):
// -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?
std::size_t json_number_length(const std::string& s, std::size_t i) {
  std::size_t p = i;
  auto digit_at = [&](std::size_t k) { return k < s.size() && is_digit(s[k]); };
  if (p < s.size() && s[p] == '-') ++p;
  if (!digit_at(p)) return 0;
  if (s[p] == '0') {
    ++p;
  } else {
    while (digit_at(p))
      ++p;
  }
  if (p < s.size() && s[p] == '.') {
    if (!digit_at(p + 1)) return 0;
    ++p;
    while (digit_at(p))
      ++p;
  }
  if (p < s.size() && (s[p] == 'e' || s[p] == 'E')) {
    std::size_t q = p + 1;
    if (q < s.size() && (s[q] == '+' || s[q] == '-')) ++q;
    if (!digit_at(q)) return 0;
    while (digit_at(q))
      ++q;
    p = q;
  }
  return p - i;
}

} // namespace

namespace detail {

class JsonParser {
public:
  JsonParser(const std::string& text, std::string source) : s_(text), source_(std::move(source)) {}

  Json parse_document() {
    // RFC 8259 section 8.1 allows a parser to ignore a byte order mark; editors add one.
    if (s_.compare(0, 3, "\xEF\xBB\xBF") == 0) {
      pos_ = 3;
      // The mark is invisible in editors, so it does not count as a column.
    }
    skip_ws();
    Json v = parse_value(0, "a JSON value");
    skip_ws();
    if (pos_ < s_.size()) fail("end of input after the JSON value");
    return v;
  }

private:
  [[noreturn]] void fail(const std::string& expected) { fail(expected, describe_char(s_, pos_)); }
  [[noreturn]] void fail(const std::string& expected, const std::string& found) {
    throw InputError(Location{source_, line_, column_, ""}, expected, found);
  }

  bool at_end() const { return pos_ >= s_.size(); }
  char peek() const { return at_end() ? '\0' : s_[pos_]; }

  // Consumes one byte, keeping line and column (code points: continuation bytes don't count).
  void advance() {
    auto b = static_cast<unsigned char>(s_[pos_++]);
    if (b == '\n') {
      ++line_;
      column_ = 1;
    } else if ((b & 0xC0) != 0x80) {
      ++column_;
    }
  }

  void skip_ws() {
    while (!at_end()) {
      char c = s_[pos_];
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r') break;
      advance();
    }
  }

  Json parse_value(int depth, const char* expected) {
    int line = line_, column = column_;
    Json v;
    char c = peek();
    if (at_end()) fail(expected);
    if (c == '{') {
      v = parse_object(depth + 1);
    } else if (c == '[') {
      v = parse_array(depth + 1);
    } else if (c == '"') {
      v = Json::string(parse_string());
    } else if (c == '-' || is_digit(c)) {
      v = parse_number();
    } else if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_') {
      // Read the whole word so that the message names "NaN" or "True", not just a letter.
      std::size_t end = pos_;
      while (end < s_.size() &&
             (std::isalnum(static_cast<unsigned char>(s_[end])) != 0 || s_[end] == '_'))
        ++end;
      std::string word = s_.substr(pos_, end - pos_);
      if (word == "true" || word == "false") {
        v = Json::boolean(word == "true");
      } else if (word == "null") {
        v = Json::null();
      } else {
        fail(expected, "'" + word + "'");
      }
      for (std::size_t k = 0; k < word.size(); ++k)
        advance();
    } else {
      fail(expected);
    }
    v.set_position(line, column);
    return v;
  }

  Json parse_number() {
    std::size_t start = pos_;
    if (peek() == '-') advance();
    if (!is_digit(peek())) fail("a digit after '-'");
    if (peek() == '0') {
      advance();
      if (is_digit(peek())) fail("a number without leading zeros");
    } else {
      while (is_digit(peek()))
        advance();
    }
    if (peek() == '.') {
      advance();
      if (!is_digit(peek())) fail("a digit after the decimal point");
      while (is_digit(peek()))
        advance();
    }
    if (peek() == 'e' || peek() == 'E') {
      advance();
      if (peek() == '+' || peek() == '-') advance();
      if (!is_digit(peek())) fail("a digit in the exponent");
      while (is_digit(peek()))
        advance();
    }
    return Json::number_text(s_.substr(start, pos_ - start));
  }

  unsigned long parse_hex4() {
    unsigned long v = 0;
    for (int k = 0; k < 4; ++k) {
      char c = peek();
      int d = -1;
      if (c >= '0' && c <= '9') d = c - '0';
      if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
      if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
      if (d < 0 || at_end()) fail("4 hex digits after '\\u'");
      v = v * 16 + static_cast<unsigned long>(d);
      advance();
    }
    return v;
  }

  std::string parse_string() {
    advance(); // opening quote
    std::string out;
    for (;;) {
      if (at_end()) fail("a string character or closing '\"'");
      auto b = static_cast<unsigned char>(s_[pos_]);
      if (b == '"') {
        advance();
        return out;
      }
      if (b < 0x20) fail("a string character or closing '\"' (control characters must be escaped)");
      if (b == '\\') {
        advance();
        char e = peek();
        if (at_end()) fail("an escape character after '\\'");
        switch (e) {
        case '"':
          out += '"';
          break;
        case '\\':
          out += '\\';
          break;
        case '/':
          out += '/';
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          advance();
          unsigned long cp = parse_hex4();
          if (cp >= 0xDC00 && cp <= 0xDFFF) {
            // Report at the backslash of the offending escape: 6 bytes back.
            pos_ -= 6;
            column_ -= 6;
            fail("a high surrogate (\\uD800-\\uDBFF) before a low surrogate",
                 "'" + s_.substr(pos_, 6) + "'");
          }
          if (cp >= 0xD800 && cp <= 0xDBFF) {
            if (peek() != '\\' || pos_ + 1 >= s_.size() || s_[pos_ + 1] != 'u')
              fail("a low surrogate escape (\\uDC00-\\uDFFF) after a high surrogate");
            std::size_t esc_pos = pos_;
            int esc_col = column_;
            advance();
            advance();
            unsigned long lo = parse_hex4();
            if (lo < 0xDC00 || lo > 0xDFFF) {
              pos_ = esc_pos;
              column_ = esc_col;
              fail("a low surrogate escape (\\uDC00-\\uDFFF) after a high surrogate",
                   "'" + s_.substr(esc_pos, 6) + "'");
            }
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          append_utf8(out, cp);
          continue; // parse_hex4 consumed the digits
        }
        default:
          fail("an escape character ('\"', '\\', '/', 'b', 'f', 'n', 'r', 't' or 'u') after "
               "'\\'");
        }
        advance();
        continue;
      }
      if (b < 0x80) {
        out += static_cast<char>(b);
        advance();
        continue;
      }
      std::size_t len = utf8_sequence_length(s_, pos_);
      if (len == 0) fail("valid UTF-8");
      out.append(s_, pos_, len);
      for (std::size_t k = 0; k < len; ++k)
        advance();
    }
  }

  void check_depth(int depth) {
    if (depth > kMaxDepth) fail("nesting depth at most " + std::to_string(kMaxDepth));
  }

  Json parse_array(int depth) {
    check_depth(depth);
    advance(); // '['
    Json a = Json::array();
    skip_ws();
    if (peek() == ']') {
      advance();
      return a;
    }
    a.push_back(parse_value(depth, "a JSON value or ']'"));
    for (;;) {
      skip_ws();
      if (peek() == ']') {
        advance();
        return a;
      }
      if (peek() != ',') fail("',' or ']' after array element");
      advance();
      skip_ws();
      a.push_back(parse_value(depth, "a JSON value"));
    }
  }

  Json parse_object(int depth) {
    check_depth(depth);
    advance(); // '{'
    Json o = Json::object();
    std::set<std::string> seen; // set() is linear; this keeps large objects O(n log n)
    skip_ws();
    if (peek() == '}') {
      advance();
      return o;
    }
    const char* expected_key = "a string key or '}'";
    for (;;) {
      if (peek() != '"') fail(expected_key);
      int key_line = line_, key_column = column_;
      std::string key = parse_string();
      if (!seen.insert(key).second) {
        line_ = key_line;
        column_ = key_column;
        fail("a key not already used in this object", "duplicate key " + dump(Json::string(key)));
      }
      skip_ws();
      if (peek() != ':') fail("':' after object key");
      advance();
      skip_ws();
      Json v = parse_value(depth, "a JSON value");
      // Keys are known to be new, so append directly instead of set()'s linear search.
      o.members_.emplace_back(std::move(key), std::move(v));
      skip_ws();
      if (peek() == '}') {
        advance();
        return o;
      }
      if (peek() != ',') fail("',' or '}' after object member");
      advance();
      skip_ws();
      expected_key = "a string key";
    }
  }

  const std::string& s_;
  std::string source_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
};

} // namespace detail

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (std::size_t i = 0; i < s.size();) {
    // A run of bytes written as they are (printable ASCII other than '"' and '\\'): at once.
    std::size_t e = i;
    while (e < s.size()) {
      const auto c = static_cast<unsigned char>(s[e]);
      if (c < 0x20 || c >= 0x80 || c == '"' || c == '\\') break;
      ++e;
    }
    if (e > i) {
      out.append(s.data() + i, e - i);
      i = e;
      if (i == s.size()) break;
    }
    auto b = static_cast<unsigned char>(s[i]);
    if (b >= 0x80) {
      std::size_t len = utf8_sequence_length(s, i);
      if (len == 0) {
        out += "\\ufffd";
        ++i;
      } else {
        out.append(s, i, len);
        i += len;
      }
      continue;
    }
    switch (b) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\b':
      out += "\\b";
      break;
    case '\f':
      out += "\\f";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\r':
      out += "\\r";
      break;
    case '\t':
      out += "\\t";
      break;
    default:
      if (b < 0x20) {
        // Lower-case hex, as JSON.stringify and Python's json.dumps write it.
        static const char* const hex = "0123456789abcdef";
        out += "\\u00";
        out += hex[b >> 4];
        out += hex[b & 0xF];
      } else {
        out += static_cast<char>(b);
      }
    }
    ++i;
  }
  out += '"';
}

namespace {

void newline_indent(std::string& out, int indent, int level) {
  out += '\n';
  out.append(static_cast<std::size_t>(indent) * static_cast<std::size_t>(level), ' ');
}

void dump_value(std::string& out, const Json& v, int indent, int level) {
  switch (v.type()) {
  case Json::Type::Null:
    out += "null";
    return;
  case Json::Type::Bool:
    out += v.as_bool() ? "true" : "false";
    return;
  case Json::Type::Number:
    out += v.text();
    return;
  case Json::Type::String:
    append_json_string(out, v.text());
    return;
  case Json::Type::Array: {
    if (v.items().empty()) {
      out += "[]";
      return;
    }
    out += '[';
    bool first = true;
    for (const Json& item : v.items()) {
      if (!first) out += ',';
      first = false;
      if (indent >= 0) newline_indent(out, indent, level + 1);
      dump_value(out, item, indent, level + 1);
    }
    if (indent >= 0) newline_indent(out, indent, level);
    out += ']';
    return;
  }
  case Json::Type::Object: {
    if (v.members().empty()) {
      out += "{}";
      return;
    }
    out += '{';
    bool first = true;
    for (const auto& [key, value] : v.members()) {
      if (!first) out += ',';
      first = false;
      if (indent >= 0) newline_indent(out, indent, level + 1);
      append_json_string(out, key);
      out += indent >= 0 ? ": " : ":";
      dump_value(out, value, indent, level + 1);
    }
    if (indent >= 0) newline_indent(out, indent, level);
    out += '}';
    return;
  }
  }
}

[[noreturn]] void misuse(const char* what, Json::Type t) {
  throw InternalError(std::string("Json::") + what + " called on " + type_name(t));
}

} // namespace

Json Json::boolean(bool b) {
  Json v;
  v.type_ = Type::Bool;
  v.bool_ = b;
  return v;
}

Json Json::number_text(std::string text) {
  if (text.empty() || json_number_length(text, 0) != text.size())
    throw InternalError("Json::number_text: not a JSON number: '" + text + "'");
  Json v;
  v.type_ = Type::Number;
  v.text_ = std::move(text);
  return v;
}

namespace {

// The 17 significant digits printf("%.17g") gives for ax in [1e-4, 2^53) (where it writes no
// exponent), exactly: ax = m 2^-q with m < 2^53, so ax 10^k = m 5^k 2^(k-q) is an integer
// (at most 116 bits for k <= 27) shifted right, rounded half to even as glibc rounds the exact
// binary value. d in [10^16, 10^17), ax ~ d 10^(e - 16). False outside that range (the caller
// falls back to std::to_chars, several times slower).
// GCC's and Clang's 128-bit integers (__extension__: not ISO C++, hence -Wpedantic's silence).
__extension__ using U128 = unsigned __int128;

bool digits17(double ax, uint64_t& d, int& e) {
  if (!(ax >= 1e-4 && ax < 0x1p53)) return false;
  static constexpr uint64_t pow5[28] = {1ULL,
                                        5ULL,
                                        25ULL,
                                        125ULL,
                                        625ULL,
                                        3125ULL,
                                        15625ULL,
                                        78125ULL,
                                        390625ULL,
                                        1953125ULL,
                                        9765625ULL,
                                        48828125ULL,
                                        244140625ULL,
                                        1220703125ULL,
                                        6103515625ULL,
                                        30517578125ULL,
                                        152587890625ULL,
                                        762939453125ULL,
                                        3814697265625ULL,
                                        19073486328125ULL,
                                        95367431640625ULL,
                                        476837158203125ULL,
                                        2384185791015625ULL,
                                        11920928955078125ULL,
                                        59604644775390625ULL,
                                        298023223876953125ULL,
                                        1490116119384765625ULL,
                                        7450580596923828125ULL};
  uint64_t bits = 0;
  std::memcpy(&bits, &ax, sizeof bits);
  const int biased = static_cast<int>(bits >> 52); // ax is positive and normal here
  const uint64_t m = (bits & ((1ULL << 52) - 1)) | (1ULL << 52);
  const int q = 1075 - biased;  // ax = m 2^-q, 0 <= q <= 66
  const int e2 = biased - 1023; // 2^e2 <= ax < 2^(e2 + 1)
  constexpr uint64_t p16 = 10000000000000000ULL, p17 = 100000000000000000ULL;
  e = (e2 * 1233) >> 12; // floor(e2 log10 2): e or e - 1 (corrected below)
  for (int tries = 0; tries < 3; ++tries) {
    const int k = 16 - e;
    if (k < 0 || k > 27 || q < k) return false;
    const int sh = q - k; // <= 66
    const U128 n = static_cast<U128>(m) * pow5[k];
    const U128 ip = n >> sh;
    if (ip < p16) {
      --e;
      continue;
    }
    if (ip >= p17) {
      ++e;
      continue;
    }
    d = static_cast<uint64_t>(ip);
    if (sh > 0) {
      const U128 rem = n - (ip << sh);
      const U128 half = static_cast<U128>(1) << (sh - 1);
      if (rem > half || (rem == half && (d & 1) != 0)) ++d;
    }
    if (d == p17) { // rounded up to the next power of ten
      d = p16;
      ++e;
    }
    return true;
  }
  return false;
}

// The n digits of v (v < 10^n) at out, two at a time.
void write_digits(char* out, uint32_t v, int n) {
  static constexpr char pairs[] = "00010203040506070809101112131415161718192021222324252627282930"
                                  "31323334353637383940414243444546474849505152535455565758596061"
                                  "62636465666768697071727374757677787980818283848586878889909192"
                                  "93949596979899";
  while (n >= 2) {
    n -= 2;
    std::memcpy(out + n, pairs + 2 * (v % 100), 2);
    v /= 100;
  }
  if (n == 1) out[0] = static_cast<char>('0' + v);
}

} // namespace

void append_json_double(std::string& out, double x) {
  if (!std::isfinite(x)) throw InternalError("Json::number_double: not a finite double");
  char buf[40];
  char* at = buf;
  uint64_t d = 0;
  int e = 0;
  if (digits17(std::fabs(x), d, e)) {
    // %.17g without an exponent (-4 <= e < 17): 16 - e decimals, trailing zeros and a bare
    // point dropped.
    char dig[17];
    write_digits(dig, static_cast<uint32_t>(d / 100000000), 9);
    write_digits(dig + 9, static_cast<uint32_t>(d % 100000000), 8);
    if (x < 0) *at++ = '-';
    int last = 16; // the last digit kept
    while (last > std::max(e, 0) && dig[last] == '0')
      --last;
    if (e >= 0) {
      std::memcpy(at, dig, static_cast<size_t>(e) + 1);
      at += e + 1;
      if (last > e) {
        *at++ = '.';
        std::memcpy(at, dig + e + 1, static_cast<size_t>(last - e));
        at += last - e;
      }
    } else {
      *at++ = '0';
      *at++ = '.';
      for (int i = 0; i < -e - 1; ++i)
        *at++ = '0';
      std::memcpy(at, dig, static_cast<size_t>(last) + 1);
      at += last + 1;
    }
  } else {
    const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 17);
    if (r.ec != std::errc()) throw InternalError("Json::number_double: not a finite double");
    at = r.ptr;
  }
  out.append(buf, static_cast<size_t>(at - buf)); // (pointer, length): not the iterator
                                                  // overload, which goes through replace()
}

Json Json::number_double(double x) {
  Json v;
  append_json_double(v.text_, x);
  v.type_ = Type::Number;
  return v;
}

Json Json::number(long n) {
  Json v;
  v.type_ = Type::Number;
  v.text_ = std::to_string(n);
  return v;
}

Json Json::string(std::string s) {
  Json v;
  v.type_ = Type::String;
  v.text_ = std::move(s);
  return v;
}

Json Json::array() {
  Json v;
  v.type_ = Type::Array;
  return v;
}

Json Json::object() {
  Json v;
  v.type_ = Type::Object;
  return v;
}

bool Json::as_bool() const {
  if (type_ != Type::Bool) misuse("as_bool", type_);
  return bool_;
}

const std::string& Json::text() const {
  if (type_ != Type::Number && type_ != Type::String) misuse("text", type_);
  return text_;
}

const std::vector<Json>& Json::items() const {
  if (type_ != Type::Array) misuse("items", type_);
  return items_;
}

const std::vector<Json::Member>& Json::members() const {
  if (type_ != Type::Object) misuse("members", type_);
  return members_;
}

std::vector<Json::Member> Json::take_members() {
  if (type_ != Type::Object) misuse("take_members", type_);
  return std::exchange(members_, {});
}

const Json* Json::find(const std::string& key) const {
  if (type_ != Type::Object) misuse("find", type_);
  for (const auto& m : members_)
    if (m.first == key) return &m.second;
  return nullptr;
}

std::size_t Json::size() const {
  if (type_ == Type::Array) return items_.size();
  if (type_ == Type::Object) return members_.size();
  misuse("size", type_);
}

void Json::push_back(Json v) {
  if (type_ != Type::Array) misuse("push_back", type_);
  items_.push_back(std::move(v));
}

void Json::reserve(std::size_t n) {
  if (type_ != Type::Array) misuse("reserve", type_);
  items_.reserve(n);
}

void Json::set(const std::string& key, Json v) {
  if (type_ != Type::Object) misuse("set", type_);
  for (auto& m : members_) {
    if (m.first == key) {
      m.second = std::move(v);
      return;
    }
  }
  members_.emplace_back(key, std::move(v));
}

const char* type_name(Json::Type t) {
  switch (t) {
  case Json::Type::Null:
    return "null";
  case Json::Type::Bool:
    return "a boolean";
  case Json::Type::Number:
    return "a number";
  case Json::Type::String:
    return "a string";
  case Json::Type::Array:
    return "an array";
  case Json::Type::Object:
    return "an object";
  }
  return "an unknown JSON type";
}

Json parse_json(const std::string& text, const std::string& source_name) {
  return detail::JsonParser(text, source_name).parse_document();
}

std::string dump(const Json& v, int indent) {
  std::string out;
  dump_value(out, v, indent, 0);
  return out;
}

std::string json_path_child(const std::string& parent, const std::string& key) {
  bool identifier = !key.empty() && !is_digit(key[0]);
  for (char c : key)
    if (!(is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'))
      identifier = false;
  if (identifier) return parent + "." + key;
  std::string out = parent + "[";
  append_json_string(out, key);
  return out + "]";
}

std::string json_path_index(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

} // namespace surfcert::core::io
