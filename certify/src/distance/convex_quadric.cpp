#include "surfcert/certify/distance/convex_quadric.hpp"

#include <cmath>

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

} // namespace

std::optional<ConvexQuadric> convex_quadric(const core::QuadricMatrix& q) {
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
    // b must lie in the range of A (orthogonal to the kernel), else it is a paraboloid.
    if ((a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).sign() != 0) return std::nullopt;
    RMat3 B = A; // A + a a^T: positive definite, and (A + a a^T)^-1 n = A^+ n for n . a = 0
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        B[i][j] += a[i] * a[j];
    Ainv = inverse3(B, det3(B));
    out.axis = a;
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

double support_float(const ConvexQuadric& s, const std::array<double, 3>& n) {
  double nc = 0, nwn = 0;
  for (size_t i = 0; i < 3; ++i) {
    nc += n[i] * s.cd[i];
    for (size_t j = 0; j < 3; ++j)
      nwn += n[i] * s.Wd[i][j] * n[j];
  }
  return nc + std::sqrt(std::max(nwn, 0.0));
}

std::array<double, 3> support_point_float(const ConvexQuadric& s, const std::array<double, 3>& n) {
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

void support_ball(arb_t h, Ball (*p)[3], const ConvexQuadric& s, const Ball (&n)[3], long prec) {
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

} // namespace surfcert::certify
