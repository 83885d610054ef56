#include "surfcert/algebra/real_roots.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/core/budget.hpp"

#include <flint/fmpz_poly_factor.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <optional>
#include <vector>

namespace surfcert::algebra {

long count_real_roots(const UPolyZ& p) {
  if (p.degree() <= 0) return 0;
  return static_cast<long>(fmpz_poly_num_real_roots_sturm(p.raw()));
}

bool has_real_root(const UPolyZ& p) {
  if (p.degree() <= 0) return false;
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  fmpz_poly_factor_squarefree(fac, p.raw());
  bool real = false;
  for (slong i = 0; i < fac->num && !real; ++i) {
    UPolyZ f;
    fmpz_poly_set(f.raw_mut(), fac->p + i);
    real = f.degree() >= 1 && count_real_roots(f) > 0;
  }
  fmpz_poly_factor_clear(fac);
  return real;
}

std::vector<std::complex<double>> approx_complex_roots(const std::vector<double>& c) {
  using cd = std::complex<double>;
  const size_t n = c.size() - 1;
  std::vector<cd> z(n);
  if (n == 0) return z;
  // Initial points on a circle of radius given by a Fujiwara-like bound, rotated off the axes.
  double lead = c[n], r = 0;
  for (size_t i = 0; i < n; ++i)
    r = std::max(r, std::pow(std::fabs(c[i] / lead), 1.0 / static_cast<double>(n - i)));
  r = std::max(r, 1e-300);
  for (size_t k = 0; k < n; ++k)
    z[k] = std::polar(r, 2 * M_PI * (static_cast<double>(k) + 0.25) / static_cast<double>(n) + 0.4);
  // Roots whose last correction was below 1e-14 (relative) are frozen: only guesses are
  // needed here (callers check them exactly or polish them by Newton). So is a root whose
  // correction, already below 1e-7, stopped shrinking: a multiple root converges linearly to
  // the rounding's floor (~1e-8 for a double root) and then wanders there; a degree 8
  // discriminant with a double root ran all 100 iterations (~10% of a traced pipe pair).
  std::vector<char> done(n, 0);
  std::vector<double> last(n, HUGE_VAL);
  for (int it = 0; it < 100; ++it) {
    double moved = 0;
    for (size_t k = 0; k < n; ++k) {
      if (done[k]) continue;
      cd p = c[n], dp = 0;
      for (size_t i = n; i-- > 0;) {
        dp = dp * z[k] + p;
        p = p * z[k] + c[i];
      }
      if (p == cd(0)) continue;
      // Plain complex divisions (std::complex's operator/ guards against overflow with slow
      // library calls; a non-finite result is skipped below anyway).
      auto div = [](cd x, cd y) {
        double d = y.real() * y.real() + y.imag() * y.imag();
        return cd((x.real() * y.real() + x.imag() * y.imag()) / d,
                  (x.imag() * y.real() - x.real() * y.imag()) / d);
      };
      cd ratio = div(p, dp), sum = 0;
      for (size_t j = 0; j < n; ++j)
        if (j != k) sum += div(1.0, z[k] - z[j]);
      cd w = div(ratio, 1.0 - ratio * sum);
      if (!std::isfinite(w.real()) || !std::isfinite(w.imag())) continue;
      z[k] -= w;
      double aw = std::fabs(w.real()) + std::fabs(w.imag());
      double rel = aw / (1 + std::fabs(z[k].real()) + std::fabs(z[k].imag()));
      if (rel < 1e-14 || (rel < 1e-7 && aw >= last[k])) done[k] = 1;
      last[k] = aw;
      moved = std::max(moved, rel);
    }
    if (moved < 1e-15) break;
  }
  return z;
}

std::vector<double> approx_real_roots(const std::vector<double>& coeffs, size_t count) {
  auto z = approx_complex_roots(coeffs);
  std::sort(z.begin(), z.end(), [](auto a, auto b) {
    return std::fabs(a.imag()) / (1 + std::abs(a)) < std::fabs(b.imag()) / (1 + std::abs(b));
  });
  std::vector<double> r;
  for (size_t i = 0; i < std::min(count, z.size()); ++i)
    r.push_back(z[i].real());
  std::sort(r.begin(), r.end());
  return r;
}

// Real roots of c3 x^3 + c2 x^2 + c1 x + c0 (closed form, trigonometric or Cardano),
// each polished by two Newton steps. Returns their number (0 when c3 == 0).
int approx_cubic_real_roots(double c3, double c2, double c1, double c0, double* out) {
  if (c3 == 0 || !std::isfinite(c3)) return 0;
  double a = c2 / c3, b = c1 / c3, c = c0 / c3;
  double p = b - a * a / 3, q = 2 * a * a * a / 27 - a * b / 3 + c;
  int n;
  if (p < 0 && 4 * p * p * p + 27 * q * q < 0) {
    double m = 2 * std::sqrt(-p / 3);
    double th = std::acos(std::clamp(3 * q / (p * m), -1.0, 1.0)) / 3;
    for (int k = 0; k < 3; ++k)
      out[k] = m * std::cos(th - 2 * M_PI * k / 3) - a / 3;
    n = 3;
  } else {
    double d = std::sqrt(std::max(0.0, q * q / 4 + p * p * p / 27));
    out[0] = std::cbrt(-q / 2 + d) + std::cbrt(-q / 2 - d) - a / 3;
    n = 1;
  }
  for (int k = 0; k < n; ++k)
    for (int it = 0; it < 2; ++it) {
      double x = out[k];
      double v = ((x + a) * x + b) * x + c, dv = (3 * x + 2 * a) * x + b;
      if (dv != 0 && std::isfinite(v / dv)) out[k] = x - v / dv;
    }
  std::sort(out, out + n);
  return n;
}

size_t critical_point_separators(const double* c, size_t n, size_t k, double* out) {
  if (k <= 1 || n < 2 || n > 4 || c[n] == 0) return 0;
  // Real roots of p' (degree n - 1 <= 3).
  double crit[3];
  int ncrit = 0;
  if (n == 4) {
    ncrit = approx_cubic_real_roots(4 * c[4], 3 * c[3], 2 * c[2], c[1], crit);
  } else if (n == 3) {
    double qa = 3 * c[3], qb = 2 * c[2], qc = c[1], disc = qb * qb - 4 * qa * qc;
    if (disc > 0) {
      double r = std::sqrt(disc);
      double x1 = (-qb - std::copysign(r, qb)) / (2 * qa); // stable pair of roots
      double x2 = x1 != 0 ? qc / (qa * x1) : -qb / qa;
      crit[0] = std::min(x1, x2);
      crit[1] = std::max(x1, x2);
      ncrit = 2;
    }
  } else {
    crit[0] = -c[1] / (2 * c[2]);
    ncrit = 1;
  }
  auto value = [&](double x) {
    double v = 0;
    for (size_t i = n + 1; i-- > 0;)
      v = v * x + c[i];
    return v;
  };
  if (static_cast<size_t>(ncrit) == k - 1) {
    std::copy(crit, crit + ncrit, out);
    return static_cast<size_t>(ncrit);
  }
  if (k == 2 && ncrit == 3) {
    // Between the two roots p has the sign opposite to its leading coefficient: take the
    // critical point where sign(lead) * p is lowest.
    int best = 0;
    for (int i = 1; i < 3; ++i)
      if ((c[n] > 0 ? value(crit[i]) : -value(crit[i])) <
          (c[n] > 0 ? value(crit[best]) : -value(crit[best])))
        best = i;
    out[0] = crit[best];
    return 1;
  }
  return 0;
}

std::vector<double> critical_point_separators(const std::vector<double>& c, size_t k) {
  if (c.empty()) return {};
  double out[3];
  const size_t m = critical_point_separators(c.data(), c.size() - 1, k, out);
  return std::vector<double>(out, out + m);
}

namespace {

// True when the separators certify an isolation of the k real roots of p (see header).
bool separators_certify(const UPolyZ& p, const std::vector<Rational>& s, long k) {
  if (static_cast<long>(s.size()) != k + 1) return false;
  int prev = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    if (i > 0 && !(s[i - 1] < s[i])) return false;
    int sg = p.sign_at(s[i]);
    if (sg == 0) return false;
    if (i > 0 && sg == prev) return false;
    prev = sg;
  }
  return true;
}

// The dyadic number with the fewest fraction bits in (lo, hi) (or their midpoint): short
// separators keep the exact sign and inertia computations at them cheap.
double simplest_dyadic_between(double lo, double hi);

// A short dyadic close to x (within 2^-24 relative): the exact check decides whether it works.
double simplest_dyadic_near(double x) {
  double w = std::ldexp(std::fabs(x) + 1e-300, -24);
  return simplest_dyadic_between(x - w, x + w);
}

double simplest_dyadic_between(double lo, double hi) {
  double mid = 0.5 * (lo + hi);
  if (!(lo < hi) || !std::isfinite(mid)) return mid;
  for (int k = 0; k < 60; ++k) {
    double scale = std::ldexp(1.0, k);
    double x = std::round(mid * scale) / scale;
    if (lo < x && x < hi) return x;
  }
  return mid;
}

// A power of two strictly above every root's absolute value (Cauchy: 1 + max|a_i/a_n|).
// The smallest such power 2^e, e >= 1: 2^e > 1 + M / L (M the largest |a_i|, i < n, L = |a_n|)
// iff (2^e - 1) L > M, decided on integers (the quotients as Rationals cost a gcd of the
// coefficients each: 6% of an intersect on pairs posed in doubles, whose coefficients run to
// hundreds of digits), e started from the bit lengths and moved by one until it is the least.
Rational root_bound(const UPolyZ& p) {
  const fmpz_poly_struct* f = p.raw();
  const long n = p.degree();
  Integer l, m, u; // L, M and (2^e - 1) L
  fmpz_abs(l.raw_mut(), f->coeffs + n);
  for (long i = 0; i < n; ++i)
    if (fmpz_cmpabs(f->coeffs + i, m.raw()) > 0) fmpz_abs(m.raw_mut(), f->coeffs + i);
  auto above = [&](long e) {
    fmpz_mul_2exp(u.raw_mut(), l.raw(), static_cast<ulong>(e));
    fmpz_sub(u.raw_mut(), u.raw(), l.raw());
    return fmpz_cmp(u.raw(), m.raw()) > 0;
  };
  long e = std::max(1L, m.bits() - l.bits());
  while (!above(e))
    ++e;
  while (e > 1 && above(e - 1))
    --e;
  Integer b(1);
  fmpz_mul_2exp(b.raw_mut(), b.raw(), static_cast<ulong>(e));
  return Rational(b);
}

} // namespace

namespace {

// Certified isolation from Arb's complex root isolation (disjoint balls, one root each; a real
// root's ball is detected exactly real by conjugate symmetry): separators between the real
// balls. Much cheaper than a Sturm sequence for high degrees and large coefficients (degree 36
// with 11,000-bit coefficients: 17 ms against 360 ms). nullopt if the balls are not disjoint
// on the real line (never expected) or when the precision the roots need passes the cap below:
// the caller then falls back to the Sturm count and the exact isolators, which check the
// thread's budget. Used from degree 12 only: below it the float guess + CGAL's Descartes
// isolation is fast, while Arb's Durand-Kerner needs thousands of bits when the roots span a
// huge dynamic range (the pencil of spheres of radius 1e-150 and 1 at 1e150 apart: minutes in
// Arb, 30 ms now).
// Not arb_fmpz_poly_complex_roots: it doubles the precision until it succeeds, with no limit
// and no budget check (helper-21 measured stalls past 60 s on clustered or hugely scaled
// roots). The same steps here (Durand-Kerner at a precision, Arb's validation of the balls and
// of the real ones, doubling) stop at a cap and check the budget between rounds.
std::optional<RootSeparation> isolate_with_arb(const UPolyZ& p) {
  const slong d = p.degree();
  ComplexBallVec roots(d);
  acb_ptr r = roots.v;
  ComplexBallPoly cp;
  // Where this pays, the rounds succeed early: over the distance, pencil and trace tests every
  // success came at 64 to 1024 bits. Where it does not (two roots 10^-1000 apart among 13, or
  // roots near 10^1000), the rounds at 16384 and 32768 bits took 3.4 and 9.6 s before failing
  // anyway, and the exact isolators then answered in 0.5 s. So: at most 8192 bits, and no
  // further round after one that took over 50 ms (the next costs about four times more).
  constexpr slong kCap = 8192;
  constexpr double kSlowRoundMs = 50;
  bool done = false;
  for (slong prec = 64; prec <= kCap && !done; prec *= 2) {
    core::check_budget();
    const auto t0 = std::chrono::steady_clock::now();
    acb_poly_set_fmpz_poly(cp.v, p.raw(), prec);
    const slong maxiter = std::min<slong>(4 * d + 64, prec);
    const slong isolated = acb_poly_find_roots(r, cp.v, prec == 64 ? nullptr : r, maxiter, prec);
    done = isolated == d && acb_poly_validate_real_roots(r, cp.v, prec);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!done && ms > kSlowRoundMs) break;
  }
  if (!done) return std::nullopt;
  std::vector<std::pair<Rational, Rational>> iv;
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  for (slong i = 0; i < d; ++i)
    if (arb_contains_zero(acb_imagref(r + i))) {
      arb_get_lbound_arf(lo, acb_realref(r + i), 64);
      arb_get_ubound_arf(hi, acb_realref(r + i), 64);
      Rational a, b;
      arf_get_fmpq(a.raw_mut(), lo);
      arf_get_fmpq(b.raw_mut(), hi);
      iv.emplace_back(a, b);
    }
  arf_clear(lo);
  arf_clear(hi);
  RootSeparation out;
  if (iv.empty()) {
    out.separators = {Rational(0)};
    return out;
  }
  std::sort(iv.begin(), iv.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  for (size_t i = 0; i + 1 < iv.size(); ++i)
    if (!(iv[i].second < iv[i + 1].first)) return std::nullopt;
  out.separators.push_back(iv.front().first - Rational(1));
  for (size_t i = 0; i + 1 < iv.size(); ++i)
    out.separators.push_back((iv[i].second + iv[i + 1].first) * Rational(1, 2));
  out.separators.push_back(iv.back().second + Rational(1));
  return out;
}

} // namespace

namespace {

// Separators from exact rational roots when p (square-free, k real roots) splits into linear
// factors over Q; nullopt otherwise. Pencils of concentric spheres of radii 1e300 and 1 have
// the roots 1 and 1e600: beyond the double range of the float guess, and ~2000 bisections
// deep for CGAL's Descartes (milliseconds), while factoring a quadratic or quartic is cheap.
std::optional<std::vector<Rational>> rational_root_separators(const UPolyZ& p, long k) {
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  fmpz_poly_factor(fac, p.raw());
  std::vector<Rational> roots;
  for (slong i = 0; i < fac->num; ++i) {
    const fmpz_poly_struct* f = fac->p + i;
    if (fmpz_poly_degree(f) != 1) break;
    Rational r;
    fmpq_set_fmpz_frac(r.raw_mut(), f->coeffs + 0, f->coeffs + 1); // root -c0/c1
    fmpq_neg(r.raw_mut(), r.raw());
    roots.push_back(r);
  }
  const bool linear = static_cast<slong>(roots.size()) == fac->num;
  fmpz_poly_factor_clear(fac);
  if (!linear || static_cast<long>(roots.size()) != k) return std::nullopt;
  std::sort(roots.begin(), roots.end());
  std::vector<Rational> s{roots.front() - Rational(1)};
  for (size_t i = 0; i + 1 < roots.size(); ++i)
    s.push_back((roots[i] + roots[i + 1]) * Rational(1, 2));
  s.push_back(roots.back() + Rational(1));
  return s;
}

} // namespace

namespace {

// Sign variations of the coefficients of (1 + x)^n p((lo + hi x) / (1 + x)) (zeros skipped): by
// Descartes' rule an upper bound on the roots of p in (lo, hi) of the same parity; 0 and 1 are
// exact counts.
long descartes_variations(const UPolyZ& p, const Rational& lo, const Rational& hi) {
  const slong n = p.degree();
  fmpz_t an, ad, bn, bd;
  fmpz_init_set(an, fmpq_numref(lo.raw()));
  fmpz_init_set(ad, fmpq_denref(lo.raw()));
  fmpz_init_set(bn, fmpq_numref(hi.raw()));
  fmpz_init_set(bd, fmpq_denref(hi.raw()));
  // (lo + hi x) / (1 + x) = (an bd + bn ad x) / (ad bd (1 + x)): q = sum c_i A^i D^(n-i).
  fmpz_poly_t A, D, Ap, t, q;
  fmpz_poly_init(A);
  fmpz_poly_init(D);
  fmpz_poly_init(Ap);
  fmpz_poly_init(t);
  fmpz_poly_init(q);
  fmpz_t c;
  fmpz_init(c);
  fmpz_mul(c, an, bd);
  fmpz_poly_set_coeff_fmpz(A, 0, c);
  fmpz_mul(c, bn, ad);
  fmpz_poly_set_coeff_fmpz(A, 1, c);
  fmpz_mul(c, ad, bd);
  fmpz_poly_set_coeff_fmpz(D, 0, c);
  fmpz_poly_set_coeff_fmpz(D, 1, c);
  std::vector<UPolyZ> dpow(static_cast<size_t>(n + 1)); // D^j
  fmpz_poly_one(dpow[0].raw_mut());
  for (slong j = 1; j <= n; ++j)
    fmpz_poly_mul(dpow[static_cast<size_t>(j)].raw_mut(), dpow[static_cast<size_t>(j - 1)].raw(),
                  D);
  fmpz_poly_one(Ap); // A^i
  for (slong i = 0; i <= n; ++i) {
    const fmpz* ci = p.raw()->coeffs + i;
    if (!fmpz_is_zero(ci)) {
      fmpz_poly_mul(t, Ap, dpow[static_cast<size_t>(n - i)].raw());
      fmpz_poly_scalar_addmul_fmpz(q, t, ci);
    }
    if (i < n) fmpz_poly_mul(Ap, Ap, A);
  }
  long v = 0;
  int prev = 0;
  for (slong i = 0; i < fmpz_poly_length(q); ++i) {
    const int sg = fmpz_sgn(q->coeffs + i);
    if (sg == 0) continue;
    if (prev != 0 && sg != prev) ++v;
    prev = sg;
  }
  fmpz_clear(c);
  fmpz_poly_clear(A);
  fmpz_poly_clear(D);
  fmpz_poly_clear(Ap);
  fmpz_poly_clear(t);
  fmpz_poly_clear(q);
  fmpz_clear(an);
  fmpz_clear(ad);
  fmpz_clear(bn);
  fmpz_clear(bd);
  return v;
}

// u with every root of p (c_n != 0) of modulus < 2^u (Cauchy: 1 + max |c_i / c_n|), u >= 1.
slong cauchy_exponent(const fmpz_poly_struct* p) {
  const slong n = fmpz_poly_degree(p);
  const slong lead = static_cast<slong>(fmpz_bits(p->coeffs + n));
  slong t = 0;
  for (slong i = 0; i < n; ++i)
    if (!fmpz_is_zero(p->coeffs + i))
      t = std::max(t, static_cast<slong>(fmpz_bits(p->coeffs + i)) - lead + 1);
  return t + 1;
}

// Isolating intervals (lo, hi), 0 < lo, of the positive roots of q (square-free, q(0) != 0):
// Descartes' rule on intervals split at the geometric mean of their ends while they span more
// than a factor 4 (a pencil of a sphere of radius 1e20000 and a unit one has roots some 130000
// binary orders apart: found in ~17 splits of the exponent), then halved. A loop over a work
// list, not a recursion (CGAL's Descartes recursed once per halving: 40,000 frames deep on that
// pencil, a stack overflow), with a budget check per interval.
void positive_root_intervals(const UPolyZ& q, std::vector<std::pair<Rational, Rational>>& out) {
  const slong up = cauchy_exponent(q.raw());
  UPolyZ rev;
  fmpz_poly_reverse(rev.raw_mut(), q.raw(), q.degree() + 1);
  const slong down = cauchy_exponent(rev.raw());
  std::vector<std::pair<Rational, Rational>> work{{core::pow2(-down), core::pow2(up)}};
  while (!work.empty()) {
    core::check_budget();
    auto [lo, hi] = std::move(work.back());
    work.pop_back();
    const long v = descartes_variations(q, lo, hi);
    if (v == 0) continue;
    if (v == 1) {
      out.emplace_back(std::move(lo), std::move(hi));
      continue;
    }
    Rational mid;
    if (hi > Rational(4) * lo) {
      // 2^e with e halfway between the ends' binary orders, strictly inside (lo, hi).
      const auto order = [](const Rational& x) {
        return static_cast<slong>(fmpz_bits(fmpq_numref(x.raw()))) -
               static_cast<slong>(fmpz_bits(fmpq_denref(x.raw())));
      };
      mid = core::pow2((order(lo) + order(hi)) / 2);
      if (!(lo < mid && mid < hi)) mid = (lo + hi) * Rational(1, 2);
    } else {
      mid = (lo + hi) * Rational(1, 2);
    }
    // Never split at a root (at most n moves).
    while (q.sign_at(mid) == 0)
      mid = (lo + mid) * Rational(1, 2);
    work.emplace_back(mid, std::move(hi));
    work.emplace_back(std::move(lo), std::move(mid));
  }
}

// One root of an irreducible factor f: the point lo == hi (a rational root), or inside the
// open interval (lo, hi), f(lo) f(hi) < 0, holding no other root of f.
struct FactorRoot {
  size_t factor;
  Rational lo, hi;
};

// Quadratic interval refinement (Abbott's QIR, exact signs only): (lo, hi) narrowed to width at
// most `width` around the one root of f it holds (f(lo) f(hi) < 0). Each round proposes a
// bracket of 1/n of the interval around the secant point; a hit squares n (quadratic
// convergence: a root 10^-16000 from another is reached in ~20 rounds, where halving took
// 53,000), a miss halves it (n = 2 is a bisection). Budget checked per round.
void qir_refine(const UPolyZ& f, Rational& lo, Rational& hi, const Rational& width) {
  const int slo = f.sign_at(lo);
  if (slo == 0 || lo == hi) return;
  core::Integer n(4);
  std::vector<Rational> coeffs;
  for (long i = 0; i <= f.degree(); ++i)
    coeffs.emplace_back(f.coeff(i));
  const UPolyQ fq = UPolyQ::from_coeffs(coeffs);
  while (hi - lo > width) {
    core::check_budget();
    const Rational w = hi - lo;
    // The secant point (regula falsi) from exact values at the ends, rounded to the grid w / n.
    const Rational vlo = fq.evaluate(lo), vhi = fq.evaluate(hi);
    const Rational step = w / Rational(n);
    Rational guess = lo + w * (vlo / (vlo - vhi));
    Rational k = (guess - lo) / step;
    core::Integer kk;
    fmpz_fdiv_q(kk.raw_mut(), fmpq_numref(k.raw()), fmpq_denref(k.raw()));
    Rational a = lo + step * Rational(kk), b = a + step;
    bool hit = false;
    if (lo < a || b < hi) {
      const int sa = lo < a ? f.sign_at(a) : slo, sb = b < hi ? f.sign_at(b) : -slo;
      if (sa == 0) {
        lo = hi = a;
        return;
      }
      if (sb == 0) {
        lo = hi = b;
        return;
      }
      if (sa == slo && sb != slo) {
        lo = a, hi = b, hit = true;
      } else if (sa != slo) {
        hi = a;
      } else {
        lo = b;
      }
    }
    if (hit) {
      n = n * n;
    } else {
      // A miss: one exact halving besides, and a coarser grid next time.
      const Rational mid = (lo + hi) * Rational(1, 2);
      const int sm = f.sign_at(mid);
      if (sm == 0) {
        lo = hi = mid;
        return;
      }
      (sm == slo ? lo : hi) = mid;
      if (fmpz_cmp_ui(n.raw(), 4) > 0) fmpz_sqrt(n.raw_mut(), n.raw());
    }
  }
}

// The roots of the irreducible factor f (index i), each alone in its interval.
void factor_roots(const UPolyZ& f, size_t i, std::vector<FactorRoot>& out) {
  const long d = f.degree();
  if (d == 1) { // -c0 / c1
    Rational r(-f.coeff(0), f.coeff(1));
    out.push_back({i, r, r});
    return;
  }
  if (d == 2) {
    // (-b +- sqrt(D)) / 2a, D = b^2 - 4ac not a square (f irreducible): with s = floor(sqrt D),
    // each root alone in the image of (s, s + 1) (width 1 / 2|a| < sqrt(D) / |a|, the gap).
    const core::Integer a = f.coeff(2), b = f.coeff(1), c = f.coeff(0);
    core::Integer disc = b * b - core::Integer(4) * a * c;
    if (fmpz_sgn(disc.raw()) <= 0) return;
    core::Integer sq;
    fmpz_sqrt(sq.raw_mut(), disc.raw());
    const Rational two_a(core::Integer(2) * a);
    for (int sg : {-1, 1}) {
      Rational e1 = (Rational(-b) + Rational(sg) * Rational(sq)) / two_a;
      Rational e2 = (Rational(-b) + Rational(sg) * Rational(sq + core::Integer(1))) / two_a;
      if (e2 < e1) std::swap(e1, e2);
      out.push_back({i, e1, e2});
    }
    return;
  }
  std::vector<std::pair<Rational, Rational>> pos, neg;
  positive_root_intervals(f, pos);
  UPolyZ minus = f; // f(-x)
  for (slong j = 1; j <= minus.degree(); j += 2)
    fmpz_neg(minus.raw_mut()->coeffs + j, minus.raw()->coeffs + j);
  positive_root_intervals(minus, neg);
  for (auto& [lo, hi] : neg)
    out.push_back({i, -hi, -lo});
  for (auto& [lo, hi] : pos)
    out.push_back({i, lo, hi});
}

} // namespace

long max_coefficient_bits(const UPolyZ& p) {
  return static_cast<long>(std::labs(fmpz_poly_max_bits(p.raw())));
}

RootSeparation isolate_real_roots_descartes(const UPolyZ& p) {
  RootSeparation out;
  if (p.degree() < 1) {
    out.separators = {Rational(0)};
    return out;
  }
  // Irreducible factors apart: roots of different factors may be 10^-16000 apart (the pencil
  // of spheres of radii 1e8000 and 1: the root 1 and a root of a quadratic factor), which
  // Descartes' halvings separate only after 53,000 of them; QIR below does it in ~20 rounds.
  std::vector<UPolyZ> factors;
  {
    fmpz_poly_factor_t fac;
    fmpz_poly_factor_init(fac);
    fmpz_poly_factor(fac, p.raw());
    for (slong i = 0; i < fac->num; ++i) {
      factors.emplace_back();
      fmpz_poly_set(factors.back().raw_mut(), fac->p + i);
    }
    fmpz_poly_factor_clear(fac);
  }
  std::vector<FactorRoot> roots;
  for (size_t i = 0; i < factors.size(); ++i)
    factor_roots(factors[i], i, roots);
  if (roots.empty()) {
    out.separators = {Rational(0)};
    return out;
  }
  // Until no two intervals meet: each round narrows the two that do to 2^-(64 * 2^round) of
  // their width (a point interval, a rational root, stays).
  const auto by_lo = [](const FactorRoot& x, const FactorRoot& y) { return x.lo < y.lo; };
  for (long bits = 64;; bits = std::min<long>(2 * bits, 1L << 20)) {
    core::check_budget();
    std::sort(roots.begin(), roots.end(), by_lo);
    std::vector<char> narrow(roots.size(), 0);
    bool met = false;
    for (size_t i = 0; i + 1 < roots.size(); ++i)
      if (!(roots[i].hi < roots[i + 1].lo)) {
        met = true;
        narrow[i] = narrow[i + 1] = 1;
      }
    if (!met) break;
    for (size_t i = 0; i < roots.size(); ++i)
      if (narrow[i] && roots[i].lo != roots[i].hi) {
        Rational w = roots[i].hi - roots[i].lo;
        fmpq_div_2exp(w.raw_mut(), w.raw(), static_cast<ulong>(bits));
        qir_refine(factors[roots[i].factor], roots[i].lo, roots[i].hi, w);
      }
  }
  // Apart now, each interval holds exactly one root of p: separators between them.
  out.separators.push_back(roots.front().lo - Rational(1));
  for (size_t i = 0; i + 1 < roots.size(); ++i)
    out.separators.push_back((roots[i].hi + roots[i + 1].lo) * Rational(1, 2));
  out.separators.push_back(roots.back().hi + Rational(1));
  return out;
}

namespace {

// Separators from the float roots, proved by Descartes' rule instead of a Sturm count: the
// roots with a small imaginary part (relative), separated by short dyadics between them and
// by the root bound outside; every separator a nonzero of p, and exactly one sign variation on
// each gap (Descartes: exactly one root there; none on (-B, B) when no root looks real). The
// Sturm sequence's pseudo-remainders on coefficients of hundreds of bits (a pencil posed by
// rational rotations) were ~25% of a cone pair's affine topology; a few Taylor shifts of a
// quartic by short dyadics cost far less. Nullopt (the Sturm route) when anything fails:
// roots too close for the doubles, a complex pair read as real or the reverse.
// Two float roots too close for doubles to tell apart (centre c, spread w), between the
// separators lo < c < hi: a double root of an exact pose that the rounding of the input split
// into two real roots or a complex pair a few ulps apart. Decided exactly through the root of
// p' between them (Rolle): a short dyadic window (l, h) around c with no root of p on (lo, l]
// and [h, hi), an even count in (l, h) and exactly one root of p' there; that root is
// narrowed (refine_root_newton: exact signs) until p has the other sign at an end of its
// bracket (two real roots, one on each side of that end: p is monotone on either side of the
// bracket) or a ball evaluation of p over the bracket misses 0 (no root at all: p is monotone
// outside it and keeps its sign inside). Floats only place the window. Returns the separator,
// an empty optional for no root, nullopt when not decided (the caller isolates otherwise).
enum class PairOutcome { Split, Empty, Undecided };
PairOutcome split_close_pair(const UPolyZ& p, const Rational& lo, const Rational& hi, double c,
                             double w, Rational& separator) {
  const double lo_d = lo.to_double_approx(), hi_d = hi.to_double_approx();
  double d = std::max(8 * w, std::ldexp(1 + std::fabs(c), -40));
  d = std::min({d, 0.5 * (c - lo_d), 0.5 * (hi_d - c)});
  if (!(d > 0) || !std::isfinite(d)) return PairOutcome::Undecided;
  const double ld = simplest_dyadic_between(c - d, c - d / 2);
  const double hd = simplest_dyadic_between(c + d / 2, c + d);
  if (!std::isfinite(ld) || !std::isfinite(hd) || !(ld < hd)) return PairOutcome::Undecided;
  const Rational l = Rational::exact_from_double(ld), h = Rational::exact_from_double(hd);
  if (!(lo < l && l < h && h < hi)) return PairOutcome::Undecided;
  const int sl = p.sign_at(l);
  if (sl == 0 || p.sign_at(h) != sl) return PairOutcome::Undecided;
  if (descartes_variations(p, lo, l) != 0 || descartes_variations(p, h, hi) != 0)
    return PairOutcome::Undecided;
  const long v = descartes_variations(p, l, h);
  if (v == 0) return PairOutcome::Empty;
  if (v != 2) return PairOutcome::Undecided;
  const UPolyZ dp = p.derivative();
  const int dl = dp.sign_at(l);
  if (dl == 0 || dp.sign_at(h) != -dl || descartes_variations(dp, l, h) != 1)
    return PairOutcome::Undecided;
  Rational a = l, b = h;
  for (int round = 0; round < 12; ++round) {
    Rational width = b - a;
    fmpq_div_2exp(width.raw_mut(), width.raw(), 32);
    refine_root_newton(dp, a, b, width);
    for (const Rational* x : {&a, &b}) {
      const int sx = p.sign_at(*x);
      if (sx == 0) return PairOutcome::Undecided; // a rational root of p, found by chance
      if (sx != sl) {
        separator = *x;
        return PairOutcome::Split;
      }
    }
    if (a == b) return PairOutcome::Empty; // p' vanishes exactly at a, where p has p(l)'s sign
    // p over [a, b] (the union of the balls of its ends), at a precision above the bits that
    // p's value at the critical point needs to show its sign.
    const slong prec =
        128 + 2 * std::max(fmpz_bits(fmpq_denref(a.raw())), fmpz_bits(fmpq_denref(b.raw()))) +
        2 * max_coefficient_bits(p) / std::max<slong>(1, p.degree());
    BallPoly q;
    arb_poly_set_fmpz_poly(q.v, p.raw(), prec);
    Ball xa, xb, x, y;
    arb_set_fmpq(xa.v, a.raw(), prec);
    arb_set_fmpq(xb.v, b.raw(), prec);
    arb_union(x.v, xa.v, xb.v, prec);
    arb_poly_evaluate(y.v, q.v, x.v, prec);
    if (!arb_contains_zero(y.v) && (arb_is_positive(y.v) ? 1 : -1) == sl) return PairOutcome::Empty;
  }
  return PairOutcome::Undecided;
}

// Separators from the float roots, each interval's count proved by Descartes' rule: 1 for a
// root, 0 for none (merged into a neighbour), and for two roots closer than doubles resolve
// (within 2^-16 of their size) the exact decision above. Cuts go between the real roots and at
// the real part of each non-real pair: Descartes' count on (a, b) sees the roots in the disc
// over (a, b), and a pair near the real axis inside a wide interval made it 3 (a pencil of
// doubles with roots near 0, near 1e17 and a pair 0.125 +- 0.48i: 9 of 10 failed guesses on
// intersect_peers_bench's doubles). nullopt when the guess does not prove out.
std::optional<std::vector<Rational>> float_guess_descartes(const UPolyZ& p,
                                                           const std::vector<double>& c) {
  if (p.degree() < 1 ||
      !std::all_of(c.begin(), c.end(), [](double x) { return std::isfinite(x); }) || c.back() == 0)
    return std::nullopt;
  std::vector<double> r, complex_cuts;
  for (const auto& z : approx_complex_roots(c)) {
    if (!std::isfinite(z.real()) || !std::isfinite(z.imag())) return std::nullopt;
    if (std::fabs(z.imag()) <= 1e-7 * (1 + std::abs(z)))
      r.push_back(z.real());
    else if (z.imag() > 0) // a short dyadic near the real part of the pair, once per pair
      complex_cuts.push_back(
          simplest_dyadic_between(z.real() - z.imag() / 4, z.real() + z.imag() / 4));
  }
  if ((static_cast<long>(r.size()) - p.degree()) % 2 != 0) return std::nullopt;
  std::sort(r.begin(), r.end());
  // Groups of float roots: one root, or two too close to tell apart (more: not handled).
  struct Group {
    double first, last;
    int size;
  };
  std::vector<Group> groups;
  for (double x : r) {
    if (!groups.empty() && x - groups.back().last <= std::ldexp(1 + std::fabs(x), -16)) {
      Group& g = groups.back();
      if (++g.size > 2) return std::nullopt;
      g.last = x;
    } else {
      groups.push_back({x, x, 1});
    }
  }
  const Rational bound = root_bound(p);
  if (r.empty()) {
    if (descartes_variations(p, -bound, bound) != 0) return std::nullopt;
    return std::vector<Rational>{Rational(0)};
  }
  // The cuts: between consecutive groups, and the pairs' real parts away from every group.
  std::vector<double> cuts;
  for (size_t i = 0; i + 1 < groups.size(); ++i) {
    const double gap = groups[i + 1].first - groups[i].last;
    const double mid =
        simplest_dyadic_between(groups[i].last + 0.25 * gap, groups[i + 1].first - 0.25 * gap);
    if (!std::isfinite(mid) || !(gap > 0)) return std::nullopt;
    cuts.push_back(mid);
  }
  for (double x : complex_cuts) {
    bool away = std::isfinite(x);
    for (const auto& g : groups)
      away = away && (x < g.first - std::ldexp(1 + std::fabs(x), -12) ||
                      x > g.last + std::ldexp(1 + std::fabs(x), -12));
    if (away) cuts.push_back(x);
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<Rational> s{-bound};
  for (double x : cuts)
    s.push_back(Rational::exact_from_double(x));
  s.push_back(bound);
  for (size_t i = 1; i < s.size(); ++i)
    if (!(s[i - 1] < s[i])) return std::nullopt;
  for (size_t i = 1; i + 1 < s.size(); ++i)
    if (p.sign_at(s[i]) == 0) return std::nullopt;
  // Each interval proved: the group the floats put in it, or none. Invariant: p has no root on
  // (out.back(), s[i]].
  std::vector<Rational> out{s.front()};
  size_t next = 0; // the first group not placed yet
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    const double hi = i + 2 < s.size() ? cuts[i] : HUGE_VAL;
    const bool has = next < groups.size() && groups[next].last < hi;
    if (!has) {
      if (descartes_variations(p, s[i], s[i + 1]) != 0) return std::nullopt;
      continue;
    }
    const Group& g = groups[next++];
    if (next < groups.size() && groups[next].last < hi) return std::nullopt; // two in one
    if (g.size == 1) {
      if (descartes_variations(p, s[i], s[i + 1]) != 1) return std::nullopt;
      out.push_back(s[i + 1]);
      continue;
    }
    Rational m;
    switch (split_close_pair(p, s[i], s[i + 1], 0.5 * (g.first + g.last), g.last - g.first, m)) {
    case PairOutcome::Undecided:
      return std::nullopt;
    case PairOutcome::Split:
      out.push_back(m);
      out.push_back(s[i + 1]);
      break;
    case PairOutcome::Empty: // no root on (s[i], s[i + 1]), p(s[i + 1]) != 0
      break;
    }
  }
  if (next != groups.size()) return std::nullopt;
  if (out.size() == 1) return std::vector<Rational>{Rational(0)}; // no real root at all
  out.back() = bound; // the rootless tail (out.back(), bound) joins the last interval
  return out;
}

} // namespace

namespace {

// p's coefficients as doubles scaled by a common power of two (no overflow for huge integers;
// the roots are unchanged).
std::vector<double> scaled_doubles(const UPolyZ& p) {
  std::vector<double> c;
  slong emax = LONG_MIN;
  std::vector<slong> ex(static_cast<size_t>(p.degree() + 1));
  std::vector<double> mant(ex.size());
  for (long i = 0; i <= p.degree(); ++i) {
    auto ui = static_cast<size_t>(i);
    mant[ui] = fmpz_get_d_2exp(&ex[ui], p.raw()->coeffs + i);
    if (mant[ui] != 0) emax = std::max(emax, ex[ui]);
  }
  for (size_t i = 0; i < ex.size(); ++i)
    c.push_back(mant[i] == 0
                    ? 0.0
                    : std::ldexp(mant[i], static_cast<int>(std::max<slong>(ex[i] - emax, -2000))));
  return c;
}

} // namespace

namespace {

// Descartes' count for (lo, hi) in Arb balls: the coefficients of
// (1 + x)^n p((lo + hi x) / (1 + x)) = rev(p(lo + (hi - lo) t))(1 + x), at `prec` bits. Their
// sign variations when every coefficient's sign is certain (a ball not containing 0, or an
// exact 0); -1 otherwise. The exact count (descartes_variations) multiplies polynomials of
// coefficients of hundreds of bits; balls of 128 bits decide the same signs in a fraction.
long ball_variations(const UPolyZ& p, const Rational& lo, const Rational& hi, slong prec) {
  const slong n = p.degree();
  BallPoly q;
  arb_poly_set_fmpz_poly(q.v, p.raw(), prec);
  Ball a, w;
  arb_set_fmpq(a.v, lo.raw(), prec);
  arb_poly_taylor_shift(q.v, q.v, a.v, prec);
  const Rational width = hi - lo;
  arb_set_fmpq(w.v, width.raw(), prec);
  Ball wp(1.0);
  for (slong i = 0; i <= n; ++i) {
    arb_mul(q.v->coeffs + i, q.v->coeffs + i, wp.v, prec);
    arb_mul(wp.v, wp.v, w.v, prec);
  }
  _arb_poly_reverse(q.v->coeffs, q.v->coeffs, n + 1, n + 1); // in place: x^n q(1/x)
  _arb_poly_normalise(q.v);
  Ball one(1.0);
  arb_poly_taylor_shift(q.v, q.v, one.v, prec);
  long v = 0;
  int prev = 0;
  for (slong i = 0; i <= n; ++i) {
    const arb_struct* c = q.v->coeffs + i;
    if (i >= q.v->length || arb_is_zero(c)) continue;
    int sg = 0;
    if (arb_is_positive(c))
      sg = 1;
    else if (arb_is_negative(c))
      sg = -1;
    else
      return -1;
    if (prev != 0 && sg != prev) ++v;
    prev = sg;
  }
  return v;
}

// p(x) != 0, proved by a ball evaluation or else exactly.
bool nonzero_at(const UPolyZ& p, const Rational& x) {
  BallPoly q;
  arb_poly_set_fmpz_poly(q.v, p.raw(), 128);
  Ball xb, y;
  arb_set_fmpq(xb.v, x.raw(), 128);
  arb_poly_evaluate(y.v, q.v, xb.v, 128);
  if (!arb_contains_zero(y.v)) return true;
  return p.sign_at(x) != 0;
}

// No real root of p on (lo, hi), proved by Descartes' rule on pieces: split at the dyadics
// nearest the real parts of p's non-real float roots in there (a root off the real axis at a
// piece's end lies outside the disc on that piece, which by the one-circle theorem is all a
// count of 0 needs), then halved where a count is still positive, within a budget.
bool no_root_on(const UPolyZ& p, const Rational& lo, const Rational& hi,
                const std::vector<double>& hints) {
  std::vector<Rational> cuts{lo};
  {
    std::vector<Rational> inner;
    for (double x : hints) {
      const double d = simplest_dyadic_near(x);
      if (!std::isfinite(d)) continue;
      const Rational r = Rational::exact_from_double(d);
      if (lo < r && r < hi) inner.push_back(r);
    }
    std::sort(inner.begin(), inner.end());
    for (const Rational& r : inner)
      if (cuts.back() < r) cuts.push_back(r);
  }
  cuts.push_back(hi);
  for (size_t i = 1; i + 1 < cuts.size(); ++i)
    if (!nonzero_at(p, cuts[i])) return false;
  std::vector<std::pair<Rational, Rational>> todo;
  for (size_t i = 0; i + 1 < cuts.size(); ++i)
    todo.emplace_back(cuts[i], cuts[i + 1]);
  int budget = 32;
  while (!todo.empty()) {
    if (budget-- <= 0) return false;
    const auto [a, b] = todo.back();
    todo.pop_back();
    long v = ball_variations(p, a, b, 128);
    if (v < 0) v = ball_variations(p, a, b, 512);
    if (v < 0) v = descartes_variations(p, a, b);
    if (v == 0) continue;
    if (v % 2 == 1) return false; // a real root there
    const Rational m = (a + b) * Rational(1, 2);
    if (!nonzero_at(p, m)) return false;
    todo.emplace_back(a, m);
    todo.emplace_back(m, b);
  }
  return true;
}

} // namespace

std::optional<RootRange> real_root_range(const UPolyZ& p) {
  RootRange out;
  if (p.degree() < 1) return out; // a nonzero constant
  const std::vector<double> c = scaled_doubles(p);
  if (!std::all_of(c.begin(), c.end(), [](double x) { return std::isfinite(x); }) || c.back() == 0)
    return std::nullopt;
  double rlo = HUGE_VAL, rhi = -HUGE_VAL;
  std::vector<double> hints; // real parts of the roots that do not look real
  for (const auto& z : approx_complex_roots(c)) {
    if (!std::isfinite(z.real()) || !std::isfinite(z.imag())) return std::nullopt;
    if (std::fabs(z.imag()) <= 1e-7 * (1 + std::abs(z))) {
      rlo = std::min(rlo, z.real());
      rhi = std::max(rhi, z.real());
    } else {
      hints.push_back(z.real());
    }
  }
  const Rational bound = root_bound(p);
  if (rlo > rhi) { // no root looks real: none on (-B, B), i.e. none at all
    if (!no_root_on(p, -bound, bound, hints)) return std::nullopt;
    return out;
  }
  // A margin of 1/16 of the roots' spread plus 2^-20 of their size, and a short dyadic in the
  // outer half of it (short: the Taylor shifts below stay cheap).
  const double margin = (rhi - rlo) / 16 + 0x1p-20 * (1 + std::max(std::fabs(rlo), std::fabs(rhi)));
  const double dlo = simplest_dyadic_between(rlo - margin, rlo - margin / 2);
  const double dhi = simplest_dyadic_between(rhi + margin / 2, rhi + margin);
  if (!std::isfinite(dlo) || !std::isfinite(dhi)) return std::nullopt;
  out.lo = Rational::exact_from_double(dlo);
  out.hi = Rational::exact_from_double(dhi);
  if (out.lo <= -bound) out.lo = -bound; // B bounds every root strictly
  if (out.hi >= bound) out.hi = bound;
  if (!(out.lo < out.hi)) return std::nullopt;
  if (out.hi < bound && (!nonzero_at(p, out.hi) || !no_root_on(p, out.hi, bound, hints)))
    return std::nullopt;
  if (-bound < out.lo && (!nonzero_at(p, out.lo) || !no_root_on(p, -bound, out.lo, hints)))
    return std::nullopt;
  out.any = true;
  return out;
}

RootSeparation isolate_real_roots(const UPolyZ& p) {
  if (p.degree() >= 12)
    if (auto s = isolate_with_arb(p)) return *s;
  RootSeparation out;
  const std::vector<double> c = scaled_doubles(p);
  if (auto s = float_guess_descartes(p, c)) {
    out.separators = std::move(*s);
    return out;
  }
  long k = count_real_roots(p);
  if (k == 0) {
    out.separators = {Rational(0)};
    // p has no real root, so p(0) != 0 unless p is zero (precondition).
    return out;
  }
  bool finite = std::all_of(c.begin(), c.end(), [](double x) { return std::isfinite(x); });
  if (finite && c.back() != 0) {
    Rational bound = root_bound(p);
    std::vector<Rational> s{-bound};
    bool ok = true;
    std::vector<double> r;
    if (p.degree() <= 4) {
      // Critical points separate the roots (Rolle): no iteration needed.
      for (double x : critical_point_separators(c, static_cast<size_t>(k))) {
        double y = simplest_dyadic_near(x);
        if (!std::isfinite(y)) {
          ok = false;
          break;
        }
        s.push_back(Rational::exact_from_double(y));
      }
      ok = ok && static_cast<long>(s.size()) == k;
    } else {
      r = approx_real_roots(c, static_cast<size_t>(k));
    }
    for (size_t i = 0; i + 1 < r.size() && ok; ++i) {
      double gap = r[i + 1] - r[i];
      double mid = simplest_dyadic_between(r[i] + 0.25 * gap, r[i + 1] - 0.25 * gap);
      if (!std::isfinite(mid))
        ok = false;
      else
        s.push_back(Rational::exact_from_double(mid));
    }
    s.push_back(bound);
    if (ok && separators_certify(p, s, k)) {
      out.separators = std::move(s);
      return out;
    }
  }
  if (p.degree() <= 4)
    if (auto s = rational_root_separators(p, k); s && separators_certify(p, *s, k)) {
      out.separators = std::move(*s); // exact roots: CGAL not needed
      return out;
    }
  // CGAL's Descartes recurses once per halving of its interval: coefficients of 66,000 bits
  // (a sphere of radius 1e20000 against a unit one) took it 40,000 frames deep, a stack
  // overflow. Beyond kCgalMaxBits the loop above (a work list, exponent splits first) instead.
  out = max_coefficient_bits(p) > kCgalMaxBits ? isolate_real_roots_descartes(p)
                                               : isolate_real_roots_cgal(p);
  out.used_fallback = true;
  if (!separators_certify(p, out.separators, k))
    throw std::logic_error("isolate_real_roots: fallback separators failed the exact check");
  return out;
}

namespace {

// Exact bisection of (lo, hi) (p(lo) has sign slo != 0, p(hi) the opposite) until
// hi - lo <= width or a midpoint is a root.
void bisect_root(const UPolyZ& p, int slo, Rational& lo, Rational& hi, const Rational& width) {
  const Rational half(1, 2);
  while (hi - lo > width) {
    Rational mid = (lo + hi) * half;
    int sm = p.sign_at(mid);
    if (sm == 0) {
      lo = hi = mid;
      return;
    }
    if (sm == slo)
      lo = mid;
    else
      hi = mid;
  }
}

// log2 of |x| rounded up (x != 0), from the sizes of its numerator and denominator (+-1).
slong log2_upper(const Rational& x) {
  return static_cast<slong>(fmpz_bits(fmpq_numref(x.raw()))) -
         static_cast<slong>(fmpz_bits(fmpq_denref(x.raw()))) + 1;
}

// A start for newton_guess's Arb iteration: the same safeguarded Newton (bisection whenever a
// step leaves the bracket) in doubles, on the coefficients scaled by a power of two, until a
// step or the bracket is below 2^-44 of the iterate. From a wide isolating interval most of
// the ~20 Arb evaluations per refinement were spent getting there (30% of a cone pair's
// instructions); from this start two or three remain. nullopt when doubles do not hold the
// problem (an end beyond the double range, a non-finite value). A proposal like the rest.
std::optional<double> double_start(const UPolyZ& p, int slo, const Rational& lo,
                                   const Rational& hi) {
  const slong deg = p.degree();
  if (deg < 1) return std::nullopt;
  std::vector<double> c(static_cast<size_t>(deg + 1));
  std::vector<slong> e(c.size());
  slong emax = LONG_MIN;
  for (slong i = 0; i <= deg; ++i) {
    c[static_cast<size_t>(i)] = fmpz_get_d_2exp(&e[static_cast<size_t>(i)], p.raw()->coeffs + i);
    if (c[static_cast<size_t>(i)] != 0) emax = std::max(emax, e[static_cast<size_t>(i)]);
  }
  for (size_t i = 0; i < c.size(); ++i)
    c[i] = c[i] == 0 ? 0 : std::ldexp(c[i], static_cast<int>(std::max<slong>(e[i] - emax, -2000)));
  double a = lo.to_double_approx(), b = hi.to_double_approx();
  if (!std::isfinite(a) || !std::isfinite(b)) return std::nullopt;
  double x = 0.5 * a + 0.5 * b;
  for (int it = 0; it < 200; ++it) {
    double y = 0, dy = 0;
    for (slong i = deg; i >= 0; --i) {
      dy = dy * x + y;
      y = y * x + c[static_cast<size_t>(i)];
    }
    if (!std::isfinite(y) || !std::isfinite(dy)) return std::nullopt;
    if (y == 0) return x;
    ((y > 0 ? 1 : -1) == slo ? a : b) = x;
    double nx = dy != 0 ? x - y / dy : a;
    if (!(nx > std::min(a, b) && nx < std::max(a, b))) nx = 0.5 * a + 0.5 * b;
    const double step = std::fabs(nx - x);
    x = nx;
    if (step <= 0x1p-44 * std::fabs(x) || std::fabs(b - a) <= 0x1p-44 * std::fabs(x)) break;
  }
  return x;
}

// A float estimate of the root of p in (lo, hi) to about `width` / 16: safeguarded Newton on
// the midpoints of Arb evaluations at `prec` bits (a bisection step on float signs whenever
// Newton leaves the float bracket). Only a proposal: no sign here decides anything;
// refine_root_near checks it with exact signs. nullopt when it does not settle.
std::optional<Rational> newton_guess(const UPolyZ& p, int slo, const Rational& lo,
                                     const Rational& hi, const Rational& width) {
  const Rational big = core::abs(lo) > core::abs(hi) ? core::abs(lo) : core::abs(hi);
  const slong wexp = log2_upper(width) - 1; // 2^wexp <= ~width
  const slong span = big.is_zero() ? wexp : std::max(log2_upper(big), wexp);
  const slong prec = std::max<slong>(64, span - wexp + 32 + 4 * p.degree());
  if (prec > 20000) return std::nullopt;
  arb_poly_t f, df;
  arb_poly_init(f);
  arb_poly_init(df);
  arb_poly_set_fmpz_poly(f, p.raw(), prec);
  arb_poly_derivative(df, f, prec);
  Ball a, b, x, y, dy, step, tmp;
  arb_set_fmpq(a.v, lo.raw(), prec);
  arb_set_fmpq(b.v, hi.raw(), prec);
  arb_get_mid_arb(a.v, a.v);
  arb_get_mid_arb(b.v, b.v);
  if (const auto x0 = double_start(p, slo, lo, hi)) {
    arb_set_d(x.v, *x0);
  } else {
    arb_add(x.v, a.v, b.v, prec);
    arb_mul_2exp_si(x.v, x.v, -1);
  }
  std::optional<Rational> out;
  for (int it = 0; it < 4 * prec + 64; ++it) {
    arb_poly_evaluate2(y.v, dy.v, f, x.v, prec);
    const int sy = arf_sgn(arb_midref(y.v));
    if (sy == 0) {
      out.emplace();
      arf_get_fmpq(out->raw_mut(), arb_midref(x.v));
      break;
    }
    // Keep the float bracket (a, b) with the sign slo at a.
    if (sy == slo)
      arb_set(a.v, x.v);
    else
      arb_set(b.v, x.v);
    bool newton = !arf_is_zero(arb_midref(dy.v));
    if (newton) {
      arf_div(arb_midref(step.v), arb_midref(y.v), arb_midref(dy.v), prec, ARF_RND_NEAR);
      mag_zero(arb_radref(step.v));
      arb_sub(tmp.v, x.v, step.v, prec);
      arb_get_mid_arb(tmp.v, tmp.v);
      const bool a_first = arf_cmp(arb_midref(a.v), arb_midref(b.v)) < 0;
      const arf_struct* fl = a_first ? arb_midref(a.v) : arb_midref(b.v);
      const arf_struct* fh = a_first ? arb_midref(b.v) : arb_midref(a.v);
      newton = arf_cmp(arb_midref(tmp.v), fl) > 0 && arf_cmp(arb_midref(tmp.v), fh) < 0;
    }
    if (!newton) {
      arb_add(tmp.v, a.v, b.v, prec);
      arb_mul_2exp_si(tmp.v, tmp.v, -1);
      arb_sub(step.v, x.v, tmp.v, prec);
    }
    arb_swap(x.v, tmp.v);
    // Settled: the last move (or the float bracket) below width / 16.
    arb_sub(tmp.v, b.v, a.v, prec);
    const bool small_step =
        !arf_is_zero(arb_midref(step.v)) && arf_cmpabs_2exp_si(arb_midref(step.v), wexp - 4) < 0;
    if (small_step || arf_cmpabs_2exp_si(arb_midref(tmp.v), wexp - 4) < 0) {
      out.emplace();
      arf_get_fmpq(out->raw_mut(), arb_midref(x.v));
      break;
    }
  }
  arb_poly_clear(f);
  arb_poly_clear(df);
  return out;
}

enum class Round { Down, Up, Nearest }; // Nearest: ties up

// q rounded to a multiple of 2^e (exact dyadic arithmetic).
Rational round_to_2exp(const Rational& q, slong e, Round how) {
  const auto ue = static_cast<ulong>(e >= 0 ? e : -e);
  Rational t;
  if (e >= 0)
    fmpq_div_2exp(t.raw_mut(), q.raw(), ue);
  else
    fmpq_mul_2exp(t.raw_mut(), q.raw(), ue);
  if (how == Round::Nearest) t = t + Rational(1, 2);
  core::Integer n;
  if (how == Round::Up)
    fmpz_cdiv_q(n.raw_mut(), fmpq_numref(t.raw()), fmpq_denref(t.raw()));
  else
    fmpz_fdiv_q(n.raw_mut(), fmpq_numref(t.raw()), fmpq_denref(t.raw()));
  Rational r(n);
  if (e >= 0)
    fmpq_mul_2exp(r.raw_mut(), r.raw(), ue);
  else
    fmpq_div_2exp(r.raw_mut(), r.raw(), ue);
  return r;
}

// The sign of p at lo, after checking both ends exactly: 0 when an end is a root (then the
// interval is collapsed onto it: lo == hi).
int end_sign(const UPolyZ& p, Rational& lo, Rational& hi) {
  const int slo = p.sign_at(lo);
  if (slo == 0) {
    hi = lo;
    return 0;
  }
  if (p.sign_at(hi) == 0) {
    lo = hi;
    return 0;
  }
  return slo;
}

} // namespace

void refine_root_near(const UPolyZ& p, Rational& lo, Rational& hi, const Rational& width,
                      const Rational& guess) {
  const int slo = end_sign(p, lo, hi);
  if (slo == 0) return;
  if (hi - lo <= width) return;
  // The proposed bracket: guess -+ width / 4, its ends rounded outwards to about width / 16
  // (short dyadics), clipped to (lo, hi). Each end inside (lo, hi) is an exact sign evaluation;
  // whatever it says narrows (lo, hi) correctly, so a wrong guess costs two evaluations and
  // the bisection below does the rest.
  const slong wexp = log2_upper(width) - 1;
  const Rational quarter = width * Rational(1, 4);
  // The ends rounded outwards to multiples of 2^(wexp - 4).
  const Rational ends[2] = {round_to_2exp(guess - quarter, wexp - 4, Round::Down),
                            round_to_2exp(guess + quarter, wexp - 4, Round::Up)};
  for (const Rational& e : ends) {
    if (!(lo < e && e < hi)) continue;
    const int se = p.sign_at(e);
    if (se == 0) {
      lo = hi = e;
      return;
    }
    if (se == slo)
      lo = e;
    else
      hi = e;
  }
  bisect_root(p, slo, lo, hi, width);
}

namespace {

std::atomic<RootPlacement> g_placement{RootPlacement::Bisect};

// The testing placements (RootPlacement): the root first pinned by bisection to `fine`, then
// an interval of width <= width around it, clipped to the input (lo, hi). Its new ends lie in
// the input interval outside the pinned one, so they are not roots and keep the input's signs
// (one simple root in the input): valid by construction, no further sign needed.
void place_root(const UPolyZ& p, int slo, Rational& lo, Rational& hi, const Rational& width,
                RootPlacement pl) {
  const Rational olo = lo, ohi = hi;
  Rational fine = width;
  fmpq_div_2exp(fine.raw_mut(), fine.raw(), pl == RootPlacement::Tiny ? 20 : 16);
  bisect_root(p, slo, lo, hi, fine);
  if (lo == hi || pl == RootPlacement::Tiny) return;
  Rational half = width * Rational(1, 2);
  Rational a, b;
  if (pl == RootPlacement::RootNearLo) {
    a = lo;
    b = lo + width;
  } else if (pl == RootPlacement::RootNearHi) {
    a = hi - width;
    b = hi;
  } else { // Centred: the midpoint snapped to a grid of about width / 64
    const Rational m =
        round_to_2exp((lo + hi) * Rational(1, 2), log2_upper(width) - 7, Round::Nearest);
    a = m - half * Rational(63, 64);
    b = m + half * Rational(63, 64);
    if (!(a < lo && hi < b)) return; // the grid moved the centre too far: keep the pinned one
  }
  lo = olo < a ? a : olo;
  hi = b < ohi ? b : ohi;
}

} // namespace

void set_root_placement(RootPlacement placement) {
  g_placement.store(placement);
}
RootPlacement root_placement() {
  return g_placement.load(std::memory_order_relaxed);
}

void refine_root(const UPolyZ& p, Rational& lo, Rational& hi, const Rational& width) {
  const RootPlacement pl = root_placement();
  if (pl == RootPlacement::Newton) {
    refine_root_newton(p, lo, hi, width);
    return;
  }
  const int slo = end_sign(p, lo, hi);
  if (slo == 0) return;
  if (pl == RootPlacement::Bisect || hi - lo <= width) {
    bisect_root(p, slo, lo, hi, width);
    return;
  }
  place_root(p, slo, lo, hi, width, pl);
}

void refine_root_newton(const UPolyZ& p, Rational& lo, Rational& hi, const Rational& width) {
  const int slo = end_sign(p, lo, hi);
  if (slo == 0) return;
  if (hi - lo <= width) return;
  // Far from the width (more than a few bisections), a Newton estimate proposes the bracket.
  if (p.degree() >= 1 && hi - lo > width * Rational(16))
    if (auto g = newton_guess(p, slo, lo, hi, width)) {
      refine_root_near(p, lo, hi, width, *g);
      return;
    }
  bisect_root(p, slo, lo, hi, width);
}

int sign_at_root(const UPolyQ& p, const UPolyZ& f, Rational lo, Rational hi) {
  if (lo == hi) return p.evaluate(lo).sign();
  for (long bits : {32L, 128L, 512L, 2048L}) {
    refine_root_newton(f, lo, hi, (hi - lo) * Rational::exact_from_double(std::ldexp(1.0, -bits)));
    const long prec = bits + 64;
    Ball x, r, v, c;
    arb_set_fmpq(x.v, ((lo + hi) * Rational(1, 2)).raw(), prec);
    arb_set_fmpq(r.v, ((hi - lo) * Rational(1, 2)).raw(), prec);
    arb_add_error(x.v, r.v);
    for (long k = p.degree(); k >= 0; --k) {
      arb_mul(v.v, v.v, x.v, prec);
      arb_set_fmpq(c.v, p.coeff(k).raw(), prec);
      arb_add(v.v, v.v, c.v, prec);
    }
    if (arb_is_positive(v.v)) return 1;
    if (arb_is_negative(v.v)) return -1;
  }
  return 0;
}

RootSeparation separate_rational_roots(std::vector<Rational> roots) {
  RootSeparation out;
  if (roots.empty()) {
    out.separators = {Rational(0)};
    return out;
  }
  std::sort(roots.begin(), roots.end());
  out.separators.push_back(round_to_2exp(roots.front(), 0, Round::Down) - Rational(1));
  for (size_t i = 0; i + 1 < roots.size(); ++i) {
    const Rational w = roots[i + 1] - roots[i];
    if (w.sign() <= 0) throw std::logic_error("separate_rational_roots: roots not distinct");
    // 2^e < w / 2 (w > 2^(log2_upper(w) - 2)); the next multiple of 2^e above roots[i].
    const slong e = log2_upper(w) - 3;
    Rational step(1);
    if (e >= 0)
      fmpq_mul_2exp(step.raw_mut(), step.raw(), static_cast<ulong>(e));
    else
      fmpq_div_2exp(step.raw_mut(), step.raw(), static_cast<ulong>(-e));
    out.separators.push_back(round_to_2exp(roots[i], e, Round::Down) + step);
  }
  out.separators.push_back(round_to_2exp(roots.back(), 0, Round::Up) + Rational(1));
  return out;
}

} // namespace surfcert::algebra
