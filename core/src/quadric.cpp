#include "surfcert/core/quadric.hpp"

#include <flint/fmpq_mat.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

namespace surfcert::core {

bool is_symmetric(const Mat4& m) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i + 1; j < 4; ++j)
      if (m[i][j] != m[j][i]) return false;
  return true;
}

bool is_zero(const Mat4& m) {
  for (const auto& row : m)
    for (const auto& v : row)
      if (!v.is_zero()) return false;
  return true;
}

Mat4 identity4() {
  Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    m[i][i] = Rational(1);
  return m;
}

Mat4 transpose(const Mat4& m) {
  Mat4 t;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      t[i][j] = m[j][i];
  return t;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      Rational s;
      for (size_t k = 0; k < 4; ++k)
        if (!a[i][k].is_zero() && !b[k][j].is_zero()) s += a[i][k] * b[k][j];
      r[i][j] = s;
    }
  return r;
}

Mat4 congruence(const Mat4& p, const Mat4& m) {
  // On integers: P = pn / dp and M = mn / dm over their common denominators, the products
  // summed in FLINT integers, each entry of P^T M P = pn^T mn pn / (dm dp^2) canonicalised once.
  std::array<const Rational*, 16> pp{}, mp{};
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      pp[4 * i + j] = &p[i][j];
      mp[4 * i + j] = &m[i][j];
    }
  std::array<Integer, 16> pn, mn, t; // t = mn pn
  Integer dp, dm;
  over_common_denominator(pp.data(), 16, pn.data(), dp);
  over_common_denominator(mp.data(), 16, mn.data(), dm);
  for (size_t k = 0; k < 4; ++k)
    for (size_t j = 0; j < 4; ++j)
      for (size_t l = 0; l < 4; ++l)
        if (!mn[4 * k + l].is_zero() && !pn[4 * l + j].is_zero())
          fmpz_addmul(t[4 * k + j].raw_mut(), mn[4 * k + l].raw(), pn[4 * l + j].raw());
  Integer den, s;
  fmpz_mul(den.raw_mut(), dp.raw(), dp.raw());
  fmpz_mul(den.raw_mut(), den.raw(), dm.raw());
  Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j) {
      fmpz_zero(s.raw_mut());
      for (size_t k = 0; k < 4; ++k)
        if (!pn[4 * k + i].is_zero() && !t[4 * k + j].is_zero())
          fmpz_addmul(s.raw_mut(), pn[4 * k + i].raw(), t[4 * k + j].raw());
      fmpq_set_fmpz_frac(r[i][j].raw_mut(), s.raw(), den.raw());
      if (j != i) r[j][i] = r[i][j];
    }
  return r;
}

Mat4 operator+(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      r[i][j] = a[i][j] + b[i][j];
  return r;
}

Mat4 scaled(const Mat4& a, const Rational& c) {
  Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      r[i][j] = a[i][j] * c;
  return r;
}

Rational leading_minor(const Mat4& m, int k) {
  fmpq_mat_t t;
  fmpq_mat_init(t, k, k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      fmpq_set(fmpq_mat_entry(t, i, j), m[static_cast<size_t>(i)][static_cast<size_t>(j)].raw());
  Rational d;
  fmpq_mat_det(d.raw_mut(), t);
  fmpq_mat_clear(t);
  return d;
}

Rational det(const Mat4& m) {
  return leading_minor(m, 4);
}

QuadricMatrix::QuadricMatrix(const Mat4& m) : state_(std::make_shared<State>()) {
  if (!is_symmetric(m)) throw std::invalid_argument("quadric matrix is not symmetric");
  if (is_zero(m)) throw std::invalid_argument("quadric matrix is zero");
  state_->m = m; // formed: matrix() reads it without the once flag
}

QuadricMatrix::QuadricMatrix(const ShapeSpec& s) : state_(std::make_shared<State>()) {
  state_->shape = s;
}

QuadricMatrix QuadricMatrix::from_double_matrix(const DoubleMat4& d) {
  bool zero = true;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      if (!std::isfinite(d[i][j])) throw std::invalid_argument("quadric matrix entry not finite");
      // d_ij + d_ji = 0 exactly iff d_ji = -d_ij (gradual underflow: a nonzero exact sum never
      // rounds to zero), so this is the exact test of a zero symmetric part.
      zero = zero && d[i][j] == -d[j][i];
    }
  if (zero) throw std::invalid_argument("quadric matrix is zero");
  QuadricMatrix q;
  q.state_ = std::make_shared<State>();
  q.state_->doubles = d;
  return q;
}

Mat4 symmetric_part_exact(const DoubleMat4& d) {
  Mat4 m;
  for (size_t i = 0; i < 4; ++i) {
    m[i][i] = Rational::exact_from_double(d[i][i]);
    for (size_t j = i + 1; j < 4; ++j) {
      Rational v = Rational::exact_from_double(d[i][j]);
      if (d[j][i] != d[i][j]) v = (v + Rational::exact_from_double(d[j][i])) * Rational(1, 2);
      m[j][i] = v;
      m[i][j] = std::move(v);
    }
  }
  return m;
}

const Mat4& QuadricMatrix::matrix() const {
  State& s = *state_;
  if (!s.shape && !s.doubles) return s.m; // formed at construction
  std::call_once(s.formed, [&s] {
    s.m = s.shape ? exact_matrix(*s.shape) : symmetric_part_exact(*s.doubles);
  });
  return s.m;
}

QuadricMatrix QuadricMatrix::from_poly(const Poly3& p) {
  int d = p.total_degree();
  if (d < 1 || d > 2) throw std::invalid_argument("quadric needs total degree 1 or 2");
  Mat4 m;
  const Rational half(1, 2);
  for (const auto& [e, c] : p.terms()) {
    // Index of each variable occurrence: x=0, y=1, z=2, w (missing degree) = 3.
    int idx[2];
    int n = 0;
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < e[static_cast<size_t>(v)]; ++k)
        idx[n++] = v;
    while (n < 2)
      idx[n++] = 3;
    auto i = static_cast<size_t>(idx[0]), j = static_cast<size_t>(idx[1]);
    if (i == j) {
      m[i][i] += c;
    } else {
      m[i][j] += c * half;
      m[j][i] += c * half;
    }
  }
  return QuadricMatrix(m);
}

Poly3 QuadricMatrix::to_poly() const {
  Poly3 p;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      Poly3::Exponent e{0, 0, 0};
      if (i < 3) ++e[i];
      if (j < 3) ++e[j];
      p.add_term(e, matrix()[i][j]);
    }
  return p;
}

QuadricMatrix QuadricMatrix::congruent(const Mat4& p) const {
  return QuadricMatrix(congruence(p, matrix()));
}

QuadricMatrix QuadricMatrix::translated(const std::array<double, 3>& c) const {
  if (const ShapeSpec* sp = shape()) {
    // The same exact surface as the congruence below when every centre coordinate minus c
    // is exact in double; its exact matrix (hundreds of digits for a double quaternion) is
    // then still not formed.
    ShapeSpec moved = *sp;
    bool exact = true;
    for (size_t k = 0; k < 3 && exact; ++k) {
      moved.center[k] = sp->center[k] - c[k];
      exact = std::isfinite(moved.center[k]) &&
              Rational::exact_from_double(moved.center[k]) ==
                  Rational::exact_from_double(sp->center[k]) - Rational::exact_from_double(c[k]);
    }
    if (exact) return with_invariants_of(QuadricMatrix(moved));
  }
  Mat4 p = identity4();
  for (size_t i = 0; i < 3; ++i)
    p[i][3] = Rational::exact_from_double(c[i]);
  return with_invariants_of(congruent(p));
}

// log2 |x| within 1 (x != 0), from the bit lengths of its numerator and denominator: no
// double conversion, which under- or overflows at the scales this is for.
namespace {
long log2_about(const Rational& x) {
  return x.num().bits() - x.den().bits();
}
} // namespace

QuadricMatrix QuadricMatrix::rescaled(int k) const {
  if (const ShapeSpec* sp = shape()) {
    ShapeSpec moved = *sp;
    bool exact = true;
    auto shrink = [k, &exact](double& v) {
      const double w = std::ldexp(v, -k);
      exact = exact && std::isfinite(w) && std::ldexp(w, k) == v; // no rounding either way
      v = w;
    };
    for (size_t i = 0; i < 3; ++i) {
      shrink(moved.center[i]);
      shrink(moved.radii[i]);
    }
    if (exact) return with_invariants_of(QuadricMatrix(moved));
  }
  Mat4 p{};
  for (size_t i = 0; i < 3; ++i)
    p[i][i] = pow2(k);
  p[3][3] = Rational(1);
  Mat4 m = congruence(p, matrix());
  // Divided by a power of two near its largest entry (the same quadric): the quadratic block
  // grew by 2^2k, and the double computations downstream need entries of moderate size.
  long top = LONG_MIN;
  for (const auto& row : m)
    for (const Rational& x : row)
      if (!x.is_zero()) top = std::max(top, log2_about(x));
  return with_invariants_of(QuadricMatrix(top == LONG_MIN ? m : scaled(m, pow2(-top))));
}

// A translation and a positive scaling are affine changes of coordinates: the moved quadric
// has this one's kind and is singular exactly when this one is, so what this one has already
// computed is handed on (the translated pairs of the tracer asked both again: ~4% of a pair).
QuadricMatrix QuadricMatrix::with_invariants_of(QuadricMatrix moved) const {
  moved.state_->kind.store(state_->kind.load(std::memory_order_relaxed), std::memory_order_relaxed);
  moved.state_->singular.store(state_->singular.load(std::memory_order_relaxed),
                               std::memory_order_relaxed);
  return moved;
}

// See quadric.hpp.
std::optional<long> length_order(const QuadricMatrix& q) {
  if (const ShapeSpec* sp = q.shape()) {
    double m = 0;
    for (size_t k = 0; k < 3; ++k)
      m = std::max({m, std::fabs(sp->center[k]), std::fabs(sp->radii[k])});
    if (!(m > 0) || !std::isfinite(m)) return std::nullopt;
    return std::ilogb(m);
  }
  std::optional<long> la, lb, lc;
  auto grow = [](std::optional<long>& l, const Rational& x) {
    if (x.is_zero()) return;
    const long v = log2_about(x);
    l = l ? std::max(*l, v) : v;
  };
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      grow(la, q(i, j));
    grow(lb, q(i, 3));
  }
  grow(lc, q(3, 3));
  std::optional<long> out;
  auto take = [&out](long v) { out = out ? std::max(*out, v) : v; };
  if (la) {
    if (lb) take(*lb - *la);
    if (lc) take((*lc - *la) / 2);
  } else if (lb && lc) {
    take(*lc - *lb);
  }
  return out;
}

bool QuadricMatrix::is_plane() const {
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      if (!matrix()[i][j].is_zero()) return false;
  return true;
}

namespace {

// kind() from the exact matrix (see kind()).
QuadricKind kind_of(const Mat4& mm) {
  // Sylvester's criterion, each minor only when the smaller ones left the block possibly
  // definite (the 1x1 and 2x2 ones directly: through fmpq_mat they were ~3% of a traced pair).
  const int s = mm[0][0].sign();
  if (s == 0) return QuadricKind::Other;
  if ((mm[0][0] * mm[1][1] - mm[0][1] * mm[0][1]).sign() <= 0) return QuadricKind::Other;
  if (leading_minor(mm, 3).sign() != s) return QuadricKind::Other;
  // Normalise to a positive definite block: det scales by s^4 = 1, so the real-point test is
  // det(A) < 0 for both signs.
  int sd = det(mm).sign();
  if (sd < 0) return QuadricKind::Ellipsoid;
  if (sd > 0) return QuadricKind::ImaginaryEllipsoid;
  return QuadricKind::Other; // a single point (imaginary cone with real vertex)
}

} // namespace

QuadricKind QuadricMatrix::kind() const {
  // Upper 3x3 block definite (up to sign) <=> ellipsoid-like; then real iff det has the
  // opposite sign of the definite block's sign (e.g. diag(1,1,1,-1): det < 0).
  if (const ShapeSpec* sp = shape()) // by construction (radii > 0, R invertible)
    return sp->type == ShapeType::Sphere || sp->type == ShapeType::Ellipsoid
               ? QuadricKind::Ellipsoid
               : QuadricKind::Other;
  const int known = state_->kind.load(std::memory_order_relaxed);
  if (known >= 0) return static_cast<QuadricKind>(known);
  const QuadricKind k = kind_of(matrix());
  state_->kind.store(static_cast<int>(k), std::memory_order_relaxed);
  return k;
}

bool QuadricMatrix::singular() const {
  if (const ShapeSpec* sp = shape()) {
    // det diag(q0, q1, [[q2, lz/2], [lz/2, k]]) = q0 q1 (q2 k - lz^2 / 4), up to the positive
    // factors of the radii and the congruence by the (invertible) pose.
    const LocalForm lf = local_form(sp->type);
    const int q01 = lf.q_sign[0] * lf.q_sign[1];
    return q01 == 0 || 4 * lf.q_sign[2] * lf.constant == lf.linear_z * lf.linear_z;
  }
  const int known = state_->singular.load(std::memory_order_relaxed);
  if (known >= 0) return known == 1;
  const bool s = det(matrix()).is_zero();
  state_->singular.store(s ? 1 : 0, std::memory_order_relaxed);
  return s;
}

bool QuadricMatrix::is_sphere() const {
  if (kind() != QuadricKind::Ellipsoid) return false;
  const Mat4& mm = matrix();
  return mm[0][1].is_zero() && mm[0][2].is_zero() && mm[1][2].is_zero() && mm[0][0] == mm[1][1] &&
         mm[1][1] == mm[2][2];
}

} // namespace surfcert::core
