#include "surfcert/certify/distance/revolution.hpp"

#include <flint/fmpq_mat.h>

#include <vector>

namespace surfcert::certify {

using core::Integer;
using core::Rational;

std::optional<Axis> revolution_axis(const core::QuadricMatrix& q) {
  auto M = [&](size_t i, size_t j) { return q(static_cast<int>(i), static_cast<int>(j)); };
  // A double eigenvalue mu: Q3 - mu I has rank 1, its nonzero columns are parallel to the
  // axis. mu is rational (a double root of a rational cubic). Find it from the cubic's
  // gcd with its derivative, exactly.
  Rational tr = M(0, 0) + M(1, 1) + M(2, 2);
  Rational s2 = M(0, 0) * M(1, 1) - M(0, 1) * M(0, 1) + M(0, 0) * M(2, 2) - M(0, 2) * M(0, 2) +
                M(1, 1) * M(2, 2) - M(1, 2) * M(1, 2);
  // Candidates for mu: the rank-1 condition is checked directly on each candidate.
  // For lambda^3 - tr lambda^2 + s2 lambda - det with a double root mu: 3 mu^2 - 2 tr mu + s2 = 0.
  // Solve that quadratic exactly when its discriminant is a rational square.
  Rational disc = tr * tr - Rational(3) * s2; // (2tr)^2 - 12 s2, divided by 4
  if (disc.sign() < 0) return std::nullopt;
  Integer nd = disc.num() * disc.den(), root, rem;
  fmpz_sqrtrem(root.raw_mut(), rem.raw_mut(), nd.raw());
  if (!rem.is_zero()) return std::nullopt;
  const Rational sq = Rational(root) / Rational(disc.den());
  for (const Rational& mu : {(tr + sq) / Rational(3), (tr - sq) / Rational(3)}) {
    std::array<Rational, 3> a{};
    bool found = false;
    for (size_t j = 0; j < 3 && !found; ++j) {
      for (size_t i = 0; i < 3; ++i)
        a[i] = M(i, j) - (i == j ? mu : Rational(0));
      found = !(a[0].is_zero() && a[1].is_zero() && a[2].is_zero());
    }
    if (!found) continue; // Q3 = mu I: a sphere (or no quadratic part)
    // Rank one: every column parallel to a.
    bool rank1 = true;
    for (size_t j = 0; j < 3 && rank1; ++j) {
      std::array<Rational, 3> c;
      for (size_t i = 0; i < 3; ++i)
        c[i] = M(i, j) - (i == j ? mu : Rational(0));
      rank1 = (c[1] * a[2] - c[2] * a[1]).is_zero() && (c[2] * a[0] - c[0] * a[2]).is_zero() &&
              (c[0] * a[1] - c[1] * a[0]).is_zero();
    }
    if (!rank1) continue;
    // A point of the axis: (Q3 c + b) x a = 0 and c . a = 0 (3 linear equations, rank 3).
    fmpq_mat_t A, B, X;
    fmpq_mat_init(A, 4, 3);
    fmpq_mat_init(B, 4, 1);
    fmpq_mat_init(X, 3, 1);
    // rows: the three components of (Q3 c + b) x a, and c . a.
    for (size_t r = 0; r < 3; ++r) {
      size_t i1 = (r + 1) % 3, i2 = (r + 2) % 3; // (v x a)_r = v_i1 a_i2 - v_i2 a_i1
      for (size_t k = 0; k < 3; ++k) {
        Rational coef = M(i1, k) * a[i2] - M(i2, k) * a[i1];
        fmpq_set(fmpq_mat_entry(A, static_cast<slong>(r), static_cast<slong>(k)), coef.raw());
      }
      Rational rhs = -(M(i1, 3) * a[i2] - M(i2, 3) * a[i1]);
      fmpq_set(fmpq_mat_entry(B, static_cast<slong>(r), 0), rhs.raw());
    }
    for (size_t k = 0; k < 3; ++k)
      fmpq_set(fmpq_mat_entry(A, 3, static_cast<slong>(k)), a[k].raw());
    // Least-squares-free: pick 3 independent rows by trying the row triples.
    std::optional<Axis> ax;
    const int triples[4][3] = {{0, 1, 3}, {0, 2, 3}, {1, 2, 3}, {0, 1, 2}};
    for (const auto& tri : triples) {
      fmpq_mat_t A3, B3;
      fmpq_mat_init(A3, 3, 3);
      fmpq_mat_init(B3, 3, 1);
      for (slong r = 0; r < 3; ++r) {
        for (slong k = 0; k < 3; ++k)
          fmpq_set(fmpq_mat_entry(A3, r, k), fmpq_mat_entry(A, tri[r], k));
        fmpq_set(fmpq_mat_entry(B3, r, 0), fmpq_mat_entry(B, tri[r], 0));
      }
      if (fmpq_mat_solve_fraction_free(X, A3, B3)) {
        // Check all four equations.
        bool okall = true;
        for (slong r = 0; r < 4 && okall; ++r) {
          Rational v;
          for (slong k = 0; k < 3; ++k) {
            Rational e, x;
            fmpq_set(e.raw_mut(), fmpq_mat_entry(A, r, k));
            fmpq_set(x.raw_mut(), fmpq_mat_entry(X, k, 0));
            v += e * x;
          }
          Rational rhs;
          fmpq_set(rhs.raw_mut(), fmpq_mat_entry(B, r, 0));
          okall = v == rhs;
        }
        if (okall) {
          Axis out;
          out.direction = a;
          for (slong k = 0; k < 3; ++k)
            fmpq_set(out.point[static_cast<size_t>(k)].raw_mut(), fmpq_mat_entry(X, k, 0));
          ax = out;
        }
      }
      fmpq_mat_clear(A3);
      fmpq_mat_clear(B3);
      if (ax) break;
    }
    fmpq_mat_clear(A);
    fmpq_mat_clear(B);
    fmpq_mat_clear(X);
    if (ax) return ax;
  }
  return std::nullopt;
}

std::optional<core::QuadricMatrix> meridian_conic(const core::QuadricMatrix& q, const Axis& ax,
                                                  int height_var) {
  const auto& a = ax.direction;
  Rational aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  Integer an2 = aa.num() * aa.den(); // aa a square iff num*den is (both coprime)
  Integer root;
  fmpz_sqrtrem(root.raw_mut(), Integer().raw_mut(), an2.raw());
  // |a|, when rational: needed only for a linear term in the height (beta != 0 below).
  const std::optional<Rational> alen =
      root * root == an2 ? std::optional<Rational>(Rational(root) / Rational(aa.den()))
                         : std::nullopt;
  auto M = [&](size_t i, size_t j) { return q(static_cast<int>(i), static_cast<int>(j)); };
  std::array<Rational, 3> Ma, v; // M a, and M c + b
  for (size_t i = 0; i < 3; ++i) {
    v[i] = M(i, 3);
    for (size_t j = 0; j < 3; ++j) {
      Ma[i] += M(i, j) * a[j];
      v[i] += M(i, j) * ax.point[j];
    }
  }
  Rational aMa = a[0] * Ma[0] + a[1] * Ma[1] + a[2] * Ma[2];
  const Rational lambda = aMa / aa;
  for (size_t i = 0; i < 3; ++i)
    if (!(Ma[i] == lambda * a[i])) return std::nullopt; // a is an eigenvector
  // Two vectors spanning a-perp (cross products with the coordinate axes), same eigenvalue.
  std::vector<std::array<Rational, 3>> perp;
  for (size_t k = 0; k < 3 && perp.size() < 2; ++k) {
    std::array<Rational, 3> e{}, u{};
    e[k] = Rational(1);
    u = {a[1] * e[2] - a[2] * e[1], a[2] * e[0] - a[0] * e[2], a[0] * e[1] - a[1] * e[0]};
    if (u[0].is_zero() && u[1].is_zero() && u[2].is_zero()) continue;
    if (perp.size() == 1) { // independent of the first?
      const auto& w = perp[0];
      std::array<Rational, 3> x{w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2],
                                w[0] * u[1] - w[1] * u[0]};
      if (x[0].is_zero() && x[1].is_zero() && x[2].is_zero()) continue;
    }
    perp.push_back(u);
  }
  std::optional<Rational> mu;
  for (const auto& u : perp) {
    std::array<Rational, 3> Mu{};
    Rational uu;
    for (size_t i = 0; i < 3; ++i) {
      uu += u[i] * u[i];
      for (size_t j = 0; j < 3; ++j)
        Mu[i] += M(i, j) * u[j];
    }
    Rational m = (u[0] * Mu[0] + u[1] * Mu[1] + u[2] * Mu[2]) / uu;
    for (size_t i = 0; i < 3; ++i)
      if (!(Mu[i] == m * u[i])) return std::nullopt;
    if (mu && !(*mu == m)) return std::nullopt;
    mu = m;
  }
  // M c + b = beta a.
  std::optional<Rational> beta;
  for (size_t i = 0; i < 3; ++i) {
    if (a[i].is_zero()) {
      if (!v[i].is_zero()) return std::nullopt;
      continue;
    }
    Rational bb = v[i] / a[i];
    if (beta && !(*beta == bb)) return std::nullopt;
    beta = bb;
  }
  Rational fc = M(3, 3);
  for (size_t i = 0; i < 3; ++i) {
    fc += Rational(2) * M(i, 3) * ax.point[i];
    for (size_t j = 0; j < 3; ++j)
      fc += ax.point[i] * M(i, j) * ax.point[j];
  }
  core::Mat4 g;
  const size_t h = static_cast<size_t>(height_var);
  g[0][0] = *mu;
  g[h][h] = lambda;
  if (!beta->is_zero() && !alen) return std::nullopt;
  if (!beta->is_zero()) g[h][3] = g[3][h] = *beta * *alen;
  g[3][3] = fc;
  if (mu->is_zero() && lambda.is_zero()) return std::nullopt; // a plane: the closed form applies
  return core::QuadricMatrix(g);
}

} // namespace surfcert::certify
