// surfcert::algebra::conic_has_rational_point (see conic_isotropy.hpp).
#include "surfcert/algebra/conic_isotropy.hpp"

#include <flint/fmpz.h>
#include <flint/fmpz_factor.h>

#include <array>
#include <vector>

namespace surfcert::algebra {

using core::Integer;

namespace {

// The odd primes dividing x (x != 0), by FLINT's factorisation.
void odd_primes(const Integer& x, std::vector<Integer>& out) {
  fmpz_factor_t f;
  fmpz_factor_init(f);
  fmpz_factor(f, x.raw());
  for (slong i = 0; i < f->num; ++i)
    if (!fmpz_equal_ui(f->p + i, 2)) {
      Integer p;
      fmpz_set(p.raw_mut(), f->p + i);
      out.push_back(p);
    }
  fmpz_factor_clear(f);
}

// x = p^e u with u prime to p (x != 0).
unsigned long split_off(const Integer& x, const Integer& p, Integer& u) {
  u = x;
  unsigned long e = 0;
  while (true) {
    Integer q, rem;
    fmpz_fdiv_qr(q.raw_mut(), rem.raw_mut(), u.raw(), p.raw());
    if (!rem.is_zero()) return e;
    u = q;
    ++e;
  }
}

// The Legendre symbol (u | p), p an odd prime not dividing u: +1 or -1.
int legendre(const Integer& u, const Integer& p) {
  Integer r;
  fmpz_mod(r.raw_mut(), u.raw(), p.raw());
  return fmpz_jacobi(r.raw(), p.raw());
}

// (a, b)_p for an odd prime p (Serre III.1.2 Theorem 1).
int hilbert_odd(const Integer& a, const Integer& b, const Integer& p) {
  Integer u, v;
  const unsigned long al = split_off(a, p, u), be = split_off(b, p, v);
  int s = 1;
  // (-1)^(al be eps(p)), eps(p) = (p - 1) / 2 mod 2.
  if ((al & be & 1) && fmpz_fdiv_ui(p.raw(), 4) == 3) s = -s;
  if ((be & 1) && legendre(u, p) < 0) s = -s;
  if ((al & 1) && legendre(v, p) < 0) s = -s;
  return s;
}

// (a, b)_2: (-1)^(eps(u) eps(v) + al omega(v) + be omega(u)), a = 2^al u, b = 2^be v.
int hilbert_two(const Integer& a, const Integer& b) {
  Integer u, v;
  const Integer two(2);
  const unsigned long al = split_off(a, two, u), be = split_off(b, two, v);
  const unsigned long u8 = fmpz_fdiv_ui(u.raw(), 8), v8 = fmpz_fdiv_ui(v.raw(), 8);
  auto eps = [](unsigned long w) { return ((w - 1) / 2) & 1; };       // w odd, mod 8
  auto omega = [](unsigned long w) { return ((w * w - 1) / 8) & 1; }; // w odd, mod 8
  const unsigned long e = eps(u8) * eps(v8) + (al & 1) * omega(v8) + (be & 1) * omega(u8);
  return (e & 1) ? -1 : 1;
}

} // namespace

std::optional<bool> conic_has_rational_point(const core::Mat4& m4, long max_bits) {
  core::Mat4 sub{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      sub[i][j] = m4[i][j];
  const core::Mat4 mi = core::integer_multiple(sub);
  std::array<std::array<Integer, 3>, 3> m;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      m[i][j] = mi[i][j].num();
  for (size_t i = 0; i < 3; ++i)
    if (m[i][i].is_zero()) return true; // e_i is a point
  // M00 q = (M00 x0 + M01 x1 + M02 x2)^2 + [x1 x2] S [x1 x2]^T, S_ij = M00 M_ij - M0i M0j.
  const Integer s11 = m[0][0] * m[1][1] - m[0][1] * m[0][1];
  const Integer s12 = m[0][0] * m[1][2] - m[0][1] * m[0][2];
  const Integer s22 = m[0][0] * m[2][2] - m[0][2] * m[0][2];
  if (s11.is_zero()) return true; // (x1, x2) = (1, 0) completes a point
  const Integer d = s11 * s22 - s12 * s12;
  if (d.is_zero()) return std::nullopt; // a degenerate conic
  // <1, S11, D> isotropic iff (-S11, -D)_v = 1 everywhere.
  const Integer a = -s11, b = -d;
  if (a.sign() < 0 && b.sign() < 0) return false; // no real point
  if (static_cast<long>(fmpz_bits(a.raw())) > max_bits ||
      static_cast<long>(fmpz_bits(b.raw())) > max_bits)
    return std::nullopt;
  std::vector<Integer> primes;
  odd_primes(a, primes);
  odd_primes(b, primes);
  for (const Integer& p : primes)
    if (hilbert_odd(a, b, p) < 0) return false;
  if (hilbert_two(a, b) < 0) return false;
  return true;
}

} // namespace surfcert::algebra
