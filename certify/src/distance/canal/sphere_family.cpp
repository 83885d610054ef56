#include "surfcert/certify/distance/sphere_family.hpp"
#include "surfcert/core/budget.hpp"

#include "surfcert/certify/distance/ball.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

using Poly = std::vector<Rational>; // constant first

Poly derivative(const Poly& p) {
  Poly d;
  for (size_t k = 1; k < p.size(); ++k)
    d.push_back(p[k] * Rational(static_cast<long>(k)));
  return d;
}

void horner(arb_t out, const Poly& c, const arb_t t, long prec) {
  Ball x;
  arb_zero(out);
  for (size_t k = c.size(); k-- > 0;) {
    arb_mul(out, out, t, prec);
    arb_set_fmpq(x.v, c[k].raw(), prec);
    arb_add(out, out, x.v, prec);
  }
}

// A ball around the exact interval [a, b].
void interval(arb_t out, const Rational& a, const Rational& b, long prec) {
  Ball y;
  arb_set_fmpq(out, a.raw(), prec);
  arb_set_fmpq(y.v, b.raw(), prec);
  arb_union(out, out, y.v, prec);
}

// Centre, radius and their first two derivatives over a parameter ball.
struct Jet {
  Ball c[3], dc[3], ddc[3], r, dr, ddr;
};

// One family of balls: a canal surface (polynomial centre and radius on [t0, t1]) or a torus
// (core circle o + R (cos(pi t) u + sin(pi t) v), constant radius, t in [0, 2), periodic).
struct Family {
  bool periodic = false;
  Rational t0, t1;
  std::array<Poly, 3> C, dC, ddC;
  Poly r, dr, ddr;
  Ball o[3], u[3], v[3], R, rt; // torus, at the working precision

  Family(const core::Surface& s, long prec) {
    if (const auto* c = std::get_if<core::CanalSurface>(&s)) {
      t0 = c->t0;
      t1 = c->t1;
      for (size_t i = 0; i < 3; ++i) {
        C[i] = c->spine[i];
        dC[i] = derivative(C[i]);
        ddC[i] = derivative(dC[i]);
      }
      r = c->radius;
      dr = derivative(r);
      ddr = derivative(dr);
      return;
    }
    const auto& t = std::get<core::Torus>(s);
    periodic = true;
    t0 = Rational(0);
    t1 = Rational(2);
    unit_plane_frame(u, v, t.axis, prec); // the core circle: o + R (cos u + sin v)
    for (size_t i = 0; i < 3; ++i)
      arb_set_fmpq(o[i].v, t.centre[i].raw(), prec);
    arb_set_fmpq(R.v, t.R.raw(), prec);
    arb_set_fmpq(rt.v, t.r.raw(), prec);
  }

  void at(const arb_t t, Jet& j, long prec) const {
    if (!periodic) {
      for (size_t i = 0; i < 3; ++i) {
        horner(j.c[i].v, C[i], t, prec);
        horner(j.dc[i].v, dC[i], t, prec);
        horner(j.ddc[i].v, ddC[i], t, prec);
      }
      horner(j.r.v, r, t, prec);
      horner(j.dr.v, dr, t, prec);
      horner(j.ddr.v, ddr, t, prec);
      return;
    }
    Ball sn, cs, pi, piR, pi2R, k;
    arb_sin_cos_pi(sn.v, cs.v, t, prec);
    arb_const_pi(pi.v, prec);
    arb_mul(piR.v, pi.v, R.v, prec);
    arb_mul(pi2R.v, piR.v, pi.v, prec);
    for (size_t i = 0; i < 3; ++i) {
      arb_mul(k.v, cs.v, u[i].v, prec); // k = cos u + sin v
      arb_addmul(k.v, sn.v, v[i].v, prec);
      arb_mul(j.c[i].v, k.v, R.v, prec);
      arb_add(j.c[i].v, j.c[i].v, o[i].v, prec);
      arb_mul(j.ddc[i].v, k.v, pi2R.v, prec);
      arb_neg(j.ddc[i].v, j.ddc[i].v);
      arb_mul(j.dc[i].v, cs.v, v[i].v, prec);
      arb_submul(j.dc[i].v, sn.v, u[i].v, prec);
      arb_mul(j.dc[i].v, j.dc[i].v, piR.v, prec);
    }
    arb_set(j.r.v, rt.v);
    arb_zero(j.dr.v);
    arb_zero(j.ddr.v);
  }
};

// r > 0 on the whole parameter interval, certified by bisection (false when not proven).
bool radius_positive(const Family& f, long prec) {
  if (f.periodic) return true;
  std::vector<std::pair<Rational, Rational>> live{{f.t0, f.t1}};
  for (int round = 0; round < 40 && !live.empty(); ++round) {
    core::check_budget();
    std::vector<std::pair<Rational, Rational>> next;
    for (const auto& [a, b] : live) {
      Ball T, x;
      interval(T.v, a, b, prec);
      horner(x.v, f.r, T.v, prec);
      if (arb_is_positive(x.v)) continue;
      const Rational m = (a + b) * Rational(1, 2);
      next.emplace_back(a, m);
      next.emplace_back(m, b);
    }
    if (next.size() > 512) return false;
    live = std::move(next);
  }
  return live.empty();
}

// F(s, t) = |C1(s) - C2(t)| - r1(s) - r2(t), its gradient and (optionally) its Hessian
// (H[0][0] = F_ss, H[0][1] = H[1][0] = F_st, H[1][1] = F_tt) over the balls S, T.
struct Eval {
  Ball F, g[2], H[2][2];
  Jet a, b;
};

void evaluate(Eval& e, const Family& A, const Family& B, const arb_t S, const arb_t T, bool hessian,
              long prec) {
  A.at(S, e.a, prec);
  B.at(T, e.b, prec);
  Ball w[3], n2, n, wa, wb, tmp, n3;
  for (size_t i = 0; i < 3; ++i) {
    arb_sub(w[i].v, e.a.c[i].v, e.b.c[i].v, prec);
    arb_addmul(n2.v, w[i].v, w[i].v, prec);
    arb_addmul(wa.v, w[i].v, e.a.dc[i].v, prec);
    arb_addmul(wb.v, w[i].v, e.b.dc[i].v, prec);
  }
  arb_sqrtpos(n.v, n2.v, prec);
  arb_sub(e.F.v, n.v, e.a.r.v, prec);
  arb_sub(e.F.v, e.F.v, e.b.r.v, prec);
  arb_div(e.g[0].v, wa.v, n.v, prec); // F_s = w.C1'/n - r1'
  arb_sub(e.g[0].v, e.g[0].v, e.a.dr.v, prec);
  arb_div(e.g[1].v, wb.v, n.v, prec); // F_t = -w.C2'/n - r2'
  arb_neg(e.g[1].v, e.g[1].v);
  arb_sub(e.g[1].v, e.g[1].v, e.b.dr.v, prec);
  if (!hessian) return;
  Ball aa, bb, ab, wA, wB;
  for (size_t i = 0; i < 3; ++i) {
    arb_addmul(aa.v, e.a.dc[i].v, e.a.dc[i].v, prec);
    arb_addmul(bb.v, e.b.dc[i].v, e.b.dc[i].v, prec);
    arb_addmul(ab.v, e.a.dc[i].v, e.b.dc[i].v, prec);
    arb_addmul(wA.v, w[i].v, e.a.ddc[i].v, prec);
    arb_addmul(wB.v, w[i].v, e.b.ddc[i].v, prec);
  }
  arb_mul(n3.v, n2.v, n.v, prec);
  // F_ss = (C1'.C1' + w.C1'')/n - (w.C1')^2/n^3 - r1''
  arb_add(tmp.v, aa.v, wA.v, prec);
  arb_div(e.H[0][0].v, tmp.v, n.v, prec);
  arb_sqr(tmp.v, wa.v, prec);
  arb_div(tmp.v, tmp.v, n3.v, prec);
  arb_sub(e.H[0][0].v, e.H[0][0].v, tmp.v, prec);
  arb_sub(e.H[0][0].v, e.H[0][0].v, e.a.ddr.v, prec);
  // F_tt = (C2'.C2' - w.C2'')/n - (w.C2')^2/n^3 - r2''
  arb_sub(tmp.v, bb.v, wB.v, prec);
  arb_div(e.H[1][1].v, tmp.v, n.v, prec);
  arb_sqr(tmp.v, wb.v, prec);
  arb_div(tmp.v, tmp.v, n3.v, prec);
  arb_sub(e.H[1][1].v, e.H[1][1].v, tmp.v, prec);
  arb_sub(e.H[1][1].v, e.H[1][1].v, e.b.ddr.v, prec);
  // F_st = -C1'.C2'/n + (w.C1')(w.C2')/n^3
  arb_div(e.H[0][1].v, ab.v, n.v, prec);
  arb_neg(e.H[0][1].v, e.H[0][1].v);
  arb_mul(tmp.v, wa.v, wb.v, prec);
  arb_div(tmp.v, tmp.v, n3.v, prec);
  arb_add(e.H[0][1].v, e.H[0][1].v, tmp.v, prec);
  arb_set(e.H[1][0].v, e.H[0][1].v);
}

struct Box {
  Rational s0, s1, t0, t1;
  arf_struct lower[1], upper[1]; // certified lower bound of F on the box; F at (sp, tp)
  Rational sp, tp;               // the box's best evaluated point
  Box() {
    arf_init(lower);
    arf_init(upper);
  }
  Box(const Box& o) : Box() { *this = o; }
  Box& operator=(const Box& o) {
    if (this == &o) return *this;
    s0 = o.s0, s1 = o.s1, t0 = o.t0, t1 = o.t1, sp = o.sp, tp = o.tp;
    arf_set(lower, o.lower);
    arf_set(upper, o.upper);
    return *this;
  }
  ~Box() {
    arf_clear(lower);
    arf_clear(upper);
  }
};

void bound(Box& b, const Family& A, const Family& B, long prec) {
  Ball S, T, sm, tm, mv, d1, d2;
  Eval whole, mid;
  interval(S.v, b.s0, b.s1, prec);
  interval(T.v, b.t0, b.t1, prec);
  const Rational sr = (b.s0 + b.s1) * Rational(1, 2), tr = (b.t0 + b.t1) * Rational(1, 2);
  arb_set_fmpq(sm.v, sr.raw(), prec);
  arb_set_fmpq(tm.v, tr.raw(), prec);
  evaluate(whole, A, B, S.v, T.v, false, prec);
  evaluate(mid, A, B, sm.v, tm.v, false, prec);
  arb_get_ubound_arf(b.upper, mid.F.v, prec);
  b.sp = sr;
  b.tp = tr;
  // A minimum on an edge of the parameter domain (an end ball) has a nonzero gradient: the
  // midpoint's value lags by O(width) there, so the box's points on that edge are tried too.
  std::vector<Rational> ss{sr}, ts{tr};
  if (!A.periodic && b.s0 == A.t0) ss.push_back(A.t0);
  if (!A.periodic && b.s1 == A.t1) ss.push_back(A.t1);
  if (!B.periodic && b.t0 == B.t0) ts.push_back(B.t0);
  if (!B.periodic && b.t1 == B.t1) ts.push_back(B.t1);
  arf_t x;
  arf_init(x);
  for (const Rational& si : ss)
    for (const Rational& ti : ts) {
      if (si == sr && ti == tr) continue;
      Ball sb, tb;
      Eval e;
      arb_set_fmpq(sb.v, si.raw(), prec);
      arb_set_fmpq(tb.v, ti.raw(), prec);
      evaluate(e, A, B, sb.v, tb.v, false, prec);
      arb_get_ubound_arf(x, e.F.v, prec);
      if (arf_cmp(x, b.upper) < 0) {
        arf_swap(x, b.upper);
        b.sp = si;
        b.tp = ti;
      }
    }
  // Mean-value form F(m) - max|F_s| hs - max|F_t| ht with the half-widths at full precision
  // (as ball radii they would be rounded to 30 bits and stall the convergence at an edge).
  const Rational hs = (b.s1 - b.s0) * Rational(1, 2), ht = (b.t1 - b.t0) * Rational(1, 2);
  arb_set(mv.v, mid.F.v);
  for (int k = 0; k < 2; ++k) {
    arb_get_abs_ubound_arf(x, whole.g[k].v, prec);
    arb_set_arf(d1.v, x);
    arb_set_fmpq(d2.v, (k == 0 ? hs : ht).raw(), prec);
    arb_submul(mv.v, d1.v, d2.v, prec);
  }
  arb_get_lbound_arf(b.lower, whole.F.v, prec);
  arb_get_lbound_arf(x, mv.v, prec);
  if (!arf_is_finite(b.lower) || (arf_is_finite(x) && arf_cmp(x, b.lower) > 0)) arf_set(b.lower, x);
  if (!arf_is_finite(b.lower)) arf_neg_inf(b.lower);
  arf_clear(x);
}

enum class Outcome { Done, Meet, Crowded, Budget };

constexpr size_t kMaxBoxes = 400;

// Bisects `live` until the enclosure [min lower, min upper] (extra_lower / extra_upper: bounds
// from elsewhere, may be infinite) has relative width <= 10^-digits (then d holds it).
Outcome branch_and_bound(std::vector<Box>& live, const Family& A, const Family& B, long prec,
                         long digits, const arf_t extra_lower, const arf_t extra_upper, Ball& d,
                         int max_rounds) {
  for (int round = 0; round < max_rounds; ++round) {
    core::check_budget();
    arf_t best, lowest;
    arf_init(best);
    arf_init(lowest);
    arf_set(best, extra_upper);
    for (auto& bx : live) {
      bound(bx, A, B, prec);
      if (arf_cmp(bx.upper, best) < 0) arf_set(best, bx.upper);
    }
    std::vector<Box> keep;
    arf_set(lowest, extra_lower);
    for (auto& bx : live)
      if (arf_cmp(bx.lower, best) <= 0) {
        if (arf_cmp(bx.lower, lowest) < 0) arf_set(lowest, bx.lower);
        keep.push_back(bx);
      }
    live = std::move(keep);
    Ball lo, hi;
    arb_set_arf(lo.v, lowest);
    arb_set_arf(hi.v, best);
    const bool meet = arf_sgn(best) < 0;
    arf_clear(best);
    arf_clear(lowest);
    if (meet) return Outcome::Meet; // two balls overlap: the solids meet
    if (live.size() > kMaxBoxes) return Outcome::Crowded;
    if (relative_enclosure(d.v, lo.v, hi.v, digits, prec)) return Outcome::Done;
    std::vector<Box> next;
    next.reserve(4 * live.size());
    for (const auto& bx : live) {
      const Rational sm = (bx.s0 + bx.s1) * Rational(1, 2), tm = (bx.t0 + bx.t1) * Rational(1, 2);
      const Rational s[3] = {bx.s0, sm, bx.s1}, t[3] = {bx.t0, tm, bx.t1};
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          Box c;
          c.s0 = s[i];
          c.s1 = s[i + 1];
          c.t0 = t[j];
          c.t1 = t[j + 1];
          next.push_back(c);
        }
    }
    live = std::move(next);
  }
  return Outcome::Budget;
}

// A cluster of touching surviving boxes (across the seam of a periodic parameter), with its
// hull (a seam-crossing hull is written around 0) and its best evaluated point.
struct Cluster {
  std::vector<size_t> members;
  Rational s0, s1, t0, t1, sp, tp;
  bool proven = false;
  std::string kind; // "interior", "edge", "corner" when proven
  Ball ps, pt;      // the refined point (exact midpoints) when proven
  arf_struct lo[1], hi[1];
  Cluster() {
    arf_init(lo);
    arf_init(hi);
  }
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;
  Cluster(Cluster&& o) noexcept : Cluster() {
    members.swap(o.members);
    s0 = o.s0, s1 = o.s1, t0 = o.t0, t1 = o.t1, sp = o.sp, tp = o.tp;
    proven = o.proven;
    kind = o.kind;
    arb_swap(ps.v, o.ps.v);
    arb_swap(pt.v, o.pt.v);
    arf_swap(lo, o.lo);
    arf_swap(hi, o.hi);
  }
  ~Cluster() {
    arf_clear(lo);
    arf_clear(hi);
  }
};

bool touch(const Rational& a0, const Rational& a1, const Rational& b0, const Rational& b1) {
  return !(a1 < b0 || b1 < a0);
}

std::vector<Cluster> clusters_of(const std::vector<Box>& live, const Family& A, const Family& B) {
  const size_t m = live.size();
  std::vector<size_t> parent(m);
  std::iota(parent.begin(), parent.end(), size_t{0});
  std::function<size_t(size_t)> find = [&](size_t i) {
    return parent[i] == i ? i : parent[i] = find(parent[i]);
  };
  auto wrap_touch = [](const Family& f, const Rational& a0, const Rational& a1, const Rational& b0,
                       const Rational& b1) {
    if (touch(a0, a1, b0, b1)) return true;
    return f.periodic && ((a0 == f.t0 && b1 == f.t1) || (b0 == f.t0 && a1 == f.t1));
  };
  for (size_t i = 0; i < m; ++i)
    for (size_t j = i + 1; j < m; ++j)
      if (wrap_touch(A, live[i].s0, live[i].s1, live[j].s0, live[j].s1) &&
          wrap_touch(B, live[i].t0, live[i].t1, live[j].t0, live[j].t1))
        parent[find(i)] = find(j);
  std::vector<Cluster> out;
  std::vector<size_t> id(m, m);
  for (size_t i = 0; i < m; ++i) {
    const size_t r = find(i);
    if (id[r] == m) {
      id[r] = out.size();
      out.emplace_back();
    }
    out[id[r]].members.push_back(i);
  }
  // Hulls; a periodic coordinate whose cluster touches both 0 and 2 is shifted by -2 above 1.
  for (auto& c : out) {
    bool s_lo = false, s_hi = false, t_lo = false, t_hi = false;
    for (size_t i : c.members) {
      s_lo |= live[i].s0 == A.t0;
      s_hi |= live[i].s1 == A.t1;
      t_lo |= live[i].t0 == B.t0;
      t_hi |= live[i].t1 == B.t1;
    }
    const bool ws = A.periodic && s_lo && s_hi, wt = B.periodic && t_lo && t_hi;
    const Box* best = &live[c.members.front()];
    bool first = true;
    for (size_t i : c.members) {
      const Box& b = live[i];
      Rational a0 = b.s0, a1 = b.s1, b0 = b.t0, b1 = b.t1;
      if (ws && a0 >= Rational(1)) a0 -= Rational(2), a1 -= Rational(2);
      if (wt && b0 >= Rational(1)) b0 -= Rational(2), b1 -= Rational(2);
      if (first) {
        c.s0 = a0, c.s1 = a1, c.t0 = b0, c.t1 = b1;
        first = false;
      } else {
        c.s0 = std::min(c.s0, a0), c.s1 = std::max(c.s1, a1);
        c.t0 = std::min(c.t0, b0), c.t1 = std::max(c.t1, b1);
      }
      if (arf_cmp(b.upper, best->upper) < 0) best = &b;
    }
    c.sp = best->sp;
    c.tp = best->tp;
  }
  return out;
}

// F restricted to the free coordinates: both (n = 2), or one with the other fixed at a domain
// edge (n = 1; fixed = 0: s fixed, 1: t fixed).
struct Restricted {
  const Family& A;
  const Family& B;
  int n = 2, fixed = -1;
  Rational edge;

  // F, gradient and Hessian in the free coordinates at the balls x[0..n).
  void eval(const arb_t* x, Ball& F, Ball (&g)[2], Ball (&H)[2][2], bool hessian, long prec) const {
    Eval e;
    Ball fix;
    arb_set_fmpq(fix.v, edge.raw(), prec);
    if (n == 2)
      evaluate(e, A, B, x[0], x[1], hessian, prec);
    else if (fixed == 0)
      evaluate(e, A, B, fix.v, x[0], hessian, prec);
    else
      evaluate(e, A, B, x[0], fix.v, hessian, prec);
    arb_swap(F.v, e.F.v);
    if (n == 2) {
      for (int i = 0; i < 2; ++i) {
        arb_swap(g[i].v, e.g[i].v);
        for (int j = 0; j < 2; ++j)
          arb_swap(H[i][j].v, e.H[i][j].v);
      }
    } else {
      const int k = fixed == 0 ? 1 : 0;
      arb_swap(g[0].v, e.g[k].v);
      arb_swap(H[0][0].v, e.H[k][k].v);
    }
  }
};

// Y ~ H^-1 from midpoints (exact balls of radius 0); false when singular.
bool approx_inverse(Ball (&Y)[2][2], const Ball (&H)[2][2], int n, long prec) {
  if (n == 1) {
    Ball m;
    arb_set_arf(m.v, arb_midref(H[0][0].v));
    if (arf_is_zero(arb_midref(m.v))) return false;
    arb_inv(Y[0][0].v, m.v, prec);
    mag_zero(arb_radref(Y[0][0].v));
    return arb_is_finite(Y[0][0].v);
  }
  Ball m[2][2], det, tmp;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      arb_set_arf(m[i][j].v, arb_midref(H[i][j].v));
  arb_mul(det.v, m[0][0].v, m[1][1].v, prec);
  arb_submul(det.v, m[0][1].v, m[1][0].v, prec);
  if (arf_is_zero(arb_midref(det.v))) return false;
  mag_zero(arb_radref(det.v));
  arb_div(Y[0][0].v, m[1][1].v, det.v, prec);
  arb_div(Y[1][1].v, m[0][0].v, det.v, prec);
  arb_div(Y[0][1].v, m[0][1].v, det.v, prec);
  arb_neg(Y[0][1].v, Y[0][1].v);
  arb_div(Y[1][0].v, m[1][0].v, det.v, prec);
  arb_neg(Y[1][0].v, Y[1][0].v);
  for (auto& row : Y)
    for (auto& y : row) {
      mag_zero(arb_radref(y.v));
      if (!arb_is_finite(y.v)) return false;
    }
  return true;
}

// Krawczyk: K(X) = m - Y g(m) + (I - Y H(X)) (X - m) inside the interior of X proves exactly
// one zero of the gradient in X.
bool krawczyk(const Restricted& P, const Ball (&X)[2], long prec) {
  const int n = P.n;
  Ball m[2], dx[2], F, g[2], H[2][2], Fx, gx[2], Hx[2][2], Y[2][2];
  arb_t xs[2], ms[2];
  for (int i = 0; i < n; ++i) {
    arb_set_arf(m[i].v, arb_midref(X[i].v));
    arb_zero(dx[i].v);
    mag_set(arb_radref(dx[i].v), arb_radref(X[i].v));
    xs[i][0] = *X[i].v;
    ms[i][0] = *m[i].v;
  }
  P.eval(ms, F, g, H, true, prec);
  P.eval(xs, Fx, gx, Hx, true, prec);
  if (!approx_inverse(Y, H, n, prec)) return false;
  for (int i = 0; i < n; ++i) {
    Ball k, t, c;
    arb_set(k.v, m[i].v);
    for (int j = 0; j < n; ++j) {
      arb_submul(k.v, Y[i][j].v, g[j].v, prec);
      // (I - Y Hx)_{ij}
      arb_set_si(c.v, i == j ? 1 : 0);
      for (int l = 0; l < n; ++l)
        arb_submul(c.v, Y[i][l].v, Hx[l][j].v, prec);
      arb_mul(t.v, c.v, dx[j].v, prec);
      arb_add(k.v, k.v, t.v, prec);
    }
    if (!arb_is_finite(k.v) || !arb_contains_interior(X[i].v, k.v)) return false;
  }
  return true;
}

// Newton's iteration from x (exact midpoints) at doubling precision up to prec; then a small
// box around the result proven (Krawczyk) to hold the zero, inside `outer`. x holds the final
// point (exact), X the proven box.
bool newton_refine(const Restricted& P, Ball (&x)[2], const Ball (&outer)[2], Ball (&X)[2],
                   long prec) {
  const int n = P.n;
  arf_t step;
  arf_init(step);
  std::vector<long> precs;
  for (long p = 64; p < prec; p *= 2)
    precs.push_back(p);
  precs.insert(precs.end(), {prec, prec, prec});
  for (long p : precs) {
    Ball F, g[2], H[2][2], Y[2][2];
    arb_t xs[2];
    for (int i = 0; i < n; ++i)
      xs[i][0] = *x[i].v;
    P.eval(xs, F, g, H, true, p);
    if (!approx_inverse(Y, H, n, p)) break;
    arf_zero(step);
    for (int i = 0; i < n; ++i) {
      Ball d;
      for (int j = 0; j < n; ++j)
        arb_addmul(d.v, Y[i][j].v, g[j].v, p);
      arb_sub(x[i].v, x[i].v, d.v, p);
      mag_zero(arb_radref(x[i].v));
      arf_t a;
      arf_init(a);
      arf_abs(a, arb_midref(d.v));
      if (arf_cmp(a, step) > 0) arf_set(step, a);
      arf_clear(a);
    }
  }
  bool ok = false;
  // The box radius: well above the last step and the rounding level, then larger on failure.
  mag_t rho, floor_;
  mag_init(rho);
  mag_init(floor_);
  arf_get_mag(rho, step);
  mag_mul_2exp_si(rho, rho, 4);
  mag_set_ui_2exp_si(floor_, 1, -(prec - 24));
  for (int i = 0; i < n; ++i) { // relative to the size of the coordinates
    mag_t a;
    mag_init(a);
    arf_get_mag(a, arb_midref(x[i].v));
    mag_mul_2exp_si(a, a, -(prec - 24));
    mag_max(floor_, floor_, a);
    mag_clear(a);
  }
  mag_max(rho, rho, floor_);
  for (int attempt = 0; attempt < 6 && !ok; ++attempt) {
    bool inside = true;
    for (int i = 0; i < n; ++i) {
      arb_set(X[i].v, x[i].v);
      mag_set(arb_radref(X[i].v), rho);
      inside = inside && arb_contains(outer[i].v, X[i].v);
    }
    if (!inside) break;
    ok = krawczyk(P, X, prec);
    mag_mul_2exp_si(rho, rho, 16);
  }
  mag_clear(rho);
  mag_clear(floor_);
  arf_clear(step);
  return ok;
}

// Certified bound: (the upper end of) ball x lies below the exact rational q.
bool below(const arb_t x, const Rational& q, long prec) {
  Ball u, Q;
  arf_t a;
  arf_init(a);
  arb_get_ubound_arf(a, x, prec);
  arb_set_arf(u.v, a);
  arf_clear(a);
  arb_set_fmpq(Q.v, q.raw(), prec);
  return arb_lt(u.v, Q.v);
}
bool above(const arb_t x, const Rational& q, long prec) {
  Ball l, Q;
  arf_t a;
  arf_init(a);
  arb_get_lbound_arf(a, x, prec);
  arb_set_arf(l.v, a);
  arf_clear(a);
  arb_set_fmpq(Q.v, q.raw(), prec);
  return arb_gt(l.v, Q.v);
}

// Tries to prove that the cluster holds exactly one candidate for the minimum (an interior
// critical point, a critical point of the restriction to an edge, or a corner) and encloses F
// there tightly; sets c.proven, c.lo, c.hi, c.ps, c.pt.
void prove_cluster(Cluster& c, const Family& A, const Family& B, long prec) {
  Ball S, T;
  interval(S.v, c.s0, c.s1, prec);
  interval(T.v, c.t0, c.t1, prec);
  Eval whole;
  evaluate(whole, A, B, S.v, T.v, false, prec);
  // Per coordinate: 0 free (hull inside the domain, or periodic), -1 / +1 fixed at the low /
  // high edge (the hull reaches it and the derivative's sign pushes the minimum onto it).
  auto state = [&](const Family& f, const Rational& h0, const Rational& h1, const arb_t H,
                   const arb_t deriv, int& st, Rational& edge) {
    if (f.periodic) {
      st = 0;
      return h1 - h0 < Rational(1); // less than half the circle
    }
    if (h0 == f.t0 && h1 != f.t1 && arb_is_positive(deriv)) {
      st = -1, edge = f.t0;
      return true;
    }
    if (h1 == f.t1 && h0 != f.t0 && arb_is_negative(deriv)) {
      st = 1, edge = f.t1;
      return true;
    }
    st = 0;
    return above(H, f.t0, prec) && below(H, f.t1, prec);
  };
  int ss = 0, st = 0;
  Rational es, et;
  if (!state(A, c.s0, c.s1, S.v, whole.g[0].v, ss, es)) return;
  if (!state(B, c.t0, c.t1, T.v, whole.g[1].v, st, et)) return;
  if (ss != 0 && st != 0) { // a corner: the minimum of the cluster is F(es, et)
    Eval e;
    arb_set_fmpq(c.ps.v, es.raw(), prec);
    arb_set_fmpq(c.pt.v, et.raw(), prec);
    evaluate(e, A, B, c.ps.v, c.pt.v, false, prec);
    arb_get_lbound_arf(c.lo, e.F.v, prec);
    arb_get_ubound_arf(c.hi, e.F.v, prec);
    c.kind = "corner";
    c.proven = arf_is_finite(c.lo) && arf_is_finite(c.hi);
    return;
  }
  Restricted P{A, B, 2, -1, Rational()};
  Ball outer[2], x[2], X[2];
  if (ss == 0 && st == 0) {
    P.n = 2;
    arb_set(outer[0].v, S.v);
    arb_set(outer[1].v, T.v);
    arb_set_fmpq(x[0].v, c.sp.raw(), prec);
    arb_set_fmpq(x[1].v, c.tp.raw(), prec);
  } else {
    P.n = 1;
    P.fixed = ss != 0 ? 0 : 1;
    P.edge = ss != 0 ? es : et;
    arb_set(outer[0].v, ss != 0 ? T.v : S.v);
    arb_set_fmpq(x[0].v, (ss != 0 ? c.tp : c.sp).raw(), prec);
  }
  for (int i = 0; i < P.n; ++i)
    mag_zero(arb_radref(x[i].v));
  if (!krawczyk(P, outer, prec)) return; // uniqueness in the cluster's hull
  if (!newton_refine(P, x, outer, X, prec)) return;
  Ball F, g[2], H[2][2], Fx, gx[2], Hx[2][2], mv, r;
  arb_t xs[2], Xs[2];
  for (int i = 0; i < P.n; ++i) {
    xs[i][0] = *x[i].v;
    Xs[i][0] = *X[i].v;
  }
  P.eval(xs, F, g, H, false, prec);
  P.eval(Xs, Fx, gx, Hx, false, prec);
  // lower bound over X: interval extension or F(x) - sum |g(X)| rad(X)
  arb_set(mv.v, F.v);
  for (int i = 0; i < P.n; ++i) {
    arb_zero(r.v);
    mag_set(arb_radref(r.v), arb_radref(X[i].v));
    arb_addmul(mv.v, gx[i].v, r.v, prec);
  }
  arf_t a;
  arf_init(a);
  arb_get_lbound_arf(c.lo, Fx.v, prec);
  arb_get_lbound_arf(a, mv.v, prec);
  if (arf_cmp(a, c.lo) > 0) arf_set(c.lo, a);
  arf_clear(a);
  arb_get_ubound_arf(c.hi, F.v, prec);
  if (P.n == 2) {
    arb_set(c.ps.v, x[0].v);
    arb_set(c.pt.v, x[1].v);
    c.kind = "interior";
  } else if (P.fixed == 0) {
    arb_set_fmpq(c.ps.v, es.raw(), prec);
    arb_set(c.pt.v, x[0].v);
    c.kind = "edge";
  } else {
    arb_set(c.ps.v, x[0].v);
    arb_set_fmpq(c.pt.v, et.raw(), prec);
    c.kind = "edge";
  }
  c.proven = arf_is_finite(c.lo) && arf_is_finite(c.hi);
}

std::array<std::array<double, 3>, 2> pair_at(const Family& A, const Family& B, const arb_t s,
                                             const arb_t t, long prec) {
  Jet ja, jb;
  A.at(s, ja, prec);
  B.at(t, jb, prec);
  double w[3], n = 0;
  for (size_t i = 0; i < 3; ++i) {
    w[i] = arf_get_d(arb_midref(jb.c[i].v), ARF_RND_NEAR) -
           arf_get_d(arb_midref(ja.c[i].v), ARF_RND_NEAR);
    n += w[i] * w[i];
  }
  n = std::sqrt(n);
  const double ra = arf_get_d(arb_midref(ja.r.v), ARF_RND_NEAR),
               rb = arf_get_d(arb_midref(jb.r.v), ARF_RND_NEAR);
  std::array<std::array<double, 3>, 2> pr{};
  for (size_t i = 0; i < 3; ++i) {
    pr[0][i] = arf_get_d(arb_midref(ja.c[i].v), ARF_RND_NEAR) + ra * w[i] / n;
    pr[1][i] = arf_get_d(arb_midref(jb.c[i].v), ARF_RND_NEAR) - rb * w[i] / n;
  }
  return pr;
}

std::vector<std::array<double, 2>> region(const Family& A, const Rational& s0, const Rational& s1,
                                          long prec) {
  Ball S;
  Jet j;
  interval(S.v, s0, s1, prec);
  A.at(S.v, j, prec);
  std::vector<std::array<double, 2>> reg;
  for (const Ball& c : j.c)
    reg.push_back(outward_interval(c.v));
  return reg;
}

} // namespace

std::optional<DistanceResult> sphere_family_distance(const core::Surface& a, const core::Surface& b,
                                                     long digits) {
  auto ok_kind = [](const core::Surface& s) {
    return std::holds_alternative<core::CanalSurface>(s) || std::holds_alternative<core::Torus>(s);
  };
  if (!ok_kind(a) || !ok_kind(b) || digits < 1) return std::nullopt;
  // Stage 1: branch and bound to d1 digits at a matching precision.
  const long d1 = std::min(digits, 10L);
  const long prec1 = bits_for(d1 + 10), prec = bits_for(digits + 10);
  const Family A1(a, prec1), B1(b, prec1);
  if (!radius_positive(A1, prec1) || !radius_positive(B1, prec1)) return std::nullopt;
  std::vector<Box> live;
  const int n0 = 8;
  for (int i = 0; i < n0; ++i)
    for (int j = 0; j < n0; ++j) {
      Box x;
      x.s0 = A1.t0 + (A1.t1 - A1.t0) * Rational(i, n0);
      x.s1 = A1.t0 + (A1.t1 - A1.t0) * Rational(i + 1, n0);
      x.t0 = B1.t0 + (B1.t1 - B1.t0) * Rational(j, n0);
      x.t1 = B1.t0 + (B1.t1 - B1.t0) * Rational(j + 1, n0);
      live.push_back(x);
    }
  arf_t inf, ninf;
  arf_init(inf);
  arf_init(ninf);
  arf_pos_inf(inf);
  arf_neg_inf(ninf);
  Ball d;
  const Outcome o1 = branch_and_bound(live, A1, B1, prec1, d1, inf, inf, d,
                                      static_cast<int>(3.4 * static_cast<double>(d1)) + 80);
  if (o1 != Outcome::Done) {
    arf_clear(inf);
    arf_clear(ninf);
    return std::nullopt;
  }
  // Stage 2: per cluster, uniqueness (Krawczyk) and Newton refinement at the full precision.
  const Family A(a, prec), B(b, prec);
  std::vector<Cluster> cl = clusters_of(live, A, B);
  const int candidates = static_cast<int>(cl.size());
  arf_t lo1, hi, lo, x;
  arf_init(lo1);
  arf_init(hi);
  arf_init(lo);
  arf_init(x);
  arb_get_lbound_arf(lo1, d.v, prec); // stage 1 bounds stay valid
  arb_get_ubound_arf(hi, d.v, prec);
  arf_pos_inf(lo);
  size_t proven = 0;
  for (auto& c : cl) {
    prove_cluster(c, A, B, prec);
    if (c.proven) {
      ++proven;
      if (arf_cmp(c.hi, hi) < 0) arf_set(hi, c.hi);
      if (arf_cmp(c.lo, lo) < 0) arf_set(lo, c.lo);
    } else {
      for (size_t i : c.members)
        if (arf_cmp(live[i].lower, lo) < 0) arf_set(lo, live[i].lower);
    }
  }
  if (arf_cmp(lo1, lo) > 0) arf_set(lo, lo1);
  Ball blo, bhi;
  arb_set_arf(blo.v, lo);
  arb_set_arf(bhi.v, hi);
  bool done = relative_enclosure(d.v, blo.v, bhi.v, digits, prec);
  // Stage 3: the clusters without a proof are bisected on to the full precision.
  std::vector<Box> rest;
  std::vector<Cluster> rest_cl;
  if (!done) {
    arf_t plo;
    arf_init(plo);
    arf_pos_inf(plo);
    for (const auto& c : cl)
      if (c.proven) {
        if (arf_cmp(c.lo, plo) < 0) arf_set(plo, c.lo);
      } else
        for (size_t i : c.members)
          rest.push_back(live[i]);
    const Outcome o3 =
        rest.empty() ? Outcome::Budget
                     : branch_and_bound(rest, A, B, prec, digits, plo, hi, d,
                                        static_cast<int>(3.4 * static_cast<double>(digits)) + 80);
    arf_clear(plo);
    done = o3 == Outcome::Done;
    if (done) {
      rest_cl = clusters_of(rest, A, B);
      for (auto& c : rest_cl) { // bounds of the remaining groups
        arf_pos_inf(c.lo);
        for (size_t i : c.members)
          if (arf_cmp(rest[i].lower, c.lo) < 0) arf_set(c.lo, rest[i].lower);
      }
    }
  } else {
    for (auto& c : cl)
      if (!c.proven) {
        arf_pos_inf(c.lo);
        for (size_t i : c.members)
          if (arf_cmp(live[i].lower, c.lo) < 0) arf_set(c.lo, live[i].lower);
      }
  }
  arf_clear(lo1);
  arf_clear(lo);
  arf_clear(x);
  arf_clear(inf);
  arf_clear(ninf);
  if (!done) {
    arf_clear(hi);
    return std::nullopt;
  }
  arb_get_ubound_arf(hi, d.v, prec);

  DistanceResult out;
  out.status = Status::Certified;
  set_distance_enclosure(out, d.v, digits);
  out.method = Method::SphereFamilyBnb;
  out.critical_candidates = candidates;
  size_t count = 0, unique = 0;
  std::string kinds;
  auto report = [&](const arb_t s, const arb_t t, const Rational& s0, const Rational& s1) {
    out.pairs.push_back(pair_at(A, B, s, t, prec));
    out.tie_regions.push_back(region(A, s0, s1, prec));
    ++count;
  };
  const bool stage3 = !rest_cl.empty();
  for (auto& c : cl) {
    if (arf_cmp(c.lo, hi) > 0) continue; // above the minimum
    if (c.proven) {
      report(c.ps.v, c.pt.v, c.s0, c.s1);
      ++unique;
      kinds += (kinds.empty() ? "" : ", ") + c.kind;
    } else if (!stage3) {
      Ball s, t;
      arb_set_fmpq(s.v, c.sp.raw(), prec);
      arb_set_fmpq(t.v, c.tp.raw(), prec);
      report(s.v, t.v, c.s0, c.s1);
    }
  }
  for (auto& c : rest_cl) {
    if (arf_cmp(c.lo, hi) > 0) continue;
    Ball s, t;
    arb_set_fmpq(s.v, c.sp.raw(), prec);
    arb_set_fmpq(t.v, c.tp.raw(), prec);
    report(s.v, t.v, c.s0, c.s1);
  }
  arf_clear(hi);
  out.minimizers = Minimizers::count(static_cast<long>(count), Minimizers::Proof::Interval);
  out.note = "disjoint solids as unions of balls: d = min over both parameters of |C1(s) - "
             "C2(t)| - r1(s) - r2(t), by a 2-D branch and bound with mean-value bounds (Arb); a "
             "positive minimum proves the solids disjoint; " +
             std::to_string(unique) + " of " + std::to_string(count) +
             " minimizer(s) proven unique in their cluster and refined by Newton (Krawczyk" +
             (kinds.empty() ? std::string() : ": " + kinds) + ")" +
             (unique < count ? "; the others enclosed by bisection" : "");
  // Tie regions (symmetry.hpp) need at most one minimizer per region: only when every
  // reported cluster was proven to hold a single candidate.
  if (unique < count) out.tie_regions.clear();
  note_unproven_ties(out, count);
  // A cluster without the Krawczyk proof holds every minimizer inside it (at least one), but
  // maybe several (two minima closer than its boxes, a bump between them below 10^-digits):
  // the count is proven only when every reported cluster was.
  if (unique < count) out.count_unproven = true;
  return out;
}

} // namespace surfcert::certify
