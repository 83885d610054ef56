// QuadricPair (the pair as normalised doubles) and project_onto_curve (minimum-norm
// Gauss-Newton onto f = g = 0). Approximate, like all of surfcert::trace.
#include "surfcert/trace/curve.hpp"

#include "surfcert/certify/enclosure.hpp"

#include "double_double.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace surfcert::trace {

namespace {

using M4 = std::array<std::array<double, 4>, 4>;

// A scaled to max|A| in [1/2, 1) entrywise in double: each entry rounded once
// (certify::approx: num/den, or for a shape posed in doubles the midpoint of its enclosure,
// without forming the rationals), then scaled by a power of two, which rounds nothing. So a
// matrix posed in doubles is traced exactly as given: a pair of nearly singular members (two
// pipes rounded to doubles) has a neck of ~1e-8 of its size whose side is decided by
// perturbations of ~1e-16, and dividing by the maximum would add one of that size.
// A matrix of doubles that is not exactly symmetric (M^T Q M computed in double) stands for its
// symmetric part, whose entries (d_ij + d_ji) / 2 need up to 54 bits: hi + lo, both doubles
// (an exact two-sum), which a long double holds exactly; form() evaluates with hi + lo.
// `exact` is cleared unless hi + lo is the exact matrix times that power of two.
// `scale` receives e with out = (rounded A) 2^-e; `pow2` is cleared when the entries were
// divided exactly instead (beyond the doubles).
void normalised(const core::QuadricMatrix& q, M4& out, M4& lo, bool& exact, int& scale,
                bool& pow2) {
  lo = M4{};
  const core::DoubleMat4* d = q.shape() ? nullptr : q.double_matrix();
  if (d) {
    for (size_t i = 0; i < 4; ++i) {
      out[i][i] = (*d)[i][i];
      for (size_t j = i + 1; j < 4; ++j) {
        const double x = (*d)[i][j], y = (*d)[j][i];
        const double s = x + y, yv = s - x, err = (x - (s - yv)) + (y - yv); // s + err = x + y
        const double h = 0.5 * s, l = 0.5 * err;
        const long double hl = static_cast<long double>(h) + l;
        if (h * 2 != s || l * 2 != err || hl - h != l || !std::isfinite(s)) exact = false;
        out[i][j] = out[j][i] = h;
        lo[i][j] = lo[j][i] = l;
      }
    }
  } else {
    out = certify::approx(q);
    exact = exact && certify::approx_is_exact(q);
  }
  double mx = 0;
  for (const auto& row : out)
    for (double v : row)
      mx = std::max(mx, std::fabs(v));
  if (std::isfinite(mx) && mx > 0) {
    int e = 0;
    std::frexp(mx, &e); // mx = f 2^e, f in [1/2, 1)
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        const double y = std::ldexp(out[i][j], -e), yl = std::ldexp(lo[i][j], -e);
        // underflow: a tiny entry lost bits
        if (std::ldexp(y, e) != out[i][j] || std::ldexp(yl, e) != lo[i][j]) exact = false;
        out[i][j] = y;
        lo[i][j] = yl;
      }
    scale = e;
    return;
  }
  exact = false;
  pow2 = false;
  lo = M4{};
  // Entries beyond the double range: divide exactly first.
  core::Rational mq;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (mq < core::abs(q(i, j))) mq = core::abs(q(i, j));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      out[static_cast<size_t>(i)][static_cast<size_t>(j)] = (q(i, j) / mq).to_double_approx();
}

// Evaluated in long double (64-bit mantissa on x86-64): near the curve f is the difference of
// terms of size ~|p|^2, and where the two surfaces meet at a small angle a the rounding error
// of f becomes a sideways error of the corrected points ~1/a times larger. Extended precision
// keeps that below the steps even for loops of size 2^-20 at some distance from the origin.
// (Unless the pair is posed in doubles, the coefficients themselves are rounded: the traced
// curve is then that of the rounded pair, a fixed, smooth perturbation of the exact one.)
// The symmetric form's ten distinct products (m symmetric): x (m00 x + 2 (m01 y + m02 z +
// m03)) + y (m11 y + 2 (m12 z + m13)) + z (m22 z + 2 m23) + m33, as form_fast below.
// With `lo` (see normalised) the coefficients are m + lo, exact in long double.
double form(const M4& m, const Point3& p, const M4* lo = nullptr) {
  const long double x = p[0], y = p[1], z = p[2];
  auto e = [&m, lo](size_t i, size_t j) {
    return lo ? static_cast<long double>(m[i][j]) + (*lo)[i][j] : static_cast<long double>(m[i][j]);
  };
  const long double s = x * (e(0, 0) * x + 2 * (e(0, 1) * y + e(0, 2) * z + e(0, 3))) +
                        y * (e(1, 1) * y + 2 * (e(1, 2) * z + e(1, 3))) +
                        z * (e(2, 2) * z + 2 * e(2, 3)) + e(3, 3);
  return static_cast<double>(s);
}

// Gradient in double: it only steers the Newton steps; the zero set is decided by form().
Point3 gradient(const M4& m, const Point3& p) {
  Point3 g{};
  for (size_t i = 0; i < 3; ++i)
    g[i] = 2 * (m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3]);
  return g;
}

// X^T M X in plain double (symmetric M, 10 products): the first Newton steps, far from the
// rounding floor, do not need extended precision.
double form_fast(const M4& m, const Point3& p) {
  const double x = p[0], y = p[1], z = p[2];
  return x * (m[0][0] * x + 2 * (m[0][1] * y + m[0][2] * z + m[0][3])) +
         y * (m[1][1] * y + 2 * (m[1][2] * z + m[1][3])) + z * (m[2][2] * z + 2 * m[2][3]) +
         m[3][3];
}

double dot(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The size of the terms of X^T M X at p: sum |m_ij x_i x_j| (x = (p, 1)). The rounding floor of
// f's evaluation is ~1e-19 of it, and f / it is scale-free: a curve scaled by 10^4 and
// translated by 10^5 meets the same relative criterion as a unit one (1 + |p|^2 would not be:
// there it lets points lie ~1e-3 of the curve's size off it).
// (m symmetric: the ten distinct products, the off-diagonal ones twice.)
double term_size(const std::array<std::array<double, 4>, 4>& m, const Point3& p) {
  const double x = std::fabs(p[0]), y = std::fabs(p[1]), z = std::fabs(p[2]);
  auto a = [&m](size_t i, size_t j) { return std::fabs(m[i][j]); };
  return x * (a(0, 0) * x + 2 * (a(0, 1) * y + a(0, 2) * z + a(0, 3))) +
         y * (a(1, 1) * y + 2 * (a(1, 2) * z + a(1, 3))) + z * (a(2, 2) * z + 2 * a(2, 3)) +
         a(3, 3);
}

// In a refined pair the gradient is the exact matrices' too (hi + lo, in long double): next to
// a cone's apex it is a difference of terms ~|p| that cancel to ~r, and the rounded matrix's
// moved the tangent grad f x grad g by more than the gap between two pieces of curve there
// (refined walks stepped against the curve's orientation on 12 of 40 cylinders through the
// apex of a cone posed in doubles). (A matrix of doubles carried as hi + lo keeps the hi
// gradient: the same pair read exactly, as rationals, must give the same points.)
Point3 gradient_refined(const M4& m, const M4& lo, const Point3& p) {
  Point3 g{};
  for (size_t i = 0; i < 3; ++i) {
    long double s = 0;
    for (size_t j = 0; j < 3; ++j)
      s += (static_cast<long double>(m[i][j]) + lo[i][j]) * p[j];
    s += static_cast<long double>(m[i][3]) + lo[i][3];
    g[i] = static_cast<double>(2 * s);
  }
  return g;
}

} // namespace

QuadricPair::QuadricPair(const core::QuadricMatrix& qa, const core::QuadricMatrix& qb) {
  bool exact = true;
  normalised(qa, a, a_lo, exact, a_scale, scaled_by_pow2);
  normalised(qb, b, b_lo, exact, b_scale, scaled_by_pow2);
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      split = split || a_lo[i][j] != 0 || b_lo[i][j] != 0;
  // form() rounds at most 8 times along any term's path (products, the nested sums, the four
  // partial sums), each by u = epsilon / 2 of its type: |error| <= gamma_8 F ~ 8u F = 4 epsilon F
  // (long double on x86-64: 4.3e-19 F; where long double is double, 8.9e-16 F).
  const double evaluation = 4 * static_cast<double>(std::numeric_limits<long double>::epsilon());
  noise_unit = exact ? evaluation : 0x1p-53 + evaluation;
}

std::optional<QuadricPair> QuadricPair::refined(const core::QuadricMatrix& qa,
                                                const core::QuadricMatrix& qb) const {
  if (!scaled_by_pow2) return std::nullopt;
  QuadricPair r = *this;
  // The remainder of each exact entry, scaled as its double was, after that double: exact as a
  // rational, rounded once (a matrix of doubles symmetrised: the split's remainder again).
  dd::remainders(qa, core::pow2(-a_scale), a, r.a_lo);
  dd::remainders(qb, core::pow2(-b_scale), b, r.b_lo);
  r.refined_form = true;
  r.noise_unit = 0x1p-96;
  return r;
}

double QuadricPair::f(const Point3& p) const {
  if (refined_form) return dd::form(a, a_lo, p);
  return form(a, p, split ? &a_lo : nullptr);
}
double QuadricPair::g(const Point3& p) const {
  if (refined_form) return dd::form(b, b_lo, p);
  return form(b, p, split ? &b_lo : nullptr);
}
Point3 QuadricPair::grad_f(const Point3& p) const {
  return refined_form ? gradient_refined(a, a_lo, p) : gradient(a, p);
}
Point3 QuadricPair::grad_g(const Point3& p) const {
  return refined_form ? gradient_refined(b, b_lo, p) : gradient(b, p);
}

double QuadricPair::noise_radius(const Point3& p) const {
  const Point3 gf = gradient(a, p), gg = gradient(b, p);
  const double nf = std::sqrt(dot(gf, gf)), ng = std::sqrt(dot(gg, gg));
  const Point3 c{gf[1] * gg[2] - gf[2] * gg[1], gf[2] * gg[0] - gf[0] * gg[2],
                 gf[0] * gg[1] - gf[1] * gg[0]};
  const double sine_nf_ng = std::sqrt(dot(c, c)); // sin(angle) |grad f| |grad g|
  if (!(sine_nf_ng > 0)) return HUGE_VAL;
  // max(Fa / nf, Fb / ng) / sin = max(Fa ng, Fb nf) / (sin nf ng)
  const double r = noise_unit * std::max(term_size(a, p) * ng, term_size(b, p) * nf) / sine_nf_ng;
  if (!(noise_unit < 0x1p-53)) return r;
  // Evaluated beyond its doubles (as posed, or refined), the evaluation's noise can be far below
  // the doubles' spacing: two pieces of curve closer than a few units of the points' last place
  // cannot be told apart by double points (a cylinder 2^-60 from a cone's apex: its loops on
  // the two nappes 2e-18 apart).
  const double big = std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2]), 1.0});
  return std::max(r, 0x1p-48 * big);
}

double QuadricPair::distance_bound(const Point3& p, double enough) const {
  if (enough > 0) {
    // form_fast rounds at most 8 times along a term's path: |error| <= 8 2^-53 F; the lo parts
    // (at most 2^-53 of an entry) add at most 2^-53 F more.
    auto quick = [&p](const M4& m) {
      const Point3 g = gradient(m, p);
      const double gn = std::sqrt(dot(g, g));
      const double f = std::fabs(form_fast(m, p)) + 0x1p-53 * 10 * term_size(m, p);
      return gn > 0 ? f / gn : HUGE_VAL;
    };
    const double d = std::max(quick(a), quick(b));
    if (d <= enough) return d;
  }
  auto one = [&p](const M4& m, const M4* lo) {
    const Point3 g = gradient(m, p);
    const double gn = std::sqrt(dot(g, g));
    const double f = std::fabs(form(m, p, lo)) + 0x1p-53 * term_size(m, p);
    return gn > 0 ? f / gn : HUGE_VAL;
  };
  return std::max(one(a, split ? &a_lo : nullptr), one(b, split ? &b_lo : nullptr));
}

namespace {

// One minimum-norm Gauss-Newton step: p - J^T (J J^T)^-1 (f, g). False when J J^T is
// singular (the gradients parallel to ~1e-15 rad) or the data are not finite.
bool gauss_newton_step(const QuadricPair& q, const Point3& p, double fv, double gv, Point3& out,
                       double& step_norm) {
  const Point3 gf = q.grad_f(p), gg = q.grad_g(p);
  const double a11 = dot(gf, gf), a12 = dot(gf, gg), a22 = dot(gg, gg);
  const double det = a11 * a22 - a12 * a12;
  if (!(det > 1e-30 * a11 * a22) || !std::isfinite(det)) return false;
  const double m1 = (a22 * fv - a12 * gv) / det;
  const double m2 = (a11 * gv - a12 * fv) / det;
  double s2 = 0;
  for (size_t i = 0; i < 3; ++i) {
    const double st = m1 * gf[i] + m2 * gg[i];
    out[i] = p[i] - st;
    s2 += st * st;
  }
  step_norm = std::sqrt(s2);
  return std::isfinite(step_norm);
}

double residual(const QuadricPair& q, const Point3& x) {
  return std::max(std::abs(q.f(x)), std::abs(q.g(x)));
}

// The terms' sizes of both forms at a point (see term_size).
struct TermSizes {
  double f, g;
};
TermSizes term_sizes(const QuadricPair& q, const Point3& x) {
  return {term_size(q.a, x), term_size(q.b, x)};
}

// max(|f| / F, |g| / G): the residual relative to the terms' size (see term_size).
double relative_residual(const TermSizes& t, double fv, double gv) {
  return std::max(t.f > 0 ? std::abs(fv) / t.f : std::abs(fv),
                  t.g > 0 ? std::abs(gv) / t.g : std::abs(gv));
}

// Once within the tolerance: up to two more steps while the residual keeps dropping. Where the
// surfaces meet at a small angle a the tolerance band around the curve is ~1/a times wider
// than the rounding floor, so stopping at its edge would leave the point visibly off the
// curve sideways.
// fv, gv: f and g at p, already evaluated by the caller (the acceptance test).
void polish(const QuadricPair& q, Point3& p, double fv, double gv) {
  // Only needed where the surfaces meet at a small angle (sin^2 < 1/100); elsewhere the
  // tolerance band is already as narrow as the rounding floor allows.
  // For a pair evaluated beyond its doubles (traced exactly as posed, or refined) at every
  // angle: the acceptance test's residual, 1e-15 of the terms, is no distance where a gradient
  // is small (next to a cone's apex, |grad f| ~ 2r: up to 5e-6 off at r = 1e-10), while the
  // noise radius there lets the walk in; walks stepped between the two sheets of a rounded
  // cone's waist and back (a cylinder through the apex posed in doubles: 2 of 40 such pictures
  // certified with stretches against the curve's orientation), or from one nappe to the other.
  if (q.noise_unit < 0x1p-53) {
    // Traced exactly as posed: the residuals are evaluated to ~1e-19, far below the ~1e-16 that
    // a double point on the curve leaves. The residual test accepts a band ~1e-16 / sin wide
    // sideways (~1e-8 around a neck of pipes posed in doubles), but Gauss-Newton's steps, which
    // divide by sin^2, still see where in it the curve runs: steps while they shrink, until
    // they no longer move p.
    double last = HUGE_VAL;
    const double floor = 0x1p-50 * (1 + std::sqrt(dot(p, p)));
    for (int k = 0; k < 6; ++k) {
      Point3 x{};
      double sn = 0;
      if (k > 0) fv = q.f(p), gv = q.g(p);
      if (!gauss_newton_step(q, p, fv, gv, x, sn) || !(sn < last)) return;
      p = x;
      if (sn <= floor) return;
      last = 0.5 * sn;
    }
    return;
  }
  {
    const Point3 gf = q.grad_f(p), gg = q.grad_g(p);
    const double a11 = dot(gf, gf), a12 = dot(gf, gg), a22 = dot(gg, gg);
    if (a11 * a22 - a12 * a12 > 1e-2 * a11 * a22) return;
  }
  double r = std::max(std::abs(fv), std::abs(gv));
  for (int k = 0; k < 2 && r > 0; ++k) {
    Point3 x{};
    double sn = 0;
    if (!gauss_newton_step(q, p, q.f(p), q.g(p), x, sn)) return;
    const double rx = residual(q, x);
    if (!(rx < r)) return;
    p = x;
    r = rx;
  }
}

} // namespace

bool project_onto_curve(const QuadricPair& q, Point3& p, int iterations) {
  // The terms' sizes once, at the point given: the steps move it by a small fraction of its
  // distance from the origin and of the curve's size (a predictor lands within its step's
  // sagitta of the curve), so the sizes, which only scale the tests' tolerances, barely change
  // (recomputed per test they were 8% of a traced ellipsoid pair). Recomputed after a step
  // that moves p further than 1/16 of its norm plus the terms' own scale would allow.
  TermSizes ts = term_sizes(q, p);
  Point3 at = p;
  auto sizes = [&]() -> const TermSizes& {
    const double d2 = (p[0] - at[0]) * (p[0] - at[0]) + (p[1] - at[1]) * (p[1] - at[1]) +
                      (p[2] - at[2]) * (p[2] - at[2]);
    if (d2 > (1.0 / 256) * (1 + dot(at, at))) {
      ts = term_sizes(q, p);
      at = p;
    }
    return ts;
  };
  // Double-precision steps while the residual is far above the rounding floor, then the
  // extended-precision loop below decides convergence. From within 1e-11 one more double step
  // is taken: Newton's quadratic convergence puts it at the double evaluation's floor (~1e-16),
  // where the extended loop usually accepts at its first evaluation (it would otherwise take
  // that step itself, at twice the cost).
  for (int it = 0; it < iterations; ++it) {
    const double fv = form_fast(q.a, p), gv = form_fast(q.b, p);
    if (!std::isfinite(fv) || !std::isfinite(gv)) return false;
    const double rel = relative_residual(sizes(), fv, gv);
    if (rel <= 1e-14) break; // at the double floor already
    Point3 x{};
    double sn = 0;
    if (!gauss_newton_step(q, p, fv, gv, x, sn)) {
      if (rel <= 1e-11) break;
      return false;
    }
    p = x;
    if (rel <= 1e-11) break;
  }
  for (int it = 0; it <= iterations; ++it) {
    const double fv = q.f(p), gv = q.g(p);
    if (!std::isfinite(fv) || !std::isfinite(gv)) return false;
    if (relative_residual(sizes(), fv, gv) <= 1e-15) {
      polish(q, p, fv, gv);
      return true;
    }
    if (it == iterations) break;
    Point3 x{};
    double sn = 0;
    if (!gauss_newton_step(q, p, fv, gv, x, sn)) return false;
    p = x;
    if (sn <= 1e-16 * (1 + std::sqrt(dot(p, p)))) {
      // The steps no longer move p: accept it at a little above the rounding floor.
      return relative_residual(sizes(), q.f(p), q.g(p)) <= 1e-13;
    }
  }
  return false;
}

} // namespace surfcert::trace
