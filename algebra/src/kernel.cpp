#include "surfcert/algebra/kernel.hpp"

#include "surfcert/algebra/inertia.hpp"

#include <flint/fmpz_mat.h>

namespace surfcert::algebra {

std::vector<std::array<core::Rational, 4>> kernel_basis(const core::Mat4& m) {
  fmpz_mat_t z, n;
  fmpz_mat_init(z, 4, 4);
  fmpz_mat_init(n, 4, 4);
  scaled_integer_matrix(z, m); // a positive multiple: the same kernel
  const slong nullity = fmpz_mat_nullspace(n, z);
  std::vector<std::array<core::Rational, 4>> out;
  for (slong c = 0; c < nullity; ++c) {
    std::array<core::Rational, 4> v;
    for (size_t i = 0; i < 4; ++i) {
      core::Integer t;
      fmpz_set(t.raw_mut(), fmpz_mat_entry(n, static_cast<slong>(i), c));
      v[i] = core::Rational(t);
    }
    out.push_back(v);
  }
  fmpz_mat_clear(z);
  fmpz_mat_clear(n);
  return out;
}

} // namespace surfcert::algebra
