// certify::box_exits on plane sections, whose faces are read in closed form (a line of the face
// against a conic, box_exits_line_conic): against two independent routes on random rational
// planes P, L, quadrics Q and boxes:
//  * the generic reading (resultants over Q, exact root isolation, Arb): the pair (Q, Q + P L)
//    meets in (Q ∩ P) ∪ (Q ∩ L), so its crossings are those of (P, Q) and (L, Q) together;
//  * MPFR at 256 bits: each face's line intersected with Q by the quadratic formula.
// Exact cases the closed form must refuse: a tangency inside a face, a crossing on an edge, a
// line of the curve in a face's plane; a tangency outside the face rectangle is no point.
#include "support/canonical.hpp"

#include "surfcert/certify/affine.hpp"
#include "surfcert/certify/box_exits.hpp"

#include <gtest/gtest.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace surfcert;
using core::Mat4;
using core::Rational;
using V4 = std::array<Rational, 4>;
using R3 = std::array<Rational, 3>;

namespace {

Mat4 plane(const V4& n) {
  return certify::plane_as_quadric(n);
}

// (p . X)(l . X) + q as a symmetric matrix.
Mat4 plus_product(const Mat4& q, const V4& p, const V4& l) {
  Mat4 m = q;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] += (p[i] * l[j] + l[i] * p[j]) * Rational(1, 2);
  return m;
}

struct Pt {
  int axis;
  bool at_max;
  std::array<double, 3> x;
};

std::vector<Pt> points(const certify::BoxExits& e) {
  std::vector<Pt> out;
  for (const auto& c : e.points)
    out.push_back({c.axis, c.at_max, c.approx});
  return out;
}

// Every point of `a` is exactly one point of `b` (same face, within tol) and the sizes agree.
void expect_same(const std::vector<Pt>& a, const std::vector<Pt>& b, double tol,
                 const std::string& ctx) {
  ASSERT_EQ(a.size(), b.size()) << ctx;
  for (const auto& p : a) {
    int hits = 0;
    for (const auto& q : b) {
      double d = 0;
      for (size_t k = 0; k < 3; ++k)
        d = std::max(d, std::fabs(p.x[k] - q.x[k]));
      hits += p.axis == q.axis && p.at_max == q.at_max && d <= tol ? 1 : 0;
    }
    EXPECT_EQ(hits, 1) << ctx;
  }
}

// MPFR: the crossings of the plane n . (x, 1) = 0 and the quadric q with the box's faces
// (points strictly inside a face rectangle); `clear` false when a root lies within 2^-100 of
// a rectangle's side or the line meets q tangentially (then the case is skipped).
std::vector<Pt> mpfr_crossings(const V4& n, const Mat4& q, const R3& lo, const R3& hi,
                               bool& clear) {
  constexpr mpfr_prec_t prec = 256;
  struct F {
    mpfr_t v;
    F() {
      mpfr_init2(v, prec);
      mpfr_set_zero(v, 1);
    }
    explicit F(const Rational& r) {
      mpfr_init2(v, prec);
      mpq_t m;
      mpq_init(m);
      fmpq_get_mpq(m, r.raw());
      mpfr_set_q(v, m, MPFR_RNDN);
      mpq_clear(m);
    }
    F(const F& o) {
      mpfr_init2(v, prec);
      mpfr_set(v, o.v, MPFR_RNDN);
    }
    F& operator=(const F& o) {
      mpfr_set(v, o.v, MPFR_RNDN);
      return *this;
    }
    ~F() { mpfr_clear(v); }
    double d() const { return mpfr_get_d(v, MPFR_RNDN); }
  };
  // r = a op b, rounded to nearest, for op one of MPFR's binary operations.
  using Op = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_srcptr, mpfr_rnd_t);
  auto op = [](Op f) {
    return [f](const F& a, const F& b) {
      F r;
      f(r.v, a.v, b.v, MPFR_RNDN);
      return r;
    };
  };
  const auto add = op(mpfr_add), sub = op(mpfr_sub), mul = op(mpfr_mul), div = op(mpfr_div);
  auto small = [](const F& a) { return mpfr_zero_p(a.v) || mpfr_get_exp(a.v) < -100; };
  std::vector<Pt> out;
  clear = true;
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      const size_t ku = static_cast<size_t>(k), i = (ku + 1) % 3, j = (ku + 2) % 3;
      const F c(side ? hi[ku] : lo[ku]);
      // n_i x_i + n_j x_j + (n_k c + n_3) = 0 in the face.
      const F ni(n[i]), nj(n[j]), n0 = add(mul(F(n[ku]), c), F(n[3]));
      if (mpfr_zero_p(ni.v) && mpfr_zero_p(nj.v)) continue;
      std::array<F, 4> p, d; // X = p + t d (homogeneous, last 1 / 0)
      for (auto* v : {&p, &d})
        for (auto& e : *v)
          mpfr_set_zero(e.v, 1);
      p[ku] = c;
      mpfr_set_ui(p[3].v, 1, MPFR_RNDN);
      if (!mpfr_zero_p(nj.v)) { // x_i = t, x_j = -(n_i t + n0) / n_j
        p[j] = div(sub(F(), n0), nj);
        mpfr_set_ui(d[i].v, 1, MPFR_RNDN);
        d[j] = div(sub(F(), ni), nj);
      } else {
        p[i] = div(sub(F(), n0), ni);
        mpfr_set_ui(d[j].v, 1, MPFR_RNDN);
      }
      F a, b, cc;
      for (size_t r = 0; r < 4; ++r)
        for (size_t s = 0; s < 4; ++s) {
          const F m(q[r][s]);
          a = add(a, mul(mul(d[r], m), d[s]));
          b = add(b, mul(mul(d[r], m), p[s]));
          cc = add(cc, mul(mul(p[r], m), p[s]));
        }
      const F disc = sub(mul(b, b), mul(a, cc));
      if (small(a) || small(disc)) {
        clear = false; // degenerate for this check: skip the case
        return out;
      }
      if (mpfr_sgn(disc.v) < 0) continue;
      F sq;
      mpfr_sqrt(sq.v, disc.v, MPFR_RNDN);
      for (const F& t : {div(sub(sub(F(), b), sq), a), div(add(sub(F(), b), sq), a)}) {
        std::array<F, 3> x{add(p[0], mul(t, d[0])), add(p[1], mul(t, d[1])),
                           add(p[2], mul(t, d[2]))};
        bool inside = true;
        for (size_t e : {i, j}) {
          const F l = sub(x[e], F(lo[e])), h = sub(F(hi[e]), x[e]);
          if (small(l) || small(h)) clear = false;
          inside = inside && mpfr_sgn(l.v) > 0 && mpfr_sgn(h.v) > 0;
        }
        if (inside) out.push_back({k, side == 1, {x[0].d(), x[1].d(), x[2].d()}});
      }
    }
  return out;
}

} // namespace

TEST(LineConicExits, PlaneSectionsAgainstTheGenericReadingAndMpfr) {
  std::mt19937_64 rng(surfcert::testing::test_seed() + 31);
  std::uniform_int_distribution<long> e(-4, 4), den(1, 5);
  auto r = [&] { return Rational(e(rng), static_cast<unsigned long>(den(rng))); };
  int checked = 0, with_points = 0;
  for (int it = 0; it < 300; ++it) {
    Mat4 q;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j)
        q[i][j] = q[j][i] = r();
    const V4 p{r(), r(), r(), r()}, l{r(), r(), r(), r()};
    if ((p[0].is_zero() && p[1].is_zero() && p[2].is_zero()) ||
        (l[0].is_zero() && l[1].is_zero() && l[2].is_zero()) || core::det(q).is_zero())
      continue;
    R3 lo, hi;
    for (size_t k = 0; k < 3; ++k) {
      lo[k] = Rational(-1 - static_cast<long>(rng() % 3), static_cast<unsigned long>(den(rng)));
      hi[k] = Rational(1 + static_cast<long>(rng() % 3), static_cast<unsigned long>(den(rng)));
    }
    const std::string ctx = "case " + std::to_string(it);
    bool clear_p = true, clear_l = true;
    const auto mp = mpfr_crossings(p, q, lo, hi, clear_p);
    const auto ml = mpfr_crossings(l, q, lo, hi, clear_l);
    const auto ep = certify::box_exits(plane(p), q, lo, hi);
    const auto el = certify::box_exits(plane(l), q, lo, hi);
    if (clear_p) {
      ASSERT_TRUE(ep.certified) << ctx << ": " << ep.reason;
      expect_same(points(ep), mp, 1e-12, ctx + " P against MPFR");
    }
    if (clear_l) {
      ASSERT_TRUE(el.certified) << ctx << ": " << el.reason;
      expect_same(points(el), ml, 1e-12, ctx + " L against MPFR");
    }
    if (!clear_p || !clear_l) continue;
    // The generic reading of (Q, Q + P L): both sections at once (when they do not share a
    // crossing: then a multiple root, not certified, and nothing to compare).
    const auto both = certify::box_exits(q, plus_product(q, p, l), lo, hi);
    if (!both.certified) continue;
    auto sum = points(ep);
    for (const auto& x : points(el))
      sum.push_back(x);
    expect_same(points(both), sum, 1e-12, ctx + " (P, Q) + (L, Q) against (Q, Q + P L)");
    ++checked;
    with_points += sum.empty() ? 0 : 1;
  }
  EXPECT_GE(checked, 100);
  EXPECT_GE(with_points, 50);
}

TEST(LineConicExits, TangencyEdgeAndComponentAreRefusedExactly) {
  // The paraboloid z = x^2 + y^2 cut by the plane y = 0: the parabola z = x^2.
  Mat4 par;
  par[0][0] = par[1][1] = Rational(1);
  par[2][3] = par[3][2] = Rational(-1, 2);
  const Mat4 y0 = plane({Rational(0), Rational(1), Rational(0), Rational(0)});
  auto exits = [&](const Mat4& a, const Mat4& b, R3 lo, R3 hi) {
    return certify::box_exits(a, b, lo, hi);
  };
  const Rational m1(-1), p1(1), p2(2), z(0);
  // Touching the bottom face z = 0 at its vertex, inside the face: a tangency.
  EXPECT_FALSE(exits(y0, par, {-p2, m1, z}, {p2, p1, p2}).certified);
  // The same tangency outside the face rectangle (x in [1/2, 2]): no point there; the top face
  // z = 2 is crossed once at x = sqrt(2), the side x = 1/2 at z = 1/4.
  // Both routes: the interval filter (line_face_crossings: points within 2^-46 of the face)
  // and the exact closed form (128-bit enclosures).
  for (bool filter : {true, false}) {
    const auto off = certify::box_exits(y0, par, {Rational(1, 2), m1, z}, {p2, p1, p2}, filter);
    ASSERT_TRUE(off.certified) << off.reason;
    ASSERT_EQ(off.points.size(), 2u);
    for (const auto& c : off.points) {
      if (c.axis == 2) {
        EXPECT_NEAR(c.approx[0], std::sqrt(2.0), c.radius + 4e-16);
      }
      if (c.axis == 0) {
        EXPECT_NEAR(c.approx[2], 0.25, c.radius + 1e-16);
      }
      EXPECT_LE(c.radius, filter ? 0x1p-46 * 2 : 1e-30);
    }
  }
  // Crossing z = 1 exactly at the corners x = +-1: an edge.
  EXPECT_FALSE(exits(y0, par, {m1, m1, m1}, {p1, p1, p1}).certified);
  // The plane x = 1 against the cylinder x^2 + z^2 = 1: the line x = 1, z = 0 touches; in the
  // box's face x = 1 the plane is the face itself (zero form): not certified either way.
  Mat4 cyl;
  cyl[0][0] = cyl[2][2] = Rational(1);
  cyl[3][3] = Rational(-1);
  const Mat4 x1 = plane({Rational(1), Rational(0), Rational(0), Rational(-1)});
  EXPECT_FALSE(exits(x1, cyl, {m1, m1, m1}, {p1, p1, p1}).certified);
  // A hyperbolic paraboloid z = x y and the plane z = 0: the lines x = 0 and y = 0 lie in the
  // plane; in the box the face y = 1/2 meets the plane z = 0 along a line on which z - x y is
  // -x/2: one simple root x = 0, inside the face (-1, 1) x (-1, 1).
  Mat4 hp;
  hp[0][1] = hp[1][0] = Rational(1, 2);
  hp[2][3] = hp[3][2] = Rational(-1, 2);
  const Mat4 z0 = plane({Rational(0), Rational(0), Rational(1), Rational(0)});
  const auto lines = exits(z0, hp, {m1, Rational(-1, 3), m1}, {p1, Rational(1, 2), p1});
  ASSERT_TRUE(lines.certified) << lines.reason;
  EXPECT_EQ(lines.points.size(), 4u); // x = 0 at y = -1/3, 1/2; y = 0 at x = -1, 1
}
