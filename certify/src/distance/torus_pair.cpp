#include "surfcert/certify/distance/torus_pair.hpp"

#include "surfcert/certify/distance/ball.hpp"

#include <arb.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

// A value and its derivative (forward differentiation), both balls.
struct Dual {
  Ball v, d;
};

void set_q(arb_t x, const Rational& q, long prec) {
  arb_set_fmpq(x, q.raw(), prec);
}

// A circle as Arb balls: centre o, unit normal n, orthonormal frame (u, v), radius R.
struct Circle {
  Ball o[3], n[3], u[3], v[3], R;
  Circle(const core::Torus& t, long prec) {
    size_t k = 0; // the smallest axis component: e_k is far from the axis, u != 0
    for (size_t i = 1; i < 3; ++i)
      if (core::abs(t.axis[i]) < core::abs(t.axis[k])) k = i;
    Ball len, tmp;
    for (size_t i = 0; i < 3; ++i) {
      set_q(o[i].v, t.centre[i], prec);
      set_q(n[i].v, t.axis[i], prec);
      arb_addmul(len.v, n[i].v, n[i].v, prec);
    }
    arb_sqrt(len.v, len.v, prec);
    for (auto& x : n)
      arb_div(x.v, x.v, len.v, prec);
    // u = n x e_k normalised, v = n x u
    const size_t k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    arb_zero(u[k].v);
    arb_set(u[k1].v, n[k2].v); // (n x e_k)_{k1} = n_{k2}
    arb_neg(u[k2].v, n[k1].v); // (n x e_k)_{k2} = -n_{k1}
    arb_zero(len.v);
    for (auto& x : u)
      arb_addmul(len.v, x.v, x.v, prec);
    arb_sqrt(len.v, len.v, prec);
    for (auto& x : u)
      arb_div(x.v, x.v, len.v, prec);
    for (size_t i = 0; i < 3; ++i) {
      const size_t i1 = (i + 1) % 3, i2 = (i + 2) % 3;
      arb_mul(v[i].v, n[i1].v, u[i2].v, prec);
      arb_mul(tmp.v, n[i2].v, u[i1].v, prec);
      arb_sub(v[i].v, v[i].v, tmp.v, prec);
    }
    set_q(R.v, t.R, prec);
  }
};

// f(t) = dist(K1(pi t), K2) and f'(t) over the ball t; the point K1(t) (for the pairs).
void circle_circle(Dual& f, Ball (*point)[3], const Circle& c1, const Circle& c2, const arb_t t,
                   long prec) {
  Ball s, c, pi, w[3], dw[3], tmp, h, dh, w2, dw2, rho2, drho2, rho, drho, g, dg;
  arb_sin_cos_pi(s.v, c.v, t, prec);
  arb_const_pi(pi.v, prec);
  for (size_t i = 0; i < 3; ++i) {
    // K1 = o1 + R1 (cos u + sin v), K1' = pi R1 (-sin u + cos v); w = K1 - o2
    arb_mul(w[i].v, c.v, c1.u[i].v, prec);
    arb_addmul(w[i].v, s.v, c1.v[i].v, prec);
    arb_mul(w[i].v, w[i].v, c1.R.v, prec);
    arb_add(w[i].v, w[i].v, c1.o[i].v, prec);
    if (point) arb_set((*point)[i].v, w[i].v);
    arb_sub(w[i].v, w[i].v, c2.o[i].v, prec);
    arb_mul(dw[i].v, c.v, c1.v[i].v, prec);
    arb_submul(dw[i].v, s.v, c1.u[i].v, prec);
    arb_mul(dw[i].v, dw[i].v, c1.R.v, prec);
    arb_mul(dw[i].v, dw[i].v, pi.v, prec);
    arb_addmul(h.v, w[i].v, c2.n[i].v, prec);
    arb_addmul(dh.v, dw[i].v, c2.n[i].v, prec);
    arb_addmul(w2.v, w[i].v, w[i].v, prec);
    arb_addmul(dw2.v, w[i].v, dw[i].v, prec);
  }
  arb_mul_2exp_si(dw2.v, dw2.v, 1);
  // rho^2 = |w|^2 - h^2, rho = sqrt(rho^2) (its derivative is infinite where rho may be 0:
  // then the mean-value form is useless and the interval extension alone bounds f)
  arb_sqr(tmp.v, h.v, prec);
  arb_sub(rho2.v, w2.v, tmp.v, prec);
  arb_mul(tmp.v, h.v, dh.v, prec);
  arb_mul_2exp_si(tmp.v, tmp.v, 1);
  arb_sub(drho2.v, dw2.v, tmp.v, prec);
  arb_sqrtpos(rho.v, rho2.v, prec);
  arb_div(drho.v, drho2.v, rho.v, prec);
  arb_mul_2exp_si(drho.v, drho.v, -1);
  // g = (rho - R2)^2 + h^2, f = sqrt(g)
  arb_sub(tmp.v, rho.v, c2.R.v, prec);
  arb_sqr(g.v, tmp.v, prec);
  arb_addmul(g.v, h.v, h.v, prec);
  arb_mul(dg.v, tmp.v, drho.v, prec);
  arb_addmul(dg.v, h.v, dh.v, prec);
  arb_mul_2exp_si(dg.v, dg.v, 1);
  arb_sqrtpos(f.v.v, g.v, prec);
  arb_div(f.d.v, dg.v, f.v.v, prec);
  arb_mul_2exp_si(f.d.v, f.d.v, -1);
}

struct Interval {
  arf_struct mid[1];
  mag_struct rad[1]; // the t-interval [mid - rad, mid + rad], exact dyadic
  Ball lower, upper;
  Interval() {
    arf_init(mid);
    mag_init(rad);
  }
  Interval(const Interval& o) : Interval() {
    arf_set(mid, o.mid);
    mag_set(rad, o.rad);
    arb_set(lower.v, o.lower.v);
    arb_set(upper.v, o.upper.v);
  }
  Interval& operator=(const Interval& o) {
    arf_set(mid, o.mid);
    mag_set(rad, o.rad);
    arb_set(lower.v, o.lower.v);
    arb_set(upper.v, o.upper.v);
    return *this;
  }
  ~Interval() {
    arf_clear(mid);
    mag_clear(rad);
  }
};

void bound(Interval& I, const Circle& c1, const Circle& c2, long prec) {
  Ball t, tm, dt;
  arb_set_arf(tm.v, I.mid);
  arb_set(t.v, tm.v);
  mag_set(arb_radref(t.v), I.rad);
  Dual whole, at;
  circle_circle(whole, nullptr, c1, c2, t.v, prec);
  circle_circle(at, nullptr, c1, c2, tm.v, prec);
  // mean-value form f(t_m) + f'(T) [-rad, rad]
  arb_zero(dt.v);
  mag_set(arb_radref(dt.v), I.rad);
  Ball mv;
  arb_mul(mv.v, whole.d.v, dt.v, prec);
  arb_add(mv.v, mv.v, at.v.v, prec);
  arf_t a, b;
  arf_init(a);
  arf_init(b);
  arb_get_lbound_arf(a, whole.v.v, prec);
  if (arb_is_finite(mv.v)) {
    arb_get_lbound_arf(b, mv.v, prec);
    if (arf_cmp(b, a) > 0) arf_set(a, b);
  }
  arb_set_arf(I.lower.v, a);
  arb_get_ubound_arf(b, at.v.v, prec);
  arb_set_arf(I.upper.v, b);
  arf_clear(a);
  arf_clear(b);
}

} // namespace

std::optional<DistanceResult> torus_pair_distance(const core::Torus& a, const core::Torus& b,
                                                  long digits) {
  const long prec = bits_for(digits + 10);
  const Circle c1(a, prec), c2(b, prec);
  Ball r12;
  {
    Ball r;
    set_q(r12.v, a.r, prec);
    set_q(r.v, b.r, prec);
    arb_add(r12.v, r12.v, r.v, prec);
  }
  // 32 starting intervals of t in [0, 2), shifted by 1/64 so symmetric positions are interior
  const int N = 32;
  std::vector<Interval> live;
  for (int k = 0; k < N; ++k) {
    Interval I;
    arf_set_si_2exp_si(I.mid, 2 * (2 * k + 1) + 1, -6); // (2k + 1)/32 + 1/64 = t_mid
    mag_set_ui_2exp_si(I.rad, 1, -5);                   // 1/32
    live.push_back(I);
  }
  arf_t best, lowest;
  arf_init(best);
  arf_init(lowest);
  std::optional<DistanceResult> out;
  const int max_rounds = static_cast<int>(4 * prec);
  for (int round = 0; round < max_rounds; ++round) {
    arf_pos_inf(best);
    for (auto& I : live) {
      bound(I, c1, c2, prec);
      if (arf_cmp(arb_midref(I.upper.v), best) < 0) arf_set(best, arb_midref(I.upper.v));
    }
    // drop intervals that cannot hold the minimum
    std::vector<Interval> keep;
    arf_pos_inf(lowest);
    for (const auto& I : live)
      if (arf_cmp(arb_midref(I.lower.v), best) <= 0) {
        keep.push_back(I);
        if (arf_cmp(arb_midref(I.lower.v), lowest) < 0) arf_set(lowest, arb_midref(I.lower.v));
      }
    live.swap(keep);
    if (live.size() > 96) break; // a continuum of minimizers (coaxial tori), or too flat
    // d in [lowest - r1 - r2, best - r1 - r2]
    Ball lo, hi, d;
    arb_set_arf(lo.v, lowest);
    arb_sub(lo.v, lo.v, r12.v, prec);
    arb_set_arf(hi.v, best);
    arb_sub(hi.v, hi.v, r12.v, prec);
    if (arb_is_negative(hi.v)) break; // the tubes overlap: not this route's answer
    if (relative_enclosure(d.v, lo.v, hi.v, digits, prec)) {
      if (static_cast<int>(live.size()) >= N * 3 / 4) break; // nearly the whole circle
      DistanceResult r;
      r.status = Status::Certified;
      set_distance_enclosure(r, d.v, digits);
      // one pair per group of adjacent intervals (its best interval's midpoint)
      std::sort(live.begin(), live.end(),
                [](const Interval& x, const Interval& y) { return arf_cmp(x.mid, y.mid) < 0; });
      std::vector<std::vector<const Interval*>> groups;
      for (const auto& I : live) {
        bool adjacent = false;
        if (!groups.empty()) {
          const Interval& p = *groups.back().back();
          arf_t gap, rr;
          arf_init(gap);
          arf_init(rr);
          arf_sub(gap, I.mid, p.mid, prec, ARF_RND_NEAR);
          arf_set_mag(rr, I.rad);
          arf_add(rr, rr, rr, prec, ARF_RND_UP);
          adjacent = arf_cmp(gap, rr) <= 0;
          arf_clear(gap);
          arf_clear(rr);
        }
        if (adjacent)
          groups.back().push_back(&I);
        else
          groups.push_back({&I});
      }
      if (groups.size() > 1) { // the circle wraps: first and last may be one group
        const Interval& f = *groups.front().front();
        const Interval& l = *groups.back().back();
        if (arf_cmp_si(f.mid, 0) >= 0 && arf_cmp_si(l.mid, 2) <= 0) {
          arf_t s;
          arf_init(s);
          arf_sub_si(s, l.mid, 2, prec, ARF_RND_NEAR);
          arf_sub(s, f.mid, s, prec, ARF_RND_NEAR);
          arf_t rr;
          arf_init(rr);
          arf_set_mag(rr, f.rad);
          arf_add(rr, rr, rr, prec, ARF_RND_UP);
          if (arf_cmp(s, rr) <= 0) {
            groups.front().insert(groups.front().end(), groups.back().begin(), groups.back().end());
            groups.pop_back();
          }
          arf_clear(s);
          arf_clear(rr);
        }
      }
      for (const auto& g : groups) {
        const Interval* bestI = g.front();
        for (const Interval* I : g)
          if (arf_cmp(arb_midref(I->upper.v), arb_midref(bestI->upper.v)) < 0) bestI = I;
        Ball tm, p[3];
        Dual f;
        arb_set_arf(tm.v, bestI->mid);
        circle_circle(f, &p, c1, c2, tm.v, prec);
        // nearest point of K2 to p (double): o2 + R2 (radial unit), then both surface points
        std::array<double, 3> pd{}, q{}, w{}, nd{};
        double h = 0, fd = arf_get_d(arb_midref(f.v.v), ARF_RND_NEAR);
        for (size_t i = 0; i < 3; ++i) {
          pd[i] = arf_get_d(arb_midref(p[i].v), ARF_RND_NEAR);
          nd[i] = arf_get_d(arb_midref(c2.n[i].v), ARF_RND_NEAR);
          w[i] = pd[i] - b.centre[i].to_double_approx();
          h += w[i] * nd[i];
        }
        double rl = 0;
        for (size_t i = 0; i < 3; ++i)
          rl += (w[i] - h * nd[i]) * (w[i] - h * nd[i]);
        rl = std::sqrt(rl);
        for (size_t i = 0; i < 3; ++i)
          q[i] = b.centre[i].to_double_approx() +
                 (rl > 0 ? b.R.to_double_approx() * (w[i] - h * nd[i]) / rl : 0);
        std::array<std::array<double, 3>, 2> pr{};
        const double ra = a.r.to_double_approx(), rb = b.r.to_double_approx();
        for (size_t i = 0; i < 3; ++i) {
          const double dir = fd > 0 ? (q[i] - pd[i]) / fd : 0;
          pr[0][i] = pd[i] + ra * dir;
          pr[1][i] = q[i] - rb * dir;
        }
        r.pairs.push_back(pr);
      }
      r.minimizers = std::to_string(groups.size());
      r.critical_candidates = static_cast<int>(groups.size());
      r.method = "torus_circle_pair";
      r.note = "disjoint tubes: distance of the core circles minus both tube radii, by branch "
               "and bound over one circle (Arb)";
      if (groups.size() > 1)
        r.note += "; several minimizing pairs at distances that agree to the requested "
                  "precision: listed as minimizers (their equality is not proven)";
      out = std::move(r);
      break;
    }
    // bisect every interval that still matters
    std::vector<Interval> next;
    for (const auto& I : live) {
      for (int sgn : {-1, 1}) {
        Interval c;
        mag_mul_2exp_si(c.rad, I.rad, -1);
        arf_set_mag(c.mid, c.rad);
        if (sgn < 0) arf_neg(c.mid, c.mid);
        arf_add(c.mid, c.mid, I.mid, ARF_PREC_EXACT, ARF_RND_DOWN); // exact
        next.push_back(c);
      }
    }
    live.swap(next);
  }
  arf_clear(best);
  arf_clear(lowest);
  return out;
}

} // namespace surfcert::certify
