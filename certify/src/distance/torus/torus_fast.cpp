#include "surfcert/certify/distance/torus_fast.hpp"
#include "surfcert/core/budget.hpp"

#include "surfcert/certify/distance/group_uniqueness.hpp"
#include "surfcert/certify/distance/mp_float.hpp"
#include <flint/fmpq.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

using D3 = std::array<double, 3>;
template <class T> using V3 = std::array<T, 3>;

constexpr double kPi = 3.14159265358979323846;

// Limits of the branch and bound: beyond them the minimizers may form a continuum (or a
// degenerate minimum), and the exact path answers.
constexpr size_t kMaxAlive = 64;
constexpr size_t kMaxClusters = 8;
constexpr int kMaxEvaluations = 1500;
constexpr double kMinWidth = 0x1p-40;
// Double guidance reaches ~1e-30 relative: up to this many digits one precision usually
// suffices; beyond, phase 1 only isolates the clusters, to 2^-kClusterBits.
constexpr long kSinglePhaseDigits = 26;
constexpr long kClusterBits = 40;

// ---- exact data ---------------------------------------------------------------------------

// core::plane_frame of the axis: u0 = a x e_k (k the smallest
// |a_k|, so u0 != 0), v0 = a x u0. Its unit version is irrational: Arb balls / MPFR / double.
struct PlaneFrame {
  V3<Rational> u0, v0;
};

PlaneFrame exact_frame(const V3<Rational>& a) {
  const auto fr = core::plane_frame(a);
  return PlaneFrame{fr[0], fr[1]};
}

// ---- double model (guidance only: chooses where to certify, never decides) ---------------

double dot(const D3& a, const D3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
D3 unit(const std::array<Rational, 3>& v) {
  D3 d{v[0].to_double_approx(), v[1].to_double_approx(), v[2].to_double_approx()};
  const double n = std::sqrt(dot(d, d));
  return {d[0] / n, d[1] / n, d[2] / n};
}

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: A = Q diag(w) Q^T
// (the columns of Q are the eigenvectors).
void jacobi3(const std::array<D3, 3>& a_in, std::array<D3, 3>& Q, D3& w) {
  std::array<D3, 3> A = a_in;
  Q = {D3{1, 0, 0}, D3{0, 1, 0}, D3{0, 0, 1}};
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = A[0][1] * A[0][1] + A[0][2] * A[0][2] + A[1][2] * A[1][2];
    const double diag = A[0][0] * A[0][0] + A[1][1] * A[1][1] + A[2][2] * A[2][2];
    if (!(off > 1e-34 * diag)) break;
    for (size_t p = 0; p < 2; ++p)
      for (size_t q = p + 1; q < 3; ++q) {
        const double apq = A[p][q];
        if (apq == 0) continue;
        const double theta = (A[q][q] - A[p][p]) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::hypot(theta, 1.0));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (size_t k = 0; k < 3; ++k) { // A J
          const double akp = A[k][p], akq = A[k][q];
          A[k][p] = c * akp - s * akq;
          A[k][q] = s * akp + c * akq;
        }
        for (size_t k = 0; k < 3; ++k) { // J^T (A J)
          const double apk = A[p][k], aqk = A[q][k];
          A[p][k] = c * apk - s * aqk;
          A[q][k] = s * apk + c * aqk;
        }
        for (size_t k = 0; k < 3; ++k) { // Q J
          const double qkp = Q[k][p], qkq = Q[k][q];
          Q[k][p] = c * qkp - s * qkq;
          Q[k][q] = s * qkp + c * qkq;
        }
      }
  }
  w = {A[0][0], A[1][1], A[2][2]};
}

// Positions relative to the torus centre (o = 0), so that far translations cost no accuracy.
struct FloatModel {
  D3 o, u, v, c;
  double R = 0, r = 0;
  std::array<D3, 3> Q; ///< eigenvectors of W (columns)
  D3 w;                ///< eigenvalues of W = squared semi-axes
  D3 K(double tau) const {
    const double C = std::cos(kPi * tau), S = std::sin(kPi * tau);
    return {o[0] + R * (C * u[0] + S * v[0]), o[1] + R * (C * u[1] + S * v[1]),
            o[2] + R * (C * u[2] + S * v[2])};
  }
  D3 dK(double tau) const { // dK / dtau
    const double C = std::cos(kPi * tau), S = std::sin(kPi * tau), k = kPi * R;
    return {k * (C * v[0] - S * u[0]), k * (C * v[1] - S * u[1]), k * (C * v[2] - S * u[2])};
  }
};

FloatModel float_model(const ConvexQuadric& e, const core::Torus& t, const PlaneFrame& f) {
  FloatModel m;
  for (size_t i = 0; i < 3; ++i) {
    m.o[i] = 0; // coordinates relative to the torus centre (exact difference, then rounded)
    m.c[i] = (e.c[i] - t.centre[i]).to_double_approx();
  }
  m.u = unit(f.u0);
  m.v = unit(f.v0);
  m.R = t.R.to_double_approx();
  m.r = t.r.to_double_approx();
  std::array<D3, 3> W;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      W[i][j] = e.Wd[i][j];
  jacobi3(W, m.Q, m.w);
  return m;
}

// The closest point of E to x (outside E) and the outward unit normal there, in double:
// with y = Q^T (x - c), p - c = Q z, z_i = y_i w_i / (w_i + t), where t > 0 solves
// S(t) = sum w_i y_i^2 / (w_i + t)^2 = 1; Newton on S^-1/2 - 1 (linear in t for a sphere),
// safeguarded by bisection on [0, sqrt(w_max) |y|].
struct Foot {
  bool outside = false;
  double dist = 0;
  D3 n{}, p{};
};

Foot foot(const FloatModel& m, const D3& x) {
  Foot out;
  D3 d{x[0] - m.c[0], x[1] - m.c[1], x[2] - m.c[2]}, y{};
  for (size_t i = 0; i < 3; ++i)
    y[i] = m.Q[0][i] * d[0] + m.Q[1][i] * d[1] + m.Q[2][i] * d[2];
  double s0 = 0;
  for (size_t i = 0; i < 3; ++i)
    s0 += y[i] * y[i] / m.w[i];
  if (!(s0 > 1) || !std::isfinite(s0)) return out;
  double lo = 0, hi = std::sqrt(std::max({m.w[0], m.w[1], m.w[2]}) * dot(y, y)), t = 0;
  for (int it = 0; it < 200; ++it) {
    double S = 0, dS = 0;
    for (size_t i = 0; i < 3; ++i) {
      const double k = 1 / (m.w[i] + t), a = m.w[i] * y[i] * y[i] * k * k;
      S += a;
      dS -= 2 * a * k;
    }
    const double chi = 1 / std::sqrt(S) - 1;
    if (chi < 0)
      lo = t;
    else
      hi = t;
    const double dchi = -0.5 * dS / (S * std::sqrt(S));
    double tn = t - chi / dchi;
    if (!(tn > lo && tn < hi)) tn = 0.5 * (lo + hi);
    const bool last = std::fabs(tn - t) <= 1e-16 * (t + m.w[0] + m.w[1] + m.w[2]);
    t = tn;
    if (last) break;
  }
  D3 z{}, nn{};
  for (size_t i = 0; i < 3; ++i) {
    z[i] = y[i] * m.w[i] / (m.w[i] + t);
    nn[i] = y[i] / (m.w[i] + t);
  }
  double len = 0;
  for (size_t i = 0; i < 3; ++i) {
    out.p[i] = m.c[i] + m.Q[i][0] * z[0] + m.Q[i][1] * z[1] + m.Q[i][2] * z[2];
    out.n[i] = m.Q[i][0] * nn[0] + m.Q[i][1] * nn[1] + m.Q[i][2] * nn[2];
    len += out.n[i] * out.n[i];
  }
  len = std::sqrt(len);
  for (auto& c : out.n)
    c /= len;
  out.dist = std::hypot(x[0] - out.p[0], x[1] - out.p[1], x[2] - out.p[2]);
  out.outside = std::isfinite(out.dist);
  return out;
}

// f(tau) = dist(K(tau), E), f' = n . K' (envelope), and by central differences f'' and the
// derivative n1 of the optimal normal (only steering: any n1 gives a valid bound, and its
// error enters the bound's curvature quadratically).
struct Guide {
  bool ok = false;
  double tau = 0, f = 0, f1 = 0, f2 = 0;
  D3 n{}, n1{};
};

Guide guide(const FloatModel& m, double tau) {
  Guide g;
  g.tau = tau;
  constexpr double h = 1e-6;
  const Foot a = foot(m, m.K(tau)), b = foot(m, m.K(tau + h)), c = foot(m, m.K(tau - h));
  if (!a.outside || !b.outside || !c.outside) return g;
  g.ok = true;
  g.f = a.dist;
  g.n = a.n;
  g.f1 = dot(a.n, m.dK(tau));
  g.f2 = (dot(b.n, m.dK(tau + h)) - dot(c.n, m.dK(tau - h))) / (2 * h);
  for (size_t i = 0; i < 3; ++i)
    g.n1[i] = (b.n[i] - c.n[i]) / (2 * h);
  return g;
}

// The point of [a, b] where the bound is evaluated: Newton on f' from the midpoint, clamped
// to the interval (the minimizer when the interval holds one, else usually an endpoint).
Guide choose_tau(const FloatModel& m, double a, double b, const Guide* mid = nullptr) {
  Guide g = mid ? *mid : guide(m, 0.5 * (a + b));
  for (int it = 0; it < 6 && g.ok && g.f2 > 0; ++it) {
    const double tn = std::clamp(g.tau - g.f1 / g.f2, a, b);
    if (tn == g.tau) break;
    const bool small = std::fabs(tn - g.tau) < 1e-14 * (b - a);
    Guide gn = guide(m, tn);
    if (!gn.ok) break;
    g = gn;
    if (small) break;
  }
  return g;
}

// ---- Arb model and the certified bound ------------------------------------------------------

struct ArbModel {
  long prec;
  Ball c[3];        ///< ellipsoid centre
  Ball oc[3];       ///< o - c (torus centre minus ellipsoid centre)
  Ball o[3], ah[3]; ///< torus centre, unit axis
  Ball u[3], v[3];  ///< unit frame of the torus plane (balls around irrational values)
  Ball W[3][3], R, r, piR, half_pi2R;
  ArbModel(const ConvexQuadric& e, const core::Torus& t, const PlaneFrame& f, long p) : prec(p) {
    Ball nu, nv, na;
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(o[i].v, t.centre[i].raw(), prec);
      arb_set_fmpq(c[i].v, e.c[i].raw(), prec);
      arb_sub(oc[i].v, o[i].v, c[i].v, prec);
      arb_set_fmpq(u[i].v, f.u0[i].raw(), prec);
      arb_set_fmpq(v[i].v, f.v0[i].raw(), prec);
      arb_set_fmpq(ah[i].v, t.axis[i].raw(), prec);
      arb_addmul(nu.v, u[i].v, u[i].v, prec);
      arb_addmul(nv.v, v[i].v, v[i].v, prec);
      arb_addmul(na.v, ah[i].v, ah[i].v, prec);
      for (size_t j = 0; j < 3; ++j)
        arb_set_fmpq(W[i][j].v, e.W[i][j].raw(), prec);
    }
    arb_rsqrt(nu.v, nu.v, prec);
    arb_rsqrt(nv.v, nv.v, prec);
    arb_rsqrt(na.v, na.v, prec);
    for (size_t i = 0; i < 3; ++i) {
      arb_mul(u[i].v, u[i].v, nu.v, prec);
      arb_mul(v[i].v, v[i].v, nv.v, prec);
      arb_mul(ah[i].v, ah[i].v, na.v, prec);
    }
    arb_set_fmpq(R.v, t.R.raw(), prec);
    arb_set_fmpq(r.v, t.r.raw(), prec);
    arb_const_pi(piR.v, prec);
    arb_sqr(half_pi2R.v, piR.v, prec);
    arb_mul(half_pi2R.v, half_pi2R.v, R.v, prec);
    arb_mul_2exp_si(half_pi2R.v, half_pi2R.v, -1);
    arb_mul(piR.v, piR.v, R.v, prec);
  }
};

// Truncated Taylor series (value, first derivative, second derivative / 2).
struct Jet {
  Ball c[3];
};

void jet_sqrt(Jet& out, const Jet& a, long prec) {
  Ball t;
  arb_sqrt(out.c[0].v, a.c[0].v, prec); // not finite when the ball reaches below 0
  arb_div(out.c[1].v, a.c[1].v, out.c[0].v, prec);
  arb_mul_2exp_si(out.c[1].v, out.c[1].v, -1);
  arb_sqr(t.v, out.c[1].v, prec);
  arb_sub(out.c[2].v, a.c[2].v, t.v, prec);
  arb_div(out.c[2].v, out.c[2].v, out.c[0].v, prec);
  arb_mul_2exp_si(out.c[2].v, out.c[2].v, -1);
}

void jet_div(Jet& out, const Jet& a, const Jet& b, long prec) {
  arb_div(out.c[0].v, a.c[0].v, b.c[0].v, prec);
  arb_set(out.c[1].v, a.c[1].v);
  arb_submul(out.c[1].v, out.c[0].v, b.c[1].v, prec);
  arb_div(out.c[1].v, out.c[1].v, b.c[0].v, prec);
  arb_set(out.c[2].v, a.c[2].v);
  arb_submul(out.c[2].v, out.c[0].v, b.c[2].v, prec);
  arb_submul(out.c[2].v, out.c[1].v, b.c[1].v, prec);
  arb_div(out.c[2].v, out.c[2].v, b.c[0].v, prec);
}

// The bound g(tau) = (n . K(tau) - h_E(n)) / |n| with n = n0 + (tau - tau0) n1, as a jet in
// tau, valid for every tau in the ball T: g <= dist(K(tau), E) for every tau (duality).
void bound_jet(Jet& g, const ArbModel& M, const arb_t T, const arb_t tau0, const Ball (&n0)[3],
               const Ball (&n1)[3]) {
  const long prec = M.prec;
  Ball s, C, S, e, f, n[3], k0[3], k1[3], k2[3], Wn[3], Wn1[3];
  arb_sub(s.v, T, tau0, prec);
  arb_sin_cos_pi(S.v, C.v, T, prec);
  for (size_t i = 0; i < 3; ++i) {
    arb_mul(e.v, C.v, M.u[i].v, prec);
    arb_addmul(e.v, S.v, M.v[i].v, prec);
    arb_mul(f.v, C.v, M.v[i].v, prec);
    arb_submul(f.v, S.v, M.u[i].v, prec);
    arb_set(k0[i].v, M.oc[i].v);
    arb_addmul(k0[i].v, M.R.v, e.v, prec);
    arb_mul(k1[i].v, M.piR.v, f.v, prec);
    arb_mul(k2[i].v, M.half_pi2R.v, e.v, prec);
    arb_neg(k2[i].v, k2[i].v);
    arb_set(n[i].v, n0[i].v);
    arb_addmul(n[i].v, s.v, n1[i].v, prec);
  }
  Jet A, q, nn, sq, ln;
  for (size_t i = 0; i < 3; ++i) {
    arb_addmul(A.c[0].v, n[i].v, k0[i].v, prec);
    arb_addmul(A.c[1].v, n[i].v, k1[i].v, prec);
    arb_addmul(A.c[1].v, n1[i].v, k0[i].v, prec);
    arb_addmul(A.c[2].v, n[i].v, k2[i].v, prec);
    arb_addmul(A.c[2].v, n1[i].v, k1[i].v, prec);
    for (size_t j = 0; j < 3; ++j) {
      arb_addmul(Wn[i].v, M.W[i][j].v, n[j].v, prec);
      arb_addmul(Wn1[i].v, M.W[i][j].v, n1[j].v, prec);
    }
  }
  for (size_t i = 0; i < 3; ++i) {
    arb_addmul(q.c[0].v, n[i].v, Wn[i].v, prec);
    arb_addmul(q.c[1].v, n1[i].v, Wn[i].v, prec);
    arb_addmul(q.c[2].v, n1[i].v, Wn1[i].v, prec);
    arb_addmul(nn.c[0].v, n[i].v, n[i].v, prec);
    arb_addmul(nn.c[1].v, n1[i].v, n[i].v, prec);
    arb_addmul(nn.c[2].v, n1[i].v, n1[i].v, prec);
  }
  arb_mul_2exp_si(q.c[1].v, q.c[1].v, 1);
  arb_mul_2exp_si(nn.c[1].v, nn.c[1].v, 1);
  jet_sqrt(sq, q, prec);
  jet_sqrt(ln, nn, prec);
  for (size_t k = 0; k < 3; ++k)
    arb_sub(A.c[k].v, A.c[k].v, sq.c[k].v, prec);
  jet_div(g, A, ln, prec);
}

// A certified lower bound of dist(K(tau), E) over tau in [a, b] (tau0 in [a, b]): the
// second-order Taylor form g(tau0 + s) >= g0 + g1 s + m s^2 with m a lower bound of g''/2
// over the interval, minimised over s in [a - tau0, b - tau0] (endpoints, and the vertex when
// m > 0 and it may lie inside), and the plain interval value of g. -inf when nothing finite.
void interval_lower(arf_t out, const ArbModel& M, const arf_t a, const arf_t b, const arf_t tau0,
                    const Ball (&n0)[3], const Ball (&n1)[3]) {
  const long prec = M.prec;
  Ball T, t0, sa, sb, m, q, best, vs, tmp;
  arb_set_interval_arf(T.v, a, b, prec);
  arb_set_arf(t0.v, tau0);
  Jet gp, gb;
  bound_jet(gp, M, t0.v, t0.v, n0, n1);
  bound_jet(gb, M, T.v, t0.v, n0, n1);
  arf_pos_inf(out);
  bool any = false;
  if (arb_is_finite(gb.c[0].v)) {
    arb_get_lbound_arf(out, gb.c[0].v, prec);
    any = true;
  }
  if (arb_is_finite(gb.c[2].v) && arb_is_finite(gp.c[0].v) && arb_is_finite(gp.c[1].v)) {
    arf_t lb;
    arf_init(lb);
    arb_get_lbound_arf(lb, gb.c[2].v, prec);
    arb_set_arf(m.v, lb); // exact lower bound of g''/2 on [a, b]
    arb_set_arf(sa.v, a);
    arb_sub(sa.v, sa.v, t0.v, prec);
    arb_set_arf(sb.v, b);
    arb_sub(sb.v, sb.v, t0.v, prec);
    arf_pos_inf(arb_midref(best.v));
    auto candidate = [&](const Ball& s) {
      arb_mul(q.v, m.v, s.v, prec);
      arb_add(q.v, q.v, gp.c[1].v, prec);
      arb_mul(q.v, q.v, s.v, prec);
      arb_add(q.v, q.v, gp.c[0].v, prec);
      arb_get_lbound_arf(lb, q.v, prec);
      if (arf_cmp(lb, arb_midref(best.v)) < 0) arf_set(arb_midref(best.v), lb);
    };
    candidate(sa);
    candidate(sb);
    if (arf_sgn(arb_midref(m.v)) > 0) {
      // vertex s = -g1 / (2 m): value g0 - g1^2 / (4 m)
      arb_div(vs.v, gp.c[1].v, m.v, prec);
      arb_mul_2exp_si(vs.v, vs.v, -1);
      arb_neg(vs.v, vs.v);
      arb_union(tmp.v, sa.v, sb.v, prec);
      if (arb_overlaps(vs.v, tmp.v)) {
        arb_sqr(q.v, gp.c[1].v, prec);
        arb_div(q.v, q.v, m.v, prec);
        arb_mul_2exp_si(q.v, q.v, -2);
        arb_sub(q.v, gp.c[0].v, q.v, prec);
        arb_get_lbound_arf(lb, q.v, prec);
        if (arf_cmp(lb, arb_midref(best.v)) < 0) arf_set(arb_midref(best.v), lb);
      }
    }
    if (arf_is_finite(arb_midref(best.v)) && (!any || arf_cmp(arb_midref(best.v), out) > 0))
      arf_set(out, arb_midref(best.v));
    any = any || arf_is_finite(arb_midref(best.v));
    arf_clear(lb);
  }
  if (!any) arf_neg_inf(out);
}

// A genuine pair: the support point p = p_E(n0) (an exact point of E, enclosed) and its
// distance to K, sqrt((rho - R)^2 + h^2) (h the height over the torus plane, rho the distance
// to the axis). Also the approximate pair (p, nearest torus point) for the report.
struct Upper {
  Ball D; ///< dist(p, K)
  D3 p{}, q{};
};

bool upper_at(Upper& U, const ArbModel& M, const Ball (&n0)[3], double r) {
  const long prec = M.prec;
  Ball p[3], w[3], hgt, w2, rho, tmp;
  // p = c + W n0 / sqrt(n0^T W n0) (support_ball, with the balls of W and c cached in M)
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      arb_addmul(p[i].v, M.W[i][j].v, n0[j].v, prec);
  for (size_t i = 0; i < 3; ++i)
    arb_addmul(tmp.v, n0[i].v, p[i].v, prec);
  arb_rsqrt(tmp.v, tmp.v, prec); // not finite unless n0^T W n0 > 0
  for (size_t i = 0; i < 3; ++i) {
    arb_mul(p[i].v, p[i].v, tmp.v, prec);
    arb_add(p[i].v, p[i].v, M.c[i].v, prec);
  }
  for (size_t i = 0; i < 3; ++i) {
    arb_sub(w[i].v, p[i].v, M.o[i].v, prec);
    arb_addmul(hgt.v, w[i].v, M.ah[i].v, prec);
    arb_addmul(w2.v, w[i].v, w[i].v, prec);
  }
  arb_sqr(tmp.v, hgt.v, prec);
  arb_sub(rho.v, w2.v, tmp.v, prec);
  arb_sqrtpos(rho.v, rho.v, prec);
  arb_sub(U.D.v, rho.v, M.R.v, prec);
  arb_sqr(U.D.v, U.D.v, prec);
  arb_addmul(U.D.v, hgt.v, hgt.v, prec);
  arb_sqrtpos(U.D.v, U.D.v, prec);
  if (!arb_is_finite(U.D.v)) return false;
  const double hd = arf_get_d(arb_midref(hgt.v), ARF_RND_NEAR),
               rd = arf_get_d(arb_midref(rho.v), ARF_RND_NEAR),
               Rd = arf_get_d(arb_midref(M.R.v), ARF_RND_NEAR);
  D3 k{};
  for (size_t i = 0; i < 3; ++i) {
    U.p[i] = arf_get_d(arb_midref(p[i].v), ARF_RND_NEAR);
    const double wi = arf_get_d(arb_midref(w[i].v), ARF_RND_NEAR),
                 ai = arf_get_d(arb_midref(M.ah[i].v), ARF_RND_NEAR);
    k[i] = arf_get_d(arb_midref(M.o[i].v), ARF_RND_NEAR) + (rd > 0 ? Rd * (wi - hd * ai) / rd : 0);
  }
  const double pk = std::hypot(U.p[0] - k[0], U.p[1] - k[1], U.p[2] - k[2]);
  for (size_t i = 0; i < 3; ++i)
    U.q[i] = pk > 0 ? k[i] + r * (U.p[i] - k[i]) / pk : k[i];
  return true;
}

// ---- MPFR refinement of (tau*, n*) for many digits --------------------------------------

Mp mp(const Rational& r) {
  return mp_from(r);
}

// Newton on the stationarity system of the closest pair (K(tau), p_E(n)):
//   K(tau) - p(n) - lambda n = 0 (the segment is normal to E at p), K'(tau) . n = 0 (and to
//   the circle), nbar . n = 1 (scale),
// unknowns tau, n, lambda; dp/dn = (W - Wn Wn^T / q) / sqrt(q), q = n^T W n. Only chooses the
// point certified afterwards.
bool refine_mpfr(const ConvexQuadric& e, const core::Torus& t, const PlaneFrame& f, long bits,
                 double tau_d, const D3& n_d, double lambda_d, Mp& tau, V3<Mp>& n) {
  V3<Mp> o, u, v, c, nbar;
  std::array<V3<Mp>, 3> W;
  Mp nu(0), nv(0);
  for (size_t i = 0; i < 3; ++i) {
    o[i] = 0; // relative to the torus centre, as in the double model
    c[i] = mp(e.c[i] - t.centre[i]);
    u[i] = mp(f.u0[i]);
    v[i] = mp(f.v0[i]);
    nu += u[i] * u[i];
    nv += v[i] * v[i];
    for (size_t j = 0; j < 3; ++j)
      W[i][j] = mp(e.W[i][j]);
  }
  nu = sqrt(nu);
  nv = sqrt(nv);
  for (size_t i = 0; i < 3; ++i) {
    u[i] /= nu;
    v[i] /= nv;
  }
  const Mp R = mp(t.R);
  Mp pi;
  mpfr_const_pi(pi.backend().data(), MPFR_RNDN);
  tau = Mp(tau_d);
  Mp lambda(lambda_d);
  for (size_t i = 0; i < 3; ++i)
    n[i] = nbar[i] = Mp(n_d[i]);
  const Mp eps = ldexp(Mp(1), static_cast<int>(-bits + 12));
  for (int it = 0; it < 64; ++it) {
    const Mp C = cos(pi * tau), S = sin(pi * tau);
    V3<Mp> K, K1, K2, Wn;
    Mp q(0), K2n(0), K1n(0), nb(0);
    for (size_t i = 0; i < 3; ++i) {
      const Mp ei = C * u[i] + S * v[i];
      K[i] = o[i] + R * ei;
      K1[i] = pi * R * (C * v[i] - S * u[i]);
      K2[i] = -pi * pi * R * ei;
      Wn[i] = W[i][0] * n[0] + W[i][1] * n[1] + W[i][2] * n[2];
    }
    for (size_t i = 0; i < 3; ++i) {
      q += n[i] * Wn[i];
      K2n += K2[i] * n[i];
      K1n += K1[i] * n[i];
      nb += nbar[i] * n[i];
    }
    if (!(q > 0)) return false;
    const Mp sq = sqrt(q);
    Mp J[5][5], F[5];
    for (size_t i = 0; i < 3; ++i) {
      F[i] = K[i] - c[i] - Wn[i] / sq - lambda * n[i];
      J[i][0] = K1[i];
      for (size_t j = 0; j < 3; ++j)
        J[i][1 + j] = -(W[i][j] - Wn[i] * Wn[j] / q) / sq - (i == j ? lambda : Mp(0));
      J[i][4] = -n[i];
    }
    F[3] = K1n;
    J[3][0] = K2n;
    for (size_t j = 0; j < 3; ++j) {
      J[3][1 + j] = K1[j];
      J[4][1 + j] = nbar[j];
    }
    J[3][4] = 0;
    J[4][0] = 0;
    J[4][4] = 0;
    F[4] = nb - 1;
    // Gaussian elimination with partial pivoting: J dx = -F.
    for (size_t col = 0; col < 5; ++col) {
      size_t piv = col;
      for (size_t rr = col + 1; rr < 5; ++rr)
        if (abs(J[rr][col]) > abs(J[piv][col])) piv = rr;
      if (J[piv][col] == 0) return false;
      if (piv != col) {
        for (size_t k = 0; k < 5; ++k)
          std::swap(J[piv][k], J[col][k]);
        std::swap(F[piv], F[col]);
      }
      for (size_t rr = col + 1; rr < 5; ++rr) {
        const Mp fac = J[rr][col] / J[col][col];
        for (size_t k = col; k < 5; ++k)
          J[rr][k] -= fac * J[col][k];
        F[rr] -= fac * F[col];
      }
    }
    Mp dx[5];
    for (size_t k = 5; k-- > 0;) {
      Mp s = -F[k];
      for (size_t j = k + 1; j < 5; ++j)
        s -= J[k][j] * dx[j];
      dx[k] = s / J[k][k];
    }
    tau += dx[0];
    for (size_t i = 0; i < 3; ++i)
      n[i] += dx[1 + i];
    lambda += dx[4];
    Mp step = abs(dx[0]);
    for (size_t i = 1; i < 4; ++i)
      step = std::max(step, Mp(abs(dx[i])));
    if (step < eps) return true;
  }
  return false;
}

// ---- the branch and bound ---------------------------------------------------------------

struct Interval {
  double a = 0, b = 0;
  bool evaluated = false;
  bool star = false; ///< holds the refined minimizer (tau*, n*) of its cluster
  Ball lb;           ///< certified lower bound of dist(K, E) on [a, b] (midpoint, exact)
  bool has_upper = false;
  Upper up;
  double f = 0; ///< float dist(K(tau0), E) (ordering only)
  Guide mid;    ///< float data at the midpoint (the start of choose_tau)
};

// A cluster's refined minimizer: tau* and n* exact (midpoints of the balls), n1 from double.
struct Star {
  double at = 0; ///< tau* rounded to double (strictly inside its star intervals)
  Ball tau0, n0[3], n1[3];
};

class Search {
public:
  Search(const ConvexQuadric& e, const core::Torus& t, long digits)
      : e_(e), t_(t), frame_(exact_frame(t.axis)), fm_(float_model(e, t, frame_)), digits_(digits) {
    arf_init(best_);
    arf_pos_inf(best_);
  }
  ~Search() { arf_clear(best_); }
  Search(const Search&) = delete;
  Search& operator=(const Search&) = delete;

  std::optional<DistanceResult> run(bool quadric_first);

private:
  bool place_stars(const std::vector<std::vector<size_t>>& groups, long bits);
  std::optional<DistanceResult> finish(const ArbModel& M,
                                       const std::vector<std::vector<size_t>>& groups,
                                       bool quadric_first) const;
  bool evaluate(Interval& I, const ArbModel& M);
  // Done: every surviving lower bound within the target of the best upper bound. Stuck: an
  // interval would need splitting below kMinWidth, or too many intervals survive (the double
  // guidance is not accurate enough, or the minimizers form a continuum); the surviving set
  // is still a valid cover. GiveUp: not for this path.
  enum class Outcome { Done, Stuck, GiveUp };
  Outcome branch_and_bound(const ArbModel& M, long target_bits);
  void split(std::vector<Interval>& out, const Interval& I) const;
  bool clusters(std::vector<std::vector<size_t>>& groups);
  const Star* star_of(const Interval& I) const {
    for (const auto& s : stars_)
      if (I.a < s.at && s.at < I.b) return &s;
    return nullptr;
  }

  const ConvexQuadric& e_;
  const core::Torus& t_;
  PlaneFrame frame_;
  FloatModel fm_;
  long digits_;
  std::vector<Interval> alive_;
  arf_t best_; ///< best genuine upper bound of dist(E, K)
  int evaluations_ = 0;
  std::vector<Star> stars_;
};

bool Search::evaluate(Interval& I, const ArbModel& M) {
  ++evaluations_;
  const long prec = M.prec;
  Ball tau0, n0[3], n1[3];
  arf_t a, b;
  arf_init(a);
  arf_init(b);
  arf_set_d(a, I.a);
  arf_set_d(b, I.b);
  const Star* st = I.star ? star_of(I) : nullptr;
  // The Taylor form needs tau0 in [a, b] (exactly).
  if (st && (arf_cmp(arb_midref(st->tau0.v), a) < 0 || arf_cmp(arb_midref(st->tau0.v), b) > 0))
    st = nullptr;
  if (st) {
    arb_set(tau0.v, st->tau0.v);
    for (size_t i = 0; i < 3; ++i) {
      arb_set(n0[i].v, st->n0[i].v);
      arb_set(n1[i].v, st->n1[i].v);
    }
  } else {
    const Guide g = choose_tau(fm_, I.a, I.b, I.mid.ok ? &I.mid : nullptr);
    if (!g.ok) { // a point of K inside E (in double): not for this path
      arf_clear(a);
      arf_clear(b);
      return false;
    }
    I.f = g.f;
    arb_set_d(tau0.v, g.tau);
    for (size_t i = 0; i < 3; ++i) {
      arb_set_d(n0[i].v, g.n[i]);
      arb_set_d(n1[i].v, g.n1[i]);
    }
  }
  interval_lower(arb_midref(I.lb.v), M, a, b, arb_midref(tau0.v), n0, n1);
  mag_zero(arb_radref(I.lb.v));
  arf_clear(a);
  arf_clear(b);
  I.evaluated = true;
  I.has_upper = false;
  if (arf_cmp(arb_midref(I.lb.v), best_) <= 0 && upper_at(I.up, M, n0, fm_.r)) {
    I.has_upper = true;
    arf_t u;
    arf_init(u);
    arb_get_ubound_arf(u, I.up.D.v, prec);
    if (arf_cmp(u, best_) < 0) arf_set(best_, u);
    arf_clear(u);
  }
  return true;
}

void Search::split(std::vector<Interval>& out, const Interval& I) const {
  std::vector<double> cuts;
  const Star* st = I.star ? star_of(I) : nullptr;
  if (st) {
    // Shrink around the refined minimizer: [a, t - w/4], [t - w/4, t + w/4], [t + w/4, b].
    const double t = st->at, q = 0.25 * (I.b - I.a);
    if (t - q > I.a) cuts.push_back(t - q);
    if (t + q < I.b) cuts.push_back(t + q);
  } else {
    cuts.push_back(0.5 * (I.a + I.b));
  }
  double lo = I.a;
  cuts.push_back(I.b);
  for (double c : cuts) {
    Interval J;
    J.a = lo;
    J.b = c;
    J.star = st && J.a < st->at && st->at < J.b;
    out.push_back(std::move(J));
    lo = c;
  }
}

// Branch and bound at the precision of M until every surviving interval's lower bound is
// within 2^-target_bits (best - r) of the best upper bound.
Search::Outcome Search::branch_and_bound(const ArbModel& M, long target_bits) {
  const long prec = M.prec;
  Ball thr, tmp;
  for (int round = 0; round < 200; ++round) {
    core::check_budget();
    // Float order: the most promising first, so the upper bound drops early.
    std::vector<size_t> order;
    for (size_t i = 0; i < alive_.size(); ++i)
      if (!alive_[i].evaluated) order.push_back(i);
    for (size_t i : order)
      if (!alive_[i].star) {
        alive_[i].mid = guide(fm_, 0.5 * (alive_[i].a + alive_[i].b));
        if (!alive_[i].mid.ok) return Outcome::GiveUp; // K meets E (in double)
        alive_[i].f = alive_[i].mid.f;
      }
    std::sort(order.begin(), order.end(),
              [&](size_t x, size_t y) { return alive_[x].f < alive_[y].f; });
    for (size_t i : order) {
      if (!evaluate(alive_[i], M)) return Outcome::GiveUp;
      if (evaluations_ > kMaxEvaluations) return Outcome::GiveUp;
    }
    // A genuine point of E within r of K: E meets the solid torus.
    arb_set_arf(tmp.v, best_);
    if (!arf_is_finite(best_) || !arb_gt(tmp.v, M.r.v)) return Outcome::GiveUp;
    std::vector<Interval> kept;
    for (auto& I : alive_)
      if (arf_cmp(arb_midref(I.lb.v), best_) <= 0) kept.push_back(std::move(I));
    alive_ = std::move(kept);
    // Too many survivors: a continuum of minimizers, or guidance short of the target.
    if (alive_.size() > kMaxAlive) return Outcome::Stuck;
    // threshold: best - 2^-target_bits (best - r), rounded down
    arb_sub(thr.v, tmp.v, M.r.v, prec);
    arb_mul_2exp_si(thr.v, thr.v, -target_bits);
    arb_sub(thr.v, tmp.v, thr.v, prec);
    arf_t t;
    arf_init(t);
    arb_get_lbound_arf(t, thr.v, prec);
    std::vector<bool> need(alive_.size());
    bool any = false, stuck = false;
    for (size_t i = 0; i < alive_.size(); ++i) {
      need[i] = arf_cmp(arb_midref(alive_[i].lb.v), t) < 0;
      any = any || need[i];
      stuck = stuck || (need[i] && alive_[i].b - alive_[i].a < kMinWidth);
    }
    arf_clear(t);
    if (!any) return Outcome::Done;
    if (stuck) return Outcome::Stuck; // alive_ intact: every interval evaluated
    std::vector<Interval> next;
    for (size_t i = 0; i < alive_.size(); ++i)
      if (need[i])
        split(next, alive_[i]);
      else
        next.push_back(std::move(alive_[i]));
    alive_ = std::move(next);
  }
  return Outcome::GiveUp;
}

// Maximal runs of contiguous surviving intervals on the circle (tau mod 2); false when they
// cover the whole circle (a continuum of minimizers is possible). A run crossing the start of
// the parametrisation is moved by +2 (cos / sin (pi tau) are 2-periodic).
bool Search::clusters(std::vector<std::vector<size_t>>& groups) {
  std::sort(alive_.begin(), alive_.end(),
            [](const Interval& x, const Interval& y) { return x.a < y.a; });
  groups.clear();
  for (size_t i = 0; i < alive_.size(); ++i) {
    if (groups.empty() || alive_[groups.back().back()].b != alive_[i].a) groups.emplace_back();
    groups.back().push_back(i);
  }
  if (groups.empty()) return false;
  const double start = alive_.front().a, end = alive_.back().b;
  if (groups.size() == 1 && end - start >= 2) return false;
  if (groups.size() > 1 && end - start == 2) { // first and last runs touch across tau = start
    for (size_t i : groups.front()) {
      alive_[i].a += 2;
      alive_[i].b += 2;
    }
    groups.back().insert(groups.back().end(), groups.front().begin(), groups.front().end());
    groups.erase(groups.begin());
  }
  return true;
}

std::optional<DistanceResult> Search::run(bool quadric_first) {
  // Initial cover of the circle: 16 intervals of tau, offset from 0 by an odd dyadic so that
  // symmetric positions (tau* = k/4) do not fall on the cuts.
  constexpr double shift = 7.0 / 512.0;
  for (int i = 0; i < 16; ++i) {
    Interval I;
    I.a = shift + i / 8.0;
    I.b = shift + (i + 1) / 8.0;
    alive_.push_back(std::move(I));
  }
  const bool single = digits_ <= kSinglePhaseDigits;
  const long target_bits = static_cast<long>(static_cast<double>(digits_) * 3.33) + 3;
  // Phase 1 at modest precision with double guidance: for few digits it usually finishes;
  // otherwise (many digits, or guidance not accurate enough, e.g. far from the origin) it
  // isolates the clusters of candidate minimizers.
  // (128 bits keep Arb's mantissas inline, without allocation.)
  const ArbModel M1(e_, t_, frame_,
                    std::max(128L, bits_for(std::min(digits_, kSinglePhaseDigits) + 4)));
  const Outcome o1 = branch_and_bound(M1, single ? target_bits : kClusterBits);
  if (o1 == Outcome::GiveUp) return std::nullopt;
  std::vector<std::vector<size_t>> groups;
  if (!clusters(groups) || groups.size() > kMaxClusters) return std::nullopt;
  if (single && o1 == Outcome::Done)
    if (auto r = finish(M1, groups, quadric_first)) return r;
  // Phase 2: refine each cluster's best pair in MPFR and certify again at the working
  // precision on the cluster hull cut at tau* -+ delta (the outer pieces lie far above the
  // minimum).
  const ArbModel M2(e_, t_, frame_, bits_for(digits_ + 10));
  if (!place_stars(groups, M2.prec)) return std::nullopt;
  if (branch_and_bound(M2, target_bits) != Outcome::Done) return std::nullopt;
  if (!clusters(groups)) return std::nullopt;
  return finish(M2, groups, quadric_first);
}

bool Search::place_stars(const std::vector<std::vector<size_t>>& groups, long bits) {
  std::vector<Interval> next;
  stars_.clear();
  for (const auto& g : groups) {
    size_t bi = g.front();
    for (size_t i : g)
      if (alive_[i].has_upper &&
          (!alive_[bi].has_upper || arb_lt(alive_[i].up.D.v, alive_[bi].up.D.v)))
        bi = i;
    const double ha = alive_[g.front()].a, hb = alive_[g.back()].b;
    const Guide gd = choose_tau(fm_, alive_[bi].a, alive_[bi].b);
    if (!gd.ok) return false;
    Star sa;
    {
      const MpPrecision scope(bits);
      Mp tau;
      V3<Mp> n;
      if (!refine_mpfr(e_, t_, frame_, bits, gd.tau, gd.n, gd.f, tau, n)) return false;
      while (tau < ha) // tau* into the hull (mod 2)
        tau += 2;
      while (tau >= ha + 2)
        tau -= 2;
      if (!(tau <= hb)) return false;
      arf_set_mpfr(arb_midref(sa.tau0.v), tau.backend().data());
      for (size_t i = 0; i < 3; ++i)
        arf_set_mpfr(arb_midref(sa.n0[i].v), n[i].backend().data());
      sa.at = tau.convert_to<double>();
    }
    for (size_t i = 0; i < 3; ++i)
      arb_set_d(sa.n1[i].v, gd.n1[i]);
    const double delta = std::min(0x1p-20, 0.25 * (hb - ha));
    std::vector<double> cuts{ha};
    if (sa.at - delta > ha) cuts.push_back(sa.at - delta);
    if (sa.at + delta < hb) cuts.push_back(sa.at + delta);
    cuts.push_back(hb);
    for (size_t k = 0; k + 1 < cuts.size(); ++k) {
      Interval I;
      I.a = cuts[k];
      I.b = cuts[k + 1];
      I.star = I.a < sa.at && sa.at < I.b;
      next.push_back(std::move(I));
    }
    stars_.push_back(std::move(sa));
  }
  alive_ = std::move(next);
  return true;
}

std::optional<DistanceResult> Search::finish(const ArbModel& M,
                                             const std::vector<std::vector<size_t>>& groups,
                                             bool quadric_first) const {
  const long prec = M.prec;

  // Enclosure: [min lb - r, best - r]; disjointness needs min lb > r.
  arf_t L;
  arf_init(L);
  arf_pos_inf(L);
  for (const auto& I : alive_)
    if (arf_cmp(arb_midref(I.lb.v), L) < 0) arf_set(L, arb_midref(I.lb.v));
  Ball lo, hi, d;
  arb_set_arf(lo.v, L);
  arb_sub(lo.v, lo.v, M.r.v, prec);
  arb_set_arf(hi.v, best_);
  arb_sub(hi.v, hi.v, M.r.v, prec);
  arf_clear(L);
  if (!relative_enclosure(d.v, lo.v, hi.v, digits_, prec)) return std::nullopt;

  DistanceResult out;
  out.status = Status::Certified;
  set_distance_enclosure(out, d.v, digits_);
  // One pair per cluster: its interval with the smallest genuine upper bound.
  std::vector<const Interval*> reps;
  for (const auto& g : groups) {
    const Interval* best = nullptr;
    for (size_t i : g)
      if (alive_[i].has_upper && (!best || arb_lt(alive_[i].up.D.v, best->up.D.v)))
        best = &alive_[i];
    if (!best) return std::nullopt;
    reps.push_back(best);
  }
  std::sort(reps.begin(), reps.end(), [](const Interval* x, const Interval* y) {
    return arf_cmp(arb_midref(x->up.D.v), arb_midref(y->up.D.v)) < 0;
  });
  for (const Interval* I : reps)
    out.pairs.push_back(quadric_first ? std::array<D3, 2>{I->up.p, I->up.q}
                                      : std::array<D3, 2>{I->up.q, I->up.p});
  out.minimizers = Minimizers::count(static_cast<long>(reps.size()), Minimizers::Proof::Interval);
  out.critical_candidates = static_cast<int>(reps.size());
  out.eliminated_degree = 0;
  out.method = Method::TorusCircleBound;
  out.note = "ellipsoid outside the solid torus: certified by branch and bound over the core "
             "circle (support-function duality lower bounds with Taylor forms, Arb; genuine "
             "pairs: support points and their exact distance to the torus); no elimination "
             "needed";
  note_unproven_ties(out, reps.size());
  // Every minimizing tau lies in a cluster; a cluster holds at most one when D(tau) =
  // dist(K(tau), E)^2 (same minimizers as the distance) has at most one critical point on its
  // hull (group_uniqueness.hpp). Adjacent survivors alone prove nothing: two minimizers closer
  // than the surviving intervals (a bump between them below 10^-digits) make one cluster.
  std::vector<Ball> hulls;
  for (const auto& g : groups) {
    Ball T, a, b;
    bool first = true;
    for (size_t i : g) {
      arb_set_d(a.v, alive_[i].a);
      arb_set_d(b.v, alive_[i].b);
      arb_union(a.v, a.v, b.v, prec);
      if (first)
        arb_swap(T.v, a.v);
      else
        arb_union(T.v, T.v, a.v, prec);
      first = false;
    }
    hulls.push_back(std::move(T));
  }
  // y(tau) = K(tau) - c = (o - c) + R (cos(pi tau) u + sin(pi tau) v) as series at T; W fixed.
  auto derivs = [&](arb_t d1, arb_t d2, const arb_t T) {
    Series x, sn, cs, y[3], W[3][3];
    arb_poly_set_coeff_arb(x.p, 0, T);
    arb_poly_set_coeff_si(x.p, 1, 1);
    arb_poly_sin_cos_pi_series(sn.p, cs.p, x.p, 3, prec);
    for (size_t i = 0; i < 3; ++i) {
      Series t1, t2, k;
      arb_poly_scalar_mul(t1.p, cs.p, M.u[i].v, prec);
      arb_poly_scalar_mul(t2.p, sn.p, M.v[i].v, prec);
      arb_poly_add(t1.p, t1.p, t2.p, prec);
      arb_poly_scalar_mul(t1.p, t1.p, M.R.v, prec);
      arb_poly_set_arb(k.p, M.oc[i].v);
      arb_poly_add(y[i].p, t1.p, k.p, prec);
      for (size_t j = 0; j < 3; ++j)
        arb_poly_set_arb(W[i][j].p, M.W[i][j].v);
    }
    ellipsoid_dist2_derivatives(d1, d2, y, W, prec);
  };
  prove_one_per_group(out, hulls, derivs, 1, "a minimizing arc of the core circle");
  // Tie regions (symmetry.hpp): per cluster the core points K(tau) over its intervals, which
  // hold every minimizing tau (the branch and bound dropped the others); an isometry keeping
  // the torus maps its core circle onto itself.
  for (const auto& g : groups) {
    Ball hull[3];
    bool first = true;
    for (size_t i : g) {
      Ball T, a, b, sn, cs, k;
      arb_set_d(a.v, alive_[i].a);
      arb_set_d(b.v, alive_[i].b);
      arb_union(T.v, a.v, b.v, prec);
      arb_sin_cos_pi(sn.v, cs.v, T.v, prec);
      for (size_t l = 0; l < 3; ++l) {
        arb_mul(k.v, cs.v, M.u[l].v, prec);
        arb_addmul(k.v, sn.v, M.v[l].v, prec);
        arb_mul(k.v, k.v, M.R.v, prec);
        arb_add(k.v, k.v, M.o[l].v, prec);
        if (first)
          arb_swap(hull[l].v, k.v);
        else
          arb_union(hull[l].v, hull[l].v, k.v, prec);
      }
      first = false;
    }
    std::vector<std::array<double, 2>> reg;
    for (const Ball& x : hull)
      reg.push_back(outward_interval(x.v));
    out.tie_regions.push_back(std::move(reg));
  }
  return out;
}

} // namespace

std::optional<DistanceResult> ellipsoid_torus_fast(const ConvexQuadric& e, const core::Torus& t,
                                                   long digits, bool quadric_first) {
  if (!e.is_ellipsoid() || digits < 1) return std::nullopt;
  Search s(e, t, digits);
  return s.run(quadric_first);
}

} // namespace surfcert::certify
