#include "surfcert/algebra/upoly.hpp"

#include <flint/fmpz_poly_factor.h>
#include <flint/nmod_poly.h>
#include <flint/ulong_extras.h>

#include <algorithm>
#include <cstdlib>

namespace surfcert::algebra {

UPolyZ UPolyZ::from_coeffs(const std::vector<Integer>& c) {
  UPolyZ p;
  for (size_t i = 0; i < c.size(); ++i)
    fmpz_poly_set_coeff_fmpz(p.v_, static_cast<slong>(i), c[i].raw());
  return p;
}

Integer UPolyZ::coeff(long i) const {
  Integer r;
  fmpz_poly_get_coeff_fmpz(r.raw_mut(), v_, i);
  return r;
}

int UPolyZ::sign_at(const Rational& x) const {
  // sign p(n/d) = sign(d^deg p(n/d)) (d > 0): the homogenised value sum a_i n^i d^(deg-i) by
  // Horner in integers, exact and without the gcds of rational Horner.
  const slong len = fmpz_poly_length(v_);
  if (len == 0) return 0;
  const fmpz* n = fmpq_numref(x.raw());
  const fmpz* d = fmpq_denref(x.raw());
  if (fmpz_is_one(d)) {
    fmpz_t s;
    fmpz_init(s);
    fmpz_poly_evaluate_fmpz(s, v_, n);
    const int sg = fmpz_sgn(s);
    fmpz_clear(s);
    return sg;
  }
  fmpz_t s, pw, t;
  fmpz_init_set(s, v_->coeffs + len - 1);
  fmpz_init_set(pw, d);
  fmpz_init(t);
  for (slong i = len - 2; i >= 0; --i) {
    fmpz_mul(s, s, n);
    if (!fmpz_is_zero(v_->coeffs + i)) {
      fmpz_mul(t, v_->coeffs + i, pw);
      fmpz_add(s, s, t);
    }
    if (i > 0) fmpz_mul(pw, pw, d);
  }
  const int sg = fmpz_sgn(s);
  fmpz_clear(s);
  fmpz_clear(pw);
  fmpz_clear(t);
  return sg;
}

UPolyZ UPolyZ::primitive_part() const {
  UPolyZ r;
  fmpz_poly_primitive_part(r.v_, v_);
  if (fmpz_poly_length(r.v_) > 0 && fmpz_sgn(fmpz_poly_lead(r.v_)) < 0) fmpz_poly_neg(r.v_, r.v_);
  return r;
}

UPolyZ UPolyZ::derivative() const {
  UPolyZ r;
  fmpz_poly_derivative(r.v_, v_);
  return r;
}

static std::string poly_text(const std::vector<Rational>& c, const char* var) {
  std::string s;
  for (long i = static_cast<long>(c.size()) - 1; i >= 0; --i) {
    const Rational& a = c[static_cast<size_t>(i)];
    if (a.is_zero()) continue;
    Rational m = core::abs(a);
    if (s.empty())
      s += a.sign() < 0 ? "-" : "";
    else
      s += a.sign() < 0 ? " - " : " + ";
    std::string mono =
        i == 0 ? "" : (i == 1 ? std::string(var) : std::string(var) + "^" + std::to_string(i));
    if (mono.empty())
      s += m.to_string();
    else if (m == Rational(1))
      s += mono;
    else
      s += m.to_string() + "*" + mono;
  }
  return s.empty() ? "0" : s;
}

std::string UPolyZ::to_string(const char* var) const {
  std::vector<Rational> c;
  for (long i = 0; i <= degree(); ++i)
    c.emplace_back(coeff(i));
  return poly_text(c, var);
}

UPolyQ UPolyQ::from_coeffs(const std::vector<Rational>& c) {
  UPolyQ p;
  for (size_t i = 0; i < c.size(); ++i)
    fmpq_poly_set_coeff_fmpq(p.v_, static_cast<slong>(i), c[i].raw());
  return p;
}

Rational UPolyQ::coeff(long i) const {
  Rational r;
  fmpq_poly_get_coeff_fmpq(r.raw_mut(), v_, i);
  return r;
}

Rational UPolyQ::evaluate(const Rational& x) const {
  Rational r;
  fmpq_poly_evaluate_fmpq(r.raw_mut(), v_, x.raw());
  return r;
}

UPolyQ UPolyQ::linear(const Rational& a, const Rational& b) {
  UPolyQ p;
  fmpq_poly_set_coeff_fmpq(p.v_, 1, a.raw());
  fmpq_poly_set_coeff_fmpq(p.v_, 0, b.raw());
  return p;
}

UPolyQ UPolyQ::rem(const UPolyQ& g) const {
  UPolyQ r;
  fmpq_poly_rem(r.v_, v_, g.v_);
  return r;
}

UPolyZ UPolyQ::primitive_integer() const {
  UPolyZ z;
  fmpq_poly_get_numerator(z.raw_mut(), v_);
  return z.primitive_part();
}

std::string UPolyQ::to_string(const char* var) const {
  std::vector<Rational> c;
  for (long i = 0; i <= degree(); ++i)
    c.push_back(coeff(i));
  return poly_text(c, var);
}

std::vector<Rational> rational_roots(const UPolyQ& p) {
  std::vector<Rational> out;
  if (p.degree() < 1) return out;
  for (const IrreducibleFactor& f : irreducible_factors(p.primitive_integer()))
    if (f.poly.degree() == 1) // a x + b: root -b / a
      out.push_back(-Rational(f.poly.coeff(0)) / Rational(f.poly.coeff(1)));
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

// Whether p (primitive, degree n >= 2) is proved irreducible over Q by its factorisations
// modulo a few word-size primes: a factor of degree k over Z stays a factor of degree k modulo
// every prime not dividing the leading coefficient, so k must be a sum of some of the modular
// factors' degrees, for each prime; when no k in 1..n-1 is such a sum for every prime tried,
// p is irreducible. Modulo a prime where p is not square-free the degrees say nothing (that
// prime is skipped; a p not square-free over Q is never proved so). False: not proved (FLINT
// then factors). Why: the points at infinity of two cones posed in doubles are the roots of a
// quartic with coefficients of hundreds of bits, irreducible almost always; fmpz_poly_factor
// spent ~40% of their exact affine reading getting there (its own prime selection, then
// setting up the lifting). Only for coefficients beyond 64 bits: on small ones FLINT is as
// quick, and the twelve modular factorisations cost the generated pencils 3-5% of a batch.
bool irreducible_by_primes(const UPolyZ& p) {
  const slong n = p.degree();
  if (n < 2 || n > 60) return false;
  unsigned long long possible = ((1ULL << n) - 1) & ~1ULL; // bit k: degree k (1..n-1) possible
  ulong prime = (1UL << 22) + 15;
  nmod_poly_t q;
  nmod_poly_factor_t fac;
  for (int tried = 0; tried < 12 && possible; ++tried) {
    prime = n_nextprime(prime, 1);
    nmod_poly_init(q, prime);
    fmpz_poly_get_nmod_poly(q, p.raw());
    if (nmod_poly_degree(q) == n) {
      nmod_poly_t dq, g;
      nmod_poly_init(dq, prime);
      nmod_poly_init(g, prime);
      nmod_poly_derivative(dq, q);
      nmod_poly_gcd(g, q, dq);
      const bool squarefree = nmod_poly_degree(g) == 0;
      nmod_poly_clear(dq);
      nmod_poly_clear(g);
      if (squarefree) {
        nmod_poly_factor_init(fac);
        nmod_poly_factor(fac, q);
        unsigned long long sums = 1; // bit s: a sum s of some factors' degrees
        for (slong i = 0; i < fac->num; ++i)
          for (slong e = 0; e < fac->exp[i]; ++e)
            sums |= sums << nmod_poly_degree(fac->p + i);
        nmod_poly_factor_clear(fac);
        possible &= sums;
      }
    }
    nmod_poly_clear(q);
  }
  return possible == 0;
}

} // namespace

std::vector<IrreducibleFactor> irreducible_factors(const UPolyZ& p) {
  // (Small coefficients: FLINT's own factorisation is as quick.)
  if (p.degree() >= 2 && std::abs(fmpz_poly_max_bits(p.raw())) > 64) {
    const UPolyZ g = p.primitive_part();
    if (irreducible_by_primes(g)) {
      IrreducibleFactor x;
      x.poly = g;
      x.exponent = 1;
      return {x};
    }
  }
  // RAII for FLINT's factor structure (cleared on every path, exceptions included).
  struct Fac {
    fmpz_poly_factor_t f;
    Fac() { fmpz_poly_factor_init(f); }
    ~Fac() { fmpz_poly_factor_clear(f); }
    Fac(const Fac&) = delete;
    Fac& operator=(const Fac&) = delete;
  } fac;
  fmpz_poly_factor(fac.f, p.raw());
  std::vector<IrreducibleFactor> out;
  out.reserve(static_cast<size_t>(fac.f->num));
  for (slong i = 0; i < fac.f->num; ++i) {
    IrreducibleFactor x;
    fmpz_poly_set(x.poly.raw_mut(), fac.f->p + i);
    x.exponent = static_cast<int>(fac.f->exp[i]);
    if (x.poly.degree() >= 1) out.push_back(std::move(x));
  }
  return out;
}

} // namespace surfcert::algebra
