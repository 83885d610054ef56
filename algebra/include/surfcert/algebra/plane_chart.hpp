// surfcert::algebra::plane_chart: exact affine coordinates (s, t) on the plane of a plane
// quadric, X = cols[0] s + cols[1] t + cols[2] (homogeneous 4-vectors, last entry 0, 0, 1).
//
// Contract: `plane` is the symmetric matrix of n.x + c (n = 2 (p[0][3], p[1][3], p[2][3]),
// c = p[3][3], the quadratic part zero). The chart solves for the first coordinate k with
// n_k != 0 and keeps the other two in increasing order as s and t: exact over the rationals,
// one-to-one onto the plane. nullopt when n = 0 (no affine plane: the plane at infinity or no
// plane at all). Shared by the exact plane sections of certify/affine and the tracer's closed
// form line components (trace/plane_sections), which restrict the other quadric to it with
// restrict_form.
#pragma once

#include "surfcert/core/quadric.hpp"

#include <array>
#include <optional>
#include <utility>

namespace surfcert::algebra {

inline std::optional<std::array<std::array<core::Rational, 4>, 3>>
plane_chart(const core::Mat4& plane) {
  using core::Rational;
  const std::array<Rational, 3> n{Rational(2) * plane[0][3], Rational(2) * plane[1][3],
                                  Rational(2) * plane[2][3]};
  size_t k = 0;
  while (k < 3 && n[k].is_zero())
    ++k;
  if (k == 3) return std::nullopt;
  size_t j1 = (k + 1) % 3, j2 = (k + 2) % 3;
  if (j1 > j2) std::swap(j1, j2);
  std::array<std::array<Rational, 4>, 3> col;
  col[0][j1] = Rational(1);
  col[0][k] = -n[j1] / n[k];
  col[1][j2] = Rational(1);
  col[1][k] = -n[j2] / n[k];
  col[2][3] = Rational(1);
  col[2][k] = -plane[3][3] / n[k];
  return col;
}

} // namespace surfcert::algebra
