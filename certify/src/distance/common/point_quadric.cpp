// Point-quadric critical distances: the offset sextic in alpha (see point_quadric.hpp).
//
// Roots of P with D != 0: one foot point p = N(alpha)/D(alpha), distance enclosed with Arb from
// the exact isolating interval. Roots with D == 0 (alpha0 = -1/lambda for an eigenvalue lambda
// of Q3): decided exactly when alpha0 is rational (always the case for a repeated eigenvalue):
// with K = ker(I + alpha0 Q3) (the lambda-eigenspace) and p0 any solution of
// (I + alpha0 Q3) p0 = x - alpha0 b, every p = p0 + w (w in K) satisfies
//   Q(p) = Q(p0) - (|x - p|^2 - |x - p0|^2) / alpha0,
// so the foot points are the points of p0 + K at the rational squared distance
// d2 = |x - p0|^2 + alpha0 Q(p0); they exist iff d2 >= h2 = dist(x, p0 + K)^2, and form a
// circle (continuum) when dim K >= 2 and d2 > h2. An irrational alpha0 with D == 0 is left
// undecided (ok = false, with a note).
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/core/rational_vec3.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/upoly.hpp"

#include <flint/fmpz_poly.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace surfcert::certify {

using algebra::UPolyQ;
using algebra::UPolyZ;
using core::add;
using core::dot;
using core::Rational;
using core::scale;
using core::sub;

namespace {

using Vec3 = std::array<Rational, 3>;

void set_enclosure(CriticalDistance& out, const arb_t d, long digits, long prec) {
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  arb_get_lbound_arf(lo, d, prec);
  arb_get_ubound_arf(hi, d, prec);
  if (arf_sgn(lo) < 0) arf_zero(lo); // a distance is never negative
  out.lower = decimal_bound(lo, false, digits + 5);
  out.upper = decimal_bound(hi, true, digits + 5);
  out.approx = arf_get_d(arb_midref(d), ARF_RND_NEAR);
  arf_clear(lo);
  arf_clear(hi);
}

// Relative radius <= 10^-digits (or the ball is exactly zero): rad <= lower bound / 10^digits.
bool accurate_enough(const arb_t d, long digits) {
  if (arb_is_zero(d)) return true;
  if (!arb_is_finite(d)) return false;
  arf_t lo, radf;
  arf_init(lo);
  arf_init(radf);
  arb_get_lbound_arf(lo, d, 64);
  arf_set_mag(radf, arb_radref(d));
  bool ok = false;
  if (arf_sgn(lo) > 0) {
    Ball bound, lowb, r;
    arb_set_ui(bound.v, 10);
    arb_pow_ui(bound.v, bound.v, static_cast<ulong>(digits), 64);
    arb_set_arf(lowb.v, lo);
    arb_div(lowb.v, lowb.v, bound.v, 64);
    arb_set_arf(r.v, radf);
    ok = arb_le(r.v, lowb.v) != 0;
  }
  arf_clear(lo);
  arf_clear(radf);
  return ok;
}

// Reduced row echelon form of a rows x cols rational matrix; returns the pivot columns.
std::vector<int> rref(std::vector<std::vector<Rational>>& a) {
  std::vector<int> piv;
  size_t rows = a.size(), cols = a.empty() ? 0 : a[0].size();
  size_t r = 0;
  for (size_t c = 0; c < cols && r < rows; ++c) {
    size_t p = r;
    while (p < rows && a[p][c].is_zero())
      ++p;
    if (p == rows) continue;
    std::swap(a[p], a[r]);
    Rational inv = Rational(1) / a[r][c];
    for (size_t j = 0; j < cols; ++j)
      a[r][j] *= inv;
    for (size_t i = 0; i < rows; ++i) {
      if (i == r || a[i][c].is_zero()) continue;
      Rational f = a[i][c];
      for (size_t j = 0; j < cols; ++j)
        a[i][j] -= f * a[r][j];
    }
    piv.push_back(static_cast<int>(c));
    ++r;
  }
  return piv;
}

// Kernel basis of an n x n matrix from its RREF (pivots among the first n columns).
std::vector<std::vector<Rational>> kernel_from_rref(const std::vector<std::vector<Rational>>& a,
                                                    const std::vector<int>& piv, int n) {
  std::vector<std::vector<Rational>> ker;
  for (int f = 0; f < n; ++f) {
    if (std::find(piv.begin(), piv.end(), f) != piv.end()) continue;
    std::vector<Rational> v(static_cast<size_t>(n), Rational(0));
    v[static_cast<size_t>(f)] = Rational(1);
    for (size_t i = 0; i < piv.size(); ++i)
      v[static_cast<size_t>(piv[i])] = -a[i][static_cast<size_t>(f)];
    ker.push_back(v);
  }
  return ker;
}

// Horner evaluation of a UPolyQ at a ball.
void eval_ball(arb_t out, const UPolyQ& p, const arb_t x, long prec) {
  arb_zero(out);
  Ball c;
  for (long i = p.degree(); i >= 0; --i) {
    arb_mul(out, out, x, prec);
    Rational ci = p.coeff(i);
    arb_set_fmpq(c.v, ci.raw(), prec);
    arb_add(out, out, c.v, prec);
  }
}

std::array<double, 3> to_doubles(const Vec3& v) {
  return {v[0].to_double_approx(), v[1].to_double_approx(), v[2].to_double_approx()};
}

struct Data {
  Vec3 x;
  Rational Q3[3][3];
  Vec3 b;
  Rational c;
  Rational qval(const Vec3& p) const { // p^T Q3 p + 2 b.p + c
    Rational s = c + Rational(2) * dot(b, p);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        s += Q3[i][j] * p[static_cast<size_t>(i)] * p[static_cast<size_t>(j)];
    return s;
  }
};

// Distance sqrt(d2) of a rational squared distance, enclosed.
void enclose_sqrt(CriticalDistance& cd, const Rational& d2, long digits) {
  long prec = 64 + 4 * digits;
  for (int it = 0; it < 6; ++it, prec *= 2) {
    Ball d;
    arb_set_fmpq(d.v, d2.raw(), prec);
    arb_sqrt(d.v, d.v, prec);
    if (accurate_enough(d.v, digits) || it == 5) {
      set_enclosure(cd, d.v, digits, prec);
      return;
    }
  }
}

// Rational alpha0 with D(alpha0) == 0 and P(alpha0) == 0: the exact analysis described above.
// Appends the foot points found (none when the root is spurious).
void rational_singular_root(const Data& dt, const Rational& a0, long digits,
                            std::vector<CriticalDistance>& out) {
  std::vector<std::vector<Rational>> m(3, std::vector<Rational>(4));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      m[static_cast<size_t>(i)][static_cast<size_t>(j)] =
          (i == j ? Rational(1) : Rational(0)) + a0 * dt.Q3[i][j];
    m[static_cast<size_t>(i)][3] = dt.x[static_cast<size_t>(i)] - a0 * dt.b[static_cast<size_t>(i)];
  }
  std::vector<int> piv = rref(m);
  if (std::find(piv.begin(), piv.end(), 3) != piv.end()) return; // inconsistent: no foot point
  Vec3 p0{Rational(0), Rational(0), Rational(0)};
  for (size_t i = 0; i < piv.size(); ++i)
    p0[static_cast<size_t>(piv[i])] = m[i][3];
  auto ker = kernel_from_rref(m, piv, 3);
  // orthogonal basis of K (Gram-Schmidt over Q)
  std::vector<Vec3> u;
  for (auto& k : ker) {
    Vec3 w{k[0], k[1], k[2]};
    for (auto& e : u)
      w = sub(w, scale(dot(w, e) / dot(e, e), e));
    u.push_back(w);
  }
  Vec3 r = sub(dt.x, p0);
  Rational d2 = dot(r, r) + a0 * dt.qval(p0);
  Vec3 pstar = p0;
  for (auto& e : u)
    pstar = add(pstar, scale(dot(r, e) / dot(e, e), e));
  Vec3 rs = sub(dt.x, pstar);
  Rational h2 = dot(rs, rs);
  if (d2 < h2) return; // the sphere |x - p| = d misses p0 + K: no real foot point
  std::array<double, 3> ps = to_doubles(pstar);
  if (d2 == h2) {
    CriticalDistance cd;
    cd.d2_exact = true;
    cd.d2 = d2;
    cd.foot = ps;
    enclose_sqrt(cd, d2, digits);
    out.push_back(cd);
    return;
  }
  // d2 > h2: dim K >= 1 here (dim 0 would force d2 == h2)
  const Vec3& e = u.front();
  double len = std::sqrt((d2 - h2).to_double_approx() / dot(e, e).to_double_approx());
  std::array<double, 3> ed = to_doubles(e);
  if (u.size() >= 2) {
    CriticalDistance cd;
    cd.continuum = true;
    cd.d2_exact = true; // every point of the circle is at the rational d2
    cd.d2 = d2;
    for (int i = 0; i < 3; ++i)
      cd.foot[static_cast<size_t>(i)] =
          ps[static_cast<size_t>(i)] + len * ed[static_cast<size_t>(i)];
    enclose_sqrt(cd, d2, digits);
    out.push_back(cd);
    return;
  }
  for (int s : {-1, 1}) {
    CriticalDistance cd;
    cd.d2_exact = true;
    cd.d2 = d2;
    for (int i = 0; i < 3; ++i)
      cd.foot[static_cast<size_t>(i)] =
          ps[static_cast<size_t>(i)] + s * len * ed[static_cast<size_t>(i)];
    enclose_sqrt(cd, d2, digits);
    out.push_back(cd);
  }
}

} // namespace

PointQuadricResult point_quadric_critical(const std::array<core::Rational, 3>& x,
                                          const core::QuadricMatrix& q, long digits) {
  PointQuadricResult res;
  if (digits < 1) digits = 1;
  Data dt;
  dt.x = x;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      dt.Q3[i][j] = q(i, j);
    dt.b[static_cast<size_t>(i)] = q(i, 3);
  }
  dt.c = q(3, 3);
  bool quadratic = false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      quadratic = quadratic || !dt.Q3[i][j].is_zero();
  if (!quadratic) {
    res.note = "the quadratic part is zero (a plane): not handled here";
    return res;
  }

  // M(alpha) = I + alpha Q3, adjugate, determinant, N = adj(M) (x - alpha b)
  UPolyQ M[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      M[i][j] = UPolyQ::linear(dt.Q3[i][j], i == j ? Rational(1) : Rational(0));
  UPolyQ adj[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // cofactor C_ji goes to adj[i][j]
      int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      adj[i][j] = M[r0][c0] * M[r1][c1] - M[r0][c1] * M[r1][c0];
    }
  UPolyQ D = M[0][0] * adj[0][0] + M[0][1] * adj[1][0] + M[0][2] * adj[2][0];
  UPolyQ v[3], N[3];
  for (int i = 0; i < 3; ++i)
    v[i] = UPolyQ::linear(-dt.b[static_cast<size_t>(i)], x[static_cast<size_t>(i)]);
  for (int i = 0; i < 3; ++i)
    N[i] = adj[i][0] * v[0] + adj[i][1] * v[1] + adj[i][2] * v[2];
  UPolyQ P = UPolyQ(dt.c) * D * D;
  for (int i = 0; i < 3; ++i) {
    P = P + UPolyQ(Rational(2) * dt.b[static_cast<size_t>(i)]) * D * N[i];
    for (int j = 0; j < 3; ++j)
      P = P + UPolyQ(dt.Q3[i][j]) * N[i] * N[j];
  }
  res.sextic_degree = static_cast<int>(P.degree());
  if (P.is_zero()) {
    res.note = "the point-quadric polynomial P(alpha) vanishes identically";
    return res;
  }

  // square-free part and its common part with D
  UPolyZ Pz = P.primitive_integer();
  UPolyZ sqf;
  {
    UPolyZ g;
    UPolyZ dP = Pz.derivative();
    fmpz_poly_gcd(g.raw_mut(), Pz.raw(), dP.raw());
    fmpz_poly_div(sqf.raw_mut(), Pz.raw(), g.raw());
    sqf = sqf.primitive_part();
  }
  UPolyZ Dz = D.primitive_integer();
  UPolyZ G;
  fmpz_poly_gcd(G.raw_mut(), sqf.raw(), Dz.raw());
  G = G.primitive_part();
  std::vector<UPolyZ> gfactors;
  if (G.degree() >= 1)
    for (algebra::IrreducibleFactor& f : algebra::irreducible_factors(G))
      gfactors.push_back(std::move(f.poly));

  algebra::RootSeparation sep = algebra::isolate_real_roots(sqf);
  bool all_ok = true;
  std::string notes;
  for (size_t k = 0; k + 1 < sep.separators.size() && sep.num_roots() > 0; ++k) {
    Rational lo = sep.separators[k], hi = sep.separators[k + 1];
    // does D vanish at this root? exactly, through the factors of gcd(sqf, D)
    bool dzero = false;
    bool rational_root = false;
    Rational a0;
    for (auto& f : gfactors) {
      int sl = f.sign_at(lo), sh = f.sign_at(hi);
      if (sl * sh < 0) {
        dzero = true;
        if (f.degree() == 1) {
          rational_root = true;
          a0 = -Rational(f.coeff(0), f.coeff(1));
        }
      }
    }
    if (dzero) {
      if (rational_root) {
        rational_singular_root(dt, a0, digits, res.criticals);
      } else {
        all_ok = false;
        notes += "a root alpha with D(alpha) = 0 is irrational: not handled; ";
      }
      continue;
    }
    // D != 0: foot point N/D; enclose the distance from the exact interval
    if (sqf.sign_at(Rational(0)) == 0 && lo < Rational(0) && Rational(0) < hi) {
      lo = Rational(0); // alpha = 0: x lies on Q (distance 0)
      hi = Rational(0);
    }
    long bits = static_cast<long>(3.33 * static_cast<double>(digits)) + 20;
    long prec = 64 + 4 * digits;
    bool done = false;
    for (int it = 0; it < 10 && !done; ++it) {
      Ball a, t, dd, d, lob, hib;
      arb_set_fmpq(lob.v, lo.raw(), prec);
      arb_set_fmpq(hib.v, hi.raw(), prec);
      arb_union(a.v, lob.v, hib.v, prec);
      eval_ball(dd.v, D, a.v, prec);
      arb_zero(d.v);
      std::array<double, 3> foot{};
      for (int i = 0; i < 3; ++i) {
        eval_ball(t.v, N[i], a.v, prec);
        arb_div(t.v, t.v, dd.v, prec);
        foot[static_cast<size_t>(i)] = arf_get_d(arb_midref(t.v), ARF_RND_NEAR);
        Ball xi;
        arb_set_fmpq(xi.v, x[static_cast<size_t>(i)].raw(), prec);
        arb_sub(t.v, xi.v, t.v, prec);
        arb_addmul(d.v, t.v, t.v, prec);
      }
      // |x - p|^2 >= 0: clip the ball before the square root
      if (arb_contains_negative(d.v) && arb_is_finite(d.v)) {
        arf_t u;
        arf_init(u);
        arb_get_ubound_arf(u, d.v, prec);
        if (arf_sgn(u) >= 0) {
          Ball z, uu;
          arb_set_arf(uu.v, u);
          arb_union(d.v, z.v, uu.v, prec);
        }
        arf_clear(u);
      }
      arb_sqrt(d.v, d.v, prec);
      if (arb_is_finite(d.v) && (accurate_enough(d.v, digits) || lo == hi)) {
        CriticalDistance cd;
        cd.foot = foot;
        set_enclosure(cd, d.v, digits, prec);
        res.criticals.push_back(cd);
        done = true;
        break;
      }
      // refine the exact interval
      Rational mag = core::abs(lo) > core::abs(hi) ? core::abs(lo) : core::abs(hi);
      if (mag.is_zero()) mag = Rational(1);
      Rational width = (hi - lo) * core::pow2(-bits);
      Rational wrel = mag * core::pow2(-bits);
      if (wrel < width) width = wrel;
      if (width.is_zero()) width = core::pow2(-bits);
      algebra::refine_root(sqf, lo, hi, width);
      // Near a pole of N/D (x close to an axis, D(alpha) tiny) the evaluation loses about as
      // many bits as D is small: grow the refinement geometrically, not linearly, so that ten
      // rounds reach far past the loss.
      prec += prec / 2;
      if (it >= 2) {
        bits *= 2;
        prec = std::max(prec, 2 * bits + 64);
      }
    }
    if (!done) {
      all_ok = false;
      notes += "a critical distance could not be enclosed to the requested width; ";
    }
  }

  // singular point of Q (vertex of a cone): kernel of the 4x4 matrix when the rank is 3
  {
    std::vector<std::vector<Rational>> A(4, std::vector<Rational>(4));
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        A[static_cast<size_t>(i)][static_cast<size_t>(j)] = q(i, j);
    std::vector<int> piv = rref(A);
    if (piv.size() == 3) {
      auto ker = kernel_from_rref(A, piv, 4);
      if (ker.size() == 1 && !ker[0][3].is_zero()) {
        Vec3 vtx{ker[0][0] / ker[0][3], ker[0][1] / ker[0][3], ker[0][2] / ker[0][3]};
        Vec3 r = sub(x, vtx);
        CriticalDistance cd;
        cd.singular_point = true;
        cd.foot = to_doubles(vtx);
        cd.d2_exact = true; // a rational vertex: a rational squared distance
        cd.d2 = dot(r, r);
        enclose_sqrt(cd, cd.d2, digits);
        res.criticals.push_back(cd);
      }
    }
  }

  // Sorted by the certified lower bounds (decimal strings with digits + 5 significant digits,
  // read rounding down at enough bits that distinct strings stay distinct): then front()'s
  // lower bound is the least of all, and [front().lower, front().upper] encloses the minimum
  // (lower <= the minimum <= front's own distance <= upper) even when two distances are too
  // close to order; which candidate attains it is still not decided by this order.
  {
    const mpfr_prec_t bits = static_cast<mpfr_prec_t>(4 * (digits + 10)) + 64;
    std::vector<__mpfr_struct> keys(res.criticals.size());
    for (size_t i = 0; i < keys.size(); ++i) {
      mpfr_init2(&keys[i], bits);
      mpfr_set_str(&keys[i], res.criticals[i].lower.c_str(), 10, MPFR_RNDD);
    }
    std::vector<size_t> order(keys.size());
    for (size_t i = 0; i < order.size(); ++i)
      order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return mpfr_cmp(&keys[a], &keys[b]) < 0; });
    std::vector<CriticalDistance> sorted;
    sorted.reserve(order.size());
    for (size_t i : order)
      sorted.push_back(res.criticals[i]);
    res.criticals.swap(sorted);
    for (auto& k : keys)
      mpfr_clear(&k);
  }
  res.ok = all_ok;
  res.note = notes;
  return res;
}

} // namespace surfcert::certify
