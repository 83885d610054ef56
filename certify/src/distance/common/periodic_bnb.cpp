#include "surfcert/certify/distance/periodic_bnb.hpp"
#include "surfcert/core/budget.hpp"

#include <algorithm>

namespace surfcert::certify {

namespace {

struct Interval {
  arf_struct mid[1];
  mag_struct rad[1]; // [mid - rad, mid + rad], exact dyadic
  arf_struct lower[1], upper[1];
  Interval() {
    arf_init(mid);
    mag_init(rad);
    arf_init(lower);
    arf_init(upper);
  }
  Interval(const Interval& o) : Interval() { *this = o; }
  Interval& operator=(const Interval& o) {
    arf_set(mid, o.mid);
    mag_set(rad, o.rad);
    arf_set(lower, o.lower);
    arf_set(upper, o.upper);
    return *this;
  }
  ~Interval() {
    arf_clear(mid);
    mag_clear(rad);
    arf_clear(lower);
    arf_clear(upper);
  }
};

// |x.mid - y.mid| <= 2 rad (adjacent or overlapping), with an optional period shift of y.
bool adjacent(const Interval& x, const Interval& y, long shift, long prec) {
  arf_t gap, rr;
  arf_init(gap);
  arf_init(rr);
  arf_sub(gap, y.mid, x.mid, prec, ARF_RND_NEAR);
  if (shift != 0) arf_add_si(gap, gap, shift, prec, ARF_RND_NEAR);
  arf_abs(gap, gap);
  arf_set_mag(rr, x.rad);
  arf_mul_2exp_si(rr, rr, 1);
  const bool a = arf_cmp(gap, rr) <= 0;
  arf_clear(gap);
  arf_clear(rr);
  return a;
}

} // namespace

void mean_value_lower(arf_t lower, const arb_t f_T, const arb_t df_T, const arb_t f_tm,
                      const arb_t T, long prec) {
  Ball dt, mv;
  mag_set(arb_radref(dt.v), arb_radref(T));
  arb_mul(mv.v, df_T, dt.v, prec);
  arb_add(mv.v, mv.v, f_tm, prec);
  arb_get_lbound_arf(lower, f_T, prec);
  if (arb_is_finite(mv.v)) {
    arf_t m;
    arf_init(m);
    arb_get_lbound_arf(m, mv.v, prec);
    if (arf_cmp(m, lower) > 0) arf_set(lower, m);
    arf_clear(m);
  }
}

bool periodic_minimize(const PeriodicBound& bound, const arb_t shift, long digits, long prec,
                       PeriodicMinimum& out) {
  const int N = 32;
  std::vector<Interval> live(N);
  for (int k = 0; k < N; ++k) {
    arf_set_si_2exp_si(live[static_cast<size_t>(k)].mid, 2 * (2 * k + 1) + 1, -6);
    mag_set_ui_2exp_si(live[static_cast<size_t>(k)].rad, 1, -5);
  }
  // RAII: the loop below may leave by a budget exception (core/budget.hpp).
  algebra::Arf best_owner, lowest_owner;
  arf_ptr best = best_owner.v, lowest = lowest_owner.v;
  bool ok = false;
  const int max_rounds = static_cast<int>(2 * prec);
  for (int round = 0; round < max_rounds && !ok; ++round) {
    core::check_budget();
    arf_pos_inf(best);
    for (auto& I : live) {
      Ball tm, T;
      arb_set_arf(tm.v, I.mid);
      arb_set(T.v, tm.v);
      mag_set(arb_radref(T.v), I.rad);
      bound(tm.v, T.v, I.lower, I.upper);
      if (arf_cmp(I.upper, best) < 0) arf_set(best, I.upper);
    }
    std::vector<Interval> keep;
    arf_pos_inf(lowest);
    for (const auto& I : live)
      if (arf_cmp(I.lower, best) <= 0) {
        keep.push_back(I);
        if (arf_cmp(I.lower, lowest) < 0) arf_set(lowest, I.lower);
      }
    live.swap(keep);
    if (live.size() > 96) break; // a continuum of minimizers, or too flat a minimum
    Ball lo, hi;
    arb_set_arf(lo.v, lowest);
    arb_sub(lo.v, lo.v, shift, prec);
    arb_set_arf(hi.v, best);
    arb_sub(hi.v, hi.v, shift, prec);
    if (arb_is_negative(hi.v)) break; // certainly below the shift: not a positive distance
    if (relative_enclosure(out.enclosure.v, lo.v, hi.v, digits, prec)) {
      if (static_cast<int>(live.size()) >= N * 3 / 4) break; // nearly the whole circle
      ok = true;
      break;
    }
    std::vector<Interval> next;
    for (const auto& I : live)
      for (int sgn : {-1, 1}) {
        Interval c;
        mag_mul_2exp_si(c.rad, I.rad, -1);
        arf_set_mag(c.mid, c.rad);
        if (sgn < 0) arf_neg(c.mid, c.mid);
        arf_add(c.mid, c.mid, I.mid, ARF_PREC_EXACT, ARF_RND_DOWN); // exact
        next.push_back(c);
      }
    live.swap(next);
  }
  if (!ok) return false;
  // Groups of adjacent survivors (sorted by t; the first and the last group may join across
  // t = 0 = 2); one representative each: its interval with the smallest upper bound.
  std::sort(live.begin(), live.end(),
            [](const Interval& x, const Interval& y) { return arf_cmp(x.mid, y.mid) < 0; });
  std::vector<std::vector<const Interval*>> groups;
  for (const auto& I : live)
    if (!groups.empty() && adjacent(*groups.back().back(), I, 0, prec))
      groups.back().push_back(&I);
    else
      groups.push_back({&I});
  if (groups.size() > 1 && adjacent(*groups.back().back(), *groups.front().front(), 2, prec)) {
    groups.front().insert(groups.front().end(), groups.back().begin(), groups.back().end());
    groups.pop_back();
  }
  for (const auto& g : groups) {
    const Interval* b = g.front();
    for (const Interval* I : g)
      if (arf_cmp(I->upper, b->upper) < 0) b = I;
    Ball t;
    arb_set_arf(t.v, b->mid);
    out.minimizers.push_back(std::move(t));
    Ball hull;
    for (size_t k = 0; k < g.size(); ++k) {
      Ball T, two;
      arb_set_arf(T.v, g[k]->mid);
      mag_set(arb_radref(T.v), g[k]->rad);
      arf_t gap;
      arf_init(gap);
      arf_sub(gap, g[k]->mid, g.front()->mid, prec, ARF_RND_DOWN);
      if (arf_cmp_si(gap, 1) > 0) { // joined across t = 0: the same points at t - 2
        arb_set_si(two.v, 2);
        arb_sub(T.v, T.v, two.v, prec);
      }
      arf_clear(gap);
      if (k == 0)
        arb_swap(hull.v, T.v);
      else
        arb_union(hull.v, hull.v, T.v, prec);
    }
    out.group_hulls.push_back(std::move(hull));
  }
  return true;
}

} // namespace surfcert::certify
