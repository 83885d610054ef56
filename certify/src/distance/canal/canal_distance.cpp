#include "surfcert/certify/distance/canal_distance.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/kernel.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/solution_cover.hpp"
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/convex_quadric.hpp"
#include "surfcert/certify/distance/offset_minimum.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/certify/distance/quadratic_forms.hpp"

#include <flint/fmpq_mpoly_factor.h>
#include <flint/fmpz_poly_factor.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace surfcert::certify {

using core::Integer;
using core::Poly3;
using core::Rational;

namespace {

// Ball value of a rational coefficient list at the ball t.
void eval_ball(arb_t out, const std::vector<Rational>& c, const arb_t t, long prec) {
  Ball b;
  arb_zero(out);
  for (size_t i = c.size(); i-- > 0;) {
    arb_mul(out, out, t, prec);
    arb_set_fmpq(b.v, c[i].raw(), prec);
    arb_add(out, out, b.v, prec);
  }
}

std::vector<Rational> derivative(const std::vector<Rational>& c) {
  std::vector<Rational> d;
  for (size_t i = 1; i < c.size(); ++i)
    d.push_back(c[i] * Rational(static_cast<long>(i)));
  if (d.empty()) d.push_back(Rational(0));
  return d;
}

// Exact: does the polynomial vanish somewhere in [t0, t1]? (isolation + exact refinement)
bool has_root_in(const std::vector<Rational>& c, const Rational& t0, const Rational& t1) {
  algebra::UPolyQ p = algebra::UPolyQ::from_coeffs(c);
  if (p.degree() <= 0) return p.is_zero();
  algebra::UPolyZ z = p.primitive_integer();
  fmpz_poly_factor_t f;
  fmpz_poly_factor_init(f);
  fmpz_poly_factor_squarefree(f, z.raw());
  algebra::UPolyZ sq;
  fmpz_poly_one(sq.raw_mut());
  for (slong i = 0; i < f->num; ++i)
    fmpz_poly_mul(sq.raw_mut(), sq.raw(), f->p + i);
  fmpz_poly_factor_clear(f);
  algebra::RootSeparation s = algebra::isolate_real_roots(sq);
  for (size_t i = 0; i + 1 < s.separators.size(); ++i) {
    Rational lo = s.separators[i], hi = s.separators[i + 1];
    // The root lies in (lo, hi); decide its position against t0 and t1 by refinement.
    for (int k = 0; k < 4000; ++k) {
      if (hi < t0 || lo > t1) break;             // outside
      if (!(lo < t0) && !(hi > t1)) return true; // inside
      if (lo == hi) return !(lo < t0) && !(lo > t1);
      if (sq.sign_at(t0) == 0 || sq.sign_at(t1) == 0) return true;
      algebra::refine_root(sq, lo, hi, (hi - lo) * Rational(1, 2));
    }
  }
  return false;
}

// dist(x, S1) for a rational point x, as a ball (exact point-quadric sextic, or a plane's
// closed form); the foot (approximate) in `foot`. nullopt when undecided.
bool point_distance(arb_t out, const std::array<Rational, 3>& x, const core::QuadricMatrix& q,
                    long digits, std::array<double, 3>& foot) {
  const long prec = bits_for(digits + 10);
  if (q.is_plane()) {
    Rational v = q(3, 3), nn;
    for (int i = 0; i < 3; ++i) {
      v += Rational(2) * q(i, 3) * x[static_cast<size_t>(i)];
      nn += Rational(4) * q(i, 3) * q(i, 3);
    }
    Rational d2 = v * v / nn;
    arb_set_fmpq(out, d2.raw(), prec);
    arb_sqrt(out, out, prec);
    for (size_t i = 0; i < 3; ++i)
      foot[i] = x[i].to_double_approx() -
                (v / nn).to_double_approx() * 2 * q(static_cast<int>(i), 3).to_double_approx();
    return true;
  }
  PointQuadricResult pq = point_quadric_critical(x, q, digits + 5);
  if (!pq.ok || pq.criticals.empty()) return false;
  // criticals are sorted by certified lower bounds: [front.lower, front.upper] contains the
  // minimum (min lower <= min <= front's value <= front.upper), whichever candidate attains it;
  // the foot is display only.
  Ball hi;
  arb_set_str(out, pq.criticals.front().lower.c_str(), prec);
  arb_set_str(hi.v, pq.criticals.front().upper.c_str(), prec);
  arb_union(out, out, hi.v, prec);
  foot = pq.criticals.front().foot;
  return true;
}

struct Candidate {
  Ball lo, up;     // lower bound of phi over the t-interval; phi(t_c) (a ball)
  Rational tc;     // the rational parameter of the upper bound
  Rational ta, tb; // the t-interval (hull of the merged ones): a tie region is C([ta, tb])
  // Which critical parameter this is, exactly: the index of its isolated root (distinct
  // indices are distinct real numbers), or kEnd0 / kEnd1 for t0 / t1 (a root equal to an end
  // is given the end's key, decided by an exact evaluation).
  long key = 0;
  std::array<double, 3> p{}, q{};
};

// phi(t_c) = dist(C(t_c), S1) - r(t_c), and the lower bound over [ta, tb] (see header).
bool candidate(Candidate& cd, const core::QuadricMatrix& q, const core::CanalSurface& c,
               const Rational& ta, const Rational& tb, long digits) {
  const long prec = bits_for(digits + 10);
  cd.tc = (ta + tb) * Rational(1, 2);
  cd.ta = ta;
  cd.tb = tb;
  std::array<Rational, 3> x;
  for (size_t i = 0; i < 3; ++i)
    x[i] = core::eval_poly(c.spine[i], cd.tc);
  Ball d, rc;
  if (!point_distance(d.v, x, q, digits + 8, cd.p)) return false;
  Rational rtc = core::eval_poly(c.radius, cd.tc);
  arb_set_fmpq(rc.v, rtc.raw(), prec);
  arb_sub(cd.up.v, d.v, rc.v, prec);
  // sup |C(T) - C(t_c)| and sup r(T) over the interval ball T.
  Ball T, tb_, dc, s, rT;
  arb_set_fmpq(T.v, ta.raw(), prec);
  arb_set_fmpq(tb_.v, tb.raw(), prec);
  arb_union(T.v, T.v, tb_.v, prec);
  for (size_t i = 0; i < 3; ++i) {
    Ball ci, xi;
    eval_ball(ci.v, c.spine[i], T.v, prec);
    arb_set_fmpq(xi.v, x[i].raw(), prec);
    arb_sub(ci.v, ci.v, xi.v, prec);
    arb_addmul(s.v, ci.v, ci.v, prec);
  }
  arb_sqrtpos(s.v, s.v, prec);
  eval_ball(rT.v, c.radius, T.v, prec);
  arf_t a;
  arf_init(a);
  arb_get_ubound_arf(a, s.v, prec);
  arb_set_arf(s.v, a);
  arb_get_ubound_arf(a, rT.v, prec);
  arb_set_arf(rT.v, a);
  arf_clear(a);
  arb_sub(cd.lo.v, d.v, s.v, prec);
  arb_sub(cd.lo.v, cd.lo.v, rT.v, prec);
  // The pair at t_c (approximate): foot p on S1, q on the sphere of C(t_c) toward p.
  double n = 0;
  for (size_t i = 0; i < 3; ++i)
    n += (cd.p[i] - x[i].to_double_approx()) * (cd.p[i] - x[i].to_double_approx());
  n = std::sqrt(n);
  for (size_t i = 0; i < 3; ++i)
    cd.q[i] = x[i].to_double_approx() +
              (n > 0 ? rtc.to_double_approx() * (cd.p[i] - x[i].to_double_approx()) / n : 0);
  return true;
}

constexpr long kEnd0 = -1, kEnd1 = -2;
// Keys of the parameters with feet on singular lines (singular_line_parameters): the roots
// of line k's cover at kSingularKeys + k kSingularStride + index, the isolated ones below
// kSingularKeys; all far above the main cover's indices.
constexpr long kSingularKeys = 1L << 40, kSingularStride = 1L << 20;

// Whether the foot of every spine point C(t), t in [ta, tb], on q is unique, proven: always
// for a plane; for a sphere when C([ta, tb]) avoids its centre; for the convex solid of an
// ellipsoid or elliptic cylinder when C([ta, tb]) is strictly outside it (the nearest point of
// a convex set to an outside point is unique).
// Otherwise unknown (a point inside, or a non-convex quadric, may have several feet).
bool unique_foot(const core::QuadricMatrix& q, const core::CanalSurface& c, const Rational& ta,
                 const Rational& tb) {
  if (q.is_plane()) return true;
  const auto cq = convex_quadric(q);
  if (!cq || cq->is_paraboloid()) return false;
  const long prec = 128;
  Ball T, hi, x[4], v, term;
  arb_set_fmpq(T.v, ta.raw(), prec);
  arb_set_fmpq(hi.v, tb.raw(), prec);
  arb_union(T.v, T.v, hi.v, prec);
  for (size_t i = 0; i < 3; ++i)
    eval_ball(x[i].v, c.spine[i], T.v, prec);
  arb_one(x[3].v);
  if (q.is_sphere()) { // inside too: every point but the centre has one nearest point
    Ball d2, ci;
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(ci.v, cq->c[i].raw(), prec);
      arb_sub(ci.v, x[i].v, ci.v, prec);
      arb_addmul(d2.v, ci.v, ci.v, prec);
    }
    if (arb_is_positive(d2.v)) return true;
  }
  // sign of q on C(T) against its sign at the centre (inside the solid).
  std::array<Rational, 4> centre{cq->c[0], cq->c[1], cq->c[2], Rational(1)};
  Rational at_centre;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      at_centre += q(i, j) * centre[static_cast<size_t>(i)] * centre[static_cast<size_t>(j)];
      arb_mul(term.v, x[i].v, x[j].v, prec);
      Ball qij;
      arb_set_fmpq(qij.v, q(i, j).raw(), prec);
      arb_addmul(v.v, qij.v, term.v, prec);
    }
  const int inside = at_centre.sign();
  return inside != 0 && (inside < 0 ? arb_is_positive(v.v) : arb_is_negative(v.v));
}

// The (alpha, t) system over Z (variables x = alpha, y = t).
// Returns F, G and det(I + alpha M3).
std::array<Poly3, 3> canal_system(const core::QuadricMatrix& q, const core::CanalSurface& c) {
  Integer den(1);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      fmpz_lcm(den.raw_mut(), den.raw(), q(i, j).den().raw());
  auto Mq = [&](int i, int j) { return Poly3((q(i, j) * Rational(den)).num()); };
  Integer dc(1), dr(1);
  for (const auto& s : c.spine)
    for (const auto& v : s)
      fmpz_lcm(dc.raw_mut(), dc.raw(), v.den().raw());
  const auto rp = derivative(c.radius);
  for (const auto& v : rp)
    fmpz_lcm(dr.raw_mut(), dr.raw(), v.den().raw());
  const Poly3 al = Poly3::variable(0), t = Poly3::variable(1);
  auto poly_t = [&](const std::vector<Rational>& cf, const Integer& scale) {
    Poly3 r, pw(1);
    for (const auto& v : cf) {
      r = r + Poly3((v * Rational(scale)).num()) * pw;
      pw = pw * t;
    }
    return r;
  };
  std::array<Poly3, 3> C, Cp;
  for (size_t i = 0; i < 3; ++i) {
    C[i] = poly_t(c.spine[i], dc);
    Cp[i] = poly_t(derivative(c.spine[i]), dc);
  }
  // A = I + alpha M3; adjugate and determinant.
  std::array<std::array<Poly3, 3>, 3> A;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      A[static_cast<size_t>(i)][static_cast<size_t>(j)] =
          (i == j ? Poly3(1) : Poly3(0)) + al * Mq(i, j);
  auto a = [&](size_t i, size_t j) -> const Poly3& { return A[i][j]; };
  std::array<std::array<Poly3, 3>, 3> adj;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      // adj[i][j] = cofactor of a(j, i)
      size_t r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      adj[i][j] = a(r0, c0) * a(r1, c1) - a(r0, c1) * a(r1, c0);
    }
  const Poly3 D = a(0, 0) * adj[0][0] + a(0, 1) * adj[1][0] + a(0, 2) * adj[2][0];
  std::array<Poly3, 3> V, Np;
  for (size_t i = 0; i < 3; ++i)
    V[i] = C[i] - al * Poly3(dc) * Mq(static_cast<int>(i), 3);
  for (size_t i = 0; i < 3; ++i)
    Np[i] = adj[i][0] * V[0] + adj[i][1] * V[1] + adj[i][2] * V[2];
  const Poly3 den_p = Poly3(dc) * D; // p = Np / den_p
  Poly3 F = Mq(3, 3) * den_p * den_p;
  for (size_t i = 0; i < 3; ++i) {
    F = F + Poly3(2) * Mq(static_cast<int>(i), 3) * Np[i] * den_p;
    for (size_t j = 0; j < 3; ++j)
      F = F + Np[i] * Mq(static_cast<int>(i), static_cast<int>(j)) * Np[j];
  }
  std::array<Poly3, 3> u; // dc D (C - p)
  for (size_t i = 0; i < 3; ++i)
    u[i] = C[i] * D - Np[i];
  const Poly3 uc = u[0] * Cp[0] + u[1] * Cp[1] + u[2] * Cp[2];
  bool const_r = true;
  for (const auto& v : rp)
    const_r = const_r && v.is_zero();
  if (const_r) return {F, uc, D};
  const Poly3 rpt = poly_t(rp, dr), uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  return {F, Poly3(dr) * Poly3(dr) * uc * uc - Poly3(dc) * Poly3(dc) * rpt * rpt * uu, D};
}

// Divides F and G by their common factors that involve alpha only (see the caller), each
// irreducible one given in `stripped`; false (with a note) when a common factor involves t.
bool strip_alpha_factors(Poly3& F, Poly3& G, const Poly3& D, std::vector<Poly3>& stripped,
                         std::string& note) {
  Poly3 H = algebra::gcd(F, G);
  if (H.is_constant()) return true;
  fmpq_mpoly_factor_t fac;
  fmpq_mpoly_factor_init(fac, Poly3::ctx());
  if (!fmpq_mpoly_factor(fac, H.raw(), Poly3::ctx())) {
    fmpq_mpoly_factor_clear(fac, Poly3::ctx());
    note = "factorisation failed";
    return false;
  }
  bool ok = true;
  for (slong i = 0; i < fac->num && ok; ++i) {
    Poly3 h;
    fmpq_mpoly_set(h.raw_mut(), fac->poly + i, Poly3::ctx());
    Poly3 quo;
    if (h.degree(1) > 0 || !fmpq_mpoly_divides(quo.raw_mut(), D.raw(), h.raw(), Poly3::ctx())) {
      ok = false; // a genuine curve of critical pairs (or the spine on the quadric)
      note = "the canal system has a curve of solutions (a common factor not from the "
             "parametrisation)";
      break;
    }
    for (Poly3* P : {&F, &G})
      for (;;) {
        Poly3 qd;
        if (!fmpq_mpoly_divides(qd.raw_mut(), P->raw(), h.raw(), Poly3::ctx())) break;
        *P = qd;
      }
    stripped.push_back(std::move(h));
  }
  fmpq_mpoly_factor_clear(fac, Poly3::ctx());
  return ok;
}

// The critical parameters hidden by the factors strip_alpha_factors divides out. A factor
// h(alpha) of det(I + alpha Q3) divides F and G when, on its line alpha = alpha_i
// (alpha_i = -1/lambda for an eigenvalue lambda of Q3), M = I + alpha_i Q3 is singular: the
// feet there are not p(alpha, t) but the solutions of M X = w(t) = C(t) - alpha_i b, which
// exist iff n.w(t) = 0 for every n in ker M, and then form a line (or plane) of candidates.
// Dividing h out loses every critical pair with such a foot: the cone x^2 + y^2 = z^2 and the
// capsule on (5, t, 0), t in [-1, 1], radius 1: the nearest feet of (5, 0, 0) are
// (5/2, 0, +-5/2), at alpha = 1, and the distance 5/sqrt 2 - 1 was certified as the ends'
// sqrt 13 - 1. So, for each stripped factor (a double or triple eigenvalue is rational; a
// simple irrational one is declined):
//  - the n.w(t) not all identically zero: singular feet exist only at their common real
//    roots, which are added as candidate parameters (a superset is sound);
//  - all identically zero and ker M of dimension 1 (a simple eigenvalue: the spine lies in
//    that principal plane): the feet are X = X_p(t) + s v (v spans ker M, X_p = K^-1 w with
//    K = M + v v^T / v.v, so X_p is orthogonal to v); f(X) = 0 and the envelope condition
//    (squared as in canal_system) are two equations in (s, t), covered exactly like the main
//    system, and their t-intervals are added;
//  - otherwise (the whole spine on an axis of revolution or at a sphere's centre): declined.
// Every added parameter gets the same lower bound over its interval as the main ones.
struct SingularParameters {
  std::vector<algebra::SolutionCover> covers; ///< (s, t) systems of singular lines
  std::vector<algebra::UPolyZ> factors;       ///< isolated parameters with singular feet
  std::vector<algebra::RootInterval> roots;
};

bool singular_line_parameters(const core::QuadricMatrix& q, const core::CanalSurface& c,
                              const std::vector<Poly3>& stripped, SingularParameters& out,
                              std::string& note) {
  for (const Poly3& h : stripped) {
    if (h.degree(0) != 1) {
      note = "feet on a singular line of the point-quadric parametrisation at an irrational "
             "alpha (a simple irrational eigenvalue whose principal plane holds the spine)";
      return false;
    }
    Rational h0, h1;
    h.for_each_term(
        [&](const Poly3::Exponent& e, const Rational& v) { (e[0] == 0 ? h0 : h1) = v; });
    // canal_system's alpha multiplies den Q3 (den: the lcm of q's denominators).
    Integer den(1);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        fmpz_lcm(den.raw_mut(), den.raw(), q(i, j).den().raw());
    const Rational al = -h0 / h1 * Rational(den);
    core::Mat4 m{}; // M = I + alpha_i Q3, bordered by 1: kernel vectors end in 0
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        m[i][j] = Rational(i == j ? 1 : 0) +
                  (i < 3 && j < 3 ? al * q(static_cast<int>(i), static_cast<int>(j)) : Rational(0));
    const auto ker = algebra::kernel_basis(m);
    std::array<std::vector<Rational>, 3> w; // C(t) - alpha_i b
    for (size_t i = 0; i < 3; ++i) {
      w[i] = c.spine[i];
      if (w[i].empty()) w[i].push_back(Rational(0));
      w[i][0] -= al * q(static_cast<int>(i), 3);
    }
    algebra::UPolyQ g; // gcd of the nonzero n.w(t)
    bool all_zero = true;
    for (const auto& n : ker) {
      algebra::UPolyQ p;
      for (size_t i = 0; i < 3; ++i)
        p = p + algebra::UPolyQ(n[i]) * algebra::UPolyQ::from_coeffs(w[i]);
      if (p.is_zero()) continue;
      if (all_zero)
        g = p;
      else
        fmpq_poly_gcd(g.raw_mut(), g.raw(), p.raw());
      all_zero = false;
    }
    if (!all_zero) {
      if (g.degree() <= 0) continue; // no singular foot for any t
      for (algebra::IrreducibleFactor& f : algebra::irreducible_factors(g.primitive_integer())) {
        algebra::RootSeparation sep = algebra::isolate_real_roots(f.poly);
        for (size_t k = 0; k + 1 < sep.separators.size(); ++k)
          out.roots.push_back({sep.separators[k], sep.separators[k + 1], out.factors.size()});
        out.factors.push_back(std::move(f.poly));
      }
      continue;
    }
    if (ker.size() != 1) {
      note = "a continuum of feet along the whole spine (an axis of revolution or a centre)";
      return false;
    }
    const std::array<Rational, 3> v{ker[0][0], ker[0][1], ker[0][2]};
    const Rational vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    std::array<std::array<Rational, 3>, 3> K, Ki;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        K[i][j] = m[i][j] + v[i] * v[j] / vv;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const size_t r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
        Ki[i][j] = K[r0][c0] * K[r1][c1] - K[r0][c1] * K[r1][c0]; // adjugate
      }
    const Rational det = K[0][0] * Ki[0][0] + K[0][1] * Ki[1][0] + K[0][2] * Ki[2][0];
    const Poly3 s = Poly3::variable(0), t = Poly3::variable(1);
    auto poly_t = [&](const std::vector<Rational>& cf) {
      Poly3 r, pw(1);
      for (const auto& a : cf) {
        r = r + Poly3(a) * pw;
        pw = pw * t;
      }
      return r;
    };
    std::array<Poly3, 3> X, u;
    for (size_t i = 0; i < 3; ++i) {
      X[i] = Poly3(v[i]) * s;
      for (size_t j = 0; j < 3; ++j)
        X[i] = X[i] + Poly3(Ki[i][j] / det) * poly_t(w[j]);
      u[i] = poly_t(c.spine[i]) - X[i];
    }
    Poly3 F(q(3, 3)), G;
    for (size_t i = 0; i < 3; ++i) {
      F = F + Poly3(Rational(2) * q(static_cast<int>(i), 3)) * X[i];
      for (size_t j = 0; j < 3; ++j)
        F = F + Poly3(q(static_cast<int>(i), static_cast<int>(j))) * X[i] * X[j];
      G = G + u[i] * poly_t(derivative(c.spine[i]));
    }
    const auto rp = derivative(c.radius);
    if (!std::all_of(rp.begin(), rp.end(), [](const Rational& a) { return a.sign() == 0; }))
      G = G * G - poly_t(rp) * poly_t(rp) * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if ((F.is_constant() && !F.is_zero()) || (G.is_constant() && !G.is_zero()))
      continue; // no solution on this line
    if (!algebra::gcd(F, G).is_constant()) {
      note = "a curve of critical pairs with feet on a singular line";
      return false;
    }
    algebra::SolutionCover cover = algebra::cover_real_solutions_2d(F, G, Rational(1, 16));
    if (!cover.ok) {
      note = "feet on a singular line: " + cover.note;
      return false;
    }
    out.covers.push_back(std::move(cover));
  }
  return true;
}

// A certified point of the ellipsoid outside every ball B(C(t), r(t)): the extreme points of
// the ellipsoid in the six axis directions (gradient-line projections from far points,
// SourceQuadric), each tested with |q - C(T)| - r(T) > 0 on 512 subintervals of [t0, t1].
bool ellipsoid_point_outside(const core::QuadricMatrix& q, const core::CanalSurface& c) {
  SourceQuadric src(q);
  const long prec = 128;
  std::array<Rational, 3> base;
  for (size_t i = 0; i < 3; ++i)
    base[i] = core::eval_poly(c.spine[i], c.t0);
  for (size_t axis = 0; axis < 3; ++axis)
    for (long sign : {1L, -1L}) {
      Rational far[3] = {base[0], base[1], base[2]};
      far[axis] += Rational(sign * 100000);
      Ball p[3];
      if (!src.project(far, p, prec)) continue;
      bool outside = true;
      const long pieces = 512;
      for (long k = 0; k < pieces && outside; ++k) {
        const Rational ta = c.t0 + (c.t1 - c.t0) * Rational(k, static_cast<unsigned long>(pieces)),
                       tb = c.t0 +
                            (c.t1 - c.t0) * Rational(k + 1, static_cast<unsigned long>(pieces));
        Ball T, hi, d, r;
        arb_set_fmpq(T.v, ta.raw(), prec);
        arb_set_fmpq(hi.v, tb.raw(), prec);
        arb_union(T.v, T.v, hi.v, prec);
        for (size_t i = 0; i < 3; ++i) {
          Ball ci;
          eval_ball(ci.v, c.spine[i], T.v, prec);
          arb_sub(ci.v, p[i].v, ci.v, prec);
          arb_addmul(d.v, ci.v, ci.v, prec);
        }
        arb_sqrtpos(d.v, d.v, prec);
        eval_ball(r.v, c.radius, T.v, prec);
        arb_sub(d.v, d.v, r.v, prec);
        outside = arb_is_positive(d.v);
      }
      if (outside) return true;
    }
  return false;
}

} // namespace

bool canal_radius_positive(const core::CanalSurface& c) {
  return core::eval_poly(c.radius, c.t0).sign() > 0 && !has_root_in(c.radius, c.t0, c.t1);
}

// The plane n.x + q33 = 0 (n = 2 q(i, 3)) against the spheres (C(t), r(t)): sphere t is
// tangent to the plane iff g(t) = (n.C(t) + q33)^2 - |n|^2 r(t)^2 = 0 (exact, over Q; both
// sides of the squared equation are >= 0 when the spine does not cross the plane). A root in
// [t0, t1] means min phi <= 0: the plane touches or enters the canal solid, and a plane (not
// bounded) then meets the solid's boundary, the canal surface.
// n.C(t) + q33, n = 2 q(i, 3): |n| times the signed distance of the spine from the plane.
std::vector<Rational> plane_side(const core::QuadricMatrix& q, const core::CanalSurface& c) {
  std::vector<Rational> side(1, q(3, 3));
  for (size_t i = 0; i < 3; ++i) {
    const auto& ci = c.spine[i];
    if (side.size() < ci.size()) side.resize(ci.size());
    for (size_t k = 0; k < ci.size(); ++k)
      side[k] += Rational(2) * q(static_cast<int>(i), 3) * ci[k];
  }
  return side;
}

// n x C'(t) not identically 0: the spine moves across the plane's normal.
bool spine_moves_across(const core::QuadricMatrix& q, const core::CanalSurface& c) {
  std::array<algebra::UPolyQ, 3> dc; // C'
  for (size_t i = 0; i < 3; ++i)
    dc[i] = algebra::UPolyQ::from_coeffs(derivative(c.spine[i]));
  std::array<Rational, 3> n;
  for (size_t i = 0; i < 3; ++i)
    n[i] = Rational(2) * q(static_cast<int>(i), 3);
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3, k = (i + 2) % 3;
    if (!(algebra::UPolyQ(n[j]) * dc[k] - algebra::UPolyQ(n[k]) * dc[j]).is_zero()) return true;
  }
  return false;
}

algebra::UPolyQ plane_tangency(const core::QuadricMatrix& q, const core::CanalSurface& c) {
  const algebra::UPolyQ side = algebra::UPolyQ::from_coeffs(plane_side(q, c)),
                        r = algebra::UPolyQ::from_coeffs(c.radius);
  Rational nn;
  for (int i = 0; i < 3; ++i)
    nn += Rational(4) * q(i, 3) * q(i, 3);
  return side * side - algebra::UPolyQ(nn) * r * r;
}

bool sphere_tangent_to_plane(const core::QuadricMatrix& q, const core::CanalSurface& c) {
  const algebra::UPolyQ g = plane_tangency(q, c);
  if (g.is_zero()) return true;
  std::vector<Rational> co;
  for (long k = 0; k <= g.degree(); ++k)
    co.push_back(g.coeff(k));
  return has_root_in(co, c.t0, c.t1);
}

// Every sphere tangent (g = 0 identically) and the spine moving across n: a continuum of
// contact points; otherwise the contact set is not counted here.
Minimizers plane_touch_minimizers(const core::QuadricMatrix& q, const core::CanalSurface& c) {
  if (plane_tangency(q, c).is_zero() && spine_moves_across(q, c))
    return Minimizers::continuum(Minimizers::Proof::Exact);
  return Minimizers::undecided(1);
}

DistanceResult quadric_canal_distance(const core::QuadricMatrix& q, const core::CanalSurface& c,
                                      long digits, bool quadric_first) {
  DistanceResult out;
  auto pair_out = [&](const Candidate& cd) {
    out.pairs.push_back(quadric_first ? std::array<std::array<double, 3>, 2>{cd.p, cd.q}
                                      : std::array<std::array<double, 3>, 2>{cd.q, cd.p});
  };
  if (has_root_in(c.radius, c.t0, c.t1)) {
    out.status = Status::Undecided;
    out.note = "the canal radius vanishes inside the parameter interval";
    return out;
  }
  // A definite quadratic block that is no real ellipsoid: a single point (x^2 + y^2 + z^2 = 0)
  // or nothing. Its point is singular, a foot the (alpha, t) system below never yields, so
  // min phi would be read at the ends of the spine only (a point inside the solid was
  // certified at the end's distance, 0.428 for 0.449).
  if (!components_unbounded(q) && q.kind() != core::QuadricKind::Ellipsoid) {
    out.status = Status::Undecided;
    out.note = "not supported yet: a quadric whose only real point is singular (or none)";
    return out;
  }
  // Interior critical parameters: an exact cover of the (alpha, t) system, or for a plane the
  // roots of the derivative of phi.
  std::vector<algebra::UPolyZ> tfactors;    // plane: factors of the critical-t polynomial
  std::vector<algebra::RootInterval> tints; // and their isolated roots
  std::optional<algebra::SolutionCover> cover;
  SingularParameters singular; // parameters with feet on singular lines (not for a plane)
  bool plane = q.is_plane();
  if (plane) {
    // |n| phi(t) = s (n.C(t) - delta) - |n| r(t): interior critical t solve
    // (n.C')^2 = |n|^2 r'^2 (squared: a superset).
    std::vector<Rational> nc(1, Rational(0)), rp = derivative(c.radius);
    Rational nn;
    for (size_t i = 0; i < 3; ++i) {
      const Rational ni = Rational(2) * q(static_cast<int>(i), 3);
      nn += ni * ni;
      auto d = derivative(c.spine[i]);
      if (nc.size() < d.size()) nc.resize(d.size());
      for (size_t k = 0; k < d.size(); ++k)
        nc[k] += ni * d[k];
    }
    // The spine crossing the plane (n.C(t) = delta inside the interval): they meet.
    const std::vector<Rational> side = plane_side(q, c);
    if (has_root_in(side, c.t0, c.t1)) {
      out.status = Status::Certified;
      out.distance = Enclosure::zero();
      out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
      out.note = "the spine crosses the plane: they meet";
      return out;
    }
    algebra::UPolyQ a = algebra::UPolyQ::from_coeffs(nc), b = algebra::UPolyQ::from_coeffs(rp);
    algebra::UPolyQ e = a * a - algebra::UPolyQ(nn) * b * b;
    // The critical parameters: the real roots of p (factor by factor).
    auto add_roots = [&](const algebra::UPolyQ& p) {
      if (p.degree() <= 0) return;
      for (algebra::IrreducibleFactor& f : algebra::irreducible_factors(p.primitive_integer())) {
        algebra::RootSeparation s = algebra::isolate_real_roots(f.poly);
        for (size_t k = 0; k + 1 < s.separators.size(); ++k)
          tints.push_back({s.separators[k], s.separators[k + 1], tfactors.size()});
        tfactors.push_back(std::move(f.poly));
      }
    };
    if (e.is_zero()) {
      // (n.C')^2 = |n|^2 r'^2 identically: n.C' = sigma |n| r' with one sign sigma (or both
      // zero), so phi' = s n.C' / |n| - r' = (s sigma - 1) r', s the spine's side of the plane.
      // s sigma = -1: phi' = -2 r', whose roots are the critical parameters (a spine rising
      // from z = 0 as its radius shrinks, (t, 0, 5 + t^2) with r = 1 - t^2, was read as
      // constant: certified 4.5 'infinite' for 4 at t = 0). s sigma = 1 (or both zero): phi is
      // constant and every t minimizes; the pairs form a continuum only if the spine moves
      // across n (else every t gives the same contact: (0, 0, 5 + t), r = 1 + t, one pair).
      const int s_side = core::eval_poly(side, c.t0).sign(); // nonzero: no root (above)
      const int sigma = a.is_zero() ? 0 : a.coeff(a.degree()).sign() * b.coeff(b.degree()).sign();
      if (sigma != 0 && s_side * sigma < 0) {
        add_roots(b);
      } else {
        if (spine_moves_across(q, c))
          out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
        else
          out.count_unproven = true;
      }
    } else {
      add_roots(e);
    }
  } else {
    auto [F, G, Dalpha] = canal_system(q, c);
    // Common factors in alpha alone come from the parametrisation (alpha with
    // det(I + alpha Q3) = 0: p(alpha, t) has a removable pole there, or the foot is a circle
    // because C(t) is on an axis of revolution, which happens at isolated t unless the whole
    // spine lies on that axis: checked below at the middle parameter). Any other common
    // factor is a genuine curve of critical pairs: not supported yet.
    std::string curve_note;
    std::vector<Poly3> stripped;
    if (!strip_alpha_factors(F, G, Dalpha, stripped, curve_note)) {
      out.status = Status::Undecided;
      out.note = "not supported yet: " + curve_note;
      return out;
    }
    {
      // Two unrelated inner parameters both with a circle of feet: the spine lies on an axis.
      int continua = 0;
      for (const Rational& frac : {Rational(17, 41), Rational(29, 53)}) {
        std::array<Rational, 3> xm;
        const Rational tm = c.t0 + (c.t1 - c.t0) * frac;
        for (size_t i = 0; i < 3; ++i)
          xm[i] = core::eval_poly(c.spine[i], tm);
        PointQuadricResult pm = point_quadric_critical(xm, q, 15);
        bool cont = false;
        for (const auto& cd : pm.criticals)
          cont = cont || cd.continuum;
        continua += cont ? 1 : 0;
      }
      if (continua == 2) {
        out.status = Status::Undecided;
        out.note = "not supported yet: the spine lies on an axis of revolution of the quadric (a "
                   "continuum of feet along the whole spine)";
        return out;
      }
    }
    if (!singular_line_parameters(q, c, stripped, singular, curve_note)) {
      out.status = Status::Undecided;
      out.note = "not supported yet: " + curve_note;
      return out;
    }
    cover = algebra::cover_real_solutions_2d(F, G, Rational(1, 16));
    out.system_degrees = {F.total_degree(), G.total_degree()};
    out.bivariate_degrees = {F.degree(0), G.degree(0)};
    out.univariate_degrees = {cover->eliminant_degree[0], cover->eliminant_degree[1]};
    out.squarefree_degrees = {cover->squarefree_degree[0], cover->squarefree_degree[1]};
    out.eliminated_degree = static_cast<int>(cover->eliminant_degree[1]);
    if (!cover->ok) {
      out.status = Status::Undecided;
      out.note =
          "not supported yet: the canal system has a curve of solutions (" + cover->note + ")";
      return out;
    }
  }
  // Relative width 10^-digits; the point-quadric enclosures are 10^-(digits + 8) wide.
  const long target_bits = static_cast<long>(static_cast<double>(digits) * 3.33) + 4;
  Candidate e0, e1;
  if (!candidate(e0, q, c, c.t0, c.t0, digits) || !candidate(e1, q, c, c.t1, c.t1, digits)) {
    out.status = Status::Undecided;
    out.note = "point-quadric distance undecided at an end of the spine";
    return out;
  }
  const long prec = bits_for(digits + 10);
  std::vector<Candidate> best;
  Ball L, U;
  bool done = false;
  for (long bits = 16; !done; bits *= 2) {
    Rational width(1);
    fmpq_div_2exp(width.raw_mut(), width.raw(), static_cast<ulong>(bits));
    struct TInterval {
      Rational lo, hi;
      long key;
    };
    std::vector<TInterval> ts;
    // The key of an isolated root of `factor` in [lo, hi]: an end's key when the root is that
    // end (the factor vanishes there: the interval isolates one root), its index otherwise.
    auto key_of = [&](const algebra::UPolyZ& factor, const Rational& lo, const Rational& hi,
                      long index) {
      if (lo <= c.t0 && c.t0 <= hi && factor.sign_at(c.t0) == 0) return kEnd0;
      if (lo <= c.t1 && c.t1 <= hi && factor.sign_at(c.t1) == 0) return kEnd1;
      return index;
    };
    if (cover) {
      algebra::refine_cover(*cover, width);
      for (const auto& b : cover->boxes) {
        const auto& r = cover->roots[1][b[1]];
        ts.push_back(
            {r.lo, r.hi, key_of(cover->factors[1][r.factor], r.lo, r.hi, static_cast<long>(b[1]))});
      }
    } else {
      for (size_t i = 0; i < tints.size(); ++i) { // plane: the exact critical parameters
        auto& r = tints[i];
        algebra::refine_root(tfactors[r.factor], r.lo, r.hi, width);
        ts.push_back({r.lo, r.hi, key_of(tfactors[r.factor], r.lo, r.hi, static_cast<long>(i))});
      }
    }
    for (size_t k = 0; k < singular.covers.size(); ++k) {
      algebra::SolutionCover& sc = singular.covers[k];
      algebra::refine_cover(sc, width);
      for (const auto& b : sc.boxes) {
        const auto& r = sc.roots[1][b[1]];
        ts.push_back({r.lo, r.hi,
                      key_of(sc.factors[1][r.factor], r.lo, r.hi,
                             kSingularKeys + static_cast<long>(k) * kSingularStride +
                                 static_cast<long>(b[1]))});
      }
    }
    for (size_t i = 0; i < singular.roots.size(); ++i) {
      auto& r = singular.roots[i];
      algebra::refine_root(singular.factors[r.factor], r.lo, r.hi, width);
      ts.push_back({r.lo, r.hi,
                    key_of(singular.factors[r.factor], r.lo, r.hi,
                           kSingularKeys - 1 - static_cast<long>(i))});
    }
    std::vector<Candidate> cands;
    for (auto [lo, hi, key] : ts) {
      if (hi < c.t0 || lo > c.t1) continue;
      if (lo < c.t0) lo = c.t0;
      if (hi > c.t1) hi = c.t1;
      Candidate cd;
      cd.key = key;
      if (!candidate(cd, q, c, lo, hi, digits)) {
        out.status = Status::Undecided;
        out.note = "point-quadric distance undecided inside the interval";
        return out;
      }
      cands.push_back(std::move(cd));
    }
    // The ends.
    for (Candidate* e : {&e0, &e1}) {
      Candidate cd;
      arb_set(cd.lo.v, e->lo.v);
      arb_set(cd.up.v, e->up.v);
      cd.tc = e->tc;
      cd.ta = e->ta;
      cd.tb = e->tb;
      cd.p = e->p;
      cd.q = e->q;
      cd.key = e == &e0 ? kEnd0 : kEnd1;
      cands.push_back(std::move(cd));
    }
    arf_t l, u, w;
    arf_init(l);
    arf_init(u);
    arf_init(w);
    arf_pos_inf(l);
    arf_pos_inf(u);
    for (const auto& cd : cands) {
      arf_t x;
      arf_init(x);
      arb_get_lbound_arf(x, cd.lo.v, prec);
      if (arf_cmp(x, l) < 0) arf_set(l, x);
      arb_get_ubound_arf(x, cd.up.v, prec);
      if (arf_cmp(x, u) < 0) arf_set(u, x);
      arf_clear(x);
    }
    best.clear();
    for (auto& cd : cands) {
      arf_t x;
      arf_init(x);
      arb_get_lbound_arf(x, cd.lo.v, prec);
      if (arf_cmp(x, u) <= 0) best.push_back(std::move(cd));
      arf_clear(x);
    }
    arb_set_arf(L.v, l);
    arb_set_arf(U.v, u);
    arf_sub(w, u, l, prec, ARF_RND_UP);
    arf_abs(l, l);
    arf_mul_2exp_si(l, l, -target_bits);
    done = arf_cmp(w, l) <= 0;
    arf_clear(l);
    arf_clear(u);
    arf_clear(w);
    if (bits > 2 * target_bits + 256) break;
  }
  // One minimizer per critical parameter: candidates with the same key are the same spine
  // point (several alpha boxes over one isolated t root, or a root equal to an end), merged
  // exactly. Each spine point gives one minimizing pair only if its foot on q is unique:
  // proven for a plane and for points outside an ellipsoid or elliptic cylinder; otherwise the
  // count is not proven (a point may have several nearest feet).
  {
    // A parameter with feet on a singular line has several nearest feet (+-s, a circle), and
    // it may be a parameter of the main system (or of another line) found again under another
    // key: such a candidate joins any kept one whose interval it meets (one region, listed
    // once), and the count is not proven.
    auto singular_key = [](long key) { return key >= kSingularKeys / 2; };
    std::vector<Candidate> uniq;
    for (auto& cd : best) {
      out.count_unproven = out.count_unproven || singular_key(cd.key);
      auto same = std::find_if(uniq.begin(), uniq.end(), [&](const Candidate& u) {
        return u.key == cd.key ||
               ((singular_key(u.key) || singular_key(cd.key)) && !(cd.tb < u.ta || u.tb < cd.ta));
      });
      if (same == uniq.end()) {
        uniq.push_back(std::move(cd));
        continue;
      }
      same->ta = std::min(same->ta, cd.ta); // its interval joins the kept one's region
      same->tb = std::max(same->tb, cd.tb);
    }
    best = std::move(uniq);
    for (const auto& cd : best)
      out.count_unproven = out.count_unproven || !unique_foot(q, c, cd.ta, cd.tb);
  }
  out.critical_candidates = static_cast<int>(best.size());
  arf_t l, u;
  arf_init(l);
  arf_init(u);
  arb_get_lbound_arf(l, L.v, prec);
  arb_get_ubound_arf(u, U.v, prec);
  if (arf_sgn(l) > 0) { // S1 misses every ball: the distance is min phi
    out.status = done ? Status::Certified : Status::Undecided;
    if (!done) {
      out.note = "the enclosure did not reach the requested width";
      out.width_short = true;
    }
    out.distance = Enclosure::from_bounds(l, u, digits);
    if (out.minimizers.empty())
      out.minimizers =
          Minimizers::count(static_cast<long>(best.size()), Minimizers::Proof::Interval);
    for (const auto& cd : best)
      pair_out(cd);
    if (!out.minimizers.is_continuum()) note_unproven_ties(out, best.size());
    // Tie regions (symmetry.hpp): the spine points C([ta, tb]); every minimizing parameter
    // lies in a kept interval, and a symmetry of both surfaces maps spine points to spine
    // points with the same phi.
    for (const auto& cd : best) {
      Ball T, a, b;
      arb_set_fmpq(a.v, cd.ta.raw(), prec);
      arb_set_fmpq(b.v, cd.tb.raw(), prec);
      arb_union(T.v, a.v, b.v, prec);
      std::vector<std::array<double, 2>> reg;
      for (size_t i = 0; i < 3; ++i) {
        Ball v, k;
        for (size_t j = c.spine[i].size(); j-- > 0;) {
          arb_mul(v.v, v.v, T.v, prec);
          arb_set_fmpq(k.v, c.spine[i][j].raw(), prec);
          arb_add(v.v, v.v, k.v, prec);
        }
        reg.push_back(outward_interval(v.v));
      }
      out.tie_regions.push_back(std::move(reg));
    }
  } else if (arf_sgn(u) < 0 && components_unbounded(q)) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
    out.note = "the quadric enters the canal solid and, being unbounded, leaves it: they meet";
  } else if (arf_sgn(u) < 0 && ellipsoid_point_outside(q, c)) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
    out.note = "the ellipsoid has certified points inside and outside the canal solid: they meet";
  } else if (plane && sphere_tangent_to_plane(q, c)) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = plane_touch_minimizers(q, c);
    out.note = "a sphere of the family is tangent to the plane at an exact parameter: the "
               "plane touches or enters the canal solid, and being unbounded meets its surface";
  } else {
    out.status = Status::Undecided;
    out.note = arf_sgn(u) < 0 ? "the quadric enters the canal solid; it may lie inside it"
                              : "touching? min phi not separated from 0";
  }
  arf_clear(l);
  arf_clear(u);
  return out;
}

} // namespace surfcert::certify
