// no_compact_component_in_box (inner_loops.hpp): a cover of the box by cells on each of which
// f, g or h_d = det[d; grad f; grad g] provably misses 0, for one direction d.
#include "surfcert/certify/inner_loops.hpp"

#include "surfcert/certify/enclosure.hpp"

#include <CGAL/Interval_nt.h>

#include <cmath>
#include <vector>

namespace surfcert::certify {

namespace {

using IM4 = std::array<std::array<Interval, 4>, 4>;

IM4 enclose_matrix(const core::Mat4& m) {
  IM4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      r[i][j] = enclose(m[i][j]);
  return r;
}

struct Cell {
  std::array<double, 3> lo, hi;
};

// Enclosures of q over the cell c + t (t_i in [lo_i - c_i, hi_i - c_i]): the value by its exact
// Taylor expansion at c (centred form: q(c) + 2 v.t + t^T A t, v = A (c, 1)), and half the
// gradient at c, v (its first three entries).
struct OverCell {
  Interval value;
  std::array<Interval, 3> half_grad_at_mid;
};

OverCell over(const IM4& m, const std::array<double, 3>& c, const std::array<Interval, 3>& t) {
  std::array<Interval, 4> v;
  for (size_t i = 0; i < 4; ++i)
    v[i] = m[i][0] * Interval(c[0]) + m[i][1] * Interval(c[1]) + m[i][2] * Interval(c[2]) + m[i][3];
  OverCell r;
  Interval at_c = v[3];
  for (size_t i = 0; i < 3; ++i)
    at_c += Interval(c[i]) * v[i];
  Interval quad(0);
  for (size_t i = 0; i < 3; ++i) {
    quad += m[i][i] * CGAL::square(t[i]);
    for (size_t j = i + 1; j < 3; ++j)
      quad += Interval(2) * m[i][j] * t[i] * t[j];
  }
  r.value = at_c + Interval(2) * (v[0] * t[0] + v[1] * t[1] + v[2] * t[2]) + quad;
  for (size_t i = 0; i < 3; ++i)
    r.half_grad_at_mid[i] = v[i];
  return r;
}

Interval triple(const std::array<int, 3>& d, const std::array<Interval, 3>& p,
                const std::array<Interval, 3>& q) {
  return Interval(d[0]) * (p[1] * q[2] - p[2] * q[1]) +
         Interval(d[1]) * (p[2] * q[0] - p[0] * q[2]) +
         Interval(d[2]) * (p[0] * q[1] - p[1] * q[0]);
}

// h_d / 4 = det[d; p; q] over the cell, with p = P + A t and q = Q + B t the half gradients
// (P, Q at the midpoint, A, B the quadrics' 3x3 blocks): expanded exactly in t,
//   det[d; P; Q] + sum_k t_k (det[d; P; B e_k] + det[d; A e_k; Q]) + det[d; A t; B t],
// so that only the last, quadratic term is enclosed naively (the product of the two interval
// gradients would lose their dependence on the same t: width O(w) instead of O(w^2)).
Interval critical_form(const IM4& a, const IM4& b, const std::array<int, 3>& d, const OverCell& fa,
                       const OverCell& fb, const std::array<Interval, 3>& t) {
  const std::array<Interval, 3>&pc = fa.half_grad_at_mid, &qc = fb.half_grad_at_mid;
  std::array<Interval, 3> at, bt;
  for (size_t i = 0; i < 3; ++i) {
    at[i] = a[i][0] * t[0] + a[i][1] * t[1] + a[i][2] * t[2];
    bt[i] = b[i][0] * t[0] + b[i][1] * t[1] + b[i][2] * t[2];
  }
  Interval h = triple(d, pc, qc) + triple(d, at, bt);
  for (size_t k = 0; k < 3; ++k) {
    std::array<Interval, 3> ak, bk;
    for (size_t i = 0; i < 3; ++i)
      ak[i] = a[i][k], bk[i] = b[i][k];
    h += t[k] * (triple(d, pc, bk) + triple(d, ak, qc));
  }
  return h;
}

bool misses_zero(const Interval& x) {
  return !x.do_overlap(Interval(0));
}

enum class Cover { Proven, OutOfBudget, Blocked };

// Whether the cells cover the box for direction d within `budget` cells (`cells` counts them):
// Blocked when a cell too small to split further (or 1e-9 of the box) is not cleared (most
// likely a critical point in the box: more budget would not help).
Cover cover(const IM4& a, const IM4& b, const std::array<int, 3>& d, const Cell& box, long budget,
            long& cells) {
  double size = 0;
  for (size_t k = 0; k < 3; ++k)
    size = std::max(size, box.hi[k] - box.lo[k]);
  std::vector<Cell> todo{box};
  while (!todo.empty()) {
    if (budget-- <= 0) return Cover::OutOfBudget;
    ++cells;
    const Cell c = todo.back();
    todo.pop_back();
    std::array<double, 3> mid;
    std::array<Interval, 3> t;
    size_t widest = 0;
    for (size_t k = 0; k < 3; ++k) {
      mid[k] = 0.5 * c.lo[k] + 0.5 * c.hi[k];
      t[k] = Interval(c.lo[k], c.hi[k]) - Interval(mid[k]);
      if (!std::isfinite(t[k].inf()) || !std::isfinite(t[k].sup())) return Cover::Blocked;
      if (c.hi[k] - c.lo[k] > c.hi[widest] - c.lo[widest]) widest = k;
    }
    const OverCell fa = over(a, mid, t);
    if (misses_zero(fa.value)) continue;
    const OverCell fb = over(b, mid, t);
    if (misses_zero(fb.value)) continue;
    if (misses_zero(critical_form(a, b, d, fa, fb, t))) continue;
    const double m = mid[widest];
    if (c.hi[widest] - c.lo[widest] <= 1e-9 * size || !(c.lo[widest] < m && m < c.hi[widest]))
      return Cover::Blocked;
    Cell left = c, right = c;
    left.hi[widest] = m;
    right.lo[widest] = m;
    todo.push_back(left);
    todo.push_back(right);
  }
  return Cover::Proven;
}

} // namespace

InnerLoopProof no_compact_component_in_box(const core::Mat4& a, const core::Mat4& b,
                                           const std::array<double, 3>& lo,
                                           const std::array<double, 3>& hi, long budget) {
  InnerLoopProof out;
  for (size_t k = 0; k < 3; ++k)
    if (!(lo[k] <= hi[k]) || !std::isfinite(lo[k]) || !std::isfinite(hi[k])) {
      out.reason = "the box is empty or not finite";
      return out;
    }
  // The axes first (cheap to read), then the face and the body diagonals.
  static const std::array<std::array<int, 3>, 13> directions{{{1, 0, 0},
                                                              {0, 1, 0},
                                                              {0, 0, 1},
                                                              {1, 1, 0},
                                                              {1, -1, 0},
                                                              {1, 0, 1},
                                                              {1, 0, -1},
                                                              {0, 1, 1},
                                                              {0, 1, -1},
                                                              {1, 1, 1},
                                                              {1, 1, -1},
                                                              {1, -1, 1},
                                                              {-1, 1, 1}}};
  CGAL::Protect_FPU_rounding<true> guard;
  const IM4 ia = enclose_matrix(a), ib = enclose_matrix(b);
  // Iterative deepening over the directions (budgets 1/64, 1/8, 1 of `budget`): a direction
  // that is easy is found before a hard one spends the whole budget.
  std::array<bool, 13> blocked{};
  for (long share : {64L, 8L, 1L})
    for (size_t i = 0; i < directions.size(); ++i) {
      if (blocked[i]) continue;
      const Cover c = cover(ia, ib, directions[i], Cell{lo, hi}, budget / share, out.cells);
      if (c == Cover::Proven) {
        out.proven = true;
        out.direction = directions[i];
        return out;
      }
      blocked[i] = c == Cover::Blocked;
    }
  out.reason = "for each of 13 directions a critical point of the curve may lie in the box";
  return out;
}

} // namespace surfcert::certify
