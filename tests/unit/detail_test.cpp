// Detail levels (certify/detail.hpp) of classify, intersect and distance answers:
// - the contract: "detail": "full" is byte for byte the answer without a detail, for every
//   pencil of data/fixtures, every op and mode;
// - each field is present at its level and absent below it, and a lean answer's fields equal
//   the full answer's (topology and certificate against full; distance value against full);
// - the ellipsoid relation at topology level, computed without the exact report data, against
//   an independent geometric truth: random double ellipsoid pairs built separated (centres
//   farther apart than the radii allow), nested (one inside a ball inside the other, the
//   smaller volume inside) and overlapping (a common centre, each poking out of the other), in
//   the three modes;
// - bad detail values are input errors at their JSON path (batch line, scene query) and bad
//   --detail values are command-line errors;
// - the distance envelope's text (append_distance_envelope, written directly) equals the
//   document the envelope was built as before (a reference builder here: a Json tree, doubles
//   by printf "%.17g", dump()), for results with every optional field on and off, both
//   levels, awkward notes and doubles (subnormal, -0, 1e300, non-finite pairs left out).
#include "support/canonical.hpp"
#include "support/fixtures.hpp"

#include "surfcert/app/scene.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace surfcert;
using certify::Mode;
using core::io::Json;

namespace {

const Mode kModes[] = {Mode::Exact, Mode::Filtered, Mode::Float};

// The fields of a classification "result" by the level that introduces them.
const std::set<std::string> kTopology = {
    "pencil", "tu_case",      "morphology", "description",        "tu_label_reconstructed",
    "segre",  "root_pattern", "components", "ellipsoid_relation", "containment"};
const std::set<std::string> kCertificate = {"matrices",
                                            "pencil_basis",
                                            "characteristic_polynomial",
                                            "characteristic_polynomial_coeffs",
                                            "characteristic_polynomial_coeffs_approx",
                                            "invariants",
                                            "real_roots",
                                            "complex_roots",
                                            "signature_sequence",
                                            "definite_member",
                                            "certificate"};
const std::set<std::string> kFull = {"special_points", "special_points_complete"};
// intersect's own fields (the curve): at every level.
const std::set<std::string> kCurve = {"branches",
                                      "box",
                                      "isolated_points",
                                      "branches_match_topology",
                                      "branch_points_approximate",
                                      "max_residual",
                                      "tolerance",
                                      "affine"};
// distance: the certificate data only a full answer carries.
const std::set<std::string> kDistanceFull = {"critical_candidates", "eliminated_degree", "degrees"};

// A batch answer with its wall time blanked (the only field that differs between runs).
Json answer(const std::string& line, Mode m, certify::Detail def = certify::Detail::Full) {
  Json j = app::process_batch_line(line, 7, m, nullptr, 0, def);
  j.set("time_ms", Json::number_text("0"));
  return j;
}

std::string with_detail(const std::string& line, const std::string& d) {
  return "{\"detail\":\"" + d + "\"," + line.substr(1);
}

std::set<std::string> keys(const Json& o) {
  std::set<std::string> k;
  for (const auto& [name, v] : o.members())
    k.insert(name);
  return k;
}

std::set<std::string> operator+(std::set<std::string> a, const std::set<std::string>& b) {
  a.insert(b.begin(), b.end());
  return a;
}

std::set<std::string> only(const std::set<std::string>& a, const std::set<std::string>& allowed) {
  std::set<std::string> r;
  for (const auto& k : a)
    if (allowed.count(k)) r.insert(k);
  return r;
}

// Every field of the lean answer `lean` equals the full one's, and the lean one has exactly
// the fields of `full` that `allowed` admits (besides the envelope's "detail").
void expect_lean_of(const Json& lean, const Json& full, const std::set<std::string>& allowed,
                    const std::string& level, const std::string& what) {
  ASSERT_NE(lean.find("detail"), nullptr) << what;
  EXPECT_EQ(lean.find("detail")->text(), level) << what;
  EXPECT_EQ(full.find("detail"), nullptr) << what;
  for (const auto& [k, v] : lean.members()) {
    if (k == "detail" || k == "result") continue;
    ASSERT_NE(full.find(k), nullptr) << what << " envelope field " << k;
    EXPECT_EQ(core::io::dump(v), core::io::dump(*full.find(k))) << what << " " << k;
  }
  EXPECT_EQ(keys(lean).size(), keys(full).size() + 1) << what; // + "detail"
  const Json& lr = *lean.find("result");
  const Json& fr = *full.find("result");
  EXPECT_EQ(keys(lr), only(keys(fr), allowed)) << what << " at " << level;
  for (const auto& [k, v] : lr.members())
    EXPECT_EQ(core::io::dump(v), core::io::dump(*fr.find(k))) << what << " " << k;
}

struct FixtureLine {
  std::string id, a, b; // a, b: JSON surfaces
};

// Every pencil of data/fixtures as two JSON surfaces (matrices or equations).
std::vector<FixtureLine> fixture_pairs() {
  std::vector<FixtureLine> out;
  auto matrix = [](const Json& m) { return "{\"matrix\":" + core::io::dump(m) + "}"; };
  auto equation = [](const Json& e) {
    // "x^2/1/4" in the readable fixtures means x^2/(1/4): each denominator is one rational.
    std::string s = std::regex_replace(e.text(), std::regex("/([0-9]+)/([0-9]+)"), "/($1/$2)");
    return core::io::dump(Json::string(s));
  };
  for (const auto& [file, ka, kb] : {std::make_tuple("canonical_examples", "A", "B"),
                                     std::make_tuple("ellipsoid_fixtures", "E1", "E2"),
                                     std::make_tuple("nice_axis_aligned_fixtures", "E1", "E2")}) {
    Json doc = fixtures::load_json(std::string("fixtures/") + file + ".json");
    for (const auto& [key, e] : doc.members()) {
      const Json& a = *e.find(ka);
      const Json& b = *e.find(kb);
      out.push_back({std::string(file) + "/" + key, a.is_string() ? equation(a) : matrix(a),
                     b.is_string() ? equation(b) : matrix(b)});
    }
  }
  return out;
}

std::string line_of(const std::string& op, const FixtureLine& f) {
  return R"({"id":")" + f.id + R"(","op":")" + op + R"(","a":)" + f.a + R"(,"b":)" + f.b + "}";
}

} // namespace

TEST(Detail, FullIsTheContractAndLevelsNestForEveryFixture) {
  const auto pairs = fixture_pairs();
  ASSERT_GE(pairs.size(), 70u);
  for (const auto& f : pairs)
    for (const std::string op : {"classify", "intersect"})
      for (Mode m : kModes) {
        const std::string line = line_of(op, f);
        const std::string what = op + " " + f.id + " " + certify::to_string(m);
        const Json none = answer(line, m);
        const Json full = answer(with_detail(line, "full"), m);
        // The contract: full is the answer without a detail, byte for byte.
        EXPECT_EQ(core::io::dump(full), core::io::dump(none)) << what;
        const Json& fr = *full.find("result");
        const auto extra = op == "intersect" ? kCurve : std::set<std::string>{};
        // Every field of a full answer belongs to a level.
        for (const auto& k : keys(fr))
          EXPECT_TRUE((kTopology + kCertificate + kFull + extra).count(k)) << what << " " << k;
        const Json topo = answer(with_detail(line, "topology"), m);
        const Json cert = answer(with_detail(line, "certificate"), m);
        expect_lean_of(topo, full, kTopology + extra, "topology", what);
        expect_lean_of(cert, full, kTopology + kCertificate + extra, "certificate", what);
        // Present at its level: a regular pencil's full answer has the certificate data (and
        // the special points when certified exactly or by the filter).
        if (fr.find("pencil")->text() == "regular") {
          for (const char* k : {"matrices", "real_roots", "signature_sequence", "certificate"})
            EXPECT_NE(cert.find("result")->find(k), nullptr) << what << " " << k;
          if (m != Mode::Float && full.find("status")->text() != "error" && op == "classify") {
            EXPECT_NE(fr.find("special_points"), nullptr) << what;
          }
        }
      }
}

TEST(Detail, DistanceValueAndFull) {
  // The ellipsoid fixtures (every relation two ellipsoids can have) and a few spheres.
  std::vector<FixtureLine> pairs;
  for (const auto& f : fixture_pairs())
    if (f.id.rfind("canonical_examples/", 0) != 0) pairs.push_back(f);
  pairs.push_back({"spheres", "\"x^2+y^2+z^2=1\"", "\"(x-3)^2+y^2+z^2=1\""});
  int with_candidates = 0;
  for (const auto& f : pairs)
    for (Mode m : {Mode::Filtered, Mode::Float}) {
      const std::string line = line_of("distance", f);
      const std::string what = "distance " + f.id + " " + certify::to_string(m);
      const Json none = answer(line, m);
      const Json full = answer(with_detail(line, "full"), m);
      EXPECT_EQ(core::io::dump(full), core::io::dump(none)) << what;
      const Json value = answer(with_detail(line, "value"), m);
      std::set<std::string> all = keys(*full.find("result"));
      std::set<std::string> lean;
      for (const auto& k : all)
        if (!kDistanceFull.count(k)) lean.insert(k);
      expect_lean_of(value, full, lean, "value", what);
      for (const auto& k : kDistanceFull)
        EXPECT_EQ(value.find("result")->find(k), nullptr) << what << " " << k;
      if (full.find("result")->find("critical_candidates")) ++with_candidates;
    }
  EXPECT_EQ(with_candidates, static_cast<int>(2 * pairs.size())); // present at full
}

namespace {

// A random double ellipsoid (shape JSON) with the given centre and radii, random rotation.
std::string ellipsoid(std::mt19937_64& g, const std::array<double, 3>& c,
                      const std::array<double, 3>& r, const std::array<double, 4>* q = nullptr) {
  std::normal_distribution<double> n(0, 1);
  std::array<double, 4> quat;
  if (q) {
    quat = *q;
  } else {
    double s = 0;
    do {
      for (auto& x : quat)
        x = n(g);
      s = std::sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]);
    } while (s < 1e-3);
    for (auto& x : quat)
      x /= s;
  }
  auto num = [](double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return std::string(buf);
  };
  return R"({"type":"ellipsoid","center":[)" + num(c[0]) + "," + num(c[1]) + "," + num(c[2]) +
         R"(],"radii":[)" + num(r[0]) + "," + num(r[1]) + "," + num(r[2]) +
         R"(],"rotation":{"quaternion":[)" + num(quat[0]) + "," + num(quat[1]) + "," +
         num(quat[2]) + "," + num(quat[3]) + "]}}";
}

struct RelationCase {
  std::string a, b, relation, containment;
};

// Pairs whose relation geometry decides: separated (centre distance > the largest radii's
// sum), nested (the small one inside a ball inside the big one; the small one is inside),
// overlapping (a common centre, each with a long axis the other's short axes cannot hold).
std::vector<RelationCase> relation_cases(std::uint64_t seed, int per_kind) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5), big(0.5, 1.0), small(0.02, 0.1);
  std::normal_distribution<double> n(0, 1);
  std::vector<RelationCase> out;
  for (int i = 0; i < per_kind; ++i) {
    // separated
    std::array<double, 3> ca{u(g), u(g), u(g)}, ra{big(g), big(g), big(g)},
        rb{big(g), big(g), big(g)};
    std::array<double, 3> dir{n(g), n(g), n(g)};
    double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    const double gap = 2.0 + 0.5 * std::fabs(u(g)) + 0.01; // > 1 + 1 >= max ra + max rb
    std::array<double, 3> cb{ca[0] + gap * dir[0] / len, ca[1] + gap * dir[1] / len,
                             ca[2] + gap * dir[2] / len};
    out.push_back({ellipsoid(g, ca, ra), ellipsoid(g, cb, rb), "separated", ""});
    // nested: b's centre within 0.2 of a's, its radii <= 0.1, a's ball of radius 0.5 holds it
    std::array<double, 3> cn{ca[0] + 0.1 * u(g), ca[1] + 0.1 * u(g), ca[2] + 0.1 * u(g)};
    std::array<double, 3> rn{small(g), small(g), small(g)};
    const std::string outer = ellipsoid(g, ca, ra), inner = ellipsoid(g, cn, rn);
    if (i % 2 == 0)
      out.push_back({outer, inner, "nested", "b_inside_a"});
    else
      out.push_back({inner, outer, "nested", "a_inside_b"});
    // overlapping: the same centre and rotation, long axes along different local axes
    std::array<double, 4> q{n(g), n(g), n(g), n(g)};
    double s = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (auto& x : q)
      x /= s;
    std::array<double, 3> rl{big(g), small(g), small(g)}, rm{small(g), big(g), small(g)};
    out.push_back({ellipsoid(g, ca, rl, &q), ellipsoid(g, ca, rm, &q), "overlapping", ""});
  }
  return out;
}

std::string str_or_empty(const Json& r, const char* k) {
  const Json* v = r.find(k);
  return v ? v->text() : std::string();
}

} // namespace

TEST(Detail, TopologyRelationAgainstGeometry) {
  const auto cases = relation_cases(surfcert::testing::test_seed(), 70);
  ASSERT_EQ(cases.size(), 210u);
  for (const auto& c : cases) {
    const std::string line = R"({"op":"classify","a":)" + c.a + R"(,"b":)" + c.b + "}";
    for (Mode m : kModes) {
      const std::string what = line + " " + certify::to_string(m);
      const Json topo = answer(with_detail(line, "topology"), m);
      const Json full = answer(line, m);
      const Json& tr = *topo.find("result");
      EXPECT_EQ(str_or_empty(tr, "ellipsoid_relation"), c.relation) << what;
      EXPECT_EQ(str_or_empty(tr, "containment"), c.containment) << what;
      expect_lean_of(topo, full, kTopology, "topology", what);
    }
  }
}

TEST(Detail, BatchDefaultMapsOntoEachOp) {
  const std::string cl = R"({"op":"classify","a":"x^2+y^2+z^2=1","b":"(x-1)^2+y^2+z^2=1"})";
  const std::string di = R"({"op":"distance","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1"})";
  EXPECT_EQ(answer(cl, Mode::Filtered, certify::Detail::Value).find("detail")->text(), "topology");
  EXPECT_EQ(answer(di, Mode::Filtered, certify::Detail::Topology).find("detail")->text(), "value");
  EXPECT_EQ(answer(di, Mode::Filtered, certify::Detail::Certificate).find("detail")->text(),
            "value");
  // A line's own detail overrides the default.
  EXPECT_EQ(
      answer(with_detail(cl, "full"), Mode::Filtered, certify::Detail::Topology).find("detail"),
      nullptr);
}

// The batch reader hands parse_detail / detail_accepted / detail_for_op views into its line:
// they must read exactly the view's bytes (no NUL after them), never a prefix or a longer run.
TEST(Detail, SpellingsAreReadFromTheViewsBytesOnly) {
  using certify::Detail;
  const std::string buf = "topologyfullvaluecertificateclassifyintersectdistance";
  auto at = [&](std::size_t pos, std::size_t n) { return std::string_view(buf).substr(pos, n); };
  EXPECT_EQ(certify::parse_detail(at(0, 8)), Detail::Topology);
  EXPECT_EQ(certify::parse_detail(at(8, 4)), Detail::Full);
  EXPECT_EQ(certify::parse_detail(at(12, 5)), Detail::Value);
  EXPECT_EQ(certify::parse_detail(at(17, 11)), Detail::Certificate);
  for (auto [pos, n] : {std::pair<std::size_t, std::size_t>{0, 7},
                        {0, 9},
                        {8, 3},
                        {8, 5},
                        {12, 4},
                        {17, 10},
                        {17, 12},
                        {0, 0}})
    EXPECT_EQ(certify::parse_detail(at(pos, n)), std::nullopt) << buf.substr(pos, n);
  const std::string_view classify = at(28, 8), intersect = at(36, 9), distance = at(45, 8);
  EXPECT_TRUE(certify::detail_accepted(classify, Detail::Topology));
  EXPECT_FALSE(certify::detail_accepted(classify, Detail::Value));
  EXPECT_TRUE(certify::detail_accepted(intersect, Detail::Certificate));
  EXPECT_TRUE(certify::detail_accepted(distance, Detail::Value));
  EXPECT_FALSE(certify::detail_accepted(distance, Detail::Topology));
  EXPECT_FALSE(certify::detail_accepted(at(28, 7), Detail::Topology)); // "classif"
  EXPECT_FALSE(certify::detail_accepted(at(45, 7), Detail::Value));    // "distanc"
  EXPECT_EQ(certify::detail_for_op(distance, Detail::Topology), Detail::Value);
  EXPECT_EQ(certify::detail_for_op(at(45, 7), Detail::Value), Detail::Topology);
  EXPECT_EQ(certify::detail_for_op(classify, Detail::Value), Detail::Topology);
  EXPECT_STREQ(certify::detail_spellings(distance), "\"value\" or \"full\"");
}

TEST(Detail, BadValuesAreInputErrorsWithLocation) {
  const std::string cl = R"({"op":"classify","a":"x^2+y^2+z^2=1","b":"(x-1)^2+y^2+z^2=1"})";
  const std::string it = R"({"op":"intersect","a":"x^2+y^2+z^2=1","b":"(x-1)^2+y^2+z^2=1"})";
  const std::string di = R"({"op":"distance","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1"})";
  const std::string ve =
      R"({"op":"verify","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1","claims":[]})";
  for (const auto& [line, d] :
       {std::make_pair(cl, "\"value\""), std::make_pair(it, "\"value\""),
        std::make_pair(cl, "\"Full\""), std::make_pair(cl, "2"), std::make_pair(cl, "null"),
        std::make_pair(di, "\"topology\""), std::make_pair(di, "\"certificate\""),
        std::make_pair(ve, "\"full\"")}) {
    const std::string bad = "{\"detail\":" + std::string(d) + "," + line.substr(1);
    const Json r = app::process_batch_line(bad, 5, Mode::Filtered);
    ASSERT_EQ(r.find("status")->text(), "error") << bad;
    const Json& e = *r.find("error");
    EXPECT_EQ(e.find("kind")->text(), "input") << bad;
    EXPECT_EQ(e.find("json_path")->text(), "$.detail") << bad;
    EXPECT_EQ(e.find("line")->text(), "5") << bad;
    EXPECT_EQ(e.find("column")->text(), "11") << bad; // the value after {"detail":
  }
  // A scene query: the error names the query's path.
  const std::string scene = R"({"surfaces":{"s":"x^2+y^2+z^2=1","t":"(x-3)^2+y^2+z^2=1"},)"
                            R"("queries":[{"op":"classify","a":"s","b":"t","detail":"full"},)"
                            R"({"op":"distance","a":"s","b":"t","detail":"topology"}]})";
  try {
    app::read_scene(core::io::parse_json(scene, "scene"), "scene", Mode::Filtered);
    ADD_FAILURE() << "a distance query with detail topology was accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where().json_path, "$.queries[1].detail");
    EXPECT_GT(e.where().column, 0);
  }
  // Good scene values are kept per query.
  const std::string good = R"({"surfaces":{"s":"x^2+y^2+z^2=1","t":"(x-3)^2+y^2+z^2=1"},)"
                           R"("queries":[{"op":"classify","a":"s","b":"t","detail":"topology"},)"
                           R"({"op":"distance","a":"s","b":"t","detail":"value"}]})";
  app::Scene s = app::read_scene(core::io::parse_json(good, "scene"), "scene", Mode::Filtered);
  const Json q0 = app::run_query(s, s.queries[0]);
  const Json q1 = app::run_query(s, s.queries[1]);
  EXPECT_EQ(q0.find("detail")->text(), "topology");
  EXPECT_EQ(q0.find("result")->find("matrices"), nullptr);
  EXPECT_EQ(q1.find("detail")->text(), "value");
  EXPECT_EQ(q1.find("result")->find("eliminated_degree"), nullptr);
}

namespace {

struct CliRun {
  int code;
  std::string out;
};

CliRun run(const std::string& args, const std::string& stdin_text = "") {
  const std::string base =
      std::string(::testing::TempDir().empty() ? "/tmp/" : ::testing::TempDir()) +
      "surfcert_detail_" + std::to_string(getpid());
  const std::string in = base + "_in", out = base + "_out";
  std::ofstream(in) << stdin_text;
  const std::string cmd =
      std::string(SURFCERT_BINARY) + " " + args + " <" + in + " >" + out + " 2>/dev/null";
  const int st = std::system(cmd.c_str());
  std::ifstream f(out);
  std::stringstream s;
  s << f.rdbuf();
  std::remove(in.c_str());
  std::remove(out.c_str());
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, s.str()};
}

} // namespace

TEST(Detail, CommandLine) {
  const std::string eqs = "'x^2+y^2+z^2=1' '(x-1)^2+y^2+z^2=1'";
  for (const char* cmd : {"classify", "intersect"}) {
    CliRun t = run(std::string(cmd) + " --json --detail topology " + eqs);
    ASSERT_EQ(t.code, 0) << cmd;
    Json j = core::io::parse_json(t.out, "stdout");
    EXPECT_EQ(j.find("detail")->text(), "topology");
    EXPECT_EQ(j.find("result")->find("matrices"), nullptr);
    EXPECT_EQ(j.find("result")->find("tu_case")->text(), "17");
    CliRun c = run(std::string(cmd) + " --json --detail=certificate " + eqs);
    ASSERT_EQ(c.code, 0);
    EXPECT_NE(core::io::parse_json(c.out, "stdout").find("result")->find("matrices"), nullptr);
    EXPECT_EQ(run(std::string(cmd) + " --json --detail value " + eqs).code, 2);
    EXPECT_EQ(run(std::string(cmd) + " --json --detail bogus " + eqs).code, 2);
  }
  const std::string far = "'x^2+y^2+z^2=1' '(x-3)^2+y^2+z^2=1'";
  CliRun v = run("distance --json --detail value " + far);
  ASSERT_EQ(v.code, 0);
  Json dv = core::io::parse_json(v.out, "stdout");
  EXPECT_EQ(dv.find("detail")->text(), "value");
  EXPECT_EQ(dv.find("result")->find("eliminated_degree"), nullptr);
  EXPECT_NE(dv.find("result")->find("distance"), nullptr);
  EXPECT_EQ(run("distance --json --detail topology " + far).code, 2);
  // batch: the default for every line, mapped per op; a line's own detail wins.
  CliRun b = run("batch --detail topology",
                 R"({"op":"classify","a":"x^2+y^2+z^2=1","b":"(x-1)^2+y^2+z^2=1"})"
                 "\n"
                 R"({"op":"distance","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1"})"
                 "\n"
                 R"({"op":"classify","detail":"full","a":"x^2+y^2+z^2=1","b":"x^2+y^2+z^2=4"})"
                 "\n");
  ASSERT_EQ(b.code, 0);
  std::istringstream lines(b.out);
  std::string l;
  std::vector<Json> got;
  while (std::getline(lines, l))
    got.push_back(core::io::parse_json(l, "stdout"));
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0].find("detail")->text(), "topology");
  EXPECT_EQ(got[1].find("detail")->text(), "value");
  EXPECT_EQ(got[2].find("detail"), nullptr);
  EXPECT_EQ(run("batch --detail bogus", "").code, 2);
}

namespace {

// The envelope as distance_envelope_json built it as a document (before it was written as
// text directly): the reference for the text's bytes.
Json reference_distance_envelope(const certify::DistanceResult& r, long digits,
                                 certify::Detail detail) {
  auto g17 = [](double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return std::string(buf);
  };
  Json o = Json::object();
  o.set("status", Json::string(certify::to_string(r.status)));
  if (r.budget_exhausted) o.set("reason", Json::string("budget"));
  if (!r.note.empty()) o.set("note", Json::string(r.note));
  const bool full = detail == certify::Detail::Full;
  if (!full) o.set("detail", Json::string("value"));
  Json res = Json::object();
  if (r.distance) {
    Json d = Json::object();
    d.set("lower", Json::string(r.distance->lower()));
    d.set("upper", Json::string(r.distance->upper()));
    d.set("approx", Json::string(g17(r.distance->approx())));
    res.set("distance", d);
  }
  if (r.estimate) {
    Json e = Json::object();
    e.set("value", Json::string(g17(r.estimate->value)));
    e.set("certified", Json::boolean(false));
    res.set("estimate", e);
  }
  if (!r.minimizers.empty()) {
    res.set("minimizers", Json::string(r.minimizers.str()));
    res.set("minimizers_proof", Json::string(r.minimizers.proof_str()));
  }
  if (r.minimizer_candidates() > 0)
    res.set("minimizer_candidates", Json::number(r.minimizer_candidates()));
  Json pairs = Json::array();
  for (const auto& pr : r.pairs) {
    bool finite = true;
    for (const auto& p : pr)
      for (double x : p)
        finite = finite && std::isfinite(x);
    if (!finite) continue;
    Json pj = Json::array();
    for (const auto& p : pr) {
      Json a3 = Json::array();
      for (double x : p)
        a3.push_back(Json::number_text(g17(x)));
      pj.push_back(a3);
    }
    pairs.push_back(pj);
  }
  res.set("pairs", pairs);
  res.set("pair_points_approximate", Json::boolean(true));
  if (full) {
    res.set("critical_candidates", Json::number(r.critical_candidates));
    res.set("eliminated_degree", Json::number(r.eliminated_degree));
  }
  if (full && !r.system_degrees.empty()) {
    Json deg = Json::object();
    auto arr = [](const std::vector<long>& v) {
      Json a = Json::array();
      for (long x : v)
        a.push_back(Json::number(x));
      return a;
    };
    deg.set("system", arr(r.system_degrees));
    deg.set("bivariate", arr(r.bivariate_degrees));
    deg.set("univariate", arr(r.univariate_degrees));
    deg.set("squarefree", arr(r.squarefree_degrees));
    res.set("degrees", deg);
  }
  res.set("digits", Json::number(digits));
  res.set("solid", Json::boolean(r.solid));
  res.set("mode", Json::string(certify::to_string(r.mode)));
  if (r.method != certify::Method::None)
    res.set("method", Json::string(certify::to_string(r.method)));
  if (r.reduced_by != certify::Method::None)
    res.set("reduced_by", Json::string(certify::to_string(r.reduced_by)));
  if (r.ties != certify::Ties::None) res.set("ties", Json::string(certify::to_string(r.ties)));
  o.set("result", res);
  return o;
}

} // namespace

TEST(Detail, DistanceEnvelopeTextEqualsTheReferenceDocument) {
  using certify::DistanceResult;
  using certify::Minimizers;
  std::mt19937_64 rng(20261125);
  const double doubles[] = {0.1,     -0.0,        5e-324, 2.2250738585072014e-308, 1e300, -1.5e-7,
                            1.0 / 3, 123456789.0, 0.5};
  const char* notes[] = {"", "plain", "quote \" and backslash \\", "new\nline\ttab \x01",
                         "UTF-8 \xc3\xa9 \xe2\x88\x9a"};
  const certify::Status statuses[] = {certify::Status::Certified, certify::Status::Undecided,
                                      certify::Status::Uncertified, certify::Status::Error};
  const Minimizers mins[] = {Minimizers(), Minimizers::count(2, Minimizers::Proof::Exact),
                             Minimizers::continuum(Minimizers::Proof::Interval),
                             Minimizers::undecided(3)};
  long checked = 0;
  for (int t = 0; t < 400; ++t) {
    auto bit = [&](int k) { return ((rng() >> k) & 1u) != 0; };
    DistanceResult r;
    r.status = statuses[rng() % 4];
    r.note = notes[rng() % 5];
    r.budget_exhausted = bit(1);
    if (bit(2)) {
      algebra::Ball d;
      arb_set_d(d.v, doubles[rng() % 9]);
      arb_abs(d.v, d.v);
      arb_add_error_2exp_si(d.v, -60 + static_cast<long>(rng() % 50));
      certify::set_distance_enclosure(r, d.v, 15);
    }
    if (bit(3)) r.estimate = certify::Estimate{doubles[rng() % 9]};
    r.minimizers = mins[rng() % 4];
    for (unsigned k = rng() % 3; k > 0; --k) {
      std::array<std::array<double, 3>, 2> pr{};
      for (auto& p : pr)
        for (double& x : p)
          x = doubles[rng() % 9];
      if (rng() % 5 == 0) pr[1][2] = rng() % 2 ? INFINITY : NAN; // left out
      r.pairs.push_back(pr);
    }
    r.critical_candidates = static_cast<int>(rng() % 7);
    r.eliminated_degree = static_cast<int>(rng() % 40);
    if (bit(4)) {
      r.system_degrees = {2, 2, 2};
      r.bivariate_degrees = {16, 16};
      r.univariate_degrees = {};
      r.squarefree_degrees = {12};
    }
    r.solid = bit(5);
    r.mode = kModes[rng() % 3];
    if (bit(6)) r.method = certify::Method::ConvexDuality;
    if (bit(7)) r.reduced_by = certify::Method::NestedConvexDuality;
    r.ties = bit(8)   ? certify::Ties::Proven
             : bit(9) ? certify::Ties::Unproven
                      : certify::Ties::None;
    for (certify::Detail d : {certify::Detail::Full, certify::Detail::Value}) {
      const long digits = 1 + static_cast<long>(rng() % 60);
      std::string text;
      certify::append_distance_envelope(text, r, digits, d);
      ASSERT_EQ(text, core::io::dump(reference_distance_envelope(r, digits, d))) << t;
      ASSERT_EQ(core::io::dump(certify::distance_envelope_json(r, digits, d)), text) << t;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 800);
}
