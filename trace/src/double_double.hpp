// Double-double evaluation of a quadratic form, shared by QuadricPair's refined mode and
// RefinedPair: a symmetric matrix carried as hi + lo (two doubles per entry) evaluated at a
// double point with error-free transformations (Knuth's two-sum, the fma two-product), to
// ~2^-104 of the running sum per operation. Internal to the trace library.
#pragma once

#include "surfcert/core/quadric.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <cmath>

namespace surfcert::trace::dd {

using M4 = std::array<std::array<double, 4>, 4>;

/// The remainders of q's exact entries scaled by `scale` after their doubles `hi`, each exact
/// as a rational and rounded once: (q s)_ij = hi_ij + lo_ij to ~2^-106 of the entry. The one
/// builder of the lo part (QuadricPair::refined, RefinedPair).
inline void remainders(const core::QuadricMatrix& q, const core::Rational& scale, const M4& hi,
                       M4& lo) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j) {
      const core::Rational v = q(static_cast<int>(i), static_cast<int>(j)) * scale;
      lo[i][j] = lo[j][i] = (v - core::Rational::exact_from_double(hi[i][j])).to_double_approx();
    }
}

/// s + e == a + b exactly.
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

/// p + e == a * b exactly (fma).
inline void two_prod(double a, double b, double& p, double& e) {
  p = a * b;
  e = std::fma(a, b, -p);
}

/// (ah + al) * (bh + bl), to ~2^-104 relative.
inline void mul(double ah, double al, double bh, double bl, double& ph, double& pl) {
  double p, e;
  two_prod(ah, bh, p, e);
  e += ah * bl + al * bh;
  two_sum(p, e, ph, pl);
}

/// (sh + sl) += (bh + bl).
inline void add(double& sh, double& sl, double bh, double bl) {
  double s, e;
  two_sum(sh, bh, s, e);
  e += sl + bl;
  two_sum(s, e, sh, sl);
}

/// X^T (hi + lo) X at X = (p, 1), hi + lo symmetric: the ten distinct terms (off-diagonal ones
/// twice), each product and sum in double-double, rounded to double at the end. Its error is
/// at most 2^-98 of the terms' size sum |hi_ij x_i x_j| (ten operations of ~2^-104 each).
inline double form(const M4& hi, const M4& lo, const std::array<double, 3>& p) {
  const double x[4] = {p[0], p[1], p[2], 1.0};
  double sh = 0, sl = 0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j) {
      double xh, xl; // x_i x_j exactly
      two_prod(x[i], x[j], xh, xl);
      double th, tl;
      mul(hi[i][j], lo[i][j], xh, xl, th, tl);
      if (i != j) th *= 2, tl *= 2;
      add(sh, sl, th, tl);
    }
  return sh + sl;
}

} // namespace surfcert::trace::dd
