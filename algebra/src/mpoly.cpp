#include "surfcert/algebra/mpoly.hpp"

#include <flint/fmpz_mpoly_factor.h>
#include <flint/fmpz_poly.h>

#include <stdexcept>
#include <vector>

namespace surfcert::algebra {

namespace {

// One context for the whole program: three variables, lexicographic (x > y > z). FLINT
// contexts are read-only after initialisation, so sharing it between threads is safe.
struct Ctx {
  fmpz_mpoly_ctx_t c;
  Ctx() { fmpz_mpoly_ctx_init(c, 3, ORD_LEX); }
  ~Ctx() { fmpz_mpoly_ctx_clear(c); }
};

fmpz_mpoly_ctx_struct* shared_ctx() {
  static Ctx ctx;
  return ctx.c;
}

} // namespace

const fmpz_mpoly_ctx_struct* MPoly::ctx() {
  return shared_ctx();
}

MPoly::MPoly() {
  fmpz_mpoly_init(v_, shared_ctx());
}
MPoly::MPoly(long c) : MPoly() {
  fmpz_mpoly_set_si(v_, c, shared_ctx());
}
MPoly::MPoly(const core::Integer& c) : MPoly() {
  fmpz_mpoly_set_fmpz(v_, c.raw(), shared_ctx());
}
MPoly::MPoly(const MPoly& o) : MPoly() {
  fmpz_mpoly_set(v_, o.v_, shared_ctx());
}
MPoly::MPoly(MPoly&& o) noexcept : MPoly() {
  fmpz_mpoly_swap(v_, o.v_, shared_ctx());
}
MPoly& MPoly::operator=(MPoly o) noexcept {
  fmpz_mpoly_swap(v_, o.v_, shared_ctx());
  return *this;
}
MPoly::~MPoly() {
  fmpz_mpoly_clear(v_, shared_ctx());
}

MPoly MPoly::var(int i) {
  MPoly r;
  fmpz_mpoly_gen(r.v_, i, shared_ctx());
  return r;
}

bool MPoly::is_zero() const {
  return fmpz_mpoly_is_zero(v_, shared_ctx());
}
bool MPoly::is_constant() const {
  return fmpz_mpoly_is_fmpz(v_, shared_ctx());
}
long MPoly::total_degree() const {
  return fmpz_mpoly_total_degree_si(v_, shared_ctx());
}
long MPoly::degree(int var) const {
  return fmpz_mpoly_degree_si(v_, var, shared_ctx());
}
long MPoly::terms() const {
  return fmpz_mpoly_length(v_, shared_ctx());
}
MPoly MPoly::derivative(int var) const {
  MPoly r;
  fmpz_mpoly_derivative(r.v_, v_, var, shared_ctx());
  return r;
}

MPoly operator+(const MPoly& a, const MPoly& b) {
  MPoly r;
  fmpz_mpoly_add(r.v_, a.v_, b.v_, shared_ctx());
  return r;
}
MPoly operator-(const MPoly& a, const MPoly& b) {
  MPoly r;
  fmpz_mpoly_sub(r.v_, a.v_, b.v_, shared_ctx());
  return r;
}
MPoly operator*(const MPoly& a, const MPoly& b) {
  MPoly r;
  fmpz_mpoly_mul(r.v_, a.v_, b.v_, shared_ctx());
  return r;
}
MPoly operator-(const MPoly& a) {
  MPoly r;
  fmpz_mpoly_neg(r.v_, a.v_, shared_ctx());
  return r;
}
bool operator==(const MPoly& a, const MPoly& b) {
  return fmpz_mpoly_equal(a.v_, b.v_, shared_ctx());
}

namespace {

// Resultant in `var` of two polynomials that involve only `var` and `keep`, by evaluation at
// integer points of `keep` (univariate modular resultants, FLINT) and exact interpolation.
// A point where a leading coefficient in `var` vanishes is skipped (the specialisation would
// not commute with the resultant there). The degree bound is the Bezout bound
// tdeg(a) tdeg(b); one extra point checks the interpolant. Empty when it does not apply.
bool resultant_by_interpolation(MPoly& out, const MPoly& a, const MPoly& b, int var, int keep) {
  const long bound = a.total_degree() * b.total_degree();
  const long da = a.degree(var), db = b.degree(var);
  if (bound <= 0 || da <= 0 || db <= 0) return false;
  std::vector<fmpz> xs, ys;
  fmpz_t k, v;
  fmpz_init(k);
  fmpz_init(v);
  fmpz_mpoly_t sa, sb;
  fmpz_mpoly_init(sa, shared_ctx());
  fmpz_mpoly_init(sb, shared_ctx());
  fmpz_poly_t pa, pb;
  fmpz_poly_init(pa);
  fmpz_poly_init(pb);
  bool ok = true;
  for (long x = 0; static_cast<long>(xs.size()) < bound + 2 && x < 4 * bound + 100; ++x) {
    const long pt = (x % 2 == 0) ? x / 2 : -(x + 1) / 2; // 0, -1, 1, -2, 2, ...
    fmpz_set_si(k, pt);
    if (!fmpz_mpoly_evaluate_one_fmpz(sa, a.raw(), keep, k, shared_ctx()) ||
        !fmpz_mpoly_evaluate_one_fmpz(sb, b.raw(), keep, k, shared_ctx()) ||
        !fmpz_mpoly_get_fmpz_poly(pa, sa, var, shared_ctx()) ||
        !fmpz_mpoly_get_fmpz_poly(pb, sb, var, shared_ctx())) {
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
    if (ok) {
      fmpz_mpoly_set_fmpz_poly(out.raw_mut(), r, keep, shared_ctx());
    }
    fmpz_poly_clear(r);
  }
  for (auto& x : xs)
    fmpz_clear(&x);
  for (auto& y : ys)
    fmpz_clear(&y);
  fmpz_poly_clear(pa);
  fmpz_poly_clear(pb);
  fmpz_mpoly_clear(sa, shared_ctx());
  fmpz_mpoly_clear(sb, shared_ctx());
  fmpz_clear(k);
  fmpz_clear(v);
  return ok;
}

// The variable other than `var` that a bivariate pair involves, or -1.
int other_variable(const MPoly& a, const MPoly& b, int var) {
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

MPoly resultant(const MPoly& a, const MPoly& b, int var) {
  MPoly r;
  const int keep = other_variable(a, b, var);
  if (keep >= 0 && a.total_degree() * b.total_degree() >= 24 &&
      resultant_by_interpolation(r, a, b, var, keep))
    return r;
  if (!fmpz_mpoly_resultant(r.raw_mut(), a.raw(), b.raw(), var, shared_ctx()))
    throw std::runtime_error("fmpz_mpoly_resultant failed");
  return r;
}

MPoly dot(const MVec3& a, const MVec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

MVec3 cross(const MVec3& a, const MVec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

MPoly gcd(const MPoly& a, const MPoly& b) {
  MPoly r;
  if (!fmpz_mpoly_gcd(r.raw_mut(), a.raw(), b.raw(), shared_ctx()))
    throw std::runtime_error("fmpz_mpoly_gcd failed");
  return r;
}

MPoly squarefree_part(const MPoly& a) {
  if (a.is_zero() || a.is_constant()) return a;
  fmpz_mpoly_factor_t f;
  fmpz_mpoly_factor_init(f, shared_ctx());
  if (!fmpz_mpoly_factor_squarefree(f, a.raw(), shared_ctx())) {
    fmpz_mpoly_factor_clear(f, shared_ctx());
    throw std::runtime_error("fmpz_mpoly_factor_squarefree failed");
  }
  MPoly r(1);
  for (slong i = 0; i < f->num; ++i) {
    MPoly t;
    fmpz_mpoly_set(t.raw_mut(), f->poly + i, shared_ctx());
    r = r * t;
  }
  fmpz_mpoly_factor_clear(f, shared_ctx());
  return r;
}

UPolyZ to_univariate(const MPoly& a, int var) {
  UPolyZ r;
  if (!fmpz_mpoly_is_fmpz_poly(a.raw(), var, shared_ctx()) ||
      !fmpz_mpoly_get_fmpz_poly(r.raw_mut(), a.raw(), var, shared_ctx()))
    throw std::invalid_argument("to_univariate: the polynomial involves another variable");
  return r;
}

void evaluate(arb_t out, const MPoly& a, const std::array<const arb_struct*, 3>& b, long prec) {
  const slong n = a.terms();
  arb_zero(out);
  if (n == 0) return;
  // Powers of each variable up to its degree, then term by term.
  std::array<std::vector<arb_struct>, 3> pw;
  for (int v = 0; v < 3; ++v) {
    const long d = a.degree(v);
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
    fmpz_mpoly_get_term_coeff_fmpz(c, a.raw(), i, shared_ctx());
    fmpz_mpoly_get_term_exp_si(e, a.raw(), i, shared_ctx());
    arb_set_fmpz(term, c);
    for (int v = 0; v < 3; ++v)
      if (e[v] > 0)
        arb_mul(term, term, &pw[static_cast<size_t>(v)][static_cast<size_t>(e[v])], prec);
    arb_add(out, out, term, prec);
  }
  arb_clear(term);
  fmpz_clear(c);
  for (auto& t : pw)
    for (auto& x : t)
      arb_clear(&x);
}

MPoly quadric_poly(const std::array<std::array<core::Rational, 4>, 4>& m) {
  // Common denominator of the entries, so every coefficient becomes an integer.
  core::Integer den(1);
  for (const auto& row : m)
    for (const auto& x : row) {
      fmpz_lcm(den.raw_mut(), den.raw(), x.den().raw());
    }
  std::array<MPoly, 4> p{MPoly::var(0), MPoly::var(1), MPoly::var(2), MPoly(1)};
  MPoly r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j) {
      core::Rational c = m[i][j] * core::Rational(den);
      if (j != i) c = c * core::Rational(2);
      if (c.is_zero()) continue;
      r = r + MPoly(c.num()) * p[i] * p[j];
    }
  return r;
}

} // namespace surfcert::algebra
