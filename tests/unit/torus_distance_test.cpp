// Certified distance between a quadric and a ring torus, each against an independent route:
// - sphere vs torus in closed form: centre on the axis, sqrt(R^2 + h^2) - r - rho (a circle of
//   minimizers); centre in the torus plane, |c| - R - r - rho; centre on the core circle;
// - plane vs torus: (|n.c - delta| - R |n x a|/|a|) / |n| - r, exact touching;
// - ellipsoid vs torus: a float search (sampling both surfaces) never finds a closer pair and
//   comes close; rational rigid motions (integer quaternions) leave the enclosure unchanged;
// - contact: an ellipsoid crossing the tube gives 0 with a witness on both surfaces;
// - input: spindle tori and zero axes are refused with a location.
#include "surfcert/app/scene.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace surfcert;

namespace {

core::Surface eq(const std::string& s) {
  return core::io::quadric_from_equation(s, {"t", 1, 1, ""});
}
core::Surface torus(const std::string& json) {
  return core::io::read_surface(core::io::parse_json(json, "t"), "t", "$");
}
const char* kTorus = R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,)"
                     R"("minor_radius":1})";

double lo(const certify::DistanceResult& r) {
  return std::stod(r.lower());
}
double hi(const certify::DistanceResult& r) {
  return std::stod(r.upper());
}

void expect_value(const certify::DistanceResult& r, double v, const std::string& ctx) {
  ASSERT_EQ(r.status, certify::Status::Certified) << ctx << " " << r.note;
  EXPECT_LE(lo(r), v + 1e-14 * (1 + v)) << ctx;
  EXPECT_GE(hi(r), v - 1e-14 * (1 + v)) << ctx;
  EXPECT_LE(hi(r) - lo(r), 1e-14 * (1 + v)) << ctx;
}

// Rotation matrix of the integer quaternion (w, x, y, z), scaled by n = w^2+x^2+y^2+z^2.
std::array<std::array<long, 3>, 3> rot(long w, long x, long y, long z) {
  return {{{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}}};
}

} // namespace

TEST(TorusDistance, SphereClosedForms) {
  auto t = torus(kTorus);
  // Centre on the axis at height 5, radius 1: sqrt(9 + 25) - 1 - 1, a circle of minimizers.
  auto r = certify::surface_distance(eq("x^2+y^2+(z-5)^2=1"), t, 15, false);
  expect_value(r, std::sqrt(34.0) - 2, "on axis");
  EXPECT_EQ(r.minimizers, "infinite");
  // In the hole (centre on the axis, in the plane): 3 - 1 - 1/2.
  expect_value(certify::surface_distance(eq("x^2+y^2+z^2=1/4"), t, 15, false), 1.5, "hole");
  // Centre in the torus plane, outside: |c| - R - r - rho = 10 - 3 - 1 - 2.
  auto s = certify::surface_distance(eq("(x-6)^2+(y-8)^2+z^2=4"), t, 15, false);
  expect_value(s, 4.0, "in plane");
  EXPECT_EQ(s.minimizers, "1");
  ASSERT_EQ(s.pairs.size(), 1u);
  EXPECT_NEAR(s.pairs[0][0][0], 4.8, 1e-12); // on the sphere
  EXPECT_NEAR(s.pairs[0][1][1], 3.2, 1e-12); // on the torus (4/5 of (4, 0)... (2.4, 3.2, 0))
  // Centre on the core circle, inside the tube: r - rho, a circle of minimizers.
  auto c = certify::surface_distance(eq("(x-3)^2+y^2+z^2=1/16"), t, 15, false);
  expect_value(c, 0.75, "on K");
  EXPECT_EQ(c.minimizers, "infinite");
  // A sphere around the whole torus: rho - (|c| + R + r) with c = 0: 10 - 4.
  expect_value(certify::surface_distance(eq("x^2+y^2+z^2=100"), t, 15, false), 6.0, "around");
  // Crossing: 0.
  auto m = certify::surface_distance(eq("(x-3)^2+y^2+(z-1)^2=1"), t, 15, false);
  ASSERT_EQ(m.status, certify::Status::Certified);
  EXPECT_EQ(m.upper(), "0");
  // 100 digits: the closed form sqrt(34) - 2 to 100 digits (computed by bc: sqrt(34)).
  auto p = certify::surface_distance(eq("x^2+y^2+(z-5)^2=1"), t, 100, false);
  ASSERT_EQ(p.status, certify::Status::Certified);
  // sqrt(34) - 2 from bc ("scale=95; sqrt(34)" gives 5.83095189484530047087415287754558...).
  const std::string s34 = "3.830951894845300470874152877545583076521398334885971954450006744867"
                          "81006199671262766524032645303";
  EXPECT_EQ(p.lower().substr(0, 90), s34.substr(0, 90));
}

TEST(TorusDistance, SphereCentreJustOffTheAxisHasItsPairOnItsSide) {
  // Centre (e, 0, 1/3), radius 1/2, e = +-1e-10 ... +-2^-100: one minimizer (the meridian
  // through the centre), d = sqrt((3 - |e|)^2 + 1/9) - 3/2. The approximate pair must be the
  // closest pair: the torus point was read from balls where |w|^2 - h^2 cancelled, and came
  // out 1.9 off the torus (the two points 0.37 apart) from e = 1e-20 down. Checked against the
  // closed form: the torus point on the torus, the sphere point on the sphere, their distance
  // the certified one, both on the side of x = 0 the centre is on.
  auto t = torus(kTorus);
  const std::pair<const char*, double> offsets[] = {
      {"1/10000000000", 1e-10},
      {"1/100000000000000000000", 1e-20},
      {"1/10^30", 1e-30},
      {"1/1267650600228229401496703205376", 0x1p-100}};
  for (const auto& [e, ev] : offsets)
    for (int sg : {1, -1}) {
      const std::string x = std::string(sg < 0 ? "-" : "") + "(" + e + ")";
      const std::string ctx = std::string("x0 = ") + x;
      auto r = certify::surface_distance(eq("(x - " + x + ")^2 + y^2 + (z - 1/3)^2 = 1/4"), t, 15,
                                         false);
      const double d = std::sqrt((3 - ev) * (3 - ev) + 1.0 / 9) - 1.5;
      const double cx = sg * ev;
      expect_value(r, d, ctx);
      EXPECT_EQ(r.minimizers, "1") << ctx;
      ASSERT_EQ(r.pairs.size(), 1u) << ctx;
      const auto& s = r.pairs[0][0];
      const auto& k = r.pairs[0][1];
      const double rho = std::hypot(k[0], k[1]);
      EXPECT_NEAR(std::hypot(rho - 3, k[2]), 1.0, 1e-12) << ctx;                   // on the torus
      EXPECT_NEAR(std::hypot(s[0] - cx, s[1], s[2] - 1.0 / 3), 0.5, 1e-12) << ctx; // on the sphere
      EXPECT_NEAR(std::hypot(k[0] - s[0], k[1] - s[1], k[2] - s[2]), d, 1e-12) << ctx;
      EXPECT_GT(sg * k[0], 2.0) << ctx;
      EXPECT_GT(sg * s[0], 0.4) << ctx;
    }
}

TEST(TorusDistance, PlaneClosedFormsAndTouching) {
  auto t = torus(kTorus);
  expect_value(certify::surface_distance(eq("z = 5"), t, 15, false), 4.0, "z=5");
  expect_value(certify::surface_distance(eq("x + z = 10"), t, 15, false), 7 / std::sqrt(2.0) - 1,
               "x+z=10");
  expect_value(certify::surface_distance(eq("x + y + z = 7"), t, 15, false),
               (7 - 3 * std::sqrt(2.0)) / std::sqrt(3.0) - 1, "x+y+z=7");
  for (const char* touching : {"z = 1", "x = 4", "z = -1"}) {
    auto r = certify::surface_distance(eq(touching), t, 15, false);
    ASSERT_EQ(r.status, certify::Status::Certified) << touching;
    EXPECT_EQ(r.upper(), "0") << touching;
    EXPECT_NE(r.note.find("touches"), std::string::npos) << touching;
  }
  auto cut = certify::surface_distance(eq("x = 7/2"), t, 15, false);
  EXPECT_NE(cut.note.find("cuts"), std::string::npos);
}

TEST(TorusDistance, EllipsoidAgainstFloatSearchAndRigidMotions) {
  // The ellipsoid (semi-axes 1, 2, 3/2) centred at (1, 2, 4), tilted torus axis (1, 2, 2).
  const char* tj = R"({"type":"torus","center":[0,0,0],"axis":[1,2,2],"major_radius":3,)"
                   R"("minor_radius":"1/2"})";
  auto r =
      certify::surface_distance(eq("(x-1)^2 + (y-2)^2/4 + 4*(z-4)^2/9 = 1"), torus(tj), 15, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  EXPECT_LE((hi(r) - lo(r)) / lo(r), 1e-14);
  // Exact mode: the offset system itself (the default mode answers by the circle bound),
  // with the seed 000 Table 1 torus degrees, and the same enclosure.
  auto ex = certify::surface_distance(eq("(x-1)^2 + (y-2)^2/4 + 4*(z-4)^2/9 = 1"), torus(tj), 15,
                                      false, certify::Mode::Exact);
  ASSERT_EQ(ex.status, certify::Status::Certified) << ex.note;
  EXPECT_EQ(ex.system_degrees, (std::vector<long>{2, 2, 4}));
  EXPECT_EQ(ex.method, certify::Method::OffsetSystem);
  EXPECT_LE(lo(ex), hi(r));
  EXPECT_LE(lo(r), hi(ex));
  // Float search: ellipsoid samples against the torus distance |dist(x, K) - r|.
  double best = 1e300;
  const double an = 3;
  for (int i = 0; i <= 400; ++i)
    for (int j = 0; j < 800; ++j) {
      double th = M_PI * i / 400, ph = M_PI * j / 400;
      double x = 1 + std::sin(th) * std::cos(ph), y = 2 + 2 * std::sin(th) * std::sin(ph),
             z = 4 + 1.5 * std::cos(th);
      double h = (x + 2 * y + 2 * z) / an,
             rho = std::sqrt(std::max(0.0, x * x + y * y + z * z - h * h));
      best = std::min(best, std::fabs(std::hypot(rho - 3, h) - 0.5));
    }
  EXPECT_LE(lo(r), best);
  EXPECT_LT(best - hi(r), 1e-3);
  // Rigid motions: rotate and translate both surfaces exactly; same enclosure.
  for (auto q : std::vector<std::array<long, 4>>{{1, 2, 2, 1}, {3, -1, 4, 2}}) {
    auto R = rot(q[0], q[1], q[2], q[3]);
    const long n = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    const core::Rational tr[3] = {core::Rational(1, 3), core::Rational(-2), core::Rational(5, 7)};
    // Ellipsoid: the congruence by the inverse motion.
    core::Mat4 P;
    for (size_t i = 0; i < 3; ++i) {
      core::Rational s;
      for (size_t j = 0; j < 3; ++j) {
        P[i][j] = core::Rational(R[j][i], static_cast<unsigned long>(n));
        s += P[i][j] * tr[j];
      }
      P[i][3] = -s;
    }
    P[3][3] = core::Rational(1);
    auto e = std::get<core::QuadricMatrix>(eq("(x-1)^2 + (y-2)^2/4 + 4*(z-4)^2/9 = 1"));
    auto em = e.congruent(P);
    // Torus: centre R 0 + t, axis R (1, 2, 2).
    std::array<core::Rational, 3> ax{}, ce{};
    const long a[3] = {1, 2, 2};
    for (size_t i = 0; i < 3; ++i) {
      for (size_t j = 0; j < 3; ++j)
        ax[i] += core::Rational(R[i][j] * a[j], static_cast<unsigned long>(n));
      ce[i] = tr[i];
    }
    core::Surface tm = core::make_torus(ce, ax, core::Rational(3), core::Rational(1, 2));
    auto m = certify::surface_distance(core::Surface(em), tm, 15, false);
    ASSERT_EQ(m.status, certify::Status::Certified) << m.note;
    EXPECT_NEAR(lo(m), lo(r), 1e-14 * lo(r));
    EXPECT_NEAR(hi(m), hi(r), 1e-14 * lo(r));
    // Swapping the surfaces keeps the value and swaps the points.
    auto sw = certify::surface_distance(tm, core::Surface(em), 15, false);
    ASSERT_EQ(sw.status, certify::Status::Certified) << sw.note;
    EXPECT_EQ(sw.lower(), m.lower());
    ASSERT_FALSE(sw.pairs.empty());
    ASSERT_FALSE(m.pairs.empty());
    for (size_t i = 0; i < 3; ++i)
      EXPECT_NEAR(sw.pairs[0][0][i], m.pairs[0][1][i], 1e-9);
  }
}

TEST(TorusDistance, CoaxialSurfacesOfRevolution) {
  // A circle of minimizers with the distance still certified (the meridian problem).
  auto t = torus(kTorus);
  auto c = certify::surface_distance(eq("x^2 + y^2 = 25"), t, 15, false); // 5 - 3 - 1
  expect_value(c, 1.0, "cylinder around");
  EXPECT_EQ(c.minimizers, "infinite");
  expect_value(certify::surface_distance(eq("x^2 + y^2 = 1"), t, 15, false), 1.0, "cyl inside");
  expect_value(certify::surface_distance(eq("x^2 + y^2 + z^2/4 = 1"), t, 15, false), 1.0,
               "spheroid in the hole");
  // Paraboloid z = rho^2/8 + 2 over the torus: the float search in the meridian plane.
  auto p = certify::surface_distance(eq("z = (x^2 + y^2)/8 + 2"), t, 15, false);
  ASSERT_EQ(p.status, certify::Status::Certified) << p.note;
  double best = 1e300;
  for (int i = 0; i <= 2000000; ++i) {
    double rho = 6.0 * i / 2000000, z = rho * rho / 8 + 2;
    best = std::min(best, std::hypot(rho - 3, z) - 1);
  }
  EXPECT_LE(lo(p), best);
  EXPECT_LT(best - hi(p), 1e-9);
  EXPECT_EQ(p.minimizers, "infinite");
  // Entering the tube: 0. Touching along a circle (x^2/4 + y^2/4 + z^2 = 1 reaches the inner
  // equator rho = 2): never a guess.
  auto m = certify::surface_distance(eq("z = x^2 + y^2 - 9"), t, 15, false);
  EXPECT_EQ(m.upper(), "0");
  auto tt = certify::surface_distance(eq("x^2/4 + y^2/4 + z^2 = 1"), t, 15, false);
  EXPECT_NE(tt.status, certify::Status::Certified);
}

TEST(TorusDistance, ContactAndInput) {
  auto t = torus(kTorus);
  // The ellipsoid x^2/9 + y^2/16 + z^2 = 1 runs inside the tube at z = 0 and above the hole:
  // it crosses the torus; the witness lies on both surfaces (approximately).
  auto r = certify::surface_distance(eq("x^2/9 + y^2/16 + z^2 = 1"), t, 15, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  EXPECT_EQ(r.upper(), "0");
  ASSERT_EQ(r.pairs.size(), 1u);
  const auto& w = r.pairs[0][0];
  EXPECT_NEAR(w[0] * w[0] / 9 + w[1] * w[1] / 16 + w[2] * w[2], 1.0, 1e-9);
  EXPECT_NEAR(std::hypot(std::hypot(w[0], w[1]) - 3, w[2]), 1.0, 1e-9);
  // A paraboloid through the hole meets the torus only if it enters the tube: z = x^2 + y^2 - 9
  // passes through the core circle.
  auto p = certify::surface_distance(eq("z = x^2 + y^2 - 9"), t, 15, false);
  ASSERT_EQ(p.status, certify::Status::Certified) << p.note;
  EXPECT_EQ(p.upper(), "0");
  // Input errors: a spindle torus and a zero axis, with their JSON path.
  try {
    torus(R"({"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":1,"minor_radius":2})");
    FAIL() << "spindle torus accepted";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("major_radius"), std::string::npos) << e.what();
  }
  try {
    torus(R"({"type":"torus","center":[0,0,0],"axis":[0,0,0],"major_radius":3,"minor_radius":1})");
    FAIL() << "zero axis accepted";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("axis"), std::string::npos) << e.what();
  }
}

TEST(TorusDistance, BatchAndSceneContract) {
  // A batch line with a torus: the distance envelope; classify with a torus: an input error at
  // $.a, the batch goes on.
  auto ok = app::process_batch_line(
      R"({"id":7,"op":"distance","a":{"type":"torus","center":[0,0,0],"axis":[0,0,1],)"
      R"("major_radius":3,"minor_radius":1},"b":"z = 5","digits":20})",
      1, certify::Mode::Filtered);
  EXPECT_EQ(ok.find("status")->text(), "certified");
  EXPECT_EQ(ok.find("result")->find("distance")->find("lower")->text(), "4");
  auto bad = app::process_batch_line(
      R"({"op":"classify","a":{"type":"torus","center":[0,0,0],"axis":[0,0,1],)"
      R"("major_radius":3,"minor_radius":1},"b":"z = 5"})",
      2, certify::Mode::Filtered);
  EXPECT_EQ(bad.find("status")->text(), "error");
  EXPECT_EQ(bad.find("error")->find("json_path")->text(), "$.a");
  // A scene naming a torus: distance accepted; intersect refused on reading (nothing runs).
  auto doc = core::io::parse_json(
      R"({"surfaces":{"T":{"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,)"
      R"("minor_radius":1},"P":"z = 5"},"queries":[{"op":"distance","a":"P","b":"T"}]})",
      "scene");
  auto scene = app::read_scene(doc, "scene", certify::Mode::Filtered);
  auto res = app::run_query(scene, scene.queries[0]);
  EXPECT_EQ(res.find("result")->find("distance")->find("upper")->text(), "4");
  // A scene query's "digits" is honoured (it was ignored before this test existed).
  auto doc3 = core::io::parse_json(
      R"({"surfaces":{"S":"x^2+y^2+z^2=1","P":"x+y+z=3"},"queries":[{"op":"distance",)"
      R"("a":"S","b":"P","digits":40}]})",
      "scene");
  auto scene3 = app::read_scene(doc3, "scene", certify::Mode::Filtered);
  EXPECT_EQ(scene3.queries[0].digits, 40);
  auto r3 = app::run_query(scene3, scene3.queries[0]);
  EXPECT_GE(r3.find("result")->find("distance")->find("lower")->text().size(), 40u);
  auto doc2 = core::io::parse_json(
      R"({"surfaces":{"T":{"type":"torus","center":[0,0,0],"axis":[0,0,1],"major_radius":3,)"
      R"("minor_radius":1},"P":"z = 5"},"queries":[{"op":"intersect","a":"P","b":"T"}]})",
      "scene");
  EXPECT_THROW(app::read_scene(doc2, "scene", certify::Mode::Filtered), core::InputError);
}
