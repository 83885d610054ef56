#include "surfcert/algebra/solution_cover.hpp"
#include "surfcert/core/budget.hpp"

#include "surfcert/algebra/real_roots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace surfcert::algebra {

using core::Poly3;
using core::Rational;

namespace {

// Cost model of fmpz_poly_factor on an eliminant of degree d with b-bit coefficients, measured
// on the development machine (FLINT 3, load ~8 on 2 cores; products of two or three random
// factors, d = 24..72, b = 500..33000, and the offset eliminants: d = 72, b = 33000 take
// 2.4 s): ms ~ k d^2 b with k between 1.3e-6 and 1.6e-5; 5e-6 is the typical value.
double factor_cost_ms(const UPolyZ& p) {
  const double d = static_cast<double>(p.degree());
  const double b = static_cast<double>(std::labs(fmpz_poly_max_bits(p.raw())));
  return 5e-6 * d * d * b;
}

std::vector<UPolyZ> distinct_factors(const UPolyZ& p) {
  // One FLINT call that cannot be interrupted: started only when the budget can cover it.
  core::check_budget_for(factor_cost_ms(p));
  std::vector<UPolyZ> out;
  for (IrreducibleFactor& f : irreducible_factors(p))
    out.push_back(std::move(f.poly));
  return out;
}

// An element of the ideal (a, b) free of `var`: the Sylvester resultant, except when neither
// polynomial involves `var` (FLINT's resultant of two constants in `var` is 1, which would
// silently drop every solution): then a itself (or b when a is constant) already qualifies.
Poly3 eliminant(const Poly3& a, const Poly3& b, int var) {
  core::check_budget(); // each resultant is a budget step (a long one also checks inside)
  if (a.degree(var) <= 0 && b.degree(var) <= 0) return a.is_constant() ? b : a;
  return resultant(a, b, var);
}

// Eliminant onto variable `keep` (0 = x, 1 = y from resultants in (x, y); `other` is the
// variable eliminated second). Tries the pairs in order; zero when all vanish identically.
Poly3 eliminate_pair(const std::vector<Poly3>& R, int other) {
  for (size_t i = 0; i < R.size(); ++i)
    for (size_t j = i + 1; j < R.size(); ++j) {
      if (R[i].is_zero() || R[j].is_zero()) continue;
      Poly3 e = eliminant(R[i], R[j], other);
      if (!e.is_zero()) return e;
    }
  return Poly3();
}

// Isolating intervals (exactly one root each) of the irreducible factors.
std::vector<RootInterval> isolate(const std::vector<UPolyZ>& factors, const Rational& width) {
  std::vector<RootInterval> out;
  for (size_t f = 0; f < factors.size(); ++f) {
    core::check_budget(); // each factor's isolation, and each root's refinement, is a step
    RootSeparation s = isolate_real_roots(factors[f]);
    for (size_t i = 0; i + 1 < s.separators.size(); ++i) {
      core::check_budget();
      RootInterval r{s.separators[i], s.separators[i + 1], f};
      refine_root(factors[f], r.lo, r.hi, width);
      out.push_back(std::move(r));
    }
  }
  return out;
}

void interval_ball(arb_t out, const RootInterval& iv, long prec) {
  arb_t a;
  arb_init(a);
  arb_set_fmpq(out, iv.lo.raw(), prec);
  arb_set_fmpq(a, iv.hi.raw(), prec);
  arb_union(out, out, a, prec);
  arb_clear(a);
}

bool excludes_zero(const Poly3& f, const std::array<const arb_struct*, 3>& b, long prec) {
  arb_t v;
  arb_init(v);
  evaluate(v, f, b, prec);
  bool ex = !arb_contains_zero(v);
  arb_clear(v);
  return ex;
}

// Keeps the boxes in which no equation (and no (x, y) resultant) is proved nonzero.
void discard(SolutionCover& c, long prec) {
  std::vector<std::array<size_t, 3>> kept;
  arb_t x, y, z;
  arb_init(x);
  arb_init(y);
  arb_init(z);
  for (const auto& b : c.boxes) {
    box_balls(c, b, x, y, z, prec);
    std::array<const arb_struct*, 3> bb{x, y, z};
    bool empty = false;
    for (const auto& r : c.xy_resultants)
      if (!empty && excludes_zero(r, bb, prec)) empty = true;
    for (const auto& f : c.system)
      if (!empty && excludes_zero(f, bb, prec)) empty = true;
    if (!empty) kept.push_back(b);
  }
  arb_clear(x);
  arb_clear(y);
  arb_clear(z);
  c.boxes = std::move(kept);
}

} // namespace

long precision_for_width(const Rational& width) {
  if (width.sign() <= 0) return 256;
  double w = width.to_double_approx();
  long bits = w > 0 ? static_cast<long>(-std::log2(w)) : 2000;
  return std::max<long>(128, 2 * bits + 96);
}

void box_balls(const SolutionCover& c, const std::array<size_t, 3>& box, arb_t x, arb_t y, arb_t z,
               long prec) {
  interval_ball(x, c.roots[0][box[0]], prec);
  interval_ball(y, c.roots[1][box[1]], prec);
  interval_ball(z, c.roots[2][box[2]], prec);
}

SolutionCover cover_real_solutions(const std::array<Poly3, 3>& F, const Rational& width0) {
  SolutionCover c;
  c.system = F;
  // (x, y) resultants: z eliminated from pairs of equations; (y, z) ones: x eliminated.
  std::vector<Poly3> rz{eliminant(F[0], F[1], 2), eliminant(F[0], F[2], 2)};
  std::vector<Poly3> rx{eliminant(F[0], F[1], 0), eliminant(F[0], F[2], 0)};
  Poly3 ex = eliminate_pair(rz, 1), ey = eliminate_pair(rz, 0), ez = eliminate_pair(rx, 1);
  if (ex.is_zero() || ey.is_zero() || ez.is_zero()) {
    rz.push_back(eliminant(F[1], F[2], 2));
    rx.push_back(eliminant(F[1], F[2], 0));
    if (ex.is_zero()) ex = eliminate_pair(rz, 1);
    if (ey.is_zero()) ey = eliminate_pair(rz, 0);
    if (ez.is_zero()) ez = eliminate_pair(rx, 1);
  }
  c.bivariate_degree = {rz[0].total_degree(), rz[1].total_degree()};
  if (ex.is_zero() || ey.is_zero() || ez.is_zero()) {
    c.note = "the elimination vanishes identically (the system has a curve of solutions)";
    return c;
  }
  for (const auto& r : rz)
    if (!r.is_zero()) c.xy_resultants.push_back(r);
  const std::array<Poly3*, 3> e{&ex, &ey, &ez};
  for (size_t k = 0; k < 3; ++k) {
    UPolyZ u = to_univariate(*e[k], static_cast<int>(k));
    c.eliminant_degree[k] = u.degree();
    c.factors[k] = distinct_factors(u);
    for (const auto& f : c.factors[k])
      c.squarefree_degree[k] += f.degree();
    c.roots[k] = isolate(c.factors[k], width0);
  }
  // (x, y) pairs first (discarded with the (x, y) resultants, which do not involve z), then
  // each surviving pair with every z interval.
  const long prec = precision_for_width(width0);
  arb_t x, y, z;
  arb_init(x);
  arb_init(y);
  arb_init(z);
  arb_zero(z);
  for (size_t i = 0; i < c.roots[0].size(); ++i)
    for (size_t j = 0; j < c.roots[1].size(); ++j) {
      interval_ball(x, c.roots[0][i], prec);
      interval_ball(y, c.roots[1][j], prec);
      bool empty = false;
      for (const auto& r : c.xy_resultants)
        if (!empty && excludes_zero(r, {x, y, z}, prec)) empty = true;
      if (empty) continue;
      for (size_t k = 0; k < c.roots[2].size(); ++k)
        c.boxes.push_back({i, j, k});
    }
  arb_clear(x);
  arb_clear(y);
  arb_clear(z);
  discard(c, prec);
  c.ok = true;
  return c;
}

SolutionCover cover_real_solutions_2d(const Poly3& F, const Poly3& G, const Rational& width0) {
  SolutionCover c;
  if (F.degree(2) > 0 || G.degree(2) > 0)
    throw std::invalid_argument("cover_real_solutions_2d: the equations involve z");
  c.dims = 2;
  c.system = {F, G, Poly3::variable(2)};
  const Poly3 ex = eliminant(F, G, 1), ey = eliminant(F, G, 0);
  c.bivariate_degree = {F.total_degree(), G.total_degree()};
  if (ex.is_zero() || ey.is_zero()) {
    c.note = "the two equations share a curve of solutions";
    return c;
  }
  const std::array<const Poly3*, 2> e{&ex, &ey};
  for (size_t k = 0; k < 2; ++k) {
    UPolyZ u = to_univariate(*e[k], static_cast<int>(k));
    c.eliminant_degree[k] = u.degree();
    c.factors[k] = distinct_factors(u);
    for (const auto& f : c.factors[k])
      c.squarefree_degree[k] += f.degree();
    c.roots[k] = isolate(c.factors[k], width0);
  }
  UPolyZ z;
  fmpz_poly_set_coeff_si(z.raw_mut(), 1, 1);
  c.factors[2] = {z};
  c.roots[2] = {RootInterval{Rational(0), Rational(0), 0}};
  for (size_t i = 0; i < c.roots[0].size(); ++i)
    for (size_t j = 0; j < c.roots[1].size(); ++j)
      c.boxes.push_back({i, j, 0});
  discard(c, precision_for_width(width0));
  c.ok = true;
  return c;
}

void refine_cover(SolutionCover& c, const Rational& width) {
  core::check_budget(); // each refinement round of a caller's loop is a budget step
  std::array<std::vector<bool>, 3> used;
  for (size_t k = 0; k < 3; ++k)
    used[k].assign(c.roots[k].size(), false);
  for (const auto& b : c.boxes)
    for (size_t k = 0; k < 3; ++k)
      used[k][b[k]] = true;
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < c.roots[k].size(); ++i)
      if (used[k][i]) {
        core::check_budget();
        RootInterval& r = c.roots[k][i];
        refine_root(c.factors[k][r.factor], r.lo, r.hi, width);
      }
  discard(c, precision_for_width(width));
}

} // namespace surfcert::algebra
