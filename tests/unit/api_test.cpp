// The embedding API (surfcert/surfcert.hpp) against the batch line (app::process_batch_line),
// the independent route its contract names: to_json() of an answer equals the batch line's
// result object without "id" and "time_ms", for the QSIC fixtures (classify at every detail,
// intersect), distances, verify, double matrices (a non-symmetric one: the readings), posed
// shapes and errors (the same JSON path). Also: the typed fields agree with the JSON, and the
// status of a budget that runs out.
#include "support/fixtures.hpp"
#include "surfcert/app/scene.hpp"
#include "surfcert/surfcert.hpp"

#include <gtest/gtest.h>

namespace {

using namespace surfcert;
using core::io::dump;

// The batch line's answer without id and time_ms.
Json batch(const std::string& line) {
  Json r = app::process_batch_line(line, 1, Mode::Filtered);
  Json out = Json::object();
  for (const auto& [k, v] : r.members())
    if (k != "id" && k != "time_ms") out.set(k, v);
  return out;
}

std::string matrix_text(const Json& m) {
  return "{\"matrix\":" + dump(m) + "}";
}

std::array<std::array<Rational, 4>, 4> mat(const Json& m) {
  core::Mat4 r = fixtures::mat4_from_json(m);
  return r;
}

TEST(Api, ClassifyEqualsBatchOnFixtures) {
  const Json canon = fixtures::load_json("fixtures/canonical_examples.json");
  const Json ell = fixtures::load_json("fixtures/ellipsoid_fixtures.json");
  int n = 0;
  for (const auto& [file, ka, kb] :
       {std::make_tuple(&canon, "A", "B"), std::make_tuple(&ell, "E1", "E2")}) {
    for (const auto& [name, fx] : file->members()) {
      const Json& ja = *fx.find(ka);
      const Json& jb = *fx.find(kb);
      const Surface a = Surface::from_matrix(mat(ja), "$.a");
      const Surface b = Surface::parse(matrix_text(jb), "<b>", "$.b");
      for (const char* detail : {"topology", "certificate", "full"}) {
        Options o;
        o.detail = *certify::parse_detail(detail);
        const std::string line = "{\"op\":\"classify\",\"a\":" + matrix_text(ja) +
                                 ",\"b\":" + matrix_text(jb) + ",\"detail\":\"" + detail + "\"}";
        const Classification c = classify(a, b, o);
        EXPECT_EQ(dump(c.to_json()), dump(batch(line))) << name << " " << detail;
        EXPECT_EQ(c.to_json().find("status")->text(), certify::to_string(c.status()));
        if (c.qsic.morphology) {
          EXPECT_EQ(c.to_json().find("result")->find("morphology")->text(), c.qsic.morphology->id);
        }
        ++n;
      }
    }
  }
  EXPECT_GE(n, 3 * (35 + 21));
}

TEST(Api, IntersectAndDistanceEqualBatch) {
  const Json ell = fixtures::load_json("fixtures/ellipsoid_fixtures.json");
  int n = 0;
  for (const auto& [name, fx] : ell.members()) {
    if (++n > 6) break;
    const std::string ta = matrix_text(*fx.find("E1")), tb = matrix_text(*fx.find("E2"));
    const Surface a = Surface::parse(ta, "<a>", "$.a"), b = Surface::parse(tb, "<b>", "$.b");
    const Intersection x = intersect(a, b);
    const Json xj = x.to_json();
    // The curves carry doubles: equal text means equal points.
    EXPECT_EQ(dump(xj), dump(batch("{\"op\":\"intersect\",\"a\":" + ta + ",\"b\":" + tb + "}")))
        << name;
    EXPECT_EQ(xj.find("result")->find("branches")->size(), x.curve.branches.size());
    Options o;
    o.digits = 20;
    const Distance d = distance(a, b, o);
    EXPECT_EQ(dump(d.to_json()),
              dump(batch("{\"op\":\"distance\",\"a\":" + ta + ",\"b\":" + tb + ",\"digits\":20}")))
        << name;
    if (d.result.distance) {
      EXPECT_EQ(d.to_json().find("result")->find("distance")->find("lower")->text(),
                d.result.lower());
    }
  }
}

TEST(Api, DoublesAndShapesReadAsOnABatchLine) {
  // numpy's R D R^T: non-symmetric by one ulp, read as its symmetric part (a reading).
  const std::array<std::array<double, 4>, 4> m{
      {{1.4542225778012692, -1.3907645443352732, 0.0, -3.2183270812025913},
       {-1.3907645443352734, 3.2402218666431755, 0.0, 2.5048448008452313},
       {0.0, 0.0, 2.0408163265306127, 0.20408163265306128},
       {-3.2183270812025913, 2.5048448008452313, 0.20408163265306128, 6.314772426018214}}};
  const Surface a = Surface::from_matrix(m, "$.a");
  ASSERT_EQ(a.readings().size(), 1u);
  EXPECT_EQ(a.readings()[0].path, "$.a.matrix");
  const Surface b = Surface::from_shape("ellipsoid", {0.1, -0.2, 0.3}, {1.0, 0.8, 0.6},
                                        std::array<double, 4>{0.9, 0.1, 0.2, 0.3}, "$.b");
  const std::string ja =
      "{\"matrix\":[[1.4542225778012692,-1.3907645443352732,0.0,-3.2183270812025913],"
      "[-1.3907645443352734,3.2402218666431755,0.0,2.5048448008452313],"
      "[0.0,0.0,2.0408163265306127,0.20408163265306128],"
      "[-3.2183270812025913,2.5048448008452313,0.20408163265306128,6.314772426018214]]}";
  const std::string jb = "{\"type\":\"ellipsoid\",\"center\":[0.1,-0.2,0.3],\"radii\":[1.0,0.8,"
                         "0.6],\"rotation\":{\"quaternion\":[0.9,0.1,0.2,0.3]}}";
  Options o;
  o.detail = Detail::Certificate;
  EXPECT_EQ(dump(classify(a, b, o).to_json()),
            dump(batch("{\"op\":\"classify\",\"a\":" + ja + ",\"b\":" + jb +
                       ",\"detail\":\"certificate\"}")));
  const Surface s = Surface::from_shape("sphere", {3, 0, 0}, {0.5, 0, 0}, std::nullopt, "$.b");
  EXPECT_EQ(dump(distance(b, s).to_json()),
            dump(batch("{\"op\":\"distance\",\"a\":" + jb +
                       ",\"b\":{\"type\":\"sphere\",\"center\":[3,0,0],\"radius\":0.5}}")));
}

TEST(Api, VerifyEqualsBatch) {
  const std::string claims = R"([{"kind":"distance","value":1.5,"abs_tol":1e-9},)"
                             R"({"kind":"solids_collide","value":true}])";
  const Surface a = Surface::parse("x^2+y^2+z^2=1", "<a>", "$.a");
  const Surface b = Surface::parse("(x-3)^2+y^2+z^2=1/4", "<b>", "$.b");
  const Verification v = verify(a, b, core::io::parse_json(claims, "<claims>"));
  EXPECT_EQ(dump(v.to_json()),
            dump(batch(R"({"op":"verify","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1/4",)"
                       R"("claims":)" +
                       claims + "}")));
  EXPECT_EQ(v.status(), Status::Certified);
}

TEST(Api, ErrorsNameTheBatchLinesPath) {
  const std::string bad = R"({"type":"sphere","center":[0,0,0],"radius":-1})";
  Json line = batch(R"({"op":"classify","a":)" + bad + R"(,"b":"x^2+y^2=1"})");
  ASSERT_EQ(line.find("status")->text(), "error");
  try {
    (void)Surface::parse(bad, "<a>", "$.a");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().json_path, line.find("error")->find("json_path")->text());
    EXPECT_EQ(e.where().json_path, "$.a.radius");
    EXPECT_EQ(e.where().line, 1);
    EXPECT_GT(e.where().column, 1);
  }
  // A torus for classify: the batch's error, at $.b.
  const Surface t = Surface::parse(
      R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})");
  const Surface q = Surface::parse("x^2+y^2+z^2=1");
  try {
    (void)classify(q, t);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().json_path, "$.b");
  }
  Options o;
  o.detail = Detail::Value; // classify has no "value" level
  EXPECT_THROW((void)classify(q, q, o), InputError);
  o = Options{};
  o.digits = 0;
  EXPECT_THROW((void)distance(q, t, o), InputError);
  EXPECT_THROW((void)Surface::from_matrix(std::array<std::array<double, 4>, 4>{{{NAN}}}),
               InputError);
}

TEST(Api, BudgetRunsOutAsUndecided) {
  // Two tori overlapping by 1e-18 (README example 4): more than 20 ms to prove.
  const Surface a = Surface::parse(
      R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})");
  const Surface b = Surface::parse(R"({"type":"torus","center":["7.999999999999999999",0,0],)"
                                   R"("axis":[0,0,1],"major_radius":3,"minor_radius":1})");
  Options o;
  o.budget_ms = 20;
  const Distance d = distance(a, b, o);
  EXPECT_NE(d.status(), Status::Certified);
  const Json j = d.to_json();
  EXPECT_EQ(j.find("status")->text(), "undecided");
}

TEST(Api, ForEachParallelVisitsEveryItemOnce) {
  std::vector<int> hits(1000, 0);
  for_each_parallel(hits.size(), 3, [&](std::size_t i) { hits[i] += 1; });
  for (int h : hits)
    EXPECT_EQ(h, 1);
}

} // namespace

// generate: each case's label is what classify / distance answer through the API on its
// surfaces read back (a separate route: the API's readers and the engine at full detail),
// and the case built for Tu case k is labelled k. A bad encoding is an InputError.
TEST(Api, GeneratedCasesCarryTheApisAnswers) {
  GenerateOptions g;
  g.cases = "7";
  g.count = 2;
  g.seed = 3;
  g.encoding = "double";
  const std::vector<GeneratedCase> cs = generate(g);
  ASSERT_EQ(cs.size(), 2u);
  for (const GeneratedCase& c : cs) {
    EXPECT_EQ(c.op, "classify");
    ASSERT_EQ(c.status, "certified");
    EXPECT_EQ(c.tu_case, 7);
    const Classification r = classify(c.surface_a(), c.surface_b());
    const Json j = r.to_json();
    EXPECT_EQ(j.find("result")->find("morphology")->text(), c.morphology);
    EXPECT_EQ(dump(*c.line.find("a")), dump(c.a));
  }
  g.cases = "distance";
  g.encoding = "exact";
  g.count = 1;
  int n = 0;
  for (const GeneratedCase& c : generate(g)) {
    ASSERT_EQ(c.op, "distance");
    if (c.status != "certified") continue;
    const Distance d = distance(c.surface_a(), c.surface_b());
    EXPECT_EQ(dump(*d.to_json().find("result")->find("distance")), dump(*c.label.find("distance")));
    ++n;
  }
  EXPECT_GT(n, 0);
  g.encoding = "float";
  EXPECT_THROW(generate(g), InputError);
}
