// certify::box_exits' interval filter (box_exits_filter.hpp: a face's crossings proved by
// subdivision and Krawczyk boxes) against two independent routes:
//  * the exact route (box_exits with interval_filter = false: resultants over Q, exact root
//    isolation, Arb) on random natural-quadric pairs under random rational poses, and on the
//    same pairs scaled by 2^-60 / 2^60 and moved 10^5 out;
//  * closed forms: two spheres whose common circle just clears (or just reaches over) a face,
//    at gaps of +-1e-10, 1e-20, 1e-30, 2^-100 (two crossings that close together, or none), and
//    a crossing at a rational point moved +-1e-10 ... 2^-100 off an edge of the box. The filter
//    must prove or defer, never miscount: the answers are the closed form's, with a tangency
//    and an edge crossing not certified. The same with the spheres' radical plane in place of
//    the second sphere (line_face_crossings: a line and a conic on each face), and random
//    planes against posed natural quadrics.
#include "support/distance_checks.hpp"

#include "surfcert/certify/box_exits.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace surfcert;
using core::Mat4;
using core::Rational;
using R3 = std::array<Rational, 3>;

namespace {

Mat4 diag(const Rational& a, const Rational& b, const Rational& c, const Rational& d) {
  Mat4 m;
  m[0][0] = a, m[1][1] = b, m[2][2] = c, m[3][3] = d;
  return m;
}

// (x - c)^2 + y^2 + z^2 - r2.
Mat4 sphere_x(const Rational& c, const Rational& r2) {
  Mat4 m = diag(Rational(1), Rational(1), Rational(1), c * c - r2);
  m[0][3] = m[3][0] = -c;
  return m;
}

Mat4 posed(const Mat4& local, const Mat4& motion) {
  return core::congruence(motion, local);
}

// Every crossing of `f` is one crossing of `e` on the same face, within the two enclosures'
// radii (plus the doubles' rounding of the midpoints), and the counts agree.
void expect_same(const certify::BoxExits& f, const certify::BoxExits& e, double scale,
                 const std::string& ctx) {
  ASSERT_EQ(f.certified, e.certified) << ctx << ": " << f.reason << " / " << e.reason;
  if (!f.certified) return;
  ASSERT_EQ(f.points.size(), e.points.size()) << ctx;
  std::vector<bool> used(e.points.size(), false);
  for (const auto& p : f.points) {
    int hits = 0;
    for (size_t j = 0; j < e.points.size(); ++j) {
      const auto& q = e.points[j];
      if (q.axis != p.axis || q.at_max != p.at_max || used[j]) continue;
      double d = 0;
      for (size_t k = 0; k < 3; ++k)
        d = std::max(d, std::abs(p.approx[k] - q.approx[k]));
      if (d <= p.radius + q.radius + 1e-14 * scale) {
        used[j] = true;
        ++hits;
        break;
      }
    }
    EXPECT_EQ(hits, 1) << ctx << ": filtered crossing (" << p.approx[0] << ", " << p.approx[1]
                       << ", " << p.approx[2] << ") not among the exact ones";
  }
}

Rational pow2(int k) {
  return Rational::exact_from_double(std::ldexp(1.0, k));
}

// Random spheres, cylinders and cones (radius or slope in [0.3, 1]) at the origin, and random
// rational motions (integer quaternions, translations in [-1, 1] by hundredths).
struct NaturalPairs {
  std::mt19937_64 rng;
  std::uniform_int_distribution<long> q{-9, 9}, t{-100, 100}, r{30, 100}, kind{0, 2};
  explicit NaturalPairs(unsigned long seed) : rng(seed) {}
  Mat4 local() {
    const Rational a(r(rng), 100);
    switch (kind(rng)) {
    case 0:
      return diag(Rational(1), Rational(1), Rational(1), -a * a); // sphere
    case 1:
      return diag(Rational(1), Rational(1), Rational(0), -a * a); // cylinder
    default:
      return diag(Rational(1), Rational(1), -a * a, Rational(0)); // cone
    }
  }
  Mat4 pose() {
    long w, x, y, z;
    do {
      w = q(rng), x = q(rng), y = q(rng), z = q(rng);
    } while (w == 0 && x == 0 && y == 0 && z == 0);
    return surfcert::testing::motion(
        w, x, y, z, {Rational(t(rng), 100), Rational(t(rng), 100), Rational(t(rng), 100)});
  }
};

// The number of distinct faces holding at least one crossing.
int faces_with_crossings(const certify::BoxExits& e) {
  std::vector<std::pair<int, bool>> faces;
  for (const auto& p : e.points)
    faces.emplace_back(p.axis, p.at_max);
  std::sort(faces.begin(), faces.end());
  return static_cast<int>(std::unique(faces.begin(), faces.end()) - faces.begin());
}

// 1e-10, 1e-20, 1e-30, 2^-100: the gaps every threshold is probed at.
std::vector<Rational> gaps() {
  const Rational e10(1, 10000000000UL);
  return {e10, e10 * e10, e10 * e10 * e10, pow2(-100)};
}

} // namespace

// Random cones, cylinders and spheres under random rational poses, in boxes that cut them:
// wherever the exact route certifies, the filtered one gives the same crossings on the same
// faces (and the filter proves most faces with crossings itself, or it would save nothing).
TEST(BoxExitsFilter, AgreesWithTheExactRouteOnRandomNaturalPairs) {
  NaturalPairs gen(27);
  const auto local = [&]() { return gen.local(); };
  const auto pose = [&]() { return gen.pose(); };
  int pairs = 0, compared = 0, crossing_faces = 0, filtered_faces = 0;
  for (int n = 0; n < 200; ++n) {
    const Mat4 a = posed(local(), pose()), b = posed(local(), pose());
    const R3 lo{Rational(-3, 2), Rational(-5, 4), Rational(-2)};
    const R3 hi{Rational(7, 4), Rational(3, 2), Rational(5, 4)};
    const auto f = certify::box_exits(a, b, lo, hi);
    const auto e = certify::box_exits(a, b, lo, hi, false);
    ++pairs;
    expect_same(f, e, 4, "pair " + std::to_string(n));
    if (!e.certified) continue;
    ++compared;
    crossing_faces += faces_with_crossings(e);
    filtered_faces += f.filtered_faces;
    EXPECT_EQ(e.filtered_faces, 0);
  }
  EXPECT_GE(compared, 180);
  EXPECT_GE(crossing_faces, 120);
  // Most faces with crossings proved by the filter (a filter that never succeeds, or a test
  // whose pairs never cross a face, fails here).
  EXPECT_GE(filtered_faces, crossing_faces * 3 / 4)
      << filtered_faces << " of " << crossing_faces << " faces with crossings";
  std::printf("%d pairs, %d certified, %d faces with crossings, %d proved by the filter\n", pairs,
              compared, crossing_faces, filtered_faces);
}

// A cone along z (apex at the origin, slope 0.8 ... 1.2) and one along x (slope 2 ... 2.4, apex
// at (0, 1/3, 0)), in the box [-2, 7/3]^3, moved by T = (5/4, 0, 0) or (10^5, 0, 0) and scaled
// by 2^-60, 1, 2^60 (coordinates and box): the quadric at X / s - T. The crossings agree with
// the exact route's. Near the origin the filter proves faces at every scale (a dyadic scaling
// changes no rounding); 10^5 out, the coefficients' rounding (~1e10 * 2^-53) leaves the
// crossings known to ~1e-6 only, wider than the points' promised precision: it defers there.
TEST(BoxExitsFilter, ScaledAndTranslatedPairsAgreeWithTheExactRoute) {
  std::mt19937_64 rng(2027);
  std::uniform_int_distribution<long> r(80, 120);
  for (const Rational& off : {Rational(5, 4), Rational(100000)})
    for (int k : {-60, 0, 60}) {
      int filtered = 0;
      for (int n = 0; n < 8; ++n) {
        const Rational s = pow2(k);
        const R3 t{off, Rational(0), Rational(0)};
        Mat4 p;
        for (size_t i = 0; i < 3; ++i) {
          p[i][i] = Rational(1) / s;
          p[i][3] = -t[i];
        }
        p[3][3] = Rational(1);
        const Rational a1(r(rng), 100), b1(r(rng) + 120, 100);
        const Mat4 cone = diag(Rational(1), Rational(1), -a1 * a1, Rational(0));
        // b^2 x^2 - (y - 1/3)^2 - z^2: a cone along x, its apex at (0, 1/3, 0); a b > 1, so
        // the two cones share four real directions and the curve runs out through the faces.
        Mat4 other = diag(b1 * b1, Rational(-1), Rational(-1), Rational(-1, 9));
        other[1][3] = other[3][1] = Rational(1, 3);
        const Mat4 a = posed(cone, p), b = posed(other, p);
        R3 lo, hi;
        for (size_t i = 0; i < 3; ++i) {
          lo[i] = (Rational(-2) + t[i]) * s;
          hi[i] = (Rational(7, 3) + t[i]) * s;
        }
        const auto f = certify::box_exits(a, b, lo, hi);
        const auto e = certify::box_exits(a, b, lo, hi, false);
        const std::string ctx = "pair " + std::to_string(n) + " at " + off.to_string() +
                                " scaled 2^" + std::to_string(k);
        EXPECT_TRUE(e.certified) << ctx << ": " << e.reason;
        EXPECT_GE(e.points.size(), 4u) << ctx; // branches running out of the box
        filtered += f.filtered_faces;
        expect_same(f, e, (1 + off.to_double_approx()) * s.to_double_approx(), ctx);
      }
      if (off < Rational(2)) {
        EXPECT_GT(filtered, 0) << "scale 2^" << k;
      }
    }
}

// Two unit-radius spheres centred at the origin and at (1, 0, 0) with r^2 = 2 - 2 x0 meet in
// the circle x = x0, radius sqrt(1 - x0^2). With x0 = 4/5 - eta, the face z = 3/5 of the box
// [-2, 2] x [-2, 2] x [3/5, 2] meets it at y = +-sqrt(eta (8/5 - eta)) (eta > 0: two crossings
// 2.5 sqrt(eta) apart), not at all for eta < 0, tangentially for eta = 0.
TEST(BoxExitsFilter, CrossingsThatCloseTogetherAreNeverMiscounted) {
  const R3 lo{Rational(-2), Rational(-2), Rational(3, 5)},
      hi{Rational(2), Rational(2), Rational(2)};
  const Mat4 a = sphere_x(Rational(0), Rational(1));
  for (const Rational& g : gaps())
    for (int sign : {1, -1})
      for (bool plane : {false, true}) {
        const Rational eta = sign > 0 ? g : -g;
        const Rational x0 = Rational(4, 5) - eta;
        const Mat4 sb = sphere_x(Rational(1), Rational(2) - Rational(2) * x0);
        // The radical plane 2 x - 2 x0 = 0 (a - sb) instead of the second sphere: the same
        // curve, its face sections a line and a conic (line_face_crossings).
        const Mat4 b = plane ? a + core::scaled(sb, Rational(-1)) : sb;
        const std::string ctx = "eta " + eta.to_string() + (plane ? " (plane)" : "");
        for (bool filter : {true, false}) {
          const auto r = certify::box_exits(a, b, lo, hi, filter);
          ASSERT_TRUE(r.certified) << ctx << ": " << r.reason;
          if (sign < 0) {
            EXPECT_TRUE(r.points.empty()) << ctx;
            continue;
          }
          ASSERT_EQ(r.points.size(), 2u) << ctx;
          // y = +-sqrt(eta (8/5 - eta)): the square exact, then one rounding and a square root.
          const double y = std::sqrt((eta * (Rational(8, 5) - eta)).to_double_approx());
          std::vector<double> ys;
          for (const auto& p : r.points) {
            EXPECT_EQ(p.axis, 2) << ctx;
            EXPECT_FALSE(p.at_max) << ctx;
            EXPECT_NEAR(p.approx[0], x0.to_double_approx(), p.radius + 1e-15) << ctx;
            ys.push_back(p.approx[1]);
            // The promised width (2^-80 of the box exactly, 2^-46 on the interval route) and the
            // point within it: near a tangency the chart's root was narrow while the face
            // coordinates were not (points 1e-6 off at 2^-100, helper-27).
            EXPECT_LE(p.radius, (filter ? 0x1p-46 : 0x1p-80) * 4) << ctx;
            EXPECT_LE(std::abs(std::abs(p.approx[1]) - y), p.radius + 4e-16 * y + 1e-300) << ctx;
          }
          // Upper and lower bound: one crossing on each side of y = 0.
          EXPECT_LT(std::min(ys[0], ys[1]), 0) << ctx;
          EXPECT_GT(std::max(ys[0], ys[1]), 0) << ctx;
        }
      }
  // eta = 0: the circle touches the face (a tangency): not certified on either route.
  const Mat4 b = sphere_x(Rational(1), Rational(2) - Rational(8, 5));
  for (const Mat4& bb : {b, a + core::scaled(b, Rational(-1))})
    for (bool filter : {true, false}) {
      const auto r = certify::box_exits(a, bb, lo, hi, filter);
      EXPECT_FALSE(r.certified);
    }
}

// The spheres above with x0 = 2/3: the circle crosses the face z = 1/3 at (2/3, +-2/3, 1/3),
// rational points. The box's face y = 2/3 + eps puts the crossing (2/3, 2/3, 1/3) just inside
// (eps > 0: both crossings on the face z = 1/3) or just outside (eps < 0: the arc leaves through
// the face y = 2/3 + eps instead, one crossing there and one on z = 1/3); eps = 0 puts it on
// the edge: not certified.
TEST(BoxExitsFilter, CrossingsNearAnEdgeGoToTheRightFace) {
  const Mat4 a = sphere_x(Rational(0), Rational(1));
  const Mat4 sb = sphere_x(Rational(1), Rational(2, 3));
  const Mat4 pb = a + core::scaled(sb, Rational(-1)); // the radical plane x = 2/3
  for (const Rational& g : gaps())
    for (int sign : {1, -1})
      for (const Mat4* bp : {&sb, &pb}) {
        const Mat4& b = *bp;
        const Rational eps = sign > 0 ? g : -g;
        const R3 lo{Rational(-2), Rational(-2), Rational(1, 3)};
        const R3 hi{Rational(2), Rational(2, 3) + eps, Rational(2)};
        const std::string ctx = "eps " + eps.to_string() + (bp == &pb ? " (plane)" : "");
        for (bool filter : {true, false}) {
          const auto r = certify::box_exits(a, b, lo, hi, filter);
          ASSERT_TRUE(r.certified) << ctx << ": " << r.reason;
          ASSERT_EQ(r.points.size(), 2u) << ctx;
          int on_bottom = 0, on_side = 0;
          for (const auto& p : r.points) {
            if (p.axis == 2 && !p.at_max) {
              ++on_bottom;
              EXPECT_NEAR(std::abs(p.approx[1]), 2.0 / 3, p.radius + 1e-15) << ctx;
            }
            if (p.axis == 1 && p.at_max) ++on_side;
          }
          EXPECT_EQ(on_bottom, sign > 0 ? 2 : 1) << ctx;
          EXPECT_EQ(on_side, sign > 0 ? 0 : 1) << ctx;
        }
      }
  const R3 lo{Rational(-2), Rational(-2), Rational(1, 3)};
  const R3 hi{Rational(2), Rational(2, 3), Rational(2)};
  for (const Mat4* bp : {&sb, &pb})
    for (bool filter : {true, false})
      EXPECT_FALSE(certify::box_exits(a, *bp, lo, hi, filter).certified);
}

// Planes (random rational normals and offsets) against random cones, cylinders and spheres
// under random rational poses: every face where the plane's section is a line. Wherever the
// exact route certifies, the filtered one gives the same crossings on the same faces, and the
// interval route proves most faces with crossings itself; the reported points satisfy both
// equations (exact substitution of the doubles, within the radius' effect).
TEST(BoxExitsFilter, PlaneSectionsAgreeWithTheExactRoute) {
  NaturalPairs gen(28);
  auto& rng = gen.rng;
  auto& q = gen.q;
  auto& t = gen.t;
  const auto local = [&]() { return gen.local(); };
  const auto pose = [&]() { return gen.pose(); };
  int compared = 0, crossing_faces = 0, filtered_faces = 0;
  for (int n = 0; n < 200; ++n) {
    const Mat4 a = posed(local(), pose());
    // n . x = d, n with small integer entries (an axis-parallel plane now and then).
    Mat4 b;
    long nx, ny, nz;
    do {
      nx = q(rng) / 3, ny = q(rng) / 2, nz = q(rng);
    } while (nx == 0 && ny == 0 && nz == 0);
    b[0][3] = b[3][0] = Rational(nx, 2);
    b[1][3] = b[3][1] = Rational(ny, 2);
    b[2][3] = b[3][2] = Rational(nz, 2);
    b[3][3] = Rational(-t(rng), 100);
    const R3 lo{Rational(-3, 2), Rational(-5, 4), Rational(-2)};
    const R3 hi{Rational(7, 4), Rational(3, 2), Rational(5, 4)};
    for (bool swap : {false, true}) {
      const auto f = swap ? certify::box_exits(b, a, lo, hi) : certify::box_exits(a, b, lo, hi);
      const auto e =
          swap ? certify::box_exits(b, a, lo, hi, false) : certify::box_exits(a, b, lo, hi, false);
      expect_same(f, e, 4, "pair " + std::to_string(n) + (swap ? " swapped" : ""));
      if (!e.certified || swap) continue;
      ++compared;
      crossing_faces += faces_with_crossings(e);
      filtered_faces += f.filtered_faces;
      // The filtered points on both surfaces: |X^T M X| at the double point within what a
      // displacement of radius + rounding can produce (gradients here are below ~30).
      for (const auto& p : f.points) {
        std::array<Rational, 4> x;
        for (size_t k = 0; k < 3; ++k)
          x[k] = Rational::exact_from_double(p.approx[k]);
        x[3] = Rational(1);
        for (const Mat4* m : {&a, static_cast<const Mat4*>(&b)}) {
          Rational v;
          for (size_t i = 0; i < 4; ++i)
            for (size_t j = 0; j < 4; ++j)
              v += x[i] * (*m)[i][j] * x[j];
          EXPECT_LE(std::abs(v.to_double_approx()), 100 * (p.radius + 1e-15))
              << "pair " << n << ": a crossing off a surface";
        }
      }
    }
  }
  EXPECT_GE(compared, 180);
  EXPECT_GE(crossing_faces, 150);
  EXPECT_GE(filtered_faces, crossing_faces * 3 / 4)
      << filtered_faces << " of " << crossing_faces << " faces with crossings";
  std::printf("%d certified, %d faces with crossings, %d proved by the filter\n", compared,
              crossing_faces, filtered_faces);
}
