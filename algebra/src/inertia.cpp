#include "surfcert/algebra/inertia.hpp"

#include "surfcert/algebra/upoly.hpp"

#include <flint/fmpq_mat.h>
#include <flint/fmpz_mat.h>

#include <array>
#include <cmath>

namespace surfcert::algebra {

using core::Mat4;

static int variations(const int* s, int n) {
  int v = 0, prev = 0;
  for (int i = 0; i < n; ++i) {
    if (s[i] == 0) continue;
    if (prev != 0 && s[i] != prev) ++v;
    prev = s[i];
  }
  return v;
}

Inertia inertia_from_charpoly_signs(const int s[4]) {
  // Coefficients from the leading one: 1, c3, c2, c1, c0; for chi(-mu): 1, -c3, c2, -c1, c0.
  int pos[5] = {1, s[3], s[2], s[1], s[0]};
  int neg[5] = {1, -s[3], s[2], -s[1], s[0]};
  return Inertia{variations(pos, 5), variations(neg, 5)};
}

void scaled_integer_matrix(fmpz_mat_t out, const Mat4& m) {
  core::Integer l(1);
  for (const auto& row : m)
    for (const auto& v : row)
      fmpz_lcm(l.raw_mut(), l.raw(), fmpq_denref(v.raw()));
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      fmpz* e = fmpz_mat_entry(out, static_cast<slong>(i), static_cast<slong>(j));
      fmpz_divexact(e, l.raw(), fmpq_denref(m[i][j].raw()));
      fmpz_mul(e, e, fmpq_numref(m[i][j].raw()));
    }
}

Inertia inertia_descartes(const Mat4& m) {
  fmpz_mat_t z;
  fmpz_mat_init(z, 4, 4);
  scaled_integer_matrix(z, m); // a positive factor keeps the signs of the eigenvalues
  fmpz_poly_t cp;
  fmpz_poly_init(cp);
  // Berkowitz (division-free, O(n^4) ring operations) rather than FLINT's default multimodular
  // charpoly: for a 4x4 matrix the latter spends most of its time generating primes when the
  // entries are large (a sphere of radius 1e-320 gives ~2000-bit entries), the former a few
  // dozen big-integer products. The polynomial is the same exact one either way.
  fmpz_mat_charpoly_berkowitz(cp, z);
  int s[4];
  for (slong k = 0; k < 4; ++k) {
    fmpz_t c;
    fmpz_init(c);
    fmpz_poly_get_coeff_fmpz(c, cp, k);
    s[k] = fmpz_sgn(c);
    fmpz_clear(c);
  }
  fmpz_poly_clear(cp);
  fmpz_mat_clear(z);
  return inertia_from_charpoly_signs(s);
}

Inertia inertia_ldlt(const Mat4& m0) {
  Mat4 m = m0;
  Inertia r;
  bool active[4] = {true, true, true, true};
  for (int step = 0; step < 4; ++step) {
    int piv = -1;
    for (int i = 0; i < 4 && piv < 0; ++i)
      if (active[i] && !m[static_cast<size_t>(i)][static_cast<size_t>(i)].is_zero()) piv = i;
    if (piv < 0) {
      // All active diagonal entries vanish: a nonzero off-diagonal m_ij lets the congruence
      // e_i <- e_i + e_j create the diagonal entry 2 m_ij != 0.
      int pi = -1, pj = -1;
      for (int i = 0; i < 4 && pi < 0; ++i)
        for (int j = 0; j < 4; ++j)
          if (i != j && active[i] && active[j] &&
              !m[static_cast<size_t>(i)][static_cast<size_t>(j)].is_zero()) {
            pi = i;
            pj = j;
            break;
          }
      if (pi < 0) break; // the remaining block is zero
      auto I = static_cast<size_t>(pi), J = static_cast<size_t>(pj);
      for (size_t k = 0; k < 4; ++k)
        m[I][k] += m[J][k]; // row i += row j
      for (size_t k = 0; k < 4; ++k)
        m[k][I] += m[k][J]; // column i += column j
      piv = pi;
    }
    auto P = static_cast<size_t>(piv);
    Rational d = m[P][P];
    (d.sign() > 0 ? r.p : r.n)++;
    active[piv] = false;
    for (size_t i = 0; i < 4; ++i) {
      if (!active[i] || m[i][P].is_zero()) continue;
      Rational f = m[i][P] / d;
      for (size_t j = 0; j < 4; ++j)
        if (active[j]) m[i][j] -= f * m[P][j];
    }
    for (size_t i = 0; i < 4; ++i)
      m[i][P] = m[P][i] = Rational(0);
  }
  return r;
}

int rank_exact(const Mat4& m) {
  fmpq_mat_t t;
  fmpq_mat_init(t, 4, 4);
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      fmpq_set(fmpq_mat_entry(t, static_cast<slong>(i), static_cast<slong>(j)), m[i][j].raw());
  fmpq_mat_t e;
  fmpq_mat_init(e, 4, 4);
  int r = static_cast<int>(fmpq_mat_rref(e, t));
  fmpq_mat_clear(e);
  fmpq_mat_clear(t);
  return r;
}

QuadraticNumber quadratic_add(const QuadraticNumber& x, const QuadraticNumber& y, int s) {
  return {x.a + Rational(s) * y.a, x.b + Rational(s) * y.b, x.d};
}

QuadraticNumber quadratic_mul(const QuadraticNumber& x, const QuadraticNumber& y) {
  const Rational dd(x.d);
  return {x.a * y.a + x.b * y.b * dd, x.a * y.b + x.b * y.a, x.d};
}

QuadraticNumber quadratic_div(const QuadraticNumber& x, const QuadraticNumber& y) {
  const Rational dd(x.d);
  // y.a^2 - y.b^2 d != 0: y != 0 and d is not a square (or y.b = 0).
  const Rational n = y.a * y.a - y.b * y.b * dd;
  const QuadraticNumber p = quadratic_mul(x, {y.a, -y.b, x.d});
  return {p.a / n, p.b / n, x.d};
}

int QuadraticNumber::sign() const {
  int sa = a.sign(), sb = b.sign();
  if (sb == 0 || d.is_zero()) return sa;
  if (sa == 0) return sb;
  if (sa == sb) return sa;
  // a and b*sqrt(d) have opposite signs: compare a^2 with b^2 d.
  Rational diff = a * a - b * b * Rational(d);
  return sa * diff.sign();
}

namespace {

// The primes below 2000 (303 of them), sieved at compile time.
constexpr std::array<unsigned long, 303> small_primes() {
  std::array<bool, 2000> composite{};
  std::array<unsigned long, 303> out{};
  size_t n = 0;
  for (unsigned long p = 2; p < 2000; ++p) {
    if (composite[p]) continue;
    out[n++] = p;
    for (unsigned long m = p * p; m < 2000; m += p)
      composite[m] = true;
  }
  return out;
}

// The primes in runs whose products fit a machine word (greedy, in order): one remainder of d
// per run instead of one per prime. kRuns[k] = (first index, product).
struct PrimeRun {
  size_t first = 0;
  unsigned long product = 1;
};
constexpr size_t kRunCount = [] {
  size_t n = 1;
  unsigned long prod = 1;
  for (const unsigned long p : small_primes()) {
    if (prod > ~0UL / p) ++n, prod = 1;
    prod *= p;
  }
  return n;
}();
constexpr std::array<PrimeRun, kRunCount> prime_runs() {
  std::array<PrimeRun, kRunCount> out{};
  size_t n = 0;
  const auto primes = small_primes();
  for (size_t i = 0; i < primes.size(); ++i) {
    if (out[n].product > ~0UL / primes[i]) out[++n].first = i;
    out[n].product *= primes[i];
  }
  return out;
}

// Divisibility of a word by each odd prime without a division: p | r exactly when
// r * p^-1 mod 2^64 <= (2^64 - 1) / p (p^-1 the inverse of p modulo 2^64).
struct WordDivisor {
  unsigned long inverse = 0, limit = 0;
};
constexpr std::array<WordDivisor, 303> word_divisors() {
  std::array<WordDivisor, 303> out{};
  const auto primes = small_primes();
  for (size_t i = 0; i < primes.size(); ++i) {
    const unsigned long p = primes[i];
    if (p % 2 == 0) continue; // 2: the low bit
    unsigned long x = p;      // p * p == 1 mod 8: correct to 3 bits, doubled per step
    for (int k = 0; k < 5; ++k)
      x *= 2 - p * x;
    out[i] = {x, ~0UL / p};
  }
  return out;
}
constexpr bool inverses_hold() {
  const auto primes = small_primes();
  const auto d = word_divisors();
  for (size_t i = 1; i < primes.size(); ++i)
    if (primes[i] * d[i].inverse != 1) return false;
  return true;
}
static_assert(inverses_hold(), "p * p^-1 == 1 mod 2^64 for every odd prime below 2000");

} // namespace

QuadraticNumber::SquareSplit square_split(const core::Integer& d) {
  // The square factors p^2 of d for the primes p < 2000 moved out of the root (a composite's
  // square divides no more once its primes' are out), then a perfect square rest. Only the
  // primes dividing d are tried, found from one remainder of d per run of primes (a word) by
  // a multiplication each (a remainder of d for each of the 303 was a sixth of a cone-plane
  // pair's instructions).
  static constexpr auto primes = small_primes();
  static constexpr auto runs = prime_runs();
  static constexpr auto divisors = word_divisors();
  core::Integer out(1), rest = d;
  // The powers of 2 at once, by shifts: the radicands of surfaces posed in doubles carry a
  // denominator 2^k (sqrt(p / q) = sqrt(p q) / q), and dividing 4 out ~k / 2 times, each a pass
  // over a number of hundreds of bits, was a third of this function on a cone-plane pair.
  if (!rest.is_zero()) {
    const flint_bitcnt_t v = fmpz_val2(rest.raw());
    if (v >= 2) {
      fmpz_fdiv_q_2exp(rest.raw_mut(), rest.raw(), v - v % 2);
      fmpz_mul_2exp(out.raw_mut(), out.raw(), v / 2);
    }
  }
  for (size_t k = 0; k < runs.size(); ++k) {
    // p divides d exactly when it divides d mod (the run's product).
    const unsigned long m = fmpz_fdiv_ui(rest.raw(), runs[k].product);
    const size_t end = k + 1 < runs.size() ? runs[k + 1].first : primes.size();
    for (size_t i = runs[k].first; i < end; ++i) {
      const unsigned long p = primes[i];
      const bool divides = p == 2 ? (m & 1) == 0 : m * divisors[i].inverse <= divisors[i].limit;
      if (!divides) continue;
      while (fmpz_fdiv_ui(rest.raw(), p * p) == 0) {
        fmpz_divexact_ui(rest.raw_mut(), rest.raw(), p * p);
        fmpz_mul_ui(out.raw_mut(), out.raw(), p);
      }
    }
  }
  core::Integer s;
  fmpz_sqrt(s.raw_mut(), rest.raw());
  if (s * s == rest) {
    out = out * s;
    rest = core::Integer(1);
  }
  return {out, rest};
}

QuadraticNumber QuadraticNumber::normalized() const {
  if (b.is_zero() || d.sign() <= 0) return *this;
  return normalized(square_split(d));
}

QuadraticNumber QuadraticNumber::normalized(const SquareSplit& split) const {
  QuadraticNumber r = *this;
  if (r.b.is_zero() || r.d.sign() <= 0) return r;
  r.b = r.b * Rational(split.square);
  r.d = split.rest;
  if (split.rest == core::Integer(1)) {
    r.a = r.a + r.b;
    r.b = Rational(0);
  }
  return r;
}

double QuadraticNumber::to_double_approx() const {
  return a.to_double_approx() + b.to_double_approx() * std::sqrt(d.to_double_approx());
}

std::string QuadraticNumber::to_string() const {
  if (b.is_zero() || d.is_zero()) return a.to_string();
  std::string s = a.is_zero() ? "" : a.to_string() + (b.sign() < 0 ? " - " : " + ");
  if (a.is_zero() && b.sign() < 0) s += "-";
  Rational mb = core::abs(b);
  if (mb != Rational(1)) s += mb.to_string() + "*";
  return s + "sqrt(" + d.to_string() + ")";
}

} // namespace surfcert::algebra
