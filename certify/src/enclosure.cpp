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

// The matrix of a posed shape, in intervals, by the same formula as core::posed_quadric_matrix:
// M = T^T L T with T = [[R^T, -R^T c], [0, 1]] and R the quaternion's rotation over |q|^2.
IMat4 enclose_shape(const core::ShapeSpec& s) {
  const core::LocalForm f = core::local_form(s.type);
  IMat4 local;
  for (auto& row : local)
    row.fill(I(0));
  for (size_t i = 0; i < 3; ++i)
    if (f.q_sign[i] != 0) {
      const I r(s.radii[i]);
      const I q = I(1) / (r * r);
      local[i][i] = f.q_sign[i] > 0 ? q : -q;
    }
  local[2][3] = local[3][2] = I(0.5 * f.linear_z);
  local[3][3] = I(f.constant);
  // inv = R^-1 = R^T.
  std::array<std::array<I, 3>, 3> inv;
  if (s.rotated) {
    const I w(s.quaternion[0]), x(s.quaternion[1]), y(s.quaternion[2]), z(s.quaternion[3]);
    // Each product and partial sum once: the same operations on the same operands as the
    // textbook formula (w*w + x*x - y*y - z*z and so on, left to right), so the same intervals
    // (the compiler cannot share them itself: interval operations are opaque to it).
    const I ww = w * w, xx = x * x, yy = y * y, zz = z * z;
    const I xy = x * y, wz = w * z, xz = x * z, wy = w * y, yz = y * z, wx = w * x;
    const I ww_p_xx = ww + xx, ww_m_xx = ww - xx;
    const I n = ww_p_xx + yy + zz;
    const I two(2);
    const std::array<std::array<I, 3>, 3> r = {
        {{ww_p_xx - yy - zz, two * (xy - wz), two * (xz + wy)},
         {two * (xy + wz), ww_m_xx + yy - zz, two * (yz - wx)},
         {two * (xz - wy), two * (yz + wx), ww_m_xx - yy + zz}}};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        inv[i][j] = r[j][i] / n;
  } else {
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        inv[i][j] = I(i == j ? 1 : 0);
  }
  // T = [[R^T, tc], [0, 1]] with tc = -R^T c; L = [[diag(d), l], [l^T, k]] with l = (0, 0, h).
  // The products below are those of the plain 4x4 formulas M = T^T (L T) without the terms
  // that are exact zeros (T's last row, L's zero entries), summed in the same order: adding an
  // exact zero changes no interval, so the enclosure is the same, at a third of the cost.
  std::array<I, 3> tc;
  for (size_t i = 0; i < 3; ++i) {
    I acc(0);
    for (size_t j = 0; j < 3; ++j)
      acc += inv[i][j] * I(s.center[j]);
    tc[i] = -acc;
  }
  const I h = local[2][3], k = local[3][3];
  // lt = L T.
  std::array<std::array<I, 4>, 4> lt;
  for (size_t i = 0; i < 3; ++i) {
    const I& d = local[i][i];
    for (size_t j = 0; j < 3; ++j)
      lt[i][j] = d * inv[i][j];
    lt[i][3] = d * tc[i];
  }
  lt[2][3] += h; // h * T[3][3] = h
  for (size_t j = 0; j < 3; ++j)
    lt[3][j] = h * inv[2][j];
  lt[3][3] = h * tc[2] + k;
  // Symmetric by construction: compute the upper triangle once and mirror it, so the
  // enclosure is exactly symmetric as the exact matrix is.
  IMat4 m;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = i; j < 4; ++j) {
      I acc(0);
      for (size_t q = 0; q < 3; ++q)
        acc += inv[q][i] * lt[q][j];
      m[i][j] = m[j][i] = acc;
    }
  I acc(0);
  for (size_t q = 0; q < 3; ++q)
    acc += tc[q] * lt[q][3];
  m[3][3] = acc + lt[3][3];
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

} // namespace surfcert::certify
