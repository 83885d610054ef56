// Touching or not, probed from both sides across the registry: for each pair kind a
// configuration whose gap is exactly e in closed form (e > 0: separated by e; e < 0: the
// solids overlap by |e|, so the surfaces cross), at e = +-10^-10, +-10^-20, +-10^-30 and
// +-2^-100. A certified answer must contain the closed form (upper bound included): e when
// e > 0, 0 when e < 0; undecided is allowed (honest), a wrong certified value is not.
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <string>

using namespace surfcert;

namespace {

core::Surface S(const std::string& text) {
  if (!text.empty() && text[0] == '{')
    return core::io::read_surface(core::io::parse_json(text, "t"), "t", "$");
  return core::io::read_surface(core::io::Json::string(text), "t", "$");
}

struct Gap {
  const char* text;  ///< e as an exact decimal/rational literal, for the inputs
  const char* value; ///< e as a decimal for MPFR (exact: 1e-10 is read exactly as 10^-10)
};

// e = num / den with den a power of ten or of two, written for the inputs.
const Gap kGaps[] = {{"1/10000000000", "1e-10"},
                     {"1/100000000000000000000", "1e-20"},
                     {"1/1000000000000000000000000000000", "1e-30"},
                     {"1/1267650600228229401496703205376",
                      "7.8886090522101180541172856528278622967320643510902300477027893066"
                      "40625e-31"}};

// Checks r against the closed form: e > 0 -> [lower, upper] contains e exactly; e < 0 -> 0.
// Certified answers on the separated side (e > 0), where every route must decide: the probes
// must not pass vacuously. On the overlapping side a tiny crossing region (width ~ sqrt|e|)
// may leave contact undecided (e.g. two tori at -10^-20): honest, and checked not to be wrong.
int g_certified = 0;

void expect_gap(const certify::DistanceResult& r, const Gap& g, int sign, const std::string& what) {
  SCOPED_TRACE(what + (sign > 0 ? " +" : " -") + g.value);
  g_certified += sign > 0 && r.status == certify::Status::Certified;
  if (r.status != certify::Status::Certified) {
    // Honest undecided; but what it established must still hold.
    if (r.distance && sign > 0) {
      mpfr_t e;
      mpfr_init2(e, 4000);
      mpfr_set_str(e, g.value, 10, MPFR_RNDN);
      EXPECT_TRUE(surfcert::testing::contains(r, e)) << r.lower() << " " << r.upper();
      mpfr_clear(e);
    }
    return;
  }
  ASSERT_TRUE(r.distance.has_value());
  if (sign < 0) {
    EXPECT_TRUE(r.distance->is_zero()) << r.lower() << " " << r.upper() << " " << r.note;
    return;
  }
  mpfr_t e;
  mpfr_init2(e, 4000);
  mpfr_set_str(e, g.value, 10, MPFR_RNDN);
  EXPECT_TRUE(surfcert::testing::contains(r, e)) << r.lower() << " " << r.upper() << " " << r.note;
  mpfr_clear(e);
}

// c + sign * e as one exact rational literal (JSON numbers are single rationals).
std::string plus_gap(long c, int sign, const Gap& g) {
  const core::Rational e = *core::Rational::from_string(g.text);
  return (core::Rational(c) + (sign > 0 ? e : -e)).to_string();
}

std::string shifted(const char* base, int sign, const Gap& g) {
  return std::string(base) + (sign > 0 ? "+" : "-") + g.text;
}

} // namespace

TEST(ThresholdProbes, TwoSpheres) {
  g_certified = 0;
  for (const Gap& g : kGaps)
    for (int s : {+1, -1}) {
      const auto r = certify::surface_distance(
          S("x^2+y^2+z^2=1"),
          S("(x-(2" + std::string(s > 0 ? "+" : "-") + g.text + "))^2+y^2+z^2=1"), 15, false);
      expect_gap(r, g, s, "spheres");
    }
  EXPECT_EQ(g_certified, 4) << "probes answered undecided";
}

TEST(ThresholdProbes, EllipsoidAndPlane) {
  g_certified = 0;
  for (const Gap& g : kGaps)
    for (int s : {+1, -1}) {
      const auto r =
          certify::surface_distance(S("x^2/4+y^2+z^2=1"), S(shifted("x=2", s, g)), 15, false);
      expect_gap(r, g, s, "ellipsoid-plane");
    }
  EXPECT_EQ(g_certified, 4) << "probes answered undecided";
}

TEST(ThresholdProbes, TwoEllipsoids) {
  g_certified = 0;
  for (const Gap& g : kGaps)
    for (int s : {+1, -1})
      for (auto mode : {certify::Mode::Filtered, certify::Mode::Exact}) {
        const auto r = certify::surface_distance(
            S("x^2/4+y^2+z^2/9=1"),
            S("(x-(4" + std::string(s > 0 ? "+" : "-") + g.text + "))^2/4+y^2+z^2/9=1"), 15, false,
            mode);
        expect_gap(r, g, s, mode == certify::Mode::Exact ? "ellipsoids exact" : "ellipsoids");
      }
  EXPECT_EQ(g_certified, 8) << "probes answered undecided";
}

TEST(ThresholdProbes, SphereAndTorus) {
  g_certified = 0;
  // Torus R = 3, r = 1 about z: its outer equator is at distance 4 from the axis.
  const auto torus =
      S(R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})");
  for (const Gap& g : kGaps)
    for (int s : {+1, -1}) {
      const auto r = certify::surface_distance(
          S("(x-(5" + std::string(s > 0 ? "+" : "-") + g.text + "))^2+y^2+z^2=1"), torus, 15,
          false);
      expect_gap(r, g, s, "sphere-torus");
    }
  EXPECT_EQ(g_certified, 4) << "probes answered undecided";
}

TEST(ThresholdProbes, TwoTori) {
  g_certified = 0;
  const auto a =
      S(R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})");
  for (const Gap& g : kGaps)
    for (int s : {+1, -1}) {
      const auto b = S(std::string(R"({"type":"torus","center":[")") + plus_gap(8, s, g) +
                       R"(",0,0],"axis":[0,0,1],"major_radius":3,"minor_radius":1})");
      const auto r = certify::surface_distance(a, b, 15, false);
      expect_gap(r, g, s, "torus-torus");
    }
  EXPECT_EQ(g_certified, 4) << "probes answered undecided";
}

TEST(ThresholdProbes, SphereAndCapsule) {
  g_certified = 0;
  const auto cap = S(R"({"type":"capsule","from":[0,0,0],"to":[4,0,0],"radius":1})");
  for (const Gap& g : kGaps)
    for (int s : {+1, -1}) {
      const auto r = certify::surface_distance(
          S("(x-2)^2+(y-(2" + std::string(s > 0 ? "+" : "-") + g.text + "))^2+z^2=1"), cap, 15,
          false);
      expect_gap(r, g, s, "sphere-capsule");
    }
  EXPECT_EQ(g_certified, 4) << "probes answered undecided";
}

TEST(ThresholdProbes, TwoCapsules) {
  g_certified = 0;
  const auto a = S(R"({"type":"capsule","from":[0,0,0],"to":[4,0,0],"radius":1})");
  for (const Gap& g : kGaps)
    for (int s : {+1, -1}) {
      const std::string y = "\"" + plus_gap(2, s, g) + "\"";
      const auto b =
          S(R"({"type":"capsule","from":[2,)" + y + R"(,-3],"to":[2,)" + y + R"(,3],"radius":1})");
      const auto r = certify::surface_distance(a, b, 15, false);
      expect_gap(r, g, s, "capsules");
    }
  EXPECT_EQ(g_certified, 4) << "probes answered undecided";
}
