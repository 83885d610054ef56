// The surfcert executable end to end: every bad-input class gives exit code 2, a message with
// its location, and no output file; batch keeps going after a bad line, answers in input order
// with any thread count, and follows the JSON contract documented in docs/json-contract.md.
#include "surfcert/core/io/json.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using surfcert::core::io::Json;

namespace {

// Batch answers without their wall times ("time_ms" differs from run to run; everything else
// must be identical).
std::string untimed(const std::string& out) {
  static const std::regex time_field(R"(,"time_ms":[0-9.]+)");
  return std::regex_replace(out, time_field, "");
}

struct Run {
  int code;
  std::string out, err;
};

std::string tmp_path(const std::string& name) {
  return (::testing::TempDir().empty() ? std::string("/tmp/") : ::testing::TempDir()) +
         "surfcert_cli_" + std::to_string(getpid()) + "_" + name;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

Run run(const std::string& args, const std::string& stdin_text = "") {
  std::string in = tmp_path("stdin"), out = tmp_path("stdout"), err = tmp_path("stderr");
  std::ofstream(in) << stdin_text;
  std::string cmd =
      std::string(SURFCERT_BINARY) + " " + args + " <" + in + " >" + out + " 2>" + err;
  int st = std::system(cmd.c_str());
  auto slurp = [](const std::string& p) {
    std::ifstream f(p);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  };
  Run r{WIFEXITED(st) ? WEXITSTATUS(st) : -1, slurp(out), slurp(err)};
  std::remove(in.c_str());
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

bool exists(const std::string& p) {
  return std::ifstream(p).good();
}

} // namespace

TEST(Cli, ClassifyHumanAndJson) {
  auto r = run("classify 'x^2+y^2+z^2=1' '(x-1)^2+y^2+z^2=1'");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("one_conic"), std::string::npos) << r.out;
  auto j = run("classify --json --mode exact 'x^2+y^2+z^2=1' '(x-1)^2+y^2+z^2=1'");
  ASSERT_EQ(j.code, 0);
  Json doc = surfcert::core::io::parse_json(j.out, "stdout");
  EXPECT_EQ(doc.find("status")->text(), "certified");
  EXPECT_EQ(doc.find("result")->find("tu_case")->text(), "17");
  EXPECT_EQ(doc.find("result")->find("morphology")->text(), "one_conic");
  // The normalized matrix is echoed: (x-1)^2 + y^2 + z^2 - 1 has A[0][3] = -1, A[3][3] = 0.
  const Json& b = *doc.find("result")->find("matrices")->find("b");
  EXPECT_EQ(b.items()[0].items()[3].text(), "-1");
  EXPECT_EQ(b.items()[3].items()[3].text(), "0");
}

TEST(Cli, BadEquationsExitTwoWithLocation) {
  struct Bad {
    const char* a;
    const char* needle;
  } cases[] = {
      {"x^2 + * y", "<argument 1>:1:"},  // malformed expression
      {"x^3 + y^2 - 1", "degree"},       // degree > 2
      {"x^2 + w^2 - 1", "'w'"},          // unknown variable
      {"x^2 / (y - y)", "<argument 1>"}, // division by zero
      {"", "<argument 1>"},              // empty
  };
  for (const auto& c : cases) {
    auto r = run(std::string("classify ") + quote(c.a) + " 'x^2+y^2+z^2=1'");
    EXPECT_EQ(r.code, 2) << c.a;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.a << " -> " << r.err;
    EXPECT_TRUE(r.out.empty()) << c.a;
  }
}

TEST(Cli, BadScenesExitTwoAndWriteNothing) {
  struct Bad {
    const char* scene;
    const char* needle;
  } cases[] = {
      {R"({"surfaces": {"A": {"matrix": [[1,0,0,0],[0,1,"1/0",0],[0,0,1,0],[0,0,0,-1]]}, "B": "x^2+y^2+z^2=4"}, "queries": [{"op": "classify", "a": "A", "b": "B"}]})",
       "$.surfaces.A.matrix[1][2]"},
      {R"({"surfaces": {"A": {"type": "sphere", "radius": 0}, "B": "x^2=1"}, "queries": []})",
       "$.surfaces.A.radius"},
      {R"({"surfaces": {"A": {"type": "ellipsoid", "radii": [1, -2, 1]}, "B": "x^2=1"}, "queries": []})",
       "$.surfaces.A.radii[1]"},
      {R"({"surfaces": {"A": {"type": "sphere", "radius": 1e999}, "B": "x^2=1"}, "queries": []})",
       "finite"},
      {R"({"surfaces": {"A": {"type": "sphere", "radius": 1, "colour": "red"}, "B": "x^2=1"}, "queries": []})",
       "unknown field \"colour\""},
      {R"({"surfaces": {"A": "x^2+y^2=1", "B": "x^2=1"}, "queries": [{"op": "classify", "a": "A", "b": "C"}]})",
       "$.queries[0].b"},
      {R"({"surfaces": {"A": "x^2+y^2=1", "B": "x^2=1"}, "queries": [{"op": "volume", "a": "A", "b": "B"}]})",
       "$.queries[0].op"},
      {"{\"surfaces\": {\"A\": \"x^2+y^2=1\",\n \"B\": \"x^2 + + = 1\"}, \"queries\": []}", ":2:"},
      {"{\"surfaces\": {}, \n\n  \"queries\": [,]}", ":3:"},
      {R"({"surfaces": {"A": {"type": "ellipsoid", "radii": [1,1,1], "rotation": {"matrix": [[1,0,0],[0,1,0],[0,1,0]]}}, "B": "x^2=1"}, "queries": []})",
       "invertible"},
  };
  for (const auto& c : cases) {
    std::string scene = tmp_path("scene.json"), report = tmp_path("report.json");
    std::ofstream(scene) << c.scene;
    std::remove(report.c_str());
    auto r = run("run " + scene + " -o " + report);
    EXPECT_EQ(r.code, 2) << c.scene;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.scene << " -> " << r.err;
    EXPECT_NE(r.err.find(scene), std::string::npos) << "message names the file: " << r.err;
    EXPECT_FALSE(exists(report)) << "a report was written for a bad scene";
    EXPECT_FALSE(exists(report + ".tmp"));
    std::remove(scene.c_str());
  }
}

TEST(Cli, RunWritesReportAtomically) {
  std::string scene = tmp_path("good.json"), report = tmp_path("good_report.json");
  std::ofstream(scene) << R"({"surfaces": {"S": {"type": "sphere", "center": [0,0,0], "radius": 1},
    "E": {"type": "ellipsoid", "center": ["1/2", 0, 0], "radii": [2, 1, 1], "rotation": {"quaternion": [1, 0, 0, 1]}}},
    "queries": [{"id": "q1", "op": "classify", "a": "S", "b": "E", "mode": "exact"}]})";
  auto r = run("run " + scene + " -o " + report);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(report);
  std::stringstream s;
  s << f.rdbuf();
  Json doc = surfcert::core::io::parse_json(s.str(), report);
  const Json& q = doc.find("results")->items()[0];
  EXPECT_EQ(q.find("id")->text(), "q1");
  EXPECT_EQ(q.find("status")->text(), "certified");
  // quaternion (1,0,0,1) is a quarter turn about z: the long axis 2 lies along y.
  const Json& b = *q.find("result")->find("matrices")->find("b");
  EXPECT_EQ(b.items()[0].items()[0].text(), "1");
  EXPECT_EQ(b.items()[1].items()[1].text(), "1/4");
  std::remove(scene.c_str());
  std::remove(report.c_str());
}

// A slow line (two tori 1e-20 apart, stopped by its budget after >= 300 ms) ahead of fast ones:
// in input order it comes first; with --unordered a fast answer overtakes it.
TEST(Cli, BatchUnorderedStreamsAsCompleted) {
  std::string in =
      R"({"id":"slow","op":"distance","a":{"type":"torus","center":[0,0,0],"axis":[0,0,1],)"
      R"("major_radius":3,"minor_radius":1},"b":{"type":"torus","center":)"
      R"(["799999999999999999999/100000000000000000000",0,0],"axis":[0,0,1],"major_radius":3,)"
      R"("minor_radius":1},"budget_ms":300})"
      "\n";
  for (int i = 0; i < 4; ++i)
    in += "{\"id\": " + std::to_string(i) +
          R"(, "op": "classify", "a": "x^2+y^2+z^2=1", "b": "(x-3)^2+y^2+z^2=1"})" + "\n";
  auto first_id = [](const std::string& out) {
    const Json o = surfcert::core::io::parse_json(out.substr(0, out.find('\n')), "out");
    return surfcert::core::io::dump(*o.find("id"));
  };
  auto ordered = run("batch --threads 2", in);
  auto unordered = run("batch --threads 2 --unordered", in);
  EXPECT_EQ(first_id(ordered.out), "\"slow\"");
  EXPECT_NE(first_id(unordered.out), "\"slow\"");
  EXPECT_EQ(std::count(unordered.out.begin(), unordered.out.end(), '\n'), 5);
  EXPECT_NE(unordered.out.find("\"reason\":\"budget\""), std::string::npos);
}

TEST(Cli, BatchKeepsOrderAndSurvivesBadLines) {
  std::string in;
  std::vector<std::string> ids;
  const char* pairs[][2] = {{"x^2+y^2+z^2=1", "(x-3)^2+y^2+z^2=1"},
                            {"x^2+y^2+z^2=1", "(x-2)^2+y^2+z^2=1"},
                            {"x^2+y^2+z^2=1", "(x-1)^2+y^2+z^2=1"}};
  for (int i = 0; i < 60; ++i) {
    if (i % 7 == 3) {
      in += "{\"id\": " + std::to_string(i) +
            ", \"op\": \"classify\", \"a\": \"x^2+\", \"b\": \"y=1\"}\n";
    } else if (i % 11 == 5) {
      in += "this is not json\n";
    } else {
      in += "{\"id\": " + std::to_string(i) + ", \"op\": \"classify\", \"a\": \"" +
            pairs[i % 3][0] + "\", \"b\": {\"equation\": \"" + pairs[i % 3][1] + "\"}}\n";
    }
  }
  auto one = run("batch --threads 1", in);
  auto two = run("batch --threads 2 --mode filtered", in);
  ASSERT_EQ(one.code, 2); // every line answered; bad input lines make the exit code 2
  ASSERT_EQ(two.code, 2);
  EXPECT_EQ(untimed(one.out), untimed(two.out));
  std::istringstream lines(one.out);
  std::string l;
  int n = 0;
  while (std::getline(lines, l)) {
    Json o = surfcert::core::io::parse_json(l, "out");
    const std::string status = o.find("status")->text();
    if (n % 11 == 5 && n % 7 != 3) {
      EXPECT_EQ(status, "error");
      EXPECT_EQ(o.find("error")->find("line")->text(), std::to_string(n + 1)); // stdin line number
    } else if (n % 7 == 3) {
      EXPECT_EQ(status, "error");
      EXPECT_EQ(o.find("id")->text(), std::to_string(n));
      EXPECT_EQ(o.find("error")->find("json_path")->text(), "$.a");
    } else {
      EXPECT_EQ(status, "certified");
      EXPECT_EQ(o.find("id")->text(), std::to_string(n));
      int expect = n % 3 == 0 ? 16 : (n % 3 == 1 ? 25 : 17);
      EXPECT_EQ(o.find("result")->find("tu_case")->text(), std::to_string(expect));
      EXPECT_TRUE(o.find("result")->find("segre") && o.find("result")->find("root_pattern"));
    }
    ++n;
  }
  EXPECT_EQ(n, 60);
}

TEST(Cli, DefaultSceneRuns) {
  auto r = run(std::string("run ") + SURFCERT_DATA_DIR + "/scenes/default.json --json");
  ASSERT_EQ(r.code, 0) << r.err;
  Json doc = surfcert::core::io::parse_json(r.out, "stdout");
  EXPECT_GE(doc.find("results")->size(), 5u);
  for (const auto& q : doc.find("results")->items())
    EXPECT_EQ(q.find("status")->text(), "certified");
}

TEST(Cli, IntersectWritesPictureAndPolylines) {
  std::string svg = tmp_path("curve.svg"), obj = tmp_path("curve.obj"), ply = tmp_path("curve.ply");
  auto r = run("intersect 'x^2+y^2/4+z^2=1' 'x^2-2x+9y^2+9/4 z^2=8' --svg " + svg + " --export " +
               obj + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  Json doc = surfcert::core::io::parse_json(r.out, "stdout");
  EXPECT_EQ(doc.find("status")->text(), "certified");
  const Json& branches = *doc.find("result")->find("branches");
  ASSERT_EQ(branches.size(), 2u); // seed 002 Example 4.2: two loops
  size_t points = 0;
  for (const auto& b : branches.items()) {
    EXPECT_EQ(b.find("kind")->text(), "loop");
    points += b.find("points")->size();
  }
  // OBJ: one "v" line per point and one "l" element per branch.
  std::ifstream o(obj);
  std::string line;
  size_t v = 0, l = 0;
  while (std::getline(o, line)) {
    v += line.rfind("v ", 0) == 0;
    l += line.rfind("l ", 0) == 0;
  }
  EXPECT_EQ(v, points);
  EXPECT_EQ(l, 2u);
  std::ifstream sv(svg);
  std::stringstream ss;
  ss << sv.rdbuf();
  EXPECT_NE(ss.str().find("<svg"), std::string::npos);
  auto bad = run("intersect 'x^2+y^2+z^2=1' 'x^2=1/4' --export " + ply + ".stl");
  EXPECT_EQ(bad.code, 2);
  EXPECT_FALSE(exists(ply + ".stl"));
  for (const auto& f : {svg, obj})
    std::remove(f.c_str());
}

TEST(Cli, JsonDoublesAreReadAsExactDyadicsAndStringsAsDecimals) {
  // 0.1 as a JSON number is the binary double 3602879701896397 / 2^55; "0.1" is 1/10.
  std::string line =
      R"({"id": 1, "op": "classify", "a": {"matrix": [[0.1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]]},)"
      R"( "b": {"matrix": [["0.1",0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,"-1/4"]]}})";
  auto r = run("batch", line + "\n");
  ASSERT_EQ(r.code, 0) << r.err;
  Json o = surfcert::core::io::parse_json(r.out, "out");
  const Json& m = *o.find("result")->find("matrices");
  EXPECT_EQ(m.find("a")->items()[0].items()[0].text(), "3602879701896397/36028797018963968");
  EXPECT_EQ(m.find("b")->items()[0].items()[0].text(), "1/10");
  EXPECT_EQ(m.find("b")->items()[3].items()[3].text(), "-1/4");
}

// classify / intersect take JSON surfaces on the command line like distance; a non-symmetric
// matrix is read as its symmetric part and the answer says so ("readings").
TEST(Cli, ClassifyTakesJsonSurfacesAndReportsReadings) {
  const std::string a = R"('{"matrix": [[1,1,0,0],[-1,1,0,0],[0,0,1,0],[0,0,0,-1]]}')";
  const std::string b = R"('{"type": "sphere", "center": [3, 0, 0], "radius": 1}')";
  auto r = run("classify --json " + a + " " + b);
  ASSERT_EQ(r.code, 0) << r.err;
  Json o = surfcert::core::io::parse_json(r.out, "out");
  ASSERT_NE(o.find("readings"), nullptr) << r.out;
  EXPECT_EQ(o.find("readings")->items()[0].find("path")->text(), "$.matrix");
  EXPECT_EQ(o.find("status")->text(), "certified");
  auto t = run("intersect " + a + " " + b);
  EXPECT_NE(t.out.find("reading $.matrix"), std::string::npos) << t.out;
}

TEST(Cli, OptionsTakeTheirValueEitherWay) {
  const std::string a = "'x^2+y^2+z^2=1'", b = "'(x-3)^2+y^2+z^2=1'";
  auto spaced = run("distance --digits 20 --mode exact --json " + a + " " + b);
  auto joined = run("distance --digits=20 --mode=exact --json " + a + " " + b);
  ASSERT_EQ(spaced.code, 0) << spaced.err;
  ASSERT_EQ(joined.code, 0) << joined.err;
  EXPECT_EQ(untimed(spaced.out), untimed(joined.out));
  std::string in = "{\"id\": 1, \"op\": \"classify\", \"a\": " + std::string("\"x^2+y^2+z^2=1\"") +
                   ", \"b\": \"(x-1)^2+y^2+z^2=1\"}\n";
  auto t1 = run("batch --threads 2 --mode exact", in);
  auto t2 = run("batch --threads=2 --mode=exact", in);
  ASSERT_EQ(t1.code, 0) << t1.err;
  EXPECT_EQ(untimed(t1.out), untimed(t2.out));
  auto tol = run("intersect --tol=1/1000 'x^2+y^2+z^2=1' '(x-1)^2+y^2+z^2=1' --json");
  EXPECT_EQ(tol.code, 0) << tol.err;
  // An equation may start with '-' (not an option).
  auto neg = run("classify '-x^2-y^2-z^2=-1' '(x-1)^2+y^2+z^2=1'");
  EXPECT_EQ(neg.code, 0) << neg.err;
  EXPECT_NE(neg.out.find("one_conic"), std::string::npos) << neg.out;
}

TEST(Cli, BadOptionsExitTwoNamingTheOption) {
  const std::string eqs = " 'x^2+y^2+z^2=1' '(x-3)^2+y^2+z^2=1'";
  struct Bad {
    std::string args, needle;
  } cases[] = {
      {"distance --digits 2000" + eqs, "--digits"},
      {"distance --digits=0" + eqs, "--digits"},
      {"distance --digits=many" + eqs, "--digits"},
      {"classify --mode=fast" + eqs, "--mode"},
      {"classify --mode" + eqs, "--mode"},
      {"intersect --tol 5" + eqs, "--tol"},
      {"classify --bogus" + eqs, "--bogus"},
      {"batch --threads 0", "--threads"},
      {"batch --threads=257", "--threads"},
      {"batch --frobnicate", "--frobnicate"},
      {"frobnicate", "frobnicate"},
      {"run", "scene"},
  };
  for (const auto& c : cases) {
    auto r = run(c.args, "");
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << " -> " << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args << " -> " << r.out;
  }
}

TEST(Cli, VersionAndHelp) {
  auto v = run("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_EQ(v.out.rfind("surfcert ", 0), 0u) << v.out;
  EXPECT_EQ(std::count(v.out.begin(), v.out.end(), '\n'), 1) << v.out;
  auto h = run("--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("--opt=value"), std::string::npos);
  EXPECT_NE(h.out.find(v.out.substr(0, v.out.size() - 1)), std::string::npos)
      << "one version string: " << v.out << " / " << h.out;
  auto sub = run("distance --help");
  EXPECT_EQ(sub.code, 0);
  EXPECT_NE(sub.out.find("--digits"), std::string::npos) << sub.out;
  auto none = run("");
  EXPECT_EQ(none.code, 2);
}

// --box corners are read exactly and rounded once to doubles: a corner that moves is named on
// stderr (1-2^-100 becomes 1, which puts the face on Steinmetz's node); exact doubles are not.
TEST(Cli, BoxCornersThatRoundAreNamed) {
  const std::string pair = quote("x^2+y^2=1") + " " + quote("x^2+z^2=1");
  auto r = run("intersect " + pair + " --box -2,-2,-2,1/2,2,2");
  EXPECT_TRUE(r.code == 0 || r.code == 3) << r.code << " " << r.err; // certified or undecided
  EXPECT_EQ(r.err.find("--box"), std::string::npos) << r.err;
  r = run("intersect " + pair +
          " --box -2,-2,-2,1267650600228229401496703205375/1267650600228229401496703205376,2,2");
  EXPECT_NE(r.err.find("is used as the double 1\n"), std::string::npos) << r.err;
  r = run("intersect " + pair + " --box -0.1,-2,-2,2,2,2");
  EXPECT_NE(r.err.find("--box -0.1 is used as the double -0.10000000000000001"), std::string::npos)
      << r.err;
}

// --box corners are exact numbers of the equation grammar (docs/input.md), as a surface's are:
// 1-1/2^64 is read and rounds onto 1 (the same box as 1). A bad corner is an input error
// located in the --box value ("--box:1:COLUMN", the offending character), never a message
// about min < max.
TEST(Cli, BoxCornersAreExactNumbersAndBadOnesAreLocated) {
  const std::string pair = quote("x^2+y^2=1") + " " + quote("x^2+z^2=1");
  for (const char* box : {"-2,-2,-2,1-1/2^64,2,2", "-2,-2,-2,(1+1/3)/2,2,2",
                          "-2,-2,-2,1+1/2^50/2^50,2,2", "-2, -2, -2, 3/4, 2, 2"}) {
    auto r = run("intersect " + pair + " --box " + quote(box));
    EXPECT_TRUE(r.code == 0 || r.code == 3) << box << ": " << r.code << " " << r.err;
  }
  auto rounded = run("intersect --json " + pair + " --box " + quote("-2,-2,-2,1-1/2^64,2,2"));
  auto exact = run("intersect --json " + pair + " --box -2,-2,-2,1,2,2");
  EXPECT_EQ(rounded.code, exact.code);
  EXPECT_EQ(rounded.out, exact.out);
  struct Bad {
    const char* box;
    const char* at;
  } bad[] = {
      {"-2,-2,-2,1-2^-100,2,2", "--box:1:14"}, // the exponent's '-' (exponents are 0..64)
      {"-2,-2,-2,x,2,2", "--box:1:10"},        // not a number
      {"-2,-2,-2,,2,2", "--box:1:10"},         // empty corner
      {"-2,-2,-2,1e400,2,2", "--box:1:10"},    // beyond the double range
      {"-2,-2,-2,2,2,-3", "--box:1:14"},       // Z1 below Z0: located at Z1
      {"-2,1,-2,2,1+1/2^64,2", "--box:1:11"},  // Y1 above Y0, but rounds onto it
      {"-2,-2,-2,1,2", "--box:1:1"},           // five corners
  };
  for (const auto& b : bad) {
    auto r = run("intersect " + pair + " --box " + quote(b.box));
    EXPECT_EQ(r.code, 2) << b.box;
    EXPECT_NE(r.err.find(std::string("error: ") + b.at + ":"), std::string::npos)
        << b.box << " -> " << r.err;
    EXPECT_TRUE(r.out.empty()) << b.box;
  }
}

// classify and intersect need two quadrics: a batch line with another surface is an input
// error at that surface's path whose "found" tells what it is, the same for both ops, and
// different for different kinds (and degrees) of surface.
TEST(Cli, BatchNonQuadricErrorsSayWhatWasFound) {
  const std::vector<std::string> others = {
      "\"x^3+y^2=1\"", "\"x^4+y^4+z^4=1\"",
      R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})",
      R"({"type":"capsule","from":[0,0,0],"to":[1,0,0],"radius":"1/2"})",
      R"J({"type":"parametric","x":"2u","y":"4v","z":"-6(u^2+v^2)","w":"1+u^2+v^2"})J"};
  std::string in;
  for (const auto& s : others)
    for (const char* op : {"classify", "intersect"}) {
      in += std::string("{\"op\":\"") + op + "\",\"a\":" + s + ",\"b\":\"x^2+y^2+z^2=1\"}\n";
      in += std::string("{\"op\":\"") + op + "\",\"a\":\"x^2+y^2+z^2=1\",\"b\":" + s + "}\n";
    }
  auto r = run("batch", in);
  ASSERT_EQ(r.code, 2) << r.err;
  std::istringstream lines(r.out);
  std::vector<std::string> found;
  std::string l;
  for (int n = 0; std::getline(lines, l); ++n) {
    Json o = surfcert::core::io::parse_json(l, "out");
    ASSERT_EQ(o.find("status")->text(), "error") << l;
    const Json& e = *o.find("error");
    EXPECT_EQ(e.find("kind")->text(), "input");
    EXPECT_EQ(e.find("json_path")->text(), n % 2 == 0 ? "$.a" : "$.b") << l;
    EXPECT_EQ(e.find("line")->text(), std::to_string(n + 1));
    found.push_back(e.find("found")->text());
  }
  ASSERT_EQ(found.size(), 4 * others.size());
  for (size_t i = 0; i < others.size(); ++i)
    for (size_t k = 1; k < 4; ++k)
      EXPECT_EQ(found[4 * i + k], found[4 * i]) << others[i];
  for (size_t i = 0; i < others.size(); ++i)
    for (size_t j = i + 1; j < others.size(); ++j)
      EXPECT_NE(found[4 * i], found[4 * j]) << others[i] << " / " << others[j];
}

// Every input error of a batch line has a json_path: "$" for a line that is not JSON (or not an
// object), with its line number.
TEST(Cli, BatchErrorsAlwaysHaveAJsonPath) {
  auto r = run("batch", "this is not json\n[1, 2]\n{\"id\": 1, \"op\": \"classify\"\n");
  ASSERT_EQ(r.code, 2) << r.err;
  std::istringstream lines(r.out);
  std::string l;
  int n = 0;
  for (; std::getline(lines, l); ++n) {
    Json o = surfcert::core::io::parse_json(l, "out");
    EXPECT_EQ(o.find("status")->text(), "error") << l;
    const Json* path = o.find("error")->find("json_path");
    ASSERT_NE(path, nullptr) << l;
    EXPECT_EQ(path->text(), "$") << l;
    EXPECT_EQ(o.find("error")->find("line")->text(), std::to_string(n + 1)) << l;
  }
  EXPECT_EQ(n, 3);
}

// The --case line of the usage lists every value generate accepts.
TEST(Cli, HelpListsEveryGenerateCase) {
  auto h = run("--help");
  ASSERT_EQ(h.code, 0);
  const size_t at = h.out.find("--case ");
  ASSERT_NE(at, std::string::npos) << h.out;
  const std::string line = h.out.substr(at, h.out.find('\n', at) - at);
  // "[--case N|all|...|distance]": the values between "--case " and "]", split at '|'.
  const std::string values = line.substr(7, line.find(']') - 7);
  std::vector<std::string> listed;
  std::istringstream vs(values);
  for (std::string v; std::getline(vs, v, '|');)
    listed.push_back(v);
  for (const char* c :
       {"N", "all", "degenerate_pencil", "coincident", "ellipsoid", "natural", "distance"}) {
    EXPECT_NE(std::find(listed.begin(), listed.end(), c), listed.end())
        << c << " missing from: " << line;
    if (std::string(c) == "N") continue;
    auto g = run(std::string("generate --count 1 --case ") + c);
    EXPECT_TRUE(g.code == 0 || g.code == 3) << c << ": " << g.err;
  }
  EXPECT_EQ(listed.size(), 7u) << line;
}

// Every distance answer that is not certified says "minimizers": "undecided" (with proof
// "unproven"), also one stopped by its budget before any route answered.
TEST(Cli, UndecidedDistanceAnswersSayMinimizersUndecided) {
  const std::string torus =
      R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})";
  const std::string near =
      R"({"type":"torus","center":["7.999999999999999999",0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})";
  std::string in;
  for (const char* extra : {"", ",\"detail\":\"value\"", ",\"solid\":true"})
    in += "{\"op\":\"distance\",\"a\":" + torus + ",\"b\":" + near + ",\"budget_ms\":1" + extra +
          "}\n";
  auto r = run("batch --threads 1", in);
  ASSERT_EQ(r.code, 3) << r.err << r.out;
  std::istringstream lines(r.out);
  std::string l;
  int n = 0;
  for (; std::getline(lines, l); ++n) {
    Json o = surfcert::core::io::parse_json(l, "out");
    ASSERT_EQ(o.find("status")->text(), "undecided") << l;
    const Json* res = o.find("result");
    ASSERT_NE(res, nullptr) << l;
    const Json* m = res->find("minimizers");
    ASSERT_NE(m, nullptr) << l;
    EXPECT_EQ(m->text(), "undecided") << l;
    ASSERT_NE(res->find("minimizers_proof"), nullptr) << l;
    EXPECT_EQ(res->find("minimizers_proof")->text(), "unproven") << l;
  }
  EXPECT_EQ(n, 3);
}

// Exact mode gives a root in closed form from its own irreducible factor over Q: f = (4l - 9)
// (l - 36)(l^2 - 9l + 9) is square-free, and its roots 9/4 and 36 are rationals, 9/2 -+
// sqrt(45)/2 quadratic numbers (docs/json-contract.md, "real_roots[].exact").
TEST(Cli, ExactModeRootsAreInClosedForm) {
  auto r = run("classify --json --mode exact " + quote("x^2 + y^2/4 + z^2 = 1") + " " +
               quote("x^2 - 2x + 9y^2 + 9/4 z^2 = 8"));
  ASSERT_EQ(r.code, 0) << r.err;
  Json doc = surfcert::core::io::parse_json(r.out, "stdout");
  const auto& roots = doc.find("result")->find("real_roots")->items();
  ASSERT_EQ(roots.size(), 4u) << r.out;
  EXPECT_EQ(roots[1].find("exact")->text(), "9/4");
  EXPECT_EQ(roots[3].find("exact")->text(), "36");
  for (size_t i : {0, 2}) {
    const std::string ex = roots[i].find("exact")->text();
    EXPECT_NE(ex.find("sqrt("), std::string::npos) << ex;
    EXPECT_EQ(ex.find("root of"), std::string::npos) << ex;
  }
}
