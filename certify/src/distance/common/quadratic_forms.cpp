#include "surfcert/certify/distance/quadratic_forms.hpp"

#include <flint/fmpq_mat.h>
#include <flint/fmpz_mat.h>

namespace surfcert::certify {

using core::Rational;

RMat3 quadratic_block(const core::QuadricMatrix& q) {
  RMat3 m;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      m[i][j] = q(static_cast<int>(i), static_cast<int>(j));
  return m;
}

bool components_unbounded(const core::QuadricMatrix& q) {
  const RMat3 A = quadratic_block(q);
  const Rational m1 = A[0][0], m2 = A[0][0] * A[1][1] - A[0][1] * A[0][1];
  const Rational m3 = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[1][2]) -
                      A[0][1] * (A[0][1] * A[2][2] - A[1][2] * A[0][2]) +
                      A[0][2] * (A[0][1] * A[1][2] - A[1][1] * A[0][2]);
  const bool definite = m2.sign() > 0 && m1.sign() != 0 && m3.sign() == m1.sign();
  return !definite;
}

Rational restricted_resultant(const RMat3& a, const RMat3& b, const RVec3& u, const RVec3& v) {
  // Res(a11 s^2 + 2 a12 s t + a22 t^2, b11 s^2 + 2 b12 s t + b22 t^2) by the 2 x 2 Bezout
  // formula (a11 b22 - a22 b11)^2 - (a11 b12' - a12' b11)(a12' b22 - a22 b12'), ' = doubled.
  const Rational a11 = bilinear(a, u, u), a12 = bilinear(a, u, v) * Rational(2),
                 a22 = bilinear(a, v, v);
  const Rational b11 = bilinear(b, u, u), b12 = bilinear(b, u, v) * Rational(2),
                 b22 = bilinear(b, v, v);
  const Rational p = a11 * b22 - a22 * b11;
  return p * p - (a11 * b12 - a12 * b11) * (a12 * b22 - a22 * b12);
}

std::vector<std::vector<Rational>> common_kernel(const core::QuadricMatrix& a,
                                                 const core::QuadricMatrix& b, int n) {
  fmpq_mat_t m;
  fmpq_mat_init(m, 8, n);
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < n; ++c)
      fmpq_set(fmpq_mat_entry(m, r, c), (r < 4 ? a(r, c) : b(r - 4, c)).raw());
  fmpz_mat_t z, ker;
  fmpz_mat_init(z, 8, n);
  fmpz_mat_init(ker, n, n);
  fmpq_mat_get_fmpz_mat_rowwise(z, nullptr, m); // rows scaled to integers: the same kernel
  const slong nullity = fmpz_mat_nullspace(ker, z);
  std::vector<std::vector<Rational>> basis;
  for (slong j = 0; j < nullity; ++j) {
    std::vector<Rational> v(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
      fmpq_set_fmpz_frac(v[static_cast<size_t>(i)].raw_mut(), fmpz_mat_entry(ker, i, j),
                         core::Integer(1).raw());
    basis.push_back(std::move(v));
  }
  fmpz_mat_clear(ker);
  fmpz_mat_clear(z);
  fmpq_mat_clear(m);
  return basis;
}

} // namespace surfcert::certify
