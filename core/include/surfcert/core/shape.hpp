// surfcert::core::ShapeSpec: a quadric shape posed by a centre and a rotation, exactly as the
// caller gave it in binary64 numbers, and the exact matrix it defines.
//
// What it represents: the quadric c + R S, where S is the unit shape of `type` scaled by the
// radii (x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 for an ellipsoid, ...), c the centre and R the
// rotation of the unit quaternion q / |q| (or the identity). Every number is a double and
// stands for its exact dyadic value, so the surface is exact; only its matrix is not formed
// until someone asks (QuadricMatrix built from a ShapeSpec is lazy): the interval filter
// reads enclosures of the matrix straight from these doubles (certify/enclosure.hpp), and the
// exact rationals (hundreds of digits for a double quaternion) are formed only when a
// decision or a report needs them.
// Contract: radii finite and > 0, centre and quaternion finite, quaternion nonzero (the
// reader checks and reports errors with locations; posed_quadric_matrix assumes it).
#pragma once

#include "surfcert/core/rational.hpp"

#include <array>

namespace surfcert::core {

using Mat4 = std::array<std::array<Rational, 4>, 4>;
using Mat3 = std::array<std::array<Rational, 3>, 3>;

enum class ShapeType {
  Sphere,
  Ellipsoid,
  Cylinder,
  Cone,
  EllipticParaboloid,
  HyperbolicParaboloid,
  HyperboloidOneSheet,
  HyperboloidTwoSheets
};

struct ShapeSpec {
  ShapeType type = ShapeType::Sphere;
  std::array<double, 3> radii{1, 1, 1}; ///< semi-axes (the unused ones are ignored)
  std::array<double, 3> center{0, 0, 0};
  bool rotated = false;                         ///< false: the identity
  std::array<double, 4> quaternion{1, 0, 0, 0}; ///< (w, x, y, z), any nonzero length
};

/// The local form diag(q0, q1, q2) + lz z + k of a shape type with exact radii r:
/// (q, lz, k) with q = +-1/r^2 or 0. Used by the exact builder and (in intervals) the filter.
struct LocalForm {
  std::array<int, 3> q_sign; ///< sign of q_i (0: the term is absent)
  int linear_z;              ///< coefficient of z in the local equation (-1 or 0)
  int constant;              ///< the constant k (-1, 0 or 1)
};
LocalForm local_form(ShapeType t);

/// The exact rotation matrix of the quaternion q (divided by |q|^2, so exactly orthogonal).
Mat3 quaternion_rotation(const std::array<Rational, 4>& q);

/// The matrix of the shape c + R S with exact radii (3 values, unused ones ignored), centre
/// and the exact inverse of R (R^T for a rotation): M = T^T L T, T = [[R^-1, -R^-1 c], [0, 1]].
Mat4 posed_quadric_matrix(ShapeType t, const std::array<Rational, 3>& radii,
                          const std::array<Rational, 3>& center, const Mat3& r_inverse);

/// The exact matrix of a ShapeSpec (the doubles read exactly).
Mat4 exact_matrix(const ShapeSpec& s);

} // namespace surfcert::core
