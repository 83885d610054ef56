#include "surfcert/algebra/real_roots.hpp"

#include <algorithm>
#include <cmath>

namespace surfcert::algebra {

long count_real_roots(const UPolyZ& p) {
  if (p.degree() <= 0) return 0;
  return static_cast<long>(fmpz_poly_num_real_roots_sturm(p.raw()));
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
  for (int it = 0; it < 200; ++it) {
    double moved = 0;
    for (size_t k = 0; k < n; ++k) {
      cd p = c[n], dp = 0;
      for (size_t i = n; i-- > 0;) {
        dp = dp * z[k] + p;
        p = p * z[k] + c[i];
      }
      if (p == cd(0)) continue;
      cd ratio = p / dp, sum = 0;
      for (size_t j = 0; j < n; ++j)
        if (j != k) sum += 1.0 / (z[k] - z[j]);
      cd w = ratio / (1.0 - ratio * sum);
      if (!std::isfinite(w.real()) || !std::isfinite(w.imag())) continue;
      z[k] -= w;
      moved = std::max(moved, std::abs(w) / (1 + std::abs(z[k])));
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

// A power of two strictly above every root's absolute value (Cauchy: 1 + max|a_i/a_n|).
Rational root_bound(const UPolyZ& p) {
  long n = p.degree();
  Integer lead = p.coeff(n);
  Rational m(0);
  for (long i = 0; i < n; ++i) {
    Rational q = core::abs(Rational(p.coeff(i), lead));
    if (m < q) m = q;
  }
  Rational b(1);
  while (b <= m + Rational(1))
    b *= Rational(2);
  return b;
}

} // namespace

RootSeparation isolate_real_roots(const UPolyZ& p) {
  RootSeparation out;
  long k = count_real_roots(p);
  if (k == 0) {
    out.separators = {Rational(0)};
    // p has no real root, so p(0) != 0 unless p is zero (precondition).
    return out;
  }
  std::vector<double> c;
  for (long i = 0; i <= p.degree(); ++i)
    c.push_back(p.coeff(i).to_double_approx());
  bool finite = std::all_of(c.begin(), c.end(), [](double x) { return std::isfinite(x); });
  if (finite && c.back() != 0) {
    auto r = approx_real_roots(c, static_cast<size_t>(k));
    Rational bound = root_bound(p);
    std::vector<Rational> s{-bound};
    bool ok = true;
    for (size_t i = 0; i + 1 < r.size() && ok; ++i) {
      double mid = 0.5 * (r[i] + r[i + 1]);
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
  out = isolate_real_roots_cgal(p);
  out.used_fallback = true;
  if (!separators_certify(p, out.separators, k))
    throw std::logic_error("isolate_real_roots: CGAL separators failed the exact check");
  return out;
}

void refine_root(const UPolyZ& p, Rational& lo, Rational& hi, const Rational& width) {
  int slo = p.sign_at(lo);
  if (slo == 0) {
    hi = lo;
    return;
  }
  if (p.sign_at(hi) == 0) {
    lo = hi;
    return;
  }
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

} // namespace surfcert::algebra
