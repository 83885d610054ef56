// Two smooth ovals with four real points at infinity where no member of the pencil is a cone
// or cylinder with a rational apex (det(lA - B) irreducible over Q, checked here with FLINT):
// the points at infinity allow {1 loop, 4 unbounded} and {0 loops, 4 unbounded}, and
// certify/cone_ovals.hpp cannot choose. certify/proven_loops.hpp settles it: a traced closed
// branch proves a loop (lower bound), the critical points of the coordinates box every compact
// component (upper bound). Before it, every pair below was undecided.
//
// Ground truth, independent of surfcert:
//  - PERTURBED (1 loop): A = z^2 - x^2 + 9x + 2y - 9, B = x^2 - y^2 - 1 + (xz + 2yz + z^2/2 +
//    x - z)/64. Unperturbed (the /64 term dropped) it is cone_ovals_test's cylinder case, 1
//    loop (x in [1, 1.5], closed form there) and 4 unbounded; the perturbation keeps the curve
//    smooth (two_ovals, 4 simple points at infinity, both certified here), so the loop persists.
//    Checked by dense sampling too: bench/loop_count_float.py (the curve sampled on 3 x 2000
//    planes of [-30, 30]^3, clustered): 1 loop, 4 unbounded pieces, same at half resolution.
//  - PERTURBED0 (0 loops): A = z^2 - x^2 - y + 9 against the same B: unperturbed 0 loops
//    (cone_ovals_test, closed form); loop_count_float.py [-40, 40]^3: 0 loops, 4 pieces; sympy
//    (offline): the eliminant of the z-critical points Res_x(Res_y(f, g), Res_y(f, h_z)) has no
//    real root, so z has no critical point on the curve and no component is compact.
//  - RANDOM274 (1 loop) and RANDOM10 (0 loops): pairs 274 and 10 of bench/two_ovals_pairs.py
//    --seed 1 (integer entries in [-5, 5]); loop_count_float.py --R 30 --n 2000: 1 loop and 0
//    loops, each agreeing at half resolution.
//  - RANDOM1039 (0 loops): pair 1039 of 2000 drawn by two_ovals_pairs.py's random_quadric with
//    seed 11 (all morphologies kept); loop_count_float.py --R 30 --n 2000: 0 loops, agreeing at
//    half resolution. No axis, face or body diagonal bounds its compact components by 0 (the
//    critical points of the unbounded arcs in the box): a direction with an entry +-2 does.
#include "support/distance_checks.hpp"
#include "support/fixtures.hpp"
#include "support/pair_variants.hpp"

#include "surfcert/algebra/pencil.hpp"
#include "surfcert/certify/cone_ovals.hpp"
#include "surfcert/certify/proven_loops.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <flint/fmpz_poly_factor.h>
#include <gtest/gtest.h>

#include <random>

using namespace surfcert;
using certify::Mode;
using core::Mat4;
using core::Rational;
using surfcert::testing::motion;
using surfcert::testing::scaling;

namespace {

const char* kLoopA = "z^2 - x^2 + 9*x + 2*y - 9 = 0";
const char* kNoLoopA = "z^2 - x^2 - y + 9 = 0";
const char* kPerturbedB = "x^2 - y^2 - 1 + (x*z + 2*y*z + z^2/2 + x - z)/64 = 0";

Mat4 ints(const std::array<std::array<long, 4>, 4>& m) {
  Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      r[i][j] = Rational(m[i][j]);
  return r;
}

const Mat4 kRandom274A = ints({{{5, 4, -3, 4}, {4, 4, 0, -1}, {-3, 0, -4, 3}, {4, -1, 3, 3}}});
const Mat4 kRandom274B = ints({{{1, -4, 1, -3}, {-4, -1, 1, 3}, {1, 1, 1, -5}, {-3, 3, -5, -4}}});
const Mat4 kRandom10A = ints({{{-2, 3, 2, 4}, {3, -5, -5, 5}, {2, -5, 4, -2}, {4, 5, -2, -1}}});
const Mat4 kRandom10B = ints({{{5, 2, -3, 3}, {2, 0, 2, 1}, {-3, 2, -4, -2}, {3, 1, -2, 4}}});
const Mat4 kRandom1039A =
    ints({{{1, -2, 2, -3}, {-2, -4, -5, 4}, {2, -5, -3, -3}, {-3, 4, -3, 1}}});
const Mat4 kRandom1039B =
    ints({{{-5, -4, 3, -3}, {-4, 0, 0, -4}, {3, 0, -2, -1}, {-3, -4, -1, -3}}});

// det(lA - B) irreducible over Q (FLINT's factorisation of its primitive integer multiple).
bool char_poly_irreducible(const Mat4& a, const Mat4& b) {
  const algebra::UPolyZ p = algebra::pencil_char_poly(a, b).primitive_integer();
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  fmpz_poly_factor(fac, p.raw());
  const bool irreducible = fac->num == 1 && fac->exp[0] == 1;
  fmpz_poly_factor_clear(fac);
  return irreducible;
}

void expect_settled(const Mat4& a0, const Mat4& b0, int loops, const std::string& what) {
  ASSERT_TRUE(char_poly_irreducible(a0, b0)) << what;
  for (const auto& v : surfcert::testing::pair_variants(a0, b0)) {
    const std::string ctx = what + " " + v.name;
    // No cone member of the pencil decides (A, B themselves are no cones; no rational root).
    EXPECT_FALSE(certify::cone_oval_counts(v.a.matrix(), v.b.matrix(), 2, 4)) << ctx;
    EXPECT_FALSE(certify::cone_oval_counts(v.b.matrix(), v.a.matrix(), 2, 4)) << ctx;
    const auto r = trace::intersect_curve(v.a, v.b, Mode::Exact, {});
    ASSERT_TRUE(r.topology.morphology) << ctx;
    ASSERT_EQ(r.topology.morphology->id, std::string("two_ovals")) << ctx;
    ASSERT_EQ(r.affine.points_at_infinity.size(), 4u) << ctx;
    ASSERT_TRUE(r.affine.certified()) << ctx;
    EXPECT_EQ(r.affine.route, "proven_loops") << ctx;
    EXPECT_EQ(*r.affine.loops, loops) << ctx;
    EXPECT_EQ(*r.affine.unbounded_branches, 4) << ctx;
    // A loop is proven by its box; 0 loops only by the upper bound.
    EXPECT_EQ(r.affine.loop_boxes.size(), static_cast<size_t>(loops)) << ctx;
    ASSERT_EQ(r.status, certify::Status::Certified) << ctx << ": " << r.note;
    int closed = 0;
    for (const auto& br : r.branches)
      closed += br.closed ? 1 : 0;
    EXPECT_EQ(closed, loops) << ctx;
    ASSERT_TRUE(r.box_exits && r.box_exits->certified) << ctx;
  }
}

} // namespace

TEST(ProvenLoops, PerturbedCylinderPencilHasOneLoop) {
  expect_settled(surfcert::testing::q(kLoopA).matrix(), surfcert::testing::q(kPerturbedB).matrix(),
                 1, "perturbed");
}

TEST(ProvenLoops, RandomPairWithOneLoop) {
  expect_settled(kRandom274A, kRandom274B, 1, "random274");
}

TEST(ProvenLoops, NoLoopIsCertifiedOnlyByTheUpperBound) {
  // 0 loops: nothing traced closed, nothing proven below; the answer is certified only when
  // loops_upper_bound proves at most 0 compact components, else undecided.
  for (const auto& [a0, b0] : {std::pair<Mat4, Mat4>{surfcert::testing::q(kNoLoopA).matrix(),
                                                     surfcert::testing::q(kPerturbedB).matrix()},
                               std::pair<Mat4, Mat4>{kRandom10A, kRandom10B},
                               std::pair<Mat4, Mat4>{kRandom1039A, kRandom1039B}}) {
    ASSERT_TRUE(char_poly_irreducible(a0, b0));
    const auto u = certify::loops_upper_bound(a0, b0, 0);
    ASSERT_TRUE(u.bound.has_value()) << u.reason;
    EXPECT_EQ(*u.bound, 0);
    expect_settled(a0, b0, 0, "no loop");
  }
}

TEST(ProvenLoops, UpperBoundNeverBelowTheLoops) {
  // The loop pairs: a bound below 1 would certify a missed loop away.
  for (const auto& [a0, b0] : {std::pair<Mat4, Mat4>{surfcert::testing::q(kLoopA).matrix(),
                                                     surfcert::testing::q(kPerturbedB).matrix()},
                               std::pair<Mat4, Mat4>{kRandom274A, kRandom274B}}) {
    const auto u = certify::loops_upper_bound(a0, b0, 0);
    if (u.bound) {
      EXPECT_GE(*u.bound, 1);
      // The box of the critical values (critical_value_polynomial's slabs) holds the loop the
      // trace proved in its own box (prove_loop_in_box: an independent proof).
      const auto r =
          trace::intersect_curve(core::QuadricMatrix(a0), core::QuadricMatrix(b0), Mode::Exact, {});
      ASSERT_EQ(r.affine.loop_boxes.size(), 1u);
      for (size_t k = 0; k < 3; ++k) {
        EXPECT_LE(u.box.lo[k], r.affine.loop_boxes[0][0][k]) << k;
        EXPECT_GE(u.box.hi[k], r.affine.loop_boxes[0][1][k]) << k;
      }
    }
  }
}

TEST(ProvenLoops, BoxProofs) {
  const Mat4 a = surfcert::testing::q(kLoopA).matrix();
  const Mat4 b = surfcert::testing::q(kPerturbedB).matrix();
  const auto r =
      trace::intersect_curve(core::QuadricMatrix(a), core::QuadricMatrix(b), Mode::Exact, {});
  ASSERT_EQ(r.affine.loop_boxes.size(), 1u);
  certify::RationalBox loop{r.affine.loop_boxes[0][0], r.affine.loop_boxes[0][1]};
  // The box the trace proved holds the loop (x in ~[0.84, 1.65]: the unperturbed loop has
  // x in [1, 1.5]).
  const auto in = certify::prove_loop_in_box(a, b, loop);
  ASSERT_TRUE(in.proven) << in.reason;
  EXPECT_GE(in.crossings, 2);
  EXPECT_GT(loop.lo[0], Rational(1, 2));
  EXPECT_LT(loop.hi[0], Rational(2));
  // Cut through the middle of each axis: the curve crosses the faces, no proof.
  for (size_t k = 0; k < 3; ++k) {
    certify::RationalBox cut = loop;
    cut.hi[k] = (loop.lo[k] + loop.hi[k]) / Rational(2);
    const auto c = certify::prove_loop_in_box(a, b, cut);
    EXPECT_FALSE(c.proven) << "axis " << k;
  }
  // A box with no point of the curve (far off): no face crossed, no split crossed either.
  const certify::RationalBox far{{Rational(100), Rational(100), Rational(100)},
                                 {Rational(101), Rational(102), Rational(103)}};
  const auto f = certify::prove_loop_in_box(a, b, far);
  EXPECT_FALSE(f.proven);
  EXPECT_EQ(f.reason, "no split plane of the box crosses the curve");
  // A box around both ovals' pieces and more: the unbounded branches cross it.
  const certify::RationalBox big{{Rational(-50), Rational(-50), Rational(-50)},
                                 {Rational(50), Rational(50), Rational(50)}};
  EXPECT_FALSE(certify::prove_loop_in_box(a, b, big).proven);
  // The same loop proposed twice (and an overlapping box) counts once.
  certify::RationalBox wider = loop;
  for (size_t k = 0; k < 3; ++k)
    wider.lo[k] -= Rational(1, 8), wider.hi[k] += Rational(1, 8);
  const auto p = certify::proven_loops(a, b, {{loop}, {wider}, {far}});
  EXPECT_EQ(p.count, 1);
  EXPECT_EQ(p.rejected.size(), 2u);
}

TEST(ProvenLoops, SettleKeepsOnlyReadingsTheBoundsAllow) {
  certify::AffineTopology t;
  t.computed = true;
  t.route = "pencil";
  t.unbounded_branches = 4;
  t.readings = {{0, 4}, {1, 4}};
  t.undecided = {{"loops", "several"}};
  certify::ProvenLoops none;
  EXPECT_FALSE(certify::settle_by_proven_loops(t, none));
  EXPECT_FALSE(t.loops);
  certify::ProvenLoops one;
  one.count = 1;
  one.boxes.push_back(
      {{Rational(0), Rational(0), Rational(0)}, {Rational(1), Rational(1), Rational(1)}});
  certify::AffineTopology t1 = t;
  ASSERT_TRUE(certify::settle_by_proven_loops(t1, one));
  EXPECT_EQ(*t1.loops, 1);
  EXPECT_EQ(t1.route, "proven_loops");
  EXPECT_TRUE(t1.undecided.empty());
  // Two proven where the readings allow one at most: inconsistent, nothing settled.
  certify::ProvenLoops two = one;
  two.count = 2;
  certify::AffineTopology t2 = t;
  EXPECT_FALSE(certify::settle_by_proven_loops(t2, two));
  // An upper bound 0 with nothing proven below: 0 loops.
  certify::LoopUpperBound u;
  u.bound = 0;
  certify::AffineTopology t3 = t;
  ASSERT_TRUE(certify::settle_by_proven_loops(t3, none, &u));
  EXPECT_EQ(*t3.loops, 0);
  // An upper bound 1 decides nothing when nothing was proven below.
  u.bound = 1;
  certify::AffineTopology t4 = t;
  EXPECT_FALSE(certify::settle_by_proven_loops(t4, none, &u));
}

namespace {

// A quadric x^T M3 x + 2 l.x + c through the rational point p with gradient grad at p: M3 given,
// l = grad / 2 - M3 p, c from f(p) = 0.
Mat4 through(const std::array<std::array<long, 3>, 3>& m3, const std::array<Rational, 3>& p,
             const std::array<Rational, 3>& grad) {
  Mat4 m;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      m[i][j] = Rational(m3[i][j]);
  Rational c(0);
  for (size_t i = 0; i < 3; ++i) {
    Rational mp(0);
    for (size_t j = 0; j < 3; ++j)
      mp += m[i][j] * p[j];
    m[i][3] = m[3][i] = grad[i] / Rational(2) - mp;
  }
  for (size_t i = 0; i < 3; ++i) { // f(p) = p^T M3 p + 2 l.p + c = 0
    for (size_t j = 0; j < 3; ++j)
      c -= m[i][j] * p[i] * p[j];
    c -= Rational(2) * m[i][3] * p[i];
  }
  m[3][3] = c;
  return m;
}

} // namespace

// critical_value_polynomial (the slab of loops_upper_bound): its real roots must include every
// critical value of x_k on the curve. Independent route: pairs built through a rational point P
// with grad g(P) = grad f(P) + t e_k, so that the tangent grad f x grad g is perpendicular to
// e_k there: P is a critical point of x_k and D_k(P_k) must vanish exactly. The same pairs with
// t e_j (j != k) instead: P is not critical for x_k and D_k(P_k) is nonzero for almost every
// draw (a wrong polynomial that vanished everywhere, or nowhere, fails one side). A cone with
// apex P against a quadric through P: the curve is singular at P, a root for every axis.
TEST(ProvenLoops, CriticalValuePolynomialVanishesAtEveryCriticalValue) {
  std::mt19937 rng(36);
  std::uniform_int_distribution<long> e(-5, 5), num(-40, 40), den(1, 9);
  auto sym = [&] {
    std::array<std::array<long, 3>, 3> m{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = i; j < 3; ++j)
        m[i][j] = m[j][i] = e(rng);
    return m;
  };
  auto rat = [&] { return Rational(num(rng), den(rng)); };
  int critical = 0, not_critical_nonzero = 0, draws = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const std::array<Rational, 3> p{rat(), rat(), rat()};
    std::array<Rational, 3> gf{rat(), rat(), rat()};
    const size_t k = static_cast<size_t>(trial % 3), j = (k + 1) % 3;
    const Rational t(1 + trial % 4);
    std::array<Rational, 3> gk = gf, gj = gf;
    gk[k] += t;
    gj[j] += t;
    const Mat4 a = through(sym(), p, gf);
    const auto m3 = sym();
    const Mat4 bk = through(m3, p, gk), bj = through(m3, p, gj);
    const auto dk = certify::critical_value_polynomial(a, bk, static_cast<int>(k));
    ASSERT_FALSE(dk.is_zero()) << trial;
    EXPECT_LE(dk.degree(), 8) << trial;
    EXPECT_EQ(dk.sign_at(p[k]), 0) << "trial " << trial << ": P is critical for x_" << k;
    critical += dk.sign_at(p[k]) == 0 ? 1 : 0;
    const auto dj = certify::critical_value_polynomial(a, bj, static_cast<int>(k));
    if (!dj.is_zero()) {
      ++draws;
      not_critical_nonzero += dj.sign_at(p[k]) != 0 ? 1 : 0;
    }
    // A positive factor on either quadric, and the order of the two, change nothing.
    Mat4 a2 = a, b3 = bk;
    for (auto& row : a2)
      for (auto& x : row)
        x *= Rational(2);
    for (auto& row : b3)
      for (auto& x : row)
        x *= Rational(3, 7);
    EXPECT_EQ(certify::critical_value_polynomial(a2, b3, static_cast<int>(k)), dk) << trial;
    EXPECT_EQ(certify::critical_value_polynomial(bk, a, static_cast<int>(k)), dk) << trial;
  }
  EXPECT_EQ(critical, 60);
  EXPECT_GE(draws, 55);
  EXPECT_GE(not_critical_nonzero, draws - 2);
  // Singular point: the cone (x - 1)^2 + (y + 2)^2 - (z - 3/2)^2 = 0 (apex (1, -2, 3/2)) against
  // quadrics through the apex.
  const std::array<Rational, 3> apex{Rational(1), Rational(-2), Rational(3, 2)};
  const Mat4 cone =
      through({{{1, 0, 0}, {0, 1, 0}, {0, 0, -1}}}, apex, {Rational(0), Rational(0), Rational(0)});
  for (int trial = 0; trial < 10; ++trial) {
    const Mat4 other = through(sym(), apex, {rat(), rat(), rat()});
    for (int k = 0; k < 3; ++k) {
      const auto d = certify::critical_value_polynomial(cone, other, k);
      ASSERT_FALSE(d.is_zero()) << trial;
      EXPECT_EQ(d.sign_at(apex[static_cast<size_t>(k)]), 0) << trial << " axis " << k;
    }
  }
}
