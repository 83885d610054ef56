// surfcert::certify::ellipses_in_box (see ellipses_in_box.hpp): exact arithmetic, over Q or over
// Q(sqrt D) for the conjugate planes of a member that splits only there.
#include "surfcert/certify/ellipses_in_box.hpp"

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/inertia.hpp"
#include "surfcert/certify/affine.hpp"

#include <flint/fmpz.h>

#include <vector>

namespace surfcert::certify {

using core::Integer;
using core::Rational;

namespace {

// a + b sqrt(d) for one fixed d > 0 (held by the caller; unset while b is zero): just the field
// operations the ellipse test needs. Exact.
struct QN {
  Rational a, b;
  const Integer* d = nullptr;
  QN() = default;
  QN(const Rational& x) : a(x) {} // NOLINT(google-explicit-constructor): a rational is one
  QN(const Rational& x, const Rational& y, const Integer* dd) : a(x), b(y), d(dd) {}
  bool is_zero() const { return a.is_zero() && b.is_zero(); }
  int sign() const { return algebra::QuadraticNumber{a, b, d ? *d : Integer(0)}.sign(); }
  static const Integer* common(const QN& x, const QN& y) { return x.d ? x.d : y.d; }
  friend QN operator+(const QN& x, const QN& y) { return {x.a + y.a, x.b + y.b, common(x, y)}; }
  friend QN operator-(const QN& x, const QN& y) { return {x.a - y.a, x.b - y.b, common(x, y)}; }
  QN operator-() const { return {-a, -b, d}; }
  QN& operator+=(const QN& y) { return *this = *this + y; }
  friend QN operator*(const QN& x, const QN& y) {
    const Integer* d = common(x, y);
    const Rational bb = x.b * y.b;
    return {x.a * y.a + (bb.is_zero() ? Rational(0) : bb * Rational(*d)), x.a * y.b + x.b * y.a, d};
  }
  friend QN operator/(const QN& x, const QN& y) {
    const Integer* d = common(x, y);
    const Rational norm = y.a * y.a - (y.b.is_zero() ? Rational(0) : y.b * y.b * Rational(*d));
    const QN p = x * QN{y.a, -y.b, d};
    return {p.a / norm, p.b / norm, d};
  }
};

template <class T> using P4 = std::array<T, 4>;

// The affine chart X = col[0] s + col[1] t + col[2] of the plane n . (x, y, z, 1) = 0, solving
// for the first coordinate k with n_k != 0 (algebra::plane_chart's, over T).
template <class T> std::optional<std::array<P4<T>, 3>> chart_of(const P4<T>& n) {
  size_t k = 0;
  while (k < 3 && n[k].is_zero())
    ++k;
  if (k == 3) return std::nullopt;
  const size_t j1 = k == 0 ? 1 : 0, j2 = k == 2 ? 1 : 2;
  std::array<P4<T>, 3> col{};
  col[0][j1] = Rational(1);
  col[0][k] = -n[j1] / n[k];
  col[1][j2] = Rational(1);
  col[1][k] = -n[j2] / n[k];
  col[2][3] = Rational(1);
  col[2][k] = -n[3] / n[k];
  return col;
}

template <class T> bool same_plane(const P4<T>& n, const P4<T>& m) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i + 1; j < 4; ++j)
      if (!(n[i] * m[j] - n[j] * m[i]).is_zero()) return false;
  return true;
}

enum class Place { NotEllipse, Inside, NotInside };

// The section of the quadric a (over T) by the plane n: a real ellipse inside the box, one not
// inside it, or no ellipse (see ellipses_in_box.hpp for the test).
template <class T>
Place section_place(const std::array<P4<T>, 4>& a, const P4<T>& n,
                    const std::array<Rational, 3>& lo, const std::array<Rational, 3>& hi) {
  const auto chart = chart_of(n);
  if (!chart) return Place::NotEllipse;
  const auto& col = *chart;
  const auto cm = algebra::restrict_form(a, col);
  T s00 = cm[0][0], s01 = cm[0][1], s11 = cm[1][1], b0 = cm[0][2], b1 = cm[1][2], c = cm[2][2];
  const T det = s00 * s11 - s01 * s01;
  if (det.sign() <= 0) return Place::NotEllipse; // no definite quadratic part
  if (s00.sign() < 0) {
    s00 = -s00, s01 = -s01, s11 = -s11, b0 = -b0, b1 = -b1, c = -c;
  }
  // (x, y) S^-1 (u, v), S^-1 = [[s11, -s01], [-s01, s00]] / det.
  auto inv = [&](const T& x, const T& y, const T& u, const T& v) {
    return (x * (s11 * u - s01 * v) + y * (s00 * v - s01 * u)) / det;
  };
  const T rho = inv(b0, b1, b0, b1) - c;
  if (rho.sign() <= 0) return Place::NotEllipse; // a point or nothing
  const T u0 = -(s11 * b0 - s01 * b1) / det, v0 = -(s00 * b1 - s01 * b0) / det;
  for (size_t k = 0; k < 3; ++k) {
    const T &g0 = col[0][k], &g1 = col[1][k], &h = col[2][k];
    const T m = g0 * u0 + g1 * v0 + h;
    const T r = rho * inv(g0, g1, g0, g1);
    const T up = T(hi[k]) - m, down = m - T(lo[k]);
    if (up.sign() < 0 || down.sign() < 0 || (r - up * up).sign() > 0 ||
        (r - down * down).sign() > 0)
      return Place::NotInside;
  }
  return Place::Inside;
}

// The planes of a rank-2 member e that are real but split only over Q(sqrt D): x^T e x =
// p alpha^2 + 2 q alpha beta + r beta^2 in alpha = C_i . x, beta = C_j . x (C the columns of a
// nonzero principal minor S, [[p, q], [q, r]] = S^-1), alpha = ((-q +- sqrt(q^2 - p r)) / p)
// beta; D = num * den of q^2 - p r. nullopt for a rational square (rational_plane_pair's), a
// non-positive discriminant or p = 0 (then the planes are rational).
std::optional<std::array<P4<QN>, 2>> conjugate_planes(const core::Mat4& e, Integer& D) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i + 1; j < 4; ++j) {
      const Rational det = e[i][i] * e[j][j] - e[i][j] * e[i][j];
      if (det.is_zero()) continue;
      const Rational p = e[j][j] / det, q = -e[i][j] / det, r = e[i][i] / det;
      const Rational disc = q * q - p * r;
      if (disc.sign() <= 0 || p.is_zero()) return std::nullopt;
      D = disc.num() * disc.den();
      if (fmpz_is_square(D.raw())) return std::nullopt;
      // alpha - ((-q +- sqrt(disc)) / p) beta, sqrt(disc) = sqrt(D) / den.
      const Rational s = Rational(1) / (Rational(disc.den()) * p);
      std::array<P4<QN>, 2> n;
      for (size_t k = 0; k < 4; ++k) {
        const Rational &al = e[k][i], &be = e[k][j];
        n[0][k] = QN{al + (q / p) * be, -s * be, &D};
        n[1][k] = QN{al + (q / p) * be, s * be, &D};
      }
      return n;
    }
  return std::nullopt;
}

} // namespace

std::optional<int> ellipses_in_box(const algebra::PencilFacts& facts, int loops,
                                   const std::array<Rational, 3>& lo,
                                   const std::array<Rational, 3>& hi) {
  const core::Mat4& a = facts.a;
  const core::Mat4& b = facts.b;
  if (a == core::Mat4{}) return std::nullopt; // the basis is not set
  std::vector<P4<Rational>> seen;
  int ellipses = 0, inside = 0;
  auto count = [&](Place p) {
    if (p == Place::NotEllipse) return;
    ++ellipses;
    inside += p == Place::Inside ? 1 : 0;
  };
  for (const auto& root : facts.real_roots) {
    if (root.rank > 2 || !root.rational_value) continue;
    const core::Mat4 e = core::scaled(a, *root.rational_value) + core::scaled(b, -1);
    const auto planes = rational_member_planes(e, root.rank);
    for (const auto& n : planes) {
      bool again = false;
      for (const auto& m : seen)
        again = again || same_plane(n, m);
      if (again) continue;
      seen.push_back(n);
      count(section_place(a, n, lo, hi));
    }
    if (!planes.empty() || root.rank != 2) continue;
    // Two conjugate planes over Q(sqrt D): one conic in each (no plane of another member).
    Integer D;
    const auto conj = conjugate_planes(e, D);
    if (!conj) continue;
    std::array<P4<QN>, 4> aq;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        aq[i][j] = QN(a[i][j]);
    for (const auto& n : *conj)
      count(section_place(aq, n, lo, hi));
  }
  if (ellipses != loops) return std::nullopt;
  return inside;
}

} // namespace surfcert::certify
