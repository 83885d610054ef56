#include "surfcert/certify/distance/contact_sampling.hpp"

#include "surfcert/algebra/inertia.hpp"
#include "surfcert/certify/distance/canal_distance.hpp"
#include "surfcert/certify/distance/offset_minimum.hpp"
#include "surfcert/certify/distance/solid_relation.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace surfcert::certify {

using core::Rational;

bool quadric_connected(const core::QuadricMatrix& q) {
  core::Mat4 m3 = q.matrix();
  for (size_t i = 0; i < 4; ++i) {
    m3[i][3] = Rational(0);
    m3[3][i] = Rational(0);
  }
  const algebra::Inertia im = algebra::inertia_ldlt(m3), iq = algebra::inertia_ldlt(q.matrix());
  const bool indefinite = im.p > 0 && im.n > 0;
  if (im.rank() == 3 && indefinite && std::min(iq.p, iq.n) == 1 && iq.rank() == 4)
    return false; // two-sheeted hyperboloid: signature (3, 1) with an indefinite block
  if (im.rank() == 2 && indefinite && iq.rank() == 3) return false; // hyperbolic cylinder
  if (im.rank() == 1 && iq.rank() == 2 && iq.p == 1 && iq.n == 1) return false; // x^2 = 1
  return true;
}

namespace {

double eval_d(const core::QuadricMatrix& q, const std::array<double, 3>& x) {
  const double X[4] = {x[0], x[1], x[2], 1};
  double s = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      s += q(i, j).to_double_approx() * X[i] * X[j];
  return s;
}

// Float projection on f = 0 along the gradient (Newton, a few steps).
std::array<double, 3> project_d(const core::QuadricMatrix& q, std::array<double, 3> x) {
  for (int it = 0; it < 30; ++it) {
    std::array<double, 3> g{};
    for (int i = 0; i < 3; ++i) {
      double s = q(i, 3).to_double_approx();
      for (int j = 0; j < 3; ++j)
        s += q(i, j).to_double_approx() * x[static_cast<size_t>(j)];
      g[static_cast<size_t>(i)] = 2 * s;
    }
    const double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
    if (gg == 0) break;
    const double t = eval_d(q, x) / gg;
    for (size_t i = 0; i < 3; ++i)
      x[i] -= t * g[i];
  }
  return x;
}

// Ball of radius 0 at a double point.
void point_ball(Ball (&p)[3], const std::array<double, 3>& x) {
  for (size_t l = 0; l < 3; ++l)
    arb_set_d(p[l].v, x[l]);
}

// A disconnected real quadric (two-sheeted hyperboloid, hyperbolic cylinder, parallel plane
// pair) is x^T A x + 2 b.x + c0 = 0, i.e. y^T A y = k in y = x - c (A c = -b where a centre
// exists). Its sheets are told apart by the sign of h(x) = w^T (A x + b) = (A w).(x - c) for a
// rational w with w^T A w of the sign of k: on the plane h = 0 (the A-orthogonal complement of
// w) the form A has the other sign or vanishes, so it holds no point of y^T A y = k. The sign of
// k is read off the inertias (Q is congruent to A + (-k)). Returns false when no such w is
// found among small integer vectors (never for these three kinds).
bool sheet_separator(const core::QuadricMatrix& q, std::array<Rational, 3>& l, Rational& h0,
                     int sign_override = 0) {
  core::Mat4 m3 = q.matrix();
  for (size_t i = 0; i < 4; ++i) {
    m3[i][3] = Rational(0);
    m3[3][i] = Rational(0);
  }
  const algebra::Inertia im = algebra::inertia_ldlt(m3), iq = algebra::inertia_ldlt(q.matrix());
  const int k_sign = sign_override != 0 ? sign_override : iq.p > im.p ? -1 : 1;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (int k = -2; k <= 2; ++k) {
        const std::array<Rational, 3> w{Rational(i), Rational(j), Rational(k)};
        Rational waw;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            waw += w[static_cast<size_t>(r)] * q(r, c) * w[static_cast<size_t>(c)];
        if (waw.sign() != k_sign) continue;
        h0 = Rational(0);
        for (int r = 0; r < 3; ++r) {
          l[static_cast<size_t>(r)] = Rational(0);
          for (int c = 0; c < 3; ++c)
            l[static_cast<size_t>(r)] += q(r, c) * w[static_cast<size_t>(c)];
          h0 += w[static_cast<size_t>(r)] * q(r, 3);
        }
        return true;
      }
  return false;
}

// Samples of a quadric: certified points on the gradient lines of a rational grid at several
// scales; stops once both sides of `other` are seen on one connected piece (the whole quadric,
// or one sheet of a disconnected one, told apart exactly by sheet_separator).
// A real cone (y^T A y = 0, A indefinite of rank 3, apex c) is connected, but not once its
// apex is removed: two nappes, told apart by the sign of w^T (A x + b) for a rational w with
// w^T A w of the sign of A's single eigenvalue of its kind (A is definite on the plane
// A-orthogonal to w, which meets the cone at the apex only).
bool real_cone(const core::QuadricMatrix& q, int& minority_sign) {
  core::Mat4 m3 = q.matrix();
  for (size_t i = 0; i < 4; ++i) {
    m3[i][3] = Rational(0);
    m3[3][i] = Rational(0);
  }
  const algebra::Inertia im = algebra::inertia_ldlt(m3), iq = algebra::inertia_ldlt(q.matrix());
  if (im.rank() != 3 || im.p == 0 || im.n == 0 || iq.rank() != 3) return false;
  minority_sign = im.p == 1 ? 1 : -1;
  return true;
}

// *one_piece (when given) tells whether both sides were seen on one piece of `a` that stays
// connected when finitely many points are removed (a sheet, or a cone's nappe): then the
// common points separate that piece, so they are infinitely many. Both sides on the two nappes
// of a cone only prove a common point (a path through the apex), maybe the apex alone.
bool quadric_side_points(const core::QuadricMatrix& a, const core::Surface& other,
                         std::array<double, 3> (&at)[2],
                         const std::vector<std::array<Rational, 3>>* probes = nullptr,
                         bool* one_piece = nullptr) {
  const bool connected = quadric_connected(a);
  std::array<Rational, 3> l;
  Rational h0;
  if (!connected && !sheet_separator(a, l, h0)) return false;
  int minority = 0;
  const bool cone = connected && real_cone(a, minority) && sheet_separator(a, l, h0, minority);
  bool nappe_sides[2][2] = {{false, false}, {false, false}};
  if (one_piece != nullptr) *one_piece = !cone;
  const SourceQuadric src(a);
  const long prec = 128;
  bool have[2][2] = {{false, false}, {false, false}}; // [sheet][side]
  std::array<double, 3> pts[2][2];
  // The grid points (or the given probes, a single pass) whose gradient-line projections are
  // tried.
  std::vector<std::vector<std::array<Rational, 3>>> passes;
  if (probes) {
    passes.push_back(*probes);
  } else {
    for (long scale : {1L, 4L, 16L, 64L, 256L, 1024L}) {
      std::vector<std::array<Rational, 3>> pass;
      for (int i = -2; i <= 2; ++i)
        for (int j = -2; j <= 2; ++j)
          for (int k = -2; k <= 2; ++k) // odd offsets keep the grid off symmetry planes
            pass.push_back({Rational(scale * (2 * i) + 1, 7), Rational(scale * (2 * j) - 1, 5),
                            Rational(scale * (2 * k) + 1, 3)});
      passes.push_back(std::move(pass));
    }
  }
  for (const auto& pass : passes) {
    for (const auto& cp : pass) {
      const Rational c[3] = {cp[0], cp[1], cp[2]};
      Ball p[3];
      if (!src.project(c, p, prec)) continue;
      size_t sheet = 0;
      if (!connected) {
        Ball h, t;
        arb_set_fmpq(h.v, h0.raw(), prec);
        for (size_t r = 0; r < 3; ++r) {
          arb_set_fmpq(t.v, l[r].raw(), prec);
          arb_addmul(h.v, t.v, p[r].v, prec);
        }
        if (!arb_is_positive(h.v) && !arb_is_negative(h.v)) continue;
        sheet = arb_is_positive(h.v) ? 1 : 0;
      }
      const int sd = side_of(other, p);
      if (sd == 0) continue;
      const size_t w = sd > 0 ? 1 : 0;
      if (cone) {
        Ball h, t;
        arb_set_fmpq(h.v, h0.raw(), prec);
        for (size_t r = 0; r < 3; ++r) {
          arb_set_fmpq(t.v, l[r].raw(), prec);
          arb_addmul(h.v, t.v, p[r].v, prec);
        }
        if (arb_is_positive(h.v) || arb_is_negative(h.v)) {
          const size_t nappe = arb_is_positive(h.v) ? 1 : 0;
          nappe_sides[nappe][w] = true;
          if (one_piece != nullptr && nappe_sides[nappe][0] && nappe_sides[nappe][1])
            *one_piece = true;
        }
      }
      if (have[sheet][w]) continue;
      have[sheet][w] = true;
      for (size_t r = 0; r < 3; ++r)
        pts[sheet][w][r] = arf_get_d(arb_midref(p[r].v), ARF_RND_NEAR);
    }
    for (size_t sh = 0; sh < 2; ++sh)
      if (have[sh][0] && have[sh][1]) {
        at[0] = pts[sh][0];
        at[1] = pts[sh][1];
        return true;
      }
  }
  return false;
}

// A ring torus point at angles (theta, phi) = pi (s, t), as balls.
void torus_point(Ball (&p)[3], const core::Torus& t, const Rational& s, const Rational& u,
                 long prec) {
  const auto& a = t.axis;
  Ball U[3], V[3], na, ss, cs, sp, cp, rad, R, r, tmp;
  unit_plane_frame(U, V, a, prec);
  for (size_t i = 0; i < 3; ++i) {
    Ball x;
    arb_set_fmpq(x.v, a[i].raw(), prec);
    arb_addmul(na.v, x.v, x.v, prec);
  }
  arb_rsqrt(na.v, na.v, prec);
  arb_sin_cos_pi_fmpq(ss.v, cs.v, s.raw(), prec);
  arb_sin_cos_pi_fmpq(sp.v, cp.v, u.raw(), prec);
  arb_set_fmpq(R.v, t.R.raw(), prec);
  arb_set_fmpq(r.v, t.r.raw(), prec);
  arb_mul(rad.v, r.v, cp.v, prec);
  arb_add(rad.v, rad.v, R.v, prec); // R + r cos phi
  for (size_t i = 0; i < 3; ++i) {
    Ball ai;
    arb_set_fmpq(ai.v, a[i].raw(), prec);
    arb_mul(ai.v, ai.v, na.v, prec);
    arb_mul(tmp.v, cs.v, U[i].v, prec);
    arb_addmul(tmp.v, ss.v, V[i].v, prec);
    arb_mul(tmp.v, tmp.v, rad.v, prec);
    arb_set_fmpq(p[i].v, t.centre[i].raw(), prec);
    arb_add(p[i].v, p[i].v, tmp.v, prec);
    arb_mul(tmp.v, r.v, sp.v, prec);
    arb_addmul(p[i].v, tmp.v, ai.v, prec);
  }
}

// The approximate witness of a two-parameter surface: bisection on the parameter segment
// between par[0] (a point on the negative side of `other`) and par[1] (positive side), `point`
// giving the surface point at given parameters (false: stop there). Float guidance only: the
// contact itself is proven by the two certified sides.
template <class Point>
std::array<double, 3> bisect_params(const Rational (&par)[2][2], const core::Surface& other,
                                    const Point& point, int steps) {
  Rational lo[2] = {par[0][0], par[0][1]}, hi[2] = {par[1][0], par[1][1]};
  Ball p[3];
  for (int it = 0; it < steps; ++it) {
    const Rational m[2] = {(lo[0] + hi[0]) * Rational(1, 2), (lo[1] + hi[1]) * Rational(1, 2)};
    if (!point(m[0], m[1], p)) break;
    const int sd = side_of(other, p);
    if (sd == 0) {
      lo[0] = m[0];
      lo[1] = m[1];
      break;
    }
    (sd > 0 ? hi : lo)[0] = m[0];
    (sd > 0 ? hi : lo)[1] = m[1];
  }
  std::array<double, 3> w{};
  if (point(lo[0], lo[1], p))
    for (size_t l = 0; l < 3; ++l)
      w[l] = arf_get_d(arb_midref(p[l].v), ARF_RND_NEAR);
  return w;
}

// Samples of a torus on a grid of angles; the witness by bisection along the parameter segment
// (a path on the torus) between the two sides.
bool torus_side_points(const core::Torus& t, const core::Surface& other,
                       std::array<double, 3>& witness) {
  const long prec = 128;
  bool have[2] = {false, false};
  Rational par[2][2];
  for (int n : {16, 64}) {
    for (int i = 0; i < 2 * n; ++i)
      for (int j = 0; j < n; ++j) {
        const Rational s(2 * i + 1, static_cast<unsigned long>(2 * n)),
            u(4 * j + 1, static_cast<unsigned long>(2 * n));
        Ball p[3];
        torus_point(p, t, s, u, prec);
        const int sd = side_of(other, p);
        if (sd == 0) continue;
        const size_t w = sd > 0 ? 1 : 0;
        if (have[w]) continue;
        have[w] = true;
        par[w][0] = s;
        par[w][1] = u;
      }
    if (have[0] && have[1]) break;
  }
  if (!have[0] || !have[1]) return false;
  witness = bisect_params(
      par, other,
      [&](const Rational& a, const Rational& b, Ball(&p)[3]) {
        torus_point(p, t, a, b, prec);
        return true;
      },
      50);
  return true;
}

// The unit direction of the stereographic parameters (u, v): exact rationals.
std::array<Rational, 3> stereo(const Rational& u, const Rational& v) {
  const Rational n = Rational(1) + u * u + v * v;
  return {Rational(2) * u / n, Rational(2) * v / n, (Rational(1) - u * u - v * v) / n};
}

// Support points of a canal solid in a grid of directions: genuine points of its outer
// boundary (the boundary of the unbounded complement of a connected solid: connected), the
// witness by bisection between the two sides over the directions (approximate).
bool canal_side_points(const core::CanalSurface& c, const core::Surface& other,
                       std::array<double, 3>& witness) {
  bool have[2] = {false, false};
  Rational par[2][2];
  for (int i = -6; i <= 6; ++i)
    for (int j = -6; j <= 6; ++j) {
      const Rational u(i, 3), v(j, 3);
      Ball p[3];
      if (!canal_support_point(c, stereo(u, v), p)) continue;
      const int sd = side_of(other, p);
      if (sd == 0) continue;
      const size_t w = sd > 0 ? 1 : 0;
      if (have[w]) continue;
      have[w] = true;
      par[w][0] = u;
      par[w][1] = v;
    }
  if (!have[0] || !have[1]) return false;
  witness = bisect_params(
      par, other,
      [&](const Rational& a, const Rational& b, Ball(&p)[3]) {
        return canal_support_point(c, stereo(a, b), p);
      },
      40);
  return true;
}

bool one_side(const core::Surface& a, const core::Surface& b, std::array<double, 3>& witness,
              const std::vector<std::array<Rational, 3>>* probes = nullptr,
              bool* one_piece = nullptr) {
  if (one_piece != nullptr) *one_piece = true;
  if (const auto* t = std::get_if<core::Torus>(&a)) return torus_side_points(*t, b, witness);
  if (const auto* c = std::get_if<core::CanalSurface>(&a)) return canal_side_points(*c, b, witness);
  const auto* qa = std::get_if<core::QuadricMatrix>(&a);
  if (!qa) return false;
  std::array<double, 3> at[2]{};
  if (!quadric_side_points(*qa, b, at, probes, one_piece)) return false;
  // Approximate common point: bisection between the two points, projected on a.
  std::array<double, 3> lo = at[0], hi = at[1];
  for (int it = 0; it < 60; ++it) {
    std::array<double, 3> m{};
    for (size_t l = 0; l < 3; ++l)
      m[l] = 0.5 * (lo[l] + hi[l]);
    m = project_d(*qa, m);
    Ball mb[3];
    point_ball(mb, m);
    const int sd = side_of(b, mb);
    if (sd == 0) {
      lo = m;
      break;
    }
    (sd > 0 ? hi : lo) = m;
  }
  witness = lo;
  return true;
}

} // namespace

namespace {

// A float distance-like function that vanishes exactly on the surface (for polishing the
// approximate witness only; never used in a decision).
double level(const core::Surface& s, const std::array<double, 3>& x) {
  if (const auto* q = std::get_if<core::QuadricMatrix>(&s)) {
    std::array<double, 3> g{};
    for (int i = 0; i < 3; ++i) {
      double v = (*q)(i, 3).to_double_approx();
      for (int j = 0; j < 3; ++j)
        v += (*q)(i, j).to_double_approx() * x[static_cast<size_t>(j)];
      g[static_cast<size_t>(i)] = 2 * v;
    }
    const double n = std::hypot(g[0], g[1], g[2]);
    return eval_d(*q, x) / (n > 0 ? n : 1);
  }
  if (const auto* t = std::get_if<core::Torus>(&s)) {
    double w[3], h = 0, an = 0;
    for (size_t i = 0; i < 3; ++i) {
      w[i] = x[i] - t->centre[i].to_double_approx();
      h += w[i] * t->axis[i].to_double_approx();
      an += t->axis[i].to_double_approx() * t->axis[i].to_double_approx();
    }
    h /= std::sqrt(an);
    const double rho = std::sqrt(std::max(0.0, w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - h * h));
    return std::hypot(rho - t->R.to_double_approx(), h) - t->r.to_double_approx();
  }
  if (const auto* c = std::get_if<core::CanalSurface>(&s)) {
    auto ev = [](const std::vector<Rational>& p, double t) {
      double v = 0;
      for (size_t k = p.size(); k-- > 0;)
        v = v * t + p[k].to_double_approx();
      return v;
    };
    auto f = [&](double t) {
      return std::hypot(x[0] - ev(c->spine[0], t), x[1] - ev(c->spine[1], t),
                        x[2] - ev(c->spine[2], t)) -
             ev(c->radius, t);
    };
    const double t0 = c->t0.to_double_approx(), t1 = c->t1.to_double_approx();
    double bt = t0, best = f(t0);
    for (int k = 1; k <= 400; ++k) {
      const double t = t0 + (t1 - t0) * k / 400;
      if (f(t) < best) best = f(t), bt = t;
    }
    for (double h = (t1 - t0) / 400; h > 1e-15 * (1 + std::fabs(bt)); h *= 0.5)
      for (double dt : {-h, h})
        if (bt + dt >= t0 && bt + dt <= t1 && f(bt + dt) < best) best = f(bt + dt), bt += dt;
    return best;
  }
  if (const auto* im = std::get_if<core::ImplicitSurface>(&s)) {
    auto F = [&](const std::array<double, 3>& y) {
      double v = 0;
      for (const auto& [e, cf] : im->f.terms())
        v += cf.to_double_approx() * std::pow(y[0], e[0]) * std::pow(y[1], e[1]) *
             std::pow(y[2], e[2]);
      return v;
    };
    const double f0 = F(x), hh = 1e-7 * (1 + std::hypot(x[0], x[1], x[2]));
    double g2 = 0;
    for (size_t i = 0; i < 3; ++i) {
      std::array<double, 3> y = x;
      y[i] += hh;
      const double d = (F(y) - f0) / hh;
      g2 += d * d;
    }
    return f0 / (g2 > 0 ? std::sqrt(g2) : 1);
  }
  return 0;
}

// Gauss-Newton on (level_a, level_b) = 0 from the sampled point: the minimum-norm step of the
// 2 x 3 system (finite-difference Jacobian). Keeps the best point found.
// A quadric's value at x exactly (x read as the dyadic it is), rounded, over the double norm
// of its gradient there; nullopt for other surfaces.
std::optional<double> exact_level(const core::Surface& s, const std::array<double, 3>& x,
                                  std::array<double, 3>& unit_normal) {
  const auto* q = std::get_if<core::QuadricMatrix>(&s);
  // A step past the double range (surfaces 1.7e308 wide) has no exact value: no level.
  if (!q || !std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    return std::nullopt;
  const Rational X[4] = {Rational::exact_from_double(x[0]), Rational::exact_from_double(x[1]),
                         Rational::exact_from_double(x[2]), Rational(1)};
  Rational f;
  std::array<double, 3> g{};
  for (int i = 0; i < 4; ++i) {
    Rational row;
    for (int j = 0; j < 4; ++j)
      row += (*q)(i, j) * X[j];
    f += X[i] * row;
    if (i < 3) g[static_cast<size_t>(i)] = 2 * row.to_double_approx();
  }
  const double n = std::hypot(g[0], g[1], g[2]);
  if (!(n > 0) || !std::isfinite(n)) return std::nullopt;
  for (size_t i = 0; i < 3; ++i)
    unit_normal[i] = g[i] / n;
  return f.to_double_approx() / n;
}

// Gauss-Newton onto two quadrics with residuals from exact values (at most 8 steps, each kept
// only when the exact residual falls): the doubles' evaluation of f ~ x^2 against a constant
// ~1e12 stalls 1e-4 away at 1e6 out (a sphere cut 3e-11 deep there: its witness 5.7e-5 off it).
void polish_witness_exactly(const core::Surface& a, const core::Surface& b,
                            std::array<double, 3>& w) {
  std::array<double, 3> na{}, nb{};
  auto fa = exact_level(a, w, na), fb = exact_level(b, w, nb);
  if (!fa || !fb) return;
  double best = std::hypot(*fa, *fb);
  for (int it = 0; it < 8 && best > 0; ++it) {
    const double m00 = 1, m11 = 1, m01 = na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2];
    const double det = m00 * m11 - m01 * m01;
    if (!(det > 1e-12)) return; // tangent there: the float polish stands
    const double y0 = (m11 * *fa - m01 * *fb) / det, y1 = (m00 * *fb - m01 * *fa) / det;
    std::array<double, 3> z = w;
    for (size_t i = 0; i < 3; ++i)
      z[i] -= na[i] * y0 + nb[i] * y1;
    std::array<double, 3> za{}, zb{};
    const auto ga = exact_level(a, z, za), gb = exact_level(b, z, zb);
    if (!ga || !gb || !(std::hypot(*ga, *gb) < best)) return;
    best = std::hypot(*ga, *gb);
    w = z, fa = ga, fb = gb, na = za, nb = zb;
  }
}

double polish_witness(const core::Surface& a, const core::Surface& b, std::array<double, 3>& w) {
  auto res = [&](const std::array<double, 3>& x) { return std::hypot(level(a, x), level(b, x)); };
  double best = res(w);
  std::array<double, 3> x = w;
  for (int it = 0; it < 200 && best > 0; ++it) {
    const double h = 1e-7 * (1 + std::hypot(x[0], x[1], x[2]));
    const double r0[2] = {level(a, x), level(b, x)};
    double J[2][3];
    for (size_t i = 0; i < 3; ++i) {
      std::array<double, 3> y = x;
      y[i] += h;
      J[0][i] = (level(a, y) - r0[0]) / h;
      J[1][i] = (level(b, y) - r0[1]) / h;
    }
    // step = -J^T (J J^T)^-1 r
    const double m00 = J[0][0] * J[0][0] + J[0][1] * J[0][1] + J[0][2] * J[0][2],
                 m01 = J[0][0] * J[1][0] + J[0][1] * J[1][1] + J[0][2] * J[1][2],
                 m11 = J[1][0] * J[1][0] + J[1][1] * J[1][1] + J[1][2] * J[1][2];
    // Levenberg-Marquardt damping: the two normals may be parallel at the sampled point.
    bool improved = false;
    for (double lam = 1e-12 * (m00 + m11); lam < 1e6 * (m00 + m11 + 1); lam *= 10) {
      const double a00 = m00 + lam, a11 = m11 + lam, det = a00 * a11 - m01 * m01;
      if (!(std::fabs(det) > 0)) continue;
      const double y0 = (a11 * r0[0] - m01 * r0[1]) / det, y1 = (a00 * r0[1] - m01 * r0[0]) / det;
      std::array<double, 3> z = x;
      for (size_t i = 0; i < 3; ++i)
        z[i] -= J[0][i] * y0 + J[1][i] * y1;
      const double r = res(z);
      if (r < best) {
        best = r;
        x = z;
        w = z;
        improved = true;
        break;
      }
    }
    if (!improved) break;
  }
  polish_witness_exactly(a, b, w);
  return best;
}

} // namespace

bool surfaces_meet_by_sign_change(const core::Surface& a, const core::Surface& b,
                                  std::array<double, 3>& witness, double* residual,
                                  bool* continuum) {
  // A canal radius vanishing inside the interval pinches the solid to a point (r = t^2 along
  // the x axis: two lobes joined at the origin, which the plane x = 0 meets there alone, yet
  // its support points lie on both sides), and a negative radius makes C(t) + r(t) e no
  // support point: the sampling and side_of are sound only for r > 0 throughout.
  for (const core::Surface* s : {&a, &b})
    if (const auto* c = std::get_if<core::CanalSurface>(s); c && !canal_radius_positive(*c))
      return false;
  bool piece = false;
  if (!one_side(a, b, witness, nullptr, &piece) && !one_side(b, a, witness, nullptr, &piece))
    return false;
  if (continuum != nullptr) *continuum = piece;
  const double r = polish_witness(a, b, witness);
  if (residual) *residual = r;
  return true;
}

bool meet_by_sign_change(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                         std::array<double, 3>& witness,
                         const std::vector<std::array<double, 3>>& near) {
  if (surfaces_meet_by_sign_change(core::Surface(a), core::Surface(b), witness)) return true;
  if (near.empty()) return false;
  // Probes around the suspected common points, at several distances and in 14 directions: a
  // transversal crossing there has points of either surface on both sides of the other.
  std::vector<std::array<Rational, 3>> probes;
  const int dirs[14][3] = {{1, 0, 0},  {-1, 0, 0},  {0, 1, 0},   {0, -1, 0},  {0, 0, 1},
                           {0, 0, -1}, {1, 1, 1},   {1, 1, -1},  {1, -1, 1},  {1, -1, -1},
                           {-1, 1, 1}, {-1, 1, -1}, {-1, -1, 1}, {-1, -1, -1}};
  for (const auto& p0 : near) {
    const double size = 1 + std::fabs(p0[0]) + std::fabs(p0[1]) + std::fabs(p0[2]);
    for (int e = 2; e <= 20; e += 3)
      for (const auto& d : dirs) {
        std::array<Rational, 3> c;
        for (size_t i = 0; i < 3; ++i)
          c[i] = Rational::exact_from_double(p0[i] + std::ldexp(size, -e) * d[i]);
        probes.push_back(c);
      }
  }
  const core::Surface sa(a), sb(b);
  if (!one_side(sa, sb, witness, &probes) && !one_side(sb, sa, witness, &probes)) return false;
  polish_witness(sa, sb, witness);
  return true;
}

} // namespace surfcert::certify
