// surfcert::algebra::kernel_basis: the kernel {x : m x = 0} of a rational 4x4 matrix, exactly.
//
// Contract: 4 - rank(m) vectors spanning the kernel over Q (none when m is regular), each an
// integer vector (entries are rationals with denominator 1): FLINT's fmpz_mat_nullspace of
// scaled_integer_matrix(m) (inertia.hpp), a positive integer multiple of m with the same
// kernel. m need not be symmetric. Used where certify reads points and lines off singular
// pencil members (cubic_line.cpp, special_points.cpp).
#pragma once

#include "surfcert/core/shape.hpp"

#include <array>
#include <vector>

namespace surfcert::algebra {

std::vector<std::array<core::Rational, 4>> kernel_basis(const core::Mat4& m);

} // namespace surfcert::algebra
