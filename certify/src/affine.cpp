// affine_topology: the affine reading of a certified QSIC topology (see affine.hpp).
#include "surfcert/certify/affine.hpp"

#include "surfcert/certify/cone_ovals.hpp"
#include "surfcert/certify/curve_lines.hpp"
#include "surfcert/certify/distance/quadratic_forms.hpp"

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/kernel.hpp"
#include "surfcert/algebra/pencil.hpp"
#include "surfcert/algebra/plane_chart.hpp"
#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/upoly.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <map>
#include <set>

namespace surfcert::certify {

namespace {

using algebra::QuadraticNumber;
using algebra::UPolyQ;
using algebra::UPolyZ;
using core::Integer;
using core::Rational;
using M3 = std::array<std::array<Rational, 3>, 3>;
using V3 = std::array<Rational, 3>;
using core::io::Json;

M3 top_left(const core::Mat4& m) {
  M3 r;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      r[i][j] = m[i][j];
  return r;
}

M3 congruent(const M3& a, const M3& t) { // t^T a t
  std::array<V3, 3> cols;
  for (size_t i = 0; i < 3; ++i)
    for (size_t k = 0; k < 3; ++k)
      cols[i][k] = t[k][i];
  return algebra::restrict_form(a, cols);
}

bool is_zero3(const M3& m) {
  for (const auto& row : m)
    for (const auto& x : row)
      if (!x.is_zero()) return false;
  return true;
}

// Direction normalised so that its first nonzero coordinate is 1 (a projective point).
V3 normalise(V3 d) {
  for (const auto& x : d)
    if (!x.is_zero()) {
      Rational c = x;
      for (auto& y : d)
        y = y / c;
      break;
    }
  return d;
}

// The line n . (x, y, z) = 0 of the plane at infinity as a component lying there (n
// normalised: one text per line).
ComponentAtInfinity line_at_infinity(const V3& normal) {
  const V3 n = normalise(normal);
  ComponentAtInfinity li;
  li.kind = "line";
  li.equation =
      n[0].to_string() + "*x + " + n[1].to_string() + "*y + " + n[2].to_string() + "*z = 0 (w = 0)";
  return li;
}

std::array<double, 3> unit_approx(std::array<double, 3> d) {
  // Scaled by the largest magnitude first: the squares of directions ~1e300 (a pair posed at
  // 1e300) overflowed, and the quotient inf / inf wrote NaN into the JSON (an internal error
  // at --json; helper-26's probe). A component that itself overflowed (its exact value beyond
  // the doubles) dominates the others: it is read as +-1 and the finite ones as 0.
  double m = 0;
  for (double x : d)
    m = std::max(m, std::fabs(x));
  if (!(m > 0) || std::isnan(m)) return {0, 0, 0};
  for (double& x : d)
    x = std::isinf(m) ? (std::isinf(x) ? (x > 0 ? 1.0 : -1.0) : 0.0) : x / m;
  double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(n > 0)) return d;
  // Sign: first nonzero coordinate positive (the same projective point either way).
  double s = 1;
  for (double x : d)
    if (std::fabs(x) > 1e-300) {
      s = x < 0 ? -1 : 1;
      break;
    }
  return {s * d[0] / n, s * d[1] / n, s * d[2] / n};
}

// Polynomial in u as UPolyQ from constant, linear, quadratic coefficients.
UPolyQ poly(const Rational& c0, const Rational& c1, const Rational& c2 = Rational(0)) {
  return UPolyQ::from_coeffs({c0, c1, c2});
}

double eval_double(const UPolyQ& p, double x) {
  double s = 0;
  for (long i = p.degree(); i >= 0; --i)
    s = s * x + p.coeff(i).to_double_approx();
  return s;
}

// ---------------------------------------------------------------------------------------
// Points at infinity of the curve: common points of the conics at infinity.

struct Chart {
  M3 t;       ///< original direction = t * (u, v, s)
  UPolyQ r;   ///< resultant in u (degree 4)
  UPolyQ s11; ///< first subresultant: s11(u) v + s10(u)
  UPolyQ s10;
  /// A rational u at which s11 = s10 = 0 and the common point is one double root v.
  std::optional<std::pair<Rational, Rational>> double_point;
  Rational v_at(const Rational& u) const {
    if (double_point && double_point->first == u) return double_point->second;
    return -s10.evaluate(u) / s11.evaluate(u);
  }
};

enum class ChartOutcome { Ok, SharedComponent, Failed };

// The candidate charts: the identity, then fixed integer matrices with every entry free (a
// chart keeping x = u could never separate two points with x = 0); each invertible (a
// singular one, {1, 2, 1, 1, 1, 0, 0, 1, 1}, was listed and always skipped).
constexpr int kCharts[][9] = {
    {1, 0, 0, 0, 1, 0, 0, 0, 1},   {1, 1, 0, 0, 1, 0, 0, 0, 1},    {2, 1, -1, 1, 3, 1, -1, 2, 1},
    {1, -3, 2, 2, 1, -1, 3, 1, 2}, {3, 5, -2, -1, 2, 4, 2, -3, 1}, {1, 4, 7, -2, 1, 3, 5, -1, 2},
    {4, -1, 3, 2, 5, -3, 1, 2, 7}, {7, 2, -5, 3, -4, 1, 2, 6, 3},  {5, 11, -3, -7, 2, 9, 4, -1, 6}};

constexpr long det3(const int* k) {
  return static_cast<long>(k[0]) * (k[4] * k[8] - k[5] * k[7]) -
         static_cast<long>(k[1]) * (k[3] * k[8] - k[5] * k[6]) +
         static_cast<long>(k[2]) * (k[3] * k[7] - k[4] * k[6]);
}

constexpr bool all_invertible() {
  for (const auto& k : kCharts)
    if (det3(k) == 0) return false;
  return true;
}
static_assert(all_invertible(), "every chart candidate is invertible");

ChartOutcome find_chart(const M3& a_inf, const M3& b_inf, Chart& out) {
  // Tried in turn, each formed only when reached (the identity, first, almost always fits: the
  // ten matrices formed up front, with their determinants, were ~5% of a pipe pair's intersect).
  for (size_t c = 0; c < std::size(kCharts); ++c) {
    M3 t;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        t[i][j] = Rational(kCharts[c][3 * i + j]);
    const bool identity = c == 0;
    M3 a = identity ? a_inf : congruent(a_inf, t), b = identity ? b_inf : congruent(b_inf, t);
    // coordinates (u, v, s): index 0 = u, 1 = v, 2 = s.
    const Rational& a2 = a[1][1];
    const Rational& b2 = b[1][1];
    if (a2.is_zero() || b2.is_zero()) continue;
    UPolyQ a1 = poly(Rational(2) * a[1][2], Rational(2) * a[0][1]);
    UPolyQ a0 = poly(a[2][2], Rational(2) * a[0][2], a[0][0]);
    UPolyQ b1 = poly(Rational(2) * b[1][2], Rational(2) * b[0][1]);
    UPolyQ b0 = poly(b[2][2], Rational(2) * b[0][2], b[0][0]);
    UPolyQ A2(a2), B2(b2);
    UPolyQ x = A2 * b0 - a0 * B2;
    UPolyQ r = x * x - (A2 * b1 - a1 * B2) * (a1 * b0 - a0 * b1);
    // With a2, b2 != 0 constant, r == 0 exactly when the conics share a component.
    if (r.is_zero()) return ChartOutcome::SharedComponent;
    if (r.degree() != 4) continue; // a common point on s = 0
    UPolyQ s11 = B2 * a1 - A2 * b1, s10 = B2 * a0 - A2 * b0;
    if (s11.is_zero()) continue;
    std::optional<std::pair<Rational, Rational>> dbl;
    if (s11.degree() == 1) {
      Rational root = -s11.coeff(0) / s11.coeff(1);
      if (r.evaluate(root).is_zero()) {
        // At u = root both restrictions are proportional (s10 vanishes there too, or the
        // resultant would not): one common point when they are a double root, v0 = -a1/(2 a2);
        // two on this vertical line otherwise (then another chart).
        const Rational a1r = a1.evaluate(root), a0r = a0.evaluate(root);
        if (!s10.evaluate(root).is_zero() || !(a1r * a1r - Rational(4) * a2 * a0r).is_zero())
          continue;
        dbl = std::make_pair(root, -a1r / (Rational(2) * a2));
      }
    }
    out = Chart{t, r, s11, s10, dbl};
    return ChartOutcome::Ok;
  }
  return ChartOutcome::Failed;
}

struct Root {
  PointAtInfinity p;
  UPolyZ factor;
  Rational lo, hi; // isolating interval (lo == hi when rational)
};

std::vector<Root> roots_of(const Chart& ch) {
  std::vector<Root> out;
  const UPolyZ rz = ch.r.primitive_integer();
  // No real point at infinity (every bounded curve): a Sturm count settles it; the full
  // factorisation below (FLINT's Zassenhaus on large coefficients) cost most of this route.
  if (!algebra::has_real_root(rz)) return out;
  for (const algebra::IrreducibleFactor& fac : algebra::irreducible_factors(rz)) {
    const UPolyZ g = fac.poly.primitive_part();
    const int e = fac.exponent;
    if (g.degree() == 1) {
      Rational u0 = -Rational(g.coeff(0)) / Rational(g.coeff(1));
      Rational v0 = ch.v_at(u0);
      V3 w{u0, v0, Rational(1)};
      V3 d;
      for (size_t k = 0; k < 3; ++k)
        for (size_t l = 0; l < 3; ++l)
          d[k] += ch.t[k][l] * w[l];
      d = normalise(d);
      Root r;
      r.p.multiplicity = e;
      r.p.rational = true;
      std::array<double, 3> ap{};
      for (size_t k = 0; k < 3; ++k) {
        r.p.direction[k] = d[k].to_string();
        ap[k] = d[k].to_double_approx();
      }
      r.p.approx = unit_approx(ap);
      r.factor = g;
      r.lo = r.hi = u0;
      out.push_back(std::move(r));
      continue;
    }
    algebra::RootSeparation sep = algebra::isolate_real_roots(g);
    // Direction as polynomials in t: T * (t s11(t), -s10(t), s11(t)) (s11(t) != 0 at roots).
    UPolyQ tpoly = UPolyQ::linear(Rational(1), Rational(0));
    std::array<UPolyQ, 3> w{tpoly * ch.s11, UPolyQ(0) - ch.s10, ch.s11};
    std::array<UPolyQ, 3> dir;
    for (size_t k = 0; k < 3; ++k) {
      UPolyQ s(0);
      for (size_t l = 0; l < 3; ++l)
        s = s + UPolyQ(ch.t[k][l]) * w[l];
      dir[k] = s;
    }
    for (size_t j = 0; j + 1 < sep.separators.size(); ++j) {
      Root r;
      r.p.multiplicity = e;
      r.p.rational = false;
      r.lo = sep.separators[j];
      r.hi = sep.separators[j + 1];
      Rational lo = r.lo, hi = r.hi;
      algebra::refine_root_newton(g, lo, hi, Rational(1, 1UL << 60)); // an estimate: any bracket
      const double t0 = ((lo + hi) * Rational(1, 2)).to_double_approx();
      std::array<double, 3> ap{};
      bool finite = true;
      for (size_t k = 0; k < 3; ++k) {
        ap[k] = eval_double(dir[k], t0);
        finite = finite && std::isfinite(ap[k]);
      }
      if (!finite) {
        // Coefficients beyond the doubles (a pair posed at 1e300): the direction at the
        // bracket's midpoint exactly, divided by its largest component before rounding.
        const Rational mid = (lo + hi) * Rational(1, 2);
        std::array<Rational, 3> ex;
        Rational big(0);
        for (size_t k = 0; k < 3; ++k) {
          ex[k] = dir[k].evaluate(mid);
          big = std::max(big, core::abs(ex[k]));
        }
        for (size_t k = 0; k < 3; ++k)
          ap[k] = big.is_zero() ? 0.0 : (ex[k] / big).to_double_approx();
      }
      r.p.approx = unit_approx(ap);
      r.p.polynomial = g;
      r.p.lo = r.lo;
      r.p.hi = r.hi;
      r.p.dir_in_t = dir;
      r.factor = g;
      out.push_back(std::move(r));
    }
  }
  return out;
}

M3 inverse(const M3& m) {
  M3 r;
  Rational det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      const size_t i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      r[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
    }
  return r;
}

// Index of the root at the rational direction d (nullopt when none).
std::optional<size_t> match_root(const Chart& ch, const std::vector<Root>& roots, const V3& d) {
  M3 ti = inverse(ch.t);
  V3 w;
  for (size_t k = 0; k < 3; ++k)
    for (size_t l = 0; l < 3; ++l)
      w[k] += ti[k][l] * d[l];
  if (w[2].is_zero()) return std::nullopt;
  const Rational u0 = w[0] / w[2], v0 = w[1] / w[2];
  for (size_t i = 0; i < roots.size(); ++i) {
    const Root& r = roots[i];
    if (r.factor.sign_at(u0) != 0) continue;
    if (r.lo != r.hi && !(r.lo < u0 && u0 < r.hi)) continue; // (the double point is rational)
    if (r.lo == r.hi && r.lo != u0) continue;
    // The chart puts one point on each vertical line: v must be that point's.
    if (ch.v_at(u0) != v0) return std::nullopt;
    return i;
  }
  return std::nullopt;
}

// The same for a special point whose direction d has coordinates in Q(sqrt d) (a crossing
// at conjugate points at infinity): u0 = w0 / w2, v0 = w1 / w2 over Q(sqrt d), a root of the
// factor exactly, placed in its isolating interval by exact signs, and on the chart's point
// of that vertical line (v = -s10(u0) / s11(u0)).
std::optional<size_t> match_root(const Chart& ch, const std::vector<Root>& roots,
                                 const std::array<QuadraticNumber, 3>& d) {
  using algebra::quadratic_add;
  using algebra::quadratic_div;
  using algebra::quadratic_mul;
  const Integer& f = d[0].d;
  auto num = [&f](const Rational& r) { return QuadraticNumber{r, Rational(0), f}; };
  auto is_zero = [](const QuadraticNumber& x) { return x.a.is_zero() && x.b.is_zero(); };
  for (const auto& c : d)
    if (c.d != f && !c.b.is_zero()) return std::nullopt; // not one field
  const M3 ti = inverse(ch.t);
  std::array<QuadraticNumber, 3> w{num(Rational(0)), num(Rational(0)), num(Rational(0))};
  for (size_t k = 0; k < 3; ++k)
    for (size_t l = 0; l < 3; ++l)
      w[k] = quadratic_add(w[k], quadratic_mul(num(ti[k][l]), {d[l].a, d[l].b, f}));
  if (is_zero(w[2])) return std::nullopt;
  const QuadraticNumber u0 = quadratic_div(w[0], w[2]), v0 = quadratic_div(w[1], w[2]);
  auto at = [&](const auto& p) { // Horner over Q(sqrt d)
    QuadraticNumber s = num(Rational(0));
    for (long i = p.degree(); i >= 0; --i)
      s = quadratic_add(quadratic_mul(s, u0), num(Rational(p.coeff(i))));
    return s;
  };
  for (size_t i = 0; i < roots.size(); ++i) {
    const Root& r = roots[i];
    if (r.lo == r.hi) {
      if (!u0.b.is_zero() || u0.a != r.lo) continue;
    } else {
      if (!is_zero(at(r.factor))) continue;
      if (quadratic_add(u0, num(r.lo), -1).sign() <= 0) continue;
      if (quadratic_add(num(r.hi), u0, -1).sign() <= 0) continue;
    }
    if (ch.double_point && u0.b.is_zero() && ch.double_point->first == u0.a)
      return ch.double_point->second == v0.a && v0.b.is_zero() ? std::optional<size_t>(i)
                                                               : std::nullopt;
    const QuadraticNumber s11 = at(ch.s11);
    if (is_zero(s11)) return std::nullopt;
    const QuadraticNumber v = quadratic_div(at(ch.s10), s11);
    if (!is_zero(quadratic_add(v, v0))) return std::nullopt; // v0 must be -s10 / s11
    return i;
  }
  return std::nullopt;
}

// The sign of the linear form l . d at the point at infinity d of r, exactly (0: zero or not
// decided).
int form_sign_at(const Root& r, const V3& l) {
  if (r.p.rational) {
    Rational s;
    for (size_t k = 0; k < 3; ++k) {
      const auto dk = Rational::from_string(r.p.direction[k]);
      if (!dk) return 0;
      s += l[k] * *dk;
    }
    return s.sign();
  }
  UPolyQ s(0);
  for (size_t k = 0; k < 3; ++k)
    s = s + UPolyQ(l[k]) * r.p.dir_in_t[k];
  if (s.is_zero()) return 0;
  return algebra::sign_at_root(s, r.factor, r.lo, r.hi);
}

// (s, t) with a s^2 + 2 b s t + c t^2 > 0, exactly; nullopt when the form is <= 0 everywhere.
std::optional<std::pair<Rational, Rational>> positive_pair(const Rational& a, const Rational& b,
                                                           const Rational& c) {
  if (a.sign() > 0) return std::make_pair(Rational(1), Rational(0));
  if (c.sign() > 0) return std::make_pair(Rational(0), Rational(1));
  if (b.is_zero()) return std::nullopt; // a, c <= 0
  // a = 0: at (1, t), t (2 b + c t) > 0 for t = b / (1 + |c|) (then |c t| < |b|); c = 0 alike.
  if (a.is_zero()) return std::make_pair(Rational(1), b / (Rational(1) + core::abs(c)));
  if (c.is_zero()) return std::make_pair(b / (Rational(1) + core::abs(a)), Rational(1));
  // a, c < 0: the maximum over t at (1, t) is at t = -b / c, a - b^2 / c, positive exactly
  // when b^2 > a c.
  if (b * b > a * c) return std::make_pair(Rational(1), -b / c);
  return std::nullopt;
}

// A vector x with x^T m x > 0 for the symmetric rational 3x3 m, exactly; nullopt when m is
// negative semidefinite. A positive diagonal entry gives a unit vector; else, at a negative
// one m_ii, m = (r_i . x)^2 / m_ii + m' with m' zero in row and column i: a positive y of m'
// (in the other two coordinates), moved along e_i onto r_i . x = 0, is one of m (m' <= 0 there
// means m <= 0); with the whole diagonal zero, an off-diagonal entry's coordinate plane.
std::optional<V3> positive_direction(const M3& m) {
  for (size_t i = 0; i < 3; ++i)
    if (m[i][i].sign() > 0) {
      V3 x;
      x[i] = Rational(1);
      return x;
    }
  for (size_t i = 0; i < 3; ++i) {
    if (m[i][i].is_zero()) continue;
    const size_t j = (i + 1) % 3, k = (i + 2) % 3;
    auto reduced = [&m, i](size_t r, size_t c) { return m[r][c] - m[r][i] * m[i][c] / m[i][i]; };
    const auto st = positive_pair(reduced(j, j), reduced(j, k), reduced(k, k));
    if (!st) return std::nullopt;
    V3 x;
    x[j] = st->first;
    x[k] = st->second;
    x[i] = -(m[i][j] * x[j] + m[i][k] * x[k]) / m[i][i];
    return x;
  }
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3;
    if (m[i][j].is_zero()) continue;
    const auto st = positive_pair(Rational(0), m[i][j], Rational(0));
    V3 x;
    x[i] = st->first;
    x[j] = st->second;
    return x;
  }
  return std::nullopt;
}

// A figure eight (a real curve with one crunode p, affine) by its lobes: how many points at
// infinity lie on each. The member K of the pencil singular at p is a cone with apex p (its
// kernel: the rational root of det(l A - B) where rank 3 and the apex lies on the curve), and
// projecting from p maps the curve minus p one to one onto K's conic at infinity C (the
// generators' directions; a point at infinity of the curve onto itself), each lobe onto an arc
// of C between the directions P1, P2 of the node's two branches. Those are the generators of K
// in the tangent plane n . (x - p) = 0 of the other quadric at p: the line n . d = 0 of the
// plane at infinity meets C in P1, P2 (real and distinct exactly when n^T adj(K3) n < 0, K3 the
// quadratic part). In the chart of the plane at infinity sending a line m . d = 0 that misses C
// (m^T adj(K3) m > 0) to infinity, C is an ellipse and the two arcs lie on the two sides of the
// chord P1 P2: a point d of C lies on the arc given by the sign of (n . d) / (m . d), decided
// exactly (rational directions; Arb at the algebraic ones, refined until decided). nullopt
// when no such cone is found or a sign is not decided.
std::optional<std::pair<int, int>> lobe_split(const core::Mat4& a, const core::Mat4& b,
                                              const std::vector<Root>& roots) {
  // The candidates (K, Q) with K ∩ Q the curve: (A, B), then (l A - B, A) at each rational root
  // l of det(l A - B) (B itself at l = 0).
  std::vector<std::pair<core::Mat4, const core::Mat4*>> members{{a, &b}};
  for (const Rational& l : algebra::rational_roots(algebra::pencil_char_poly(a, b))) {
    core::Mat4 k;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        k[i][j] = l * a[i][j] - b[i][j];
    members.emplace_back(k, &a);
  }
  for (const auto& [k, q] : members) {
    const auto ker = algebra::kernel_basis(k);
    if (ker.size() != 1 || ker[0][3].is_zero()) continue; // not a cone with an affine apex
    const std::array<Rational, 4>& v = ker[0];
    if (!algebra::bilinear(*q, v, v).is_zero()) continue; // the apex is not on the curve
    V3 n; // the normal of Q's tangent plane at the apex
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 4; ++j)
        n[i] += (*q)[i][j] * v[j];
    if (n[0].is_zero() && n[1].is_zero() && n[2].is_zero()) return std::nullopt;
    // adj(K3), K3 the quadratic part of k.
    M3 adj;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const size_t i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        adj[i][j] = k[i1][j1] * k[i2][j2] - k[i1][j2] * k[i2][j1];
      }
    auto form = [&adj](const V3& x) {
      Rational s;
      for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j)
          s += x[i] * adj[i][j] * x[j];
      return s;
    };
    if (form(n).sign() >= 0) return std::nullopt; // no crunode's two real branches here
    const std::optional<V3> m = positive_direction(adj);
    if (!m) return std::nullopt;
    int first = 0, second = 0;
    for (const Root& r : roots) {
      const int sn = form_sign_at(r, n), sm = form_sign_at(r, *m);
      if (sn == 0 || sm == 0) return std::nullopt;
      (sn * sm > 0 ? first : second) += 1;
    }
    return std::pair<int, int>{first, second};
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------
// The components of each morphology, for the enumeration of assignments.

enum class CKind { Circle, Line, Lobe };

struct Comp {
  CKind kind;
  int weight = 1;           // 2 for a double component
  std::vector<int> allowed; // allowed sums of local multiplicities
  int max_local = 4;
};

Comp even_oval() {
  return {CKind::Circle, 1, {0, 2, 4}, 4};
}
Comp odd_branch() {
  return {CKind::Circle, 1, {1, 3}, 3};
}
Comp conic(int w = 1) {
  return {CKind::Circle, w, {0, 2}, 2};
}
Comp line(int w = 1) {
  return {CKind::Line, w, {1}, 1};
}

// Real curve components by Tu case (isolated points excluded); nullopt for an unknown case.
std::optional<std::vector<Comp>> components_of(int c) {
  switch (c) {
  case 1:
    return std::vector<Comp>{even_oval(), even_oval()};
  case 3:
  case 6:
    return std::vector<Comp>{even_oval()};
  case 4:
    return std::vector<Comp>{odd_branch(), odd_branch()};
  case 5:
    return std::vector<Comp>{{CKind::Lobe, 1, {0, 2, 4}, 4}, {CKind::Lobe, 1, {0, 2, 4}, 4}};
  case 8:
    return std::vector<Comp>{{CKind::Lobe, 1, {1, 3}, 3}, {CKind::Lobe, 1, {1, 3}, 3}};
  case 9: // a cuspidal loop is a topological circle; the parity of a degree-4 curve is even
    return std::vector<Comp>{even_oval()};
  case 10:
  case 11:
  case 12:
    return std::vector<Comp>{odd_branch(), line()};
  case 13:
  case 14:
  case 18:
  case 19:
    return std::vector<Comp>{conic(), conic()};
  case 17:
  case 24:
  case 27:
    return std::vector<Comp>{conic()};
  case 21:
    return std::vector<Comp>{conic(2)};
  case 23:
  case 26:
    return std::vector<Comp>{conic(), line(), line()};
  case 28:
    return std::vector<Comp>{line(), line(), line(), line()};
  case 31:
    return std::vector<Comp>{line(), line()};
  case 32:
    return std::vector<Comp>{line(2), line(2)};
  case 34:
    return std::vector<Comp>{line(2)};
  case 35:
    return std::vector<Comp>{line(2), line(), line()};
  case 2:
  case 7:
  case 15:
  case 16:
  case 20:
  case 22:
  case 25:
  case 29:
  case 30:
  case 33:
    return std::vector<Comp>{};
  default:
    return std::nullopt;
  }
}

// Cases whose every component is real (a real point on an imaginary component would be a
// singular point of the curve lying on no real branch): at a special point at infinity only
// real components can meet.
bool all_components_real(int c) {
  switch (c) {
  case 5:
  case 8:
  case 9:
  case 10:
  case 11:
  case 12:
  case 13:
  case 14:
  case 18:
  case 19:
  case 21:
  case 23:
  case 26:
  case 28:
  case 32:
  case 35:
    return true;
  default:
    return false;
  }
}

struct CurveRoot {
  int mult;
  bool special;        // a (matched) singular point of the curve: may lie on several components
  bool on_two = false; // lies on at least two components
};

// Cases whose components are all real, smooth and simple (conics, lines, a twisted cubic): a
// singular point of the curve lies on at least two of them.
bool singular_means_crossing(int c) {
  switch (c) {
  case 10:
  case 11:
  case 12:
  case 13:
  case 14:
  case 18:
  case 19:
  case 23:
  case 26:
  case 28:
    return true;
  default:
    return false;
  }
}

// Every assignment of the curve roots to components (local multiplicities) allowed by the
// exact facts; the set of (loops, unbounded) it yields.
std::set<std::pair<int, int>> enumerate(const std::vector<Comp>& comps,
                                        const std::vector<CurveRoot>& roots) {
  std::set<std::pair<int, int>> results;
  const size_t nc = comps.size();
  std::vector<std::vector<int>> local(roots.size(), std::vector<int>(nc, 0));
  std::function<void(size_t)> rec = [&](size_t i) {
    if (i == roots.size()) {
      int loops = 0, unbounded = 0;
      std::vector<int> lobe_m;
      for (size_t c = 0; c < nc; ++c) {
        int sum = 0, m = 0;
        for (size_t r = 0; r < roots.size(); ++r) {
          sum += local[r][c];
          m += local[r][c] > 0 ? 1 : 0;
        }
        const auto& al = comps[c].allowed;
        if (std::find(al.begin(), al.end(), sum) == al.end()) return;
        if (comps[c].kind == CKind::Line) {
          if (m != 1) return;
          ++unbounded;
        } else if (comps[c].kind == CKind::Circle) {
          if (m == 0)
            ++loops;
          else
            unbounded += m;
        } else {
          lobe_m.push_back(m);
        }
      }
      if (!lobe_m.empty()) { // a figure eight with an affine node: one piece through it
        int any = 0, extra = 0;
        for (int m : lobe_m) {
          any += m;
          extra += std::max(m - 1, 0);
        }
        if (any == 0)
          ++loops;
        else
          unbounded += 1 + extra;
      }
      results.insert({loops, unbounded});
      return;
    }
    const CurveRoot& r = roots[i];
    // Local multiplicity vectors: one component (smooth point) or any nonempty set (special).
    std::function<void(size_t, int, int)> pick = [&](size_t c, int left, int used) {
      if (c == nc) {
        if (left == 0 && used > 0 && (r.special || used == 1) && (!r.on_two || used >= 2))
          rec(i + 1);
        return;
      }
      pick(c + 1, left, used);
      for (int l = 1; l <= comps[c].max_local && comps[c].weight * l <= left; ++l) {
        if (!r.special && used > 0) break;
        local[i][c] = l;
        pick(c + 1, left - comps[c].weight * l, used + 1);
        local[i][c] = 0;
      }
    };
    pick(0, r.mult, 0);
  };
  rec(0);
  return results;
}

bool isolated_kind(const std::string& k) {
  return k == "acnode" || k == "isolated_point";
}

std::string conic_text(const M3& m) {
  const char* v[3] = {"x", "y", "z"};
  std::string s;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = i; j < 3; ++j) {
      Rational c = i == j ? m[i][j] : Rational(2) * m[i][j];
      if (c.is_zero()) continue;
      s += (s.empty() ? "" : " + ") + c.to_string() + "*" + v[i] + "*" + v[j];
    }
  return (s.empty() ? "0" : s) + " = 0 (w = 0)";
}

// Real locus of the conic x^T m x = 0 in the plane at infinity (a quadric's asymptotic cone).
std::optional<ComponentAtInfinity> conic_at_infinity(const M3& m) {
  core::Mat4 m4;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      m4[i][j] = m[i][j];
  // Inertia of an integer multiple (the same): no gcd of the posed doubles' denominators.
  algebra::Inertia in = algebra::inertia_ldlt(core::integer_multiple(m4));
  ComponentAtInfinity c;
  c.equation = conic_text(m);
  if (in.rank() == 3) {
    if (in.semidefinite()) return std::nullopt;
    c.kind = "conic";
  } else if (in.rank() == 2) {
    if (in.semidefinite()) {
      // One real point: the kernel, the cross product of two independent rows.
      V3 k;
      for (size_t r1 = 0; r1 < 3; ++r1)
        for (size_t r2 = r1 + 1; r2 < 3; ++r2) {
          if (!(k[0].is_zero() && k[1].is_zero() && k[2].is_zero())) break; // found
          k = {m[r1][1] * m[r2][2] - m[r1][2] * m[r2][1], m[r1][2] * m[r2][0] - m[r1][0] * m[r2][2],
               m[r1][0] * m[r2][1] - m[r1][1] * m[r2][0]};
        }
      k = normalise(k);
      c.kind = "point";
      for (size_t i = 0; i < 3; ++i)
        c.direction[i] = k[i].to_string();
    } else {
      c.kind = "line_pair";
    }
  } else if (in.rank() == 1) {
    c.kind = "double_line";
  } else {
    return std::nullopt;
  }
  return c;
}

// ---------------------------------------------------------------------------------------
// Two cones with one affine apex p (both matrices vanish on (p, 1)): each quadric is
// (x - p)^T M (x - p) = 0 with M its quadratic part, so the curve is the union of the lines
// p + t d over the real common points d of the conics at infinity; p alone when there is none.

// The apex is read off whichever of the two has an invertible quadratic block (a cone; the
// other may be a plane pair or a cylinder through it, whose singular points form a line).
std::optional<V3> common_apex(const core::Mat4& a, const core::Mat4& b) {
  auto det3 = [](const M3& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const bool use_a = !det3(top_left(a)).is_zero();
  if (!use_a && det3(top_left(b)).is_zero()) return std::nullopt; // no single affine apex
  const core::Mat4& c = use_a ? a : b;
  const M3 mi = inverse(top_left(c));
  V3 p;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      p[i] -= mi[i][j] * c[j][3];
  for (const core::Mat4* q : {&a, &b})
    for (size_t i = 0; i < 4; ++i) {
      Rational s = (*q)[i][3];
      for (size_t j = 0; j < 3; ++j)
        s += (*q)[i][j] * p[j];
      if (!s.is_zero()) return std::nullopt;
    }
  return p;
}

// The one affine point where both quadrics are singular (the kernel of A^2 + B^2, which is
// ker A ∩ ker B for symmetric A, B), when there is exactly one: two plane pairs whose axes meet
// at P are cones with apex P too, every line through P in a direction common to their conics
// at infinity lying on both (common_apex reads the apex off a cone's invertible block only).
std::optional<V3> common_singular_point(const core::Mat4& a, const core::Mat4& b) {
  core::Mat4 s;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      for (size_t k = 0; k < 4; ++k)
        s[i][j] += a[i][k] * a[k][j] + b[i][k] * b[k][j];
  const auto ker = algebra::kernel_basis(s);
  if (ker.size() != 1 || ker[0][3].is_zero()) return std::nullopt;
  V3 p;
  for (size_t i = 0; i < 3; ++i)
    p[i] = ker[0][i] / ker[0][3];
  return p;
}

AffineTopology common_apex_route(const V3& apex, const Chart& ch) {
  AffineTopology out;
  out.route = "common_apex";
  out.apex = apex;
  out.computed = true;
  out.points_at_infinity_complete = true;
  for (const auto& r : roots_of(ch))
    out.points_at_infinity.push_back(r.p);
  const int n = static_cast<int>(out.points_at_infinity.size());
  out.lines = out.unbounded_branches = n;
  out.loops = out.conics = 0;
  out.isolated_points = n == 0 ? 1 : 0;
  return out;
}

// ---------------------------------------------------------------------------------------
// Two cylinders along one rational direction d (see affine.hpp): the lines b + t d over the
// real common points b of the sections by x_k = 0, read in that plane's coordinates
// (x_i, x_j, w) with the chart machinery of the points at infinity (the same problem: two
// conics of a projective plane).

std::optional<V3> common_ruling(const core::QuadricMatrix& a, const core::QuadricMatrix& b) {
  const auto ker = common_kernel(a, b, 3);
  if (ker.empty()) return std::nullopt;
  return V3{ker[0][0], ker[0][1], ker[0][2]};
}

// A member lambda A - B of two parallel cylinders' pencil that is a rational plane pair (the
// planes as quadrics) or a double plane (second nullopt), found among the rational roots of
// det(lambda FA - FB) (FA, FB: the cross-sections). When the sections touch at a rational point
// and meet at two conjugate ones, the double root of that cubic is rational and its member is
// the tangent line and the line through the conjugate points; when they touch at two conjugate
// points, the member is the double line through them.
std::optional<std::pair<core::Mat4, std::optional<core::Mat4>>>
ruling_member(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const M3& fa,
              const M3& fb) {
  std::array<std::array<UPolyQ, 3>, 3> m;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      m[i][j] = UPolyQ::linear(fa[i][j], -fb[i][j]);
  const UPolyQ det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (det.is_zero()) return std::nullopt;
  for (const Rational& l : algebra::rational_roots(det)) {
    const core::Mat4 e = core::scaled(a.matrix(), l) + core::scaled(b.matrix(), Rational(-1));
    if (const auto planes = rational_plane_pair(e))
      return std::make_pair(plane_as_quadric((*planes)[0]),
                            std::optional<core::Mat4>(plane_as_quadric((*planes)[1])));
    // A double plane: every 2x2 minor vanishes; its plane is the row of the largest diagonal.
    size_t k = 4;
    for (size_t i = 0; i < 4; ++i)
      if (!e[i][i].is_zero() && (k == 4 || core::abs(e[i][i]) > core::abs(e[k][k]))) k = i;
    if (k == 4) continue;
    bool rank1 = true;
    for (size_t i = 0; i < 4 && rank1; ++i)
      for (size_t j = 0; j < 4 && rank1; ++j)
        rank1 = (e[i][j] * e[k][k] - e[i][k] * e[k][j]).is_zero();
    if (rank1 && !(e[k][0].is_zero() && e[k][1].is_zero() && e[k][2].is_zero()))
      return std::make_pair(plane_as_quadric({e[k][0], e[k][1], e[k][2], e[k][3]}),
                            std::optional<core::Mat4>());
  }
  return std::nullopt;
}

AffineTopology parallel_cylinders_route(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                        const V3& d) {
  AffineTopology out;
  out.route = "parallel_cylinders";
  size_t k = 0;
  for (size_t i = 1; i < 3; ++i)
    if (core::abs(d[i]) > core::abs(d[k])) k = i;
  const std::array<size_t, 3> idx{(k + 1) % 3, (k + 2) % 3, 3};
  M3 fa, fb;
  for (size_t p = 0; p < 3; ++p)
    for (size_t q = 0; q < 3; ++q) {
      fa[p][q] = a.matrix()[idx[p]][idx[q]];
      fb[p][q] = b.matrix()[idx[p]][idx[q]];
    }
  Chart ch;
  const ChartOutcome co = find_chart(fa, fb, ch);
  if (co == ChartOutcome::SharedComponent) {
    out.reason = "the cylinders share a plane along their common ruling direction: part of the "
                 "intersection is a surface";
    return out;
  }
  if (co == ChartOutcome::Failed) {
    out.reason = "no chart of the section plane separated the lines of the parallel cylinders";
    return out;
  }
  // w of the chart point (u, v, 1), as a polynomial in u where the first subresultant gives v.
  const UPolyQ upoly = UPolyQ::linear(Rational(1), Rational(0));
  const UPolyQ wpoly = UPolyQ(ch.t[2][0]) * upoly * ch.s11 - UPolyQ(ch.t[2][1]) * ch.s10 +
                       UPolyQ(ch.t[2][2]) * ch.s11;
  auto point_of = [&](const Rational& u0) {
    const Rational v0 = ch.v_at(u0);
    V3 x;
    for (size_t r = 0; r < 3; ++r)
      x[r] = ch.t[r][0] * u0 + ch.t[r][1] * v0 + ch.t[r][2];
    return x;
  };
  auto as_q = [](const UPolyZ& g) {
    std::vector<Rational> c;
    for (long i = 0; i <= g.degree(); ++i)
      c.emplace_back(g.coeff(i));
    return UPolyQ::from_coeffs(c);
  };
  // The multiplicity of the common points at infinity of the two sections (over C): the
  // factors of R whose points have w = 0.
  int at_infinity = 0;
  for (const algebra::IrreducibleFactor& fac :
       algebra::irreducible_factors(ch.r.primitive_integer())) {
    const UPolyZ& g = fac.poly;
    bool on_w0 = false;
    if (g.degree() == 1) {
      on_w0 = point_of(-Rational(g.coeff(0)) / Rational(g.coeff(1)))[2].is_zero();
    } else {
      on_w0 = wpoly.rem(as_q(g)).is_zero();
    }
    if (on_w0) at_infinity += fac.exponent * static_cast<int>(g.degree());
  }
  auto to3 = [&](const Rational& xi, const Rational& xj) {
    V3 p;
    p[idx[0]] = xi;
    p[idx[1]] = xj;
    return p; // x_k = 0
  };
  const V3 dn = normalise(d);
  bool irrational = false, multiple = false; // an irrational line; a line of multiplicity > 1
  for (const Root& r : roots_of(ch)) {
    if (r.lo == r.hi) {
      const V3 x = point_of(r.lo);
      if (x[2].is_zero()) {
        // A line at infinity through d and (x_i, x_j): n . (x, y, z) = 0, n = d x e.
        const V3 e = to3(x[0], x[1]);
        out.at_infinity_only.push_back(line_at_infinity(
            {d[1] * e[2] - d[2] * e[1], d[2] * e[0] - d[0] * e[2], d[0] * e[1] - d[1] * e[0]}));
        continue;
      }
      multiple = multiple || r.p.multiplicity > 1;
      AffineTopology::RulingLine l;
      l.base = to3(x[0] / x[2], x[1] / x[2]);
      for (size_t c = 0; c < 3; ++c)
        l.approx[c] = (*l.base)[c].to_double_approx();
      out.ruling_lines.push_back(l);
      continue;
    }
    // An algebraic point: at infinity only when its factor divides w (then the two sections'
    // quadratic parts would share an irrational root pair, i.e. be proportional: a case
    // routed to "pencil_plane" before this one; not read here).
    if (wpoly.rem(as_q(r.factor)).is_zero()) {
      out.reason = "an irrational line at infinity of two parallel cylinders (not analysed)";
      out.at_infinity_only.clear();
      out.ruling_lines.clear();
      return out;
    }
    // The base point to double precision: from the root refined to 2^-120 of its size and the
    // point there computed exactly (the unit vector r.p.approx, evaluated in doubles, put a
    // line 10^6 out some hundred ulps off).
    Rational lo = r.lo, hi = r.hi;
    const Rational size = core::abs(lo) + core::abs(hi) + Rational(1);
    algebra::refine_root_newton(r.factor, lo, hi, size * core::pow2(-120));
    const V3 x = point_of((lo + hi) / Rational(2));
    AffineTopology::RulingLine l;
    const V3 base = to3(x[0] / x[2], x[1] / x[2]);
    for (size_t c = 0; c < 3; ++c)
      l.approx[c] = base[c].to_double_approx();
    out.ruling_lines.push_back(l);
    irrational = true;
    multiple = multiple || r.p.multiplicity > 1;
  }
  const int n = static_cast<int>(out.ruling_lines.size());
  const int through_d = 4 - at_infinity; // affine lines over C, with multiplicity
  std::array<double, 3> dap{};
  for (size_t c = 0; c < 3; ++c)
    dap[c] = dn[c].to_double_approx();
  if (n > 0) {
    PointAtInfinity p;
    p.multiplicity = through_d;
    p.rational = true;
    for (size_t c = 0; c < 3; ++c)
      p.direction[c] = dn[c].to_string();
    p.approx = unit_approx(dap);
    out.points_at_infinity.push_back(p);
  } else if (through_d > 0) {
    ComponentAtInfinity pt; // conjugate lines meeting at d only
    pt.kind = "point";
    for (size_t c = 0; c < 3; ++c)
      pt.direction[c] = dn[c].to_string();
    out.at_infinity_only.push_back(pt);
  }
  if (irrational && multiple) {
    // The crossings with a box then come from a rational member of the pencil that is a plane
    // pair or a double plane (see ruling_member) cut with A: the general reading of A and B
    // on a face sees the multiple line as a multiple crossing.
    if (const auto m = ruling_member(a, b, fa, fb)) {
      out.plane = m->first;
      out.plane2 = m->second;
      out.section_of = a.matrix();
    }
  }
  out.ruling = d;
  out.computed = true;
  out.points_at_infinity_complete = true;
  out.lines = out.unbounded_branches = n;
  out.loops = out.conics = out.isolated_points = 0;
  return out;
}

// ---------------------------------------------------------------------------------------
// Two planes: one line (direction n_a x n_b), none (parallel) or a surface (the same plane).
// Written as quadrics both contain the plane at infinity too; that common part is not listed.

AffineTopology plane_plane_route(const core::QuadricMatrix& a, const core::QuadricMatrix& b) {
  AffineTopology out;
  out.route = "plane_plane";
  const core::Mat4 &pa = a.matrix(), &pb = b.matrix();
  out.plane = pa;
  out.section_of = pb;
  const V3 na{pa[0][3], pa[1][3], pa[2][3]}, nb{pb[0][3], pb[1][3], pb[2][3]};
  auto zero = [](const V3& v) { return v[0].is_zero() && v[1].is_zero() && v[2].is_zero(); };
  if (zero(na) || zero(nb)) {
    // One of them c w^2 with c != 0 (no linear part): no affine point at all (see plane_route);
    // the common part at infinity is not listed, as for two planes.
    if ((zero(na) && !pa[3][3].is_zero()) || (zero(nb) && !pb[3][3].is_zero())) {
      out.computed = true;
      out.points_at_infinity_complete = true;
      out.loops = out.unbounded_branches = out.isolated_points = out.lines = out.conics = 0;
      return out;
    }
    out.reason = "a plane quadric has no affine plane";
    return out;
  }
  const V3 d{na[1] * nb[2] - na[2] * nb[1], na[2] * nb[0] - na[0] * nb[2],
             na[0] * nb[1] - na[1] * nb[0]};
  if (zero(d)) {
    // Parallel normals: the same plane when (n_b, c_b) is a multiple of (n_a, c_a).
    size_t k = 0;
    while (na[k].is_zero())
      ++k;
    const Rational r = nb[k] / na[k];
    if (pb[3][3] == r * pa[3][3]) {
      out.reason = "the planes coincide: the intersection is a plane, not a curve";
      return out;
    }
    out.computed = true;
    out.points_at_infinity_complete = true;
    out.loops = out.unbounded_branches = out.isolated_points = out.lines = out.conics = 0;
    return out;
  }
  out.computed = true;
  out.points_at_infinity_complete = true;
  out.loops = out.isolated_points = out.conics = 0;
  out.unbounded_branches = out.lines = 1;
  PointAtInfinity p;
  p.rational = true;
  const V3 dn = normalise(d);
  std::array<double, 3> ap{};
  for (size_t k = 0; k < 3; ++k) {
    p.direction[k] = dn[k].to_string();
    ap[k] = dn[k].to_double_approx();
  }
  p.approx = unit_approx(ap);
  out.points_at_infinity.push_back(p);
  return out;
}

// The real points at infinity of a twisted cubic X(s, t) (certify/cubic_line.hpp): the roots
// (s : t) of X_3, directions (X_0 : X_1 : X_2) there (never all zero: X is a point of P^3);
// multiplicity: the root's multiplicity in X_3. In the chart t = 1, plus (1 : 0) when
// X_3's s^3 coefficient vanishes.
std::vector<PointAtInfinity> cubic_points_at_infinity(const CubicAndLine& cl) {
  std::vector<PointAtInfinity> out;
  auto rational_point = [&](const V3& d0, int mult) {
    const V3 d = normalise(d0);
    PointAtInfinity p;
    p.multiplicity = mult;
    p.rational = true;
    std::array<double, 3> ap{};
    for (size_t k = 0; k < 3; ++k) {
      p.direction[k] = d[k].to_string();
      ap[k] = d[k].to_double_approx();
    }
    p.approx = unit_approx(ap);
    out.push_back(std::move(p));
  };
  // X_i(s, 1) = sum_k cubic[i][k] s^(3 - k).
  std::array<UPolyQ, 4> x;
  for (size_t i = 0; i < 4; ++i)
    x[i] = UPolyQ::from_coeffs({cl.cubic[i][3], cl.cubic[i][2], cl.cubic[i][1], cl.cubic[i][0]});
  if (x[3].is_zero()) return {}; // the cubic in the plane at infinity: not a twisted cubic
  if (x[3].degree() < 3)
    rational_point({cl.cubic[0][0], cl.cubic[1][0], cl.cubic[2][0]},
                   3 - static_cast<int>(x[3].degree()));
  if (x[3].degree() < 1) return out;
  for (const algebra::IrreducibleFactor& fac :
       algebra::irreducible_factors(x[3].primitive_integer())) {
    const UPolyZ g = fac.poly.primitive_part();
    const int e = fac.exponent;
    if (g.degree() == 1) {
      const Rational s0 = -Rational(g.coeff(0)) / Rational(g.coeff(1));
      rational_point({x[0].evaluate(s0), x[1].evaluate(s0), x[2].evaluate(s0)}, e);
      continue;
    }
    const algebra::RootSeparation sep = algebra::isolate_real_roots(g);
    for (size_t j = 0; j + 1 < sep.separators.size(); ++j) {
      PointAtInfinity p;
      p.multiplicity = e;
      p.rational = false;
      p.lo = sep.separators[j];
      p.hi = sep.separators[j + 1];
      Rational lo = p.lo, hi = p.hi;
      algebra::refine_root_newton(g, lo, hi, Rational(1, 1UL << 60)); // an estimate: any bracket
      const double t0 = ((lo + hi) * Rational(1, 2)).to_double_approx();
      std::array<double, 3> ap{};
      for (size_t k = 0; k < 3; ++k)
        ap[k] = eval_double(x[k], t0);
      p.approx = unit_approx(ap);
      p.polynomial = g;
      p.dir_in_t = {x[0], x[1], x[2]};
      out.push_back(std::move(p));
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Plane route: one quadric is a plane (its matrix has a zero quadratic block).

// The real directions at infinity of the plane section with form cm in the chart X = col[0]
// s + col[1] t + col[2] (plane_chart): the real roots of its quadratic part a s^2 + 2 b s t +
// d t^2, as 3D vectors, each with the intersection multiplicity of the section's conic with
// the line at infinity of its plane (1 for two distinct directions, 2 for a double one). They
// are real points at infinity of the curve whether or not the affine section is real (x = 2
// against x^2 + y^2 = 1: two conjugate lines meeting at (0 : 0 : 1)). None when the quadratic
// part is definite; the direction of the line when the quadratic part is zero.
std::vector<PointAtInfinity> section_directions(const M3& cm,
                                                const std::array<std::array<Rational, 4>, 3>& col) {
  std::vector<PointAtInfinity> pts;
  const Rational &a = cm[0][0], &b = cm[0][1], &d = cm[1][1];
  auto add_direction = [&](const QuadraticNumber& s, const QuadraticNumber& t, int mult) {
    PointAtInfinity pt;
    pt.multiplicity = mult;
    pt.rational = s.b.is_zero() && t.b.is_zero();
    std::array<QuadraticNumber, 3> dir;
    for (size_t i = 0; i < 3; ++i) {
      dir[i] = {s.a * col[0][i] + t.a * col[1][i], s.b * col[0][i] + t.b * col[1][i], s.d};
      if (dir[i].b.is_zero()) dir[i].d = Integer(1);
    }
    // Normalise: divide by the first nonzero coordinate's rational part when rational.
    std::array<double, 3> ap{};
    if (pt.rational) {
      V3 r{dir[0].a, dir[1].a, dir[2].a};
      r = normalise(r);
      for (size_t i = 0; i < 3; ++i) {
        pt.direction[i] = r[i].to_string();
        ap[i] = r[i].to_double_approx();
      }
    } else {
      // One field for the three coordinates: d's square factors found once.
      const auto split = s.d.sign() > 0 ? std::optional(algebra::square_split(s.d)) : std::nullopt;
      for (size_t i = 0; i < 3; ++i) {
        pt.direction[i] =
            (split && !dir[i].b.is_zero() && dir[i].d == s.d ? dir[i].normalized(*split)
                                                             : dir[i].normalized())
                .to_string();
        ap[i] = dir[i].to_double_approx();
      }
    }
    pt.approx = unit_approx(ap);
    pts.push_back(pt);
  };
  const Integer one(1);
  if (a.is_zero() && b.is_zero() && d.is_zero()) {
    // A line 2 e s + 2 f t + g = 0 (or nothing): its direction (-f, e).
    const Rational &e = cm[0][2], &f = cm[1][2];
    if (!(e.is_zero() && f.is_zero()))
      add_direction({-f, Rational(0), one}, {e, Rational(0), one}, 1);
    return pts;
  }
  if (a.is_zero()) {
    // t (2 b s + d t) = 0: t = 0 (s = 1) and, if b != 0, (s, t) = (-d, 2 b).
    if (b.is_zero()) { // d t^2 = 0: the double direction t = 0
      add_direction({Rational(1), Rational(0), one}, {Rational(0), Rational(0), one}, 2);
      return pts;
    }
    add_direction({Rational(1), Rational(0), one}, {Rational(0), Rational(0), one}, 1);
    add_direction({-d, Rational(0), one}, {Rational(2) * b, Rational(0), one}, 1);
    return pts;
  }
  const Rational disc = b * b - a * d;
  if (disc.sign() < 0) return pts;
  if (disc.is_zero()) {
    add_direction({-b, Rational(0), one}, {a, Rational(0), one}, 2);
    return pts;
  }
  Integer dn = disc.num() * disc.den();
  Integer root;
  fmpz_sqrt(root.raw_mut(), dn.raw());
  for (int sg : {1, -1}) {
    QuadraticNumber s;
    if (root * root == dn)
      s = {-b + Rational(sg) * Rational(root, disc.den()), Rational(0), one};
    else
      s = {-b, Rational(sg) / Rational(disc.den()), dn};
    add_direction(s, {a, Rational(0), one}, 1);
  }
  return pts;
}

AffineTopology plane_route(const core::QuadricMatrix& plane, const core::QuadricMatrix& quad) {
  AffineTopology out;
  out.route = "plane_section";
  out.plane = plane.matrix();
  out.section_of = quad.matrix();
  const core::Mat4& p = plane.matrix();
  const core::Mat4& q = quad.matrix();
  // Columns of M (4x3): X = M (s, t, 1).
  const auto chart = algebra::plane_chart(p);
  if (!chart) {
    // No linear part: the "plane" is c w^2 = 0 (c = p_33), the plane at infinity counted
    // twice. Its affine equation c = 0 has no solution when c != 0, so the affine curve is
    // empty and the whole curve lies at infinity (w = 0 on the other quadric: its conic at
    // infinity, listed apart). Generated pencils of Tu 33 (a point and two imaginary double
    // lines) pose exactly this (generate --case 33 --seed 35, pair 18: undecided before).
    if (!p[3][3].is_zero()) {
      out.computed = true;
      out.points_at_infinity_complete = true;
      out.loops = out.unbounded_branches = out.isolated_points = out.lines = out.conics = 0;
      if (auto inf = conic_at_infinity(top_left(q))) out.at_infinity_only.push_back(*inf);
      return out;
    }
    out.reason = "the plane quadric has no affine plane";
    return out;
  }
  const std::array<std::array<Rational, 4>, 3>& col = *chart;
  // The section's conic, and an integer multiple of it for the decisions below (signs of its
  // determinants: no gcd of the posed doubles' denominators in their products). The
  // directions at infinity are written from the conic itself (their text is the answer's).
  const M3 cm_exact = algebra::restrict_form(q, col);
  const M3 cm = core::integer_multiple(cm_exact);
  out.computed = true;
  out.points_at_infinity_complete = true;
  if (auto inf = conic_at_infinity(top_left(q))) out.at_infinity_only.push_back(*inf);
  if (is_zero3(cm)) {
    out.computed = false;
    out.reason = "the plane lies on the other quadric: the intersection is a surface";
    return out;
  }
  const Rational &a = cm[0][0], &b = cm[0][1], &d = cm[1][1], &e = cm[0][2], &f = cm[1][2],
                 &g = cm[2][2];
  const Rational delta = a * d - b * b;
  const Rational big = a * (d * g - f * f) - b * (b * g - f * e) + e * (b * f - d * e);
  // Directions at infinity of the section (section_directions): listed where the section
  // has real affine points running to them.
  auto directions = [&] { out.points_at_infinity = section_directions(cm_exact, col); };
  int loops = 0, unbounded = 0, isolated = 0, lines = 0, conics = 0;
  const bool quad_zero = a.is_zero() && b.is_zero() && d.is_zero();
  if (quad_zero) {
    // 2 e s + 2 f t + g = 0: a line (or nothing) in the plane.
    if (!(e.is_zero() && f.is_zero())) {
      lines = 1;
      unbounded = 1;
      directions();
    }
  } else if (!big.is_zero()) {
    if (delta.sign() > 0) {
      // Ellipse: real iff (a + d) and det have opposite signs.
      if ((a + d).sign() * big.sign() < 0) {
        loops = 1;
        conics = 1;
      }
    } else if (delta.sign() < 0) {
      conics = 1;
      unbounded = 2;
      directions();
    } else {
      conics = 1;
      unbounded = 1;
      directions();
    }
  } else {
    if (delta.sign() < 0) {
      lines = 2;
      unbounded = 2;
      directions();
    } else if (delta.sign() > 0) {
      isolated = 1;
    } else {
      const Rational kk = (a * g - e * e) + (d * g - f * f);
      if (kk.sign() < 0) {
        lines = 2;
        unbounded = 2;
        directions(); // two parallel lines: one double direction, each line through it
      } else if (kk.is_zero()) {
        lines = 1; // a double line
        unbounded = 1;
        directions();
      }
    }
  }
  out.loops = loops;
  out.unbounded_branches = unbounded;
  out.isolated_points = isolated;
  out.lines = lines;
  out.conics = conics;
  return out;
}

// ---------------------------------------------------------------------------------------
// Plane pair route: one quadric is two distinct real planes with rational equations (x y = 0,
// x^2 = 1/4, ...), the other one not a plane. The curve is the union of the two plane sections
// (plane_route on each), when that union is read off them exactly: both sections certified,
// neither plane's line at infinity on the other quadric (a component at infinity), and, when
// the planes meet along a line L, L not on the other quadric (a line counted twice) and no
// isolated point (it may lie on the other section). Crossing components count separately, as
// everywhere; the points at infinity of the two sections are merged (multiplicities add).

std::optional<AffineTopology> plane_pair_route(const core::QuadricMatrix& pair,
                                               const core::QuadricMatrix& quad) {
  const auto planes = rational_plane_pair(pair.matrix());
  if (!planes) return std::nullopt;
  AffineTopology out;
  out.route = "plane_pair";
  const auto& n1 = (*planes)[0];
  const auto& n2 = (*planes)[1];
  AffineTopology sec[2];
  std::vector<PointAtInfinity> dirs[2]; // every real point at infinity of each section
  std::vector<ComponentAtInfinity> at_infinity_lines;
  for (size_t k = 0; k < 2; ++k) {
    const core::Mat4 pm = plane_as_quadric((*planes)[k]);
    const auto chart = algebra::plane_chart(pm);
    if (!chart) return std::nullopt; // the plane at infinity: not a pair of affine planes
    const M3 cm = algebra::restrict_form(quad.matrix(), *chart);
    if (cm[0][0].is_zero() && cm[0][1].is_zero() && cm[1][1].is_zero()) {
      // The plane's line at infinity lies on the other quadric: a component of the curve at
      // infinity (listed apart); the plane's affine section is a line or nothing.
      const ComponentAtInfinity li =
          line_at_infinity({(*planes)[k][0], (*planes)[k][1], (*planes)[k][2]});
      // (Parallel planes share their line at infinity: listed once.)
      if (at_infinity_lines.empty() || at_infinity_lines[0].equation != li.equation)
        at_infinity_lines.push_back(li);
    }
    dirs[k] = section_directions(cm, *chart);
    sec[k] = plane_route(core::QuadricMatrix(pm), quad);
    if (!sec[k].certified()) {
      out.reason = "a plane section of the pair was not read exactly: " + sec[k].reason;
      return out;
    }
  }
  const V3 cr{n1[1] * n2[2] - n1[2] * n2[1], n1[2] * n2[0] - n1[0] * n2[2],
              n1[0] * n2[1] - n1[1] * n2[0]};
  const bool parallel = cr[0].is_zero() && cr[1].is_zero() && cr[2].is_zero();
  if (!parallel) {
    if (*sec[0].isolated_points + *sec[1].isolated_points > 0) {
      out.reason = "a plane of the pair touches the other quadric at a point, which may lie on "
                   "the other plane's section (not analysed)";
      return out;
    }
    // L = n1 ∩ n2 spanned by two null vectors of the 2x4 matrix [n1; n2] (a nonzero 2x2 minor
    // in columns (i, j); the free columns k, l set to (1, 0) and (0, 1)).
    bool found = false;
    for (size_t i = 0; i < 4 && !found; ++i)
      for (size_t j = i + 1; j < 4 && !found; ++j) {
        const Rational det = n1[i] * n2[j] - n1[j] * n2[i];
        if (det.is_zero()) continue;
        found = true;
        std::array<std::array<Rational, 4>, 2> null{};
        size_t f = 0;
        for (size_t k = 0; k < 4; ++k) {
          if (k == i || k == j) continue;
          auto& x = null[f++];
          x[k] = Rational(1);
          // n1[i] x_i + n1[j] x_j = -n1[k], n2[i] x_i + n2[j] x_j = -n2[k] (Cramer)
          x[i] = (-n1[k] * n2[j] + n2[k] * n1[j]) / det;
          x[j] = (-n2[k] * n1[i] + n1[k] * n2[i]) / det;
        }
        const auto lq = algebra::restrict_form(quad.matrix(), null);
        if (lq[0][0].is_zero() && lq[0][1].is_zero() && lq[1][1].is_zero()) {
          out.reason = "the common line of the two planes lies on the other quadric (a line of "
                       "both sections; not analysed)";
          return out;
        }
      }
  }
  out.computed = true;
  out.points_at_infinity_complete = true;
  out.loops = *sec[0].loops + *sec[1].loops;
  out.unbounded_branches = *sec[0].unbounded_branches + *sec[1].unbounded_branches;
  out.isolated_points = *sec[0].isolated_points + *sec[1].isolated_points;
  out.lines = *sec[0].lines + *sec[1].lines;
  out.conics = *sec[0].conics + *sec[1].conics;
  // The curve's real points at infinity: those of both sections, merged (multiplicities
  // add), each real point of a section's quadratic part whether or not the section is real
  // there (x^2 = 4 against x^2 + y^2 = 1: conjugate lines meeting at (0 : 0 : 1)). A point
  // that no real affine branch of either section reaches lies at infinity only.
  bool open = false;
  auto same = [&open](const PointAtInfinity& u, const PointAtInfinity& v) {
    if (u.rational && v.rational) return u.direction == v.direction; // normalised texts
    const auto &x = u.approx, &y = v.approx;
    // Nearly one direction, not proven one (an irrational direction): left open.
    open = open || std::fabs(x[0] * y[0] + x[1] * y[1] + x[2] * y[2]) > 1 - 1e-12;
    return false;
  };
  for (const auto& d : dirs)
    for (const PointAtInfinity& pt : d) {
      auto it = std::find_if(out.points_at_infinity.begin(), out.points_at_infinity.end(),
                             [&](const PointAtInfinity& q2) { return same(pt, q2); });
      if (it != out.points_at_infinity.end())
        it->multiplicity += pt.multiplicity;
      else
        out.points_at_infinity.push_back(pt);
    }
  for (const PointAtInfinity& pt : out.points_at_infinity) {
    bool on_branch = false;
    for (const auto& s2 : sec)
      for (const PointAtInfinity& q2 : s2.points_at_infinity)
        on_branch = on_branch || same(pt, q2);
    if (on_branch) continue;
    ComponentAtInfinity c;
    c.kind = "point";
    c.direction = pt.direction;
    out.at_infinity_only.push_back(c);
  }
  out.at_infinity_only.insert(out.at_infinity_only.end(), at_infinity_lines.begin(),
                              at_infinity_lines.end());
  if (open) {
    AffineTopology undecided;
    undecided.route = "plane_pair";
    undecided.reason = "two sections have points at infinity that are close but not proven "
                       "equal or distinct";
    return undecided;
  }
  out.plane = plane_as_quadric(n1);
  out.plane2 = plane_as_quadric(n2);
  out.section_of = quad.matrix();
  return out;
}

} // namespace

// See affine.hpp.
std::vector<std::array<Rational, 4>> rational_member_planes(const core::Mat4& e, int rank) {
  if (rank == 1) {
    for (size_t i = 0; i < 4; ++i)
      if (!e[i][i].is_zero()) return {{e[i][0], e[i][1], e[i][2], e[i][3]}};
    return {};
  }
  if (rank == 2)
    if (const auto pp = rational_plane_pair(e)) return {(*pp)[0], (*pp)[1]};
  return {};
}

// The two planes of a rational plane pair, as 4-vectors n (n . (x, y, z, 1) = 0), or nullopt.
// x^T M x = (C^T x)^T S^-1 (C^T x) for a rank-2 M, S a nonzero principal 2x2 minor and C its
// two columns (checked exactly, which also proves rank 2); the binary form splits over Q when
// its discriminant is a positive rational square.
std::optional<std::array<std::array<Rational, 4>, 2>> rational_plane_pair(const core::Mat4& m) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i + 1; j < 4; ++j) {
      const Rational det = m[i][i] * m[j][j] - m[i][j] * m[i][j];
      if (det.is_zero()) continue;
      const Rational p = m[j][j] / det, q = -m[i][j] / det, r = m[i][i] / det; // S^-1
      for (size_t a = 0; a < 4; ++a)
        for (size_t b = 0; b < 4; ++b) {
          const Rational v =
              m[a][i] * (p * m[b][i] + q * m[b][j]) + m[a][j] * (q * m[b][i] + r * m[b][j]);
          if (v != m[a][b]) return std::nullopt; // rank > 2
        }
      const Rational disc = q * q - p * r;
      if (disc.sign() <= 0) return std::nullopt; // complex planes (a real line) or a double plane
      const Integer dn = disc.num() * disc.den();
      Integer root;
      fmpz_sqrt(root.raw_mut(), dn.raw());
      if (!(root * root == dn)) return std::nullopt; // planes over Q(sqrt d): not handled
      const Rational sq = Rational(root) / Rational(disc.den());
      std::array<std::array<Rational, 4>, 2> n;
      for (size_t k = 0; k < 4; ++k) {
        const Rational &al = m[k][i], &be = m[k][j]; // alpha = C_i . x, beta = C_j . x
        if (!p.is_zero()) {
          // p (alpha - r1 beta)(alpha - r2 beta), r = (-q +- sq) / p
          n[0][k] = al - ((-q + sq) / p) * be;
          n[1][k] = al - ((-q - sq) / p) * be;
        } else {
          // beta (2 q alpha + r beta)
          n[0][k] = be;
          n[1][k] = Rational(2) * q * al + r * be;
        }
      }
      return n;
    }
  return std::nullopt;
}

core::Mat4 plane_as_quadric(const std::array<Rational, 4>& n) {
  core::Mat4 pm;
  for (size_t k = 0; k < 3; ++k)
    pm[k][3] = pm[3][k] = n[k] / Rational(2);
  pm[3][3] = n[3];
  return pm;
}

// The conic at infinity has no real point: an ellipsoid's quadratic part is definite. Read
// from the shape when there is one (no exact matrix is formed for shapes posed in doubles).
bool definite_at_infinity(const core::QuadricMatrix& q) {
  const core::QuadricKind k = q.kind();
  return k == core::QuadricKind::Ellipsoid || k == core::QuadricKind::ImaginaryEllipsoid;
}

// The member theta A' - B' of the pencil at a root theta of the facts' characteristic polynomial,
// in the facts' basis (A' = t A - B, B' = -A when re-based: the roots are that pencil's);
// nullopt when that basis is not at hand.
std::optional<core::Mat4> member_at_root(const QsicResult& t, const core::QuadricMatrix& a,
                                         const core::QuadricMatrix& b, const Rational& theta) {
  const core::Mat4& fa = t.facts.a;
  if (!(fa == core::Mat4{})) return core::scaled(fa, theta) + core::scaled(t.facts.b, Rational(-1));
  if (t.facts.rebased) return std::nullopt;
  return core::scaled(a.matrix(), theta) + core::scaled(b.matrix(), Rational(-1));
}

// The rational plane pairs among A, B and the pencil's members at rational roots of rank 2,
// each with the quadric (not a plane) whose sections by its planes are the curve.
std::vector<std::pair<core::Mat4, const core::QuadricMatrix*>>
plane_pair_candidates(const QsicResult& t, const core::QuadricMatrix& a,
                      const core::QuadricMatrix& b) {
  std::vector<std::pair<core::Mat4, const core::QuadricMatrix*>> pairs{{a.matrix(), &b},
                                                                       {b.matrix(), &a}};
  for (const auto& r : t.facts.real_roots)
    if (r.rank == 2 && r.rational_value)
      if (auto m = member_at_root(t, a, b, *r.rational_value)) pairs.emplace_back(*m, &a);
  return pairs;
}

// Lines only, one of them at infinity (Tu 31, 32, 34, 35 posed with a real line in the plane at
// infinity: the conics at infinity share that line and are not proportional). A_inf = l mA and
// B_inf = l mB with l their gcd, a rational line, the only common component: l is a line of the
// curve, and the other real lines are affine, the morphology's real lines less one. A_inf and
// B_inf meet in l and P = mA x mB, so every point at infinity of the curve lies on l or at P: an
// affine line skew to l runs to P, one meeting l lies in a plane through l (a singular member's).
// exact_curve_lines looks for them there (kernel lines, the line through P, the planes'
// sections), each checked on both quadrics exactly; the reading needs every one of them.
// nullopt when this is not such a curve or a line is not found.
std::optional<AffineTopology> line_at_infinity_route(const QsicResult& t, const M3& ai,
                                                     const M3& bi) {
  if (t.status != Status::Certified || !t.morphology) return std::nullopt;
  const Morphology& m = *t.morphology;
  if (m.lines <= 0 || m.loops || m.conics || m.cubics || m.isolated_points) return std::nullopt;
  auto form = [](const M3& q) {
    core::Poly3::Terms terms;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        core::Poly3::Exponent e{0, 0, 0};
        ++e[i];
        ++e[j];
        terms[e] += q[i][j];
      }
    return core::Poly3(terms);
  };
  const core::Poly3 fa = form(ai), fb = form(bi);
  const core::Poly3 g = algebra::gcd(fa, fb);
  if (g.total_degree() != 1) return std::nullopt;
  core::Poly3 ma, mb;
  if (!fmpq_mpoly_divides(ma.raw_mut(), fa.raw(), g.raw(), core::Poly3::ctx()) ||
      !fmpq_mpoly_divides(mb.raw_mut(), fb.raw(), g.raw(), core::Poly3::ctx()))
    return std::nullopt;
  auto linear = [](const core::Poly3& f) {
    return V3{f.coeff(1, 0, 0), f.coeff(0, 1, 0), f.coeff(0, 0, 1)};
  };
  const V3 l = linear(g), la = linear(ma), lb = linear(mb);
  V3 p{la[1] * lb[2] - la[2] * lb[1], la[2] * lb[0] - la[0] * lb[2], la[0] * lb[1] - la[1] * lb[0]};
  if (p[0].is_zero() && p[1].is_zero() && p[2].is_zero()) return std::nullopt; // proportional
  p = normalise(p);
  const auto lines = exact_curve_lines(t.facts, m.lines, {p}, 1);
  if (!lines) return std::nullopt;
  AffineTopology out;
  out.route = "exact_lines";
  out.computed = true;
  out.points_at_infinity_complete = true;
  out.loops = out.conics = out.isolated_points = 0;
  out.lines = out.unbounded_branches = static_cast<int>(lines->size());
  std::vector<V3> seen;
  for (const ExactLine& ln : *lines) {
    const V3 d = normalise(ln.direction);
    const auto it = std::find(seen.begin(), seen.end(), d);
    if (it != seen.end()) {
      ++out.points_at_infinity[static_cast<size_t>(it - seen.begin())].multiplicity;
      continue;
    }
    seen.push_back(d);
    PointAtInfinity pt;
    pt.rational = true;
    std::array<double, 3> ap{};
    for (size_t k = 0; k < 3; ++k) {
      pt.direction[k] = d[k].to_string();
      ap[k] = d[k].to_double_approx();
    }
    pt.approx = unit_approx(ap);
    out.points_at_infinity.push_back(std::move(pt));
  }
  // P off l and on no real line: a real point of imaginary components only (not met in the
  // lines-only cases; refused rather than left out).
  if (!(l[0] * p[0] + l[1] * p[1] + l[2] * p[2]).is_zero() &&
      std::find(seen.begin(), seen.end(), p) == seen.end())
    return std::nullopt;
  out.at_infinity_only.push_back(line_at_infinity(l));
  out.exact_lines = *lines;
  return out;
}

AffineTopology affine_topology(QsicResult& t, const core::QuadricMatrix& a,
                               const core::QuadricMatrix& b) {
  if ((definite_at_infinity(a) || definite_at_infinity(b)) && t.status == Status::Certified &&
      t.morphology) {
    // No real point at infinity: the affine topology is the projective one.
    const Morphology& m = *t.morphology;
    AffineTopology out;
    out.route = "pencil";
    out.computed = true;
    out.points_at_infinity_complete = true;
    out.loops = m.loops + m.conics + m.cubics;
    out.unbounded_branches = 0;
    out.isolated_points = m.isolated_points;
    out.lines = m.lines;
    out.conics = m.conics;
    return out;
  }
  const bool pa = a.is_plane(), pb = b.is_plane();
  if (pa != pb) return pa ? plane_route(a, b) : plane_route(b, a);
  AffineTopology out;
  out.route = "pencil";
  if (pa && pb) return plane_plane_route(a, b);
  Chart ch;
  const ChartOutcome co = find_chart(top_left(a.matrix()), top_left(b.matrix()), ch);
  if (co == ChartOutcome::SharedComponent) {
    // Proportional quadratic parts (B_inf = c A_inf): B - c A is a plane written as a quadric
    // (the plane and the plane at infinity), so the affine curve is Q_A cut by that plane.
    const M3 ai = top_left(a.matrix()), bi = top_left(b.matrix());
    std::optional<Rational> c;
    bool prop = true;
    for (size_t i = 0; i < 3 && prop; ++i)
      for (size_t j = 0; j < 3 && prop; ++j) {
        if (ai[i][j].is_zero()) {
          prop = bi[i][j].is_zero();
        } else {
          const Rational r = bi[i][j] / ai[i][j];
          if (c && *c != r) prop = false;
          c = r;
        }
      }
    if (prop && c) {
      core::Mat4 p = b.matrix() + core::scaled(a.matrix(), -*c);
      if (!(p[0][3].is_zero() && p[1][3].is_zero() && p[2][3].is_zero())) {
        AffineTopology pr = plane_route(core::QuadricMatrix(p), a);
        pr.route = "pencil_plane";
        return pr;
      }
      if (!p[3][3].is_zero()) {
        // B - c A = const w^2: no affine point at all; the common conic at infinity remains.
        out.computed = true;
        out.points_at_infinity_complete = true;
        out.loops = out.unbounded_branches = out.isolated_points = out.lines = out.conics = 0;
        if (auto inf = conic_at_infinity(ai)) out.at_infinity_only.push_back(*inf);
        return out;
      }
    }
    if (t.status == Status::Certified && t.morphology &&
        (t.tu_case == 10 || t.tu_case == 11 || t.tu_case == 12)) {
      // A twisted cubic and a line lying at infinity (the shared component of the conics at
      // infinity): the affine curve is the cubic alone, one unbounded branch per distinct real
      // point at infinity, read from its exact parametrisation; the line is listed apart.
      CubicAndLine cl = cubic_and_line(a.matrix(), b.matrix());
      if (!t.special_points_done) complete_special_points(t, a, b);
      if (cl.found && cl.line_at_infinity && t.special_points_complete) {
        std::vector<PointAtInfinity> pts = cubic_points_at_infinity(cl);
        if (static_cast<int>(pts.size()) == cl.cubic_points_at_infinity) {
          out.route = "cubic_line";
          out.computed = true;
          out.points_at_infinity = std::move(pts);
          out.points_at_infinity_complete = true;
          out.loops = out.lines = out.conics = 0;
          out.isolated_points = t.morphology->isolated_points;
          out.unbounded_branches = cl.cubic_points_at_infinity;
          // The line at infinity: n . (x, y, z) = 0 (w = 0), n the cross product of its two
          // spanning points (both with w = 0).
          const auto& p = cl.line[0];
          const auto& q2 = cl.line[1];
          out.at_infinity_only.push_back(
              line_at_infinity({p[1] * q2[2] - p[2] * q2[1], p[2] * q2[0] - p[0] * q2[2],
                                p[0] * q2[1] - p[1] * q2[0]}));
          out.cubic_line = std::move(cl);
          return out;
        }
      }
    }
    if (t.pencil == algebra::PencilKind::Degenerate)
      if (auto d = common_ruling(a, b)) return parallel_cylinders_route(a, b, *d);
    if (t.status == Status::Certified && t.pencil == algebra::PencilKind::Regular) {
      // A rational plane pair in the pencil (z = xy against z = xy + (x - 1)(y + z - 2), whose
      // member A - B is one; x^2 = 1/4 against z = xy): the curve is the other quadric cut by
      // its two planes, read as the plane-pair route reads it.
      for (const auto& [pm, quad] : plane_pair_candidates(t, a, b)) {
        if (quad->is_plane()) continue;
        if (auto pp = plane_pair_route(core::QuadricMatrix(pm), *quad); pp && pp->certified())
          return *pp;
      }
    }
    if (auto lr = line_at_infinity_route(t, ai, bi)) return std::move(*lr);
    out.reason = "the conics at infinity share a component: part of the curve lies at infinity "
                 "(not analysed)";
    return out;
  }
  if (t.pencil == algebra::PencilKind::Degenerate && co == ChartOutcome::Ok)
    if (auto apex = common_apex(a.matrix(), b.matrix())) return common_apex_route(*apex, ch);
  if (t.status != Status::Certified || !t.morphology) {
    // A degenerate pencil with a pair of rational planes: the union of two plane sections;
    // else (or when those are not read exactly) two cylinders along one direction.
    std::optional<AffineTopology> pp = plane_pair_route(a, b);
    if (!pp) pp = plane_pair_route(b, a);
    if (pp && pp->certified()) return *pp;
    if (t.pencil == algebra::PencilKind::Degenerate)
      if (auto d = common_ruling(a, b)) {
        AffineTopology pc = parallel_cylinders_route(a, b, *d);
        if (pc.certified() || !pp) return pc;
      }
    // Two plane pairs of irrational planes whose axes meet at an affine point (generate --case
    // degenerate_pencil --seed 43, pair 10: four lines through (-3/2, 1/2, 1)).
    if (t.pencil == algebra::PencilKind::Degenerate && co == ChartOutcome::Ok)
      if (auto p = common_singular_point(a.matrix(), b.matrix())) return common_apex_route(*p, ch);
    if (pp) return *pp;
    out.reason = "no certified projective topology";
    return out;
  }
  const Morphology& m = *t.morphology;
  // A rational plane pair in a regular pencil (the member of rank 2 at a rational root): the
  // curve is A cut by its two planes, each section read exactly (plane_pair_route, which refuses
  // a line common to both sections, an isolated point and components at infinity). Its
  // (loops, unbounded), or nullopt.
  auto plane_pair_reading = [&]() -> std::optional<std::pair<int, int>> {
    if (t.pencil != algebra::PencilKind::Regular) return std::nullopt;
    for (const auto& [pm, quad] : plane_pair_candidates(t, a, b)) {
      if (quad->is_plane()) continue;
      const auto pp = plane_pair_route(core::QuadricMatrix(pm), *quad);
      if (pp && pp->certified() && pp->loops && pp->unbounded_branches)
        return std::make_pair(*pp->loops, *pp->unbounded_branches);
    }
    return std::nullopt;
  };
  if (co == ChartOutcome::Failed) {
    out.reason = "no chart of the plane at infinity separated the points at infinity";
    return out;
  }
  std::vector<Root> roots = roots_of(ch);
  out.computed = true;
  out.points_at_infinity_complete = true;
  out.lines = m.lines;
  out.conics = m.conics;
  for (const auto& r : roots)
    out.points_at_infinity.push_back(r.p);
  if (roots.empty()) {
    // No real point at infinity: every real component is bounded.
    out.loops = m.loops + m.conics + m.cubics;
    out.unbounded_branches = 0;
    out.isolated_points = m.isolated_points;
    if (m.lines > 0 || m.cubics > 0) {
      // A real line or cubic always meets the plane at infinity: the facts contradict.
      out.loops.reset();
      out.unbounded_branches.reset();
      out.undecided.push_back({"loops", "inconsistent: a line or cubic without a point at "
                                        "infinity"});
    }
    return out;
  }
  // Special points at infinity, matched exactly to the roots.
  if (!t.special_points_done) complete_special_points(t, a, b);
  auto undecide_all = [&](const std::string& why) {
    out.loops.reset();
    out.unbounded_branches.reset();
    out.isolated_points.reset();
    out.undecided.push_back({"loops", why});
    out.undecided.push_back({"unbounded_branches", why});
    out.undecided.push_back({"isolated_points", why});
  };
  if (!t.special_points_complete) {
    undecide_all("special points not all computed exactly (conjugate multiple roots)");
    return out;
  }
  std::map<size_t, std::string> special; // root index -> kind
  for (const auto& sp : t.special_points) {
    if (!sp.at_infinity) continue;
    V3 d;
    bool ok = sp.exact;
    for (size_t i = 0; i < 3 && ok; ++i) {
      auto r = Rational::from_string(sp.coords[i]);
      if (r)
        d[i] = *r;
      else
        ok = false;
    }
    std::optional<size_t> idx = ok ? match_root(ch, roots, d) : std::nullopt;
    if (!ok && sp.exact && sp.numbers) idx = match_root(ch, roots, *sp.numbers);
    if (!idx) {
      undecide_all("a special point at infinity with irrational coordinates or unmatched");
      return out;
    }
    auto it = special.find(*idx);
    if (it == special.end() || isolated_kind(sp.kind)) special[*idx] = sp.kind;
  }
  int isolated_at_infinity = 0;
  std::vector<CurveRoot> curve;
  // Where the curve has line (or cubic) components, a line may be the singular line of a
  // member; special_points skips such lines, so points where other components cross them are
  // not listed: every root may then lie on several components (a weaker, still sound premise).
  const bool unlisted_crossings = m.lines > 0 || m.cubics > 0;
  bool node_at_infinity = false, other_special = false;
  for (size_t i = 0; i < roots.size(); ++i) {
    auto it = special.find(i);
    if (it != special.end()) {
      out.points_at_infinity[i].lies_on = it->second;
      if (isolated_kind(it->second)) {
        ++isolated_at_infinity;
        ComponentAtInfinity c;
        c.kind = "point";
        c.direction = roots[i].p.direction;
        out.at_infinity_only.push_back(c);
        continue;
      }
      if (it->second == "crunode")
        node_at_infinity = true;
      else if (it->second != "cusp")
        other_special = true;
      curve.push_back({roots[i].p.multiplicity, true, singular_means_crossing(t.tu_case)});
    } else {
      curve.push_back({roots[i].p.multiplicity, unlisted_crossings});
      if (unlisted_crossings) other_special = true;
    }
  }
  if (isolated_at_infinity > m.isolated_points) {
    undecide_all("more isolated points at infinity than the morphology has");
    return out;
  }
  out.isolated_points = m.isolated_points - isolated_at_infinity;
  const int c = t.tu_case;
  if (node_at_infinity && (c == 5 || c == 8)) {
    // The figure eight cut at its node: two open arcs, each cut again at its other points.
    out.loops = 0;
    out.unbounded_branches = static_cast<int>(curve.size()) + 1;
    return out;
  }
  if (c == 10 || c == 11 || c == 12) {
    // A twisted cubic and a line: counted from their exact parametrisations (the points at
    // infinity alone cannot tell which component passes where), checked against the
    // enumeration below when that decides too.
    CubicAndLine cl = cubic_and_line(a.matrix(), b.matrix());
    if (cl.found) {
      const int unbounded = cl.cubic_points_at_infinity + (cl.line_at_infinity ? 0 : 1);
      auto comps = components_of(c);
      std::set<std::pair<int, int>> res;
      if (comps) res = enumerate(*comps, curve);
      if (res.size() == 1 && *res.begin() != std::pair<int, int>{0, unbounded}) {
        undecide_all("inconsistent: the exact cubic and line disagree with the points at "
                     "infinity");
        return out;
      }
      out.route = "cubic_line";
      out.loops = 0;
      out.unbounded_branches = unbounded;
      out.lines = cl.line_at_infinity ? 0 : 1;
      out.cubic_line = std::move(cl);
      return out;
    }
  }
  auto comps = components_of(c);
  if (!comps || ((node_at_infinity || other_special) && !all_components_real(c))) {
    // Lines only (no loop, conic, cubic or real isolated point: two real skew lines beside two
    // imaginary ones, a real double line): no component lies at infinity (the conics at
    // infinity share none: the chart's resultant is not zero), and a real line not at infinity
    // meets the plane at infinity in exactly one point, real. So each real line is one
    // unbounded branch and there is no loop, however the imaginary lines meet the real ones
    // (a real point on an imaginary line would be its crossing with the conjugate line: a real
    // isolated point, which the morphology excludes, or a point of a real line).
    if (m.lines > 0 && m.loops == 0 && m.conics == 0 && m.cubics == 0 && m.isolated_points == 0 &&
        static_cast<int>(roots.size()) <= m.lines) {
      out.loops = 0;
      out.unbounded_branches = m.lines;
      return out;
    }
    // Tu 27: one real conic and two imaginary lines crossing on it. An imaginary line's only
    // real point is its crossing with the conjugate line, on the conic: the curve's distinct real
    // points at infinity are the conic's own. Two: a hyperbola (two unbounded branches); one: a
    // parabola (tangent to the plane at infinity); none: an ellipse (a loop). (The plane pair of
    // the pencil, when rational, reads the same below; over Q(sqrt d) it is not read: generate
    // --case 27 --seed 32 pair 1 was undecided.)
    if (t.tu_case == 27 && m.conics == 1 && m.loops == 0 && m.lines == 0 && m.cubics == 0 &&
        m.isolated_points == 0 && roots.size() <= 2) {
      const int n = static_cast<int>(roots.size());
      out.loops = n == 0 ? 1 : 0;
      out.unbounded_branches = n;
      return out;
    }
    // Imaginary components may meet the real ones at a special point at infinity (a conic and
    // two imaginary lines crossing on it, Tu 27): the rational plane pair's sections, if any.
    if (const auto reading = plane_pair_reading()) {
      out.loops = reading->first;
      out.unbounded_branches = reading->second;
      return out;
    }
    out.loops.reset();
    out.unbounded_branches.reset();
    const std::string why = "a singular point at infinity where imaginary components may meet";
    out.undecided.push_back({"loops", why});
    out.undecided.push_back({"unbounded_branches", why});
    return out;
  }
  auto res = enumerate(*comps, curve);
  if (res.empty()) {
    out.loops.reset();
    out.unbounded_branches.reset();
    out.isolated_points.reset();
    const std::string why = "inconsistent: no assignment of the points at infinity to the "
                            "components fits the exact facts";
    out.undecided.push_back({"loops", why});
    out.undecided.push_back({"unbounded_branches", why});
    return out;
  }
  const bool smooth_ovals =
      m.loops > 0 && m.conics == 0 && m.lines == 0 && m.cubics == 0 && t.special_points.empty();
  // A, B and the members at the rational roots of det(l A - B): the cones among them sweep the
  // curve (certify/cone_ovals.hpp).
  auto pencil_members = [&a, &b]() {
    std::vector<core::Mat4> members{a.matrix(), b.matrix()};
    for (const Rational& l :
         algebra::rational_roots(algebra::pencil_char_poly(a.matrix(), b.matrix()))) {
      core::Mat4 k;
      for (size_t i = 0; i < 4; ++i)
        for (size_t j = 0; j < 4; ++j)
          k[i][j] = l * a.matrix()[i][j] - b.matrix()[i][j];
      if (!l.is_zero()) members.push_back(k);
    }
    return members;
  };
  const bool lobes = std::any_of(comps->begin(), comps->end(),
                                 [](const Comp& cp) { return cp.kind == CKind::Lobe; });
  if (res.size() > 1 && lobes)
    if (const auto split = lobe_split(a.matrix(), b.matrix(), roots)) {
      // A figure eight with its node affine: the points at infinity on each lobe give the
      // reading (the enumeration's rule: the piece through the node, unbounded when a lobe
      // reaches infinity, and one more piece per further point at infinity on a lobe).
      const int any = split->first + split->second;
      const std::pair<int, int> r{any == 0 ? 1 : 0, any == 0 ? 0
                                                             : 1 + std::max(split->first - 1, 0) +
                                                                   std::max(split->second - 1, 0)};
      if (res.count(r)) res = {r};
    }
  if (res.size() > 1 && smooth_ovals) {
    // Smooth ovals: when a member of the pencil is a real cone or cylinder (A, B, or the
    // member at a rational root of det(l A - B)), its generators tell which oval each point at
    // infinity lies on (certify/cone_ovals.hpp). Every reading found must agree.
    const int n = static_cast<int>(roots.size());
    const std::vector<core::Mat4> members = pencil_members();
    std::optional<std::pair<int, int>> lu;
    bool agree = true;
    for (const auto& k : members) {
      // The curve is K ∩ A for every member K but A itself, whose partner is B.
      const core::Mat4& q = &k == &members[0] ? b.matrix() : a.matrix();
      const auto r = cone_oval_counts(k, q, m.loops, n);
      if (!r) continue;
      if (lu && *lu != *r) agree = false;
      lu = r;
    }
    if (lu && agree && res.count(*lu)) res = {*lu};
  }
  if (res.size() > 1)
    // A rational plane pair in the pencil (a conic and two lines, Tu 23 and 26): a certified
    // reading of its sections that the enumeration allows decides.
    if (const auto reading = plane_pair_reading(); reading && res.count(*reading)) res = {*reading};
  std::set<int> lv, uv;
  for (const auto& [l, u] : res) {
    lv.insert(l);
    uv.insert(u);
  }
  const std::string amb = "the points at infinity can be shared among the components in "
                          "several ways the exact facts allow";
  // The readings left, for a bound on the loops to choose from (certify/proven_loops.hpp):
  // smooth ovals only, where a loop is exactly a compact connected component of the affine
  // curve (what those bounds count).
  if ((lv.size() > 1 || uv.size() > 1) && smooth_ovals) out.readings.assign(res.begin(), res.end());
  if (lv.size() == 1)
    out.loops = *lv.begin();
  else
    out.undecided.push_back({"loops", amb});
  if (uv.size() == 1)
    out.unbounded_branches = *uv.begin();
  else
    out.undecided.push_back({"unbounded_branches", amb});
  return out;
}

void keep_reading(AffineTopology& t, std::pair<int, int> r, const std::string& route) {
  t.loops = r.first;
  t.unbounded_branches = r.second;
  t.undecided.erase(std::remove_if(t.undecided.begin(), t.undecided.end(),
                                   [](const auto& u) {
                                     return u.first == "loops" || u.first == "unbounded_branches";
                                   }),
                    t.undecided.end());
  t.readings = {r};
  t.route = route;
  t.loop_boxes.clear();
  t.all_loops_box.reset();
}

Json affine_json(const AffineTopology& t) {
  Json o = Json::object();
  o.set("status", Json::string(t.certified() ? "certified" : "undecided"));
  if (!t.route.empty()) o.set("route", Json::string(t.route));
  auto count = [&](const char* k, const std::optional<int>& v) {
    o.set(k, v ? Json::number(*v) : Json::null());
  };
  count("loops", t.computed ? t.loops : std::nullopt);
  count("unbounded_branches", t.computed ? t.unbounded_branches : std::nullopt);
  count("isolated_points", t.computed ? t.isolated_points : std::nullopt);
  count("lines", t.computed ? t.lines : std::nullopt);
  count("conics", t.computed ? t.conics : std::nullopt);
  auto num = [](double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return Json::number_text(buf);
  };
  Json pts = Json::array();
  for (const auto& p : t.points_at_infinity) {
    Json e = Json::object();
    if (!p.direction[0].empty()) {
      Json d = Json::array();
      for (const auto& s : p.direction)
        d.push_back(Json::string(s));
      e.set("direction", d);
    } else {
      Json alg = Json::object();
      alg.set("polynomial", Json::string(p.polynomial.to_string("t")));
      Json iv = Json::array();
      iv.push_back(Json::string(p.lo.to_string()));
      iv.push_back(Json::string(p.hi.to_string()));
      alg.set("interval", iv);
      Json d = Json::array();
      for (const auto& s : p.dir_in_t)
        d.push_back(Json::string(s.to_string("t")));
      alg.set("direction_in_t", d);
      e.set("algebraic", alg);
    }
    Json ap = Json::array();
    for (double x : p.approx)
      ap.push_back(num(x));
    e.set("direction_approx", ap);
    e.set("multiplicity", Json::number(p.multiplicity));
    e.set("lies_on", Json::string(p.lies_on));
    pts.push_back(e);
  }
  o.set("points_at_infinity", t.computed ? pts : Json::null());
  Json inf = Json::array();
  for (const auto& c : t.at_infinity_only) {
    Json e = Json::object();
    e.set("kind", Json::string(c.kind));
    if (!c.direction[0].empty()) {
      Json d = Json::array();
      for (const auto& s : c.direction)
        d.push_back(Json::string(s));
      e.set("direction", d);
    }
    if (!c.equation.empty()) e.set("equation", Json::string(c.equation));
    inf.push_back(e);
  }
  o.set("at_infinity_only", t.computed ? inf : Json::null());
  auto box_json = [](const std::array<std::array<Rational, 3>, 2>& bx) {
    Json e = Json::object();
    for (size_t s = 0; s < 2; ++s) {
      Json c = Json::array();
      for (const auto& x : bx[s])
        c.push_back(Json::string(x.to_string()));
      e.set(s == 0 ? "min" : "max", c);
    }
    return e;
  };
  if (t.route == "proven_loops") {
    // The boxes each proven to hold one loop wholly inside; the box proven to hold every
    // compact component (null without an upper bound).
    Json boxes = Json::array();
    for (const auto& bx : t.loop_boxes)
      boxes.push_back(box_json(bx));
    o.set("loop_boxes", boxes);
    o.set("all_loops_box", t.all_loops_box ? box_json(*t.all_loops_box) : Json::null());
  }
  Json und = Json::array();
  for (const auto& [f, why] : t.undecided) {
    Json e = Json::object();
    e.set("field", Json::string(f));
    e.set("reason", Json::string(why));
    und.push_back(e);
  }
  if (!t.computed) {
    Json e = Json::object();
    e.set("field", Json::string("all"));
    e.set("reason", Json::string(t.reason));
    und.push_back(e);
  }
  o.set("undecided", und);
  return o;
}

} // namespace surfcert::certify
