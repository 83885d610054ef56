// Shapes posed in doubles (core/shape.hpp): the reader keeps the doubles and forms the exact
// matrix lazily; the filter decides from interval enclosures computed from the doubles
// (certify/enclosure.hpp). Checked against independent routes:
// - the lazy matrix equals the matrix of the same shape given as exact decimal strings (the
//   reader's exact path, which never builds a ShapeSpec);
// - every exact entry lies inside its enclosure, at ordinary scales and at 1e-300 ... 1e300
//   and subnormal sizes (where the enclosure may be infinite, never wrong);
// - on random double ellipsoid pairs the filtered answer (morphology, relation, containment)
//   equals the exact one, at topology detail (no exact report data) and at full detail;
// - pairs that are exactly tangent in doubles make the filter fall back, and the exact answer
//   is the tangency; gaps of 2^-10 ... 2^-52 (relative) and absolute scales down to 2^-100 on
//   both sides are certified with the right relation.
#include "support/canonical.hpp"
#include "surfcert/certify/distance/convex_quadric.hpp"
#include "surfcert/certify/enclosure.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <CGAL/FPU.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace surfcert;
using certify::Mode;
using core::Rational;
using surfcert::testing::test_seed;

namespace {

const char* kTypes[] = {"sphere",
                        "ellipsoid",
                        "cylinder",
                        "cone",
                        "elliptic_paraboloid",
                        "hyperbolic_paraboloid",
                        "hyperboloid_one_sheet",
                        "hyperboloid_two_sheets"};

std::string num(double x, bool as_string) {
  if (as_string) return "\"" + Rational::exact_from_double(x).to_string() + "\"";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0"; // a double literal
  return s;
}

struct Shape {
  std::string type;
  double radii[3], center[3], quat[4];
  bool rotated;
  std::string json(bool as_string) const {
    std::string s = "{\"type\": \"" + type + "\", ";
    if (type == "sphere") {
      s += "\"radius\": " + num(radii[0], as_string);
    } else {
      const bool three = type == "ellipsoid" || type == "cone" || type.rfind("hyperboloid", 0) == 0;
      s += "\"radii\": [" + num(radii[0], as_string) + ", " + num(radii[1], as_string) +
           (three ? ", " + num(radii[2], as_string) : std::string()) + "]";
    }
    s += ", \"center\": [" + num(center[0], as_string) + ", " + num(center[1], as_string) + ", " +
         num(center[2], as_string) + "]";
    if (rotated)
      s += ", \"rotation\": {\"quaternion\": [" + num(quat[0], as_string) + ", " +
           num(quat[1], as_string) + ", " + num(quat[2], as_string) + ", " +
           num(quat[3], as_string) + "]}";
    return s + "}";
  }
};

core::QuadricMatrix read(const std::string& text) {
  return core::io::read_quadric(core::io::parse_json(text, "test"), "test", "$");
}

Shape random_shape(std::mt19937_64& rng, const std::string& type, double scale) {
  std::uniform_real_distribution<double> c(-0.5, 0.5), r(0.1, 1.0);
  std::normal_distribution<double> g;
  Shape s;
  s.type = type;
  for (int i = 0; i < 3; ++i) {
    s.radii[i] = r(rng) * scale;
    s.center[i] = c(rng) * scale;
  }
  double n = 0;
  for (double& q : s.quat) {
    q = g(rng);
    n += q * q;
  }
  for (double& q : s.quat)
    q /= std::sqrt(n);
  s.rotated = rng() % 4 != 0;
  return s;
}

// lo <= x <= hi for the exact x (an infinite bound always holds).
bool contains(const certify::Interval& iv, const Rational& x) {
  const bool lo_ok = std::isinf(iv.inf()) || Rational::exact_from_double(iv.inf()) <= x;
  const bool hi_ok = std::isinf(iv.sup()) || x <= Rational::exact_from_double(iv.sup());
  return lo_ok && hi_ok;
}

} // namespace

TEST(DoubleShape, LazyMatrixEqualsTheExactReading) {
  std::mt19937_64 rng(test_seed());
  for (int it = 0; it < 80; ++it) {
    const Shape s = random_shape(rng, kTypes[it % 8], 1.0);
    const auto lazy = read(s.json(false));
    const auto exact = read(s.json(true));
    ASSERT_NE(lazy.shape(), nullptr) << s.json(false);
    ASSERT_EQ(exact.shape(), nullptr) << s.json(true);
    EXPECT_EQ(lazy.kind(), exact.kind()) << s.json(false); // kind from the type vs exact
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        EXPECT_EQ(lazy(i, j), exact(i, j)) << s.json(false) << " entry " << i << j;
  }
}

// congruence(p, m) (upper triangle, zeros skipped) against the plain products, on random
// symmetric matrices and random p with zero entries; and QuadricMatrix::translated against
// the congruence by the translation: a shape whose centre minus c is a double stays a lazy
// shape with the same exact matrix, otherwise the matrix is the congruence's.
TEST(DoubleShape, TranslatedAndCongruenceEqualThePlainProducts) {
  std::mt19937_64 rng(test_seed());
  std::uniform_int_distribution<long> small(-7, 7);
  for (int it = 0; it < 40; ++it) {
    core::Mat4 m, p;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j)
        m[i][j] = m[j][i] = Rational(small(rng), 1 + std::abs(small(rng)));
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        if (rng() % 3 != 0) p[i][j] = Rational(small(rng), 1 + std::abs(small(rng)));
    const core::Mat4 want = core::transpose(p) * m * p, got = core::congruence(p, m);
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        EXPECT_EQ(got[i][j], want[i][j]) << it << " entry " << i << j;
  }
  for (int it = 0; it < 48; ++it) {
    const Shape s = random_shape(rng, kTypes[it % 8], 1.0);
    const auto q = read(s.json(false));
    // Small dyadic shifts (multiples of 2^-24 below 2^-21, like the tracer's) of centres of
    // magnitude >= 2^-20 are exact in double, so the shape stays; 1/3 (a double with 53
    // significant bits) against centres with bits down to 2^-54 is not, nor an integer shift
    // (the centre's low bits are lost): the congruence is formed, with the same matrix.
    std::array<double, 3> c{};
    const int route = it % 3;
    bool keeps = route == 0;
    for (size_t k = 0; k < 3; ++k) {
      c[k] = route == 0   ? std::ldexp(static_cast<double>(small(rng)), -24)
             : route == 1 ? (k + 1.0) / 3.0
                          : static_cast<double>(small(rng)) + 0.5;
      keeps = keeps && std::fabs(s.center[k]) >= std::ldexp(1.0, -20);
    }
    const auto moved = q.translated(c);
    core::Mat4 t = core::identity4();
    for (size_t k = 0; k < 3; ++k)
      t[k][3] = Rational::exact_from_double(c[k]);
    const core::Mat4 want = core::transpose(t) * q.matrix() * t;
    if (keeps) {
      EXPECT_NE(moved.shape(), nullptr) << s.json(false);
    }
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        EXPECT_EQ(moved.matrix()[i][j], want[i][j]) << s.json(false) << " entry " << i << j;
  }
}

TEST(DoubleShape, EnclosureHoldsTheExactMatrixAtEveryScale) {
  std::mt19937_64 rng(test_seed() + 1);
  int finite = 0, total = 0;
  for (double scale : {1.0, 1e-300, 1e-150, 1e-30, 1e30, 1e150, 1e300, 4.9e-324 * 1e10}) {
    for (int it = 0; it < 16; ++it) {
      const Shape s = random_shape(rng, kTypes[it % 8], scale);
      const auto q = read(s.json(false));
      ASSERT_NE(q.shape(), nullptr);
      CGAL::Protect_FPU_rounding<true> guard;
      const certify::IMat4 e = certify::enclose(q);
      for (size_t i = 0; i < 4; ++i)
        for (size_t j = 0; j < 4; ++j) {
          ++total;
          finite += std::isfinite(e[i][j].inf()) && std::isfinite(e[i][j].sup());
          EXPECT_TRUE(contains(e[i][j], q.matrix()[i][j]))
              << s.json(false) << " entry " << i << j << " [" << e[i][j].inf() << ", "
              << e[i][j].sup() << "]";
        }
    }
  }
  EXPECT_GT(finite, total / 2); // ordinary scales give finite enclosures
}

TEST(DoubleShape, FilterOnDoublesAgreesWithExact) {
  std::mt19937_64 rng(test_seed() + 2);
  int fallbacks = 0, relations = 0;
  const int n = 400;
  for (int it = 0; it < n; ++it) {
    const Shape sa = random_shape(rng, "ellipsoid", 1.0);
    const Shape sb = random_shape(rng, it % 5 == 0 ? kTypes[rng() % 8] : "ellipsoid", 1.0);
    const std::string what = sa.json(false) + " / " + sb.json(false);
    // Fresh (lazy) quadrics per mode, so the filtered run cannot profit from a formed matrix.
    const auto fa = read(sa.json(false)), fb = read(sb.json(false));
    auto f = certify::classify_qsic(fa, fb, Mode::Filtered);
    certify::complete_report_data(f, fa, fb, certify::Detail::Topology);
    const auto ea = read(sa.json(true)), eb = read(sb.json(true));
    auto e = certify::classify_qsic(ea, eb, Mode::Exact);
    certify::complete_report_data(e, ea, eb, certify::Detail::Full);
    ASSERT_EQ(f.status, certify::Status::Certified) << what;
    ASSERT_EQ(e.status, certify::Status::Certified) << what;
    EXPECT_EQ(f.tu_case, e.tu_case) << what;
    EXPECT_EQ(f.segre, e.segre) << what;
    EXPECT_EQ(f.ellipsoid_relation, e.ellipsoid_relation) << what;
    EXPECT_EQ(f.containment, e.containment) << what;
    fallbacks += f.exact_fallback;
    relations += !e.ellipsoid_relation.empty();
  }
  EXPECT_LT(fallbacks, n / 20); // random pairs are decided by the filter
  EXPECT_GT(relations, n / 2);
}

TEST(DoubleShape, TangentPairsFallBackAndGapsAreCertified) {
  // Two spheres of radius s at distance 2s (1 + g): tangent for g = 0, apart for g > 0,
  // overlapping for g < 0. g = +-2^-k, k = 10 ... 52 (the relative gaps a double centre can
  // carry) at scales s = 1 and 2^-100 (absolute gaps down to 2^-152).
  for (double s : {1.0, std::ldexp(1.0, -100), std::ldexp(1.0, 100)}) {
    for (int k : {0, 10, 20, 30, 40, 52}) {
      for (int side : {-1, 1}) {
        const double g = k == 0 ? 0.0 : side * std::ldexp(1.0, -k);
        if (k == 0 && side < 0) continue;
        const double cx = 2 * s * (1 + g);
        ASSERT_EQ((cx / (2 * s)) - 1, g); // the gap is exactly representable
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "{\"type\": \"sphere\", \"radius\": %.17g, \"center\": [%.17g, 0.0, 0.0]}", s,
                      cx);
        char unit[200];
        std::snprintf(unit, sizeof unit, "{\"type\": \"sphere\", \"radius\": %.17g}", s);
        const std::string what = std::string(buf) + " k " + std::to_string(k);
        for (Mode m : {Mode::Filtered, Mode::Exact}) {
          const auto a = read(unit), b = read(buf);
          auto r = certify::classify_qsic(a, b, m);
          certify::complete_report_data(r, a, b, certify::Detail::Topology);
          ASSERT_EQ(r.status, certify::Status::Certified) << what;
          const char* expect = g == 0 ? "externally_touching" : g > 0 ? "separated" : "overlapping";
          EXPECT_EQ(r.ellipsoid_relation, expect) << what << " " << certify::to_string(m);
          if (m == Mode::Filtered && g == 0) {
            EXPECT_TRUE(r.exact_fallback) << what;
          }
        }
      }
    }
  }
  // Internally touching: the unit sphere in the ellipsoid with radii (1, 2, 3), both rotated
  // by the same double quaternion (the contact points move with them).
  const auto e = read(R"({"type": "ellipsoid", "radii": [1.0, 2.0, 3.0],
      "rotation": {"quaternion": [0.5, 0.5, 0.5, 0.5]}})");
  const auto u = read(R"({"type": "sphere", "radius": 1.0})");
  for (Mode m : {Mode::Filtered, Mode::Exact}) {
    auto r = certify::classify_qsic(u, e, m);
    certify::complete_report_data(r, u, e, certify::Detail::Topology);
    ASSERT_EQ(r.status, certify::Status::Certified);
    EXPECT_EQ(r.ellipsoid_relation, "internally_touching");
    EXPECT_EQ(r.containment, "a_inside_b");
  }
}

// The support description of an ellipsoid posed in doubles (centre, W = R D^2 R^T from the
// quaternion) is the same exact data the general route derives from the exact matrix
// (W = M^-1 scaled), and the certified distance of separated pairs agrees.
TEST(DoubleShape, ConvexDescriptionOfPosedEllipsoidsIsExact) {
  std::mt19937_64 rng(test_seed() + 3);
  for (int it = 0; it < 40; ++it) {
    const Shape s = random_shape(rng, it % 2 ? "ellipsoid" : "sphere", 1.0);
    const auto lazy = read(s.json(false));
    const auto exact = read(s.json(true));
    const auto cl = certify::convex_quadric(lazy), ce = certify::convex_quadric(exact);
    ASSERT_TRUE(cl && ce) << s.json(false);
    EXPECT_TRUE(cl->is_ellipsoid());
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(cl->c[i], ce->c[i]) << s.json(false);
      for (size_t j = 0; j < 3; ++j)
        EXPECT_EQ(cl->W[i][j], ce->W[i][j]) << s.json(false) << " W" << i << j;
    }
  }
}
