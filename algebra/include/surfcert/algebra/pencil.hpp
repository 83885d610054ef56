// surfcert::algebra::PencilFacts: everything the QSIC decision rules need about the pencil
// l*A - B of two quadrics, computed exactly over Q (analyze_pencil_exact).
//
// Invariants of an exact analysis of a regular pencil: det(A) != 0 in the basis used (the
// pencil is re-based to (tA - B, -A) when the given A is singular, research §1.1); real roots
// are listed in increasing order, root i lies in (samples[i], samples[i+1]) and nowhere else;
// indices[j] = number of positive eigenvalues of samples[j]*A - B; every multiple root carries
// its exact value (rational, or a + b sqrt(d)) and its exact rank and inertia.
// Cost: one 4x4 closed-form determinant over Z, one square-free factorisation, an isolation
// of a quartic, k+1 Descartes counts; exact work in Q(sqrt d) only at conjugate double roots.
// The basis a, b is set by the exact analysis; facts from the interval filter leave it unset
// (LazyMat4: reads as zero) until a report needs it (certify::complete_report_data).
#pragma once

#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/upoly.hpp"
#include "surfcert/core/quadric.hpp"

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace surfcert::algebra {

enum class PencilKind {
  Regular,    ///< f(l) = det(lA - B) is not identically zero
  Degenerate, ///< f == 0: every member singular (e.g. two cones with a common apex)
  Coincident  ///< B is a multiple of A: the same quadric
};

struct RootFacts {
  int multiplicity = 1;
  int rank = 3;        ///< rank of theta*A - B
  Inertia sigma;       ///< inertia of theta*A - B
  int index_left = 0;  ///< index on the interval left of theta
  int index_right = 0; ///< index on the interval right of theta
  Rational lo, hi;     ///< the root is the unique root of `factor` in (lo, hi) (or lo == hi)
  UPolyZ factor;       ///< square-free factor of f with this root (primitive, lead > 0)
  std::optional<Rational> rational_value;   ///< set when theta is rational
  std::optional<QuadraticNumber> quadratic; ///< set when theta = a + b sqrt(d), d not a square
  /// Float mode only (certify::analyze_pencil_float): the float root (a cluster's centre for a
  /// multiple root), an estimate that nothing certified reads; lo and hi are then float
  /// separators, not an isolating interval.
  std::optional<double> float_value;
  bool jump() const { return index_left != index_right; }
};

/// A pencil basis matrix (PencilFacts::a, ::b) that costs nothing until it is set. Empty, it
/// reads as the zero matrix (what a default core::Mat4 holds), so every reader sees a Mat4 as
/// before; setting it allocates one. Why: the filtered classify path never sets the basis
/// (certify::complete_report_data copies it in on demand), and two default Mat4s (32
/// Rationals) built and destroyed per answer were ~0.5 k instructions a line of a batch.
/// Copies are deep; reads of a shared const object are thread-safe (the zero is a constant).
class LazyMat4 {
public:
  LazyMat4() = default;
  LazyMat4(const core::Mat4& m) : p_(std::make_unique<core::Mat4>(m)) {} // NOLINT: implicit
  LazyMat4(const LazyMat4& o) : p_(o.p_ ? std::make_unique<core::Mat4>(*o.p_) : nullptr) {}
  LazyMat4(LazyMat4&&) noexcept = default;
  LazyMat4& operator=(const LazyMat4& o) {
    if (!o.p_)
      p_.reset();
    else if (this != &o)
      *this = *o.p_;
    return *this;
  }
  LazyMat4& operator=(LazyMat4&&) noexcept = default;
  LazyMat4& operator=(const core::Mat4& m) {
    if (p_)
      *p_ = m;
    else
      p_ = std::make_unique<core::Mat4>(m);
    return *this;
  }
  LazyMat4& operator=(core::Mat4&& m) {
    if (p_)
      *p_ = std::move(m);
    else
      p_ = std::make_unique<core::Mat4>(std::move(m));
    return *this;
  }

  /// The matrix (the zero matrix while unset).
  const core::Mat4& get() const { return p_ ? *p_ : zero(); }
  operator const core::Mat4&() const { return get(); } // NOLINT: reads as a Mat4
  const std::array<Rational, 4>& operator[](std::size_t i) const { return get()[i]; }
  /// True once set (a set zero matrix included).
  bool filled() const { return p_ != nullptr; }

  friend bool operator==(const LazyMat4& x, const LazyMat4& y) { return x.get() == y.get(); }
  friend bool operator==(const LazyMat4& x, const core::Mat4& y) { return x.get() == y; }
  friend bool operator==(const core::Mat4& x, const LazyMat4& y) { return x == y.get(); }
  friend bool operator!=(const LazyMat4& x, const LazyMat4& y) { return !(x == y); }
  friend bool operator!=(const LazyMat4& x, const core::Mat4& y) { return !(x == y); }
  friend bool operator!=(const core::Mat4& x, const LazyMat4& y) { return !(x == y); }

private:
  static const core::Mat4& zero() {
    static const core::Mat4 z{};
    return z;
  }
  std::unique_ptr<core::Mat4> p_;
};

struct PencilFacts {
  PencilKind kind = PencilKind::Regular;
  LazyMat4 a, b;          ///< the basis used (after re-basing); unset (zero) in filtered facts
  bool rebased = false;   ///< true when the given A was singular
  long rebase_t = 0;      ///< then a = t*A0 - B0, b = -A0, l0 = t + 1/l
  UPolyQ f;               ///< det(l*a - b)
  Rational d2, d3, d4, e; ///< seed 002 Lemma 1 quantities of f (fill_quartic_invariants)
  bool invariants_filled = false; ///< f, d2..e set exactly (report data)
  std::string root_pattern;       ///< "R1".."R9"
  std::vector<RootFacts> real_roots;
  std::vector<Rational> samples;    ///< rational points between the real roots (size k+1)
  std::vector<int> indices;         ///< index at each sample point
  int complex_roots = 0;            ///< number of non-real roots, with multiplicity
  bool complex_double_pair = false; ///< f = c*g^2, g irreducible with complex roots
  bool minimal_poly_split = false;  ///< g(A^-1 B) == 0 for that g (or for a real conjugate pair)
  bool quadruple_n2_zero = false;   ///< (A^-1 B - theta I)^2 == 0 at a quadruple root of rank 2
  bool definite_member = false;     ///< some index is 0 or 4 (Finsler: empty real QSIC)
  bool isolation_fallback = false;  ///< root isolation needed the CGAL fallback
};

/// Exact analysis. Precondition: a, b symmetric.
PencilFacts analyze_pencil_exact(const core::Mat4& a, const core::Mat4& b);

/// The root r in its simplest exact form, for reports: r.factor comes from the square-free
/// decomposition of f and may still be reducible over Q (f = (4l - 9)(l - 36)(l^2 - 9l + 9)
/// is square-free, so its simple roots 9/4 and 36 would read as roots of the quartic). When
/// r has a factor of degree >= 2 and an isolating interval lo < hi, the factor is factored
/// over Z (FLINT) and replaced by the irreducible factor that changes sign on (lo, hi) (the
/// root is simple in the square-free factor, so exactly one does); rational_value is set when
/// that factor is linear, quadratic when it is an irreducible quadratic. Otherwise r is
/// returned unchanged. Decisions never read this: they are made on the facts as analysed.
RootFacts simplest_root_form(RootFacts r);

/// f, D2, D3, D4, E exactly from facts.a, facts.b (integer route), and the root pattern from
/// their signs, checked against the one from the multiplicities when that is already set.
void fill_quartic_invariants(PencilFacts& facts);

/// Root pattern label from the multiplicities of an exact analysis.
std::string root_pattern_from_multiplicities(const PencilFacts& facts);

/// Root pattern label R1..R9 from the exact signs of D2, D3, D4, E (research §3.1).
std::string root_pattern_from_signs(int sd2, int sd3, int sd4, int se);

/// det(l*A - B) exactly.
UPolyQ pencil_char_poly(const core::Mat4& a, const core::Mat4& b);

/// True when B = c*A for some rational c (A nonzero).
bool proportional(const core::Mat4& a, const core::Mat4& b);

} // namespace surfcert::algebra
