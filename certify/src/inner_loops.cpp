// inner_component_bound (inner_loops.hpp): for a direction d, a cover of the box by cells on
// each of which f, g or h_d = det[d; grad f; grad g] provably misses 0, or which hold exactly
// one solution of f = g = h_d = 0 (Krawczyk); with the signs of d . tau at the box's crossings.
#include "surfcert/certify/inner_loops.hpp"

#include "surfcert/certify/enclosure.hpp"

#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>
#include <numeric>
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

// Comparisons, so that an interval with a NaN bound (overflow) never misses 0.
bool misses_zero(const Interval& x) {
  return x.inf() > 0 || x.sup() < 0;
}

using Vec3 = std::array<Interval, 3>;

// The Jacobian of (f, g, h) over the cell c + t, h = det[d; p; q] with p = P + A t, q = Q + B t
// the half gradients: rows 2 p, 2 q and dh/dx_k = det[d; A e_k; q] + det[d; p; B e_k].
std::array<Vec3, 3> jacobian(const IM4& a, const IM4& b, const std::array<int, 3>& d,
                             const OverCell& fa, const OverCell& fb, const Vec3& t) {
  Vec3 p, q;
  for (size_t i = 0; i < 3; ++i) {
    p[i] = fa.half_grad_at_mid[i] + a[i][0] * t[0] + a[i][1] * t[1] + a[i][2] * t[2];
    q[i] = fb.half_grad_at_mid[i] + b[i][0] * t[0] + b[i][1] * t[1] + b[i][2] * t[2];
  }
  std::array<Vec3, 3> j;
  for (size_t k = 0; k < 3; ++k) {
    Vec3 ak, bk;
    for (size_t i = 0; i < 3; ++i)
      ak[i] = a[i][k], bk[i] = b[i][k];
    j[0][k] = Interval(2) * p[k];
    j[1][k] = Interval(2) * q[k];
    j[2][k] = triple(d, ak, q) + triple(d, p, bk);
  }
  return j;
}

enum class Newton { Unique, Empty, Unknown };

// The Krawczyk test on the cell c + t: K = c - Y F(c) + (I - Y J(X)) t, Y a float inverse of
// J's midpoint. K inside the cell's interior: exactly one solution there, where J is
// nonsingular; K disjoint from the cell: none.
Newton krawczyk(const IM4& a, const IM4& b, const std::array<int, 3>& d, const Cell& cell,
                const std::array<double, 3>& c, const Vec3& t) {
  const Vec3 zero{Interval(0), Interval(0), Interval(0)};
  const OverCell fa = over(a, c, zero), fb = over(b, c, zero);
  const Vec3 fc{fa.value, fb.value, triple(d, fa.half_grad_at_mid, fb.half_grad_at_mid)};
  const OverCell ta = over(a, c, t), tb = over(b, c, t);
  const std::array<Vec3, 3> j = jacobian(a, b, d, ta, tb, t);
  double m[3][3];
  for (size_t i = 0; i < 3; ++i)
    for (size_t k = 0; k < 3; ++k)
      m[i][k] = 0.5 * j[i][k].inf() + 0.5 * j[i][k].sup();
  // Y = adj(m) / det(m), in floats (any Y is sound; a poor one only fails the test).
  double y[3][3];
  for (size_t i = 0; i < 3; ++i)
    for (size_t k = 0; k < 3; ++k) {
      const size_t r0 = (k + 1) % 3, r1 = (k + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      y[i][k] = m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    }
  const double det = m[0][0] * y[0][0] + m[0][1] * y[1][0] + m[0][2] * y[2][0];
  if (!(std::fabs(det) > 0) || !std::isfinite(det)) return Newton::Unknown;
  for (auto& row : y)
    for (double& v : row)
      v /= det;
  bool inside = true;
  for (size_t i = 0; i < 3; ++i) {
    Interval k = Interval(c[i]);
    for (size_t l = 0; l < 3; ++l)
      k -= Interval(y[i][l]) * fc[l];
    for (size_t l = 0; l < 3; ++l) {
      Interval mil = Interval(i == l ? 1 : 0);
      for (size_t r = 0; r < 3; ++r)
        mil -= Interval(y[i][r]) * j[r][l];
      k += mil * t[l];
    }
    if (!std::isfinite(k.inf()) || !std::isfinite(k.sup())) return Newton::Unknown;
    if (k.sup() < cell.lo[i] || k.inf() > cell.hi[i]) return Newton::Empty;
    inside = inside && cell.lo[i] < k.inf() && k.sup() < cell.hi[i];
  }
  return inside ? Newton::Unique : Newton::Unknown;
}

enum class Cover { Done, OutOfBudget, Blocked };

// One direction's cover in progress: the cells left to examine and the solutions verified so
// far. Kept between rounds (advance resumes it), so that a direction given more cells later
// never examines a cell twice.
struct CoverState {
  std::vector<Cell> todo;
  double size = 0; // the box's largest side (the floor below which a cell is not split)
  int solutions = 0;
  long cells = 0;                   // cells examined so far
  Cover state = Cover::OutOfBudget; // OutOfBudget: not finished yet
};

CoverState start_cover(const Cell& box) {
  CoverState s;
  for (size_t k = 0; k < 3; ++k)
    s.size = std::max(s.size, box.hi[k] - box.lo[k]);
  s.todo.push_back(box);
  return s;
}

// Advances the cover of the box for direction d by at most `budget` cells (`cells` counts
// them); when Done, `s.solutions` is the number of solutions of f = g = h_d = 0 in the box.
// Blocked when a cell too small to split further (or 1e-9 of the box) is neither cleared nor
// verified: a degenerate solution (a singular point, a tangency) most likely, which more budget
// would not resolve. Cells are split off centre (59/128 of the widest side) so that a solution
// with short dyadic coordinates does not fall on a cut, where no cell holds it in its interior.
Cover advance(const IM4& a, const IM4& b, const std::array<int, 3>& d, CoverState& s, long budget,
              long& cells) {
  const double size = s.size;
  std::vector<Cell>& todo = s.todo;
  int& solutions = s.solutions;
  while (!todo.empty()) {
    if (budget-- <= 0) return Cover::OutOfBudget;
    ++cells;
    const Cell c = todo.back();
    todo.pop_back();
    std::array<double, 3> mid;
    Vec3 t;
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
    const Newton n = krawczyk(a, b, d, c, mid, t);
    if (n == Newton::Empty) continue;
    if (n == Newton::Unique) {
      ++solutions;
      continue;
    }
    const double w = c.hi[widest] - c.lo[widest];
    const double m = c.lo[widest] + w * (59.0 / 128.0);
    if (w <= 1e-9 * size || !(c.lo[widest] < m && m < c.hi[widest])) return Cover::Blocked;
    Cell left = c, right = c;
    left.hi[widest] = m;
    right.lo[widest] = m;
    todo.push_back(left);
    todo.push_back(right);
  }
  return Cover::Done;
}

// sigma_e for a certified crossing: the sign of d . tau with tau oriented into the box, from an
// interval enclosure of the crossing (its Arb enclosure, midpoint rounded to doubles, widened
// by that rounding); 0 when not decided.
int inward_sign(const IM4& a, const IM4& b, const std::array<int, 3>& d, const BoxCrossing& e,
                const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  Vec3 x;
  for (size_t k = 0; k < 3; ++k) {
    const double r = e.radius + std::ldexp(std::fabs(e.approx[k]), -50) + 1e-300;
    if (!std::isfinite(r) || !std::isfinite(e.approx[k])) return 0; // no enclosure
    x[k] = Interval(e.approx[k]) + Interval(-r, r);
  }
  const size_t ax = static_cast<size_t>(e.axis);
  x[ax] = Interval(e.at_max ? hi[ax] : lo[ax]); // on the face exactly
  Vec3 p, q;
  for (size_t i = 0; i < 3; ++i) {
    p[i] = a[i][0] * x[0] + a[i][1] * x[1] + a[i][2] * x[2] + a[i][3];
    q[i] = b[i][0] * x[0] + b[i][1] * x[1] + b[i][2] * x[2] + b[i][3];
  }
  const Vec3 tau{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
  const Interval along =
      Interval(d[0]) * tau[0] + Interval(d[1]) * tau[1] + Interval(d[2]) * tau[2];
  const Interval across = e.at_max ? -tau[ax] : tau[ax];
  for (const Interval& v : {along, across})
    if (!std::isfinite(v.inf()) || !std::isfinite(v.sup()) || !misses_zero(v)) return 0;
  return (along.inf() > 0) == (across.inf() > 0) ? 1 : -1;
}

} // namespace

InnerComponentBound inner_component_bound(const core::Mat4& a, const core::Mat4& b,
                                          const std::array<double, 3>& lo,
                                          const std::array<double, 3>& hi, const BoxExits* exits,
                                          int wanted, long budget) {
  InnerComponentBound out;
  for (size_t k = 0; k < 3; ++k)
    if (!(lo[k] <= hi[k]) || !std::isfinite(lo[k]) || !std::isfinite(hi[k])) {
      out.reason = "the box is empty or not finite";
      return out;
    }
  // The axes first, then the face and the body diagonals, then the primitive directions with
  // an entry +-2 (up to sign).
  static const std::vector<std::array<int, 3>> directions = [] {
    std::vector<std::array<int, 3>> v{{1, 0, 0},  {0, 1, 0},  {0, 0, 1}, {1, 1, 0},  {1, -1, 0},
                                      {1, 0, 1},  {1, 0, -1}, {0, 1, 1}, {0, 1, -1}, {1, 1, 1},
                                      {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    for (int x = -2; x <= 2; ++x)
      for (int y = -2; y <= 2; ++y)
        for (int z = -2; z <= 2; ++z) {
          if (std::abs(x) != 2 && std::abs(y) != 2 && std::abs(z) != 2) continue;
          const std::array<int, 3> d{x, y, z};
          const std::array<int, 3> n{-x, -y, -z};
          if (std::gcd(std::gcd(std::abs(x), std::abs(y)), std::abs(z)) != 1) continue;
          if (std::find(v.begin(), v.end(), n) != v.end()) continue;
          v.push_back(d);
        }
    return v;
  }();
  CGAL::Protect_FPU_rounding<true> guard;
  const IM4 ia = enclose_matrix(a), ib = enclose_matrix(b);
  const bool crossings = exits && exits->certified;
  // Rounds over the directions with growing cell budgets, each direction's cover resumed where
  // it stopped: the axes alone with 1/16 of `budget` each, then every direction up to 1/64 (a
  // cheap scan for an easy direction further down the list), then the axes and diagonals up to
  // 1/4, then every direction with all of it. An easy direction is found before a hard one
  // spends the whole budget, and the many directions are scanned only when the axes fail
  // (measured on cone pairs posed in doubles: the first axis needed 400 to 1100 cells where a
  // first round of 1/64 over all 49 directions cost 15,000).
  std::vector<CoverState> states;
  states.reserve(directions.size());
  struct Round {
    size_t directions;
    long share;
  };
  for (const Round round :
       {Round{3, 16}, Round{directions.size(), 64}, Round{13, 4}, Round{directions.size(), 1}}) {
    const long cap = budget / round.share;
    for (size_t i = 0; i < round.directions; ++i) {
      if (i == states.size()) states.push_back(start_cover(Cell{lo, hi}));
      CoverState& st = states[i];
      if (st.state != Cover::OutOfBudget) continue;
      const long used = st.cells;
      if (used >= cap) continue;
      long spent = 0;
      st.state = advance(ia, ib, directions[i], st, cap - used, spent);
      st.cells += spent;
      out.cells += spent;
      if (st.state != Cover::Done) continue;
      const auto& d = directions[i];
      const int solutions = st.solutions;
      st.todo = {};
      int bound = -1;
      if (solutions == 0) {
        bound = 0;
      } else if (crossings) {
        int plus = 0, minus = 0;
        bool decided = true;
        for (const auto& e : exits->points) {
          const int s = inward_sign(ia, ib, d, e, lo, hi);
          decided = decided && s != 0;
          (s > 0 ? plus : minus) += 1;
        }
        if (decided && (plus + minus) % 2 == 0) {
          const int turning = std::abs(plus - minus) / 2;
          if (solutions >= turning) bound = (solutions - turning) / 2;
        }
      }
      if (bound < 0 || (out.bound && *out.bound <= bound)) continue;
      out.bound = bound;
      out.direction = d;
      out.critical_points = solutions;
      if (bound <= wanted) return out;
    }
  }
  if (!out.bound)
    out.reason = "no direction's critical points in the box were all verified (a singular "
                 "point, a tangency or a budget of cells)";
  return out;
}

} // namespace surfcert::certify
