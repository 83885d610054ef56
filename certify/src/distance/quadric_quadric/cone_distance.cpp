#include "surfcert/certify/distance/cone_distance.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/certify/distance/group_uniqueness.hpp"
#include "surfcert/certify/distance/periodic_bnb.hpp"

#include <cmath>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

using RM = std::array<std::array<Rational, 3>, 3>;

// The cone in exact form: vertex v and A = P^T L D L^T P (P a coordinate permutation: slot s
// of the permuted coordinates is coordinate perm[s]), one negative pivot (slot kneg) and two
// positive ones (slots ka, kb).
struct ConeData {
  std::array<Rational, 3> v, d;
  Rational l10, l20, l21;
  std::array<size_t, 3> perm{};
  size_t kneg = 0, ka = 0, kb = 0;
};

Rational det3(const RM& a) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

std::optional<ConeData> cone_data(const core::QuadricMatrix& q) {
  RM A;
  std::array<Rational, 3> b;
  for (size_t i = 0; i < 3; ++i) {
    b[i] = q(static_cast<int>(i), 3);
    for (size_t j = 0; j < 3; ++j)
      A[i][j] = q(static_cast<int>(i), static_cast<int>(j));
  }
  const Rational det = det3(A);
  if (det.sign() == 0) return std::nullopt;
  ConeData c;
  // v = -A^-1 b by Cramer's rule
  for (size_t k = 0; k < 3; ++k) {
    RM Ak = A;
    for (size_t i = 0; i < 3; ++i)
      Ak[i][k] = -b[i];
    c.v[k] = det3(Ak) / det;
  }
  Rational fv = q(3, 3);
  for (size_t i = 0; i < 3; ++i)
    fv += b[i] * c.v[i];
  if (fv.sign() != 0) return std::nullopt; // the vertex is not on the surface: not a cone
  const std::array<std::array<size_t, 3>, 6> perms{
      {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {1, 0, 2}, {2, 1, 0}}};
  for (const auto& p : perms) {
    auto a = [&](size_t i, size_t j) -> const Rational& { return A[p[i]][p[j]]; };
    const Rational d1 = a(0, 0), m2 = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1);
    if (d1.sign() == 0 || m2.sign() == 0) continue;
    c.perm = p;
    c.d = {d1, m2 / d1, det / m2};
    c.l10 = a(1, 0) / d1;
    c.l20 = a(2, 0) / d1;
    c.l21 = (a(2, 1) - c.l20 * c.l10 * d1) / c.d[1];
    int neg = 0;
    for (const auto& x : c.d)
      neg += x.sign() < 0;
    if (neg == 2) { // -A describes the same cone
      for (auto& x : c.d)
        x = -x;
      neg = 1;
    }
    if (neg != 1) return std::nullopt; // definite: the "cone" is the vertex alone
    for (size_t s = 0; s < 3; ++s)
      if (c.d[s].sign() < 0) c.kneg = s;
    c.ka = (c.kneg + 1) % 3;
    c.kb = (c.kneg + 2) % 3;
    return c;
  }
  return std::nullopt;
}

// A value and its derivative in t.
struct Du {
  Ball v, d;
};
void du_mul(Du& o, const Du& a, const Du& b, long prec) {
  Ball t;
  arb_mul(t.v, a.v.v, b.d.v, prec);
  arb_addmul(t.v, a.d.v, b.v.v, prec);
  arb_mul(o.v.v, a.v.v, b.v.v, prec);
  arb_swap(o.d.v, t.v);
}
void du_addmul(Du& o, const Du& a, const Du& b, long prec) {
  Du t;
  du_mul(t, a, b, prec);
  arb_add(o.v.v, o.v.v, t.v.v, prec);
  arb_add(o.d.v, o.d.v, t.d.v, prec);
}
void du_sqrt(Du& o, const Du& a, long prec) {
  arb_sqrtpos(o.v.v, a.v.v, prec);
  arb_div(o.d.v, a.d.v, o.v.v, prec);
  arb_mul_2exp_si(o.d.v, o.d.v, -1);
}
void du_div(Du& o, const Du& a, const Du& b, long prec) {
  Ball q, t;
  arb_div(q.v, a.v.v, b.v.v, prec);
  arb_mul(t.v, q.v, b.d.v, prec);
  arb_sub(t.v, a.d.v, t.v, prec);
  arb_div(o.d.v, t.v, b.v.v, prec);
  arb_swap(o.v.v, q.v);
}

// Everything in balls at one precision.
struct Model {
  const ConvexQuadric& e;
  Ball l10, l20, l21, inv_neg, inv_a, inv_b, v[3], w[3], W[3][3], pi;
  Model(const ConvexQuadric& e_, const ConeData& c, long prec) : e(e_) {
    arb_set_fmpq(l10.v, c.l10.raw(), prec);
    arb_set_fmpq(l20.v, c.l20.raw(), prec);
    arb_set_fmpq(l21.v, c.l21.raw(), prec);
    auto inv_sqrt = [&](arb_t o, const Rational& d) {
      arb_set_fmpq(o, d.raw(), prec);
      arb_abs(o, o);
      arb_rsqrt(o, o, prec);
    };
    inv_sqrt(inv_neg.v, c.d[c.kneg]);
    inv_sqrt(inv_a.v, c.d[c.ka]);
    inv_sqrt(inv_b.v, c.d[c.kb]);
    Ball t;
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(v[i].v, c.v[i].raw(), prec);
      arb_set_fmpq(t.v, e.c[i].raw(), prec);
      arb_sub(w[i].v, v[i].v, t.v, prec); // v - c_E
      for (size_t j = 0; j < 3; ++j)
        arb_set_fmpq(W[i][j].v, e.W[i][j].raw(), prec);
    }
    arb_const_pi(pi.v, prec);
  }
};

// Generator direction g(t) (original coordinates) with derivatives.
void generator(Du (&g)[3], const Model& M, const ConeData& c, const arb_t t, long prec) {
  Ball s, co;
  arb_sin_cos_pi(s.v, co.v, t, prec);
  Du y[3];
  arb_set(y[c.kneg].v.v, M.inv_neg.v);
  arb_mul(y[c.ka].v.v, co.v, M.inv_a.v, prec);
  arb_mul(y[c.ka].d.v, s.v, M.inv_a.v, prec);
  arb_mul(y[c.ka].d.v, y[c.ka].d.v, M.pi.v, prec);
  arb_neg(y[c.ka].d.v, y[c.ka].d.v);
  arb_mul(y[c.kb].v.v, s.v, M.inv_b.v, prec);
  arb_mul(y[c.kb].d.v, co.v, M.inv_b.v, prec);
  arb_mul(y[c.kb].d.v, y[c.kb].d.v, M.pi.v, prec);
  // L^T gp = y (unit upper triangular): gp2 = y2, gp1 = y1 - l21 gp2, gp0 = y0 - l10 gp1 - l20 gp2
  Du gp[3];
  for (int k : {0, 1}) { // value, derivative
    auto get = [&](Du& x) -> arb_ptr { return k == 0 ? x.v.v : x.d.v; };
    arb_set(get(gp[2]), get(y[2]));
    arb_mul(get(gp[1]), M.l21.v, get(gp[2]), prec);
    arb_sub(get(gp[1]), get(y[1]), get(gp[1]), prec);
    arb_mul(get(gp[0]), M.l10.v, get(gp[1]), prec);
    arb_addmul(get(gp[0]), M.l20.v, get(gp[2]), prec);
    arb_sub(get(gp[0]), get(y[0]), get(gp[0]), prec);
  }
  for (size_t s2 = 0; s2 < 3; ++s2) {
    arb_set(g[c.perm[s2]].v.v, gp[s2].v.v);
    arb_set(g[c.perm[s2]].d.v, gp[s2].d.v);
  }
}

// f(t) = (n.(v - c_E) - sqrt(n^T W n)) / |n| with n = n0 - (n0.g / g.g) g (orthogonal to the
// generator g(t) exactly): a lower bound of dist(E, line(t)). Also n (for the upper bound).
void slab(Du& f, Du (*n_out)[3], const Model& M, const ConeData& c, const Ball (&n0)[3],
          const arb_t t, long prec) {
  Du g[3], gg, gn, r, n[3], nn, nw, q, wn[3];
  generator(g, M, c, t, prec);
  Du n0d[3];
  for (size_t i = 0; i < 3; ++i)
    arb_set(n0d[i].v.v, n0[i].v);
  for (size_t i = 0; i < 3; ++i) {
    du_addmul(gg, g[i], g[i], prec);
    du_addmul(gn, g[i], n0d[i], prec);
  }
  du_div(r, gn, gg, prec);
  for (size_t i = 0; i < 3; ++i) {
    Du rg;
    du_mul(rg, r, g[i], prec);
    arb_sub(n[i].v.v, n0[i].v, rg.v.v, prec);
    arb_neg(n[i].d.v, rg.d.v);
  }
  Du wd[3];
  for (size_t i = 0; i < 3; ++i)
    arb_set(wd[i].v.v, M.w[i].v);
  for (size_t i = 0; i < 3; ++i) {
    du_addmul(nn, n[i], n[i], prec);
    du_addmul(nw, n[i], wd[i], prec);
    for (size_t j = 0; j < 3; ++j) {
      Du Wij;
      arb_set(Wij.v.v, M.W[i][j].v);
      du_addmul(wn[i], Wij, n[j], prec);
    }
    du_addmul(q, n[i], wn[i], prec);
  }
  Du sq, len, num;
  du_sqrt(sq, q, prec);
  du_sqrt(len, nn, prec);
  arb_sub(num.v.v, nw.v.v, sq.v.v, prec);
  arb_sub(num.d.v, nw.d.v, sq.d.v, prec);
  du_div(f, num, len, prec);
  if (n_out)
    for (size_t i = 0; i < 3; ++i) {
      arb_set((*n_out)[i].v.v, n[i].v.v);
      arb_set((*n_out)[i].d.v, n[i].d.v);
    }
}

using D3 = std::array<double, 3>;
double dot(const D3& a, const D3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Float guidance: the unit n orthogonal to g maximising n.(v - c_E) - sqrt(n^T W n) (the
// best slab between the line and the ellipsoid), by Newton on the angle in g's normal plane.
D3 best_normal(const ConvexQuadric& e, const ConeData& c, const D3& g) {
  D3 a{}, gu = g;
  const double gl = std::sqrt(dot(g, g));
  for (auto& x : gu)
    x /= gl;
  for (size_t i = 0; i < 3; ++i)
    a[i] = c.v[i].to_double_approx() - e.cd[i];
  // frame of the normal plane: e1 = a projected (or any), e2 = g x e1
  D3 e1{a[0] - dot(a, gu) * gu[0], a[1] - dot(a, gu) * gu[1], a[2] - dot(a, gu) * gu[2]};
  if (dot(e1, e1) < 1e-30) e1 = {gu[1] - gu[2], gu[2] - gu[0], gu[0] - gu[1]};
  const double l1 = std::sqrt(dot(e1, e1));
  for (auto& x : e1)
    x /= l1;
  const D3 e2{gu[1] * e1[2] - gu[2] * e1[1], gu[2] * e1[0] - gu[0] * e1[2],
              gu[0] * e1[1] - gu[1] * e1[0]};
  auto Wm = [&](const D3& x) {
    D3 o{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        o[i] += e.Wd[i][j] * x[j];
    return o;
  };
  double psi = 0;
  for (int it = 0; it < 40; ++it) {
    const double cs = std::cos(psi), sn = std::sin(psi);
    const D3 n{cs * e1[0] + sn * e2[0], cs * e1[1] + sn * e2[1], cs * e1[2] + sn * e2[2]};
    const D3 np{-sn * e1[0] + cs * e2[0], -sn * e1[1] + cs * e2[1], -sn * e1[2] + cs * e2[2]};
    const D3 Wn = Wm(n), Wnp = Wm(np);
    const double s = std::sqrt(dot(n, Wn)), a1 = dot(n, Wnp);
    const double d1 = dot(np, a) - a1 / s;
    const double d2 = -dot(n, a) - ((dot(np, Wnp) - dot(n, Wn)) / s - a1 * a1 / (s * s * s));
    double step = d2 < 0 ? -d1 / d2 : (d1 > 0 ? 0.5 : -0.5);
    step = std::max(-0.5, std::min(0.5, step));
    psi += step;
    if (std::fabs(step) < 1e-16) break;
  }
  return {std::cos(psi) * e1[0] + std::sin(psi) * e2[0],
          std::cos(psi) * e1[1] + std::sin(psi) * e2[1],
          std::cos(psi) * e1[2] + std::sin(psi) * e2[2]};
}

D3 generator_float(const ConeData& c, double t) {
  D3 y{}, gp{}, g{};
  y[c.kneg] = 1 / std::sqrt(-c.d[c.kneg].to_double_approx());
  y[c.ka] = std::cos(M_PI * t) / std::sqrt(c.d[c.ka].to_double_approx());
  y[c.kb] = std::sin(M_PI * t) / std::sqrt(c.d[c.kb].to_double_approx());
  gp[2] = y[2];
  gp[1] = y[1] - c.l21.to_double_approx() * gp[2];
  gp[0] = y[0] - c.l10.to_double_approx() * gp[1] - c.l20.to_double_approx() * gp[2];
  for (size_t s = 0; s < 3; ++s)
    g[c.perm[s]] = gp[s];
  return g;
}

} // namespace

std::optional<DistanceResult> ellipsoid_cone_distance(const ConvexQuadric& e,
                                                      const core::QuadricMatrix& cone, long digits,
                                                      bool ellipsoid_first) {
  if (!e.is_ellipsoid() || digits > 25) return std::nullopt;
  const auto c = cone_data(cone);
  if (!c) return std::nullopt;
  const long prec = bits_for(digits + 10);
  const Model M(e, *c, prec);
  // the float normal at the interval's midpoint (exact double values as balls)
  auto normal_at = [&](Ball(&n0)[3], const arb_t tm) {
    const D3 nd = best_normal(e, *c, generator_float(*c, arf_get_d(arb_midref(tm), ARF_RND_NEAR)));
    for (size_t i = 0; i < 3; ++i)
      arb_set_d(n0[i].v, nd[i]);
  };
  // genuine pair at t: the support point p of E in direction n(t) and its foot on the line
  auto pair_at = [&](arb_t dist, D3* pe, D3* pc, const Ball(&n0)[3], const arb_t tm) {
    Du f, n[3], g[3];
    slab(f, &n, M, *c, n0, tm, prec);
    Ball nb[3], h, p[3], wv[3], gg, wg, t;
    for (size_t i = 0; i < 3; ++i)
      arb_set(nb[i].v, n[i].v.v);
    support_ball(h.v, &p, e, nb, prec);
    generator(g, M, *c, tm, prec);
    for (size_t i = 0; i < 3; ++i) {
      arb_sub(wv[i].v, p[i].v, M.v[i].v, prec);
      arb_addmul(gg.v, g[i].v.v, g[i].v.v, prec);
      arb_addmul(wg.v, wv[i].v, g[i].v.v, prec);
    }
    // |w|^2 - (w.g)^2 / g.g
    arb_zero(dist);
    for (size_t i = 0; i < 3; ++i)
      arb_addmul(dist, wv[i].v, wv[i].v, prec);
    arb_sqr(t.v, wg.v, prec);
    arb_div(t.v, t.v, gg.v, prec);
    arb_sub(dist, dist, t.v, prec);
    arb_sqrtpos(dist, dist, prec);
    if (pe && pc) {
      const double lam =
          arf_get_d(arb_midref(wg.v), ARF_RND_NEAR) / arf_get_d(arb_midref(gg.v), ARF_RND_NEAR);
      for (size_t i = 0; i < 3; ++i) {
        (*pe)[i] = arf_get_d(arb_midref(p[i].v), ARF_RND_NEAR);
        (*pc)[i] = c->v[i].to_double_approx() + lam * arf_get_d(arb_midref(g[i].v.v), ARF_RND_NEAR);
      }
    }
  };
  auto bound = [&](const arb_t tm, const arb_t T, arf_t lower, arf_t upper) {
    Ball n0[3];
    normal_at(n0, tm);
    Du whole, at;
    slab(whole, nullptr, M, *c, n0, T, prec);
    slab(at, nullptr, M, *c, n0, tm, prec);
    mean_value_lower(lower, whole.v.v, whole.d.v, at.v.v, T, prec);
    if (!arf_is_finite(lower)) arf_neg_inf(lower);
    Ball d;
    pair_at(d.v, nullptr, nullptr, n0, tm);
    arb_get_ubound_arf(upper, d.v, prec);
    if (!arf_is_finite(upper)) arf_pos_inf(upper);
  };
  Ball zero;
  PeriodicMinimum pm;
  if (!periodic_minimize(bound, zero.v, digits, prec, pm)) return std::nullopt;
  DistanceResult out;
  out.status = Status::Certified;
  set_distance_enclosure(out, pm.enclosure.v, digits);
  for (const auto& tm : pm.minimizers) {
    Ball n0[3], d;
    normal_at(n0, tm.v);
    D3 pe{}, pc{};
    pair_at(d.v, &pe, &pc, n0, tm.v);
    out.pairs.push_back(ellipsoid_first ? std::array<D3, 2>{pe, pc} : std::array<D3, 2>{pc, pe});
  }
  out.minimizers =
      Minimizers::count(static_cast<long>(pm.minimizers.size()), Minimizers::Proof::Interval);
  out.critical_candidates = static_cast<int>(pm.minimizers.size());
  out.method = Method::ConeGeneratorBound;
  out.note = "ellipsoid and cone do not meet: minimum over the cone's generator lines of the "
             "line-ellipsoid distance, by branch and bound with slab (support-function) lower "
             "bounds (Arb)";
  note_unproven_ties(out, pm.minimizers.size());
  // Every minimizing line lies in a group of survivors; a group holds at most one when D(t) =
  // dist(line(t), E)^2 (same minimizers) has at most one critical point on its hull
  // (group_uniqueness.hpp). Adjacent survivors alone prove nothing: two minimizing lines
  // closer than the surviving intervals (a bump between them below 10^-digits) make one group.
  // D(t) is the squared distance of P (v - c_E) to the ellipse P E in the plane normal to g(t)
  // (P = I - g g^T / g.g), whose shape matrix is P W P.
  auto derivs = [&](arb_t d1, arb_t d2, const arb_t T) {
    Series x, sn, cs, yv[3], gp[3], g[3], gg, t1, P[3][3], PW[3][3], Mp[3][3], y[3];
    arb_poly_set_coeff_arb(x.p, 0, T);
    arb_poly_set_coeff_si(x.p, 1, 1);
    arb_poly_sin_cos_pi_series(sn.p, cs.p, x.p, 3, prec);
    arb_poly_set_arb(yv[c->kneg].p, M.inv_neg.v);
    arb_poly_scalar_mul(yv[c->ka].p, cs.p, M.inv_a.v, prec);
    arb_poly_scalar_mul(yv[c->kb].p, sn.p, M.inv_b.v, prec);
    arb_poly_set(gp[2].p, yv[2].p);
    arb_poly_scalar_mul(t1.p, gp[2].p, M.l21.v, prec);
    arb_poly_sub(gp[1].p, yv[1].p, t1.p, prec);
    arb_poly_scalar_mul(t1.p, gp[1].p, M.l10.v, prec);
    arb_poly_sub(gp[0].p, yv[0].p, t1.p, prec);
    arb_poly_scalar_mul(t1.p, gp[2].p, M.l20.v, prec);
    arb_poly_sub(gp[0].p, gp[0].p, t1.p, prec);
    for (size_t k = 0; k < 3; ++k)
      arb_poly_set(g[c->perm[k]].p, gp[k].p);
    for (size_t i = 0; i < 3; ++i) {
      arb_poly_mullow(t1.p, g[i].p, g[i].p, 3, prec);
      arb_poly_add(gg.p, gg.p, t1.p, prec);
    }
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        arb_poly_mullow(t1.p, g[i].p, g[j].p, 3, prec);
        arb_poly_div_series(t1.p, t1.p, gg.p, 3, prec);
        arb_poly_neg(P[i][j].p, t1.p);
        if (i == j) {
          Series one;
          arb_poly_one(one.p);
          arb_poly_add(P[i][j].p, P[i][j].p, one.p, prec);
        }
      }
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        for (size_t k = 0; k < 3; ++k) {
          arb_poly_scalar_mul(t1.p, P[i][k].p, M.W[k][j].v, prec);
          arb_poly_add(PW[i][j].p, PW[i][j].p, t1.p, prec);
        }
      }
    for (size_t i = 0; i < 3; ++i) {
      for (size_t j = 0; j < 3; ++j)
        for (size_t k = 0; k < 3; ++k) {
          arb_poly_mullow(t1.p, PW[i][k].p, P[k][j].p, 3, prec);
          arb_poly_add(Mp[i][j].p, Mp[i][j].p, t1.p, prec);
        }
      for (size_t k = 0; k < 3; ++k) {
        arb_poly_scalar_mul(t1.p, P[i][k].p, M.w[k].v, prec);
        arb_poly_add(y[i].p, y[i].p, t1.p, prec);
      }
    }
    ellipsoid_dist2_derivatives(d1, d2, y, Mp, prec);
  };
  prove_one_per_group(out, pm.group_hulls, derivs, 1, "an arc of minimizing generator lines");
  // Tie regions (symmetry.hpp): per group the unit directions of its generator lines (up to
  // sign: a symmetry keeps the vertex and maps lines to lines); every minimizing line is in one.
  out.tie_lines = true;
  for (const auto& T : pm.group_hulls) {
    Du g[3];
    generator(g, M, *c, T.v, prec);
    Ball len;
    for (const auto& x : g)
      arb_addmul(len.v, x.v.v, x.v.v, prec);
    arb_sqrt(len.v, len.v, prec);
    std::vector<std::array<double, 2>> reg;
    for (const auto& x : g) {
      Ball u;
      arb_div(u.v, x.v.v, len.v, prec);
      reg.push_back(outward_interval(u.v));
    }
    out.tie_regions.push_back(std::move(reg));
  }
  return out;
}

} // namespace surfcert::certify
