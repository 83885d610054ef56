// surfcert::certify::cone_oval_counts (see cone_ovals.hpp).
#include "surfcert/certify/cone_ovals.hpp"

#include "surfcert/algebra/conic_isotropy.hpp"
#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/kernel.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/upoly.hpp"

#include <flint/fmpz.h>
#include <flint/fmpz_poly.h>

#include <array>
#include <vector>

namespace surfcert::certify {

using core::Integer;
using core::Mat4;
using core::Rational;

namespace {

using V4 = std::array<Rational, 4>;
using algebra::UPolyQ;
using algebra::UPolyZ;

std::optional<Rational> rational_sqrt(const Rational& r) {
  if (r.sign() < 0) return std::nullopt;
  Integer n = r.num(), d = r.den();
  if (!fmpz_is_square(n.raw()) || !fmpz_is_square(d.raw())) return std::nullopt;
  Integer sn, sd;
  fmpz_sqrt(sn.raw_mut(), n.raw());
  fmpz_sqrt(sd.raw_mut(), d.raw());
  return Rational(sn, sd);
}

// Whether r is a square mod 64, 63, 65 and 11 (r = a value mod M = 64 * 63 * 65 * 11): an
// integer failing one of them is no square (the residues fmpz_is_square itself starts with,
// here on a machine word). Tables built at compile time.
constexpr unsigned long square_modulus = 64UL * 63 * 65 * 11;

template <unsigned long N> constexpr std::array<bool, N> squares_mod() {
  std::array<bool, N> t{};
  for (unsigned long x = 0; x < N; ++x)
    t[(x * x) % N] = true;
  return t;
}

bool maybe_square(unsigned long r) {
  static constexpr auto s64 = squares_mod<64>();
  static constexpr auto s63 = squares_mod<63>();
  static constexpr auto s65 = squares_mod<65>();
  static constexpr auto s11 = squares_mod<11>();
  return s64[r % 64] && s63[r % 63] && s65[r % 65] && s11[r % 11];
}

// The first (p, q) of the search order below (q = 1..40, p = -60..60) at which the integer
// quadratic form d(p, q) = A p^2 + B p q + C q^2 is a perfect square (>= 0), or nullopt. The
// discriminant of the search below is d(p, q) / (L q)^2 with integer A, B, C (the entries
// times a common denominator L), so it is a rational square exactly when d(p, q) is an
// integer one: the same first hit as testing the rational discriminants. A candidate whose
// d(p, q) mod M (machine words: A, B, C reduced mod M once) is no square mod M is skipped
// without forming d(p, q); the rest (~1%) are decided by fmpz_is_square. The conic of a
// randomly rotated cone (or of any cone given by doubles) rarely has a small point, and the
// 29,040 candidates of the six charts cost 1-3 ms in fmpz arithmetic per failed search: a
// third of a cone pair's time.
std::optional<std::pair<long, long>> first_square(const Integer& a, const Integer& b,
                                                  const Integer& c) {
  const unsigned long am = fmpz_fdiv_ui(a.raw(), square_modulus),
                      bm = fmpz_fdiv_ui(b.raw(), square_modulus),
                      cm = fmpz_fdiv_ui(c.raw(), square_modulus);
  Integer d, t;
  const unsigned long m = square_modulus;
  auto add_mod = [m](unsigned long x, unsigned long y) { // x, y < m
    const unsigned long z = x + y;
    return z >= m ? z - m : z;
  };
  const unsigned long a2 = add_mod(am, am);
  for (long q = 1; q <= 40; ++q) {
    // d(p, q) mod M along p by differences (two additions mod M a candidate instead of three
    // divisions): d(p + 1) - d(p) = A (2p + 1) + B q, whose own difference is 2A. Every
    // factor below M < 2^22: each product below 2^44, exact in a word.
    const auto qu = static_cast<unsigned long>(q);
    const auto p0 = static_cast<unsigned long>(-60 + static_cast<long>(m)); // p = -60 mod M
    const auto odd0 = static_cast<unsigned long>(2 * -60 + 1 + static_cast<long>(m));
    unsigned long v = (am * ((p0 * p0) % m) + bm * ((p0 * qu) % m) + cm * qu * qu) % m;
    unsigned long step = (am * odd0 + bm * qu) % m;
    for (long p = -60; p <= 60; ++p, v = add_mod(v, step), step = add_mod(step, a2)) {
      if (!maybe_square(v)) continue;
      fmpz_mul_si(d.raw_mut(), a.raw(), p * p);
      fmpz_mul_si(t.raw_mut(), b.raw(), p * q);
      fmpz_add(d.raw_mut(), d.raw(), t.raw());
      fmpz_mul_si(t.raw_mut(), c.raw(), q * q);
      fmpz_add(d.raw_mut(), d.raw(), t.raw());
      if (fmpz_sgn(d.raw()) >= 0 && fmpz_is_square(d.raw())) return std::make_pair(p, q);
    }
  }
  return std::nullopt;
}

// A rational point (x : y : z) != 0 of the conic x^T m x = 0 (3x3 block of k), by a bounded
// search: one coordinate 1, one a small fraction p/q, the last solved (a rational square root).
std::optional<std::array<Rational, 3>> conic_point(const Mat4& k) {
  // No rational point at all (proved by the Hilbert symbols): the search below could only fail,
  // after its 29,040 candidates (~190 us, 3% of the intersect bench in exact rationals).
  if (algebra::conic_has_rational_point(k) == std::optional<bool>(false)) return std::nullopt;
  for (size_t one = 0; one < 3; ++one)
    for (size_t free = 0; free < 3; ++free) {
      if (free == one) continue;
      const size_t solve = 3 - one - free;
      const Rational& a2 = k[solve][solve];
      // The candidate x_one = 1, x_free = p/q; nullopt when it gives no rational point.
      auto at = [&](long p, long q) -> std::optional<std::array<Rational, 3>> {
        std::array<Rational, 3> x;
        x[one] = Rational(1);
        x[free] = Rational(p, static_cast<unsigned long>(q));
        // m_ss y^2 + 2 (m_s,one + m_s,free x_free) y + (rest) = 0
        const Rational a1 = k[solve][one] + k[solve][free] * x[free];
        const Rational a0 =
            k[one][one] + Rational(2) * k[one][free] * x[free] + k[free][free] * x[free] * x[free];
        if (a2.is_zero()) {
          if (a1.is_zero()) return std::nullopt;
          x[solve] = -a0 / (Rational(2) * a1);
          return x;
        }
        const auto r = rational_sqrt(a1 * a1 - a2 * a0);
        if (!r) return std::nullopt;
        x[solve] = (-a1 + *r) / a2;
        return x;
      };
      if (!a2.is_zero()) {
        // (a1^2 - a2 a0) (L q)^2 as an integer form in p, q (L: the entries' common
        // denominator): a1 L q = s1 q + sf p, a0 L q^2 = o1 q^2 + 2 of p q + ff p^2.
        Integer l(1);
        for (const Rational* e : {&k[solve][solve], &k[solve][one], &k[solve][free], &k[one][one],
                                  &k[one][free], &k[free][free]})
          fmpz_lcm(l.raw_mut(), l.raw(), e->den().raw());
        auto integer = [&l](const Rational& e) {
          Integer r;
          fmpz_divexact(r.raw_mut(), l.raw(), e.den().raw());
          fmpz_mul(r.raw_mut(), r.raw(), e.num().raw());
          return r;
        };
        const Integer ss = integer(k[solve][solve]), s1 = integer(k[solve][one]),
                      sf = integer(k[solve][free]), o1 = integer(k[one][one]),
                      of = integer(k[one][free]), ff = integer(k[free][free]);
        const auto hit =
            first_square(sf * sf - ss * ff, Integer(2) * (s1 * sf - ss * of), s1 * s1 - ss * o1);
        if (!hit) continue;
        if (auto x = at(hit->first, hit->second)) return x;
      }
      for (long q = 1; q <= 40; ++q)
        for (long p = -60; p <= 60; ++p)
          if (auto x = at(p, q)) return x;
    }
  return std::nullopt;
}

// The square-free part, primitive, positive leading coefficient.
UPolyZ squarefree(const UPolyQ& p) {
  UPolyZ z = p.primitive_integer(), dz = z.derivative(), g, sq;
  fmpz_poly_gcd(g.raw_mut(), z.raw(), dz.raw());
  fmpz_poly_div(sq.raw_mut(), z.raw(), g.raw());
  return sq.primitive_part();
}

int sign_at(const UPolyQ& p, const Rational& x) {
  return p.evaluate(x).sign();
}

} // namespace

std::optional<std::pair<int, int>> cone_oval_counts(const Mat4& k, const Mat4& q, int ovals,
                                                    int points_at_infinity) {
  // Apex: the kernel of k, one rational point (k of rank 3).
  const auto ker = algebra::kernel_basis(k);
  if (ker.size() != 1) return std::nullopt;
  const V4 v = ker[0];
  const Rational a = algebra::bilinear(q, v, v);
  if (a.is_zero()) return std::nullopt; // the apex lies on the curve
  // The base plane Pi = {x_j = 0}, not through the apex: the plane at infinity for an affine
  // apex (then a point at infinity of the curve is a point of Pi: a root of c below); for an
  // apex at infinity (a cylinder) a coordinate plane x_j = 0 with v_j != 0 (then the
  // generators at infinity are those through a point of Pi at infinity: a root of P_w below).
  const bool affine_apex = !v[3].is_zero();
  size_t j = 3;
  if (!affine_apex) {
    j = 0;
    while (v[j].is_zero())
      ++j;
  }
  std::array<size_t, 3> idx{};
  for (size_t i = 0, n = 0; i < 4; ++i)
    if (i != j) idx[n++] = i;
  // k restricted to Pi (a regular conic: v is not in Pi), as the top-left block of a Mat4.
  Mat4 kp{};
  for (size_t r = 0; r < 3; ++r)
    for (size_t c = 0; c < 3; ++c)
      kp[r][c] = k[idx[r]][idx[c]];
  const auto p0 = conic_point(kp);
  if (!p0) return std::nullopt;
  V4 d0{};
  for (size_t i = 0; i < 3; ++i)
    d0[idx[i]] = (*p0)[i];
  // A complement e1, e2 of d0 in Pi (unit vectors), sheared until no form has a root at
  // t = infinity.
  size_t big = 0;
  while (d0[idx[big]].is_zero())
    ++big;
  std::vector<V4> units;
  for (size_t i = 0; i < 3; ++i)
    if (i != big) {
      V4 e{};
      e[idx[i]] = Rational(1);
      units.push_back(e);
    }
  for (long shear = 0; shear <= 6; ++shear) {
    V4 e1 = units[0], e2 = units[1];
    for (size_t i = 0; i < 4; ++i)
      e2[i] += Rational(shear) * e1[i];
    // e(t) = e1 + t e2; d(t) = -(e.K.e) d0 + 2 (d0.K.e) e: a point of K's conic in Pi,
    // quadratic in t; the generators are the lines (s2 v + s1 d(t)).
    std::array<UPolyQ, 4> dt;
    const Rational k11 = algebra::bilinear(k, e1, e1), k12 = algebra::bilinear(k, e1, e2),
                   k22 = algebra::bilinear(k, e2, e2);
    const UPolyQ eke = UPolyQ::from_coeffs({k11, Rational(2) * k12, k22});
    const UPolyQ dke =
        UPolyQ::from_coeffs({algebra::bilinear(k, d0, e1), algebra::bilinear(k, d0, e2)});
    for (size_t i = 0; i < 4; ++i) {
      const UPolyQ ei = UPolyQ::from_coeffs({e1[i], e2[i]});
      dt[i] = UPolyQ(Rational(0)) - eke * UPolyQ(d0[i]) + UPolyQ(2) * dke * ei;
    }
    UPolyQ b, c;
    for (size_t i = 0; i < 4; ++i) {
      Rational vq;
      for (size_t jj = 0; jj < 4; ++jj)
        vq += v[jj] * q[jj][i];
      b = b + UPolyQ(vq) * dt[i];
      for (size_t jj = 0; jj < 4; ++jj)
        if (!q[i][jj].is_zero()) c = c + UPolyQ(q[i][jj]) * dt[i] * dt[jj];
    }
    // On the generator t the curve is a s2^2 + 2 b(t) s1 s2 + c(t) s1^2 = 0.
    const UPolyQ disc = b * b - UPolyQ(a) * c;
    if (disc.degree() != 4) continue;
    // The marker of the points at infinity: c (affine apex: the curve's point s2 = 0 lies in
    // Pi, at infinity) or P_w = dt[3] (apex at infinity: the generator lies at infinity, and
    // both its curve points with it; disc > 0 there for two distinct real ones).
    const UPolyQ& mark = affine_apex ? c : dt[3];
    if (affine_apex ? (b.degree() != 2 || c.degree() != 4) : mark.degree() != 2) continue;
    const UPolyZ sd = squarefree(disc), sc = squarefree(mark);
    auto coprime = [](const UPolyZ& x, const UPolyZ& y) {
      UPolyZ g;
      fmpz_poly_gcd(g.raw_mut(), x.raw(), y.raw());
      return g.degree() == 0;
    };
    UPolyZ sb = UPolyZ::from_coeffs({Integer(1)});
    if (affine_apex) sb = squarefree(b);
    if (!coprime(sb, sc) || !coprime(sb, sd) || !coprime(sc, sd))
      return std::nullopt; // a common root of b, c, disc: a singular point (or a tangency)
    UPolyZ prod, tmp;
    fmpz_poly_mul(tmp.raw_mut(), sb.raw(), sc.raw());
    fmpz_poly_mul(prod.raw_mut(), tmp.raw(), sd.raw());
    const algebra::RootSeparation sep = algebra::isolate_real_roots(prod.primitive_part());
    const auto& s = sep.separators;
    const size_t n = sep.num_roots();
    // Each root attributed to the factor changing sign across its gap.
    enum Kind { D, C, B };
    std::vector<Kind> kind(n);
    for (size_t i = 0; i < n; ++i) {
      const bool in_d = sd.sign_at(s[i]) * sd.sign_at(s[i + 1]) < 0;
      const bool in_c = sc.sign_at(s[i]) * sc.sign_at(s[i + 1]) < 0;
      const bool in_b = sb.sign_at(s[i]) * sb.sign_at(s[i + 1]) < 0;
      if (in_d + in_c + in_b != 1) return std::nullopt;
      kind[i] = in_d ? D : in_c ? C : B;
    }
    // Distinct real points at infinity: one per root of c (affine apex); two per root of P_w
    // where disc > 0, none where disc < 0 (apex at infinity).
    int croots = 0;
    for (size_t i = 0; i < n; ++i) {
      if (kind[i] != C) continue;
      if (affine_apex) {
        ++croots;
        continue;
      }
      const int sg = sign_at(disc, s[i]); // disc has no root in [s_i, root]
      if (sg == 0) return std::nullopt;
      croots += sg > 0 ? 2 : 0;
    }
    if (croots != points_at_infinity) return std::nullopt;
    std::vector<size_t> droots;
    for (size_t i = 0; i < n; ++i)
      if (kind[i] == D) droots.push_back(i);
    int found_ovals = 0, through_infinity = 0;
    if (droots.empty()) {
      if (sign_at(disc, s[0]) <= 0) return std::nullopt; // no real curve
      found_ovals = 2;
      if (affine_apex) {
        bool plus = false, minus = false;
        for (size_t i = 0; i < n; ++i)
          if (kind[i] == C) (sign_at(b, s[i]) < 0 ? plus : minus) = true;
        through_infinity = (plus ? 1 : 0) + (minus ? 1 : 0);
      } else {
        // A generator at infinity carries one point of each sheet.
        through_infinity = croots > 0 ? 2 : 0;
      }
    } else {
      // Arcs of P^1 between consecutive roots of disc (cyclically, through infinity).
      const size_t m = droots.size();
      for (size_t jj = 0; jj < m; ++jj) {
        const size_t from = droots[jj], to = droots[(jj + 1) % m];
        if (sign_at(disc, s[from + 1]) <= 0) continue; // disc < 0 just after this root
        ++found_ovals;
        // Through infinity iff a root of the marker lies on the arc. (Affine apex: a root of
        // b alone cannot: where b = 0 on the arc, disc = -a c > 0, while b^2 = a c > 0 at the
        // arc's ends, so c changes sign in between; testing for any root at all would answer
        // the same.)
        bool any = false;
        for (size_t i = (from + 1) % n; i != to; i = (i + 1) % n)
          any = any || kind[i] == C;
        through_infinity += any ? 1 : 0;
      }
    }
    if (found_ovals != ovals) return std::nullopt;
    return std::pair<int, int>{ovals - through_infinity, points_at_infinity};
  }
  return std::nullopt;
}

} // namespace surfcert::certify
