// surfcert::algebra::jacobi4: eigen-decomposition of a symmetric 4x4 double matrix by cyclic
// Jacobi rotations, m = sum_k w[k] v_k v_k^T with v_k the k-th column of v. A numeric utility
// in floating point (no guarantee, nothing exact here): used by certify's float mode for its
// inertia estimates (pencil_filter.cpp) and by the tracer (surfcert::trace) to split singular
// pencil members into planes for the conic components.
#pragma once

#include <array>
#include <cmath>

namespace surfcert::algebra {

using Mat4d = std::array<std::array<double, 4>, 4>;

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
        if (a[p][q] == 0) continue;
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

} // namespace surfcert::algebra
