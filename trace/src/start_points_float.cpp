// extreme_points_float: the float twin of extreme_points (start_points.cpp). Same idea: slice
// the rotated pair by planes x = c, the x-critical points of the curve are where the slice
// conics are tangent, i.e. at the real roots of R(c) = disc_lambda det(lambda F_c - G_c), and
// the tangency point is the kernel of the degenerate member N F_c - D G_c. Here everything is
// in double and the roots of R (degree <= 8) come from Aberth's iteration, so a root can be
// missed; the caller checks the traced branches against the certified topology and then
// falls back to the exact construction.
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/trace/curve.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <initializer_list>
#include <stdexcept>
#include <vector>

namespace surfcert::trace {

namespace {

// Coefficients, constant term first, in place: at most degree 8 (the discriminant of a cubic
// in lambda whose coefficients are quadratics in c). Fixed storage: as std::vector the
// arithmetic below allocated ~40 times per pair, ~5% of a traced ellipsoid pair.
struct Poly {
  std::array<double, 9> c{};
  size_t n = 0; ///< coefficients in use
  Poly() = default;
  Poly(std::initializer_list<double> l) : n(l.size()) { std::copy(l.begin(), l.end(), c.begin()); }
  size_t size() const { return n; }
  double operator[](size_t i) const { return c[i]; }
  double& operator[](size_t i) { return c[i]; }
};

Poly pmul(const Poly& a, const Poly& b) {
  Poly r;
  if (a.n == 0 || b.n == 0 || a.n + b.n - 1 > r.c.size())
    throw std::logic_error("extreme_points_float: product beyond degree 8");
  r.n = a.n + b.n - 1; // at most 9 below: 5 x 5 and 3 x 7 coefficients
  for (size_t i = 0; i < a.n; ++i)
    for (size_t j = 0; j < b.n; ++j)
      r.c[i + j] += a.c[i] * b.c[j];
  return r;
}

Poly padd(const Poly& a, const Poly& b, double sb = 1) {
  Poly r;
  r.n = std::max(a.n, b.n);
  for (size_t i = 0; i < a.n; ++i)
    r.c[i] += a.c[i];
  for (size_t i = 0; i < b.n; ++i)
    r.c[i] += sb * b.c[i];
  return r;
}

Poly pscale(const Poly& a, double s) {
  Poly r = a;
  for (size_t i = 0; i < r.n; ++i)
    r.c[i] *= s;
  return r;
}

double peval(const Poly& p, double x) {
  double v = 0;
  for (size_t i = p.n; i-- > 0;)
    v = v * x + p.c[i];
  return v;
}

using PMat = std::array<std::array<Poly, 3>, 3>;
using M4 = std::array<std::array<double, 4>, 4>;

// Slice of X^T M X on x = c, in (y, z, w); entries polynomial in c.
PMat slice(const M4& m) {
  PMat s;
  s[0][0] = {m[1][1]};
  s[0][1] = {m[1][2]};
  s[0][2] = {m[1][3], m[0][1]};
  s[1][1] = {m[2][2]};
  s[1][2] = {m[2][3], m[0][2]};
  s[2][2] = {m[3][3], 2 * m[0][3], m[0][0]};
  s[1][0] = s[0][1];
  s[2][0] = s[0][2];
  s[2][1] = s[1][2];
  return s;
}

Poly det3(const PMat& m) {
  Poly a = padd(pmul(m[1][1], m[2][2]), pmul(m[1][2], m[2][1]), -1);
  Poly b = padd(pmul(m[1][0], m[2][2]), pmul(m[1][2], m[2][0]), -1);
  Poly c = padd(pmul(m[1][0], m[2][1]), pmul(m[1][1], m[2][0]), -1);
  return padd(padd(pmul(m[0][0], a), pmul(m[0][1], b), -1), pmul(m[0][2], c));
}

} // namespace

std::vector<Point3> extreme_points_float(const QuadricPair& q) {
  // Rotation from the quaternion (5, 1, 2, 3), as in the exact construction: X = R X'.
  const double qa = 5, qb = 1, qc = 2, qd = 3, n = qa * qa + qb * qb + qc * qc + qd * qd;
  const double r[3][3] = {{(qa * qa + qb * qb - qc * qc - qd * qd) / n, 2 * (qb * qc - qa * qd) / n,
                           2 * (qb * qd + qa * qc) / n},
                          {2 * (qb * qc + qa * qd) / n, (qa * qa - qb * qb + qc * qc - qd * qd) / n,
                           2 * (qc * qd - qa * qb) / n},
                          {2 * (qb * qd - qa * qc) / n, 2 * (qc * qd + qa * qb) / n,
                           (qa * qa - qb * qb - qc * qc + qd * qd) / n}};
  auto rotate = [&](const M4& m) {
    M4 p{}, out{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        p[i][j] = r[i][j];
    p[3][3] = 1;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        for (size_t k = 0; k < 4; ++k)
          for (size_t l = 0; l < 4; ++l)
            out[i][j] += p[k][i] * m[k][l] * p[l][j];
    return out;
  };
  const PMat f = slice(rotate(q.a)), g = slice(rotate(q.b));
  // h_k(c) by interpolation of det(l F - G) at l = 0, 1, -1, 2.
  auto at = [&](double l) {
    PMat m;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        m[i][j] = padd(pscale(f[i][j], l), g[i][j], -1);
    return det3(m);
  };
  Poly d0 = at(0), d1 = at(1), dm1 = at(-1), d2 = at(2);
  Poly h0 = d0;
  Poly h2 = padd(pscale(padd(d1, dm1), 0.5), h0, -1);
  Poly o1 = pscale(padd(d1, dm1, -1), 0.5);
  Poly o2 = padd(padd(d2, pscale(h2, 4), -1), h0, -1);
  Poly h3 = pscale(padd(o2, pscale(o1, 2), -1), 1.0 / 6);
  Poly h1 = padd(o1, h3, -1);
  Poly disc = padd(padd(padd(padd(pmul(pmul(h1, h1), pmul(h2, h2)),
                                  pscale(pmul(h0, pmul(h2, pmul(h2, h2))), -4)),
                             pscale(pmul(pmul(h1, h1), pmul(h1, h3)), -4)),
                        pscale(pmul(pmul(h0, h1), pmul(h2, h3)), 18)),
                   pscale(pmul(pmul(h0, h0), pmul(h3, h3)), -27));
  double scale = 0;
  for (size_t i = 0; i < disc.n; ++i)
    scale = std::max(scale, std::fabs(disc.c[i]));
  while (disc.n > 1 && std::fabs(disc.c[disc.n - 1]) <= 1e-14 * scale)
    --disc.n;
  std::vector<Point3> out;
  if (disc.n < 2 || scale == 0) return out;
  for (auto z : algebra::approx_complex_roots(
           std::vector<double>(disc.c.begin(), disc.c.begin() + disc.n))) {
    if (std::fabs(z.imag()) > 1e-6 * (1 + std::abs(z))) continue;
    const double c = z.real();
    const double H0 = peval(h0, c), H1 = peval(h1, c), H2 = peval(h2, c), H3 = peval(h3, c);
    const double N = 9 * H3 * H0 - H2 * H1, D = 2 * (H2 * H2 - 3 * H3 * H1);
    double m[3][3];
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        m[i][j] = N * peval(f[i][j], c) - D * peval(g[i][j], c);
    // Kernel of the (rank-2) degenerate conic: the largest column of its adjugate.
    double adj[3][3];
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        size_t i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        adj[j][i] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
      }
    size_t best = 0;
    double bn = -1;
    for (size_t j = 0; j < 3; ++j) {
      double s = std::fabs(adj[0][j]) + std::fabs(adj[1][j]) + std::fabs(adj[2][j]);
      if (s > bn) bn = s, best = j;
    }
    double w = adj[2][best];
    if (!(bn > 0) || std::fabs(w) < 1e-12 * bn) continue;
    double xr[3] = {c, adj[0][best] / w, adj[1][best] / w};
    Point3 p{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        p[i] += r[i][j] * xr[j];
    if (!std::isfinite(p[0] + p[1] + p[2]) || !project_onto_curve(q, p)) continue;
    bool dup = false;
    for (const auto& o : out)
      dup = dup || std::fabs(o[0] - p[0]) + std::fabs(o[1] - p[1]) + std::fabs(o[2] - p[2]) <
                       1e-9 * (1 + std::fabs(p[0]));
    if (!dup) out.push_back(p);
  }
  return out;
}

} // namespace surfcert::trace
