// verify (app/verify.hpp): claims made true and false by construction from closed forms get
// the expected verdicts; every refutation's counterexample is re-checked here from its own
// printed numbers (exact rationals); verdicts do not change when a and b are swapped (with
// "inside" swapped); bad claims are input errors with their JSON path; `surfcert verify` runs.
#include "support/fixtures.hpp"
#include "surfcert/app/scene.hpp"
#include "surfcert/certify/morphology.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/rational.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace surfcert;
using core::Rational;
using core::io::Json;

namespace {

const std::string kUnit = "\"x^2+y^2+z^2=1\"";

Json answer(const std::string& a, const std::string& b, const std::string& claims,
            const std::string& extra = "") {
  std::string line = "{\"id\":1,\"op\":\"verify\",\"a\":" + a + ",\"b\":" + b +
                     ",\"claims\":" + claims + extra + "}";
  return app::process_batch_line(line, 1, certify::Mode::Filtered);
}

const Json& verdict(const Json& r, size_t i) {
  return r.find("result")->find("verdicts")->items().at(i);
}

std::vector<std::string> verdicts(const Json& r) {
  std::vector<std::string> out;
  if (const Json* res = r.find("result"))
    for (const auto& v : res->find("verdicts")->items())
      out.push_back(v.find("verdict")->text());
  return out;
}

std::string status(const Json& r) {
  return r.find("status")->text();
}

Rational exact(const std::string& s) {
  auto r = Rational::from_string(s);
  EXPECT_TRUE(r) << s;
  return r ? *r : Rational(0);
}

// A refuted distance claim's counterexample, checked from its printed numbers alone: the
// certified enclosure [lower, upper] and the claimed interval are disjoint.
void expect_excludes(const Json& v) {
  ASSERT_EQ(v.find("verdict")->text(), "refuted") << core::io::dump(v);
  const Json& ce = *v.find("counterexample");
  Rational lo = exact(ce.find("distance")->find("lower")->text());
  Rational hi = exact(ce.find("distance")->find("upper")->text());
  Rational clo = exact(ce.find("claimed_interval")->find("lower")->text());
  Rational chi = exact(ce.find("claimed_interval")->find("upper")->text());
  EXPECT_TRUE(lo <= hi);
  EXPECT_TRUE(hi < clo || lo > chi) << core::io::dump(ce);
}

std::string pow2_text(long e) {
  return core::pow2(e).to_string();
}

// Swaps "a" and "b" of a relation claim's "inside" (textually: the claims here are simple).
std::string swap_inside(std::string s) {
  for (auto [from, to] : {std::pair<std::string, std::string>{"\"inside\":\"a\"", "#A"},
                          {"\"inside\":\"b\"", "\"inside\":\"a\""},
                          {"#A", "\"inside\":\"b\""}})
    for (size_t p; (p = s.find(from)) != std::string::npos;)
      s.replace(p, from.size(), to);
  return s;
}

// The answer and the answer with a and b swapped have the same verdicts.
Json answer_both_ways(const std::string& a, const std::string& b, const std::string& claims) {
  Json r = answer(a, b, claims);
  EXPECT_EQ(verdicts(r), verdicts(answer(b, a, swap_inside(claims)))) << claims;
  return r;
}

} // namespace

TEST(Verify, DistanceOfTwoUnitSpheresAtCentreDistance3) {
  const std::string b = "\"(x-3)^2+y^2+z^2=1\"";
  // The distance is exactly 1: an exact claim of 1 is confirmed.
  Json r = answer_both_ways(kUnit, b, R"([{"kind":"distance","value":1}])");
  EXPECT_EQ(status(r), "certified");
  EXPECT_EQ(verdicts(r), std::vector<std::string>{"confirmed"});
  // 1 + 2^-60 within 2^-70: refuted, with an enclosure that excludes the claimed interval.
  const std::string near = "[{\"kind\":\"distance\",\"value\":\"" +
                           (Rational(1) + core::pow2(-60)).to_string() + "\",\"abs_tol\":\"" +
                           pow2_text(-70) + "\"}]";
  r = answer_both_ways(kUnit, b, near);
  EXPECT_EQ(status(r), "certified");
  expect_excludes(verdict(r, 0));
  // 1 +- 1e-12 within 1e-9 (decimal strings: read exactly): confirmed; so is a relative one.
  r = answer_both_ways(kUnit, b,
                       R"([{"kind":"distance","value":"1.000000000001","abs_tol":"1e-9"},
          {"kind":"distance","value":"0.999999999999","abs_tol":1e-9},
          {"kind":"distance","value":"0.999999999999","rel_tol":"1e-9"},
          {"kind":"distance","value":"1.01","abs_tol":"1e-9"}])");
  EXPECT_EQ(verdicts(r),
            (std::vector<std::string>{"confirmed", "confirmed", "confirmed", "refuted"}));
  expect_excludes(verdict(r, 3));
  // The counterexample carries the (approximate) closest pair (1,0,0)-(2,0,0).
  const Json& pairs = *verdict(r, 3).find("counterexample")->find("pairs");
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(core::io::dump(pairs), "[[[1,0,0],[2,0,0]]]");
}

TEST(Verify, IrrationalDistance) {
  // Unit spheres with centres (0,0,0) and (2,2,0): distance 2 sqrt(2) - 2 = 0.828427124746...
  const std::string b = "\"(x-2)^2+(y-2)^2+z^2=1\"";
  const std::string v60 = "0.828427124746190097603377448419396157139343750753896146353359";
  const std::string v127 =
      "0.828427124746190097603377448419396157139343750753896146353359475981464956"
      "92421407770077506865528314547002769246182459404984967";
  Json r = answer_both_ways(kUnit, b,
                            R"([{"kind":"distance","value":"0.82842712474619","abs_tol":"1e-13"},
                                {"kind":"distance","value":"0.8284271247","abs_tol":"1e-12"},
                                {"kind":"distance","value":")" +
                                v60 + R"("},
                                {"kind":"distance","value":")" +
                                v60 + R"(","rel_tol":"1e-50"},
                                {"kind":"distance","value":")" +
                                v127 + R"("}])");
  // Within the tolerance; 4.6e-12 off with tolerance 1e-12; the exact rational v60 (refuted
  // once refined past 60 digits); v60 within 1e-50 relative (more than the default 15
  // digits); v127 agrees with the value beyond the 100-digit cap: undecided, and what is
  // established is an enclosure that straddles it.
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "refuted", "refuted", "confirmed",
                                                   "undecided"}));
  EXPECT_EQ(status(r), "undecided");
  expect_excludes(verdict(r, 1));
  expect_excludes(verdict(r, 2));
  const Json& est = *verdict(r, 4).find("established")->find("distance");
  EXPECT_TRUE(exact(est.find("lower")->text()) <= exact(v127));
  EXPECT_TRUE(exact(v127) <= exact(est.find("upper")->text()));
}

TEST(Verify, RelationsAtTangencyAndJustApart) {
  // Centre distance exactly 2: externally touching.
  Json r = answer_both_ways(
      kUnit, "\"(x-2)^2+y^2+z^2=1\"",
      R"([{"kind":"relation","value":"touching"},{"kind":"solids_collide","value":true},
          {"kind":"solids_collide","value":false,"touching_collides":false},
          {"kind":"relation","value":"separated"},{"kind":"distance","value":0}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "confirmed", "confirmed", "refuted",
                                                   "confirmed"}));
  EXPECT_EQ(verdict(r, 3).find("counterexample")->find("relation")->text(), "touching");
  // 2^-40 apart: separated, the solids do not collide.
  const std::string apart =
      "\"(x-2-" + pow2_text(-40) + ")^2+y^2+z^2=1\""; // 2 + 1/2^40: the parser reads p/q
  r = answer_both_ways(kUnit, apart,
                       R"([{"kind":"relation","value":"separated"},
                           {"kind":"solids_collide","value":false},
                           {"kind":"relation","value":"touching"},
                           {"kind":"solids_collide","value":true}])");
  EXPECT_EQ(verdicts(r),
            (std::vector<std::string>{"confirmed", "confirmed", "refuted", "refuted"}));
  EXPECT_EQ(verdict(r, 3).find("counterexample")->find("solids_collide")->as_bool(), false);
  // Overlapping by 2^-40.
  const std::string over = "\"(x-2+" + pow2_text(-40) + ")^2+y^2+z^2=1\"";
  r = answer_both_ways(kUnit, over,
                       R"([{"kind":"relation","value":"overlapping"},
                           {"kind":"solids_collide","value":true,"touching_collides":false},
                           {"kind":"relation","value":"separated"}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "confirmed", "refuted"}));
}

TEST(Verify, NestedEllipsoids) {
  // The unit sphere inside the ellipsoid with semi-axes 2, 2, 3 (a inside b).
  Json r = answer_both_ways(kUnit, "\"x^2/4+y^2/4+z^2/9=1\"",
                            R"([{"kind":"relation","value":"nested","inside":"a"},
                                {"kind":"relation","value":"nested","inside":"b"},
                                {"kind":"relation","value":"nested"},
                                {"kind":"relation","value":"overlapping"},
                                {"kind":"solids_collide","value":true},
                                {"kind":"distance","value":1},
                                {"kind":"distance","value":0,"solid":true}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "refuted", "confirmed", "refuted",
                                                   "confirmed", "confirmed", "confirmed"}));
  EXPECT_EQ(verdict(r, 1).find("counterexample")->find("inside")->text(), "a");
  // Internally touching (the unit sphere in the sphere of radius 2 centred at (1,0,0)):
  // touching with a inside, and colliding whatever touching counts as.
  r = answer_both_ways(kUnit, "\"(x-1)^2+y^2+z^2=4\"",
                       R"([{"kind":"relation","value":"touching","inside":"a"},
                           {"kind":"solids_collide","value":true,"touching_collides":false}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "confirmed"}));
}

TEST(Verify, TouchingOrOverlappingForAnEllipsoidAndAnotherQuadric) {
  // The unit sphere and: a cylinder of radius 1/2 through it (two circles crossed:
  // overlapping); the tangent plane x = 1 (one point: touching), the plane 2^-40 inside
  // (a circle: overlapping) and 2^-40 outside (separated); the cylinder of radius 1 (tangent
  // along the equator: touching); a paraboloid whose vertex touches the south pole and which
  // crosses along z = 0 (overlapping); a cone tangent along a circle (touching).
  const std::string claims = R"([{"kind":"relation","value":"overlapping"},
                                  {"kind":"relation","value":"touching"},
                                  {"kind":"relation","value":"separated"},
                                  {"kind":"solids_collide","value":true}])";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"\"x^2+y^2=1/4\"", {"confirmed", "refuted", "refuted", "confirmed"}},
      {"\"x=1\"", {"refuted", "confirmed", "refuted", "confirmed"}},
      {"\"x=1-" + pow2_text(-40) + "\"", {"confirmed", "refuted", "refuted", "confirmed"}},
      {"\"x=1+" + pow2_text(-40) + "\"", {"refuted", "refuted", "confirmed", "refuted"}},
      {"\"x^2+y^2=1\"", {"refuted", "confirmed", "refuted", "confirmed"}},
      {"\"z=x^2+y^2-1\"", {"confirmed", "refuted", "refuted", "confirmed"}},
      {"\"x^2+y^2=(z-2)^2/3\"", {"refuted", "confirmed", "refuted", "confirmed"}},
  };
  for (const auto& [b, expected] : cases) {
    Json r = answer_both_ways(kUnit, b, claims);
    EXPECT_EQ(verdicts(r), expected) << b;
    EXPECT_EQ(status(r), "certified") << b;
  }
  // A crossing is shown by the certified morphology (a simple conic component).
  Json r = answer(kUnit, "\"x^2+y^2=1/4\"", claims);
  const Json& ce = *verdict(r, 1).find("counterexample");
  EXPECT_TRUE(ce.find("surfaces_cross")->as_bool());
  EXPECT_EQ(ce.find("morphology")->text(), "two_disjoint_conics");
  // Which solid holds the other at a touching is not established: an external-only claim
  // (touching does not collide) stays undecided.
  r = answer(kUnit, "\"x^2+y^2=1\"",
             R"([{"kind":"solids_collide","value":true,"touching_collides":false}])");
  EXPECT_EQ(verdicts(r), std::vector<std::string>{"undecided"});
  // No ellipsoid (a torus crossing the unit sphere): surfaces meet, touching or overlapping
  // is not established.
  r = answer_both_ways(
      kUnit,
      R"({"type":"torus","center":[2,0,0],"axis":[0,0,1],"major_radius":2,"minor_radius":"1/2"})",
      R"([{"kind":"relation","value":"overlapping"},{"kind":"relation","value":"separated"}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"undecided", "refuted"}));
  EXPECT_TRUE(verdict(r, 0).find("established")->find("surfaces_meet")->as_bool());
}

TEST(Verify, TorusAwayFromASphere) {
  // A torus 1 away from the unit sphere (the plane-free pair goes through the distance).
  Json r = answer_both_ways(
      kUnit,
      R"({"type":"torus","center":[5,0,0],"axis":[0,0,1],"major_radius":2,"minor_radius":1})",
      R"([{"kind":"relation","value":"separated"},
                           {"kind":"distance","value":1},
                           {"kind":"solids_collide","value":false}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "confirmed", "confirmed"}));
}

TEST(Verify, MorphologyTuCaseComponentsOfEllipsoidFixtures) {
  auto doc = fixtures::load_json("fixtures/ellipsoid_fixtures.json");
  int n = 0;
  for (const auto& [key, e] : doc.members()) {
    int c = std::stoi(key);
    if (c != 1 && c != 2 && c != 7 && c != 21) continue;
    const auto& m = certify::morphology_of_case(c);
    const auto& other = certify::morphology_of_case(c == 1 ? 3 : 1);
    std::string a = "{\"matrix\":" + core::io::dump(*e.find("E1")) + "}";
    std::string b = "{\"matrix\":" + core::io::dump(*e.find("E2")) + "}";
    std::string claims =
        "[{\"kind\":\"morphology\",\"value\":\"" + std::string(m.id) +
        "\"},{\"kind\":\"tu_case\",\"value\":" + std::to_string(c) +
        "},{\"kind\":\"components\",\"value\":{\"loops\":" + std::to_string(m.loops) +
        ",\"isolated_points\":" + std::to_string(m.isolated_points) +
        "}},{\"kind\":\"morphology\",\"value\":\"" + other.id +
        "\"},{\"kind\":\"tu_case\",\"value\":" + std::to_string(other.tu_case) +
        "},{\"kind\":\"components\",\"value\":{\"conics\":" + std::to_string(m.conics + 1) + "}}]";
    Json r = answer_both_ways(a, b, claims);
    EXPECT_EQ(status(r), "certified") << key;
    EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "confirmed", "confirmed",
                                                     "refuted", "refuted", "refuted"}))
        << key;
    for (size_t i = 3; i < 6; ++i) {
      const Json& ce = *verdict(r, i).find("counterexample");
      EXPECT_EQ(ce.find("morphology")->text(), m.id) << key;
      EXPECT_EQ(ce.find("tu_case")->text(), std::to_string(c)) << key;
      EXPECT_EQ(ce.find("components")->find("conics")->text(), std::to_string(m.conics)) << key;
    }
    ++n;
  }
  EXPECT_EQ(n, 4);
}

TEST(Verify, FloatModeNeverGuesses) {
  Json r = answer(
      kUnit, "\"(x-3)^2+y^2+z^2=1\"",
      R"([{"kind":"distance","value":1,"abs_tol":0.5},{"kind":"morphology","value":"two_ovals"}])",
      ",\"mode\":\"float\"");
  EXPECT_EQ(status(r), "undecided");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"undecided", "undecided"}));
}

TEST(Verify, BudgetRunsOutToUndecided) {
  // Two tori overlapping by 1e-20 (seconds without a budget, budget_test.cpp): past the 50 ms
  // budget every verdict that needs the distance is undecided, with reason "budget".
  const std::string a =
      R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})";
  const std::string b =
      R"({"type":"torus","center":["799999999999999999999/100000000000000000000",)"
      R"(0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})";
  Json r = answer(a, b,
                  R"([{"kind":"distance","value":0,"abs_tol":"1e-30"},
                      {"kind":"relation","value":"separated"}])",
                  ",\"budget_ms\":50");
  EXPECT_EQ(status(r), "undecided");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"undecided", "undecided"}));
  ASSERT_NE(r.find("reason"), nullptr);
  EXPECT_EQ(r.find("reason")->text(), "budget");
  // Its own wall time is reported (not bounded here: a sanitizer build is 20-50x slower).
  ASSERT_NE(r.find("time_ms"), nullptr);
}

TEST(Verify, BudgetAndTimeFieldsKeepWorking) {
  Json r = answer(kUnit, "\"(x-3)^2+y^2+z^2=1\"", R"([{"kind":"distance","value":1}])",
                  ",\"budget_ms\":60000");
  EXPECT_EQ(status(r), "certified");
  EXPECT_TRUE(r.find("time_ms"));
}

TEST(Verify, BadClaimsAreInputErrorsWithTheirPath) {
  auto path_of = [](const std::string& a, const std::string& claims, const std::string& extra) {
    Json r = answer(kUnit, a, claims, extra);
    EXPECT_EQ(status(r), "error") << core::io::dump(r);
    const Json* e = r.find("error");
    return e && e->find("json_path") ? e->find("json_path")->text() : std::string("(none)");
  };
  const std::string b = "\"(x-3)^2+y^2+z^2=1\"";
  const std::string ok = R"({"kind":"distance","value":1},)";
  EXPECT_EQ(path_of(b, "[" + ok + R"({"kind":"closeness","value":1}])", ""), "$.claims[1].kind");
  EXPECT_EQ(path_of(b, "[" + ok + ok + R"({"kind":"distance","value":1,"abs_tol":-1e-3}])", ""),
            "$.claims[2].abs_tol");
  EXPECT_EQ(path_of(b, R"([{"kind":"distance","value":1,"rel_tol":"-1/2"}])", ""),
            "$.claims[0].rel_tol");
  EXPECT_EQ(path_of(b, R"([{"kind":"distance","value":[1]}])", ""), "$.claims[0].value");
  EXPECT_EQ(path_of(b, R"([{"kind":"relation","value":"apart"}])", ""), "$.claims[0].value");
  EXPECT_EQ(path_of(b, R"([{"kind":"relation","value":"separated","inside":"a"}])", ""),
            "$.claims[0].inside");
  EXPECT_EQ(path_of(b, R"([{"kind":"solids_collide","value":"yes"}])", ""), "$.claims[0].value");
  EXPECT_EQ(path_of(b, R"([{"kind":"tu_case","value":36}])", ""), "$.claims[0].value");
  EXPECT_EQ(path_of(b, R"([{"kind":"morphology","value":"three_ovals"}])", ""),
            "$.claims[0].value");
  EXPECT_EQ(path_of(b, R"([{"kind":"components","value":{"ovals":2}}])", ""),
            "$.claims[0].value.ovals");
  EXPECT_EQ(path_of(b, R"([{"kind":"distance","value":1,"tolerance":1}])", ""),
            "$.claims[0].tolerance");
  EXPECT_EQ(path_of(b, R"([{"value":1}])", ""), "$.claims[0].kind");
  EXPECT_EQ(path_of(b, "[]", ""), "$.claims");
  EXPECT_EQ(path_of(b, "{}", ""), "$.claims");
  // A quadric-only claim on a torus.
  EXPECT_EQ(
      path_of(
          R"({"type":"torus","center":[5,0,0],"axis":[0,0,1],"major_radius":2,"minor_radius":1})",
          R"([{"kind":"morphology","value":"two_ovals"}])", ""),
      "$.claims[0].kind");
  // No claims at all.
  Json r = app::process_batch_line(R"({"id":1,"op":"verify","a":"x^2+y^2+z^2=1","b":"z=0"})", 1,
                                   certify::Mode::Filtered);
  EXPECT_EQ(r.find("error")->find("json_path")->text(), "$.claims");
}

TEST(Verify, CommandLine) {
  std::string out = "/tmp/surfcert_verify_test_" + std::to_string(getpid());
  auto run = [&](const std::string& args) {
    int st =
        std::system((std::string(SURFCERT_BINARY) + " " + args + " >" + out + " 2>&1").c_str());
    std::FILE* f = std::fopen(out.c_str(), "r");
    std::string text;
    for (int ch; f && (ch = std::fgetc(f)) != EOF;)
      text += static_cast<char>(ch);
    if (f) std::fclose(f);
    std::remove(out.c_str());
    return std::make_pair(WIFEXITED(st) ? WEXITSTATUS(st) : -1, text);
  };
  auto [code, text] =
      run("verify --json 'x^2+y^2+z^2=1' '(x-3)^2+y^2+z^2=1' --claim '{\"kind\":\"distance\","
          "\"value\":1}' --claim '[{\"kind\":\"relation\",\"value\":\"touching\"},{\"kind\":"
          "\"solids_collide\",\"value\":false}]'");
  EXPECT_EQ(code, 0) << text;
  Json j = core::io::parse_json(text, "<stdout>");
  EXPECT_EQ(status(j), "certified");
  EXPECT_EQ(verdicts(j), (std::vector<std::string>{"confirmed", "refuted", "confirmed"}));
  std::tie(code, text) =
      run("verify 'x^2+y^2+z^2=1' '{\"type\":\"torus\",\"center\":[2,0,0],\"axis\":[0,0,1],"
          "\"major_radius\":2,\"minor_radius\":\"1/2\"}' --claim "
          "'{\"kind\":\"relation\",\"value\":\"touching\"}'");
  EXPECT_EQ(code, 3) << text; // undecided
  EXPECT_NE(text.find("claim 1 (relation): undecided"), std::string::npos) << text;
  std::tie(code, text) = run("verify 'x^2+y^2+z^2=1' 'z=0' --claim "
                             "'{\"kind\":\"distance\",\"value\":0,\"abs_tol\":-1}'");
  EXPECT_EQ(code, 2) << text;
  EXPECT_NE(text.find("$.claims[0].abs_tol"), std::string::npos) << text;
  std::tie(code, text) = run("verify 'x^2+y^2+z^2=1' 'z=0'");
  EXPECT_EQ(code, 2) << text;
}

namespace {

using P3 = std::array<Rational, 3>;

P3 point_of(const Json& j) {
  return {exact(j.items().at(0).text()), exact(j.items().at(1).text()),
          exact(j.items().at(2).text())};
}

Rational d2_of(const P3& p, const P3& q) {
  Rational s;
  for (size_t i = 0; i < 3; ++i)
    s += (p[i] - q[i]) * (p[i] - q[i]);
  return s;
}

// sqrt(u) + t < sqrt(v), exactly (the test's own reading).
bool root_plus_less(const Rational& u, const Rational& t, const Rational& v) {
  const Rational rhs = v - u - t * t;
  return rhs.sign() > 0 && Rational(4) * t * t * u < rhs * rhs;
}

// Sphere |x - c|^2 = r^2 as a function (the test's own equations).
struct Sphere {
  P3 c;
  Rational r;
  Rational f(const P3& x) const { return d2_of(x, c) - r * r; }
};

// A refuted closest_points claim's closer pair, re-checked: each segment has ends of opposite
// signs (or a zero) on its sphere, every pair of segment points is within the printed bound,
// and that bound plus tol is below the claimed |p - q|.
void expect_closer_pair(const Json& v, const Sphere& a, const Sphere& b, const P3& p, const P3& q,
                        const Rational& tol) {
  ASSERT_EQ(v.find("verdict")->text(), "refuted") << core::io::dump(v);
  const Json* cp = v.find("counterexample")->find("closer_pair");
  ASSERT_TRUE(cp) << core::io::dump(v);
  const Json& sa = *cp->find("a_segment");
  const Json& sb = *cp->find("b_segment");
  EXPECT_LE(a.f(point_of(sa.items()[0])).sign() * a.f(point_of(sa.items()[1])).sign(), 0);
  EXPECT_LE(b.f(point_of(sb.items()[0])).sign() * b.f(point_of(sb.items()[1])).sign(), 0);
  const Rational ub2 = exact(cp->find("distance_squared_upper")->text());
  for (const auto& x : sa.items())
    for (const auto& y : sb.items())
      EXPECT_TRUE(d2_of(point_of(x), point_of(y)) <= ub2);
  EXPECT_TRUE(root_plus_less(ub2, tol, d2_of(p, q)));
}

// A claimed point refuted as off the unit-radius sphere s: its exact distance | |x-c| - r |
// exceeds tol, and so does the printed lower bound.
void expect_off_sphere(const Json& v, const Sphere& s, const P3& x, const Rational& tol) {
  ASSERT_EQ(v.find("verdict")->text(), "refuted") << core::io::dump(v);
  const Json& ce = *v.find("counterexample");
  EXPECT_TRUE(tol < exact(ce.find("distance_to_surface")->find("lower")->text()));
  const Rational n2 = d2_of(x, s.c);
  EXPECT_TRUE(root_plus_less(s.r * s.r, tol, n2) || root_plus_less(n2, tol, s.r * s.r));
}

std::string pt(const P3& p) {
  return "[\"" + p[0].to_string() + "\",\"" + p[1].to_string() + "\",\"" + p[2].to_string() + "\"]";
}

std::string cp_claim(const P3& p, const P3& q, const Rational& tol) {
  return R"({"kind":"closest_points","value":[)" + pt(p) + "," + pt(q) + R"(],"abs_tol":")" +
         tol.to_string() + "\"}";
}

// The answer and the answer with a and b swapped (the claims given for each order).
Json answer_swapped(const std::string& a, const std::string& b, const std::string& claims,
                    const std::string& swapped_claims) {
  Json r = answer(a, b, claims);
  EXPECT_EQ(verdicts(r), verdicts(answer(b, a, swapped_claims))) << claims;
  return r;
}

} // namespace

TEST(Verify, ClosestPointsOfTwoSpheres) {
  const Sphere sa{{0, 0, 0}, 1}, sb{{3, 0, 0}, 1};
  const std::string b = "\"(x-3)^2+y^2+z^2=1\"";
  const Rational tol = core::pow2(-30), zero(0);
  const Rational u = Rational::exact_from_double(std::nextafter(1.0, 2.0)) - Rational(1);
  struct Case {
    P3 p, q;
    Rational tol;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {{1, 0, 0}, {2, 0, 0}, zero, "confirmed"}, // exact
      // a few ulps off, tolerance 2^-30
      {{Rational(1) + Rational(3) * u, 0, 0},
       {Rational(2) - Rational(2) * u, u, 0},
       tol,
       "confirmed"},
      // both points tol/2 inside: |p - q| = 1 + tol, at the edge of the tolerance
      {{Rational(1) - tol / Rational(2), 0, 0},
       {Rational(2) + tol / Rational(2), 0, 0},
       tol,
       "confirmed"},
      // 0.6 tol each: each point within tol, but |p - q| = 1 + 1.2 tol
      {{Rational(1) - tol * Rational(3, 5), 0, 0},
       {Rational(2) + tol * Rational(3, 5), 0, 0},
       tol,
       "refuted"},
      // p 2 tol outside a
      {{Rational(1) + Rational(2) * tol, 0, 0}, {2, 0, 0}, tol, "refuted"},
      // q 2 tol inside b
      {{1, 0, 0}, {Rational(2) + Rational(2) * tol, 0, 0}, tol, "refuted"},
      // p on a (0.6, 0.8, 0) but not closest: a closer pair exists
      {{Rational(3, 5), Rational(4, 5), 0}, {2, 0, 0}, tol, "refuted"},
      // the same midpoint for both, within 0.6 of each surface: closer than the minimum 1
      {{Rational(3, 2), 0, 0}, {Rational(3, 2), 0, 0}, Rational(3, 5), "refuted"},
  };
  std::string claims = "[", swapped = "[";
  for (const auto& c : cases) {
    claims += (claims.size() > 1 ? "," : "") + cp_claim(c.p, c.q, c.tol);
    swapped += (swapped.size() > 1 ? "," : "") + cp_claim(c.q, c.p, c.tol);
  }
  Json r = answer_swapped(kUnit, b, claims + "]", swapped + "]");
  std::vector<std::string> expected;
  for (const auto& c : cases)
    expected.push_back(c.expected);
  EXPECT_EQ(verdicts(r), expected);
  expect_closer_pair(verdict(r, 3), sa, sb, cases[3].p, cases[3].q, tol);
  expect_off_sphere(verdict(r, 4), sa, cases[4].p, tol);
  expect_off_sphere(verdict(r, 5), sb, cases[5].q, tol);
  expect_closer_pair(verdict(r, 6), sa, sb, cases[6].p, cases[6].q, tol);
  // Closer than the minimum: the printed lower bound of the minimum exceeds |p - q| + tol.
  EXPECT_TRUE(Rational(3, 5) <
              exact(verdict(r, 7).find("counterexample")->find("distance")->find("lower")->text()));
}

TEST(Verify, ClosestPointsOnAContinuumAndATorus) {
  // The unit sphere inside the cylinder x^2 + y^2 = 4: distance 1 along a circle of
  // minimizers; any pair on it is a closest pair.
  Json r = answer(kUnit, "\"x^2+y^2=4\"",
                  R"([{"kind":"closest_points","value":[[1,0,0],[2,0,0]],"abs_tol":1e-12},
                      {"kind":"closest_points","value":[["0.6","0.8",0],["1.2","1.6",0]]},
                      {"kind":"closest_points","value":[[0,0,1],[2,0,1]],"abs_tol":1e-12}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "confirmed", "refuted"}));
  // A ring torus (R = 2, r = 1 about z) and the plane z = 10: distance 9 from the top circle.
  const std::string torus =
      R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":2,"minor_radius":1})";
  r = answer(torus, "\"z=10\"",
             R"([{"kind":"closest_points","value":[[2,0,1],[2,0,10]],"abs_tol":1e-12},
                 {"kind":"closest_points","value":[[3.5,0,0],[3.5,0,10]],"abs_tol":0.1}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "refuted"}));
  // (3.5, 0, 0) is 0.5 from the tube.
  const Json& ce = *verdict(r, 1).find("counterexample");
  EXPECT_EQ(ce.find("surface")->text(), "a");
  EXPECT_TRUE(exact(ce.find("distance_to_surface")->find("lower")->text()) <= Rational(1, 2));
  EXPECT_TRUE(Rational(1, 2) <= exact(ce.find("distance_to_surface")->find("upper")->text()));
}

namespace {

using M3 = std::array<P3, 3>;

P3 apply(const M3& m, const P3& x, const P3& t) {
  P3 y;
  for (size_t i = 0; i < 3; ++i)
    y[i] = m[i][0] * x[0] + m[i][1] * x[1] + m[i][2] * x[2] + t[i];
  return y;
}

// The rotation of the quaternion (a, b, c, d), rational: entries over a^2 + b^2 + c^2 + d^2.
M3 quaternion_rotation(long a, long b, long c, long d) {
  const Rational n(a * a + b * b + c * c + d * d);
  auto e = [&](long v) { return Rational(v) / n; };
  return {P3{e(a * a + b * b - c * c - d * d), e(2 * (b * c - a * d)), e(2 * (b * d + a * c))},
          P3{e(2 * (b * c + a * d)), e(a * a - b * b + c * c - d * d), e(2 * (c * d - a * b))},
          P3{e(2 * (b * d - a * c)), e(2 * (c * d + a * b)), e(a * a - b * b - c * c + d * d)}};
}

std::string mat(const M3& m) {
  return "[" + pt(m[0]) + "," + pt(m[1]) + "," + pt(m[2]) + "]";
}

// The unit circle of the spheres |x|^2 = 1 and |x - (1,0,0)|^2 = 1: x = 1/2, y^2 + z^2 = 3/4,
// as n + 1 double points (closed).
std::vector<P3> circle(int n) {
  std::vector<P3> out;
  const double r = std::sqrt(3.0) / 2;
  for (int k = 0; k <= n; ++k) {
    const double t = 2 * M_PI * (k % n) / n;
    out.push_back({Rational(1, 2), Rational::exact_from_double(r * std::cos(t)),
                   Rational::exact_from_double(r * std::sin(t))});
  }
  return out;
}

std::string polyline(const std::vector<P3>& l, const M3& m, const P3& t) {
  std::string s = "[";
  for (const auto& p : l)
    s += (s.size() > 1 ? "," : "") + pt(apply(m, p, t));
  return s + "]";
}

std::string curve_claim(const std::vector<std::vector<P3>>& lines, const std::string& tol,
                        const M3& m, const P3& t) {
  std::string s = R"({"kind":"curve","value":[)";
  for (size_t i = 0; i < lines.size(); ++i)
    s += (i ? "," : "") + polyline(lines[i], m, t);
  return s + R"(],"abs_tol":")" + tol + "\"}";
}

// The curve claims of the two-sphere circle, moved by x -> m x + t: the full circle (tol
// 1e-2), half of it (a missed half), one point moved 1% off, and a phantom branch added.
std::string circle_claims(const M3& m, const P3& t) {
  const std::vector<P3> full = circle(64);
  const std::vector<P3> half(full.begin(), full.begin() + 33);
  std::vector<P3> moved = full;
  moved[5][1] *= Rational(101, 100), moved[5][2] *= Rational(101, 100);
  const std::vector<P3> phantom = {{Rational(1, 2), 0, 0}, {Rational(1, 2), Rational(1, 10), 0}};
  return "[" + curve_claim({full}, "0.01", m, t) + "," + curve_claim({half}, "0.01", m, t) + "," +
         curve_claim({moved}, "0.001", m, t) + "," + curve_claim({full, phantom}, "0.01", m, t) +
         "]";
}

const M3 kIdentity = {P3{1, 0, 0}, P3{0, 1, 0}, P3{0, 0, 1}};

// Distance (doubles, sampled finely) from x to the polyline's segments.
double sampled_distance(const std::vector<std::array<double, 3>>& line,
                        const std::array<double, 3>& x) {
  double best = HUGE_VAL;
  for (size_t k = 0; k + 1 < line.size(); ++k)
    for (int s = 0; s <= 1000; ++s) {
      double d2 = 0;
      for (size_t i = 0; i < 3; ++i) {
        const double y = line[k][i] + (line[k + 1][i] - line[k][i]) * s / 1000.0;
        d2 += (y - x[i]) * (y - x[i]);
      }
      best = std::min(best, std::sqrt(d2));
    }
  return best;
}

std::array<double, 3> dbl(const P3& p) {
  return {p[0].to_double_approx(), p[1].to_double_approx(), p[2].to_double_approx()};
}

// A refuted curve claim on the two-sphere circle: its point_on_curve box centre is within
// 2 half_width of the circle x = 1/2, y^2 + z^2 = 3/4 (closed form) and farther than
// tol + 2 half_width from the claimed polyline (re-measured here in doubles).
void expect_missed_circle_point(const Json& v, const std::vector<P3>& claimed, double tol) {
  ASSERT_EQ(v.find("verdict")->text(), "refuted") << core::io::dump(v);
  const Json& pc = *v.find("counterexample")->find("point_on_curve");
  const auto c = dbl(point_of(*pc.find("centre")));
  const double hw = exact(pc.find("half_width")->text()).to_double_approx();
  EXPECT_LT(hw, 1e-7);
  EXPECT_LE(std::abs(c[0] - 0.5), 2 * hw + 1e-15);
  EXPECT_LE(std::abs(std::hypot(c[1], c[2]) - std::sqrt(3.0) / 2), 2 * hw + 1e-15);
  std::vector<std::array<double, 3>> line;
  for (const auto& p : claimed)
    line.push_back(dbl(p));
  EXPECT_GT(sampled_distance(line, c), tol + 2 * hw);
}

} // namespace

TEST(Verify, CurveOfTwoSpheres) {
  const std::string b = "\"(x-1)^2+y^2+z^2=1\"";
  Json r = answer_both_ways(kUnit, b, circle_claims(kIdentity, {0, 0, 0}));
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "refuted", "refuted", "refuted"}));
  // The missed half: a certified point of the circle farther than tol from every segment.
  const std::vector<P3> full = circle(64);
  expect_missed_circle_point(verdict(r, 1), std::vector<P3>(full.begin(), full.begin() + 33), 0.01);
  // The whole 64-gon within 1e-6: its vertices are on the circle (to rounding) but its chords
  // are up to 1.1e-3 inside: refuted with a circle point off the chords.
  const Json polygon =
      answer(kUnit, b, "[" + curve_claim({full}, "1e-6", kIdentity, {0, 0, 0}) + "]");
  expect_missed_circle_point(verdict(polygon, 0), full, 1e-6);
  // Vertices on the circle but a chord through its centre (a diameter added as a polyline):
  // every claimed vertex is within tol and the circle is covered, but the diameter's midpoint
  // (1/2, ~0, 0) is 1/2 from each sphere: refuted by that point of the segment.
  const Json diameter = answer(
      kUnit, b, "[" + curve_claim({full, {full[0], full[32]}}, "0.01", kIdentity, {0, 0, 0}) + "]");
  const Json& dv = verdict(diameter, 0);
  ASSERT_EQ(dv.find("verdict")->text(), "refuted") << core::io::dump(dv);
  EXPECT_EQ(dv.find("counterexample")->find("polyline")->text(), "1");
  const P3 mid = point_of(*dv.find("counterexample")->find("claimed"));
  EXPECT_EQ(mid, (P3{Rational(1, 2), (full[0][1] + full[32][1]) / Rational(2),
                     (full[0][2] + full[32][2]) / Rational(2)}));
  expect_off_sphere(dv, Sphere{{0, 0, 0}, 1}, mid, Rational(1, 100));
  // An empty curve: refuted by the certified relation (the spheres overlap); the empty claim
  // on spheres 2^-40 apart is confirmed (separated).
  const Json empty = answer(kUnit, b, R"([{"kind":"curve","value":[],"abs_tol":0.01}])");
  EXPECT_EQ(verdicts(empty), std::vector<std::string>{"refuted"});
  EXPECT_EQ(verdict(empty, 0).find("counterexample")->find("relation")->text(), "overlapping");
  EXPECT_EQ(verdicts(answer(kUnit, "\"(x-2-" + pow2_text(-40) + ")^2+y^2+z^2=1\"",
                            R"([{"kind":"curve","value":[],"abs_tol":0.01}])")),
            std::vector<std::string>{"confirmed"});
  // The moved point: 1% farther from the axis, so about 0.0075 from each sphere.
  expect_off_sphere(verdict(r, 2), Sphere{{0, 0, 0}, 1},
                    point_of(*verdict(r, 2).find("counterexample")->find("claimed")),
                    Rational(1, 1000));
  // The phantom branch's point (1/2, 0, 0) is 1/2 from each sphere.
  expect_off_sphere(verdict(r, 3), Sphere{{0, 0, 0}, 1}, {Rational(1, 2), 0, 0}, Rational(1, 100));
}

TEST(Verify, VerdictsInvariantUnderRationalRigidMotions) {
  // Closest points: an ellipsoid with semi-axes 1, 2, 3 and the unit sphere centred at
  // (4, 0, 0): closest pair (1,0,0)-(3,0,0), distance 2. Curve: the two-sphere circle.
  const std::vector<std::pair<M3, P3>> motions = {
      {kIdentity, {0, 0, 0}},
      {{P3{0, -1, 0}, P3{0, 0, 1}, P3{-1, 0, 0}}, {Rational(1, 3), -2, Rational(5, 7)}},
      {{P3{0, 1, 0}, P3{1, 0, 0}, P3{0, 0, 1}}, {0, 0, 1}}, // a reflection
      {quaternion_rotation(1, 2, 2, 4), {Rational(-3, 2), Rational(1, 8), 2}},
      {quaternion_rotation(1, 1, 1, 1), {0, 0, 0}},
  };
  std::vector<std::string> first_cp, first_curve;
  for (const auto& [m, t] : motions) {
    const std::string ell = R"({"type":"ellipsoid","center":)" + pt(t) +
                            R"(,"radii":[1,2,3],"rotation":{"matrix":)" + mat(m) + "}}";
    const std::string sph =
        R"({"type":"sphere","center":)" + pt(apply(m, {4, 0, 0}, t)) + R"(,"radius":1})";
    auto at = [&](const P3& x) { return apply(m, x, t); };
    const Rational tol = core::pow2(-30);
    const std::vector<std::pair<P3, P3>> pairs = {{{1, 0, 0}, {3, 0, 0}},
                                                  {{0, 2, 0}, {3, 0, 0}},
                                                  {{1, 0, 0}, {Rational(31, 10), 0, 0}},
                                                  {{1, 0, 0}, {3, Rational(1, 1000), 0}}};
    std::string claims = "[", swapped = "[";
    for (const auto& [p, q] : pairs) {
      claims += (claims.size() > 1 ? "," : "") + cp_claim(at(p), at(q), tol);
      swapped += (swapped.size() > 1 ? "," : "") + cp_claim(at(q), at(p), tol);
    }
    Json r = answer_swapped(ell, sph, claims + "]", swapped + "]");
    EXPECT_EQ(verdicts(r),
              (std::vector<std::string>{"confirmed", "refuted", "refuted", "refuted"}));
    if (first_cp.empty()) first_cp = verdicts(r);
    EXPECT_EQ(verdicts(r), first_cp);
    const std::string s1 = R"({"type":"sphere","center":)" + pt(t) + R"(,"radius":1})";
    const std::string s2 =
        R"({"type":"sphere","center":)" + pt(apply(m, {1, 0, 0}, t)) + R"(,"radius":1})";
    r = answer_both_ways(s1, s2, circle_claims(m, t));
    if (first_curve.empty()) first_curve = verdicts(r);
    EXPECT_EQ(verdicts(r), first_curve);
  }
  EXPECT_EQ(first_curve, (std::vector<std::string>{"confirmed", "refuted", "refuted", "refuted"}));
}

TEST(Verify, BadGeometricClaimsAreInputErrors) {
  auto path_of = [](const std::string& a, const std::string& claims) {
    Json r = answer(kUnit, a, claims);
    EXPECT_EQ(status(r), "error") << core::io::dump(r);
    const Json* e = r.find("error");
    return e && e->find("json_path") ? e->find("json_path")->text() : std::string("(none)");
  };
  const std::string b = "\"(x-3)^2+y^2+z^2=1\"";
  EXPECT_EQ(path_of(b, R"([{"kind":"closest_points","value":[[1,0,0]]}])"), "$.claims[0].value");
  EXPECT_EQ(path_of(b, R"([{"kind":"closest_points","value":[[1,0,0],[2,0]]}])"),
            "$.claims[0].value[1]");
  EXPECT_EQ(path_of(b, R"([{"kind":"closest_points","value":[[1,0,0],[2,"x",0]]}])"),
            "$.claims[0].value[1][1]");
  EXPECT_EQ(path_of(b, R"([{"kind":"closest_points","value":[[1,0,0],[2,0,0]],"abs_tol":-1}])"),
            "$.claims[0].abs_tol");
  EXPECT_EQ(path_of(b, R"([{"kind":"closest_points","value":[[1,0,0],[2,0,0]],"rel_tol":1}])"),
            "$.claims[0].rel_tol");
  EXPECT_EQ(path_of(b, R"([{"kind":"curve","value":{}}])"), "$.claims[0].value");
  EXPECT_EQ(path_of(b, R"([{"kind":"curve","value":[[[1,0,0]],[]]}])"), "$.claims[0].value[1]");
  EXPECT_EQ(path_of(b, R"([{"kind":"curve","value":[[[1,0,0],[1,0]]]}])"),
            "$.claims[0].value[0][1]");
  EXPECT_EQ(path_of(b, R"([{"kind":"curve","value":[[[1,0,0]]],"abs_tol":"-1e-3"}])"),
            "$.claims[0].abs_tol");
  // A curve claim is about two quadrics.
  EXPECT_EQ(
      path_of(
          R"({"type":"torus","center":[5,0,0],"axis":[0,0,1],"major_radius":2,"minor_radius":1})",
          R"([{"kind":"curve","value":[[[1,0,0]]]}])"),
      "$.claims[0].kind");
}

TEST(Verify, CurveOfTwoEllipsoidsTwoOvals) {
  // x^2 + y^2/4 + z^2/9 = 1 and x^2/4 + y^2 + z^2/2 = 1 meet in two ovals, in closed form:
  // x^2 = X(z^2) = (4/15)(3 + z^2/18), y^2 = Y(z^2) = (68/135)(27/17 - z^2); each oval
  // (x = +-sqrt(X)) is z = zmax cos t, y = sqrt(68/135) zmax sin t, zmax^2 = 27/17.
  const std::string a = "\"x^2+y^2/4+z^2/9=1\"", b = "\"x^2/4+y^2+z^2/2=1\"";
  auto X = [](double z2) { return 4.0 / 15 * (3 + z2 / 18); };
  auto Y = [](double z2) { return 68.0 / 135 * (27.0 / 17 - z2); };
  const double zmax = std::sqrt(27.0 / 17), ry = std::sqrt(68.0 / 135) * zmax;
  std::vector<std::vector<P3>> ovals(2);
  std::vector<std::vector<std::array<double, 3>>> dovals(2);
  const int n = 200;
  for (int s = 0; s < 2; ++s)
    for (int k = 0; k <= n; ++k) {
      const double t = 2 * M_PI * (k % n) / n, z = zmax * std::cos(t);
      const std::array<double, 3> p = {(s ? -1 : 1) * std::sqrt(X(z * z)), ry * std::sin(t), z};
      dovals[static_cast<size_t>(s)].push_back(p);
      ovals[static_cast<size_t>(s)].push_back({Rational::exact_from_double(p[0]),
                                               Rational::exact_from_double(p[1]),
                                               Rational::exact_from_double(p[2])});
    }
  Json r = answer(a, b,
                  "[" + curve_claim(ovals, "0.02", kIdentity, {0, 0, 0}) + "," +
                      curve_claim({ovals[0]}, "0.02", kIdentity, {0, 0, 0}) + "," +
                      curve_claim(ovals, "1e-7", kIdentity, {0, 0, 0}) + "]");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"confirmed", "refuted", "refuted"}));
  // Each counterexample: a point of the closed-form curve, farther than tol from the claim.
  for (auto [i, tol] : {std::pair<size_t, double>{1, 0.02}, {2, 1e-7}}) {
    const Json* ce = verdict(r, i).find("counterexample");
    ASSERT_TRUE(ce && ce->find("point_on_curve")) << core::io::dump(verdict(r, i));
    const auto c = dbl(point_of(*ce->find("point_on_curve")->find("centre")));
    const double hw =
        exact(ce->find("point_on_curve")->find("half_width")->text()).to_double_approx();
    EXPECT_LT(std::abs(c[0] * c[0] - X(c[2] * c[2])), 1e-6);
    EXPECT_LT(std::abs(c[1] * c[1] - Y(c[2] * c[2])), 1e-6);
    double d = HUGE_VAL;
    for (size_t s = 0; s < (i == 1 ? 1u : 2u); ++s)
      d = std::min(d, sampled_distance(dovals[s], c));
    EXPECT_GT(d, tol + 2 * hw);
  }
}

TEST(Verify, SceneQuery) {
  const std::string scene = R"({"surfaces": {"u": "x^2+y^2+z^2=1", "v": "(x-3)^2+y^2+z^2=1",
    "t": {"type": "torus", "center": [0, 0, 0], "axis": [0, 0, 1], "major_radius": 2,
          "minor_radius": 1}, "p": "z=10"},
    "queries": [
      {"id": "q1", "op": "verify", "a": "u", "b": "v", "claims": [
        {"kind": "distance", "value": 1}, {"kind": "closest_points",
        "value": [[1, 0, 0], [2, 0, 0]]}, {"kind": "relation", "value": "touching"}]},
      {"id": "q2", "op": "verify", "a": "t", "b": "p", "claims": [
        {"kind": "closest_points", "value": [[2, 0, 1], [2, 0, 10]], "abs_tol": 1e-12}]}]})";
  const app::Scene s =
      app::read_scene(core::io::parse_json(scene, "scene"), "scene", certify::Mode::Filtered);
  ASSERT_EQ(s.queries.size(), 2u);
  Json r1 = app::run_query(s, s.queries[0]), r2 = app::run_query(s, s.queries[1]);
  EXPECT_EQ(verdicts(r1), (std::vector<std::string>{"confirmed", "confirmed", "refuted"}));
  EXPECT_EQ(verdicts(r2), std::vector<std::string>{"confirmed"});
  EXPECT_EQ(r1.find("op")->text(), "verify");
  // The same claims on a batch line get the same verdicts.
  EXPECT_EQ(verdicts(r1),
            verdicts(answer(kUnit, "\"(x-3)^2+y^2+z^2=1\"",
                            R"([{"kind": "distance", "value": 1}, {"kind": "closest_points",
        "value": [[1, 0, 0], [2, 0, 0]]}, {"kind": "relation", "value": "touching"}])")));
  // A bad claim is an error of the whole scene, located in it; claims on another op too.
  auto error_path = [](const std::string& text) {
    try {
      app::read_scene(core::io::parse_json(text, "scene"), "scene", certify::Mode::Filtered);
    } catch (const core::InputError& e) {
      return e.where().json_path;
    }
    return std::string("(none)");
  };
  const std::string head = R"({"surfaces": {"u": "x^2+y^2+z^2=1", "t": {"type": "torus",
    "center": [0, 0, 0], "axis": [0, 0, 1], "major_radius": 2, "minor_radius": 1}},
    "queries": [{"op": "classify", "a": "u", "b": "u"}, )";
  EXPECT_EQ(error_path(head + R"({"op": "verify", "a": "u", "b": "u", "claims": [
    {"kind": "distance", "value": 0}, {"kind": "curve", "value": [[[1, 0]]]}]}]})"),
            "$.queries[1].claims[1].value[0][0]");
  EXPECT_EQ(error_path(head + R"({"op": "verify", "a": "t", "b": "u", "claims": [
    {"kind": "tu_case", "value": 1}]}]})"),
            "$.queries[1].claims[0].kind");
  EXPECT_EQ(error_path(head + R"({"op": "verify", "a": "u", "b": "u"}]})"), "$.queries[1].claims");
  EXPECT_EQ(error_path(head + R"({"op": "distance", "a": "u", "b": "u", "claims": []}]})"),
            "$.queries[1].claims");
}

// The solid of a surface other than an ellipsoid, torus or canal surface is not modelled: its
// surface distance must not be read as the solid distance. x^4 + y^4 + z^4 <= 1 contains the
// ball of radius 1/2 (x^4 + y^4 + z^4 <= (x^2 + y^2 + z^2)^2 = 1/16 there): the solids are
// nested and collide, the solid distance is 0, the surface distance 1/2 (six axis points). It
// was certified 'separated', 'solids_collide: false' and solid distance 1/2.
TEST(Verify, NoSolidVerdictFromAnUnmodelledSolid) {
  const std::string quartic = "\"x^4+y^4+z^4=1\"";
  const std::string ball = R"({"type":"sphere","center":[0,0,0],"radius":"1/2"})";
  const Json r = answer(quartic, ball,
                        R"([{"kind":"relation","value":"separated"},
                            {"kind":"solids_collide","value":false},
                            {"kind":"relation","value":"nested"},
                            {"kind":"solids_collide","value":true},
                            {"kind":"distance","value":"1/2","abs_tol":"1e-12","solid":true},
                            {"kind":"distance","value":0,"abs_tol":"1e-12","solid":true}])");
  // The true claims (nested, collide, solid distance 0) may stay undecided; none of the six
  // may get a verdict against the truth.
  const std::vector<std::string> v = verdicts(r);
  ASSERT_EQ(v.size(), 6u) << core::io::dump(r);
  EXPECT_NE(v[0], "confirmed");
  EXPECT_NE(v[1], "confirmed");
  EXPECT_NE(v[2], "refuted");
  EXPECT_NE(v[3], "refuted");
  EXPECT_NE(v[4], "confirmed");
  EXPECT_NE(v[5], "refuted");
  // The surface distance itself stays certified: 1/2.
  const Json s = answer(quartic, ball, R"([{"kind":"distance","value":"1/2","abs_tol":"1e-12"}])");
  EXPECT_EQ(verdicts(s), std::vector<std::string>{"confirmed"}) << core::io::dump(s);
}

// An ellipsoid against a quadric whose real points are no surface: a double plane, a line
// (two conjugate imaginary planes), met transversally. Every common component is double or an
// isolated point without any tangency: the surfaces cross (the plane x = 0 cuts the sphere,
// the z axis pierces it at (0, 0, +-1) with (0, 0, 0) inside and (0, 0, 2) outside). They were
// certified 'touching', 'overlapping' refuted. The tangent plane x = 1 stays 'touching'.
TEST(Verify, DegenerateQuadricsDoNotTouchByMorphology) {
  const std::string claims =
      R"([{"kind":"relation","value":"touching"},{"kind":"relation","value":"overlapping"}])";
  for (const std::string other :
       {"\"x^2=0\"", "\"(x-1/2)^2=0\"", "\"x^2+y^2=0\"", "\"(x-1/2)^2+y^2=0\""})
    for (bool swap : {false, true}) {
      const Json r = swap ? answer(other, kUnit, claims) : answer(kUnit, other, claims);
      const std::vector<std::string> v = verdicts(r);
      ASSERT_EQ(v.size(), 2u) << core::io::dump(r);
      EXPECT_NE(v[0], "confirmed") << other << (swap ? " swapped" : "");
      EXPECT_NE(v[1], "refuted") << other << (swap ? " swapped" : "");
    }
  const Json t = answer(kUnit, "\"x=1\"", claims);
  EXPECT_EQ(verdicts(t), (std::vector<std::string>{"confirmed", "refuted"})) << core::io::dump(t);
}
