// section_lines: the lines of a degenerate plane section, and line_in_box (see conics.hpp).
//
// The section of the quadric S by the plane P is written exactly as a conic in (s, t) with
// X = s E0 + t E1 + X0 (E0, E1, X0 rational, as affine.cpp's plane route does), and read by
// exact signs: det = 0 (degenerate), delta = a d - b^2 (crossing lines when < 0, a point when
// > 0, parallel lines or one line when 0). Only the final point and direction of each line
// are rounded to doubles.
#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/plane_chart.hpp"
#include "surfcert/trace/conics.hpp"

#include <algorithm>
#include <cmath>

namespace surfcert::trace {

namespace {

using core::Rational;
using R3 = std::array<Rational, 3>;

Point3 to_double(const R3& v) {
  return {v[0].to_double_approx(), v[1].to_double_approx(), v[2].to_double_approx()};
}

} // namespace

std::optional<SectionComponents> section_lines(const core::Mat4& plane, const core::Mat4& other) {
  const auto chart = algebra::plane_chart(plane);
  if (!chart) return std::nullopt;
  const std::array<std::array<Rational, 4>, 3>& col = *chart;
  // A 3D point (s, t) and direction (ds, dt) of the plane.
  auto point = [&](const Rational& s, const Rational& t) {
    R3 p;
    for (size_t i = 0; i < 3; ++i)
      p[i] = col[0][i] * s + col[1][i] * t + col[2][i];
    return p;
  };
  auto dir = [&](double ds, double dt) {
    Point3 d;
    for (size_t i = 0; i < 3; ++i)
      d[i] = col[0][i].to_double_approx() * ds + col[1][i].to_double_approx() * dt;
    return d;
  };
  const auto cm = algebra::restrict_form(other, col);
  const Rational &a = cm[0][0], &b = cm[0][1], &d = cm[1][1], &e = cm[0][2], &f = cm[1][2],
                 &g = cm[2][2];
  SectionComponents out;
  const bool quadratic = !(a.is_zero() && b.is_zero() && d.is_zero());
  if (!quadratic) {
    // 2 e s + 2 f t + g = 0: one line (another plane), or none / the whole plane.
    if (e.is_zero() && f.is_zero()) return g.is_zero() ? std::nullopt : std::optional(out);
    const Rational nn = e * e + f * f;
    const R3 p = point(-g * e / (Rational(2) * nn), -g * f / (Rational(2) * nn));
    out.lines.push_back({to_double(p), dir(-f.to_double_approx(), e.to_double_approx())});
    return out;
  }
  const Rational det = a * (d * g - f * f) - b * (b * g - f * e) + e * (b * f - d * e);
  if (!det.is_zero()) return std::nullopt; // a proper conic: not lines
  const Rational delta = a * d - b * b;
  if (!delta.is_zero()) {
    // Centre: [a b; b d] (s, t) = -(e, f).
    const Rational s0 = (-e * d + b * f) / delta, t0 = (-a * f + b * e) / delta;
    const Point3 p = to_double(point(s0, t0));
    if (delta > Rational(0)) {
      out.points.push_back(p); // two imaginary lines crossing at a real point
      return out;
    }
    // Directions: a ds^2 + 2 b ds dt + d dt^2 = 0, with r = sqrt(-delta).
    const double r = std::sqrt((-delta).to_double_approx());
    const double ad = a.to_double_approx(), bd = b.to_double_approx(), dd = d.to_double_approx();
    for (double sg : {1.0, -1.0}) {
      if (!a.is_zero())
        out.lines.push_back({p, dir(-bd + sg * r, ad)});
      else if (!d.is_zero())
        out.lines.push_back({p, dir(dd, -bd + sg * r)});
      else
        out.lines.push_back({p, sg > 0 ? dir(1, 0) : dir(0, 1)});
    }
    return out;
  }
  // Parallel lines: the form is lambda (m . x)^2 with m = (a, b) or (b, d); along the point
  // r m the section reads alpha r^2 + beta r + gamma = 0 (exact), the lines run along m's
  // normal (-m1, m0).
  const Rational m0 = a.is_zero() ? b : a, m1 = a.is_zero() ? d : b;
  const Rational alpha = a * m0 * m0 + Rational(2) * b * m0 * m1 + d * m1 * m1;
  const Rational beta = Rational(2) * (e * m0 + f * m1), gamma = g;
  const Rational disc = beta * beta - Rational(4) * alpha * gamma;
  if (disc < Rational(0)) return out;
  const Point3 along = dir(-m1.to_double_approx(), m0.to_double_approx());
  if (disc.is_zero()) {
    out.doubled = true;
    const Rational r = -beta / (Rational(2) * alpha);
    out.lines.push_back({to_double(point(r * m0, r * m1)), along});
    return out;
  }
  const double sq = std::sqrt(disc.to_double_approx()), al = alpha.to_double_approx(),
               be = beta.to_double_approx();
  const Point3 base = to_double(point(Rational(0), Rational(0)));
  const Point3 step = dir(m0.to_double_approx(), m1.to_double_approx());
  for (double sg : {1.0, -1.0}) {
    // The root with less cancellation first, the other from the product of the roots.
    const double r1 = (-be - (be >= 0 ? 1 : -1) * sq) / (2 * al);
    const double r = sg > 0 ? r1 : gamma.to_double_approx() / (al * r1);
    Point3 p;
    for (size_t i = 0; i < 3; ++i)
      p[i] = base[i] + r * step[i];
    out.lines.push_back({p, along});
  }
  return out;
}

std::optional<Branch> line_in_box(const Point3& p, const Point3& d, const Box& box) {
  double t0 = -HUGE_VAL, t1 = HUGE_VAL;
  for (size_t k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (p[k] < box.min[k] || p[k] > box.max[k]) return std::nullopt;
      continue;
    }
    double a = (box.min[k] - p[k]) / d[k], b = (box.max[k] - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (!(t0 < t1)) return std::nullopt;
  Branch br;
  br.kind = "line";
  br.closed = false;
  const int n = 8;
  for (int i = 0; i <= n; ++i) {
    const double t = t0 + (t1 - t0) * i / n;
    br.points.push_back({p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]});
  }
  // The ends exactly on their faces (the rounding of p + t d may leave them a hair off).
  for (Point3* e : {&br.points.front(), &br.points.back()}) {
    for (size_t k = 0; k < 3; ++k) {
      if (std::fabs((*e)[k] - box.min[k]) <= 1e-12 * box.diagonal()) (*e)[k] = box.min[k];
      if (std::fabs((*e)[k] - box.max[k]) <= 1e-12 * box.diagonal()) (*e)[k] = box.max[k];
    }
  }
  return br;
}

} // namespace surfcert::trace

namespace surfcert::trace {

std::optional<std::pair<Point3, Point3>>
line_in_direction(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const Point3& d) {
  const QuadricPair q(a, b); // power-of-two scaled doubles (what the tracer walks)
  auto plane = [&d](const std::array<std::array<double, 4>, 4>& m, Point3& n, double& c) {
    for (size_t i = 0; i < 3; ++i)
      n[i] = m[i][0] * d[0] + m[i][1] * d[1] + m[i][2] * d[2];
    c = m[3][0] * d[0] + m[3][1] * d[1] + m[3][2] * d[2];
  };
  Point3 n1{}, n2{};
  double c1 = 0, c2 = 0;
  plane(q.a, n1, c1);
  plane(q.b, n2, c2);
  // Minimum-norm solution of n1 . p = -c1, n2 . p = -c2: p = N^T (N N^T)^-1 (-c).
  const double a11 = n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2];
  const double a12 = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
  const double a22 = n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2];
  const double det = a11 * a22 - a12 * a12;
  if (!(det > 1e-12 * a11 * a22) || !std::isfinite(det)) return std::nullopt;
  const double m1 = (-c1 * a22 + c2 * a12) / det, m2 = (-c2 * a11 + c1 * a12) / det;
  Point3 p{};
  for (size_t i = 0; i < 3; ++i)
    p[i] = m1 * n1[i] + m2 * n2[i];
  // On both surfaces (relative to the terms at p), else no line of the curve runs this way.
  for (const auto* m : {&q.a, &q.b}) {
    double v = 0, size = 0;
    const double x[4] = {p[0], p[1], p[2], 1.0};
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        v += (*m)[i][j] * x[i] * x[j];
        size += std::fabs((*m)[i][j] * x[i] * x[j]);
      }
    if (!(std::fabs(v) <= 1e-9 * size)) return std::nullopt;
  }
  return std::make_pair(p, d);
}

} // namespace surfcert::trace
