#include "surfcert/app/claim_geometry.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/certify/distance/enclosure.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/core/budget.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace surfcert::app {

using algebra::Ball;
using core::Rational;

namespace {

Rational dot(const RPoint& p, const RPoint& q) {
  return p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
}

RPoint sub(const RPoint& p, const RPoint& q) {
  return {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
}

Ball ball(const Rational& r) {
  Ball b;
  arb_set_fmpq(b.v, r.raw(), algebra::ball_precision());
  return b;
}

Rational quadric_value(const core::QuadricMatrix& q, const RPoint& p) {
  const std::array<Rational, 4> x = {p[0], p[1], p[2], Rational(1)};
  Rational v;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      v += q(i, j) * x[static_cast<size_t>(i)] * x[static_cast<size_t>(j)];
  return v;
}

// The ring torus's quartic (core/torus.hpp): its real zero set is exactly the tube.
Rational torus_value(const core::Torus& t, const RPoint& p) {
  const RPoint w = sub(p, t.centre);
  const Rational w2 = dot(w, w), wa = dot(w, t.axis), R2 = t.R * t.R;
  const Rational s = w2 + R2 - t.r * t.r;
  return s * s - Rational(4) * R2 * (w2 - wa * wa / dot(t.axis, t.axis));
}

double approx(const Rational& r) {
  return r.to_double_approx();
}

// A gradient of the defining polynomial at p, by exact central differences read as doubles:
// only a search direction (the witness is checked exactly).
std::optional<std::array<double, 3>> gradient(const core::Surface& s, const RPoint& p) {
  double scale = 1;
  for (const auto& c : p)
    scale = std::max(scale, std::abs(approx(c)));
  const Rational h = Rational::exact_from_double(std::ldexp(1.0, -20) * scale);
  std::array<double, 3> g{};
  for (size_t i = 0; i < 3; ++i) {
    RPoint hi = p, lo = p;
    hi[i] += h, lo[i] -= h;
    auto fh = surface_value(s, hi), fl = surface_value(s, lo);
    if (!fh || !fl) return std::nullopt;
    g[i] = approx((*fh - *fl) / (Rational(2) * h));
  }
  return g;
}

// (A X)_i for X = (x, 1) in balls.
Ball row(const core::QuadricMatrix& q, int i, const std::array<Ball, 3>& x) {
  Ball r = ball(q(i, 3));
  for (int c = 0; c < 3; ++c)
    r += ball(q(i, c)) * x[static_cast<size_t>(c)];
  return r;
}

double row_d(const core::QuadricMatrix& q, int i, const std::array<double, 3>& x) {
  double r = approx(q(i, 3));
  for (int c = 0; c < 3; ++c)
    r += approx(q(i, c)) * x[static_cast<size_t>(c)];
  return r;
}

double value_d(const core::QuadricMatrix& q, const std::array<double, 3>& x) {
  double v = approx(q(3, 3));
  for (int i = 0; i < 3; ++i)
    v += x[static_cast<size_t>(i)] * (row_d(q, i, x) + approx(q(i, 3)));
  return v;
}

} // namespace

Rational dist2(const RPoint& p, const RPoint& q) {
  const RPoint d = sub(p, q);
  return dot(d, d);
}

std::optional<Rational> surface_value(const core::Surface& s, const RPoint& p) {
  if (const auto* q = std::get_if<core::QuadricMatrix>(&s)) return quadric_value(*q, p);
  if (const auto* t = std::get_if<core::Torus>(&s)) return torus_value(*t, p);
  if (const auto* f = std::get_if<core::ImplicitSurface>(&s))
    return f->f.evaluate(p[0], p[1], p[2]);
  return std::nullopt;
}

std::optional<SurfaceWitness> surface_witness(const core::Surface& s, const RPoint& p,
                                              const Rational& reach2) {
  const std::optional<Rational> f0 = surface_value(s, p);
  if (!f0) return std::nullopt;
  if (f0->is_zero()) return SurfaceWitness{p, p};
  const auto g = gradient(s, p);
  if (!g) return std::nullopt;
  const double g2 = (*g)[0] * (*g)[0] + (*g)[1] * (*g)[1] + (*g)[2] * (*g)[2];
  if (!(g2 > 0) || !std::isfinite(g2)) return std::nullopt;
  // The Newton step along the gradient, overshot so the sign flips; a few factors in case the
  // first estimate is off (curvature, a poor difference quotient).
  const double s0 = -approx(*f0) / g2;
  for (double factor : {2.0, 1.25, 4.0, 1.05, 16.0}) {
    RPoint q = p;
    for (size_t i = 0; i < 3; ++i) {
      const double step = factor * s0 * (*g)[i];
      if (!std::isfinite(step)) return std::nullopt;
      q[i] += Rational::exact_from_double(step);
    }
    if (dist2(p, q) > reach2) continue;
    const std::optional<Rational> f1 = surface_value(s, q);
    if (f1 && f1->sign() * f0->sign() <= 0) return SurfaceWitness{p, q};
  }
  return std::nullopt;
}

std::optional<DistanceBounds> point_surface_distance(const core::Surface& s, const RPoint& p,
                                                     long digits) {
  const long prec = static_cast<long>(3.33 * static_cast<double>(digits)) + 64;
  algebra::PrecisionScope scope(prec);
  auto from_ball = [&](const Ball& d) -> DistanceBounds {
    const certify::Enclosure e = certify::Enclosure::from_ball(d.v, digits);
    return {e.lower(), e.upper(), *Rational::from_string(e.lower()),
            *Rational::from_string(e.upper())};
  };
  if (const auto* q = std::get_if<core::QuadricMatrix>(&s)) {
    if (q->is_plane()) { // 2 (n . p) + a33 = 0 with n = (a03, a13, a23): |value| / (2 |n|)
      const RPoint n = {(*q)(0, 3), (*q)(1, 3), (*q)(2, 3)};
      Ball v = ball(core::abs(quadric_value(*q, p))), nn = ball(Rational(4) * dot(n, n)), d;
      arb_sqrt(nn.v, nn.v, prec);
      arb_div(d.v, v.v, nn.v, prec);
      return from_ball(d);
    }
    const certify::PointQuadricResult r = certify::point_quadric_critical(p, *q, digits);
    if (!r.ok || r.criticals.empty()) return std::nullopt;
    // The minimum lies in [min lower, min upper] (point_quadric.hpp).
    DistanceBounds out{r.criticals[0].lower, r.criticals[0].upper,
                       *Rational::from_string(r.criticals[0].lower),
                       *Rational::from_string(r.criticals[0].upper)};
    for (const auto& c : r.criticals) {
      const Rational lo = *Rational::from_string(c.lower), hi = *Rational::from_string(c.upper);
      if (lo < out.lo) out.lo = lo, out.lower = c.lower;
      if (hi < out.hi) out.hi = hi, out.upper = c.upper;
    }
    return out;
  }
  if (const auto* t = std::get_if<core::Torus>(&s)) {
    // | sqrt((rho - R)^2 + h^2) - r | with h the height over the centre plane and rho the
    // distance from the axis.
    const RPoint w = sub(p, t->centre);
    const Rational wa = dot(w, t->axis), h2 = wa * wa / dot(t->axis, t->axis);
    Ball rho = ball(dot(w, w) - h2), d;
    arb_sqrt(rho.v, rho.v, prec);
    Ball e = rho - ball(t->R);
    d = e * e + ball(h2);
    arb_sqrt(d.v, d.v, prec);
    d = d - ball(t->r);
    arb_abs(d.v, d.v);
    return from_ball(d);
  }
  return std::nullopt;
}

std::optional<CurveWitness> curve_witness(const core::QuadricMatrix& a,
                                          const core::QuadricMatrix& b,
                                          const std::array<double, 3>& p) {
  // Proposal in doubles: the axis k along which the tangent grad f x grad g is largest is
  // fixed; Newton on the other two.
  std::array<double, 3> x = p;
  auto grads = [&](const std::array<double, 3>& y) {
    std::array<std::array<double, 3>, 2> g{};
    for (int i = 0; i < 3; ++i)
      g[0][static_cast<size_t>(i)] = 2 * row_d(a, i, y),
      g[1][static_cast<size_t>(i)] = 2 * row_d(b, i, y);
    return g;
  };
  auto g = grads(x);
  const std::array<double, 3> tangent = {g[0][1] * g[1][2] - g[0][2] * g[1][1],
                                         g[0][2] * g[1][0] - g[0][0] * g[1][2],
                                         g[0][0] * g[1][1] - g[0][1] * g[1][0]};
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(tangent[static_cast<size_t>(i)]) > std::abs(tangent[static_cast<size_t>(k)]))
      k = i;
  if (!(std::abs(tangent[static_cast<size_t>(k)]) > 0)) return std::nullopt;
  const size_t i = static_cast<size_t>((k + 1) % 3), j = static_cast<size_t>((k + 2) % 3);
  std::array<std::array<double, 2>, 2> Y{};
  for (int it = 0; it < 40; ++it) {
    g = grads(x);
    const double det = g[0][i] * g[1][j] - g[0][j] * g[1][i];
    if (!(std::abs(det) > 0)) return std::nullopt;
    Y = {{{g[1][j] / det, -g[0][j] / det}, {-g[1][i] / det, g[0][i] / det}}};
    const double f = value_d(a, x), h = value_d(b, x);
    const double di = Y[0][0] * f + Y[0][1] * h, dj = Y[1][0] * f + Y[1][1] * h;
    x[i] -= di, x[j] -= dj;
    if (!std::isfinite(x[i]) || !std::isfinite(x[j])) return std::nullopt;
    if (std::abs(di) + std::abs(dj) == 0) break;
  }
  double scale = 1;
  for (double c : x)
    scale = std::max(scale, std::abs(c));
  const RPoint m = {Rational::exact_from_double(x[0]), Rational::exact_from_double(x[1]),
                    Rational::exact_from_double(x[2])};
  // Krawczyk: K = m - Y F(m) + (I - Y J(X)) (X - m) inside the box X = m +- r (free axes)
  // proves one root of F = (f, g) in X. Y is any matrix (here the float inverse at m).
  algebra::PrecisionScope scope(256);
  const Ball fm = ball(quadric_value(a, m)), gm = ball(quadric_value(b, m));
  for (double rel : {0x1p-40, 0x1p-30, 0x1p-20}) {
    const Rational r = Rational::exact_from_double(rel * scale);
    std::array<Ball, 3> X = {ball(m[0]), ball(m[1]), ball(m[2])};
    Ball dx; // [-r, r]
    arb_zero(dx.v);
    arb_add_error(dx.v, ball(r).v);
    X[i] = X[i] + dx, X[j] = X[j] + dx;
    Ball J[2][2] = {{ball(Rational(2)) * row(a, static_cast<int>(i), X),
                     ball(Rational(2)) * row(a, static_cast<int>(j), X)},
                    {ball(Rational(2)) * row(b, static_cast<int>(i), X),
                     ball(Rational(2)) * row(b, static_cast<int>(j), X)}};
    bool inside = true;
    for (size_t l = 0; l < 2 && inside; ++l) {
      const Ball y0(Y[l][0]), y1(Y[l][1]);
      // Row l of (I - Y J) applied to (dx, dx), plus -(Y F(m))_l.
      Ball c0 = ball(Rational(l == 0 ? 1 : 0)) - (y0 * J[0][0] + y1 * J[1][0]);
      Ball c1 = ball(Rational(l == 1 ? 1 : 0)) - (y0 * J[0][1] + y1 * J[1][1]);
      Ball kr = -(y0 * fm + y1 * gm) + c0 * dx + c1 * dx;
      arf_t bound;
      arf_init(bound);
      arb_get_abs_ubound_arf(bound, kr.v, 256);
      Ball rb = ball(r);
      inside = arf_cmp(bound, arb_midref(rb.v)) < 0;
      arf_clear(bound);
    }
    if (inside) return CurveWitness{m, r, k};
  }
  return std::nullopt;
}

Rational segment_dist2(const RPoint& p, const RPoint& s, const RPoint& t) {
  const RPoint u = sub(t, s), w = sub(p, s);
  const Rational uu = dot(u, u);
  if (uu.is_zero()) return dot(w, w);
  Rational lam = dot(w, u) / uu;
  if (lam < Rational(0)) lam = Rational(0);
  if (Rational(1) < lam) lam = Rational(1);
  const RPoint f = {s[0] + lam * u[0], s[1] + lam * u[1], s[2] + lam * u[2]};
  return dist2(p, f);
}

bool sqrt_sum_within(const Rational& a, const Rational& b, const Rational& t) {
  // <=> t >= 0, t^2 >= b and t^2 + b - a >= 2 t sqrt(b).
  if (t.sign() < 0 || t * t < b) return false;
  const Rational lhs = t * t + b - a;
  return lhs.sign() >= 0 && Rational(4) * t * t * b <= lhs * lhs;
}

bool sqrt_plus_less(const Rational& u, const Rational& t, const Rational& v) {
  // sqrt(u) + t < sqrt(v)  <=>  2 t sqrt(u) < v - u - t^2  <=>  rhs > 0 and 4 t^2 u < rhs^2.
  const Rational rhs = v - u - t * t;
  return rhs.sign() > 0 && Rational(4) * t * t * u < rhs * rhs;
}

} // namespace surfcert::app

namespace surfcert::app {

namespace {

// A double d with d <= x - sqrt(e2) (down) or d >= x + sqrt(e2) (up), checked exactly.
double outward(const Rational& x, const Rational& e2, bool up) {
  const double s = std::sqrt(e2.to_double_approx()), xd = x.to_double_approx();
  double slack = 1e-12 * (1 + std::abs(xd) + s);
  for (int it = 0; it < 60; ++it, slack *= 4) {
    const double d = up ? xd + s + slack : xd - s - slack;
    const Rational gap =
        up ? Rational::exact_from_double(d) - x : x - Rational::exact_from_double(d);
    if (gap.sign() >= 0 && e2 <= gap * gap) return d;
  }
  return up ? HUGE_VAL : -HUGE_VAL;
}

// Centred-form enclosure of the quadric's equation over the box (centre c, half-widths h)
// does not contain 0.
bool excludes(const core::QuadricMatrix& q, const std::array<double, 3>& c,
              const std::array<double, 3>& h) {
  std::array<Ball, 3> cb = {Ball(c[0]), Ball(c[1]), Ball(c[2])}, xb;
  for (size_t i = 0; i < 3; ++i) {
    xb[i] = cb[i];
    Ball r(h[i]);
    arb_add_error(xb[i].v, r.v);
  }
  Ball f = ball(q(3, 3));
  for (int i = 0; i < 3; ++i)
    f += cb[static_cast<size_t>(i)] * (row(q, i, cb) + ball(q(i, 3)));
  for (int i = 0; i < 3; ++i) {
    Ball d = xb[static_cast<size_t>(i)] - cb[static_cast<size_t>(i)];
    f += ball(Rational(2)) * row(q, i, xb) * d;
  }
  return !arb_contains_zero(f.v);
}

} // namespace

std::optional<DBox> ellipsoid_bounding_box(const core::QuadricMatrix& q) {
  if (q.kind() != core::QuadricKind::Ellipsoid) return std::nullopt;
  // Q^-1 by the adjugate; centre x0 = -Q^-1 b; (x - x0)^T Q (x - x0) = k = b^T Q^-1 b - c, so
  // (x_i - x0_i)^2 <= k (Q^-1)_ii.
  auto m = [&](int i, int j) { return q(i, j); };
  std::array<std::array<Rational, 3>, 3> adj;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      adj[static_cast<size_t>(i)][static_cast<size_t>(j)] =
          m(r0, c0) * m(r1, c1) - m(r0, c1) * m(r1, c0);
    }
  Rational det;
  for (int j = 0; j < 3; ++j)
    det += m(0, j) * adj[static_cast<size_t>(j)][0];
  if (det.is_zero()) return std::nullopt;
  std::array<Rational, 3> x0;
  Rational k = -q(3, 3);
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j)
      x0[i] -= adj[i][j] / det * q(static_cast<int>(j), 3);
  }
  for (size_t i = 0; i < 3; ++i)
    k -= x0[i] * q(static_cast<int>(i), 3); // b^T Q^-1 b = -b . x0
  DBox box{};
  for (size_t i = 0; i < 3; ++i) {
    const Rational e2 = k * adj[i][i] / det;
    if (e2.sign() < 0) return std::nullopt;
    box[i] = {outward(x0[i], e2, false), outward(x0[i], e2, true)};
    if (!std::isfinite(box[i][0]) || !std::isfinite(box[i][1])) return std::nullopt;
  }
  return box;
}

Coverage prove_coverage(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                        const std::vector<std::vector<RPoint>>& lines, const Rational& tol,
                        const DBox& box, long max_boxes) {
  algebra::PrecisionScope scope(128);
  struct Seg {
    std::array<double, 3> s, e;
    const RPoint *rs, *re;
  };
  std::vector<Seg> segs;
  for (const auto& l : lines)
    for (size_t k = 0; k < l.size(); ++k) {
      const RPoint& s = l[k];
      const RPoint& e = l[k + 1 < l.size() ? k + 1 : k];
      segs.push_back({{approx(s[0]), approx(s[1]), approx(s[2])},
                      {approx(e[0]), approx(e[1]), approx(e[2])},
                      &s,
                      &e});
    }
  auto nearest = [&](const std::array<double, 3>& c) {
    size_t best = 0;
    double bd = HUGE_VAL;
    for (size_t k = 0; k < segs.size(); ++k) {
      const auto& sg = segs[k];
      double u[3], w[3], uu = 0, wu = 0;
      for (size_t i = 0; i < 3; ++i)
        u[i] = sg.e[i] - sg.s[i], w[i] = c[i] - sg.s[i], uu += u[i] * u[i], wu += w[i] * u[i];
      const double lam = uu > 0 ? std::clamp(wu / uu, 0.0, 1.0) : 0.0;
      double d2 = 0;
      for (size_t i = 0; i < 3; ++i)
        d2 += (w[i] - lam * u[i]) * (w[i] - lam * u[i]);
      if (d2 < bd) bd = d2, best = k;
    }
    return std::make_pair(best, std::sqrt(bd));
  };
  const double td = approx(tol);
  Coverage out;
  std::vector<DBox> stack = {box};
  while (!stack.empty()) {
    if (++out.boxes > max_boxes) return out;
    if (out.boxes % 1024 == 0) core::check_budget();
    const DBox bx = stack.back();
    stack.pop_back();
    std::array<double, 3> c{}, h{};
    for (size_t i = 0; i < 3; ++i)
      // h is rounded up one ulp: the box [c - h, c + h] holds bx whatever the rounding.
      c[i] = 0.5 * (bx[i][0] + bx[i][1]),
      h[i] = std::nextafter(std::max(bx[i][1] - c[i], c[i] - bx[i][0]), HUGE_VAL);
    const double hd = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    const auto [k, dist] = nearest(c);
    if (!segs.empty() && dist + hd <= td) {
      // Exactly: |c - segment| + |h| <= tol (c and h dyadic: exact rationals).
      const RPoint rc = {Rational::exact_from_double(c[0]), Rational::exact_from_double(c[1]),
                         Rational::exact_from_double(c[2])};
      Rational h2;
      for (double x : h)
        h2 += Rational::exact_from_double(x) * Rational::exact_from_double(x);
      if (sqrt_sum_within(segment_dist2(rc, *segs[k].rs, *segs[k].re), h2, tol)) continue;
    }
    if (excludes(a, c, h) || excludes(b, c, h)) continue;
    size_t axis = 0;
    for (size_t i = 1; i < 3; ++i)
      if (h[i] > h[axis]) axis = i;
    if (!(h[axis] > 0) || c[axis] <= bx[axis][0] || c[axis] >= bx[axis][1]) {
      out.stuck = c; // a box that neither excludes nor fits: near the curve, off the claim
      return out;
    }
    DBox lo = bx, hi = bx;
    lo[axis][1] = c[axis], hi[axis][0] = c[axis];
    stack.push_back(lo);
    stack.push_back(hi);
  }
  out.proven = true;
  return out;
}

} // namespace surfcert::app
