#include "surfcert/certify/distance/convex_quadric.hpp"

#include <cmath>
#include <limits>

namespace surfcert::certify {

using core::Rational;
using RMat3 = std::array<std::array<Rational, 3>, 3>;

namespace {

Rational det3(const RMat3& a) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

// Inverse by the adjugate (exact; det != 0 checked by the caller).
RMat3 inverse3(const RMat3& a, const Rational& det) {
  RMat3 r;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      const size_t i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      r[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
    }
  return r;
}

std::array<double, 3> to_double(const std::array<Rational, 3>& v) {
  return {v[0].to_double_approx(), v[1].to_double_approx(), v[2].to_double_approx()};
}

// The paraboloid's exact data from (A + a a^T)^-1 (see the header): P = A^+ =
// (A + a a^T)^-1 - a a^T / |a|^4.
ConvexQuadric paraboloid(const RMat3& Binv, const std::array<Rational, 3>& a,
                         const std::array<Rational, 3>& b, const Rational& e, const Rational& ab) {
  ConvexQuadric o;
  o.kind = ConvexQuadric::Kind::Paraboloid;
  o.axis = a;
  o.b = b;
  o.e = e;
  o.ab = ab;
  const Rational a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      o.W[i][j] = Binv[i][j] - a[i] * a[j] / (a2 * a2);
      o.Wd[i][j] = o.W[i][j].to_double_approx();
    }
  Rational bPb;
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j)
      o.Pb[i] += o.W[i][j] * b[j];
    bPb += b[i] * o.Pb[i];
  }
  o.alpha = ab / Rational(2);
  o.gamma = (bPb - e) / (Rational(2) * ab);
  o.bd = to_double(b);
  o.Pbd = to_double(o.Pb);
  o.ad = to_double(a);
  o.ed = e.to_double_approx();
  o.abd = ab.to_double_approx();
  o.alphad = o.alpha.to_double_approx();
  o.gammad = o.gamma.to_double_approx();
  return o;
}

// Exact dyadic arithmetic on Arb's arf numbers (ARF_PREC_EXACT: no rounding ever happens).
algebra::Arf dyadic(double x) {
  algebra::Arf r;
  arf_set_d(r.v, x);
  return r;
}
algebra::Arf operator*(const algebra::Arf& x, const algebra::Arf& y) {
  algebra::Arf r;
  arf_mul(r.v, x.v, y.v, ARF_PREC_EXACT, ARF_RND_DOWN);
  return r;
}
algebra::Arf operator+(const algebra::Arf& x, const algebra::Arf& y) {
  algebra::Arf r;
  arf_add(r.v, x.v, y.v, ARF_PREC_EXACT, ARF_RND_DOWN);
  return r;
}
algebra::Arf operator-(const algebra::Arf& x, const algebra::Arf& y) {
  algebra::Arf r;
  arf_sub(r.v, x.v, y.v, ARF_PREC_EXACT, ARF_RND_DOWN);
  return r;
}
Rational to_rational(const algebra::Arf& x) {
  Rational r;
  arf_get_fmpq(r.raw_mut(), x.v);
  return r;
}

// An ellipsoid posed in doubles (core::ShapeSpec): c is the centre and W = R D^2 R^T with
// R = Rq / |q|^2 the quaternion's rotation (Rq its undivided polynomial matrix) and D the
// radii: the same exact numbers the general route derives from the matrix (there W = k M^-1
// with k = 1), but without forming the matrix or inverting it. Every numerator is a dyadic
// number computed exactly in arf arithmetic; one rational division per entry.
// The exact dyadic numerators acc[i][j] of W[i][j] = acc[i][j] / n2 (upper triangle) and n2.
void posed_numerators(std::array<std::array<algebra::Arf, 3>, 3>& acc, algebra::Arf& n2,
                      const core::ShapeSpec& sp) {
  using algebra::Arf;
  std::array<Arf, 3> r2;
  for (size_t i = 0; i < 3; ++i) {
    const Arf r = dyadic(sp.radii[i]);
    r2[i] = r * r;
  }
  std::array<std::array<Arf, 3>, 3> rq;
  n2 = dyadic(1);
  if (sp.rotated) {
    const Arf w = dyadic(sp.quaternion[0]), x = dyadic(sp.quaternion[1]),
              y = dyadic(sp.quaternion[2]), z = dyadic(sp.quaternion[3]);
    const Arf ww = w * w, xx = x * x, yy = y * y, zz = z * z;
    const Arf xy = x * y, xz = x * z, yz = y * z, wx = w * x, wy = w * y, wz = w * z;
    const Arf two = dyadic(2), n = ww + xx + yy + zz;
    n2 = n * n;
    rq = {{{ww + xx - yy - zz, two * (xy - wz), two * (xz + wy)},
           {two * (xy + wz), ww - xx + yy - zz, two * (yz - wx)},
           {two * (xz - wy), two * (yz + wx), ww - xx - yy + zz}}};
  } else {
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        rq[i][j] = dyadic(i == j ? 1 : 0);
  }
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = i; j < 3; ++j) {
      acc[i][j] = dyadic(0);
      for (size_t k = 0; k < 3; ++k)
        acc[i][j] = acc[i][j] + rq[i][k] * rq[j][k] * r2[k];
    }
}

ConvexQuadric posed_ellipsoid(const core::ShapeSpec& sp) {
  ConvexQuadric out;
  std::array<std::array<algebra::Arf, 3>, 3> acc;
  algebra::Arf n2;
  posed_numerators(acc, n2, sp);
  const Rational den = to_rational(n2);
  for (size_t i = 0; i < 3; ++i) {
    out.c[i] = Rational::exact_from_double(sp.center[i]);
    out.cd[i] = sp.center[i];
    for (size_t j = i; j < 3; ++j) {
      out.W[i][j] = to_rational(acc[i][j]) / den;
      if (j != i) out.W[j][i] = out.W[i][j];
    }
  }
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      out.Wd[i][j] = out.W[i][j].to_double_approx();
  return out;
}

} // namespace

std::optional<ConvexQuadric::Kind> convex_kind(const core::QuadricMatrix& q) {
  if (const core::ShapeSpec* sp = q.shape()) {
    // By construction (radii > 0, a rotation): the solid's kind follows from the type alone.
    switch (sp->type) {
    case core::ShapeType::Sphere:
    case core::ShapeType::Ellipsoid:
      return ConvexQuadric::Kind::Ellipsoid;
    case core::ShapeType::Cylinder:
      return ConvexQuadric::Kind::Cylinder;
    case core::ShapeType::EllipticParaboloid:
      return ConvexQuadric::Kind::Paraboloid;
    default:
      return std::nullopt;
    }
  }
  const auto c = convex_quadric(q);
  return c ? std::optional<ConvexQuadric::Kind>(c->kind) : std::nullopt;
}

std::optional<ConvexQuadric> convex_quadric(const core::QuadricMatrix& q) {
  if (const core::ShapeSpec* sp = q.shape())
    if (sp->type == core::ShapeType::Sphere || sp->type == core::ShapeType::Ellipsoid)
      return posed_ellipsoid(*sp);
  RMat3 A;
  std::array<Rational, 3> b;
  Rational e = q(3, 3), trace;
  for (int i = 0; i < 3; ++i) {
    b[static_cast<size_t>(i)] = q(i, 3);
    for (int j = 0; j < 3; ++j)
      A[static_cast<size_t>(i)][static_cast<size_t>(j)] = q(i, j);
    trace += q(i, i);
  }
  if (trace.sign() == 0) return std::nullopt;
  if (trace.sign() < 0) { // orient so that the quadratic block is positive (semi)definite
    for (auto& row : A)
      for (auto& x : row)
        x = -x;
    for (auto& x : b)
      x = -x;
    e = -e;
  }
  // Characteristic polynomial l^3 - t l^2 + s l - det: all eigenvalues > 0 iff t, s, det > 0;
  // eigenvalues {0, +, +} iff det = 0 and t, s > 0.
  Rational s = A[0][0] * A[1][1] - A[0][1] * A[1][0] + A[0][0] * A[2][2] - A[0][2] * A[2][0] +
               A[1][1] * A[2][2] - A[1][2] * A[2][1];
  Rational d = det3(A);
  if (s.sign() <= 0 || d.sign() < 0) return std::nullopt;
  ConvexQuadric out;
  RMat3 Ainv;
  if (d.sign() > 0) {
    Ainv = inverse3(A, d);
  } else {
    // Axis: the kernel of A (rank 2 since s > 0), a cross product of two independent rows.
    std::array<Rational, 3> a;
    for (size_t r1 = 0; r1 < 3 && a[0].sign() == 0 && a[1].sign() == 0 && a[2].sign() == 0; ++r1)
      for (size_t r2 = r1 + 1; r2 < 3; ++r2) {
        const auto &u = A[r1], &v = A[r2];
        std::array<Rational, 3> x{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                  u[0] * v[1] - u[1] * v[0]};
        if (x[0].sign() != 0 || x[1].sign() != 0 || x[2].sign() != 0) {
          a = x;
          break;
        }
      }
    RMat3 B = A; // A + a a^T: positive definite, and (A + a a^T)^-1 n = A^+ n for n . a = 0
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        B[i][j] += a[i] * a[j];
    Ainv = inverse3(B, det3(B));
    out.axis = a;
    out.kind = ConvexQuadric::Kind::Cylinder;
    // b outside the range of A (not orthogonal to the kernel): an elliptic paraboloid.
    const Rational ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    if (ab.sign() != 0) {
      ConvexQuadric par = paraboloid(Ainv, a, b, e, ab);
      // cd: the vertex (support point along the opening direction), where searches start
      const double sg = ab.sign() > 0 ? 1 : -1;
      par.cd = support_point_float(par, {sg * par.ad[0], sg * par.ad[1], sg * par.ad[2]});
      return par;
    }
  }
  // Centre c = -A^+ b (a point of the axis for a cylinder): f = (x-c)^T A (x-c) + e + b.c.
  Rational bc;
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j)
      out.c[i] -= Ainv[i][j] * b[j];
    bc += b[i] * out.c[i];
  }
  const Rational k = -(e + bc);           // (x-c)^T (A/k) (x-c) = 1
  if (k.sign() <= 0) return std::nullopt; // a point, a line, or no real point
  for (size_t i = 0; i < 3; ++i) {
    out.cd[i] = out.c[i].to_double_approx();
    for (size_t j = 0; j < 3; ++j) {
      out.W[i][j] = k * Ainv[i][j];
      out.Wd[i][j] = out.W[i][j].to_double_approx();
    }
  }
  return out;
}

namespace {

// Paraboloid support point and value in double: s = (a.b)/(n.a), y = s P n - P b,
// t = -(s n.y + b.y + e) / (2 a.b), p = y + t a, h = n.p.
bool paraboloid_float(const ConvexQuadric& s, const std::array<double, 3>& n, double& h,
                      std::array<double, 3>& p) {
  double na = 0;
  for (size_t i = 0; i < 3; ++i)
    na += n[i] * s.ad[i];
  if (!(na / s.abd > 0)) return false;
  const double sc = s.abd / na;
  std::array<double, 3> y{};
  double ny = 0, by = 0;
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j)
      y[i] += sc * s.Wd[i][j] * n[j];
    y[i] -= s.Pbd[i];
    ny += n[i] * y[i];
    by += s.bd[i] * y[i];
  }
  const double t = -(sc * ny + by + s.ed) / (2 * s.abd);
  h = 0;
  for (size_t i = 0; i < 3; ++i) {
    p[i] = y[i] + t * s.ad[i];
    h += n[i] * p[i];
  }
  return true;
}

} // namespace

double support_float(const ConvexQuadric& s, const std::array<double, 3>& n) {
  if (s.is_paraboloid()) {
    double h;
    std::array<double, 3> p;
    return paraboloid_float(s, n, h, p) ? h : std::numeric_limits<double>::infinity();
  }
  double nc = 0, nwn = 0;
  for (size_t i = 0; i < 3; ++i) {
    nc += n[i] * s.cd[i];
    for (size_t j = 0; j < 3; ++j)
      nwn += n[i] * s.Wd[i][j] * n[j];
  }
  return nc + std::sqrt(std::max(nwn, 0.0));
}

std::array<double, 3> support_point_float(const ConvexQuadric& s, const std::array<double, 3>& n) {
  if (s.is_paraboloid()) {
    double h;
    std::array<double, 3> p;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return paraboloid_float(s, n, h, p) ? p : std::array<double, 3>{nan, nan, nan};
  }
  std::array<double, 3> wn{};
  double nwn = 0;
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j)
      wn[i] += s.Wd[i][j] * n[j];
    nwn += n[i] * wn[i];
  }
  const double r = std::sqrt(std::max(nwn, 1e-300));
  return {s.cd[0] + wn[0] / r, s.cd[1] + wn[1] / r, s.cd[2] + wn[2] / r};
}

namespace {

void set_q(arb_t x, const Rational& q, long prec) {
  arb_set_fmpq(x, q.raw(), prec);
}

// The paraboloid's h(n) and support point with balls (formulas of the header).
void paraboloid_ball(arb_t h, Ball (*p)[3], const ConvexQuadric& s, const Ball (&n)[3], long prec) {
  Ball na, t, sc, y[3], ny, by, tt, q, pt[3];
  for (size_t i = 0; i < 3; ++i) {
    set_q(t.v, (*s.axis)[i], prec);
    arb_addmul(na.v, n[i].v, t.v, prec);
  }
  // admissible only when (n.a) / (a.b) > 0 is certain
  if (!(s.ab.sign() > 0 ? arb_is_positive(na.v) : arb_is_negative(na.v))) {
    arb_indeterminate(h);
    return;
  }
  set_q(sc.v, s.ab, prec);
  arb_div(sc.v, sc.v, na.v, prec);
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j) {
      set_q(t.v, s.W[i][j], prec);
      arb_addmul(y[i].v, t.v, n[j].v, prec);
    }
    arb_mul(y[i].v, y[i].v, sc.v, prec);
    set_q(t.v, s.Pb[i], prec);
    arb_sub(y[i].v, y[i].v, t.v, prec);
    arb_addmul(ny.v, n[i].v, y[i].v, prec);
    set_q(t.v, s.b[i], prec);
    arb_addmul(by.v, t.v, y[i].v, prec);
  }
  arb_mul(tt.v, sc.v, ny.v, prec);
  arb_add(tt.v, tt.v, by.v, prec);
  set_q(t.v, s.e, prec);
  arb_add(tt.v, tt.v, t.v, prec);
  set_q(q.v, s.ab, prec);
  arb_mul_2exp_si(q.v, q.v, 1);
  arb_div(tt.v, tt.v, q.v, prec);
  arb_neg(tt.v, tt.v);
  arb_zero(h);
  for (size_t i = 0; i < 3; ++i) {
    set_q(t.v, (*s.axis)[i], prec);
    arb_mul(pt[i].v, tt.v, t.v, prec);
    arb_add(pt[i].v, pt[i].v, y[i].v, prec);
    arb_addmul(h, n[i].v, pt[i].v, prec);
  }
  if (p != nullptr)
    for (size_t i = 0; i < 3; ++i)
      arb_swap((*p)[i].v, pt[i].v);
}

} // namespace

void support_ball(arb_t h, Ball (*p)[3], const ConvexQuadric& s, const Ball (&n)[3], long prec) {
  if (s.is_paraboloid()) {
    paraboloid_ball(h, p, s, n, prec);
    return;
  }
  Ball wn[3], t, nwn, nc, r;
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j) {
      arb_mul_fmpz(t.v, n[j].v, fmpq_numref(s.W[i][j].raw()), prec);
      arb_div_fmpz(t.v, t.v, fmpq_denref(s.W[i][j].raw()), prec);
      arb_add(wn[i].v, wn[i].v, t.v, prec);
    }
    arb_addmul(nwn.v, n[i].v, wn[i].v, prec);
    arb_set_fmpq(t.v, s.c[i].raw(), prec);
    arb_addmul(nc.v, n[i].v, t.v, prec);
  }
  arb_sqrt(r.v, nwn.v, prec); // nan (not finite) when the ball reaches below 0
  arb_add(h, nc.v, r.v, prec);
  if (p == nullptr) return;
  for (size_t i = 0; i < 3; ++i) {
    arb_div((*p)[i].v, wn[i].v, r.v, prec);
    arb_set_fmpq(t.v, s.c[i].raw(), prec);
    arb_add((*p)[i].v, (*p)[i].v, t.v, prec);
  }
}

void posed_support_balls(Ball (&W)[3][3], std::array<std::array<double, 3>, 3>& Wd,
                         const core::ShapeSpec& sp, long prec) {
  std::array<std::array<algebra::Arf, 3>, 3> acc;
  algebra::Arf n2;
  posed_numerators(acc, n2, sp);
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = i; j < 3; ++j) {
      arb_set_arf(W[i][j].v, acc[i][j].v);
      arb_div_arf(W[i][j].v, W[i][j].v, n2.v, prec);
      if (j != i) arb_set(W[j][i].v, W[i][j].v);
    }
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      Wd[i][j] = arf_get_d(arb_midref(W[i][j].v), ARF_RND_NEAR);
}

} // namespace surfcert::certify
