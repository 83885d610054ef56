// box_face_points: where the curve crosses the faces of a box (float proposals), and the
// Newton step onto the curve within a face plane. Approximate, like all of surfcert::trace.
//
// On the face x_k = c both quadrics restrict to conics in the face's coordinates, rotated by
// a fixed angle so that neither conic has a vanishing leading coefficient in t for axis-aligned
// data; R(s) = Res_t of the two conics (degree <= 4) gives the s of the common points, its
// near-real roots (Aberth) are completed by the t that zeroes both conics and polished by
// Newton on f = g = 0 in the face plane.
#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/trace/curve.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

namespace surfcert::trace {

double Box::diagonal() const {
  // hypot: the squares of a box 1e200 wide (or 1e-200) leave the double range.
  return std::hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
}

namespace {

using Poly = std::vector<double>; // constant first
using M4 = std::array<std::array<double, 4>, 4>;

Poly mul(const Poly& a, const Poly& b) {
  if (a.empty() || b.empty()) return {};
  Poly r(a.size() + b.size() - 1, 0.0);
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j)
      r[i + j] += a[i] * b[j];
  return r;
}
Poly sub(const Poly& a, const Poly& b) {
  Poly r(std::max(a.size(), b.size()), 0.0);
  for (size_t i = 0; i < a.size(); ++i)
    r[i] += a[i];
  for (size_t i = 0; i < b.size(); ++i)
    r[i] -= b[i];
  return r;
}
double dot3(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

} // namespace

bool newton_on_face(const QuadricPair& q, size_t k, double c, Point3& x) {
  const size_t i = (k + 1) % 3, j = (k + 2) % 3;
  x[k] = c;
  for (int it = 0; it < 50; ++it) {
    const double fv = q.f(x), gv = q.g(x);
    if (!std::isfinite(fv) || !std::isfinite(gv)) return false;
    if (std::max(std::abs(fv), std::abs(gv)) <= 1e-15 * (1 + dot3(x, x))) return true;
    const Point3 gf = q.grad_f(x), gg = q.grad_g(x);
    const double det = gf[i] * gg[j] - gf[j] * gg[i];
    const double sc = std::sqrt(dot3(gf, gf) * dot3(gg, gg));
    if (!(std::abs(det) > 1e-14 * sc)) return false;
    const double di = (fv * gg[j] - gv * gf[j]) / det, dj = (gv * gf[i] - fv * gg[i]) / det;
    x[i] -= di;
    x[j] -= dj;
    if (std::hypot(di, dj) <= 1e-16 * (1 + std::sqrt(dot3(x, x)))) {
      const double res = std::max(std::abs(q.f(x)), std::abs(q.g(x)));
      return res <= 1e-13 * (1 + dot3(x, x));
    }
  }
  return false;
}

bool newton_on_face_in_plane(const QuadricPair& q, size_t k, double c,
                             const std::array<double, 4>& plane, Point3& x) {
  const size_t i = (k + 1) % 3, j = (k + 2) % 3;
  for (int which = 0; which < 2; ++which) {
    Point3 y = x;
    y[k] = c;
    bool done = false;
    for (int it = 0; it < 50 && !done; ++it) {
      const double pv = plane[0] * y[0] + plane[1] * y[1] + plane[2] * y[2] + plane[3];
      const double fv = which == 0 ? q.f(y) : q.g(y);
      if (!std::isfinite(pv) || !std::isfinite(fv)) break;
      const Point3 gf = which == 0 ? q.grad_f(y) : q.grad_g(y);
      const double det = plane[i] * gf[j] - plane[j] * gf[i];
      const double sc = std::hypot(plane[i], plane[j]) * std::sqrt(dot3(gf, gf));
      if (!(std::abs(det) > 1e-10 * sc)) break; // the plane or the surface along the face
      const double di = (pv * gf[j] - fv * plane[j]) / det, dj = (fv * plane[i] - pv * gf[i]) / det;
      y[i] -= di;
      y[j] -= dj;
      done = std::hypot(di, dj) <= 1e-16 * (1 + std::sqrt(dot3(y, y)));
    }
    if (done) {
      x = y;
      return true;
    }
  }
  return false;
}

std::vector<Point3> box_face_points(const QuadricPair& q, const Box& box) {
  std::vector<Point3> out;
  const double diag = box.diagonal();
  const double th = 0.5173, cs = std::cos(th), sn = std::sin(th);
  for (size_t k = 0; k < 3; ++k)
    for (double c : {box.min[k], box.max[k]}) {
      const size_t i = (k + 1) % 3, j = (k + 2) % 3;
      std::array<std::array<double, 4>, 3> e{};
      e[0][i] = cs;
      e[0][j] = sn;
      e[1][i] = -sn;
      e[1][j] = cs;
      e[2][k] = c;
      e[2][3] = 1;
      // The conics on the face: 3x3 forms in (s, t, 1), X = s E0 + t E1 + E2.
      auto ca = algebra::restrict_form(q.a, e), cb = algebra::restrict_form(q.b, e);
      // Each conic as A2 t^2 + A1(s) t + A0(s).
      auto parts = [](const std::array<std::array<double, 3>, 3>& m, Poly& p2, Poly& p1, Poly& p0) {
        p2 = {m[1][1]};
        p1 = {2 * m[1][2], 2 * m[0][1]};
        p0 = {m[2][2], 2 * m[0][2], m[0][0]};
      };
      Poly a2, a1, a0, b2, b1, b0;
      parts(ca, a2, a1, a0);
      parts(cb, b2, b1, b0);
      const Poly x = sub(mul(a2, b0), mul(a0, b2));
      Poly r = sub(mul(x, x), mul(sub(mul(a2, b1), mul(a1, b2)), sub(mul(a1, b0), mul(a0, b1))));
      double rmax = 0;
      for (double v : r)
        rmax = std::max(rmax, std::abs(v));
      if (!(rmax > 0)) continue; // a common component on the face (or nothing)
      while (r.size() > 1 && std::abs(r.back()) <= 1e-13 * rmax)
        r.pop_back();
      std::vector<std::complex<double>> roots;
      if (r.size() >= 2) roots = algebra::approx_complex_roots(r);
      for (const auto& z : roots) {
        if (std::abs(z.imag()) > 1e-4 * (1 + std::abs(z.real()))) continue;
        const double s = z.real();
        // t from the first conic (or the second when it is degenerate in t), the one that
        // zeroes the other best.
        std::vector<double> ts;
        for (int which = 0; which < 2; ++which) {
          const double p2 = which ? b2[0] : a2[0];
          const double p1 = which ? b1[0] + b1[1] * s : a1[0] + a1[1] * s;
          const double p0 =
              which ? b0[0] + s * (b0[1] + s * b0[2]) : a0[0] + s * (a0[1] + s * a0[2]);
          if (std::abs(p2) > 1e-12 * (std::abs(p1) + std::abs(p0))) {
            const double disc = std::max(0.0, p1 * p1 - 4 * p2 * p0);
            ts.push_back((-p1 + std::sqrt(disc)) / (2 * p2));
            ts.push_back((-p1 - std::sqrt(disc)) / (2 * p2));
          } else if (p1 != 0) {
            ts.push_back(-p0 / p1);
          }
        }
        for (double t : ts) {
          Point3 p{};
          for (size_t d = 0; d < 3; ++d)
            p[d] = s * e[0][d] + t * e[1][d] + e[2][d];
          if (!newton_on_face(q, k, c, p)) continue;
          if (!box.contains(p, 1e-9 * diag)) continue;
          bool dup = false;
          for (const auto& o : out) {
            const double dd =
                std::sqrt((o[0] - p[0]) * (o[0] - p[0]) + (o[1] - p[1]) * (o[1] - p[1]) +
                          (o[2] - p[2]) * (o[2] - p[2]));
            dup = dup || dd <= 1e-9 * diag;
          }
          if (!dup) out.push_back(p);
        }
      }
    }
  return out;
}

} // namespace surfcert::trace
