// surfcert::core::QuadricMatrix: a quadric X^T A X = 0 as a symmetric 4x4 rational matrix.
//
// X = (x, y, z, w) homogeneous. For an affine equation the upper-left 3x3 block holds the
// quadratic part, the last row/column half the linear coefficients, A[3][3] the constant.
// Invariants: symmetric, not identically zero. The matrix is exactly the one of the given
// equation (no rescaling), so a caller can compare it with its own reading of the input.
// A quadric built from a ShapeSpec (a shape posed in doubles, shape.hpp) is the same exact
// quadric, but its rational matrix is formed on first use of matrix() (thread-safe, once):
// the interval filter works from shape() without it. So is a quadric built from a 4x4 matrix
// of doubles (from_double_matrix): the exact quadric of its symmetric part, whose rationals are
// formed on first use of matrix(); the filter encloses it from double_matrix(). Copies share
// the matrix.
#pragma once

#include "surfcert/core/poly3.hpp"
#include "surfcert/core/rational.hpp"
#include "surfcert/core/shape.hpp"

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

namespace surfcert::core {

/// Affine kind of a real quadric, decided exactly (used for labels and for the ellipsoid
/// relation; the QSIC classification itself works on the projective pencil).
enum class QuadricKind {
  Ellipsoid,          ///< real ellipsoid (spheres included)
  ImaginaryEllipsoid, ///< no real point
  Other ///< any other quadric (cones, cylinders, paraboloids, hyperboloids, planes ...)
};

using DoubleMat4 = std::array<std::array<double, 4>, 4>;

class QuadricMatrix {
public:
  /// From a symmetric, nonzero matrix; throws std::invalid_argument otherwise (callers that
  /// read user input check first and report an InputError with a location).
  explicit QuadricMatrix(const Mat4& m);
  /// The quadric of a posed shape (lazy: the exact matrix is formed on first use).
  explicit QuadricMatrix(const ShapeSpec& s);
  /// The quadric X^T D X of a 4x4 matrix of finite doubles, each read as its exact value: the
  /// quadric of the symmetric part (D + D^T) / 2, exactly (lazy: its rational matrix is formed
  /// on first use). Throws std::invalid_argument when an entry is not finite or the symmetric
  /// part is zero.
  static QuadricMatrix from_double_matrix(const DoubleMat4& d);
  /// From a polynomial of total degree 1 or 2 (a plane counts as a degenerate quadric).
  /// Throws std::invalid_argument if the degree is not 1 or 2.
  static QuadricMatrix from_poly(const Poly3& p);

  /// The exact matrix (formed here on first use when built from a ShapeSpec).
  const Mat4& matrix() const;
  const Rational& operator()(int i, int j) const {
    return matrix()[static_cast<size_t>(i)][static_cast<size_t>(j)];
  }
  /// The shape in doubles this quadric was built from, or nullptr.
  const ShapeSpec* shape() const { return state_->shape ? &*state_->shape : nullptr; }
  /// The matrix of doubles this quadric was built from (as given, not symmetrised), or nullptr.
  const DoubleMat4* double_matrix() const { return state_->doubles ? &*state_->doubles : nullptr; }
  Poly3 to_poly() const;
  /// P^T A P (a change of homogeneous coordinates X = P X').
  QuadricMatrix congruent(const Mat4& p) const;
  /// The quadric moved by -c, exactly: its equation in y is this one's at x = y + c (the
  /// congruence by the translation P = [[I, c], [0, 1]]). A shape whose centre minus c is
  /// again exactly a double stays a (lazy) shape; otherwise the exact congruence is formed.
  QuadricMatrix translated(const std::array<double, 3>& c) const;
  /// The same surface in the coordinates u = x / 2^k, exactly: its equation in u is this one's
  /// at x = 2^k u (the congruence by diag(2^k, 2^k, 2^k, 1)). A shape whose centre and radii
  /// times 2^-k are again exactly doubles stays a (lazy) shape; otherwise the exact congruence
  /// is formed, divided by a power of two near its largest entry (the same quadric). Used to bring
  /// a pair posed at 1e-300 or 1e300 to unit size for the double computations of the tracer (a
  /// power of two: nothing is rounded).
  QuadricMatrix rescaled(int k) const;
  QuadricKind kind() const;
  /// True when det of the matrix is exactly 0 (a cone, a cylinder, a plane, a plane pair ...):
  /// for a posed shape by construction (its local form's determinant, radii > 0, R
  /// invertible), otherwise by the exact determinant, computed once per quadric (copies share
  /// it). The interval filter asks it only when the determinant's enclosure contains 0.
  bool singular() const;
  /// True when the quadratic block is zero (a plane written as a degenerate quadric).
  bool is_plane() const;
  /// True when the upper 3x3 block is a nonzero multiple of the identity and the quadric is
  /// a real ellipsoid.
  bool is_sphere() const;

private:
  QuadricMatrix() = default;
  /// `moved` (this quadric in other affine coordinates, freshly built) with this one's cached
  /// kind and singularity, where already computed.
  QuadricMatrix with_invariants_of(QuadricMatrix moved) const;
  struct State {
    Mat4 m;
    std::optional<ShapeSpec> shape;
    std::optional<DoubleMat4> doubles;
    std::once_flag formed; ///< used only when shape or doubles is set (m formed lazily)
    /// kind() once computed (-1: not yet): its exact minors and determinant were 1-1.5% of an
    /// intersect's instructions, asked for the same quadric by several stages. The matrix never
    /// changes, so any thread's value is the value; relaxed order suffices (an int, no other data).
    mutable std::atomic<int> kind{-1};
    mutable std::atomic<int> singular{-1}; ///< singular() once computed (-1: not yet), as kind
  };
  std::shared_ptr<State> state_;
};

/// The binary order of the lengths q's features lie at (its size and its distance from the
/// origin): k with those lengths about 2^k, or nullopt when it has none (a cone or a plane pair
/// through the origin). For a shape posed in doubles, from its centre and semi-axes; otherwise
/// from the matrix [[A, b], [b^T, c]]: the largest of the orders of |b| / |A| (a centre's
/// distance) and sqrt(|c| / |A|) (a radius), or of |c| / |b| for a plane. An estimate (within a
/// few units), exact-arithmetic free of overflow: what callers need to pick a power of two that
/// brings a pair near unit size (rescaled) before double or scale-sensitive computations.
std::optional<long> length_order(const QuadricMatrix& q);

bool is_symmetric(const Mat4& m);
/// The exact symmetric part (D + D^T) / 2 of a matrix of finite doubles (each read exactly).
Mat4 symmetric_part_exact(const DoubleMat4& d);
bool is_zero(const Mat4& m);
Mat4 identity4();
Mat4 transpose(const Mat4& m);
Mat4 operator*(const Mat4& a, const Mat4& b);
/// p^T m p for a symmetric m (not checked; the result is then symmetric), exactly: the same
/// value as transpose(p) * m * p, computed on the upper triangle with the zero entries skipped
/// (a translation or a posed diagonal form costs a fraction of the full products), on integers
/// over the matrices' common denominators (over_common_denominator).
Mat4 congruence(const Mat4& p, const Mat4& m);
Mat4 operator+(const Mat4& a, const Mat4& b);
Mat4 scaled(const Mat4& a, const Rational& c);
Rational det(const Mat4& m);
/// Determinant of the leading k x k block (k = 1..4).
Rational leading_minor(const Mat4& m, int k);

} // namespace surfcert::core
