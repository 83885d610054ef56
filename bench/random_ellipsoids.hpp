// Random ellipsoids for the benchmarks (seed 002 §5.1.3 recipe), header-only.
//
// Centre in [-1/2, 1/2]^3 (step 1/1000), semi-axes in [1/10, 1] (step 1/100), rotation from a
// random nonzero integer quaternion with entries in [-9, 9] (a rational rotation matrix).
// Each draw gives the exact quadric (for surfcert) and the same parameters as doubles (for
// peers such as Open CASCADE): every double is the correctly rounded value of the rational.
// The sequence of rng calls is part of the contract: qsic_bench's figures for a seed depend on
// it (radii x3, quaternion w x y z (redrawn while all zero), centre x3).
#pragma once

#include "ellipsoid_params.hpp"
#include "surfcert/core/quadric.hpp"

#include <random>

namespace surfcert::bench {

struct RandomEllipsoid {
  core::QuadricMatrix quadric; ///< exact: X^T Q X = 0 with X = (x, y, z, 1), inside negative
  EllipsoidParams params;      ///< the same ellipsoid as doubles
};

// The ellipsoid with semi-axes radii[i] / 100, rotation from the integer quaternion (w, x, y,
// z) (not all zero) and centre centre[i] / 1000, exactly and as doubles.
inline RandomEllipsoid ellipsoid_from(const long (&radii)[3], long w, long x, long y, long z,
                                      const long (&centre)[3]) {
  using core::Mat4;
  using core::Rational;
  EllipsoidParams p;
  Mat4 local;
  for (size_t i = 0; i < 3; ++i) {
    Rational rad(radii[i], 100);
    local[i][i] = Rational(1) / (rad * rad);
    p.radii[i] = static_cast<double>(radii[i]) / 100.0;
  }
  local[3][3] = Rational(-1);
  long n = w * w + x * x + y * y + z * z;
  long R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                  {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                  {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  Rational cen[3] = {Rational(centre[0], 1000), Rational(centre[1], 1000),
                     Rational(centre[2], 1000)};
  for (size_t i = 0; i < 3; ++i) {
    p.centre[i] = static_cast<double>(centre[i]) / 1000.0;
    for (size_t j = 0; j < 3; ++j)
      p.rotation[i][j] = static_cast<double>(R[i][j]) / static_cast<double>(n);
  }
  // Local coordinates: x_local = R^T (x - c) / n-normalised, i.e. t = [R^T/n, -R^T c/n; 0 1].
  Mat4 t;
  for (size_t i = 0; i < 3; ++i) {
    Rational s;
    for (size_t j = 0; j < 3; ++j) {
      t[i][j] = Rational(R[j][i]) / Rational(n);
      s += t[i][j] * cen[j];
    }
    t[i][3] = -s;
  }
  t[3][3] = Rational(1);
  return RandomEllipsoid{core::QuadricMatrix(core::transpose(t) * local * t), p};
}

inline RandomEllipsoid random_ellipsoid(std::mt19937_64& rng) {
  std::uniform_int_distribution<long> c(-500, 500), r(10, 100), q(-9, 9);
  long radii[3];
  for (long& v : radii)
    v = r(rng);
  long w, x, y, z;
  do {
    w = q(rng), x = q(rng), y = q(rng), z = q(rng);
  } while (w == 0 && x == 0 && y == 0 && z == 0);
  long ci[3];
  for (long& v : ci) // in order: x, y, z
    v = c(rng);
  return ellipsoid_from(radii, w, x, y, z, ci);
}

} // namespace surfcert::bench
