// The distance registry (route.hpp) as a structure:
// - every route has an id (its JSON method), a pair kind, at least one mode and a line saying
//   what it proves; every non-quadric table ends with the contact fallback;
// - the answer does not depend on the order of the two surfaces (canonical orientation):
//   same status, overlapping enclosures, pairs swapped (the first point on the first surface);
// - in exact mode no answer comes from a route that does not run in exact mode, and exact and
//   filtered answers overlap where both certify;
// - a float-mode answer is an estimate (Outcome::Estimate), never an enclosure.
#include "surfcert/certify/distance/route.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <set>

using namespace surfcert;
using surfcert::testing::overlap;

namespace {

core::Surface S(const std::string& text) {
  if (!text.empty() && text[0] == '{')
    return core::io::read_surface(core::io::parse_json(text, "t"), "t", "$");
  return core::io::read_surface(core::io::Json::string(text), "t", "$");
}

const char* kTorus =
    R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})";
const char* kCapsule = R"({"type":"capsule","from":[0,0,5],"to":[4,0,5],"radius":1})";

} // namespace

TEST(Registry, EveryRouteIsDescribed) {
  std::set<certify::PairKind> kinds;
  for (const auto& r : certify::distance_routes()) {
    EXPECT_NE(r.id, certify::Method::None);
    EXPECT_GT(std::strlen(certify::to_string(r.id)), 0u);
    EXPECT_GT(std::strlen(r.proves), 0u) << r.id;
    EXPECT_NE(r.modes & certify::kAllModes, 0u) << r.id;
    EXPECT_NE(r.applies, nullptr);
    EXPECT_NE(r.run, nullptr);
    kinds.insert(r.kind);
  }
  // Every pair kind has a table.
  for (auto k : {certify::PairKind::QuadricQuadric, certify::PairKind::QuadricTorus,
                 certify::PairKind::QuadricCanal, certify::PairKind::QuadricImplicit,
                 certify::PairKind::TorusTorus, certify::PairKind::TorusCanal,
                 certify::PairKind::TorusImplicit, certify::PairKind::CanalCanal,
                 certify::PairKind::CanalImplicit, certify::PairKind::ImplicitImplicit,
                 certify::PairKind::Parametric})
    EXPECT_TRUE(kinds.count(k)) << certify::to_string(k);
  // Non-quadric tables end with the contact fallback.
  for (auto k : kinds) {
    if (k == certify::PairKind::QuadricQuadric || k == certify::PairKind::Parametric) continue;
    certify::Method last = certify::Method::None;
    for (const auto& r : certify::distance_routes())
      if (r.kind == k) last = r.id;
    EXPECT_EQ(last, certify::Method::SignChangeContact) << certify::to_string(k);
  }
}

TEST(Registry, OrderOfTheSurfacesDoesNotMatter) {
  const std::pair<std::string, std::string> pairs[] = {
      {"x^2+y^2+(z-6)^2=1", kTorus},                // quadric-torus
      {"(x-9)^2+y^2+z^2=4", kCapsule},              // quadric-canal
      {kTorus, kCapsule},                           // torus-canal (sphere family)
      {"x^2+y^2+z^2=1", "(x-4)^4+y^4+z^4=1"},       // quadric-implicit
      {"x^4+y^4+z^4=1", "(x-5)^4+(y-1)^4+z^4=1"},   // implicit-implicit
      {"x^2/4+y^2/9+(z-1)^2=1", "x^2+y^2-z^2=1/4"}, // two quadrics (they meet)
      {"(x-7)^2/4+y^2+z^2=1", "x^2+y^2=1"},         // ellipsoid and cylinder
  };
  for (const auto& [ta, tb] : pairs) {
    SCOPED_TRACE(ta + " | " + tb);
    const auto a = S(ta), b = S(tb);
    const auto ab = certify::surface_distance(a, b, 15, false);
    const auto ba = certify::surface_distance(b, a, 15, false);
    ASSERT_EQ(ab.status, ba.status) << ab.note << " / " << ba.note;
    EXPECT_EQ(ab.method, ba.method);
    EXPECT_EQ(ab.minimizers, ba.minimizers);
    if (ab.distance && ba.distance) {
      EXPECT_TRUE(overlap(ab, ba)) << ab.lower() << " " << ba.lower();
    }
    // A continuum lists one representative pair, which may depend on the order; isolated
    // minimizers are the same pairs, swapped.
    if (ab.minimizers == "infinite") continue;
    ASSERT_EQ(ab.pairs.size(), ba.pairs.size());
    for (size_t i = 0; i < ab.pairs.size(); ++i)
      for (size_t k = 0; k < 3; ++k) {
        EXPECT_DOUBLE_EQ(ab.pairs[i][0][k], ba.pairs[i][1][k]);
        EXPECT_DOUBLE_EQ(ab.pairs[i][1][k], ba.pairs[i][0][k]);
      }
  }
}

TEST(Registry, ExactModeUsesExactRoutesOnly) {
  const std::pair<const char*, const char*> pairs[] = {
      {"x^2+y^2+z^2=1", "(x-5)^2/4+y^2+z^2=1"},                      // separated ellipsoids
      {"x^2 + y^2/4 + (z+3)^2/9 = 1", "x^2/4 + y^2/9 + z^2/49 = 1"}, // nested (seed 000)
      {"x^2/4+y^2+z^2=1", "x^2+y^2=(z-6)^2"},                        // ellipsoid and cone
  };
  for (const auto& [ta, tb] : pairs) {
    SCOPED_TRACE(std::string(ta) + " | " + tb);
    const auto a = S(ta), b = S(tb);
    const auto ex = certify::surface_distance(a, b, 15, false, certify::Mode::Exact);
    const auto fi = certify::surface_distance(a, b, 15, false, certify::Mode::Filtered);
    ASSERT_EQ(ex.status, certify::Status::Certified) << ex.note;
    ASSERT_EQ(fi.status, certify::Status::Certified) << fi.note;
    EXPECT_TRUE(overlap(ex, fi)) << ex.lower() << " " << fi.lower();
    bool exact_route = false;
    for (const auto& r : certify::distance_routes())
      exact_route = exact_route || (ex.method == r.id && (r.modes & certify::kExactMode));
    EXPECT_TRUE(exact_route) << ex.method;
  }
}

TEST(Registry, FloatModeIsAnEstimate) {
  const auto r = certify::surface_distance(S("x^2+y^2+z^2=1"), S("(x-5)^2/4+y^2+z^2=1"), 15, false,
                                           certify::Mode::Float);
  EXPECT_EQ(r.status, certify::Status::Uncertified);
  EXPECT_EQ(r.method, certify::Method::ConvexDualityFloat);
  EXPECT_FALSE(r.distance.has_value());
  ASSERT_TRUE(r.estimate.has_value());
}

// Method and Minimizers are enums with fixed JSON spellings: every method reads back from its
// spelling, no two share one, and the envelope carries the count with how it was proven.
TEST(Registry, MethodSpellingsRoundTrip) {
  std::set<std::string> seen;
  for (int i = 0; i <= static_cast<int>(certify::Method::LineLocus); ++i) {
    const auto m = static_cast<certify::Method>(i);
    const std::string text = certify::to_string(m);
    EXPECT_TRUE(seen.insert(text).second) << text;
    const auto back = certify::method_from_string(text);
    ASSERT_TRUE(back.has_value()) << text;
    EXPECT_EQ(*back, m);
  }
  EXPECT_FALSE(certify::method_from_string("no_such_route").has_value());
}

TEST(Registry, MinimizersCarryTheirProof) {
  using M = certify::Minimizers;
  EXPECT_EQ(M::count(2, M::Proof::Exact).str(), "2");
  EXPECT_STREQ(M::count(2, M::Proof::Interval).proof_str(), "interval");
  EXPECT_EQ(M::continuum(M::Proof::Exact).str(), "infinite");
  EXPECT_EQ(M::not_attained(M::Proof::Exact).str(), "0");
  EXPECT_EQ(M::undecided(3).str(), "undecided");
  EXPECT_STREQ(M::undecided(3).proof_str(), "unproven");
  EXPECT_TRUE(M().empty());
  // A plane and a sphere: one minimizer, proven exactly (the closed form).
  const auto plane = certify::surface_distance(S("z = 3"), S("x^2+y^2+z^2 = 1"), 15, false);
  ASSERT_EQ(plane.status, certify::Status::Certified) << plane.note;
  const auto j = certify::distance_envelope_json(plane, 15);
  const auto* res = j.find("result");
  ASSERT_NE(res, nullptr);
  ASSERT_NE(res->find("minimizers"), nullptr);
  EXPECT_EQ(res->find("minimizers")->text(), "1");
  ASSERT_NE(res->find("minimizers_proof"), nullptr);
  EXPECT_EQ(res->find("minimizers_proof")->text(), plane.minimizers.proof_str());
  EXPECT_NE(res->find("minimizers_proof")->text(), "unproven");
  // A parametric surface: this route's method, the implicit route beside it.
  const auto par = certify::surface_distance(S(R"({"type":"parametric","x":"u","y":"v","z":"0"})"),
                                             S("x^2+y^2+(z-3)^2 = 1"), 15, false);
  EXPECT_EQ(par.method, certify::Method::ParametricReduction) << par.note;
  EXPECT_NE(par.reduced_by, certify::Method::None) << par.note;
  const auto pj = certify::distance_envelope_json(par, 15);
  ASSERT_NE(pj.find("result")->find("reduced_by"), nullptr);
  EXPECT_EQ(pj.find("result")->find("method")->text(), "parametric_reduction");
}
