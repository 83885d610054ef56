// Compiled with -frounding-math -ffp-contract=off (see the top-level CMakeLists):
// CGAL::Interval_nt relies on them.
#include "surfcert/certify/enclosure.hpp"

#include "surfcert/algebra/arb.hpp"

#include <CGAL/FPU.h>

#include <array>
#include <cmath>
#include <cstring>

namespace surfcert::certify {

namespace {

using I = Interval;

// Interval enclosing an integer: exact when it has at most 53 bits, else its two directed
// roundings (Arb rounds correctly, also past the double range: then a bound is infinite and
// the filter simply fails, handing the decision to the exact path).
I enclose_integer(const fmpz* z) {
  if (fmpz_bits(z) <= 53) return I(fmpz_get_d(z));
  algebra::Arf a;
  arf_set_fmpz(a.v, z);
  return I(arf_get_d(a.v, ARF_RND_FLOOR), arf_get_d(a.v, ARF_RND_CEIL));
}

// The matrix of a posed shape, in intervals: the exact matrix of core::posed_quadric_matrix,
// M = T^T L T with T = [[S, -S c], [0, 1]], S = R^T = Q^T / n the inverse of the quaternion's
// rotation (Q the textbook matrix of the unnormalised quaternion, n = |q|^2) and
// L = [[D, l], [l^T, k]], D = diag(d), l = (0, 0, h), expanded so that n is divided once per
// radius instead of once per rotation entry:
//   M_ij = sum_q Q_iq (d_q / n^2) Q_jq                 (i, j < 3; the block A = S^T D S),
//   M_i3 = -(A c)_i + h S_2i,   M_33 = c^T A c + 2 h (-S c)_2 + k.
// Every operation is an interval one on enclosures of exact values, so each entry encloses the
// exact one (not the same intervals as the plain 4x4 product, only as rigorous).
IMat4 enclose_shape(const core::ShapeSpec& s) {
  const core::LocalForm f = core::local_form(s.type);
  // qt[q][i] = n S_qi = Q_iq: the transposed textbook matrix (the identity when unrotated).
  std::array<std::array<I, 3>, 3> qt;
  I n(1);
  if (s.rotated) {
    const double wd = s.quaternion[0], xd = s.quaternion[1], yd = s.quaternion[2],
                 zd = s.quaternion[3];
    const I w(wd), x(xd), y(yd), z(zd);
    // Each product once (interval operations are opaque to the compiler), by a double operand
    // where one is a double (CGAL's cheaper interval * double); 2 t as t + t (exact).
    const I ww = w * wd, xx = x * xd, yy = y * yd, zz = z * zd;
    const I xy = x * yd, wz = w * zd, xz = x * zd, wy = w * yd, yz = y * zd, wx = w * xd;
    const I ww_p_xx = ww + xx, ww_m_xx = ww - xx;
    n = ww_p_xx + yy + zz;
    auto twice = [](const I& t) { return t + t; };
    const std::array<std::array<I, 3>, 3> r = {
        {{ww_p_xx - yy - zz, twice(xy - wz), twice(xz + wy)},
         {twice(xy + wz), ww_m_xx + yy - zz, twice(yz - wx)},
         {twice(xz - wy), twice(yz + wx), ww_m_xx - yy + zz}}};
    for (size_t q = 0; q < 3; ++q)
      for (size_t i = 0; i < 3; ++i)
        qt[q][i] = r[i][q];
  } else {
    for (size_t q = 0; q < 3; ++q)
      for (size_t i = 0; i < 3; ++i)
        qt[q][i] = I(q == i ? 1 : 0);
  }
  const I n2 = n * n;
  // dq[q][j] = (d_q / n^2) Q_jq, d_q = +-1 / r_q^2 (0 for an absent term).
  std::array<std::array<I, 3>, 3> dq;
  for (size_t q = 0; q < 3; ++q) {
    I d(0);
    if (f.q_sign[q] != 0) {
      const I r(s.radii[q]);
      const I v = I(1) / (r * r * n2);
      d = f.q_sign[q] > 0 ? v : -v;
    }
    for (size_t j = 0; j < 3; ++j)
      dq[q][j] = d * qt[q][j];
  }
  // Symmetric by construction: the upper triangle once, mirrored, so the enclosure is exactly
  // symmetric as the exact matrix is.
  IMat4 m;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = i; j < 3; ++j) {
      I acc = qt[0][i] * dq[0][j];
      for (size_t q = 1; q < 3; ++q)
        acc += qt[q][i] * dq[q][j];
      m[i][j] = m[j][i] = acc;
    }
  const std::array<double, 3>& c = s.center;
  I ctac(0); // c^T A c
  for (size_t i = 0; i < 3; ++i) {
    I ac = m[i][0] * c[0];
    for (size_t j = 1; j < 3; ++j)
      ac += m[i][j] * c[j];
    m[i][3] = -ac;
    ctac += ac * c[i];
  }
  m[3][3] = ctac + I(f.constant);
  if (f.linear_z != 0) { // h = linear_z / 2: the terms h S_2i and 2 h (-S c)_2 = -linear_z (S c)_2
    const I h(0.5 * f.linear_z), inv_n = I(1) / n;
    I sc2(0); // (S c)_2 = sum_j S_2j c_j
    for (size_t j = 0; j < 3; ++j) {
      const I s2j = qt[2][j] * inv_n; // S_2j = Q_j2 / n
      m[j][3] += h * s2j;
      sc2 += s2j * c[j];
    }
    m[3][3] -= I(f.linear_z) * sc2;
  }
  for (size_t i = 0; i < 3; ++i)
    m[3][i] = m[i][3];
  return m;
}

bool same_shape(const core::ShapeSpec& a, const core::ShapeSpec& b) {
  // Bit for bit (-0.0 and 0.0 apart): equal specs give equal enclosures.
  auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  return a.type == b.type && a.rotated == b.rotated && same(a.radii, b.radii) &&
         same(a.center, b.center) && same(a.quaternion, b.quaternion);
}

// A line's decision encloses the same two shapes more than once (the pencil filter, then the
// ellipsoid relation): this thread's last few enclosures, keyed by the shape's value, so that
// a different shape (even at a reused address) never gets another's enclosure.
IMat4 enclose_shape_cached(const core::ShapeSpec& s) {
  struct Entry {
    core::ShapeSpec spec;
    IMat4 m;
    bool used = false;
  };
  thread_local std::array<Entry, 4> cache;
  thread_local size_t next = 0;
  for (const Entry& e : cache)
    if (e.used && same_shape(e.spec, s)) return e.m;
  Entry& e = cache[next++ % cache.size()];
  e.spec = s;
  e.m = enclose_shape(s);
  e.used = true;
  return e.m;
}

} // namespace

I enclose(const core::Rational& x) {
  I n = enclose_integer(fmpq_numref(x.raw()));
  if (fmpz_is_one(fmpq_denref(x.raw()))) return n;
  return n / enclose_integer(fmpq_denref(x.raw()));
}

IMat4 enclose(const core::QuadricMatrix& q) {
  if (const core::ShapeSpec* s = q.shape()) return enclose_shape_cached(*s);
  if (const core::DoubleMat4* d = q.double_matrix()) {
    // The symmetric part (d_ij + d_ji) / 2: exact where d_ij = d_ji, else the interval sum
    // (directed rounding; an overflow gives an infinite bound) times the exact 1/2.
    IMat4 m;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j) {
        const double x = (*d)[i][j], y = (*d)[j][i];
        m[i][j] = m[j][i] = x == y ? I(x) : (I(x) + I(y)) * I(0.5);
      }
    return m;
  }
  IMat4 m;
  const core::Mat4& e = q.matrix();
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j)
      m[i][j] = m[j][i] = enclose(e[i][j]);
  return m;
}

algebra::Mat4T<double> approx(const core::QuadricMatrix& q) {
  algebra::Mat4T<double> out;
  if (!q.shape()) { // the exact entries' quotients of doubles (float mode's reading so far)
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        const core::Rational& e = q.matrix()[i][j];
        out[i][j] = fmpz_get_d(fmpq_numref(e.raw())) / fmpz_get_d(fmpq_denref(e.raw()));
      }
    return out;
  }
  CGAL::Protect_FPU_rounding<true> guard;
  const IMat4 m = enclose(q);
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      const double lo = m[i][j].inf(), hi = m[i][j].sup();
      out[i][j] = std::isfinite(lo) && std::isfinite(hi) ? lo + (hi - lo) / 2
                  : std::isfinite(lo)                    ? lo
                                                         : hi;
    }
  return out;
}

bool approx_is_exact(const core::QuadricMatrix& q) {
  if (q.shape()) return false;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j) {
      const core::Rational& e = q.matrix()[i][j];
      const fmpz* num = fmpq_numref(e.raw());
      const fmpz* den = fmpq_denref(e.raw());
      if (fmpz_is_zero(num)) continue;
      // num / den is a double when den = 2^k and num has at most 53 significant bits, and
      // approx's quotient of the two doubles is then that double unless it leaves the normal
      // range (or den does not convert: k > 1023).
      const flint_bitcnt_t k = fmpz_bits(den) - 1;
      if (fmpz_val2(den) != k || k > 1000 || fmpz_bits(num) - fmpz_val2(num) > 53 ||
          fmpz_bits(num) > 1000)
        return false;
    }
  return true;
}

} // namespace surfcert::certify
