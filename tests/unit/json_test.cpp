// Unit tests of surfcert::core::io::Json: parsing (values, positions, every error class with
// its line and column), writing (compact and pretty), and the JSON path helpers.
#include "surfcert/core/error.hpp"
#include "surfcert/core/io/json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

using surfcert::core::InputError;
using surfcert::core::InternalError;
using surfcert::core::io::dump;
using surfcert::core::io::Json;
using surfcert::core::io::json_path_child;
using surfcert::core::io::json_path_index;
using surfcert::core::io::parse_json;

namespace {

Json parse(const std::string& s) {
  return parse_json(s, "doc.json");
}

// Parses `text`, which must fail at line:column with exactly these expected/found parts.
void expect_error(const std::string& text, int line, int column, const std::string& expected,
                  const std::string& found) {
  SCOPED_TRACE("input: " + text);
  try {
    parse(text);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().source, "doc.json");
    EXPECT_EQ(e.where().line, line);
    EXPECT_EQ(e.where().column, column);
    EXPECT_EQ(e.where().json_path, "");
    EXPECT_EQ(e.expected(), expected);
    EXPECT_EQ(e.found(), found);
  }
}

} // namespace

TEST(JsonParse, Scalars) {
  EXPECT_TRUE(parse("null").is_null());
  EXPECT_TRUE(parse("true").as_bool());
  EXPECT_FALSE(parse(" false ").as_bool());
  Json n = parse("-12.5e+3");
  ASSERT_TRUE(n.is_number());
  EXPECT_EQ(n.text(), "-12.5e+3");
  Json s = parse("\"abc\"");
  ASSERT_TRUE(s.is_string());
  EXPECT_EQ(s.text(), "abc");
}

TEST(JsonParse, NumbersKeepTheirExactText) {
  const std::string big = "123456789012345678901234567890123456789012345678901234567890";
  Json v = parse("[" + big + ", -0.1000, 1E+400, 0, -0, 0.1]");
  ASSERT_EQ(v.size(), 6u);
  EXPECT_EQ(v.items()[0].text(), big);
  EXPECT_EQ(v.items()[1].text(), "-0.1000");
  EXPECT_EQ(v.items()[2].text(), "1E+400");
  EXPECT_EQ(v.items()[3].text(), "0");
  EXPECT_EQ(v.items()[4].text(), "-0");
  EXPECT_EQ(v.items()[5].text(), "0.1");
  EXPECT_EQ(dump(v), "[" + big + ",-0.1000,1E+400,0,-0,0.1]");
}

TEST(JsonParse, ObjectsKeepOrderAndFindMembers) {
  Json o = parse(R"({"b": 1, "a": [true, null], "c": {"d": "e"}})");
  ASSERT_TRUE(o.is_object());
  ASSERT_EQ(o.size(), 3u);
  EXPECT_EQ(o.members()[0].first, "b");
  EXPECT_EQ(o.members()[1].first, "a");
  EXPECT_EQ(o.members()[2].first, "c");
  ASSERT_NE(o.find("a"), nullptr);
  EXPECT_EQ(o.find("a")->size(), 2u);
  EXPECT_TRUE(o.find("a")->items()[1].is_null());
  EXPECT_EQ(o.find("c")->find("d")->text(), "e");
  EXPECT_EQ(o.find("missing"), nullptr);
  EXPECT_EQ(o.find("c")->find("b"), nullptr); // no search in the parent
}

TEST(JsonParse, EscapesAndUnicode) {
  EXPECT_EQ(parse(R"("\"\\\/\b\f\n\r\t")").text(), "\"\\/\b\f\n\r\t");
  EXPECT_EQ(parse(R"("\u0041\u00e9\u20AC")").text(), "A\xC3\xA9\xE2\x82\xAC");
  // Surrogate pair -> one 4-byte UTF-8 sequence (U+1F600).
  EXPECT_EQ(parse(R"("\ud83d\ude00")").text(), "\xF0\x9F\x98\x80");
  EXPECT_EQ(parse(R"("\uD834\uDD1E")").text(), "\xF0\x9D\x84\x9E"); // U+1D11E
  // Raw UTF-8 passes through unchanged.
  EXPECT_EQ(parse("\"caf\xC3\xA9 \xF0\x9F\x98\x80\"").text(), "caf\xC3\xA9 \xF0\x9F\x98\x80");
  // \u0000 is a valid escape and yields a NUL byte.
  Json nul = parse(R"("a\u0000b")");
  EXPECT_EQ(nul.text(), std::string("a\0b", 3));
  EXPECT_EQ(dump(nul), R"("a\u0000b")");
}

TEST(JsonParse, PositionsOfValues) {
  const std::string text = "{\n  \"a\": [1,\n        \"x\"],\n\t\"\xC3\xA9\": true\n}";
  Json o = parse(text);
  EXPECT_EQ(o.line(), 1);
  EXPECT_EQ(o.column(), 1);
  const Json& a = *o.find("a");
  EXPECT_EQ(a.line(), 2);
  EXPECT_EQ(a.column(), 8);
  EXPECT_EQ(a.items()[0].line(), 2);
  EXPECT_EQ(a.items()[0].column(), 9);
  EXPECT_EQ(a.items()[1].line(), 3);
  EXPECT_EQ(a.items()[1].column(), 9);
  // Columns count code points: the key "é" is 3 columns wide although it is 4 bytes.
  const Json& t = *o.find("\xC3\xA9");
  EXPECT_EQ(t.line(), 4);
  EXPECT_EQ(t.column(), 7);
  EXPECT_EQ(Json::number(3).line(), 0); // built, not parsed
}

TEST(JsonParse, ByteOrderMarkIsSkipped) {
  Json v = parse("\xEF\xBB\xBF[1]");
  EXPECT_EQ(v.items()[0].text(), "1");
}

TEST(JsonParse, NestingDepthLimit) {
  std::string ok = std::string(256, '[') + std::string(256, ']');
  EXPECT_NO_THROW(parse(ok));
  std::string deep = std::string(257, '[') + std::string(257, ']');
  expect_error(deep, 1, 257, "nesting depth at most 256", "'['");
  std::string objects;
  for (int i = 0; i < 257; ++i)
    objects += "{\"a\":";
  expect_error(objects, 1, 1 + 256 * 5, "nesting depth at most 256", "'{'");
}

TEST(JsonErrors, StructuralErrors) {
  expect_error("", 1, 1, "a JSON value", "end of input");
  expect_error("   \n  ", 2, 3, "a JSON value", "end of input");
  expect_error("{\"a\":1,}", 1, 8, "a string key", "'}'");
  expect_error("[1,]", 1, 4, "a JSON value", "']'");
  expect_error("[1 2]", 1, 4, "',' or ']' after array element", "'2'");
  expect_error("[1", 1, 3, "',' or ']' after array element", "end of input");
  expect_error("{\"a\":1 \"b\":2}", 1, 8, "',' or '}' after object member", "'\"'");
  expect_error("{\"a\" 1}", 1, 6, "':' after object key", "'1'");
  expect_error("{1:2}", 1, 2, "a string key or '}'", "'1'");
  expect_error("{'a':1}", 1, 2, "a string key or '}'", "'''");
  expect_error("[,1]", 1, 2, "a JSON value or ']'", "','");
  expect_error("{\"a\":}", 1, 6, "a JSON value", "'}'");
  expect_error("{\"a\":1} x", 1, 9, "end of input after the JSON value", "'x'");
  expect_error("1 2", 1, 3, "end of input after the JSON value", "'2'");
  expect_error("// comment\n1", 1, 1, "a JSON value", "'/'");
  expect_error("[1] /* c */", 1, 5, "end of input after the JSON value", "'/'");
}

TEST(JsonErrors, ErrorOnLineThreeColumnFive) {
  expect_error("{\n  \"a\": 1,\n    x: 2\n}", 3, 5, "a string key", "'x'");
  expect_error("[\r\n1,\r\n\t\t2 3]", 3, 5, "',' or ']' after array element", "'3'");
}

TEST(JsonErrors, LiteralsAndNumbers) {
  expect_error("[NaN]", 1, 2, "a JSON value or ']'", "'NaN'");
  expect_error("Infinity", 1, 1, "a JSON value", "'Infinity'");
  expect_error("-Infinity", 1, 2, "a digit after '-'", "'I'");
  expect_error("True", 1, 1, "a JSON value", "'True'");
  expect_error("tru", 1, 1, "a JSON value", "'tru'");
  expect_error("nulls", 1, 1, "a JSON value", "'nulls'");
  expect_error("01", 1, 2, "a number without leading zeros", "'1'");
  expect_error("-", 1, 2, "a digit after '-'", "end of input");
  expect_error("1.", 1, 3, "a digit after the decimal point", "end of input");
  expect_error(".5", 1, 1, "a JSON value", "'.'");
  expect_error("+1", 1, 1, "a JSON value", "'+'");
  expect_error("1e", 1, 3, "a digit in the exponent", "end of input");
  expect_error("1e+x", 1, 4, "a digit in the exponent", "'x'");
  expect_error("0x10", 1, 2, "end of input after the JSON value", "'x'");
}

TEST(JsonErrors, Strings) {
  expect_error("\"abc", 1, 5, "a string character or closing '\"'", "end of input");
  expect_error("\"a\tb\"", 1, 3,
               "a string character or closing '\"' (control characters must be escaped)", "tab");
  expect_error("[\"a\nb\"]", 1, 4,
               "a string character or closing '\"' (control characters must be escaped)",
               "newline");
  expect_error("\"\x01\"", 1, 2,
               "a string character or closing '\"' (control characters must be escaped)",
               "control character U+0001");
  expect_error(R"("\x")", 1, 3,
               "an escape character ('\"', '\\', '/', 'b', 'f', 'n', 'r', 't' or 'u') after '\\'",
               "'x'");
  expect_error("\"\\", 1, 3, "an escape character after '\\'", "end of input");
  expect_error(R"("\u12G4")", 1, 6, "4 hex digits after '\\u'", "'G'");
  expect_error(R"("\u12")", 1, 6, "4 hex digits after '\\u'", "'\"'");
}

TEST(JsonErrors, Surrogates) {
  expect_error(R"("ab\udc00")", 1, 4, "a high surrogate (\\uD800-\\uDBFF) before a low surrogate",
               "'\\udc00'");
  expect_error(R"("\ud83d")", 1, 8,
               "a low surrogate escape (\\uDC00-\\uDFFF) after a high surrogate", "'\"'");
  expect_error(R"("\ud83dx")", 1, 8,
               "a low surrogate escape (\\uDC00-\\uDFFF) after a high surrogate", "'x'");
  expect_error(R"("\ud83d\u0041")", 1, 8,
               "a low surrogate escape (\\uDC00-\\uDFFF) after a high surrogate", "'\\u0041'");
}

TEST(JsonErrors, InvalidUtf8) {
  expect_error("\"\xFF\"", 1, 2, "valid UTF-8", "byte 0xFF (not UTF-8)");
  expect_error("\"\xC0\x80\"", 1, 2, "valid UTF-8", "byte 0xC0 (not UTF-8)");     // overlong
  expect_error("\"\xED\xA0\x80\"", 1, 2, "valid UTF-8", "byte 0xED (not UTF-8)"); // surrogate
  expect_error("\"\xC3\"", 1, 2, "valid UTF-8", "byte 0xC3 (not UTF-8)");         // truncated
  expect_error("\"\xC3\xA9\xC3\"", 1, 3, "valid UTF-8", "byte 0xC3 (not UTF-8)");
  // Outside strings a non-ASCII character is named as itself.
  expect_error("[\xC3\xA9]", 1, 2, "a JSON value or ']'", "'\xC3\xA9'");
}

TEST(JsonErrors, DuplicateKeys) {
  expect_error("{\"a\":1,\"a\":2}", 1, 8, "a key not already used in this object",
               "duplicate key \"a\"");
  expect_error("{\"x\":{},\n \"y\":[],\n \"x\":0}", 3, 2, "a key not already used in this object",
               "duplicate key \"x\"");
  // The same key in different objects is fine.
  EXPECT_NO_THROW(parse(R"({"a":{"a":1},"b":{"a":2}})"));
}

TEST(JsonDump, CompactRoundTripOfCanonicalText) {
  const char* canonical[] = {
      "null",
      "true",
      "[]",
      "{}",
      "\"\"",
      "[1,-2.50,3e10,-0.0E-7,123456789012345678901234567890]",
      R"({"b":1,"a":[true,false,null],"c":{"d":{},"e":[[]]}})",
      R"("q\"b\\s/n\nt\tc\u0001\u001fr\rb\bf\f")",
      "\"caf\xC3\xA9 \xF0\x9F\x98\x80\"",
      R"({"surfaces":[{"equation":"x^2 + y^2 = 1","radii":["1/3",0.1]}]})",
  };
  for (const char* s : canonical)
    EXPECT_EQ(dump(parse(s)), s);
}

TEST(JsonDump, EscapesWhenWriting) {
  EXPECT_EQ(dump(Json::string("a\"b\\c\n\x01\x7F")), "\"a\\\"b\\\\c\\n\\u0001\x7F\"");
  // Non-ASCII UTF-8 is kept; bytes that are not UTF-8 become U+FFFD so the output stays JSON.
  EXPECT_EQ(dump(Json::string("\xC3\xA9")), "\"\xC3\xA9\"");
  EXPECT_EQ(dump(Json::string("a\xFF"
                              "b")),
            "\"a\\ufffdb\"");
  // Escaped surrogate pairs come back as raw UTF-8.
  EXPECT_EQ(dump(parse(R"(["\ud83d\ude00"])")), "[\"\xF0\x9F\x98\x80\"]");
}

TEST(JsonDump, Pretty) {
  Json o = parse(R"({"a":1,"b":[true,{"c":null}],"d":{},"e":[]})");
  EXPECT_EQ(dump(o, 2), "{\n"
                        "  \"a\": 1,\n"
                        "  \"b\": [\n"
                        "    true,\n"
                        "    {\n"
                        "      \"c\": null\n"
                        "    }\n"
                        "  ],\n"
                        "  \"d\": {},\n"
                        "  \"e\": []\n"
                        "}");
  EXPECT_EQ(dump(parse("[1,2]"), 0), "[\n1,\n2\n]");
  EXPECT_EQ(dump(parse(dump(o, 4))), dump(o)); // pretty output parses back to the same value
}

TEST(JsonBuild, ConstructorsAndMutators) {
  Json o = Json::object();
  o.set("name", Json::string("sphere"));
  o.set("count", Json::number(-42));
  o.set("exact", Json::number_text("0.1000000000000000000001"));
  Json list = Json::array();
  list.push_back(Json::boolean(true));
  list.push_back(Json::null());
  o.set("list", std::move(list));
  EXPECT_EQ(dump(o), R"({"name":"sphere","count":-42,"exact":0.1000000000000000000001,)"
                     R"("list":[true,null]})");
  o.set("count", Json::number(7)); // replaces in place
  EXPECT_EQ(o.size(), 4u);
  EXPECT_EQ(o.members()[1].first, "count");
  EXPECT_EQ(o.find("count")->text(), "7");
  EXPECT_EQ(Json::number(-9223372036854775807L - 1).text(), "-9223372036854775808");
  EXPECT_EQ(Json::null().type(), Json::Type::Null);
  EXPECT_EQ(surfcert::core::io::type_name(Json::Type::Array), std::string("an array"));
}

TEST(JsonBuild, MisuseIsAnInternalError) {
  EXPECT_THROW(Json::number_text("01"), InternalError);
  EXPECT_THROW(Json::number_text(""), InternalError);
  EXPECT_THROW(Json::number_text("1."), InternalError);
  EXPECT_THROW(Json::number_text("NaN"), InternalError);
  EXPECT_NO_THROW(Json::number_text("-0.5e-7"));
  EXPECT_THROW(Json::string("x").as_bool(), InternalError);
  EXPECT_THROW(Json::boolean(true).text(), InternalError);
  EXPECT_THROW(Json::array().members(), InternalError);
  EXPECT_THROW(Json::object().items(), InternalError);
  EXPECT_THROW(Json::array().find("a"), InternalError);
  EXPECT_THROW(Json::number(1).size(), InternalError);
  Json a = Json::array();
  EXPECT_THROW(a.set("k", Json()), InternalError);
  Json o = Json::object();
  EXPECT_THROW(o.push_back(Json()), InternalError);
}

TEST(JsonPath, ChildAndIndex) {
  EXPECT_EQ(json_path_child("$", "surfaces"), "$.surfaces");
  EXPECT_EQ(json_path_index(json_path_child("$", "surfaces"), 1), "$.surfaces[1]");
  EXPECT_EQ(json_path_child("$.a", "_x1"), "$.a._x1");
  EXPECT_EQ(json_path_child("$", "a b"), "$[\"a b\"]");
  EXPECT_EQ(json_path_child("$", "1x"), "$[\"1x\"]");
  EXPECT_EQ(json_path_child("$", ""), "$[\"\"]");
  EXPECT_EQ(json_path_child("$", "a\"b"), "$[\"a\\\"b\"]");
  EXPECT_EQ(json_path_child("$", "a.b"), "$[\"a.b\"]");
  EXPECT_EQ(json_path_index("$", 0), "$[0]");
}

// number_double writes exactly the characters of printf("%.17g") (the reports' format), at
// every magnitude, and refuses non-finite values.
TEST(Json, NumberDoubleIsPrintfs17g) {
  for (double x : {0.0, -0.0, 1.0, -1.5, 0.1, 1.0 / 3.0, 1e-5, 1e-4, 123456789012345678.0, 1e16,
                   1e17, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, -3.25e-200}) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    EXPECT_EQ(Json::number_double(x).text(), std::string(buf)) << buf;
    EXPECT_TRUE(Json::number_double(x).is_number());
  }
  EXPECT_THROW(Json::number_double(HUGE_VAL), InternalError);
  EXPECT_THROW(Json::number_double(NAN), InternalError);
}

// append_json_double's exact integer route (1e-4 <= |x| < 2^53) and its fallback against
// glibc's printf: random bit patterns, random magnitudes 1e-20 .. 1e17 and their neighbours,
// powers of ten and their neighbours (where the decimal exponent estimate is off by one and
// rounding carries into a new digit), decimal ties (odd / 2^j: exact binary values whose
// 18th significant digit is a final 5, rounded half to even), integers up to 10^17.
TEST(Json, AppendDoubleIsPrintfs17gOnRandomAndTieValues) {
  std::mt19937_64 rng(20261125);
  long checked = 0, ties = 0;
  auto check = [&](double x) {
    if (!std::isfinite(x)) return;
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    std::string text = "<";
    surfcert::core::io::append_json_double(text, x);
    ASSERT_EQ(text, "<" + std::string(buf)) << buf;
    ++checked;
  };
  std::uniform_real_distribution<double> mag(-20, 17);
  for (int i = 0; i < 60000; ++i) {
    const uint64_t bits = rng();
    double x = 0;
    std::memcpy(&x, &bits, sizeof x);
    check(x);
    const double y = std::pow(10.0, mag(rng)) * ((rng() & 1) ? 1 : -1);
    check(y);
    check(std::nextafter(y, 0.0));
    const int p = static_cast<int>(rng() % 22) - 5;
    check(std::pow(10.0, p));
    check(std::nextafter(std::pow(10.0, p), HUGE_VAL));
    check(std::nextafter(std::pow(10.0, p), 0.0));
    check(static_cast<double>(rng() % 100000000000000000ULL));
    // odd / 2^j with j + (digits of odd) > 17: the 18th digit is often the final 5 of a tie.
    const uint64_t odd = ((rng() & ((1ULL << 53) - 1)) >> (rng() % 50)) | 1;
    const double t = std::ldexp(static_cast<double>(odd), -static_cast<int>(1 + rng() % 60));
    check(t);
  }
  // Ties by construction: 131073 / 2^18 = 0.500003814697265625 (18 digits, a final 5) rounds
  // to even ...62, 131075 / 2^18 = 0.500011444091796875 to ...88 (odd 7 rounded up).
  for (long n = 131073; n < 131073 + 2000; n += 2) {
    check(static_cast<double>(n) / 262144);
    ++ties;
  }
  EXPECT_EQ(Json::number_double(131073.0 / 262144).text(), "0.50000381469726562");
  EXPECT_EQ(Json::number_double(131075.0 / 262144).text(), "0.50001144409179688");
  for (double x : {1e-4, 9.9999999999999991e-05, 0x1p53, 0x1p53 - 1, 0x1p52, 1e16 - 2, 0.5, -2.5})
    check(x);
  EXPECT_GT(checked, 400000);
  EXPECT_EQ(ties, 1000);
  std::string text;
  EXPECT_THROW(surfcert::core::io::append_json_double(text, -HUGE_VAL), InternalError);
}

TEST(Json, ReserveKeepsTheArrayAndRefusesOtherTypes) {
  Json a = Json::array();
  a.reserve(3);
  EXPECT_EQ(a.size(), 0u);
  a.push_back(Json::number(1));
  EXPECT_EQ(dump(a), "[1]");
  Json o = Json::object();
  EXPECT_THROW(o.reserve(2), InternalError);
}
