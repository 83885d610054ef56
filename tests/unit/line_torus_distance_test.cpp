// Distances from a quadric whose real points form a line (x^2 + y^2 = 0, a rank-2 semidefinite
// form) to a ring torus (route line_locus, line_torus_distance), against closed forms derived by
// hand for the torus centred at 0 with axis z, R = 2, r = 1 (and one centred at (5, 0, 0)):
// - the axis: every core-circle point at distance R from the centre: R - r, a circle of nearest
//   points ("infinite");
// - parallel to the axis at offset s: |s - R| - r ("1"), or meeting: s = R crosses the tube at
//   2 points, s = R +- r touches it at 1;
// - in the torus plane, missing it: the distance from 0 to the line minus (R + r) ("1");
//   crossing it (the x-axis: 4 points), tangent to its top (z = r: 2 points);
// - above it, crossing the axis at height h: the nearest circle points are at horizontal
//   distance 0, so h - r, two minimizers (rational t = +-R; and for a line at offset 1 the
//   irrational t = +-sqrt 3), tied by the mirror symmetry (proven);
// - at offset s = 3, height 4: sqrt((s - R)^2 + h^2) - r = sqrt 17 - 1 ("1");
// - through the centre along (1, 0, 1): F(t) = 2t^2 + 4 - 4|t|, least at t = +-1: sqrt 2 - 1.
// Each swapped (torus first), rigidly moved by a rational rotation and translation (both
// surfaces), at 15 and 50 digits, in exact mode; tangency probed from both sides at gaps 1e-10,
// 1e-20, 1e-30 and 2^-100 (distance g, or meeting). All of these were undecided before ("the
// critical points of the torus equation on the quadric form a curve").
#include "surfcert/certify/distance/degenerate_locus.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/core/torus.hpp"

#include "support/distance_checks.hpp"

#include <gmp.h>
#include <gtest/gtest.h>
#include <mpfr.h>

#include <cmath>
#include <string>

using namespace surfcert;
using surfcert::testing::closed_form;
using surfcert::testing::contains;
using surfcert::testing::log10_rel_width;
using surfcert::testing::q;

namespace {

using certify::Method;
using certify::Status;
using core::Rational;
using Vec3 = std::array<Rational, 3>;

// A rigid motion x -> M x + t (M from the integer quaternion (w, x, y, z)), applied to a torus
// directly and to a quadric as the congruence testing::motion builds for the same motion.
struct Motion {
  long w, x, y, z;
  Vec3 t;
  Vec3 rotate(const Vec3& v) const {
    const Rational n(w * w + x * x + y * y + z * z);
    const long R[3][3] = {
        {w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
        {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
        {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
    Vec3 out;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        out[i] += Rational(R[i][j]) * v[j] / n;
    return out;
  }
  core::Torus apply(const core::Torus& T) const {
    Vec3 c = rotate(T.centre);
    for (size_t i = 0; i < 3; ++i)
      c[i] += t[i];
    return core::make_torus(c, rotate(T.axis), T.R, T.r);
  }
  core::QuadricMatrix apply(const core::QuadricMatrix& m) const {
    return m.congruent(surfcert::testing::motion(w, x, y, z, t));
  }
};

core::Torus torus(long cx, long cy, long cz, long R, long r) {
  return core::make_torus({Rational(cx), Rational(cy), Rational(cz)},
                          {Rational(0), Rational(0), Rational(1)}, Rational(R), Rational(r));
}

struct Case {
  const char* line;
  long cx;               // the torus centre (cx, 0, 0), axis z, R = 2, r = 1
  const char *s, *t, *u; // d = (sqrt(s) - t) / u; "0" "0" "1" for contact
  const char* minimizers;
};

const Case kCases[] = {
    {"x^2+y^2=0", 0, "4", "1", "1", "infinite"},   // the axis: R - r
    {"x^2+y^2=0", 5, "4", "0", "1", "1"},          // parallel, offset 5: 5 - 2 - 1
    {"(x-1/2)^2+y^2=0", 0, "1/4", "0", "1", "1"},  // in the hole: 2 - 1/2 - 1
    {"(x-5)^2+y^2=0", 0, "4", "0", "1", "1"},      // outside: 5 - 2 - 1
    {"(x-2)^2+y^2=0", 0, "0", "0", "1", "2"},      // through the tube
    {"(x-3)^2+y^2=0", 0, "0", "0", "1", "1"},      // tangent outside
    {"(x-1)^2+y^2=0", 0, "0", "0", "1", "1"},      // tangent inside
    {"(y-4)^2+z^2=0", 0, "1", "0", "1", "1"},      // in the plane: 4 - 3
    {"(x+y-6)^2+z^2=0", 0, "18", "3", "1", "1"},   // in the plane: 6/sqrt 2 - 3
    {"y^2+z^2=0", 0, "0", "0", "1", "4"},          // the x-axis: 4 crossings
    {"y^2+(z-1)^2=0", 0, "0", "0", "1", "2"},      // on the top: 2 tangencies
    {"y^2+(z-3)^2=0", 0, "4", "0", "1", "2"},      // above, across the axis: 3 - 1
    {"(y-1)^2+(z-3)^2=0", 0, "4", "0", "1", "2"},  // above, t = +-sqrt 3: 3 - 1
    {"(y-3)^2+(z-4)^2=0", 0, "17", "1", "1", "1"}, // sqrt(1 + 16) - 1
    {"(x-z)^2+y^2=0", 0, "2", "1", "1", "2"},      // tilted through the centre
    {"(x-z-5)^2+y^2=0", 5, "2", "1", "1", "2"},    // the same, translated by (5, 0, 0)
};

void check(const certify::DistanceResult& r, const mpfr_t d, const char* minimizers, long digits,
           const std::string& tag) {
  ASSERT_EQ(r.status, Status::Certified) << tag << ": " << r.note;
  EXPECT_EQ(r.method, Method::LineLocus) << tag;
  EXPECT_EQ(r.minimizers.str(), minimizers) << tag << ": " << r.note;
  EXPECT_FALSE(r.pairs.empty()) << tag;
  if (mpfr_zero_p(d)) {
    EXPECT_TRUE(r.distance->is_zero()) << tag << ": " << r.lower() << " " << r.upper();
    return;
  }
  EXPECT_TRUE(contains(r, d)) << tag << ": [" << r.lower() << ", " << r.upper() << "]";
  EXPECT_LE(log10_rel_width(r), -static_cast<double>(digits)) << tag;
}

certify::DistanceResult run(const core::QuadricMatrix& l, const core::Torus& t, bool swap,
                            long digits, certify::Mode mode = certify::Mode::Filtered) {
  return swap ? certify::surface_distance(core::Surface(t), core::Surface(l), digits, false, mode)
              : certify::surface_distance(core::Surface(l), core::Surface(t), digits, false, mode);
}

} // namespace

TEST(LineTorus, ClosedFormsSwappedMovedAndAt50Digits) {
  mpfr_t d;
  mpfr_init2(d, 1200);
  const Motion M{1, 2, 3, 4, {Rational(1, 3), Rational(-2, 7), Rational(5)}};
  for (const Case& c : kCases) {
    closed_form(d, c.s, c.t, c.u);
    for (bool moved : {false, true})
      for (bool swap : {false, true})
        for (long digits : {15L, 50L}) {
          auto l = q(c.line);
          auto t = torus(c.cx, 0, 0, 2, 1);
          if (moved) {
            l = M.apply(l);
            t = M.apply(t);
          }
          const std::string tag = std::string(c.line) + " | torus at " + std::to_string(c.cx) +
                                  (swap ? " swapped" : "") + (moved ? " moved" : "") + " @" +
                                  std::to_string(digits);
          check(run(l, t, swap, digits), d, c.minimizers, digits, tag);
        }
  }
  mpfr_clear(d);
}

// The pair points lie on their surfaces (display doubles) and realise the distance, in the
// query's order; the tilted line's two minimizers are (+-1, 0, +-1) on the line.
TEST(LineTorus, PairsOnTheirSurfaces) {
  const auto line = q("(x-z)^2+y^2=0");
  const core::Torus t = torus(0, 0, 0, 2, 1);
  for (bool swap : {false, true}) {
    const auto r = run(line, t, swap, 15);
    ASSERT_EQ(r.status, Status::Certified) << r.note;
    ASSERT_EQ(r.pairs.size(), 2u);
    for (const auto& pr : r.pairs) {
      const auto& on_line = pr[swap ? 1 : 0];
      const auto& on_torus = pr[swap ? 0 : 1];
      EXPECT_NEAR(on_line[0] - on_line[2], 0, 1e-12);
      EXPECT_NEAR(on_line[1], 0, 1e-12);
      EXPECT_NEAR(std::fabs(on_line[0]), 1, 1e-12);
      const double rho = std::hypot(on_torus[0], on_torus[1]);
      EXPECT_NEAR((rho - 2) * (rho - 2) + on_torus[2] * on_torus[2], 1, 1e-12);
      double dist = 0;
      for (int i = 0; i < 3; ++i)
        dist += (on_line[i] - on_torus[i]) * (on_line[i] - on_torus[i]);
      EXPECT_NEAR(std::sqrt(dist), r.approx(), 1e-12);
    }
  }
}

// Tangency from both sides, axis-aligned and moved, at 15 and 50 digits: a line parallel to the
// axis at offset 3 + g (distance g) or 3 - g (crossing the tube twice), at 1 - g (in the hole:
// distance g) or 1 + g (crossing twice), a line across the axis at height 1 + g (distance g,
// two minimizers t = +-2) or 1 - g (four crossings).
TEST(LineTorus, TangencyProbes) {
  const char* gaps[] = {"1/10000000000", "1/100000000000000000000",
                        "1/1000000000000000000000000000000", "1/1267650600228229401496703205376"};
  const Motion M{2, -1, 3, 1, {Rational(7, 5), Rational(0), Rational(-1, 9)}};
  mpfr_t d;
  mpfr_init2(d, 1200);
  for (const char* g : gaps)
    for (int side : {-1, 1}) {
      const std::string plus = side > 0 ? "+" : "-", minus = side > 0 ? "-" : "+";
      struct Probe {
        std::string line;
        const char *apart, *meeting; // minimizers when apart by g, when meeting
      } probes[] = {{"(x-(3" + plus + g + "))^2+y^2=0", "1", "2"},
                    {"(x-(1" + minus + g + "))^2+y^2=0", "1", "2"},
                    {"y^2+(z-(1" + plus + g + "))^2=0", "2", "4"}};
      for (const auto& p : probes)
        for (bool moved : {false, true})
          for (long digits : {15L, 50L}) {
            auto l = q(p.line);
            auto t = torus(0, 0, 0, 2, 1);
            if (moved) {
              l = M.apply(l);
              t = M.apply(t);
            }
            const std::string tag =
                p.line + (moved ? " moved" : "") + " @" + std::to_string(digits);
            if (side > 0) {
              closed_form(d, "0", (std::string("-") + g).c_str(), "1");
              check(run(l, t, false, digits), d, p.apart, digits, tag);
            } else {
              mpfr_set_zero(d, 1);
              check(run(l, t, false, digits), d, p.meeting, digits, tag);
            }
          }
    }
  mpfr_clear(d);
}

// Exact mode gives the same answers; the route reads the torus from its JSON form too.
TEST(LineTorus, ExactModeAndJson) {
  mpfr_t d;
  mpfr_init2(d, 1200);
  closed_form(d, "17", "1", "1");
  check(run(q("(y-3)^2+(z-4)^2=0"), torus(0, 0, 0, 2, 1), false, 30, certify::Mode::Exact), d, "1",
        30, "exact mode");
  mpfr_set_zero(d, 1);
  check(run(q("(x-3)^2+y^2=0"), torus(0, 0, 0, 2, 1), true, 15, certify::Mode::Exact), d, "1", 15,
        "tangent, exact mode");
  const core::Surface t = core::io::read_surface(
      core::io::parse_json(R"({"type": "torus", "center": [5, 0, 0], "axis": [0, 0, 1],
                                "major_radius": 2, "minor_radius": 1})",
                           "t"),
      "t", "$");
  const auto r = certify::surface_distance(core::Surface(q("x^2+y^2=0")), t, 15, false);
  closed_form(d, "4", "0", "1");
  check(r, d, "1", 15, "json torus");
  mpfr_clear(d);
}

// Lines in general pose (two random integer planes) against random tori (rational radii, integer
// centre and axis): the certified answer against an independent float minimisation of
// dist(x(t), K) - r over t (a fine grid, then golden-section search), within 1e-6, and a
// meeting (distance 0) exactly when the float minimum is <= 0 up to that tolerance.
TEST(LineTorus, AgainstFloatMinimisation) {
  unsigned long state = 12345;
  auto next = [&](long lo, long hi) {
    state = state * 6364136223846793005UL + 1442695040888963407UL;
    return lo + static_cast<long>((state >> 33) % static_cast<unsigned long>(hi - lo + 1));
  };
  int answered = 0;
  for (int k = 0; k < 30; ++k) {
    long n1[3], n2[3], c[3], a[3];
    for (int i = 0; i < 3; ++i) {
      n1[i] = next(-3, 3);
      n2[i] = next(-3, 3);
      c[i] = next(-2, 2);
      a[i] = next(-2, 2);
    }
    const long b1 = next(-4, 4), b2 = next(-4, 4);
    const long d[3] = {n1[1] * n2[2] - n1[2] * n2[1], n1[2] * n2[0] - n1[0] * n2[2],
                       n1[0] * n2[1] - n1[1] * n2[0]};
    if ((d[0] == 0 && d[1] == 0 && d[2] == 0) || (a[0] == 0 && a[1] == 0 && a[2] == 0)) continue;
    const Rational R = Rational(next(4, 6), 2), r = Rational(next(1, 3), 2);
    auto plane = [](const long* n, long b) {
      return "(" + std::to_string(n[0]) + "*x+" + std::to_string(n[1]) + "*y+" +
             std::to_string(n[2]) + "*z-(" + std::to_string(b) + "))^2";
    };
    const auto line = q(plane(n1, b1) + "+" + plane(n2, b2) + "=0");
    const core::Torus t = core::make_torus({Rational(c[0]), Rational(c[1]), Rational(c[2])},
                                           {Rational(a[0]), Rational(a[1]), Rational(a[2])}, R, r);
    const auto res = run(line, t, k % 2 == 1, 15);
    const std::string tag = "case " + std::to_string(k);
    ASSERT_EQ(res.status, Status::Certified) << tag << ": " << res.note;
    EXPECT_EQ(res.method, Method::LineLocus) << tag;
    ++answered;
    // The float reference: a point of the line (Cramer on n1, n2, d), then min over t.
    auto det = [](const double m[3][3]) {
      return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
             m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double M[3][3] = {{double(n1[0]), double(n1[1]), double(n1[2])},
                            {double(n2[0]), double(n2[1]), double(n2[2])},
                            {double(d[0]), double(d[1]), double(d[2])}};
    const double rhs[3] = {double(b1), double(b2), 0};
    double p[3];
    for (int j = 0; j < 3; ++j) {
      double B[3][3];
      for (int i = 0; i < 3; ++i)
        for (int l = 0; l < 3; ++l)
          B[i][l] = l == j ? rhs[i] : M[i][l];
      p[j] = det(B) / det(M);
    }
    const double an = std::sqrt(double(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]));
    const double Rd = R.to_double_approx(), rd = r.to_double_approx();
    auto F = [&](double s) {
      double x[3], h = 0, xx = 0;
      for (int i = 0; i < 3; ++i) {
        x[i] = p[i] + s * d[i] - c[i];
        h += x[i] * a[i] / an;
        xx += x[i] * x[i];
      }
      const double rho = std::sqrt(std::max(0.0, xx - h * h));
      return std::sqrt((rho - Rd) * (rho - Rd) + h * h);
    };
    double best = 0;
    for (int i = -40000; i <= 40000; ++i)
      if (F(i / 2000.0) < F(best)) best = i / 2000.0;
    double lo = best - 1e-3, hi = best + 1e-3;
    for (int it = 0; it < 200; ++it) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      (F(m1) < F(m2) ? hi : lo) = F(m1) < F(m2) ? m2 : m1;
    }
    const double ref = std::max(0.0, F(lo) - rd);
    EXPECT_NEAR(res.approx(), ref, 1e-6) << tag << ": " << res.note;
  }
  EXPECT_GE(answered, 20);
}
