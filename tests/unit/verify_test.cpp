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

TEST(Verify, MeetingNonEllipsoidsAreUndecidedBetweenTouchingAndOverlapping) {
  // A sphere and a cylinder through it: the surfaces meet (distance 0), which rules out
  // separated and nested; whether they only touch is not established from the distance.
  Json r = answer_both_ways(kUnit, "\"x^2+y^2=1/4\"",
                            R"([{"kind":"relation","value":"overlapping"},
                                {"kind":"relation","value":"separated"},
                                {"kind":"solids_collide","value":true}])");
  EXPECT_EQ(verdicts(r), (std::vector<std::string>{"undecided", "refuted", "confirmed"}));
  EXPECT_EQ(status(r), "undecided");
  EXPECT_TRUE(verdict(r, 0).find("established")->find("surfaces_meet")->as_bool());
  // A torus 1 away from the unit sphere (the plane-free pair goes through the distance).
  r = answer_both_ways(
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
  std::tie(code, text) = run("verify 'x^2+y^2+z^2=1' 'x^2+y^2=1/4' --claim "
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
