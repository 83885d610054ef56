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
#pragma once

#include <array>
#include <cstddef>

namespace surfcert::algebra {

template <class T, size_t N, size_t M>
std::array<std::array<T, M>, M> restrict_form(const std::array<std::array<T, N>, N>& q,
                                              const std::array<std::array<T, N>, M>& cols) {
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

template <class T, size_t N>
T bilinear(const std::array<std::array<T, N>, N>& q, const std::array<T, N>& u,
           const std::array<T, N>& v) {
  T s{};
  for (size_t i = 0; i < N; ++i)
    for (size_t j = 0; j < N; ++j)
      s += u[i] * q[i][j] * v[j];
  return s;
}

} // namespace surfcert::algebra
