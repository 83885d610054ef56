// Float data read exactly, never refused for rounding (surface_reader.hpp):
// - a shape posed by a double rotation matrix R (not exactly orthogonal) is c + R D S^2: checked
//   by exact substitution of points x = c + R D u (u rational on the unit sphere) into the
//   quadric read — zero on the surface, the right sign off it — and by the certified answers
//   against the same quadric given as an exact rational 4x4 matrix;
// - a non-symmetric 4x4 matrix is its symmetric part, exactly; an antisymmetric addition does
//   not change the quadric;
// - the readings report the deviations (max |R^T R - I|, max |M - M^T|) as computed here in
//   exact arithmetic; an exactly orthogonal R or a symmetric M reports nothing;
// - a singular R stays an error at its JSON path.
#include "surfcert/app/scene.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <gmp.h>
#include <gtest/gtest.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace surfcert;
using core::Rational;

namespace {

using M3 = std::array<std::array<double, 3>, 3>;

// A double rotation matrix from a random double unit quaternion (as numpy users build them).
M3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  double w = g(rng), x = g(rng), y = g(rng), z = g(rng);
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

std::string num(double d) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  std::string s = buf;
  if (s.find_first_of(".eE") == std::string::npos) s += ".0"; // a double literal
  return s;
}

std::string ellipsoid_json(const std::array<double, 3>& c, const std::array<double, 3>& r,
                           const M3& R) {
  std::string m = "[";
  for (size_t i = 0; i < 3; ++i) {
    m += i ? ",[" : "[";
    for (size_t j = 0; j < 3; ++j)
      m += (j ? "," : "") + num(R[i][j]);
    m += "]";
  }
  m += "]";
  return R"({"type":"ellipsoid","center":[)" + num(c[0]) + "," + num(c[1]) + "," + num(c[2]) +
         R"(],"radii":[)" + num(r[0]) + "," + num(r[1]) + "," + num(r[2]) +
         R"(],"rotation":{"matrix":)" + m + "}}";
}

core::QuadricMatrix read(const std::string& json, core::io::Readings* rd = nullptr) {
  return core::io::read_quadric(core::io::parse_json(json, "t"), "t", "$", rd);
}

Rational value_at(const core::QuadricMatrix& q, const std::array<Rational, 3>& x) {
  const std::array<Rational, 4> p{x[0], x[1], x[2], Rational(1)};
  Rational v;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      v += q(i, j) * p[static_cast<size_t>(i)] * p[static_cast<size_t>(j)];
  return v;
}

// x = c + R D u, exactly (the doubles as given).
std::array<Rational, 3> world(const std::array<double, 3>& c, const std::array<double, 3>& r,
                              const M3& R, const std::array<Rational, 3>& u) {
  std::array<Rational, 3> x;
  for (size_t i = 0; i < 3; ++i) {
    x[i] = Rational::exact_from_double(c[i]);
    for (size_t j = 0; j < 3; ++j)
      x[i] += Rational::exact_from_double(R[i][j]) * Rational::exact_from_double(r[j]) * u[j];
  }
  return x;
}

} // namespace

TEST(FloatReading, DoubleRotationMatrixIsReadExactly) {
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> cen(-0.5, 0.5), rad(0.1, 1);
  // Rational points of the unit sphere.
  const std::array<std::array<Rational, 3>, 4> us{
      {{Rational(3, 5), Rational(4, 5), Rational(0)},
       {Rational(2, 3), Rational(-2, 3), Rational(1, 3)},
       {Rational(0), Rational(0), Rational(-1)},
       {Rational(-2, 7), Rational(3, 7), Rational(6, 7)}}};
  int non_orthogonal = 0;
  for (int k = 0; k < 20; ++k) {
    const std::array<double, 3> c{cen(rng), cen(rng), cen(rng)}, r{rad(rng), rad(rng), rad(rng)};
    const M3 R = random_rotation(rng);
    core::io::Readings rd;
    const auto q = read(ellipsoid_json(c, r, R), &rd);
    for (const auto& u : us) {
      EXPECT_TRUE(value_at(q, world(c, r, R, u)).is_zero()) << k;
      // Off the surface: outside (u scaled by 11/10) and inside (9/10) have opposite signs.
      std::array<Rational, 3> out = u, in = u;
      for (size_t i = 0; i < 3; ++i) {
        out[i] = u[i] * Rational(11, 10);
        in[i] = u[i] * Rational(9, 10);
      }
      EXPECT_LT(value_at(q, world(c, r, R, out)).sign() * value_at(q, world(c, r, R, in)).sign(), 0)
          << k;
    }
    // The reported deviation is max |R^T R - I|, computed here exactly.
    Rational dev;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        Rational s = Rational(i == j ? -1 : 0);
        for (size_t l = 0; l < 3; ++l)
          s += Rational::exact_from_double(R[l][i]) * Rational::exact_from_double(R[l][j]);
        if (core::abs(s) > dev) dev = core::abs(s);
      }
    if (dev.is_zero()) {
      EXPECT_TRUE(rd.empty());
      continue;
    }
    ++non_orthogonal;
    ASSERT_EQ(rd.size(), 1u) << k;
    EXPECT_EQ(rd[0].path, "$.rotation.matrix");
    ASSERT_FALSE(rd[0].deviations.empty());
    EXPECT_EQ(rd[0].deviations[0].first, "max_abs(R^T R - I)");
    const double reported = std::stod(rd[0].deviations[0].second);
    EXPECT_NEAR(reported, dev.to_double_approx(), 0.01 * dev.to_double_approx()) << k;
  }
  EXPECT_GT(non_orthogonal, 10); // double rotations are almost never exactly orthogonal
}

TEST(FloatReading, SameCertifiedAnswerAsTheExactMatrix) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> cen(-0.5, 0.5), rad(0.1, 1);
  for (int k = 0; k < 6; ++k) {
    const std::array<double, 3> c1{cen(rng), cen(rng), cen(rng)}, r1{rad(rng), rad(rng), rad(rng)};
    const std::array<double, 3> c2{cen(rng) + 2, cen(rng), cen(rng)},
        r2{rad(rng), rad(rng), rad(rng)};
    const M3 R1 = random_rotation(rng), R2 = random_rotation(rng);
    const auto a = read(ellipsoid_json(c1, r1, R1));
    const auto b = read(ellipsoid_json(c2, r2, R2));
    // The same quadrics as exact rational 4x4 matrices (their text), read by another path.
    auto as_matrix = [](const core::QuadricMatrix& q) {
      std::string m = R"({"matrix":[)";
      for (int i = 0; i < 4; ++i) {
        m += i ? ",[" : "[";
        for (int j = 0; j < 4; ++j)
          m += std::string(j ? "," : "") + "\"" + q(i, j).to_string() + "\"";
        m += "]";
      }
      return m + "]}";
    };
    const auto ea = read(as_matrix(a)), eb = read(as_matrix(b));
    const auto ca = certify::classify_qsic(a, b, certify::Mode::Filtered);
    const auto ce = certify::classify_qsic(ea, eb, certify::Mode::Exact);
    ASSERT_EQ(ce.status, certify::Status::Certified);
    EXPECT_EQ(ca.status, ce.status);
    ASSERT_TRUE(ca.morphology && ce.morphology);
    EXPECT_EQ(ca.morphology->id, ce.morphology->id) << k;
    const auto da = certify::surface_distance(a, b, 15, false);
    const auto de = certify::surface_distance(ea, eb, 15, false);
    ASSERT_EQ(da.status, certify::Status::Certified) << da.note;
    ASSERT_EQ(de.status, certify::Status::Certified) << de.note;
    EXPECT_EQ(da.lower(), de.lower());
    EXPECT_EQ(da.upper(), de.upper());
  }
}

TEST(FloatReading, NonSymmetricMatrixIsItsSymmetricPart) {
  // x^2 + y^2 + z^2 - 1 with an antisymmetric part added: the same quadric.
  const auto sym = read(R"({"matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]]})");
  core::io::Readings rd;
  const auto q = read(R"({"matrix":[[1,0.5,0,0],[-0.5,1,0,0],[0,0,1,3],[0,0,-3,-1]]})", &rd);
  EXPECT_TRUE(q.matrix() == sym.matrix());
  ASSERT_EQ(rd.size(), 1u);
  EXPECT_EQ(rd[0].path, "$.matrix");
  ASSERT_FALSE(rd[0].deviations.empty());
  EXPECT_DOUBLE_EQ(std::stod(rd[0].deviations[0].second), 6.0); // |3 - (-3)|
  // A one-ulp asymmetry as numpy leaves it: read as the mean, reported.
  const double a = 0.1, b = std::nextafter(0.1, 1.0);
  core::io::Readings r2;
  const auto p = read(R"({"matrix":[[1,)" + num(a) + R"(,0,0],[)" + num(b) +
                          R"(,2,0,0],[0,0,3,0],[0,0,0,-1]]})",
                      &r2);
  EXPECT_EQ(p(0, 1),
            (Rational::exact_from_double(a) + Rational::exact_from_double(b)) * Rational(1, 2));
  ASSERT_EQ(r2.size(), 1u);
  EXPECT_NEAR(std::stod(r2[0].deviations[0].second), b - a, 0.01 * (b - a));
  // Symmetric input: nothing to report.
  core::io::Readings r3;
  read(R"({"matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-1]]})", &r3);
  EXPECT_TRUE(r3.empty());
}

TEST(FloatReading, SingularRotationIsAnError) {
  try {
    read(R"({"type":"ellipsoid","radii":[1,2,3],"rotation":{"matrix":[[1,0,0],[0,1,0],[0,1,0]]}})");
    FAIL() << "a singular matrix was accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where().json_path, "$.rotation.matrix");
  }
}

TEST(FloatReading, BatchLineCarriesTheReadings) {
  std::mt19937_64 rng(3);
  const M3 R = random_rotation(rng);
  const std::string line = R"({"id":1,"op":"classify","a":)" +
                           ellipsoid_json({0, 0, 0}, {1, 0.5, 0.25}, R) +
                           R"(,"b":"x^2+y^2+z^2=1/9"})";
  const auto out = app::process_batch_line(line, 1, certify::Mode::Filtered);
  ASSERT_NE(out.find("status"), nullptr);
  EXPECT_EQ(out.find("status")->text(), "certified");
  const auto* rd = out.find("readings");
  ASSERT_NE(rd, nullptr);
  ASSERT_EQ(rd->size(), 1u);
  EXPECT_EQ(rd->items()[0].find("path")->text(), "$.a.rotation.matrix");
}

// Rational::exact_from_double against GMP's exact mpq_set_d (an independent route): every
// class of double (normal, subnormal, powers of two, the extremes, both signs) and random bits.
TEST(FloatReading, ExactValueOfADoubleMatchesGmp) {
  std::vector<double> ds = {0.1,
                            -0.1,
                            1,
                            -1,
                            0.5,
                            3,
                            1e300,
                            -1e-300,
                            5e-324,
                            -5e-324,
                            DBL_MIN,
                            -DBL_MIN,
                            DBL_MAX,
                            -DBL_MAX,
                            0x1p-1023,
                            0x1.fffffffffffffp-1023,
                            0x1p52,
                            0x1p53 + 2,
                            0x1p-52,
                            9007199254740991.0,
                            0.18250386420143827,
                            -0.0};
  std::mt19937_64 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const uint64_t bits = rng();
    double d = 0;
    std::memcpy(&d, &bits, sizeof d);
    if (std::isfinite(d)) ds.push_back(d);
  }
  mpq_t want;
  mpq_init(want);
  for (double d : ds) {
    mpq_set_d(want, d);
    core::Rational w;
    fmpq_set_mpq(w.raw_mut(), want);
    EXPECT_EQ(core::Rational::exact_from_double(d), w) << d;
  }
  mpq_clear(want);
}
