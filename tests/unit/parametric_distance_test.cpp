// Certified distance from a rational parametric surface (to its closure: the points the
// parametrisation misses count), against independent routes: seed 000's parametrised ellipsoid
// (2u, 4v, -6(u^2+v^2)) / (1+u^2+v^2) must give exactly the implicit pair's enclosure
// (0.5302293602...), and its missed point (0, 0, -6) must be found; a sphere below the
// ellipsoid is closest to exactly that missed point (closed form 1); the implicit equation found
// by linear algebra is checked on random parameter values; a cubic parametrisation is refused.
#include "support/distance_checks.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/distance/parametric_distance.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <gtest/gtest.h>
#include <mpfr.h>

#include <random>

using namespace surfcert;

namespace {

core::Surface js(const std::string& t) {
  return core::io::read_surface(core::io::parse_json(t, "t"), "t", "$");
}
core::Surface eq(const std::string& e) {
  return core::io::quadric_from_equation(e, {"t", 1, 1, ""});
}
const char* kSeed =
    R"J({"type":"parametric","x":"2u","y":"4v","z":"-6(u^2+v^2)","w":"1+u^2+v^2"})J";

} // namespace

TEST(ParametricDistance, SeedEllipsoidAndItsMissedPoint) {
  auto p = js(kSeed);
  auto r = certify::surface_distance(p, eq("x^2/4 + y^2/9 + z^2/49 = 1"), 15, false);
  auto i = certify::surface_distance(eq("x^2 + y^2/4 + (z+3)^2/9 = 1"),
                                     eq("x^2/4 + y^2/9 + z^2/49 = 1"), 15, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  // The lower bound is the implicit pair's; the upper bound is an image witness's, so it may
  // differ from the implicit pair's upper bound within the requested width.
  EXPECT_EQ(r.lower(), i.lower());
  EXPECT_TRUE(surfcert::testing::overlap(r, i));
  EXPECT_LE(surfcert::testing::log10_rel_width(r), -15);
  // Two witnessed minimizers, but their membership in the closure is not proven: no count.
  EXPECT_EQ(r.minimizers, "undecided");
  EXPECT_EQ(r.minimizer_candidates(), 2);
  EXPECT_NE(r.note.find("misses (0, 0, -6)"), std::string::npos) << r.note;
  EXPECT_EQ(r.note.find("near the missed point"), std::string::npos) << r.note;
  // A sphere of radius 1 centred at (0, 0, -8): the closest point is the missed one, d = 1.
  auto s = certify::surface_distance(p, eq("x^2 + y^2 + (z+8)^2 = 1"), 15, false);
  ASSERT_EQ(s.status, certify::Status::Certified) << s.note;
  EXPECT_NEAR(std::stod(s.lower()), 1.0, 1e-15);
  EXPECT_NE(s.note.find("appears (float proposal) to be the missed point"), std::string::npos)
      << s.note;
  // Swapped order: same value.
  auto w = certify::surface_distance(eq("x^2 + y^2 + (z+8)^2 = 1"), p, 15, false);
  EXPECT_EQ(w.lower(), s.lower());
  EXPECT_EQ(w.status, certify::Status::Certified) << w.note;
}

TEST(ParametricDistance, ImplicitFormOnRandomParameters) {
  const core::Surface seed = js(kSeed);
  const auto& ps = std::get<core::ParametricSurface>(seed);
  auto q = certify::implicit_quadric(ps);
  ASSERT_TRUE(q.has_value());
  std::mt19937_64 rng(2026);
  std::uniform_int_distribution<long> d(-50, 50);
  for (int k = 0; k < 20; ++k) {
    core::Rational u(d(rng), 7), v(d(rng), 11);
    core::Rational W = ps.W.evaluate(u, v, core::Rational(0));
    core::Rational x = ps.X.evaluate(u, v, core::Rational(0)) / W,
                   y = ps.Y.evaluate(u, v, core::Rational(0)) / W,
                   z = ps.Z.evaluate(u, v, core::Rational(0)) / W;
    EXPECT_TRUE(q->to_poly().evaluate(x, y, z).is_zero()) << "seed 2026, k " << k;
  }
  // A cubic parametrisation: implicitised exactly (z = x^3) and answered by the implicit-surface
  // route; checked against a float sampling of the parametrisation (distance of (u, v, u^3) to
  // the sphere's centre minus its radius).
  auto c = certify::surface_distance(js(R"({"type":"parametric","x":"u","y":"v","z":"u^3"})"),
                                     eq("x^2+y^2+(z-5)^2=1"), 15, false);
  ASSERT_EQ(c.status, certify::Status::Certified) << c.note;
  EXPECT_NE(c.note.find("-x^3 + z"), std::string::npos) << c.note;
  double best = 1e300;
  for (int i = -30000; i <= 30000; ++i)
    for (int j = -4; j <= 4; ++j) {
      const double u = i * 1e-4, v = j * 0.01;
      best = std::min(best, std::sqrt(u * u + v * v + (u * u * u - 5) * (u * u * u - 5)) - 1);
    }
  EXPECT_GE(best, std::stod(c.lower()) - 1e-12);
  EXPECT_NEAR(best, c.approx(), 1e-6);
  EXPECT_EQ(c.minimizers, "undecided");
  // (u^2, v, 0) covers only the half-plane x >= 0 of z = 0: a sphere meeting the plane at
  // x = -3 must not be reported at distance 0 (the image is 2 away); one above x = 3 is 4 away.
  auto half = js(R"({"type":"parametric","x":"u^2","y":"v","z":"0"})");
  auto h0 = certify::surface_distance(half, eq("(x+3)^2+y^2+z^2=1"), 15, false);
  EXPECT_NE(h0.status, certify::Status::Certified) << h0.note;
  auto h4 = certify::surface_distance(half, eq("(x-3)^2+y^2+(z-5)^2=1"), 15, false);
  ASSERT_EQ(h4.status, certify::Status::Certified) << h4.note;
  EXPECT_NEAR(std::stod(h4.lower()), 4.0, 1e-15);
  EXPECT_EQ(h4.minimizers, "undecided");
  EXPECT_THROW(js(R"({"type":"parametric","x":"x","y":"v","z":"u"})"), core::InputError);
  EXPECT_THROW(js(R"({"type":"parametric","x":"u","y":"v"})"), core::InputError);
}

TEST(ParametricDistance, RationalTorusImplicitisedToItsQuartic) {
  // The rational torus (R = 3, r = 1, axis z; u = tan(theta/2), v = tan(phi/2)): implicit
  // degree 4, exactly the torus quartic (checked at random rational parameters), and its
  // distance to a sphere agrees with the torus route on the Torus itself.
  const auto P = js(R"J({"type":"parametric","x":"(3(1+v^2)+(1-v^2))(1-u^2)",)J"
                    R"J("y":"(3(1+v^2)+(1-v^2))*2u","z":"2v(1+u^2)","w":"(1+u^2)(1+v^2)"})J");
  const auto& ps = std::get<core::ParametricSurface>(P);
  const auto f = certify::implicit_polynomial(ps, 6);
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->total_degree(), 4);
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<long> d(-50, 50);
  for (int k = 0; k < 10; ++k) {
    const core::Rational u(d(rng), 7), v(d(rng), 11), z0(0);
    const core::Rational W = ps.W.evaluate(u, v, z0);
    const core::Rational x = ps.X.evaluate(u, v, z0) / W, y = ps.Y.evaluate(u, v, z0) / W,
                         z = ps.Z.evaluate(u, v, z0) / W;
    EXPECT_TRUE(f->evaluate(x, y, z).is_zero()) << "seed 99, k " << k;
    // the torus: (|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2)
    const core::Rational s = x * x + y * y + z * z + core::Rational(8);
    EXPECT_EQ(s * s, core::Rational(36) * (x * x + y * y)) << "seed 99, k " << k;
  }
  const auto sphere = eq("(x-6)^2+(y-1)^2+(z-1)^2=1");
  const auto viaP = certify::surface_distance(P, sphere, 15, false);
  const auto torus = core::Surface(core::make_torus({0, 0, 0}, {0, 0, 1}, 3, 1));
  const auto viaT = certify::surface_distance(torus, sphere, 15, false);
  ASSERT_EQ(viaP.status, certify::Status::Certified) << viaP.note;
  ASSERT_EQ(viaT.status, certify::Status::Certified) << viaT.note;
  EXPECT_LE(std::stod(viaP.lower()), std::stod(viaT.upper()));
  EXPECT_LE(std::stod(viaT.lower()), std::stod(viaP.upper()));
  EXPECT_EQ(viaP.minimizers, "undecided");
}

namespace {

// [lower, upper] of r contains sqrt(25 + e^2) - 1, e = 1 / den (den an exact decimal or
// power-of-two text), computed in MPFR at 4000 bits.
bool contains_truth(const certify::DistanceResult& r, const char* den_mpfr, bool zero_offset) {
  mpfr_t e, t;
  mpfr_inits2(4000, e, t, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(e, den_mpfr, 10, MPFR_RNDN); // exact: an integer
  mpfr_ui_div(e, 1, e, MPFR_RNDN);
  if (zero_offset) mpfr_set_zero(e, 1);
  mpfr_sqr(t, e, MPFR_RNDN);
  mpfr_add_ui(t, t, 25, MPFR_RNDN);
  mpfr_sqrt(t, t, MPFR_RNDN);
  mpfr_sub_ui(t, t, 1, MPFR_RNDN);
  const bool ok = surfcert::testing::contains(r, t);
  mpfr_clears(e, t, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

} // namespace

// Issue item 1: (u^2, v, 0) covers only the half-plane x >= 0 of z = 0. A unit sphere centred
// at (-e, 0, 5) is closest to the plane at (-e, 0, 0), outside the image: the true distance is
// sqrt(25 + e^2) - 1 (closest image point (0, 0, 0)), not 4. Every answer must be undecided
// (with a lower bound <= the truth) or certified with an enclosure holding the truth. Centred
// at (+e, 0, 5) the minimizer (e, 0, 0) is in the image: certified, holding 4.
TEST(ParametricDistance, HalfPlaneImageNeverCertifiedFromTheImplicitPlane) {
  const auto half = js(R"({"type":"parametric","x":"u^2","y":"v","z":"0"})");
  struct Offset {
    const char* text; // the offset e in the equation
    const char* den;  // 1 / e as an integer for MPFR
  };
  const Offset offsets[] = {{"1/(2*10^8)", "200000000"},
                            {"1/10^10", "10000000000"},
                            {"1/10^20", "100000000000000000000"},
                            {"1/10^30", "1000000000000000000000000000000"},
                            {"1/(2^50*2^50)", "1267650600228229401496703205376"}};
  for (const auto& o : offsets) {
    for (long digits : {15L, 30L}) {
      const std::string out = std::string("(x+") + o.text + ")^2+y^2+(z-5)^2=1";
      const auto r = certify::surface_distance(half, eq(out), digits, false);
      SCOPED_TRACE(out + " digits " + std::to_string(digits));
      if (r.status == certify::Status::Certified) {
        EXPECT_TRUE(contains_truth(r, o.den, false)) << r.lower() << " " << r.upper();
      } else {
        EXPECT_EQ(r.status, certify::Status::Undecided) << r.note;
        EXPECT_EQ(r.upper(), "inf"); // only the implicit lower bound is established
        // No count is claimed: "minimizers": "undecided", as every answer that is not
        // certified says (json-contract.md).
        EXPECT_TRUE(r.minimizers.is_undecided()) << r.minimizers;
        ASSERT_FALSE(r.lower().empty());
        mpfr_t l, t;
        mpfr_inits2(4000, l, t, static_cast<mpfr_ptr>(nullptr));
        mpfr_set_str(l, r.lower().c_str(), 10, MPFR_RNDD);
        mpfr_set_ui(t, 4, MPFR_RNDN);
        EXPECT_LE(mpfr_cmp(l, t), 0) << r.lower(); // 4 <= the truth
        mpfr_clears(l, t, static_cast<mpfr_ptr>(nullptr));
      }
      // The mirrored sphere: its closest plane point (e, 0, 0) = P(sqrt(e), 0) is in the image.
      const std::string in = std::string("(x-") + o.text + ")^2+y^2+(z-5)^2=1";
      const auto s = certify::surface_distance(half, eq(in), digits, false);
      ASSERT_EQ(s.status, certify::Status::Certified) << in << ": " << s.note;
      EXPECT_TRUE(contains_truth(s, o.den, true)) << s.lower() << " " << s.upper();
      EXPECT_LE(surfcert::testing::log10_rel_width(s), -digits);
      EXPECT_EQ(s.minimizers, "undecided"); // never a count resting on an unproven step
    }
  }
  // The issue's own query: 30 digits, offset 1/(2*10^8): the truth 4 + 2.5e-18 is farther
  // from 4 than 30 digits allow, so no witness fits: undecided, lower bound 4.
  const auto r = certify::surface_distance(half, eq("(x+1/(2*10^8))^2+y^2+(z-5)^2=1"), 30, false);
  EXPECT_EQ(r.status, certify::Status::Undecided) << r.note;
  EXPECT_EQ(r.lower(), "4");
  EXPECT_EQ(r.upper(), "inf");
}

// The stereographic unit sphere covers the whole sphere but (0, 0, -1) (in its closure): against
// a sphere of radius 1 centred at (3, 3, 3) the minimizer (1, 1, 1)/sqrt(3) has irrational
// parameters; the witness certifies 3 sqrt(3) - 2 to 30 digits.
TEST(ParametricDistance, StereographicSphereCertifiedAgainstClosedForm) {
  const auto S = js(R"J({"type":"parametric","x":"2u","y":"2v","z":"1-u^2-v^2",)J"
                    R"J("w":"1+u^2+v^2"})J");
  const auto r = certify::surface_distance(S, eq("(x-3)^2+(y-3)^2+(z-3)^2=1"), 30, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  mpfr_t t;
  mpfr_init2(t, 4000);
  mpfr_set_ui(t, 27, MPFR_RNDN);
  mpfr_sqrt(t, t, MPFR_RNDN);
  mpfr_sub_ui(t, t, 2, MPFR_RNDN);
  EXPECT_TRUE(surfcert::testing::contains(r, t)) << r.lower() << " " << r.upper();
  mpfr_clear(t);
  EXPECT_LE(surfcert::testing::log10_rel_width(r), -30);
  EXPECT_EQ(r.minimizers, "undecided"); // one witnessed candidate, its membership not proven
  EXPECT_EQ(r.minimizer_candidates(), 1);
  // Swapped order: the same certified enclosure, pairs ordered (sphere, parametric).
  const auto w = certify::surface_distance(eq("(x-3)^2+(y-3)^2+(z-3)^2=1"), S, 30, false);
  ASSERT_EQ(w.status, certify::Status::Certified) << w.note;
  EXPECT_TRUE(surfcert::testing::overlap(r, w));
  ASSERT_EQ(w.pairs.size(), 1u);
  EXPECT_NEAR(w.pairs[0][1][0], 1 / std::sqrt(3.0), 1e-9);
}

// Issue item 7: mode and solid reach the implicit surface's routes. The stereographic unit
// sphere inside the ellipsoid x^2/16 + y^2/9 + z^2/9 = 1: surface distance 2; exact mode must
// not report a filtered-only route; the solid distance is 0 (image points lie inside the
// ellipsoid's solid).
TEST(ParametricDistance, ModeAndSolidArePassedThrough) {
  const auto S = js(R"J({"type":"parametric","x":"2u","y":"2v","z":"1-u^2-v^2",)J"
                    R"J("w":"1+u^2+v^2"})J");
  const auto E = eq("x^2/16 + y^2/9 + z^2/9 = 1");
  for (auto mode : {certify::Mode::Filtered, certify::Mode::Exact}) {
    const auto r = certify::surface_distance(S, E, 15, false, mode);
    SCOPED_TRACE(certify::to_string(mode));
    EXPECT_EQ(r.mode, mode);
    if (mode == certify::Mode::Exact) {
      EXPECT_NE(r.reduced_by, certify::Method::NestedConvexDuality) << r.note;
      EXPECT_NE(r.reduced_by, certify::Method::ConvexDuality) << r.note;
    }
    if (r.status == certify::Status::Certified) {
      EXPECT_LE(std::stod(r.lower()), 2.0);
      EXPECT_GE(std::stod(r.upper()), 2.0);
    } else {
      EXPECT_EQ(r.status, certify::Status::Undecided) << r.note;
    }
    const auto s = certify::surface_distance(S, E, 15, true, mode);
    EXPECT_TRUE(s.solid);
    ASSERT_EQ(s.status, certify::Status::Certified) << s.note;
    EXPECT_EQ(s.lower(), "0");
    EXPECT_EQ(s.upper(), "0");
    // An exact image point strictly inside the ellipsoid's solid: so are its image neighbours.
    EXPECT_EQ(s.minimizers, "infinite");
    EXPECT_EQ(s.note.find("solid applies to closed surfaces only"), std::string::npos) << s.note;
  }
  // Seed 000's parametrised ellipsoid inside x^2/4 + y^2/9 + z^2/49 = 1: the filtered mode
  // answers by nested convex duality; the exact mode must use the offset system instead.
  const auto seed = js(kSeed);
  const auto big = eq("x^2/4 + y^2/9 + z^2/49 = 1");
  const auto fe = certify::surface_distance(seed, big, 15, false, certify::Mode::Filtered);
  const auto ex = certify::surface_distance(seed, big, 15, false, certify::Mode::Exact);
  ASSERT_EQ(ex.status, certify::Status::Certified) << ex.note;
  // The answer is this route's; the implicit problem's route is reported beside it.
  EXPECT_EQ(fe.method, certify::Method::ParametricReduction);
  EXPECT_EQ(ex.method, certify::Method::ParametricReduction);
  EXPECT_EQ(fe.reduced_by, certify::Method::NestedConvexDuality);
  EXPECT_EQ(ex.reduced_by, certify::Method::OffsetSystem);
  EXPECT_EQ(ex.mode, certify::Mode::Exact);
  EXPECT_TRUE(surfcert::testing::overlap(fe, ex));
  const auto es = certify::surface_distance(seed, big, 15, true, certify::Mode::Exact);
  ASSERT_EQ(es.status, certify::Status::Certified) << es.note;
  EXPECT_EQ(es.upper(), "0");
  EXPECT_EQ(es.minimizers, "infinite");
  EXPECT_EQ(ex.minimizers, "undecided");
  EXPECT_TRUE(es.solid);
  // Filtered mode certifies the surface distance.
  const auto f = certify::surface_distance(S, E, 15, false);
  ASSERT_EQ(f.status, certify::Status::Certified) << f.note;
  EXPECT_NEAR(std::stod(f.lower()), 2.0, 1e-14);
}
