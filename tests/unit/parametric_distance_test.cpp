// Certified distance from a rational parametric surface (to its closure: the points the
// parametrisation misses count), against independent routes: seed 000's parametrised ellipsoid
// (2u, 4v, -6(u^2+v^2)) / (1+u^2+v^2) must give exactly the implicit pair's enclosure
// (0.5302293602...), and its missed point (0, 0, -6) must be found; a sphere below the
// ellipsoid is closest to exactly that missed point (closed form 1); the implicit equation found
// by linear algebra is checked on random parameter values; a cubic parametrisation is refused.
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/distance/parametric_distance.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <gtest/gtest.h>

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
  EXPECT_EQ(r.lower, i.lower);
  EXPECT_EQ(r.upper, i.upper);
  EXPECT_EQ(r.minimizers, "2");
  EXPECT_NE(r.note.find("misses (0, 0, -6) (not a minimizer)"), std::string::npos) << r.note;
  // A sphere of radius 1 centred at (0, 0, -8): the closest point is the missed one, d = 1.
  auto s = certify::surface_distance(p, eq("x^2 + y^2 + (z+8)^2 = 1"), 15, false);
  ASSERT_EQ(s.status, certify::Status::Certified) << s.note;
  EXPECT_NEAR(std::stod(s.lower), 1.0, 1e-15);
  EXPECT_NE(s.note.find("a minimizer is that missed point"), std::string::npos) << s.note;
  // Swapped order: same value.
  auto w = certify::surface_distance(eq("x^2 + y^2 + (z+8)^2 = 1"), p, 15, false);
  EXPECT_EQ(w.lower, s.lower);
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
  // A cubic parametrisation: not a quadric, never guessed.
  auto c = certify::surface_distance(js(R"({"type":"parametric","x":"u","y":"v","z":"u^3"})"),
                                     eq("x^2+y^2+(z-5)^2=1"), 15, false);
  EXPECT_NE(c.status, certify::Status::Certified);
  // (u^2, v, 0) covers only the half-plane x >= 0 of z = 0: a sphere meeting the plane at
  // x = -3 must not be reported at distance 0 (the image is 2 away); one above x = 3 is 4 away.
  auto half = js(R"({"type":"parametric","x":"u^2","y":"v","z":"0"})");
  auto h0 = certify::surface_distance(half, eq("(x+3)^2+y^2+z^2=1"), 15, false);
  EXPECT_NE(h0.status, certify::Status::Certified) << h0.note;
  auto h4 = certify::surface_distance(half, eq("(x-3)^2+y^2+(z-5)^2=1"), 15, false);
  ASSERT_EQ(h4.status, certify::Status::Certified) << h4.note;
  EXPECT_NEAR(std::stod(h4.lower), 4.0, 1e-15);
  EXPECT_THROW(js(R"({"type":"parametric","x":"x","y":"v","z":"u"})"), core::InputError);
  EXPECT_THROW(js(R"({"type":"parametric","x":"u","y":"v"})"), core::InputError);
}
