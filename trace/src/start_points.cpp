// extreme_points: start points on every compact branch of the QSIC, from exact algebra.
//
// Both quadrics are rotated exactly by a fixed rational rotation (integer quaternion
// (5,1,2,3); others if that one fails), so that the slicing direction x is generic. The plane
// x = c cuts them in the conics F_c, G_c (3x3 forms in (y, z, w), entries polynomial in c).
// At a point where x is critical on the curve the two slice conics are tangent, so c is a
// root of
//   R(c) = disc_lambda h,  h(lambda, c) = det(lambda F_c - G_c) = sum_k h_k(c) lambda^k
// (the discriminant of a binary cubic, exact in Q[c]; R == 0, e.g. for surfaces of revolution
// about the slicing axis, means the next rotation). The real roots of its square-free part are
// isolated exactly and refined to ~2^-62 relative (refine_root_newton: exact signs confirm a
// float Newton bracket; bisection alone was 8% of the intersect bench); at each root the degenerate
// member of the slice pencil is
//   N F_c - D G_c,  N = 9 h3 h0 - h2 h1,  D = 2 (h2^2 - 3 h3 h1)
// (the double root of the cubic as a rational function of its coefficients, so there is no
// ill-conditioned double-root solve), evaluated exactly at the refined rational c; where N and
// D are small (nearly tangent surfaces) c is refined further first. When N and D both vanish
// at the root (decided exactly, with gcd(R, N, D)) the member is the one of the triple root
// (or F_c). Its kernel (adjugate, exact; a double line gives its two points on F_c) is the
// tangency point. It is rotated back and corrected by Newton; points that Newton cannot
// handle because the curve is singular there are kept when they are on both surfaces.
// The numerical steps after the exact root isolation are not certified.
#include "surfcert/trace/curve.hpp"

#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/upoly.hpp"

#include <flint/fmpz_poly.h>

#include <algorithm>
#include <cmath>

namespace surfcert::trace {

namespace {

using algebra::UPolyQ;
using algebra::UPolyZ;
using core::Rational;

using PMat3 = std::array<std::array<UPolyQ, 3>, 3>;
using QMat3 = std::array<std::array<Rational, 3>, 3>;
using DMat3 = std::array<std::array<double, 3>, 3>;

double norm3(const Point3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// Rational rotation matrix of the integer quaternion (a, b, c, d).
std::array<std::array<Rational, 3>, 3> quaternion_rotation(long a, long b, long c, long d) {
  const long n = a * a + b * b + c * c + d * d;
  const long m[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
                        {2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)},
                        {2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d}};
  std::array<std::array<Rational, 3>, 3> r;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      r[i][j] = Rational(m[i][j], static_cast<unsigned long>(n));
  return r;
}

// The slice form of a quadric on x = c, in (y, z, w); entries polynomial in c.
PMat3 slice(const core::QuadricMatrix& q) {
  auto lin = [](const Rational& c0, const Rational& c1) { return UPolyQ::from_coeffs({c0, c1}); };
  PMat3 s;
  s[0][0] = UPolyQ(q(1, 1));
  s[0][1] = UPolyQ(q(1, 2));
  s[0][2] = lin(q(1, 3), q(0, 1));
  s[1][1] = UPolyQ(q(2, 2));
  s[1][2] = lin(q(2, 3), q(0, 2));
  s[2][2] = UPolyQ::from_coeffs({q(3, 3), q(0, 3) + q(0, 3), q(0, 0)});
  s[1][0] = s[0][1];
  s[2][0] = s[0][2];
  s[2][1] = s[1][2];
  return s;
}

template <class T> T det3(const std::array<std::array<T, 3>, 3>& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// h_k(c): det(lambda F - G) = sum_k h_k lambda^k, by interpolation at lambda = 0, 1, -1, 2.
std::array<UPolyQ, 4> slice_cubic(const PMat3& f, const PMat3& g) {
  auto at = [&](long l) {
    PMat3 m;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        m[i][j] = UPolyQ(l) * f[i][j] - g[i][j];
    return det3(m);
  };
  UPolyQ d0 = at(0), d1 = at(1), dm1 = at(-1), d2 = at(2);
  const UPolyQ half(Rational(1, 2)), sixth(Rational(1, 6));
  UPolyQ h0 = d0;
  UPolyQ h2 = half * (d1 + dm1) - h0;
  UPolyQ o1 = half * (d1 - dm1);        // h3 + h1
  UPolyQ o2 = d2 - UPolyQ(4) * h2 - h0; // 8 h3 + 2 h1
  UPolyQ h3 = sixth * (o2 - UPolyQ(2) * o1);
  UPolyQ h1 = o1 - h3;
  return {h0, h1, h2, h3};
}

UPolyQ cubic_discriminant(const std::array<UPolyQ, 4>& h) {
  const UPolyQ &h0 = h[0], &h1 = h[1], &h2 = h[2], &h3 = h[3];
  return h1 * h1 * h2 * h2 - UPolyQ(4) * h0 * h2 * h2 * h2 - UPolyQ(4) * h1 * h1 * h1 * h3 +
         UPolyQ(18) * h0 * h1 * h2 * h3 - UPolyQ(27) * h0 * h0 * h3 * h3;
}

UPolyZ squarefree(const UPolyZ& p) {
  UPolyZ d = p.derivative();
  UPolyZ g, q;
  fmpz_poly_gcd(g.raw_mut(), p.raw(), d.raw());
  fmpz_poly_div(q.raw_mut(), p.raw(), g.raw());
  return q.primitive_part();
}

QMat3 eval(const PMat3& m, const Rational& c) {
  QMat3 r;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      r[i][j] = m[i][j].evaluate(c);
  return r;
}

DMat3 to_double(const QMat3& m) {
  DMat3 r{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      r[i][j] = m[i][j].to_double_approx();
  return r;
}

double max_abs(const DMat3& m) {
  double s = 0;
  for (const auto& row : m)
    for (double v : row)
      s = std::max(s, std::abs(v));
  return s;
}

QMat3 adjugate(const QMat3& m) {
  QMat3 a;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      const size_t r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      a[i][j] = m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    }
  return a;
}

Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double bilinear(const DMat3& m, const Point3& u, const Point3& v) {
  double s = 0;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      s += u[i] * m[i][j] * v[j];
  return s;
}

// Candidate tangency points (projective (y, z, w)) of the slice pencil at one root.
// `degenerate`: N = 9 h3 h0 - h2 h1 and D = 2 (h2^2 - 3 h3 h1) both vanish at the exact root
// (decided exactly by the caller): a triple root, or a double root at lambda = infinity.
void tangency_points(const QMat3& fq, const QMat3& gq, const std::array<Rational, 4>& h,
                     bool degenerate, std::vector<Point3>& out) {
  const Rational num = Rational(9) * h[3] * h[0] - h[2] * h[1];
  const Rational den = Rational(2) * (h[2] * h[2] - Rational(3) * h[3] * h[1]);
  std::vector<std::pair<Rational, Rational>> members; // (mu, nu): mu F - nu G
  if (!degenerate) {
    members.emplace_back(num, den);
  } else {
    members.emplace_back(-h[2], Rational(3) * h[3]); // triple root -h2 / (3 h3)
    members.emplace_back(Rational(1), Rational(0));  // root at infinity: F itself
  }
  const DMat3 fd = to_double(fq), gd = to_double(gq);
  for (const auto& [mu, nu] : members) {
    QMat3 m;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        m[i][j] = mu * fq[i][j] - nu * gq[i][j];
    const DMat3 md = to_double(m);
    const double ms = max_abs(md);
    if (ms == 0) continue;
    const DMat3 ad = to_double(adjugate(m));
    const double as = max_abs(ad);
    if (as > 1e-8 * ms * ms) { // rank 2: the kernel is the largest column of the adjugate
      size_t best = 0;
      double bn = -1;
      for (size_t j = 0; j < 3; ++j) {
        double n = std::abs(ad[0][j]) + std::abs(ad[1][j]) + std::abs(ad[2][j]);
        if (n > bn) {
          bn = n;
          best = j;
        }
      }
      out.push_back({ad[0][best], ad[1][best], ad[2][best]});
    } else { // rank 1: a double line l; its points on the conic F (or G)
      size_t best = 0;
      double bn = -1;
      for (size_t i = 0; i < 3; ++i) {
        double n = norm3({md[i][0], md[i][1], md[i][2]});
        if (n > bn) {
          bn = n;
          best = i;
        }
      }
      Point3 l{md[best][0], md[best][1], md[best][2]};
      size_t k = 0;
      for (size_t i = 1; i < 3; ++i)
        if (std::abs(l[i]) < std::abs(l[k])) k = i;
      Point3 e{0, 0, 0};
      e[k] = 1;
      Point3 u = cross(l, e), v = cross(l, u);
      const DMat3& cq = (std::abs(bilinear(fd, u, u)) + std::abs(bilinear(fd, v, v)) +
                             std::abs(bilinear(fd, u, v)) >
                         1e-12 * max_abs(fd) * norm3(u) * norm3(v))
                            ? fd
                            : gd;
      const double A = bilinear(cq, v, v), B = bilinear(cq, u, v), C = bilinear(cq, u, u);
      auto push = [&](double t) {
        out.push_back({u[0] + t * v[0], u[1] + t * v[1], u[2] + t * v[2]});
      };
      if (A == 0) {
        out.push_back(v);
        if (B != 0) push(-C / (2 * B));
        continue;
      }
      double disc = B * B - A * C;
      if (disc < -1e-12 * (B * B + std::abs(A * C))) continue;
      disc = std::max(disc, 0.0);
      const double s = std::sqrt(disc);
      push((-B + s) / A);
      push((-B - s) / A);
    }
  }
}

} // namespace

std::vector<Point3> extreme_points(const core::QuadricMatrix& a, const core::QuadricMatrix& b) {
  const QuadricPair q(a, b);
  static const long quats[][4] = {{5, 1, 2, 3}, {3, -2, 5, 1}, {7, 3, -1, 4}, {2, 7, -3, 5}};
  for (const auto& qt : quats) {
    const auto rot = quaternion_rotation(qt[0], qt[1], qt[2], qt[3]);
    core::Mat4 p = core::identity4();
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        p[i][j] = rot[i][j];
    const core::QuadricMatrix ra = a.congruent(p), rb = b.congruent(p);
    const PMat3 fs = slice(ra), gs = slice(rb);
    const auto h = slice_cubic(fs, gs);
    const UPolyQ disc = cubic_discriminant(h);
    if (disc.is_zero()) continue; // e.g. a surface of revolution about the slicing axis
    std::vector<Point3> found;
    if (disc.degree() <= 0) return found; // no critical slice at all
    const UPolyZ sf = squarefree(disc.primitive_integer());
    const algebra::RootSeparation sep = algebra::isolate_real_roots(sf);
    // N(c), D(c) of the double-root formula; their common roots with R, exactly.
    const UPolyQ npoly = UPolyQ(9) * h[3] * h[0] - h[2] * h[1];
    const UPolyQ dpoly = UPolyQ(2) * (h[2] * h[2] - UPolyQ(3) * h[3] * h[1]);
    UPolyZ common = sf;
    for (const UPolyQ* np : {&npoly, &dpoly}) {
      if (np->is_zero()) continue;
      UPolyZ g;
      const UPolyZ pz = np->primitive_integer();
      fmpz_poly_gcd(g.raw_mut(), common.raw(), pz.raw());
      common = g;
    }
    double rd[3][3];
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        rd[i][j] = rot[i][j].to_double_approx();
    for (size_t k = 1; k < sep.separators.size(); ++k) {
      Rational lo = sep.separators[k - 1], hi = sep.separators[k];
      for (int round = 0; round < 4; ++round) {
        Rational mag = std::max(core::abs(lo), core::abs(hi));
        Rational width = mag.is_zero() ? core::pow2(-200) : mag * core::pow2(-62);
        if (hi - lo <= width) break;
        algebra::refine_root_newton(sf, lo, hi, width);
      }
      // The root is a root of gcd(R, N, D) iff that gcd changes sign on (lo, hi) (it divides
      // the square-free R, which has exactly this one root there).
      const bool degenerate =
          common.degree() >= 1 &&
          (lo == hi ? common.sign_at(lo) == 0 : common.sign_at(lo) != common.sign_at(hi));
      // Where N and D are small (close roots of the slice cubic: nearly tangent surfaces), c
      // is refined further so that N(c)/D(c) keeps its relative accuracy.
      Rational c = (lo + hi) * Rational(1, 2);
      for (int round = 0; round < 6 && !degenerate; ++round) {
        const double nv = std::abs(npoly.evaluate(c).to_double_approx());
        const double dv = std::abs(dpoly.evaluate(c).to_double_approx());
        double ns = 0, ds = 0;
        for (long i = 0; i <= std::max(npoly.degree(), 0L); ++i)
          ns = std::max(ns, std::abs(npoly.coeff(i).to_double_approx()));
        for (long i = 0; i <= std::max(dpoly.degree(), 0L); ++i)
          ds = std::max(ds, std::abs(dpoly.coeff(i).to_double_approx()));
        const double cs = std::max(1.0, std::abs(c.to_double_approx()));
        ns *= cs * cs * cs * cs;
        ds *= cs * cs * cs * cs;
        if (nv > 1e-4 * ns || dv > 1e-4 * ds || hi == lo) break;
        algebra::refine_root_newton(sf, lo, hi, (hi - lo) * core::pow2(-40));
        c = (lo + hi) * Rational(1, 2);
      }
      std::array<Rational, 4> hv;
      for (size_t i = 0; i < 4; ++i)
        hv[i] = h[i].evaluate(c);
      std::vector<Point3> kernels;
      tangency_points(eval(fs, c), eval(gs, c), hv, degenerate, kernels);
      const double cd = c.to_double_approx();
      for (const auto& kv : kernels) {
        const double n = norm3(kv);
        if (!(n > 0) || std::abs(kv[2]) <= 1e-13 * n) continue; // at infinity
        const double xr[3] = {cd, kv[0] / kv[2], kv[1] / kv[2]};
        Point3 x{};
        for (size_t i = 0; i < 3; ++i)
          x[i] = rd[i][0] * xr[0] + rd[i][1] * xr[1] + rd[i][2] * xr[2];
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) continue;
        Point3 y = x;
        const double scale = 1 + norm3(x);
        if (project_onto_curve(q, y)) {
          const Point3 d{y[0] - x[0], y[1] - x[1], y[2] - x[2]};
          if (norm3(d) > 1e-6 * scale) continue;
        } else {
          // Singular points (node, cusp, isolated point): Newton cannot run there, but the
          // exact construction already put them on the curve.
          const double n2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
          if (std::max(std::abs(q.f(x)), std::abs(q.g(x))) > 1e-12 * (1 + n2)) continue;
          y = x;
        }
        bool dup = false;
        for (const auto& o : found) {
          const Point3 d{o[0] - y[0], o[1] - y[1], o[2] - y[2]};
          if (norm3(d) <= 1e-12 * scale) dup = true;
        }
        if (!dup) found.push_back(y);
      }
    }
    return found;
  }
  return {};
}

} // namespace surfcert::trace
