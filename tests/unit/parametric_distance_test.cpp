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
  EXPECT_EQ(r.lower(), i.lower());
  EXPECT_EQ(r.upper(), i.upper());
  EXPECT_EQ(r.minimizers, "2");
  EXPECT_NE(r.note.find("misses (0, 0, -6) (not a minimizer)"), std::string::npos) << r.note;
  // A sphere of radius 1 centred at (0, 0, -8): the closest point is the missed one, d = 1.
  auto s = certify::surface_distance(p, eq("x^2 + y^2 + (z+8)^2 = 1"), 15, false);
  ASSERT_EQ(s.status, certify::Status::Certified) << s.note;
  EXPECT_NEAR(std::stod(s.lower()), 1.0, 1e-15);
  EXPECT_NE(s.note.find("a minimizer is that missed point"), std::string::npos) << s.note;
  // Swapped order: same value.
  auto w = certify::surface_distance(eq("x^2 + y^2 + (z+8)^2 = 1"), p, 15, false);
  EXPECT_EQ(w.lower(), s.lower());
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
  // (u^2, v, 0) covers only the half-plane x >= 0 of z = 0: a sphere meeting the plane at
  // x = -3 must not be reported at distance 0 (the image is 2 away); one above x = 3 is 4 away.
  auto half = js(R"({"type":"parametric","x":"u^2","y":"v","z":"0"})");
  auto h0 = certify::surface_distance(half, eq("(x+3)^2+y^2+z^2=1"), 15, false);
  EXPECT_NE(h0.status, certify::Status::Certified) << h0.note;
  auto h4 = certify::surface_distance(half, eq("(x-3)^2+y^2+(z-5)^2=1"), 15, false);
  ASSERT_EQ(h4.status, certify::Status::Certified) << h4.note;
  EXPECT_NEAR(std::stod(h4.lower()), 4.0, 1e-15);
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
}
