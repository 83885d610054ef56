// surfcert::algebra closed forms for a 4x4 pencil, generic in the number type.
//
// pencil_char_coeffs: the coefficients (constant term first) of f(l) = det(l*A - B) by a
// Laplace expansion over the 2x2 minors of rows {0,1} and {2,3}. quartic_invariants: the
// quantities D2, D3, D4 (= discriminant), E of seed 002 Lemma 1 (research §3.1).
// charpoly_coeffs: c3..c0 of det(mu*I - M) for a symmetric 4x4 M.
// The template is instantiated for exact integers (core::Integer), for interval arithmetic
// (the filter; caller must hold CGAL::Protect_FPU_rounding) and for plain double (float mode).
// T must support +, -, * and construction from int.
#pragma once

#include "surfcert/core/rational.hpp"

#include <array>

namespace surfcert::algebra {

template <class T> using Mat4T = std::array<std::array<T, 4>, 4>;

namespace detail {
// acc += x*y and acc -= x*y; the Integer overloads use FLINT's fused in-place operations, which
// avoid a temporary (and, for big values, an allocation) per product.
template <class T> void mul_add(T& acc, const T& x, const T& y) {
  acc = acc + x * y;
}
template <class T> void mul_sub(T& acc, const T& x, const T& y) {
  acc = acc - x * y;
}
inline void mul_add(core::Integer& acc, const core::Integer& x, const core::Integer& y) {
  fmpz_addmul(acc.raw_mut(), x.raw(), y.raw());
}
inline void mul_sub(core::Integer& acc, const core::Integer& x, const core::Integer& y) {
  fmpz_submul(acc.raw_mut(), x.raw(), y.raw());
}

// Coefficients [q0, q1, q2] of the 2x2 minor (rows r1, r2; cols c1, c2) of l*A - B.
template <class T>
std::array<T, 3> pencil_minor2(const Mat4T<T>& a, const Mat4T<T>& b, int r1, int r2, int c1,
                               int c2) {
  auto A = [&](int i, int j) -> const T& {
    return a[static_cast<size_t>(i)][static_cast<size_t>(j)];
  };
  auto B = [&](int i, int j) -> const T& {
    return b[static_cast<size_t>(i)][static_cast<size_t>(j)];
  };
  // (l*a11 - b11)(l*a22 - b22) - (l*a12 - b12)(l*a21 - b21)
  T q2(0), q1(0), q0(0);
  mul_add(q2, A(r1, c1), A(r2, c2));
  mul_sub(q2, A(r1, c2), A(r2, c1));
  mul_add(q1, A(r1, c2), B(r2, c1));
  mul_add(q1, B(r1, c2), A(r2, c1));
  mul_sub(q1, A(r1, c1), B(r2, c2));
  mul_sub(q1, B(r1, c1), A(r2, c2));
  mul_add(q0, B(r1, c1), B(r2, c2));
  mul_sub(q0, B(r1, c2), B(r2, c1));
  return {q0, q1, q2};
}
} // namespace detail

/// det(l*A - B) = sum_{i} coeffs[i] l^i.
template <class T> std::array<T, 5> pencil_char_coeffs(const Mat4T<T>& a, const Mat4T<T>& b) {
  static const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  std::array<T, 5> f{T(0), T(0), T(0), T(0), T(0)};
  for (int p = 0; p < 6; ++p) {
    int i = pairs[p][0], j = pairs[p][1];
    int k = pairs[5 - p][0], l = pairs[5 - p][1]; // complementary columns
    auto top = detail::pencil_minor2(a, b, 0, 1, i, j);
    auto bot = detail::pencil_minor2(a, b, 2, 3, k, l);
    bool negative = ((i + j + 1) % 2) != 0;
    for (size_t s = 0; s < 3; ++s)
      for (size_t t = 0; t < 3; ++t) {
        if (negative)
          detail::mul_sub(f[s + t], top[s], bot[t]);
        else
          detail::mul_add(f[s + t], top[s], bot[t]);
      }
  }
  return f;
}

/// D2, D3, D4, E of f = a l^4 + b l^3 + c l^2 + d l + e (seed 002 Lemma 1, repaired).
template <class T> struct QuarticInvariants { T d2, d3, d4, e; };

namespace detail {
// The squares D2, D3, D4 and E share, and each of the four on demand: the interval filter needs
// D3 and D2 only when D4 > 0 (the same expressions, so the same values, as when all are taken).
template <class T> struct QuarticTerms {
  const T &a, &b, &c, &d, &e;
  T b2, c2, d2, a2;
  explicit QuarticTerms(const std::array<T, 5>& f)
      : a(f[4]), b(f[3]), c(f[2]), d(f[1]), e(f[0]), b2(b * b), c2(c * c), d2(d * d), a2(a * a) {}
  T D2() const { return T(3) * b2 - T(8) * a * c; }
  T D3() const {
    return b2 * c2 - T(3) * b2 * b * d - T(6) * a * b2 * e + T(14) * a * b * c * d -
           T(4) * a * c2 * c + T(16) * a2 * c * e - T(18) * a2 * d2;
  }
  // D4 as a polynomial in e (Horner), sharing the products of a..d: the same polynomial as the
  // 16 expanded terms (seed 002 Lemma 1), with 36 products instead of 62 (what an interval
  // evaluation pays for; any formula of the same polynomial encloses its exact value):
  //   D4 = ((256 a^3 e + t2) e + t1) e + t0,
  //   t2 = 144 (ac) b^2 - 27 b^4 - 192 a^2 (bd) - 128 a^2 c^2,
  //   t1 = c (18 b^2 (bd) - 4 b^2 c^2 - 80 (ab)(cd) + 16 (ac) c^2 + 144 a^2 d^2) - 6 a b^2 d^2,
  //   t0 = d^2 (b^2 c^2 - 4 b^2 (bd) + 18 (ab)(cd) - 4 (ac) c^2 - 27 a^2 d^2).
  T D4() const {
    const T bd = b * d, ac = a * c, abcd = (a * b) * (c * d);
    const T b2c2 = b2 * c2, b3d = b2 * bd, ac3 = ac * c2, a2d2 = a2 * d2;
    const T t2 = T(144) * ac * b2 - T(27) * b2 * b2 - T(192) * a2 * bd - T(128) * a2 * c2;
    const T t1 = c * (T(18) * b3d - T(4) * b2c2 - T(80) * abcd + T(16) * ac3 + T(144) * a2d2) -
                 T(6) * a * b2 * d2;
    const T t0 = d2 * (b2c2 - T(4) * b3d + T(18) * abcd - T(4) * ac3 - T(27) * a2d2);
    return ((T(256) * a2 * a * e + t2) * e + t1) * e + t0;
  }
  T E() const { return T(8) * a2 * d + b2 * b - T(4) * a * b * c; }
};
} // namespace detail

template <class T> QuarticInvariants<T> quartic_invariants(const std::array<T, 5>& f) {
  const detail::QuarticTerms<T> t(f);
  QuarticInvariants<T> q;
  q.d2 = t.D2();
  q.d3 = t.D3();
  q.d4 = t.D4();
  q.e = t.E();
  return q;
}

/// c3, c2, c1, c0 (as [0]=c0 ... [3]=c3) of det(mu*I - M) = mu^4 + c3 mu^3 + ... + c0.
template <class T> std::array<T, 4> charpoly_coeffs(const Mat4T<T>& m) {
  auto M = [&](int i, int j) -> const T& {
    return m[static_cast<size_t>(i)][static_cast<size_t>(j)];
  };
  using detail::mul_add;
  using detail::mul_sub;
  T tr = M(0, 0) + M(1, 1) + M(2, 2) + M(3, 3);
  T s2(0);
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      mul_add(s2, M(i, i), M(j, j));
      mul_sub(s2, M(i, j), M(j, i));
    }
  // Sum of principal 3x3 minors (cofactor expansion along the first kept row).
  T s3(0);
  for (int skip = 0; skip < 4; ++skip) {
    int r[3], n = 0;
    for (int i = 0; i < 4; ++i)
      if (i != skip) r[n++] = i;
    T c1(0), c2(0), c3(0);
    mul_add(c1, M(r[1], r[1]), M(r[2], r[2]));
    mul_sub(c1, M(r[1], r[2]), M(r[2], r[1]));
    mul_add(c2, M(r[1], r[0]), M(r[2], r[2]));
    mul_sub(c2, M(r[1], r[2]), M(r[2], r[0]));
    mul_add(c3, M(r[1], r[0]), M(r[2], r[1]));
    mul_sub(c3, M(r[1], r[1]), M(r[2], r[0]));
    mul_add(s3, M(r[0], r[0]), c1);
    mul_sub(s3, M(r[0], r[1]), c2);
    mul_add(s3, M(r[0], r[2]), c3);
  }
  // Determinant via the 2x2 minors of rows {0,1} and {2,3} (Laplace).
  static const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  T det(0);
  for (int p = 0; p < 6; ++p) {
    int i = pairs[p][0], j = pairs[p][1], k = pairs[5 - p][0], l = pairs[5 - p][1];
    T top(0), bot(0);
    mul_add(top, M(0, i), M(1, j));
    mul_sub(top, M(0, j), M(1, i));
    mul_add(bot, M(2, k), M(3, l));
    mul_sub(bot, M(2, l), M(3, k));
    if ((i + j + 1) % 2)
      mul_sub(det, top, bot);
    else
      mul_add(det, top, bot);
  }
  return {det, T(0) - s3, s2, T(0) - tr};
}

} // namespace surfcert::algebra
