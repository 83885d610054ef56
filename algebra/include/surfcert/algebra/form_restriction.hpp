// surfcert::algebra::restrict_form: a quadratic form restricted to the span of given vectors,
// C[i][j] = cols[i]^T Q cols[j] (C = T^T Q T, column i of T being cols[i]).
//
// One operation behind several: the conic at infinity in a chart and a quadric's section by a
// plane (exact, over core::Rational, in certify), a quadric's trace on a box face (exact in
// certify/box_exits, in doubles in the tracer's float face proposals) and on the plane of a
// conic component (doubles). Exact for exact scalar types; for doubles, plain rounding.
//
// surfcert::algebra::bilinear: the bilinear form u^T Q v itself (a single entry of such a
// restriction), for the exact evaluations of a quadric's form at given points and directions
// (certify's cubic and line, special points, cone ovals, the 3x3 forms of the distance routes).
//
// Over core::Rational both are computed on integers: Q and the vectors are written over their
// least common denominators, the sums of products taken in FLINT integers, and each result
// entry canonicalised once (the same exact value as the rational sums, which reduce every
// product and partial sum by a gcd: on the ~150-digit rationals of a surface posed in doubles
// those gcds were a third of a plane section's intersect).
#pragma once

#include "surfcert/core/rational.hpp"

#include <array>
#include <cstddef>
#include <type_traits>

namespace surfcert::algebra {

namespace detail {

using core::over_common_denominator;

template <size_t N, size_t M>
std::array<std::array<core::Rational, M>, M>
restrict_form_rational(const std::array<std::array<core::Rational, N>, N>& q,
                       const std::array<std::array<core::Rational, N>, M>& cols) {
  std::array<const core::Rational*, N * N> qp{};
  std::array<const core::Rational*, M * N> cp{};
  for (size_t a = 0; a < N; ++a)
    for (size_t b = 0; b < N; ++b)
      qp[a * N + b] = &q[a][b];
  for (size_t j = 0; j < M; ++j)
    for (size_t b = 0; b < N; ++b)
      cp[j * N + b] = &cols[j][b];
  std::array<core::Integer, N * N> qn;
  std::array<core::Integer, M * N> cn;
  core::Integer dq, dc;
  over_common_denominator(qp.data(), qp.size(), qn.data(), dq);
  over_common_denominator(cp.data(), cp.size(), cn.data(), dc);
  // t[j][a] = (Q cols[j])[a], then r[i][j] = cols[i] . t[j], all over dq dc^2.
  std::array<core::Integer, M * N> t;
  for (size_t j = 0; j < M; ++j)
    for (size_t a = 0; a < N; ++a)
      for (size_t b = 0; b < N; ++b)
        fmpz_addmul(t[j * N + a].raw_mut(), qn[a * N + b].raw(), cn[j * N + b].raw());
  core::Integer den;
  fmpz_mul(den.raw_mut(), dc.raw(), dc.raw());
  fmpz_mul(den.raw_mut(), den.raw(), dq.raw());
  std::array<std::array<core::Rational, M>, M> r{};
  core::Integer s;
  for (size_t i = 0; i < M; ++i)
    for (size_t j = i; j < M; ++j) {
      fmpz_zero(s.raw_mut());
      for (size_t a = 0; a < N; ++a)
        fmpz_addmul(s.raw_mut(), cn[i * N + a].raw(), t[j * N + a].raw());
      fmpq_set_fmpz_frac(r[i][j].raw_mut(), s.raw(), den.raw());
      if (j != i) r[j][i] = r[i][j];
    }
  return r;
}

template <size_t N>
core::Rational bilinear_rational(const std::array<std::array<core::Rational, N>, N>& q,
                                 const std::array<core::Rational, N>& u,
                                 const std::array<core::Rational, N>& v) {
  std::array<const core::Rational*, N * N> qp{};
  std::array<const core::Rational*, 2 * N> up{};
  for (size_t a = 0; a < N; ++a) {
    for (size_t b = 0; b < N; ++b)
      qp[a * N + b] = &q[a][b];
    up[a] = &u[a];
    up[N + a] = &v[a];
  }
  std::array<core::Integer, N * N> qn;
  std::array<core::Integer, 2 * N> un;
  core::Integer dq, du;
  over_common_denominator(qp.data(), qp.size(), qn.data(), dq);
  over_common_denominator(up.data(), up.size(), un.data(), du);
  core::Integer s, row;
  for (size_t a = 0; a < N; ++a) {
    if (un[a].is_zero()) continue;
    fmpz_zero(row.raw_mut());
    for (size_t b = 0; b < N; ++b)
      fmpz_addmul(row.raw_mut(), qn[a * N + b].raw(), un[N + b].raw());
    fmpz_addmul(s.raw_mut(), un[a].raw(), row.raw());
  }
  core::Integer den;
  fmpz_mul(den.raw_mut(), du.raw(), du.raw());
  fmpz_mul(den.raw_mut(), den.raw(), dq.raw());
  core::Rational r;
  fmpq_set_fmpz_frac(r.raw_mut(), s.raw(), den.raw());
  return r;
}

} // namespace detail

template <class T, size_t N, size_t M>
std::array<std::array<T, M>, M> restrict_form(const std::array<std::array<T, N>, N>& q,
                                              const std::array<std::array<T, N>, M>& cols) {
  if constexpr (std::is_same_v<T, core::Rational>) {
    return detail::restrict_form_rational(q, cols);
  } else {
    std::array<std::array<T, M>, M> r{};
    for (size_t i = 0; i < M; ++i)
      for (size_t j = i; j < M; ++j) {
        T s{};
        for (size_t a = 0; a < N; ++a) {
          T row{};
          for (size_t b = 0; b < N; ++b)
            row += q[a][b] * cols[j][b];
          s += cols[i][a] * row;
        }
        r[i][j] = s;
        r[j][i] = s;
      }
    return r;
  }
}

template <class T, size_t N>
T bilinear(const std::array<std::array<T, N>, N>& q, const std::array<T, N>& u,
           const std::array<T, N>& v) {
  if constexpr (std::is_same_v<T, core::Rational>) {
    return detail::bilinear_rational(q, u, v);
  } else {
    T s{};
    for (size_t i = 0; i < N; ++i)
      for (size_t j = 0; j < N; ++j)
        s += u[i] * q[i][j] * v[j];
    return s;
  }
}

} // namespace surfcert::algebra
