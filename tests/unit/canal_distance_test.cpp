// Certified distance between a quadric and a canal surface (seed 000 §4), each against an
// independent route:
// - capsules (segment AB, radius r) against spheres: dist(c, AB) - r - rho in closed form,
//   with the nearest point inside the segment, at an end, and with the sphere around it;
// - capsule against planes: min over the ends of the signed distance, minus r (a segment
//   parallel to the plane gives a continuum);
// - a parabolic spine with a growing radius against a sphere: a dense float search over t;
// - rigid motions of both surfaces (integer quaternions) leave the enclosure unchanged;
// - input: a capsule with equal ends, an empty interval, a radius not positive at an end.
#include "support/distance_checks.hpp"

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
core::Surface js(const std::string& json) {
  return core::io::read_surface(core::io::parse_json(json, "t"), "t", "$");
}
const char* kCapsule = R"({"type":"capsule","from":[0,0,0],"to":[4,0,0],"radius":1})";

void expect_value(const certify::DistanceResult& r, double v, const std::string& ctx) {
  ASSERT_EQ(r.status, certify::Status::Certified) << ctx << " " << r.note;
  EXPECT_LE(std::stod(r.lower()), v + 1e-14 * (1 + v)) << ctx;
  EXPECT_GE(std::stod(r.upper()), v - 1e-14 * (1 + v)) << ctx;
  EXPECT_LE(std::stod(r.upper()) - std::stod(r.lower()), 1e-14 * (1 + v)) << ctx;
}

} // namespace

TEST(CanalDistance, CapsuleAgainstSpheres) {
  auto c = js(kCapsule);
  // Foot inside the segment: |(2,5,0) - (2,0,0)| - 1 - 1.
  auto r = certify::surface_distance(eq("(x-2)^2+(y-5)^2+z^2=1"), c, 15, false);
  expect_value(r, 3.0, "inside");
  // One minimizer, proven: candidates over one isolated spine parameter are merged exactly, and
  // the foot of a spine point on a sphere (not at its centre) is unique.
  EXPECT_EQ(r.minimizers, "1");
  EXPECT_EQ(r.minimizers.proof(), certify::Minimizers::Proof::Interval);
  // Foot at the end B = (4,0,0): |(7,4,0) - B| - 2 = 3, in the end cap.
  expect_value(certify::surface_distance(eq("(x-7)^2+(y-4)^2+z^2=1"), c, 15, false), 3.0, "end");
  // Irrational: c = (-1, 1, 1): |c - A| = sqrt(3): sqrt(3) - 1 - 1/2.
  expect_value(certify::surface_distance(eq("(x+1)^2+(y-1)^2+(z-1)^2=1/4"), c, 15, false),
               std::sqrt(3.0) - 1.5, "irrational");
  // A sphere around the capsule: rho - max |c - C(t)| - r = 10 - 2 - 1 at both ends.
  auto s = certify::surface_distance(eq("(x-2)^2+y^2+z^2=100"), c, 15, false);
  expect_value(s, 7.0, "around");
  EXPECT_EQ(s.minimizers, "2");
  // Swapping the surfaces swaps the points.
  auto w = certify::surface_distance(c, eq("(x-2)^2+(y-5)^2+z^2=1"), 15, false);
  ASSERT_EQ(w.status, certify::Status::Certified);
  ASSERT_FALSE(w.pairs.empty());
  EXPECT_NEAR(w.pairs[0][0][1], 1.0, 1e-12); // on the capsule
  EXPECT_NEAR(w.pairs[0][1][1], 4.0, 1e-12); // on the sphere
  // 60 digits: the same value, width 1e-60.
  auto p = certify::surface_distance(eq("(x+1)^2+(y-1)^2+(z-1)^2=1/4"), c, 60, false);
  ASSERT_EQ(p.status, certify::Status::Certified);
  EXPECT_EQ(p.lower().substr(0, 50), p.upper().substr(0, 50));
  EXPECT_EQ(p.lower().substr(0, 20), "0.232050807568877293"); // sqrt(3) - 3/2 (bc)
}

TEST(CanalDistance, CapsuleAgainstPlanes) {
  auto c = js(kCapsule);
  auto par = certify::surface_distance(eq("y = 3"), c, 15, false); // parallel: a continuum
  expect_value(par, 2.0, "parallel");
  EXPECT_EQ(par.minimizers, "infinite");
  // Tilted: the nearer end B: (10 - 4)/sqrt(2) - 1.
  expect_value(certify::surface_distance(eq("x + y = 10"), c, 15, false), 6 / std::sqrt(2.0) - 1,
               "tilted");
  // A sphere half inside the capsule (bounded: needs certified points inside and outside).
  auto half = certify::surface_distance(eq("(x-2)^2+(y-1)^2+z^2=1/4"), c, 15, false);
  ASSERT_EQ(half.status, certify::Status::Certified) << half.note;
  EXPECT_EQ(half.upper(), "0");
  // A small sphere entirely inside the capsule: not a contact; never guessed.
  auto inside = certify::surface_distance(eq("(x-2)^2+y^2+z^2=1/16"), c, 15, false);
  EXPECT_NE(inside.upper(), "0");
  auto cut = certify::surface_distance(eq("x = 2"), c, 15, false);
  ASSERT_EQ(cut.status, certify::Status::Certified);
  EXPECT_EQ(cut.upper(), "0");
}

TEST(CanalDistance, PolynomialSpineAndRadiusAgainstFloatSearch) {
  // C(t) = (t, t^2, 0), r(t) = 1 + t/10, t in [-1, 2], against the sphere at (1, 6, 0), rho 1.
  auto k = js(R"({"type":"canal","spine":[[0,1],[0,0,1],[0]],"radius":[1,"1/10"],)"
              R"("interval":[-1,2]})");
  auto r = certify::surface_distance(eq("(x-1)^2+(y-6)^2+z^2=1"), k, 20, false);
  ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
  double best = 1e300;
  for (int i = 0; i <= 3000000; ++i) {
    double t = -1 + 3.0 * i / 3000000;
    best = std::min(best, std::hypot(t - 1, t * t - 6) - 1 - (1 + t / 10));
  }
  EXPECT_LE(std::stod(r.lower()), best);
  EXPECT_LT(best - std::stod(r.upper()), 1e-11);
  // The same pair moved by a rational rigid motion: quaternion (1, 2, 2, 1)/ 10 plus (1/3, -2, 5).
  const long R[3][3] = {{-2, 0, 10}, {10, 0, 2}, {0, 10, 0}}; // not used: see below
  (void)R;
  // Rotation matrix of (w,x,y,z) = (1,2,2,1): entries / 10.
  const long w = 1, x = 2, y = 2, z = 1, n = 10;
  const long M[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                        {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                        {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  const core::Rational tr[3] = {core::Rational(1, 3), core::Rational(-2), core::Rational(5)};
  // Spine: C'(t) = M C(t)/n + tr, coefficient by coefficient.
  const std::vector<core::Rational> cx{0, 1}, cy{0, 0, 1}, cz{0};
  std::array<std::vector<core::Rational>, 3> sp;
  for (size_t i = 0; i < 3; ++i) {
    sp[i].assign(3, core::Rational(0));
    const std::vector<core::Rational>* comp[3] = {&cx, &cy, &cz};
    for (size_t j = 0; j < 3; ++j)
      for (size_t d = 0; d < comp[j]->size(); ++d)
        sp[i][d] += core::Rational(M[i][j], n) * (*comp[j])[d];
    sp[i][0] += tr[i];
  }
  core::Surface km = core::make_canal(sp, {core::Rational(1), core::Rational(1, 10)},
                                      core::Rational(-1), core::Rational(2));
  // Sphere centre M (1,6,0)/n + tr, radius 1.
  core::Rational cm[3];
  for (size_t i = 0; i < 3; ++i)
    cm[i] = core::Rational(M[i][0] * 1 + M[i][1] * 6, n) + tr[i];
  core::Mat4 s;
  s[0][0] = s[1][1] = s[2][2] = core::Rational(1);
  core::Rational c2;
  for (size_t i = 0; i < 3; ++i) {
    s[i][3] = s[3][i] = -cm[i];
    c2 += cm[i] * cm[i];
  }
  s[3][3] = c2 - core::Rational(1);
  auto m = certify::surface_distance(core::Surface(core::QuadricMatrix(s)), km, 20, false);
  ASSERT_EQ(m.status, certify::Status::Certified) << m.note;
  EXPECT_EQ(m.lower().substr(0, 18), r.lower().substr(0, 18));
}

TEST(CanalDistance, InputErrors) {
  EXPECT_THROW(js(R"({"type":"capsule","from":[1,2,3],"to":[1,2,3],"radius":1})"),
               core::InputError);
  EXPECT_THROW(js(R"({"type":"canal","spine":[[0,1],[0],[0]],"radius":1,"interval":[2,1]})"),
               core::InputError);
  EXPECT_THROW(js(R"({"type":"canal","spine":[[0,1],[0],[0]],"radius":[1,-1],"interval":[0,2]})"),
               core::InputError);
  EXPECT_THROW(js(R"({"type":"capsule","from":[0,0,0],"to":[1,0,0],"radius":-1})"),
               core::InputError);
  // A radius vanishing inside the interval: never a guess.
  auto r = certify::surface_distance(
      eq("x^2+y^2+(z-9)^2=1"),
      js(R"({"type":"canal","spine":[[0,1],[0],[0]],"radius":["1/4",-1,1],"interval":[-2,2]})"), 15,
      false);
  EXPECT_NE(r.status, certify::Status::Certified);
}

// A spine inside an ellipsoid, through its centre along the longest axis: from (t, 0, 0) the
// nearest points are the two feet (9t/8, 0, +-sqrt(1 - 9t^2/64)) at distance sqrt(1 - t^2/8),
// smallest at the ends t = +-1: d = sqrt(7/8) - 1/10 at four pairs. Interior points of a
// non-spherical ellipsoid may have several feet, so the route must not count one pair per
// spine parameter: "4" or "undecided", never "1" or "2".
TEST(CanalDistance, SeveralFeetPerSpinePointAreNotCountedAsOne) {
  const auto c = js(R"({"type":"capsule","from":[-1,0,0],"to":[1,0,0],"radius":"1/10"})");
  const auto r = certify::surface_distance(eq("x^2/9 + y^2/4 + z^2 = 1"), c, 15, false);
  expect_value(r, std::sqrt(7.0 / 8.0) - 0.1, "inside");
  EXPECT_TRUE(r.minimizers == "4" || r.minimizers == "undecided") << r.minimizers;
}

// Feet on a singular line of the point-quadric parametrisation (canal_distance.cpp,
// singular_line_parameters). For a spine lying in a principal plane of the quadric, every
// spine point has candidate feet at alpha = -1/lambda, where I + alpha Q3 is singular; the
// (alpha, t) system loses them with the common factor it divides out. Closed forms:
//  - the cone x^2 + y^2 = z^2 and a spine point (5, t, h): dist = (sqrt(25 + t^2) - |h|)/sqrt 2
//    (the point is outside the cone), least at t = 0; at h = 0 the nearest feet are
//    (5/2, 0, +-5/2). Capsules on (5, t, 0) were certified at the ends' sqrt 13 - 1 instead of
//    5/sqrt 2 - 1. The cone x^2 + y^2 = 9/16 z^2 (slope 4/3 in (rho, z)): dist(5, 0, 0) = 4;
//  - the ellipsoid x^2/16 + y^2/9 + z^2 = 1 and the spine (t, 0, 0): the nearest feet are
//    (16t/15, 0, +-sqrt(1 - t^2/15^2 16)) at distance sqrt(1 - t^2/15); with the radius
//    1/2 - t^2 on [-1/2, 1/2], phi(t) = sqrt(1 - t^2/15) - 1/2 + t^2 is least at t = 0: 1/2
//    (the ends give sqrt(59/60) - 1/4 = 0.7416).
// The spine moved off the plane by +-1e-10, 1e-20, 2^-100 has no singular line: the main
// system finds the interior parameter; the answer must still contain the closed form.
namespace {

// a / sqrt(2) + b, and a check that r is certified, contains it and meets its width.
void expect_closed_form(const certify::DistanceResult& r, const std::string& a,
                        const std::string& b, long digits, const std::string& ctx) {
  ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
  mpfr_t x, y;
  mpfr_inits2(4000, x, y, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_str(x, a.c_str(), 10, MPFR_RNDN); // exact: short decimals or integers / 2^k
  mpfr_sqrt_ui(y, 2, MPFR_RNDN);
  mpfr_div(x, x, y, MPFR_RNDN);
  mpfr_set_str(y, b.c_str(), 10, MPFR_RNDN);
  mpfr_add(x, x, y, MPFR_RNDN);
  EXPECT_TRUE(surfcert::testing::contains(r, x))
      << ctx << ": [" << r.lower() << ", " << r.upper() << "] misses the closed form";
  EXPECT_LE(surfcert::testing::log10_rel_width(r), static_cast<double>(-digits)) << ctx;
  mpfr_clears(x, y, static_cast<mpfr_ptr>(nullptr));
}

std::string capsule(const std::string& from, const std::string& to, const std::string& r) {
  return R"({"type":"capsule","from":)" + from + R"(,"to":)" + to + R"(,"radius":")" + r + "\"}";
}

} // namespace

TEST(CanalDistance, FeetOnASingularLine) {
  const auto cone = eq("x^2 + y^2 = z^2");
  struct Case {
    std::string from, to, radius, a, b;
  };
  const std::vector<Case> cases = {
      {"[5,-1,0]", "[5,1,0]", "1", "5", "-1"},
      {"[5,-1,0]", "[5,2,0]", "1", "5", "-1"},
      {"[5,-10,0]", "[5,10,0]", "1", "5", "-1"},
      {"[5,-1,0]", "[5,1,0]", "1/2", "5", "-0.5"},
  };
  for (const Case& k : cases)
    for (bool swap : {false, true}) {
      const auto c = js(capsule(k.from, k.to, k.radius));
      const std::string ctx = k.from + "->" + k.to + " r " + k.radius + (swap ? " swapped" : "");
      const auto r = swap ? certify::surface_distance(c, cone, 20, false)
                          : certify::surface_distance(cone, c, 20, false);
      expect_closed_form(r, k.a, k.b, 20, ctx);
      // Two nearest feet of one spine point: never one minimizer.
      EXPECT_NE(r.minimizers, "1") << ctx;
    }
  // A narrower cone: dist((5, 0, 0)) = 4.
  expect_closed_form(certify::surface_distance(eq("x^2 + y^2 = 9/16 z^2"),
                                               js(capsule("[5,-1,0]", "[5,1,0]", "1")), 20, false),
                     "0", "3", 20, "9/16 cone");
  // The ellipsoid's interior minimum with a varying radius.
  const auto canal = js(
      R"({"type":"canal","spine":[[0,1],[0],[0]],"radius":["1/2",0,-1],"interval":["-1/2","1/2"]})");
  for (bool swap : {false, true}) {
    const auto e = eq("x^2/16 + y^2/9 + z^2 = 1");
    const auto r = swap ? certify::surface_distance(canal, e, 15, false)
                        : certify::surface_distance(e, canal, 15, false);
    expect_closed_form(r, "0", "0.5", 15, swap ? "ellipsoid swapped" : "ellipsoid");
    EXPECT_NE(r.minimizers, "1");
  }
}

TEST(CanalDistance, SpineJustOffASingularPlane) {
  // (5, t, h): the minimum (5 - |h|)/sqrt 2 - 1 at t = 0, h on both sides of the plane z = 0
  // (h given as exact strings: 1e-10, 1e-20, 1e-30 and 2^-100).
  const auto cone = eq("x^2 + y^2 = z^2");
  const std::vector<std::pair<std::string, long>> hs = {
      {"1e-10", 0}, {"1e-20", 0}, {"1e-30", 0}, {"1/1267650600228229401496703205376", 100}};
  int certified = 0;
  for (const auto& [h, pow2] : hs)
    for (const std::string sign : {"", "-"}) {
      const std::string z = "\"" + sign + h + "\"";
      const auto c = js(capsule("[5,-1," + z + "]", "[5,1," + z + "]", "1"));
      const auto r = certify::surface_distance(cone, c, 20, false);
      if (r.status != certify::Status::Certified) continue; // undecided is honest
      ++certified;
      mpfr_t x, y;
      mpfr_inits2(4000, x, y, static_cast<mpfr_ptr>(nullptr));
      if (pow2 > 0)
        mpfr_set_ui_2exp(y, 1, -pow2, MPFR_RNDN);
      else
        mpfr_set_str(y, h.c_str(), 10, MPFR_RNDN); // 1e-30 at 4000 bits: 2^-3900 relative
      mpfr_ui_sub(x, 5, y, MPFR_RNDN);
      mpfr_sqrt_ui(y, 2, MPFR_RNDN);
      mpfr_div(x, x, y, MPFR_RNDN);
      mpfr_sub_ui(x, x, 1, MPFR_RNDN);
      EXPECT_TRUE(surfcert::testing::contains(r, x))
          << "h = " << sign << h << ": [" << r.lower() << ", " << r.upper() << "]";
      EXPECT_NE(r.minimizers, "infinite") << "h = " << sign << h;
      mpfr_clears(x, y, static_cast<mpfr_ptr>(nullptr));
    }
  // The interior parameter is a regular critical point here: all eight are certified today.
  EXPECT_EQ(certified, 8);
}

// A plane and a canal whose (n.C')^2 = |n|^2 r'^2 holds identically: phi' = (s sigma - 1) r'
// is not zero when the spine leaves the plane as fast as its radius shrinks. Closed forms:
//  - z = 0, spine (t, 0, 5 + t^2), r = 1 - t^2 on [-1/2, 1/2]: phi = 4 + 2 t^2, 4 at t = 0,
//    one pair ((0,0,0), (0,0,4)) (was certified 4.5, 'infinite');
//  - x + 2y + 2z = 0, spine (2t, -t, 5 + t^2), r = 1 - 2t^2/3: phi = 7/3 + 4t^2/3 (was 8/3);
//  - z = 0, spine (t, 0, 5 + t), r = 1 - t on [0, 1/2]: phi = 4 + 2t, 4 at the end t = 0;
//  - z = 0, spine (0, 0, 5 + t), r = 1 + t on [0, 1]: phi = 4 for every t, but every ball
//    touches the plane's point (0, 0, 0) from (0, 0, 4): one pair, never 'infinite';
//  - z = 0, spine (t, 0, 5), r = 1: phi = 4 and the contacts move: 'infinite'.
TEST(CanalDistance, PlaneWithTheSquaredCriticalEquationIdenticallyZero) {
  struct Case {
    std::string plane, canal;
    long num, den; // the distance num / den
    bool continuum;
  };
  const std::vector<Case> cases = {
      {"z = 0",
       R"({"type":"canal","spine":[[0,1],[0],[5,0,1]],"radius":[1,0,-1],"interval":["-1/2","1/2"]})",
       4, 1, false},
      {"x + 2y + 2z = 0",
       R"({"type":"canal","spine":[[0,2],[0,-1],[5,0,1]],"radius":[1,0,"-2/3"],"interval":["-1/2","1/2"]})",
       7, 3, false},
      {"z = 0",
       R"({"type":"canal","spine":[[0,1],[0],[5,1]],"radius":[1,-1],"interval":["0","1/2"]})", 4, 1,
       false},
      {"z = 0", R"({"type":"canal","spine":[[0],[0],[5,1]],"radius":[1,1],"interval":["0","1"]})",
       4, 1, false},
      {"z = 0", R"({"type":"canal","spine":[[0,1],[0],[5]],"radius":1,"interval":["0","1"]})", 4, 1,
       true},
  };
  for (const Case& k : cases)
    for (bool swap : {false, true}) {
      const auto p = eq(k.plane);
      const auto c = js(k.canal);
      const auto r = swap ? certify::surface_distance(c, p, 20, false)
                          : certify::surface_distance(p, c, 20, false);
      const std::string ctx = k.plane + " " + k.canal + (swap ? " swapped" : "");
      ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
      mpfr_t x;
      mpfr_init2(x, 4000);
      mpfr_set_si(x, k.num, MPFR_RNDN);
      mpfr_div_si(x, x, k.den, MPFR_RNDN);
      EXPECT_TRUE(surfcert::testing::contains(r, x))
          << ctx << ": [" << r.lower() << ", " << r.upper() << "]";
      mpfr_clear(x);
      if (k.continuum)
        EXPECT_EQ(r.minimizers, "infinite") << ctx;
      else
        EXPECT_NE(r.minimizers, "infinite") << ctx;
    }
}

TEST(CanalDistance, PlaneTouchingACanalIsContactNotUndecided) {
  // The capsule (0,0,0)-(4,0,0), r = 1, against y = 1 + e: tangent along the whole segment at
  // e = 0 (was undecided: "min phi not separated from 0"), apart by e > 0 (probed at 10^-10,
  // 10^-20, 10^-30, 2^-100), cutting it for e < 0. A tilted plane touching only the end sphere
  // at B: x + y = 4 + sqrt(2) is irrational, so x + 0 y = 5 (the cap at x = 5): one contact.
  auto c = js(kCapsule);
  for (const char* e : {"0", "1/10^10", "1/10^20", "1/10^30", "1/2^64/2^36"})
    for (int sign : {1, -1}) {
      const std::string plane = std::string("y = 1 ") + (sign > 0 ? "+ " : "- ") + e;
      const auto r = certify::surface_distance(eq(plane), c, 20, false);
      ASSERT_EQ(r.status, certify::Status::Certified) << plane << ": " << r.note;
      if (sign < 0 || std::string(e) == "0") {
        EXPECT_EQ(r.upper(), "0") << plane;
        if (std::string(e) == "0") {
          EXPECT_EQ(r.minimizers, "infinite") << plane;
        }
      } else {
        EXPECT_GT(std::stod(r.lower()), 0) << plane; // apart: never contact
        mpfr_t v;
        mpfr_init2(v, 400);
        if (std::string(e) == "1/2^64/2^36") {
          mpfr_set_ui_2exp(v, 1, -100, MPFR_RNDN);
        } else {
          mpfr_set_ui(v, 10, MPFR_RNDN);
          mpfr_pow_si(v, v, -std::stol(std::string(e).substr(5)), MPFR_RNDN);
        }
        EXPECT_TRUE(surfcert::testing::contains(r, v))
            << plane << " [" << r.lower() << ", " << r.upper() << "]";
        mpfr_clear(v);
      }
    }
  const auto cap = certify::surface_distance(eq("x = 5"), c, 20, false);
  ASSERT_EQ(cap.status, certify::Status::Certified) << cap.note;
  EXPECT_EQ(cap.upper(), "0");
  // The same contact with the surfaces swapped.
  const auto sw = certify::surface_distance(c, eq("y = 1"), 20, false);
  ASSERT_EQ(sw.status, certify::Status::Certified) << sw.note;
  EXPECT_EQ(sw.upper(), "0");
}
