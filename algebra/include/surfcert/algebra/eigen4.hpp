// surfcert::algebra::jacobi4: eigen-decomposition of a symmetric 4x4 double matrix by cyclic
// Jacobi rotations, m = sum_k w[k] v_k v_k^T with v_k the k-th column of v. A numeric utility
// in floating point (no guarantee, nothing exact here): used (values only, jacobi4_eigenvalues)
// by certify's float mode for its inertia estimates (pencil_filter.cpp) and by the tracer
// (surfcert::trace) to split singular pencil members into planes for the conic components.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

namespace surfcert::algebra {

using Mat4d = std::array<std::array<double, 4>, 4>;

namespace detail {

/// One Jacobi rotation J in the plane (p, q), p < q, that zeroes a[p][q] (nonzero):
/// a <- J^T a J. Returns J's cosine and sine (for the eigenvectors).
inline std::pair<double, double> jacobi_rotate(Mat4d& a, size_t p, size_t q) {
  double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
  double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
  double c = 1 / std::sqrt(t * t + 1), s = t * c;
  for (size_t k = 0; k < 4; ++k) { // a <- a J (columns p, q)
    double akp = a[k][p], akq = a[k][q];
    a[k][p] = c * akp - s * akq;
    a[k][q] = s * akp + c * akq;
  }
  for (size_t k = 0; k < 4; ++k) { // a <- J^T a (rows p, q)
    double apk = a[p][k], aqk = a[q][k];
    a[p][k] = c * apk - s * aqk;
    a[q][k] = s * apk + c * aqk;
  }
  return {c, s};
}

} // namespace detail

/// Stops once the matrix is diagonal to working precision, as jacobi4_eigenvalues below (an
/// off-diagonal entry too small to change either of its diagonal entries is set to zero from
/// the fifth sweep on): its former test alone (off-diagonal mass <= 1e-34 of the total) was
/// almost never met, and the 60 sweeps it then ran were ~10% of a traced ellipsoid pair's time.
inline void jacobi4(Mat4d a, std::array<double, 4>& w, Mat4d& v) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      v[i][j] = i == j ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0, all = 0;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        all += a[i][j] * a[i][j];
        if (i != j) off += a[i][j] * a[i][j];
      }
    if (off <= 1e-34 * all || off == 0) break;
    for (size_t p = 0; p < 3; ++p)
      for (size_t q = p + 1; q < 4; ++q) {
        const double g = 100 * std::fabs(a[p][q]);
        if (sweep >= 4 && std::fabs(a[p][p]) + g == std::fabs(a[p][p]) &&
            std::fabs(a[q][q]) + g == std::fabs(a[q][q])) {
          a[p][q] = a[q][p] = 0;
          continue;
        }
        if (a[p][q] == 0) continue;
        const auto [c, s] = detail::jacobi_rotate(a, p, q);
        for (size_t k = 0; k < 4; ++k) {
          double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  for (size_t k = 0; k < 4; ++k)
    w[k] = a[k][k];
}

/// The eigenvalues alone (diagonal of the converged a), by the same cyclic rotations, stopping
/// once the matrix is diagonal to working precision: from the fifth sweep on, an off-diagonal
/// entry too small to change either of its diagonal entries (100 |a_pq| lost in the rounding
/// of |a_pp| and of |a_qq|) is set to zero instead of rotated. jacobi4's own test (off-diagonal
/// mass <= 1e-34 of the total, below rounding) is almost never met, so it runs all 60 sweeps
/// (~15x the work); the values differ from its only by rounding.
inline std::array<double, 4> jacobi4_eigenvalues(Mat4d a) {
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0;
    for (size_t p = 0; p < 3; ++p)
      for (size_t q = p + 1; q < 4; ++q)
        off += std::fabs(a[p][q]);
    if (off == 0) break;
    for (size_t p = 0; p < 3; ++p)
      for (size_t q = p + 1; q < 4; ++q) {
        const double g = 100 * std::fabs(a[p][q]);
        if (sweep >= 4 && std::fabs(a[p][p]) + g == std::fabs(a[p][p]) &&
            std::fabs(a[q][q]) + g == std::fabs(a[q][q])) {
          a[p][q] = a[q][p] = 0;
          continue;
        }
        if (a[p][q] == 0) continue;
        detail::jacobi_rotate(a, p, q);
      }
  }
  return {a[0][0], a[1][1], a[2][2], a[3][3]};
}

} // namespace surfcert::algebra
