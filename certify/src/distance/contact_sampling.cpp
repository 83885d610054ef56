#include "surfcert/certify/distance/contact_sampling.hpp"

#include "surfcert/algebra/inertia.hpp"
#include "surfcert/certify/distance/offset_minimum.hpp"

#include <cmath>

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

bool one_side(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
              std::array<double, 3>& witness) {
  if (!quadric_connected(a)) return false;
  const SourceQuadric src(a), other(b);
  const long prec = 128;
  bool have[2] = {false, false};
  std::array<double, 3> at[2]{};
  for (long scale : {1L, 4L, 16L, 64L, 256L, 1024L}) {
    for (int i = -2; i <= 2; ++i)
      for (int j = -2; j <= 2; ++j)
        for (int k = -2; k <= 2; ++k) {
          // Slightly irrational-looking offsets keep the grid off symmetry planes.
          const Rational c[3] = {Rational(scale * (2 * i) + 1, 7), Rational(scale * (2 * j) - 1, 5),
                                 Rational(scale * (2 * k) + 1, 3)};
          Ball p[3], v;
          if (!src.project(c, p, prec)) continue;
          algebra::evaluate(v.v, other.f, ball_point(p), prec);
          const int s = arb_is_positive(v.v) ? 1 : arb_is_negative(v.v) ? 0 : -1;
          if (s < 0 || have[s]) continue;
          have[s] = true;
          for (size_t l = 0; l < 3; ++l)
            at[s][l] = arf_get_d(arb_midref(p[l].v), ARF_RND_NEAR);
        }
    if (have[0] && have[1]) break;
  }
  if (!have[0] || !have[1]) return false;
  // Approximate common point: bisection between the two points, projected on a.
  std::array<double, 3> lo = at[0], hi = at[1];
  for (int it = 0; it < 60; ++it) {
    std::array<double, 3> m{};
    for (size_t l = 0; l < 3; ++l)
      m[l] = 0.5 * (lo[l] + hi[l]);
    m = project_d(a, m);
    (eval_d(b, m) > 0 ? hi : lo) = m;
  }
  witness = lo;
  return true;
}

} // namespace

bool meet_by_sign_change(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                         std::array<double, 3>& witness) {
  return one_side(a, b, witness) || one_side(b, a, witness);
}

} // namespace surfcert::certify
