#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/core/budget.hpp"

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_poly.h>

#include <stdexcept>
#include <vector>

namespace surfcert::algebra {

using core::Poly3;

namespace {

const fmpz_mpoly_ctx_struct* zctx() {
  return Poly3::ctx()->zctx;
}

// The primitive integer part FLINT keeps inside a Poly3 (a = content * zpart).
const fmpz_mpoly_struct* zpart(const Poly3& a) {
  return a.raw()->zpoly;
}

// content * z as a canonical Poly3 (takes z).
Poly3 from_integer_part(fmpz_mpoly_t z, const fmpq_t content) {
  Poly3 r;
  fmpz_mpoly_swap(r.raw_mut()->zpoly, z, zctx());
  fmpq_set(r.raw_mut()->content, content);
  fmpq_mpoly_reduce(r.raw_mut(), Poly3::ctx());
  return r;
}

Poly3 from_integer_part(fmpz_mpoly_t z) {
  fmpq_t one;
  fmpq_init(one);
  fmpq_one(one);
  Poly3 r = from_integer_part(z, one);
  fmpq_clear(one);
  return r;
}

long zdegree(const fmpz_mpoly_struct* a, int var) {
  return fmpz_mpoly_degree_si(a, var, zctx());
}

// Resultant in `var` of two integer polynomials that involve only `var` and `keep`, by
// evaluation at integer points of `keep` (univariate modular resultants, FLINT) and exact
// interpolation. A point where a leading coefficient in `var` vanishes is skipped (the
// specialisation would not commute with the resultant there). The degree bound is the Bezout
// bound tdeg(a) tdeg(b); one extra point checks the interpolant. False when it does not apply.
// The points are the steps of a long resultant (a degree-72 eliminant: ~10 ms each): past the
// thread's time budget it stops between two of them and sets `out_of_time` (no throw here, so
// the FLINT objects are cleared on the way out).
bool resultant_by_interpolation(fmpz_mpoly_t out, const fmpz_mpoly_struct* a,
                                const fmpz_mpoly_struct* b, int var, int keep, bool& out_of_time) {
  const long bound = fmpz_mpoly_total_degree_si(a, zctx()) * fmpz_mpoly_total_degree_si(b, zctx());
  const long da = zdegree(a, var), db = zdegree(b, var);
  if (bound <= 0 || da <= 0 || db <= 0) return false;
  std::vector<fmpz> xs, ys;
  fmpz_t k, v;
  fmpz_init(k);
  fmpz_init(v);
  fmpz_mpoly_t sa, sb;
  fmpz_mpoly_init(sa, zctx());
  fmpz_mpoly_init(sb, zctx());
  fmpz_poly_t pa, pb;
  fmpz_poly_init(pa);
  fmpz_poly_init(pb);
  bool ok = true;
  for (long x = 0; static_cast<long>(xs.size()) < bound + 2 && x < 4 * bound + 100; ++x) {
    if (core::budget_exhausted()) {
      out_of_time = true;
      ok = false;
      break;
    }
    const long pt = (x % 2 == 0) ? x / 2 : -(x + 1) / 2; // 0, -1, 1, -2, 2, ...
    fmpz_set_si(k, pt);
    if (!fmpz_mpoly_evaluate_one_fmpz(sa, a, keep, k, zctx()) ||
        !fmpz_mpoly_evaluate_one_fmpz(sb, b, keep, k, zctx()) ||
        !fmpz_mpoly_get_fmpz_poly(pa, sa, var, zctx()) ||
        !fmpz_mpoly_get_fmpz_poly(pb, sb, var, zctx())) {
      ok = false;
      break;
    }
    if (fmpz_poly_degree(pa) != da || fmpz_poly_degree(pb) != db) continue;
    fmpz_poly_resultant(v, pa, pb);
    fmpz xv, yv;
    fmpz_init_set(&xv, k);
    fmpz_init_set(&yv, v);
    xs.push_back(xv);
    ys.push_back(yv);
  }
  ok = ok && static_cast<long>(xs.size()) == bound + 2;
  if (ok) {
    fmpz_poly_t r;
    fmpz_poly_init(r);
    // Interpolate through the first bound + 1 points, check the last one.
    fmpz_poly_interpolate_fmpz_vec(r, xs.data(), ys.data(), bound + 1);
    fmpz_poly_evaluate_fmpz(v, r, &xs[static_cast<size_t>(bound + 1)]);
    ok = fmpz_equal(v, &ys[static_cast<size_t>(bound + 1)]);
    if (ok) fmpz_mpoly_set_fmpz_poly(out, r, keep, zctx());
    fmpz_poly_clear(r);
  }
  for (auto& x : xs)
    fmpz_clear(&x);
  for (auto& y : ys)
    fmpz_clear(&y);
  fmpz_poly_clear(pa);
  fmpz_poly_clear(pb);
  fmpz_mpoly_clear(sa, zctx());
  fmpz_mpoly_clear(sb, zctx());
  fmpz_clear(k);
  fmpz_clear(v);
  return ok;
}

// The variable other than `var` that a bivariate pair involves, or -1.
int other_variable(const Poly3& a, const Poly3& b, int var) {
  int other = -1;
  for (int v = 0; v < 3; ++v) {
    if (v == var) continue;
    if (a.degree(v) > 0 || b.degree(v) > 0) {
      if (other >= 0) return -1;
      other = v;
    }
  }
  return other;
}

} // namespace

Poly3 resultant(const Poly3& a, const Poly3& b, int var) {
  // res(ca A, cb B) = ca^deg(B) cb^deg(A) res(A, B) (degrees in var), on the integer parts.
  fmpz_mpoly_t r;
  fmpz_mpoly_init(r, zctx());
  const int keep = other_variable(a, b, var);
  bool out_of_time = false;
  const bool interpolated =
      keep >= 0 && a.total_degree() * b.total_degree() >= 24 &&
      resultant_by_interpolation(r, zpart(a), zpart(b), var, keep, out_of_time);
  if (out_of_time) {
    fmpz_mpoly_clear(r, zctx());
    throw core::BudgetExceeded();
  }
  if (!interpolated && !fmpz_mpoly_resultant(r, zpart(a), zpart(b), var, zctx())) {
    fmpz_mpoly_clear(r, zctx());
    throw std::runtime_error("fmpz_mpoly_resultant failed");
  }
  fmpq_t s, t;
  fmpq_init(s);
  fmpq_init(t);
  fmpq_pow_si(s, a.raw()->content, b.is_zero() ? 0 : zdegree(zpart(b), var));
  fmpq_pow_si(t, b.raw()->content, a.is_zero() ? 0 : zdegree(zpart(a), var));
  fmpq_mul(s, s, t);
  Poly3 out = from_integer_part(r, s);
  fmpq_clear(s);
  fmpq_clear(t);
  fmpz_mpoly_clear(r, zctx());
  return out;
}

Poly3 gcd(const Poly3& a, const Poly3& b) {
  fmpz_mpoly_t g;
  fmpz_mpoly_init(g, zctx());
  if (!fmpz_mpoly_gcd(g, zpart(a), zpart(b), zctx())) {
    fmpz_mpoly_clear(g, zctx());
    throw std::runtime_error("fmpz_mpoly_gcd failed");
  }
  Poly3 r = from_integer_part(g);
  fmpz_mpoly_clear(g, zctx());
  return r;
}

Poly3 squarefree_part(const Poly3& a) {
  if (a.is_constant()) return a;
  fmpz_mpoly_factor_t f;
  fmpz_mpoly_factor_init(f, zctx());
  if (!fmpz_mpoly_factor_squarefree(f, zpart(a), zctx())) {
    fmpz_mpoly_factor_clear(f, zctx());
    throw std::runtime_error("fmpz_mpoly_factor_squarefree failed");
  }
  fmpz_mpoly_t r;
  fmpz_mpoly_init(r, zctx());
  fmpz_mpoly_one(r, zctx());
  for (slong i = 0; i < f->num; ++i)
    fmpz_mpoly_mul(r, r, f->poly + i, zctx());
  fmpz_mpoly_factor_clear(f, zctx());
  Poly3 out = from_integer_part(r);
  fmpz_mpoly_clear(r, zctx());
  return out;
}

UPolyZ to_univariate(const Poly3& a, int var) {
  UPolyZ r;
  if (!fmpz_mpoly_is_fmpz_poly(zpart(a), var, zctx()) ||
      !fmpz_mpoly_get_fmpz_poly(r.raw_mut(), zpart(a), var, zctx()))
    throw std::invalid_argument("to_univariate: the polynomial involves another variable");
  return r;
}

void evaluate(arb_t out, const Poly3& a, const std::array<const arb_struct*, 3>& b, long prec) {
  const fmpz_mpoly_struct* z = zpart(a);
  const slong n = fmpz_mpoly_length(z, zctx());
  arb_zero(out);
  if (n == 0) return;
  // Powers of each variable up to its degree, then term by term over the integer part, then
  // the content once.
  std::array<std::vector<arb_struct>, 3> pw;
  for (int v = 0; v < 3; ++v) {
    const long d = zdegree(z, v);
    pw[static_cast<size_t>(v)].resize(static_cast<size_t>(d < 0 ? 1 : d + 1));
    auto& t = pw[static_cast<size_t>(v)];
    for (auto& x : t)
      arb_init(&x);
    arb_one(&t[0]);
    for (size_t k = 1; k < t.size(); ++k)
      arb_mul(&t[k], &t[k - 1], b[static_cast<size_t>(v)], prec);
  }
  fmpz_t c;
  fmpz_init(c);
  arb_t term;
  arb_init(term);
  slong e[3];
  for (slong i = 0; i < n; ++i) {
    fmpz_mpoly_get_term_coeff_fmpz(c, z, i, zctx());
    fmpz_mpoly_get_term_exp_si(e, z, i, zctx());
    arb_set_fmpz(term, c);
    for (int v = 0; v < 3; ++v)
      if (e[v] > 0)
        arb_mul(term, term, &pw[static_cast<size_t>(v)][static_cast<size_t>(e[v])], prec);
    arb_add(out, out, term, prec);
  }
  const fmpq* content = a.raw()->content;
  if (!fmpq_is_one(content)) {
    arb_mul_fmpz(out, out, fmpq_numref(content), prec);
    if (!fmpz_is_one(fmpq_denref(content))) arb_div_fmpz(out, out, fmpq_denref(content), prec);
  }
  arb_clear(term);
  fmpz_clear(c);
  for (auto& t : pw)
    for (auto& x : t)
      arb_clear(&x);
}

Poly3 quadric_poly(const std::array<std::array<core::Rational, 4>, 4>& m) {
  // Common denominator of the entries, so every coefficient becomes an integer.
  core::Integer den(1);
  for (const auto& row : m)
    for (const auto& x : row)
      fmpz_lcm(den.raw_mut(), den.raw(), x.den().raw());
  std::array<Poly3, 4> p{Poly3::variable(0), Poly3::variable(1), Poly3::variable(2), Poly3(1)};
  Poly3 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j) {
      core::Rational c = m[i][j] * core::Rational(den);
      if (j != i) c = c * core::Rational(2);
      if (c.is_zero()) continue;
      r = r + Poly3(c) * p[i] * p[j];
    }
  return r;
}

} // namespace surfcert::algebra
