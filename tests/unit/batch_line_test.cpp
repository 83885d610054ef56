// The batch's fast line route (app/batch_line.hpp) against the document route
// (process_batch_line): byte for byte the same answer line apart from "time_ms", on
// - every pencil of data/fixtures as 4x4 matrices and as equations, every mode and detail;
// - random double shapes (every shape type, quaternions, radius / radii) and numpy-style
//   double matrices (not exactly symmetric: the readings), classify / intersect / distance;
// - edge cases of the reading: number literals (integers past 15 digits, overflow, underflow,
//   subnormals, -0), ids of every kind, escapes, control characters, duplicate keys, unknown
//   fields, trailing content, whitespace, wrong types, budgets, digits, tolerances;
// - random byte mutations of valid lines (most become input errors: same message, line,
//   column and JSON path).
#include "support/fixtures.hpp"

#include "surfcert/app/batch_line.hpp"
#include "surfcert/app/scene.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <regex>
#include <string>
#include <vector>

using namespace surfcert;
using certify::Detail;
using certify::Mode;
using core::io::Json;

namespace {

std::string untimed(const std::string& s) {
  static const std::regex time_field(R"(,"time_ms":[0-9.]+)");
  return std::regex_replace(s, time_field, "");
}

unsigned seed() {
  const char* s = std::getenv("SURFCERT_TEST_SEED");
  return s ? static_cast<unsigned>(std::strtoul(s, nullptr, 10)) : 20261124u;
}

// Both routes on one line; the fast one must equal the document one.
void expect_same(const std::string& line, Mode mode = Mode::Filtered,
                 Detail default_detail = Detail::Full, double budget_ms = 0) {
  bool fallback = false;
  const Json doc = app::process_batch_line(line, 3, mode, &fallback, budget_ms, default_detail);
  const app::BatchLineAnswer fast =
      app::answer_batch_line(line, 3, mode, budget_ms, default_detail);
  const std::string want = untimed(core::io::dump(doc));
  EXPECT_EQ(untimed(fast.text), want) << line;
  EXPECT_EQ(fast.status, doc.find("status") ? doc.find("status")->text() : "") << line;
  EXPECT_EQ(fast.fallback, fallback) << line;
  EXPECT_NE(fast.text.find("\"time_ms\":"), std::string::npos) << line;
}

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

template <size_t N> std::string vec(const std::array<double, N>& v) {
  std::string s = "[";
  for (size_t i = 0; i < N; ++i)
    s += (i ? "," : "") + num(v[i]);
  return s + "]";
}

std::string matrix_text(const Json& m) {
  return core::io::dump(m);
}

struct Rng {
  std::mt19937_64 g{seed()};
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(g); }
  size_t below(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(g); }
  std::array<double, 4> quaternion() {
    std::normal_distribution<double> n(0, 1);
    std::array<double, 4> q{n(g), n(g), n(g), n(g)};
    const double r = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& x : q)
      x /= r;
    return q;
  }
};

const char* kShapeTypes[] = {"sphere",
                             "ellipsoid",
                             "cylinder",
                             "cone",
                             "elliptic_paraboloid",
                             "hyperbolic_paraboloid",
                             "hyperboloid_one_sheet",
                             "hyperboloid_two_sheets"};

std::string random_shape(Rng& r, const char* type) {
  const std::string t = type;
  std::string s = R"({"type":")" + t + "\"";
  const std::array<double, 3> c{r.uniform(-0.5, 0.5), r.uniform(-0.5, 0.5), r.uniform(-0.5, 0.5)};
  if (r.below(4) != 0) s += ",\"center\":" + vec(c);
  if (t == "sphere" || (t == "cylinder" && r.below(2) == 0)) {
    s += ",\"radius\":" + num(r.uniform(0.1, 1));
  } else {
    const bool two = t == "cylinder" || t == "elliptic_paraboloid" || t == "hyperbolic_paraboloid";
    s += ",\"radii\":[" + num(r.uniform(0.1, 1)) + "," + num(r.uniform(0.1, 1));
    s += two ? "]" : "," + num(r.uniform(0.1, 1)) + "]";
  }
  if (r.below(3) != 0) s += R"(,"rotation":{"quaternion":)" + vec(r.quaternion()) + "}";
  return s + "}";
}

// The matrix a numpy user writes for an ellipsoid (R D R^T, b = -A c, ...): not exactly
// symmetric in general.
std::string numpy_matrix(Rng& r) {
  const auto q = r.quaternion();
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  double d[3], A[3][3], c[3], b[3];
  for (double& v : d)
    v = 1 / std::pow(r.uniform(0.1, 1), 2);
  for (double& v : c)
    v = r.uniform(-0.5, 0.5);
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      A[i][j] = R[i][0] * d[0] * R[j][0] + R[i][1] * d[1] * R[j][1] + R[i][2] * d[2] * R[j][2];
  double k = -1;
  for (size_t i = 0; i < 3; ++i) {
    b[i] = -(A[i][0] * c[0] + A[i][1] * c[1] + A[i][2] * c[2]);
    k -= c[i] * b[i];
  }
  std::string s = R"({"matrix":[)";
  for (size_t i = 0; i < 4; ++i) {
    s += i ? ",[" : "[";
    for (size_t j = 0; j < 4; ++j)
      s += (j ? "," : "") + num(i < 3 && j < 3 ? A[i][j] : i < 3 ? b[i] : j < 3 ? b[j] : k);
    s += "]";
  }
  return s + "]}";
}

} // namespace

TEST(BatchLine, FixturePencilsEveryModeAndDetail) {
  for (const char* file :
       {"fixtures/canonical_examples.json", "fixtures/ellipsoid_fixtures.json"}) {
    const Json doc = fixtures::load_json(file);
    for (const auto& [name, c] : doc.members()) {
      const Json* A = c.find("A") ? c.find("A") : c.find("E1");
      const Json* B = c.find("B") ? c.find("B") : c.find("E2");
      ASSERT_TRUE(A && B) << name;
      const std::string ma = R"({"matrix":)" + matrix_text(*A) + "}";
      const std::string mb = R"({"matrix":)" + matrix_text(*B) + "}";
      const std::string ea =
          "\"" + core::QuadricMatrix(fixtures::mat4_from_json(*A)).to_poly().to_string() + " = 0\"";
      const std::string eb =
          "{\"equation\":\"" +
          core::QuadricMatrix(fixtures::mat4_from_json(*B)).to_poly().to_string() + " = 0\"}";
      for (const auto& [a, b] : {std::pair{ma, mb}, std::pair{ea, eb}})
        for (const char* detail :
             {"", R"(,"detail":"topology")", R"(,"detail":"certificate")", R"(,"detail":"full")"})
          for (Mode m : {Mode::Exact, Mode::Filtered, Mode::Float}) {
            const std::string line = "{\"id\":\"" + name + "\",\"op\":\"classify\",\"a\":" + a +
                                     ",\"b\":" + b + detail + "}";
            expect_same(line, m);
          }
    }
  }
}

TEST(BatchLine, RandomDoubleShapesAndMatrices) {
  Rng r;
  for (int i = 0; i < 120; ++i) {
    const std::string a = i % 3 == 2 ? numpy_matrix(r) : random_shape(r, kShapeTypes[r.below(8)]);
    const std::string b = i % 3 == 1 ? numpy_matrix(r) : random_shape(r, kShapeTypes[r.below(8)]);
    const Mode m = i % 5 == 0 ? Mode::Exact : i % 5 == 1 ? Mode::Float : Mode::Filtered;
    const std::string id = std::to_string(i);
    expect_same(R"({"id":)" + id + R"(,"op":"classify","a":)" + a + R"(,"b":)" + b +
                    R"(,"detail":"topology"})",
                m);
    if (i % 4 == 0)
      expect_same(R"({"b":)" + b + R"(,"a":)" + a + R"(,"op":"classify","id":")" + id + "\"}", m,
                  Detail::Topology);
    if (i % 10 == 0)
      expect_same(R"({"id":)" + id + R"(,"op":"classify","a":)" + a + R"(,"b":)" + b +
                      R"(,"detail":"certificate"})",
                  m);
    if (i % 20 == 0)
      expect_same(R"({"id":)" + id + R"(,"op":"intersect","a":)" + a + R"(,"b":)" + b +
                      R"(,"detail":"topology","tolerance":0.01})",
                  m);
    if (i % 12 == 0) {
      const std::string e1 = random_shape(r, "ellipsoid"), e2 = random_shape(r, "sphere");
      expect_same(R"({"id":)" + id + R"(,"op":"distance","a":)" + e1 +
                      R"(,"b":{"type":"sphere","center":[3,0.5,0],"radius":0.5},"digits":12,)"
                      R"("detail":"value"})",
                  m);
      expect_same(R"({"id":)" + id + R"(,"op":"distance","a":)" + e2 + R"(,"b":)" + e1 +
                      R"(,"solid":true})",
                  m);
    }
  }
}

TEST(BatchLine, EdgeCasesOfTheReading) {
  const std::string s = R"({"type":"sphere","center":[0,0,0],"radius":1})";
  const std::string e = R"({"type":"ellipsoid","center":[0.25,0,0],"radii":[1,0.5,0.75]})";
  auto line = [&](const std::string& a, const std::string& extra = "") {
    return R"({"id":1,"op":"classify","a":)" + a + R"(,"b":)" + e + extra + "}";
  };
  const std::vector<std::string> numbers = {
      "1", "1.0", "-0", "-0.0", "0.5e1", "5E-1", "1e+0", "123456789012345", "1234567890123456",
      "-123456789012345", "-1234567890123456", "1e400", "-1e400", "1e-400", "4.9e-324",
      "2.2250738585072014e-308", "2.2250738585072011e-308", "0e5", "0.0000", "01", "1.", ".5", "+1",
      "1e", "-", "0x10", "\"1/3\"", "\"0.1\"", "true", "null", "[1]", "NaN", "Infinity", "1.5 ",
      " 2",
      // The plain-decimal road of the fast reader (at
      // most 19 digits, a fraction, no exponent) and its
      // edges: hard roundings (halfway cases tie to even),
      // 19 / 20 digits, signs, zeros, grammar.
      "0.1", "-0.1", "0.30000000000000004", "0.18250386420143827", "-0.015403155214902597",
      "0.0010655574791916811", "9007199254740993.0", "9007199254740995.0", "4503599627370496.5",
      "-4503599627370497.5", "123456789012345678.5", "9876543210.987654321",
      "9876543210.9876543210", "0.000000000000000001", "0.0000000000000000001",
      "1.00000000000000011102230246251565404", "-0.000", "00.5", "-01.5", "-.5", "1.5.5", "0.5e",
      "0.5e-1", "2.5E+2", "9007199254740993", "1e23", "5e-324", "1.5e-3"};
  for (const auto& n : numbers) {
    expect_same(line(R"({"type":"sphere","center":[0,0,0],"radius":)" + n + "}"));
    expect_same(line(R"({"type":"sphere","center":[)" + n + ",0,0],\"radius\":1}"));
    expect_same(line(R"({"type":"ellipsoid","radii":[1,1,1],"rotation":{"quaternion":[)" + n +
                     ",0,0,1]}}"));
    expect_same(line(R"({"matrix":[[)" + n + R"(,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]]})"));
    expect_same(R"({"id":)" + n + R"(,"op":"classify","a":)" + s + R"(,"b":)" + e + "}");
    expect_same(line(s, R"(,"budget_ms":)" + n));
    expect_same(R"({"id":1,"op":"distance","a":)" + s +
                R"(,"b":{"type":"sphere","center":[3,0,0],"radius":1},"digits":)" + n + "}");
    expect_same(R"({"id":1,"op":"intersect","a":)" + s + R"(,"b":)" + e + R"(,"tolerance":)" + n +
                "}");
  }
  const std::vector<std::string> lines = {
      line(s),
      line(s) + " ",
      " \t" + line(s) + "\r",
      "\xEF\xBB\xBF" + line(s),
      line(s) + "x",
      line(s) + "{}",
      line(s) + ",",
      line(s, R"(,"id":2)"),
      line(s, R"(,"a":"x^2+y^2=1")"),
      line(s, R"(,"mode":"exact")"),
      line(s, R"(,"mode":"float","detail":"topology")"),
      line(s, R"(,"mode":"fast")"),
      line(s, R"(,"mode":1)"),
      line(s, R"(,"detail":"value")"),
      line(s, R"(,"detail":"topology","budget_ms":0)"),
      line(s, R"(,"detail":"topology","budget_ms":0.000001)"),
      line(s, R"(,"detail":"topology","digits":"x","tolerance":-1,"solid":3)"),
      line(s, R"(,"frobnicate":1)"),
      line(s, R"(,"claims":[])"),
      line(R"("x^2+y^2+z^2=1")"),
      line(R"("x^2+y^2+z^2=1\u0020")"),
      line("\"x^2+y^2+z^2=1\t\""),
      line(R"("x^2+y^2+z^2=\\1")"),
      line(R"("x^3+y^2+z^2=1")"),
      line(R"("x^2+y^2+z^2=")"),
      line(R"({"equation":"x^2+y^2+z^2=1"})"),
      line(R"({"equation":"x^2+y^2+z^2=1","type":"sphere"})"),
      line(R"({"equation":1})"),
      line(R"({"type":"sphere","radius":1,"radius":2})"),
      line(R"({"type":"sphere","radii":[1,1,1]})"),
      line(R"({"type":"cylinder","radius":1,"radii":[1,2]})"),
      line(R"({"type":"cylinder","radii":[1,2,3]})"),
      line(R"({"type":"cylinder","radii":[1,2]})"),
      line(R"({"type":"cylinder","radius":0.5})"),
      line(R"({"type":"ellipsoid","radii":[1,2]})"),
      line(R"({"type":"ellipsoid","radii":[1,2,0]})"),
      line(R"({"type":"ellipsoid","radii":[1,2,-1]})"),
      line(R"({"type":"ellipsoid","radius":1})"),
      line(R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})"),
      line(R"({"type":"ellipsoid","radii":[1,2,3],"rotation":{"quaternion":[0,0,0,0]}})"),
      line(R"({"type":"ellipsoid","radii":[1,2,3],"rotation":{"quaternion":[1,0,0]}})"),
      line(R"({"type":"ellipsoid","radii":[1,2,3],"rotation":{"quaternion":[1,0,0,0],"x":1}})"),
      line(
          R"({"type":"ellipsoid","radii":[1,2,3],"rotation":{"matrix":[[0,1,0],[1,0,0],[0,0,1]]}})"),
      line(
          R"({"type":"ellipsoid","radii":[1,2,3],"rotation":{"matrix":[[0.5,1,0],[1,0,0],[0,0,1]]}})"),
      line(R"({"type":"ellipsoid","radii":[1,2,3],"rotation":{}})"),
      line(R"({"type":"ellipsoid","radii":[1,2,3],"center":[1,2]})"),
      line(R"({"type":"Ellipsoid","radii":[1,2,3]})"),
      line(R"({"type":"ellipsoid","radii":[1,2,3],"extra":null})"),
      line(R"({"matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]],"type":"sphere"})"),
      line(R"({"matrix":[[0,1,0,0],[-1,0,0,0],[0,0,0,0],[0,0,0,0]]})"),
      line(R"({"matrix":[[0,0,0,0],[0,0,0,0],[0,0,0,0],[0,0,0,0]]})"),
      line(R"({"matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0]]})"),
      line(R"({"matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1,0]]})"),
      line(R"({"matrix":[[1,2,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]]})"),
      line(R"({"matrix":[["1/2",0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]]})"),
      line(R"({"matrix":[[1e-300,0,0,0],[0,1e300,0,0],[0,0,1,0],[0,0,0,-1]]})"),
      R"({"id":"a\"b","op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      R"({"id":"\u00e9","op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      R"({"id":"é ü 🙂","op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      "{\"id\":\"a\tb\",\"op\":\"classify\",\"a\":" + s + R"(,"b":)" + e + "}",
      "{\"id\":\"\xff\",\"op\":\"classify\",\"a\":" + s + R"(,"b":)" + e + "}",
      R"({"id":[1,2],"op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      R"({"id":{"k":1},"op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      R"({"id":true,"op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      R"({"id":null,"op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      R"({"op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      R"({"\u0069d":7,"op":"classify","a":)" + s + R"(,"b":)" + e + "}",
      R"({"id":1,"op":"classify","a":)" + s + "}",
      R"({"id":1,"op":"classify","b":)" + s + "}",
      R"({"id":1,"a":)" + s + R"(,"b":)" + e + "}",
      R"({"id":1,"op":"verify","a":)" + s + R"(,"b":)" + e + R"(,"claims":[]})",
      R"({"id":1,"op":"frobnicate","a":)" + s + R"(,"b":)" + e + "}",
      R"({"id":1,"op":"distance","a":)" + s +
          R"(,"b":{"type":"torus","center":[5,0,0],"axis":[0,0,1],"major_radius":2,"minor_radius":1}})",
      R"({"id":1,"op":"classify","a":)" + s +
          R"(,"b":{"type":"torus","center":[5,0,0],"axis":[0,0,1],"major_radius":2,"minor_radius":1}})",
      "[1,2]",
      "\"classify\"",
      "",
      "   ",
      "{",
      "{}",
      "null",
  };
  for (const auto& l : lines)
    for (Mode m : {Mode::Filtered, Mode::Exact})
      expect_same(l, m, Detail::Topology);
  for (const auto& l : lines)
    expect_same(l, Mode::Float, Detail::Full, 1e6);
}

// A double matrix is a lazy quadric (core/quadric.hpp: its symmetric part, enclosed in
// intervals, rationals formed on demand) on the fast route and exact rationals on the document
// route: the same answers and readings where the asymmetry is not exact in double (1 against
// 1e-30, or a difference past the double range: the rational route of the reading), where the
// symmetric part overflows the doubles
// (the filter cannot decide: exact fallback), where it is zero (an input error), at tiny and
// huge magnitudes, with -0 against 0, and in every mode and detail.
TEST(BatchLine, DoubleMatricesAgreeWithTheExactReading) {
  const std::string e = R"({"type":"ellipsoid","center":[0.25,0,0],"radii":[1,0.5,0.75]})";
  auto mat = [](const char* rows) { return std::string(R"({"matrix":)") + rows + "}"; };
  const std::vector<std::string> matrices = {
      mat("[[1,1e-30,0,0],[1,1,0,0],[0,0,1,0],[0,0,0,-1]]"),
      mat("[[1,0.5,0,0],[0.50000000000000011,1,0,0],[0,0,1,0],[0,0,0,-0.25]]"),
      mat("[[1,1e-17,0,0],[-3e-300,1,0,0],[0,0,1,0.1],[0,0,0.10000000000000001,-0.25]]"),
      mat("[[1e308,1.5e308,0,0],[1.7e308,1e308,0,0],[0,0,1,0],[0,0,0,-1]]"),
      // m_01 - m_10 overflows the doubles (the reading's rational route): 3.2e+308.
      mat("[[1,1.5e308,0,0],[-1.7e308,1,0,0],[0,0,1,0],[0,0,0,-1]]"),
      mat("[[1e-300,0,0,0],[0,1e-300,0,0],[0,0,1e-300,0],[0,0,0,-1e-300]]"),
      mat("[[1e300,0,0,0],[0,2e300,0,0],[0,0,1e300,0],[0,0,0,-1e300]]"),
      mat("[[1,-0.0,0,0],[0,1,0,0],[0,0,1,-0.0],[0,0,0,-1]]"),
      mat("[[0,1,0,0],[-1,0,0,0],[0,0,0,0],[0,0,0,0]]"),
      mat("[[0,0,0,0],[0,0,0,0],[0,0,0,0.5],[0,0,-0.5,0]]"),
      mat("[[2.5,1,0,0],[1,1,0,0],[0,0,1,0],[0,0,0,-1]]"),
      mat("[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1.0000000000000002]]"),
  };
  for (const auto& a : matrices)
    for (Mode m : {Mode::Filtered, Mode::Exact, Mode::Float})
      for (const char* d : {"topology", "certificate", "full"}) {
        expect_same(R"({"id":1,"op":"classify","a":)" + a + R"(,"b":)" + e + R"(,"detail":")" + d +
                        "\"}",
                    m);
        expect_same(R"({"id":2,"op":"classify","a":)" + e + R"(,"b":)" + a + R"(,"detail":")" + d +
                        "\"}",
                    m);
      }
  // The same sphere as a matrix and as a shape: the same answer, certified.
  const std::string sphere = mat("[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]]");
  const auto fast = app::answer_batch_line(R"({"id":1,"op":"classify","a":)" + sphere + R"(,"b":)" +
                                               e + R"(,"detail":"topology"})",
                                           1, Mode::Filtered);
  const auto shape =
      app::answer_batch_line(R"({"id":1,"op":"classify","a":{"type":"sphere","radius":1},"b":)" +
                                 e + R"(,"detail":"topology"})",
                             1, Mode::Filtered);
  EXPECT_EQ(fast.status, "certified");
  EXPECT_EQ(untimed(fast.text), untimed(shape.text));
}

TEST(BatchLine, MutatedLines) {
  Rng r;
  const std::vector<std::string> seeds = {
      R"({"id":1,"op":"classify","a":{"type":"ellipsoid","center":[0.1,0.2,-0.3],"radii":[1,0.5,0.75],"rotation":{"quaternion":[0.5,0.5,0.5,0.5]}},"b":{"type":"sphere","center":[0,0,0.5],"radius":0.8},"detail":"topology"})",
      R"({"id":"m","op":"classify","a":{"matrix":[[2,0.5,0,0],[0.5,1,0,0],[0,0,1,0.25],[0,0,0.25,-1]]},"b":"x^2+y^2+z^2=2","mode":"exact"})",
      R"({"id":2,"op":"distance","a":{"type":"sphere","center":[0,0,0],"radius":1},"b":{"type":"ellipsoid","center":[4,0,0],"radii":[1,2,1]},"digits":10,"detail":"value"})",
  };
  const std::string alphabet = "{}[],:\"\\0123456789.eE-+ \t\x01xyz/";
  for (int i = 0; i < 600; ++i) {
    std::string l = seeds[static_cast<size_t>(i) % seeds.size()];
    const int edits = 1 + static_cast<int>(r.below(3));
    for (int k = 0; k < edits && !l.empty(); ++k) {
      const size_t at = r.below(l.size());
      switch (r.below(3)) {
      case 0:
        l.erase(at, 1);
        break;
      case 1:
        l.insert(at, 1, alphabet[r.below(alphabet.size())]);
        break;
      default:
        l[at] = alphabet[r.below(alphabet.size())];
      }
    }
    expect_same(l, Mode::Filtered, Detail::Full, 2000);
  }
}
