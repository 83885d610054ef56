#include "surfcert/certify/distance/canal_pair.hpp"

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

// A one-parameter family of balls: a canal surface (polynomial centre and radius on [t0, t1])
// or a torus (core circle o + R (cos(pi t) u + sin(pi t) v), constant radius, t in [0, 2)).
struct Family {
  bool periodic = false;
  Rational t0, t1;
  std::array<Poly, 3> C, dC;
  Poly r, dr;
  Ball o[3], u[3], v[3], R, rt; // torus, at the working precision

  Family(const core::Surface& s, long prec) {
    if (const auto* c = std::get_if<core::CanalSurface>(&s)) {
      t0 = c->t0;
      t1 = c->t1;
      for (size_t i = 0; i < 3; ++i) {
        C[i] = c->spine[i];
        dC[i] = derivative(C[i]);
      }
      r = c->radius;
      dr = derivative(r);
      return;
    }
    const auto& t = std::get<core::Torus>(s);
    periodic = true;
    t0 = Rational(0);
    t1 = Rational(2);
    // Orthonormal frame: u = a x e_k / |.|, v = a x u / |a| (balls around the exact frame).
    size_t k = 0;
    for (size_t i = 1; i < 3; ++i)
      if (core::abs(t.axis[i]) < core::abs(t.axis[k])) k = i;
    std::array<Rational, 3> e{Rational(0), Rational(0), Rational(0)};
    e[k] = Rational(1);
    const auto& a = t.axis;
    const std::array<Rational, 3> U{a[1] * e[2] - a[2] * e[1], a[2] * e[0] - a[0] * e[2],
                                    a[0] * e[1] - a[1] * e[0]};
    const std::array<Rational, 3> V{a[1] * U[2] - a[2] * U[1], a[2] * U[0] - a[0] * U[2],
                                    a[0] * U[1] - a[1] * U[0]};
    const Rational uu = U[0] * U[0] + U[1] * U[1] + U[2] * U[2],
                   vv = V[0] * V[0] + V[1] * V[1] + V[2] * V[2];
    Ball nu, nv;
    arb_set_fmpq(nu.v, uu.raw(), prec);
    arb_rsqrt(nu.v, nu.v, prec);
    arb_set_fmpq(nv.v, vv.raw(), prec);
    arb_rsqrt(nv.v, nv.v, prec);
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(o[i].v, t.centre[i].raw(), prec);
      arb_set_fmpq(u[i].v, U[i].raw(), prec);
      arb_mul(u[i].v, u[i].v, nu.v, prec);
      arb_set_fmpq(v[i].v, V[i].raw(), prec);
      arb_mul(v[i].v, v[i].v, nv.v, prec);
    }
    arb_set_fmpq(R.v, t.R.raw(), prec);
    arb_set_fmpq(rt.v, t.r.raw(), prec);
  }

  // Centre, its derivative, radius and its derivative over the ball t.
  void at(const arb_t t, Ball (&c)[3], Ball (&dc)[3], Ball& rad, Ball& drad, long prec) const {
    if (!periodic) {
      for (size_t i = 0; i < 3; ++i) {
        horner(c[i].v, C[i], t, prec);
        horner(dc[i].v, dC[i], t, prec);
      }
      horner(rad.v, r, t, prec);
      horner(drad.v, dr, t, prec);
      return;
    }
    Ball sn, cs, pi, tmp;
    arb_sin_cos_pi(sn.v, cs.v, t, prec);
    arb_const_pi(pi.v, prec);
    for (size_t i = 0; i < 3; ++i) {
      arb_mul(c[i].v, cs.v, u[i].v, prec);
      arb_addmul(c[i].v, sn.v, v[i].v, prec);
      arb_mul(c[i].v, c[i].v, R.v, prec);
      arb_add(c[i].v, c[i].v, o[i].v, prec);
      arb_mul(dc[i].v, cs.v, v[i].v, prec);
      arb_submul(dc[i].v, sn.v, u[i].v, prec);
      arb_mul(tmp.v, R.v, pi.v, prec);
      arb_mul(dc[i].v, dc[i].v, tmp.v, prec);
    }
    arb_set(rad.v, rt.v);
    arb_zero(drad.v);
  }
};

// r > 0 on the whole interval, certified by bisection (false when not proven).
bool radius_positive(const Family& f, long prec) {
  if (f.periodic) return true;
  std::vector<std::pair<Rational, Rational>> live{{f.t0, f.t1}};
  for (int round = 0; round < 30 && !live.empty(); ++round) {
    std::vector<std::pair<Rational, Rational>> next;
    for (const auto& [a, b] : live) {
      Ball T, x, y;
      arb_set_fmpq(x.v, a.raw(), prec);
      arb_set_fmpq(y.v, b.raw(), prec);
      arb_union(T.v, x.v, y.v, prec);
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

struct Box {
  Rational s0, s1, t0, t1;
  Ball lower, upper; // certified lower bound of F on the box; F at the point (sp, tp)
  Rational sp, tp;   // the box's best evaluated point (midpoint, or on the domain's edge)
};

void interval(arb_t out, const Rational& a, const Rational& b, long prec) {
  Ball y;
  arb_set_fmpq(out, a.raw(), prec);
  arb_set_fmpq(y.v, b.raw(), prec);
  arb_union(out, out, y.v, prec);
}

// F and its gradient over the balls S, T.
void F_grad(Ball& F, Ball& Fs, Ball& Ft, const Family& A, const Family& B, const arb_t S,
            const arb_t T, long prec, Ball (*w_out)[3] = nullptr) {
  Ball c1[3], d1[3], r1, dr1, c2[3], d2[3], r2, dr2, w[3], n, ws, wt;
  A.at(S, c1, d1, r1, dr1, prec);
  B.at(T, c2, d2, r2, dr2, prec);
  for (size_t i = 0; i < 3; ++i) {
    arb_sub(w[i].v, c1[i].v, c2[i].v, prec);
    arb_addmul(n.v, w[i].v, w[i].v, prec);
    arb_addmul(ws.v, w[i].v, d1[i].v, prec);
    arb_addmul(wt.v, w[i].v, d2[i].v, prec);
  }
  arb_sqrtpos(n.v, n.v, prec);
  arb_sub(F.v, n.v, r1.v, prec);
  arb_sub(F.v, F.v, r2.v, prec);
  arb_div(Fs.v, ws.v, n.v, prec);
  arb_sub(Fs.v, Fs.v, dr1.v, prec);
  arb_div(Ft.v, wt.v, n.v, prec);
  arb_neg(Ft.v, Ft.v);
  arb_sub(Ft.v, Ft.v, dr2.v, prec);
  if (w_out)
    for (size_t i = 0; i < 3; ++i)
      arb_set((*w_out)[i].v, w[i].v);
}

void bound(Box& b, const Family& A, const Family& B, long prec) {
  Ball S, T, sm, tm, F, Fs, Ft, Fm, d1, d2, mv;
  interval(S.v, b.s0, b.s1, prec);
  interval(T.v, b.t0, b.t1, prec);
  const Rational sr = (b.s0 + b.s1) * Rational(1, 2), tr = (b.t0 + b.t1) * Rational(1, 2);
  arb_set_fmpq(sm.v, sr.raw(), prec);
  arb_set_fmpq(tm.v, tr.raw(), prec);
  F_grad(F, Fs, Ft, A, B, S.v, T.v, prec);
  Ball g1, g2;
  F_grad(Fm, g1, g2, A, B, sm.v, tm.v, prec);
  arb_set(b.upper.v, Fm.v);
  b.sp = sr;
  b.tp = tr;
  // A minimum on the edge of the parameter domain (an end ball) has a nonzero gradient: the
  // midpoint's value lags by O(width) there, so the box's points on that edge are tried too.
  std::vector<Rational> ss{sr}, ts{tr};
  if (!A.periodic && b.s0 == A.t0) ss.push_back(A.t0);
  if (!A.periodic && b.s1 == A.t1) ss.push_back(A.t1);
  if (!B.periodic && b.t0 == B.t0) ts.push_back(B.t0);
  if (!B.periodic && b.t1 == B.t1) ts.push_back(B.t1);
  for (const Rational& si : ss)
    for (const Rational& ti : ts) {
      if (si == sr && ti == tr) continue;
      Ball sb, tb, Fe;
      arb_set_fmpq(sb.v, si.raw(), prec);
      arb_set_fmpq(tb.v, ti.raw(), prec);
      F_grad(Fe, g1, g2, A, B, sb.v, tb.v, prec);
      if (arb_lt(Fe.v, b.upper.v)) {
        arb_swap(b.upper.v, Fe.v);
        b.sp = si;
        b.tp = ti;
      }
    }
  // Mean-value form F(m) - max|Fs| hs - max|Ft| ht with the half-widths hs, ht at full
  // precision: as ball radii they would be rounded to 30 bits, a relative error that becomes a
  // linear term in the width and stalls the convergence near a minimum on the domain's edge.
  const Rational hs = (b.s1 - b.s0) * Rational(1, 2), ht = (b.t1 - b.t0) * Rational(1, 2);
  arf_t gmax;
  arf_init(gmax);
  arb_set(mv.v, Fm.v);
  arb_get_abs_ubound_arf(gmax, Fs.v, prec);
  arb_set_arf(d1.v, gmax);
  arb_set_fmpq(d2.v, hs.raw(), prec);
  arb_submul(mv.v, d1.v, d2.v, prec);
  arb_get_abs_ubound_arf(gmax, Ft.v, prec);
  arb_set_arf(d1.v, gmax);
  arb_set_fmpq(d2.v, ht.raw(), prec);
  arb_submul(mv.v, d1.v, d2.v, prec);
  arf_clear(gmax);
  arf_t l1, l2;
  arf_init(l1);
  arf_init(l2);
  arb_get_lbound_arf(l1, F.v, prec);
  arb_get_lbound_arf(l2, mv.v, prec);
  if (!arf_is_finite(l1) || (arf_is_finite(l2) && arf_cmp(l2, l1) > 0)) arf_set(l1, l2);
  if (!arf_is_finite(l1)) arf_neg_inf(l1);
  arb_set_arf(b.lower.v, l1);
  arf_clear(l1);
  arf_clear(l2);
}

bool touch(const Rational& a0, const Rational& a1, const Rational& b0, const Rational& b1) {
  return !(a1 < b0 || b1 < a0);
}

} // namespace

std::optional<DistanceResult> canal_pair_distance(const core::Surface& a, const core::Surface& b,
                                                  long digits) {
  auto ok_kind = [](const core::Surface& s) {
    return std::holds_alternative<core::CanalSurface>(s) || std::holds_alternative<core::Torus>(s);
  };
  if (!ok_kind(a) || !ok_kind(b)) return std::nullopt;
  if (!std::holds_alternative<core::CanalSurface>(a) &&
      !std::holds_alternative<core::CanalSurface>(b))
    return std::nullopt;
  const long prec = bits_for(digits + 10);
  const Family A(a, prec), B(b, prec);
  if (!radius_positive(A, prec) || !radius_positive(B, prec)) return std::nullopt;

  std::vector<Box> live;
  const int n0 = 8;
  for (int i = 0; i < n0; ++i)
    for (int j = 0; j < n0; ++j) {
      Box x;
      x.s0 = A.t0 + (A.t1 - A.t0) * Rational(i, n0);
      x.s1 = A.t0 + (A.t1 - A.t0) * Rational(i + 1, n0);
      x.t0 = B.t0 + (B.t1 - B.t0) * Rational(j, n0);
      x.t1 = B.t0 + (B.t1 - B.t0) * Rational(j + 1, n0);
      live.push_back(std::move(x));
    }
  Ball d;
  bool done = false;
  const int max_rounds = static_cast<int>(3.4 * static_cast<double>(digits)) + 80;
  for (int round = 0; round < max_rounds && !done; ++round) {
    arf_t best, lowest, x;
    arf_init(best);
    arf_init(lowest);
    arf_init(x);
    arf_pos_inf(best);
    for (auto& bx : live) {
      bound(bx, A, B, prec);
      arb_get_ubound_arf(x, bx.upper.v, prec);
      if (arf_cmp(x, best) < 0) arf_set(best, x);
    }
    std::vector<Box> keep;
    arf_pos_inf(lowest);
    for (auto& bx : live) {
      arb_get_lbound_arf(x, bx.lower.v, prec);
      if (arf_cmp(x, best) <= 0) {
        if (arf_cmp(x, lowest) < 0) arf_set(lowest, x);
        keep.push_back(std::move(bx));
      }
    }
    live = std::move(keep);
    Ball lo, hi;
    arb_set_arf(lo.v, lowest);
    arb_set_arf(hi.v, best);
    const bool meet = arf_sgn(best) < 0;
    arf_clear(best);
    arf_clear(lowest);
    arf_clear(x);
    if (meet) return std::nullopt;              // some pair of balls overlaps: the solids meet
    if (live.size() > 400) return std::nullopt; // a continuum, or too flat a minimum
    if (relative_enclosure(d.v, lo.v, hi.v, digits, prec)) {
      done = true;
      break;
    }
    std::vector<Box> next;
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
          next.push_back(std::move(c));
        }
    }
    live = std::move(next);
  }
  if (!done) return std::nullopt;

  // Groups of touching boxes (across t = 0 = 2 on a torus, s likewise).
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
  std::vector<std::vector<size_t>> groups;
  std::vector<size_t> id(m, m);
  for (size_t i = 0; i < m; ++i) {
    const size_t r = find(i);
    if (id[r] == m) {
      id[r] = groups.size();
      groups.emplace_back();
    }
    groups[id[r]].push_back(i);
  }

  DistanceResult out;
  out.status = Status::Certified;
  set_distance_enclosure(out, d.v, digits);
  out.method = "sphere_family_bnb";
  out.minimizers = std::to_string(groups.size());
  out.critical_candidates = static_cast<int>(groups.size());
  out.note = "disjoint solids as unions of balls: d = min over the two parameters of |C1(s) - "
             "C2(t)| - r1(s) - r2(t), by branch and bound with mean-value bounds (Arb); a "
             "positive minimum proves the solids disjoint";
  for (const auto& g : groups) {
    const Box* bestbox = &live[g.front()];
    for (size_t i : g)
      if (arb_lt(live[i].upper.v, bestbox->upper.v)) bestbox = &live[i];
    Ball sm, tm, F, g1, g2, w[3], c1[3], d1[3], r1, dr1, c2[3], d2[3], r2, dr2;
    const Rational sr = bestbox->sp, tr = bestbox->tp;
    arb_set_fmpq(sm.v, sr.raw(), prec);
    arb_set_fmpq(tm.v, tr.raw(), prec);
    A.at(sm.v, c1, d1, r1, dr1, prec);
    B.at(tm.v, c2, d2, r2, dr2, prec);
    double wv[3], wn = 0;
    for (size_t i = 0; i < 3; ++i) {
      wv[i] = arf_get_d(arb_midref(c2[i].v), ARF_RND_NEAR) -
              arf_get_d(arb_midref(c1[i].v), ARF_RND_NEAR);
      wn += wv[i] * wv[i];
    }
    wn = std::sqrt(wn);
    std::array<std::array<double, 3>, 2> pr{};
    const double ra = arf_get_d(arb_midref(r1.v), ARF_RND_NEAR),
                 rb = arf_get_d(arb_midref(r2.v), ARF_RND_NEAR);
    for (size_t i = 0; i < 3; ++i) {
      pr[0][i] = arf_get_d(arb_midref(c1[i].v), ARF_RND_NEAR) + ra * wv[i] / wn;
      pr[1][i] = arf_get_d(arb_midref(c2[i].v), ARF_RND_NEAR) - rb * wv[i] / wn;
    }
    out.pairs.push_back(pr);
    // Tie region: the first family's centres over the group's s-hull.
    Rational s0 = live[g.front()].s0, s1 = live[g.front()].s1;
    for (size_t i : g) {
      s0 = std::min(s0, live[i].s0);
      s1 = std::max(s1, live[i].s1);
    }
    Ball S;
    interval(S.v, s0, s1, prec);
    A.at(S.v, c1, d1, r1, dr1, prec);
    std::vector<std::array<double, 2>> reg;
    for (const Ball& c : c1)
      reg.push_back(outward_interval(c.v));
    out.tie_regions.push_back(std::move(reg));
  }
  note_unproven_ties(out, groups.size());
  return out;
}

} // namespace surfcert::certify
