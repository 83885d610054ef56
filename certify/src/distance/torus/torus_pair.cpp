#include "surfcert/certify/distance/torus_pair.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/group_uniqueness.hpp"
#include "surfcert/certify/distance/periodic_bnb.hpp"

#include <cmath>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

// A value and its derivative (forward differentiation), both balls.
struct Dual {
  Ball v, d;
};

void set_q(arb_t x, const Rational& q, long prec) {
  arb_set_fmpq(x, q.raw(), prec);
}

// A circle as Arb balls: centre o, unit normal n, orthonormal frame (u, v), radius R.
struct Circle {
  Ball o[3], n[3], u[3], v[3], R;
  Circle(const core::Torus& t, long prec) {
    Ball len;
    for (size_t i = 0; i < 3; ++i) {
      set_q(o[i].v, t.centre[i], prec);
      set_q(n[i].v, t.axis[i], prec);
      arb_addmul(len.v, n[i].v, n[i].v, prec);
    }
    arb_sqrt(len.v, len.v, prec);
    for (auto& x : n)
      arb_div(x.v, x.v, len.v, prec);
    unit_plane_frame(u, v, t.axis, prec);
    set_q(R.v, t.R, prec);
  }
};

// Display only (the pairs are approximate points): the midpoint of a ball point, and the
// nearest point of the core circle of t (unit axis from its Circle) to a double point p.
std::array<double, 3> midpoint(const Ball (&p)[3]) {
  return {arf_get_d(arb_midref(p[0].v), ARF_RND_NEAR), arf_get_d(arb_midref(p[1].v), ARF_RND_NEAR),
          arf_get_d(arb_midref(p[2].v), ARF_RND_NEAR)};
}
std::array<double, 3> nearest_on_core(const std::array<double, 3>& p, const core::Torus& t,
                                      const Circle& k) {
  std::array<double, 3> w{}, nd{}, out{};
  double h = 0, rl = 0;
  for (size_t i = 0; i < 3; ++i) {
    nd[i] = arf_get_d(arb_midref(k.n[i].v), ARF_RND_NEAR);
    w[i] = p[i] - t.centre[i].to_double_approx();
    h += w[i] * nd[i];
  }
  for (size_t i = 0; i < 3; ++i) {
    w[i] -= h * nd[i]; // the component in the circle's plane
    rl += w[i] * w[i];
  }
  rl = std::sqrt(rl);
  for (size_t i = 0; i < 3; ++i)
    out[i] = t.centre[i].to_double_approx() + (rl > 0 ? t.R.to_double_approx() * w[i] / rl : 0);
  return out;
}

// f(t) = dist(K1(pi t), K2) and f'(t) over the ball t; the point K1(t) (for the pairs).
void circle_circle(Dual& f, Ball (*point)[3], const Circle& c1, const Circle& c2, const arb_t t,
                   long prec) {
  Ball s, c, pi, w[3], dw[3], tmp, h, dh, w2, dw2, rho2, drho2, rho, drho, g, dg;
  arb_sin_cos_pi(s.v, c.v, t, prec);
  arb_const_pi(pi.v, prec);
  for (size_t i = 0; i < 3; ++i) {
    // K1 = o1 + R1 (cos u + sin v), K1' = pi R1 (-sin u + cos v); w = K1 - o2
    arb_mul(w[i].v, c.v, c1.u[i].v, prec);
    arb_addmul(w[i].v, s.v, c1.v[i].v, prec);
    arb_mul(w[i].v, w[i].v, c1.R.v, prec);
    arb_add(w[i].v, w[i].v, c1.o[i].v, prec);
    if (point) arb_set((*point)[i].v, w[i].v);
    arb_sub(w[i].v, w[i].v, c2.o[i].v, prec);
    arb_mul(dw[i].v, c.v, c1.v[i].v, prec);
    arb_submul(dw[i].v, s.v, c1.u[i].v, prec);
    arb_mul(dw[i].v, dw[i].v, c1.R.v, prec);
    arb_mul(dw[i].v, dw[i].v, pi.v, prec);
    arb_addmul(h.v, w[i].v, c2.n[i].v, prec);
    arb_addmul(dh.v, dw[i].v, c2.n[i].v, prec);
    arb_addmul(w2.v, w[i].v, w[i].v, prec);
    arb_addmul(dw2.v, w[i].v, dw[i].v, prec);
  }
  arb_mul_2exp_si(dw2.v, dw2.v, 1);
  // rho^2 = |w|^2 - h^2, rho = sqrt(rho^2) (its derivative is infinite where rho may be 0:
  // then the mean-value form is useless and the interval extension alone bounds f)
  arb_sqr(tmp.v, h.v, prec);
  arb_sub(rho2.v, w2.v, tmp.v, prec);
  arb_mul(tmp.v, h.v, dh.v, prec);
  arb_mul_2exp_si(tmp.v, tmp.v, 1);
  arb_sub(drho2.v, dw2.v, tmp.v, prec);
  arb_sqrtpos(rho.v, rho2.v, prec);
  arb_div(drho.v, drho2.v, rho.v, prec);
  arb_mul_2exp_si(drho.v, drho.v, -1);
  // g = (rho - R2)^2 + h^2, f = sqrt(g)
  arb_sub(tmp.v, rho.v, c2.R.v, prec);
  arb_sqr(g.v, tmp.v, prec);
  arb_addmul(g.v, h.v, h.v, prec);
  arb_mul(dg.v, tmp.v, drho.v, prec);
  arb_addmul(dg.v, h.v, dh.v, prec);
  arb_mul_2exp_si(dg.v, dg.v, 1);
  arb_sqrtpos(f.v.v, g.v, prec);
  arb_div(f.d.v, dg.v, f.v.v, prec);
  arb_mul_2exp_si(f.d.v, f.d.v, -1);
}

// f'(t) and f''(t) over the ball T for f(t) = dist(K1(pi t), K2) (circle_circle's f), by
// Taylor arithmetic: arb_poly series of length 3 at T enclose f, f', f''/2 for every t in T.
// Non-finite when rho or f may vanish in T.
void circle_circle_derivatives(arb_t d1, arb_t d2, const Circle& c1, const Circle& c2,
                               const arb_t T, long prec) {
  arb_indeterminate(d1);
  arb_indeterminate(d2);
  const slong n = 3;
  Series x, s, c, w, h, w2, sq, rho2, rho, g, f;
  arb_poly_set_coeff_arb(x.p, 0, T);
  arb_poly_set_coeff_si(x.p, 1, 1);
  arb_poly_sin_cos_pi_series(s.p, c.p, x.p, n, prec);
  for (size_t i = 0; i < 3; ++i) {
    // w_i = R1 (cos u_i + sin v_i) + o1_i - o2_i
    Series t1, t2;
    Ball k;
    arb_poly_scalar_mul(t1.p, c.p, c1.u[i].v, prec);
    arb_poly_scalar_mul(t2.p, s.p, c1.v[i].v, prec);
    arb_poly_add(w.p, t1.p, t2.p, prec);
    arb_poly_scalar_mul(w.p, w.p, c1.R.v, prec);
    arb_sub(k.v, c1.o[i].v, c2.o[i].v, prec);
    arb_poly_set_arb(t1.p, k.v);
    arb_poly_add(w.p, w.p, t1.p, prec);
    arb_poly_scalar_mul(t1.p, w.p, c2.n[i].v, prec);
    arb_poly_add(h.p, h.p, t1.p, prec);
    arb_poly_mullow(t1.p, w.p, w.p, n, prec);
    arb_poly_add(w2.p, w2.p, t1.p, prec);
  }
  arb_poly_mullow(sq.p, h.p, h.p, n, prec);
  arb_poly_sub(rho2.p, w2.p, sq.p, prec);
  Ball c0;
  arb_poly_get_coeff_arb(c0.v, rho2.p, 0);
  if (!arb_is_positive(c0.v)) return;
  arb_poly_sqrt_series(rho.p, rho2.p, n, prec);
  {
    Series r2;
    arb_poly_set_arb(r2.p, c2.R.v);
    arb_poly_sub(rho.p, rho.p, r2.p, prec);
  }
  arb_poly_mullow(g.p, rho.p, rho.p, n, prec);
  arb_poly_add(g.p, g.p, sq.p, prec);
  arb_poly_get_coeff_arb(c0.v, g.p, 0);
  if (!arb_is_positive(c0.v)) return;
  arb_poly_sqrt_series(f.p, g.p, n, prec);
  arb_poly_get_coeff_arb(d1, f.p, 1);
  arb_poly_get_coeff_arb(d2, f.p, 2);
  arb_mul_2exp_si(d2, d2, 1);
}

// The count of each group of survivors (group_uniqueness.hpp): every minimizing t lies in one
// of the groups' hulls; a hull holds at most one minimizer when f has at most one critical
// point on it (sign +1; for a maximum of f, sign -1).
void prove_groups(DistanceResult& res, const PeriodicMinimum& pm, const Circle& c1,
                  const Circle& c2, int sign, long prec) {
  prove_one_per_group(
      res, pm.group_hulls,
      [&](arb_t d1, arb_t d2, const arb_t T) {
        circle_circle_derivatives(d1, d2, c1, c2, T, prec);
      },
      sign, "a minimizing arc of the circle");
}

// Tie regions (symmetry.hpp): the points K1(t) over each group of survivors, which hold every
// minimizing t (outward double boxes).
void add_core_regions(DistanceResult& res, const PeriodicMinimum& pm, const Circle& c1,
                      const Circle& c2, long prec) {
  for (const auto& T : pm.group_hulls) {
    Ball p[3];
    Dual f;
    circle_circle(f, &p, c1, c2, T.v, prec);
    std::vector<std::array<double, 2>> reg;
    for (const Ball& x : p)
      reg.push_back(outward_interval(x.v));
    res.tie_regions.push_back(std::move(reg));
  }
}

// One tube nested in the other: d = min_t (r_out - r_in - dist(K_in(t), K_out)) when positive.
// (Every point q within r_in of K_in(t) has dist(q, K_out) <= dist(K_in(t), K_out) + r_in
// < r_out, so the inner tube lies inside the outer one; the farthest inner surface point from
// K_out is on the ray from the nearest point of K_out through K_in(t).)
std::optional<DistanceResult> nested_tubes(const core::Torus& in, const core::Torus& out,
                                           bool inner_is_a, long digits) {
  const long prec = bits_for(digits + 10);
  const Circle ci(in, prec), co(out, prec);
  Ball shift, r;
  set_q(shift.v, in.r, prec); // shift = r_in - r_out: min(-f) - shift = r_out - r_in - max f
  set_q(r.v, out.r, prec);
  arb_sub(shift.v, shift.v, r.v, prec);
  auto bound = [&](const arb_t tm, const arb_t T, arf_t lower, arf_t upper) {
    Dual whole, at;
    circle_circle(whole, nullptr, ci, co, T, prec);
    circle_circle(at, nullptr, ci, co, tm, prec);
    arb_neg(whole.v.v, whole.v.v);
    arb_neg(whole.d.v, whole.d.v);
    arb_neg(at.v.v, at.v.v);
    mean_value_lower(lower, whole.v.v, whole.d.v, at.v.v, T, prec);
    arb_get_ubound_arf(upper, at.v.v, prec);
  };
  PeriodicMinimum pm;
  if (!periodic_minimize(bound, shift.v, digits, prec, pm)) return std::nullopt;
  DistanceResult res;
  res.status = Status::Certified;
  set_distance_enclosure(res, pm.enclosure.v, digits);
  const double ri = in.r.to_double_approx(), ro = out.r.to_double_approx();
  for (const auto& tm : pm.minimizers) {
    Ball p[3];
    Dual f;
    circle_circle(f, &p, ci, co, tm.v, prec);
    // nearest point k of K_out to c = K_in(t), then the two surface points on the ray k -> c
    const std::array<double, 3> c = midpoint(p), k = nearest_on_core(c, out, co);
    const double fd = std::hypot(c[0] - k[0], c[1] - k[1], c[2] - k[2]);
    std::array<std::array<double, 3>, 2> pr{};
    for (size_t i = 0; i < 3; ++i) {
      const double dir = fd > 0 ? (c[i] - k[i]) / fd : 0;
      pr[inner_is_a ? 0 : 1][i] = c[i] + ri * dir;
      pr[inner_is_a ? 1 : 0][i] = k[i] + ro * dir;
    }
    res.pairs.push_back(pr);
  }
  const size_t groups = pm.minimizers.size();
  res.minimizers = Minimizers::count(static_cast<long>(groups), Minimizers::Proof::Interval);
  res.critical_candidates = static_cast<int>(groups);
  res.method = Method::TorusCirclePair;
  res.note = std::string("nested tubes: the ") + (inner_is_a ? "first" : "second") +
             " torus lies inside the other's tube; d = r_out - r_in - max dist(K_in, K_out), by "
             "branch and bound over the inner circle (Arb)";
  note_unproven_ties(res, groups);
  prove_groups(res, pm, ci, co, -1, prec);
  add_core_regions(res, pm, ci, co, prec);
  return res;
}

// Coaxial tori (one axis line): the distance of the meridian circles in the half-plane
// (rho, z) (rotating both surfaces together keeps every distance, and |p - q| >= the meridian
// distance), so a closed form; circles of closest pairs.
std::optional<DistanceResult> coaxial_tori(const core::Torus& a, const core::Torus& b,
                                           long digits) {
  const auto& x = a.axis;
  std::array<Rational, 3> dc, y = b.axis;
  for (size_t i = 0; i < 3; ++i)
    dc[i] = b.centre[i] - a.centre[i];
  auto cross_zero = [](const std::array<Rational, 3>& u, const std::array<Rational, 3>& v) {
    return u[1] * v[2] == u[2] * v[1] && u[2] * v[0] == u[0] * v[2] && u[0] * v[1] == u[1] * v[0];
  };
  if (!cross_zero(x, y) || !cross_zero(x, dc)) return std::nullopt;
  const Rational xx = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
  const Rational hx = dc[0] * x[0] + dc[1] * x[1] + dc[2] * x[2]; // h = hx / |x|
  const Rational h2 = hx * hx / xx, dR = a.R - b.R;
  const Rational D2 = dR * dR + h2, s = a.r + b.r, del = core::abs(a.r - b.r);
  DistanceResult out;
  out.method = Method::TorusCoaxialClosedForm;
  out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
  out.status = Status::Certified;
  // Meridian-plane points as 3D doubles: e orthogonal to the axis, n the unit axis.
  const double xn = std::sqrt(xx.to_double_approx());
  std::array<double, 3> n{}, e{};
  for (size_t i = 0; i < 3; ++i)
    n[i] = x[i].to_double_approx() / xn;
  {
    size_t k = 0;
    for (size_t i = 1; i < 3; ++i)
      if (std::fabs(n[i]) < std::fabs(n[k])) k = i;
    std::array<double, 3> ek{0, 0, 0};
    ek[k] = 1;
    e = {n[1] * ek[2] - n[2] * ek[1], n[2] * ek[0] - n[0] * ek[2], n[0] * ek[1] - n[1] * ek[0]};
    const double en = std::hypot(e[0], e[1], e[2]);
    for (auto& v : e)
      v /= en;
  }
  const double h = hx.to_double_approx() / xn;
  auto at = [&](double rho, double z) {
    std::array<double, 3> p{};
    for (size_t i = 0; i < 3; ++i)
      p[i] = a.centre[i].to_double_approx() + rho * e[i] + z * n[i];
    return p;
  };
  // Meridian circles: A at (R_A, 0) radius r_A, B at (R_B, h) radius r_B.
  const double cA[2] = {a.R.to_double_approx(), 0}, cB[2] = {b.R.to_double_approx(), h};
  const double Dd = std::sqrt(D2.to_double_approx());
  double u[2] = {1, 0};
  if (Dd > 0) {
    u[0] = (cB[0] - cA[0]) / Dd;
    u[1] = (cB[1] - cA[1]) / Dd;
  }
  const long prec = bits_for(digits + 10);
  Ball D, S, d;
  arb_set_fmpq(D.v, D2.raw(), prec);
  arb_sqrt(D.v, D.v, prec);
  const double ra = a.r.to_double_approx(), rb = b.r.to_double_approx();
  if (D2 > s * s) { // external: D - r_A - r_B
    arb_set_fmpq(S.v, s.raw(), prec);
    arb_sub(d.v, D.v, S.v, prec);
    out.pairs.push_back(
        {at(cA[0] + ra * u[0], cA[1] + ra * u[1]), at(cB[0] - rb * u[0], cB[1] - rb * u[1])});
    out.note = "coaxial tori: the meridian circles are apart; d = |c_A - c_B| - r_A - r_B in the "
               "meridian half-plane (exact comparison, Arb); circles of closest pairs (one shown)";
  } else if (D2 < del * del || (D2.is_zero() && !del.is_zero())) { // nested: |r_A - r_B| - D
    arb_set_fmpq(S.v, del.raw(), prec);
    arb_sub(d.v, S.v, D.v, prec);
    const bool a_inner = a.r < b.r;
    const double* ci = a_inner ? cA : cB;
    const double* co = a_inner ? cB : cA;
    const double ri = a_inner ? ra : rb, ro = a_inner ? rb : ra;
    double w[2] = {1, 0};
    if (Dd > 0) {
      w[0] = (ci[0] - co[0]) / Dd;
      w[1] = (ci[1] - co[1]) / Dd;
    }
    const auto pi = at(ci[0] + ri * w[0], ci[1] + ri * w[1]),
               po = at(co[0] + ro * w[0], co[1] + ro * w[1]);
    out.pairs.push_back(a_inner ? std::array<std::array<double, 3>, 2>{pi, po}
                                : std::array<std::array<double, 3>, 2>{po, pi});
    out.note = std::string("coaxial tori: the ") + (a_inner ? "first" : "second") +
               " tube lies inside the other; d = |r_A - r_B| - |c_A - c_B| in the meridian "
               "half-plane (exact comparison, Arb); " +
               (D2.is_zero() ? "the whole surfaces are equidistant" : "circles of closest pairs") +
               " (one pair shown)";
  } else if (D2.is_zero() && del.is_zero()) {
    out.distance = Enclosure::zero();
    out.note = "the tori coincide";
    return out;
  } else { // the meridian circles meet: the tori meet along circles
    out.distance = Enclosure::zero();
    // a common meridian point: radical line of the two circles
    const double t = (D2.to_double_approx() + ra * ra - rb * rb) / (2 * Dd);
    const double hh = std::sqrt(std::max(0.0, ra * ra - t * t));
    const auto w = at(cA[0] + t * u[0] - hh * u[1], cA[1] + t * u[1] + hh * u[0]);
    out.pairs.push_back({w, w});
    out.note = "coaxial tori whose meridian circles meet: the tori meet along circles";
    return out;
  }
  set_distance_enclosure(out, d.v, digits);
  out.critical_candidates = 1;
  return out;
}

} // namespace

namespace {
// Disjoint tubes: min over K1 of dist(K1(t), K2) - r1 - r2 at working precision prec
// (nullopt: not proven at that precision).
std::optional<DistanceResult> circle_pair_distance(const core::Torus& a, const core::Torus& b,
                                                   long digits, long prec);
} // namespace

std::optional<DistanceResult> torus_pair_distance(const core::Torus& a, const core::Torus& b,
                                                  long digits) {
  if (auto r = coaxial_tori(a, b, digits)) return r;
  if (b.r > a.r)
    if (auto r = nested_tubes(a, b, true, digits)) return r;
  if (a.r > b.r)
    if (auto r = nested_tubes(b, a, false, digits)) return r;
  // A tiny gap between the tubes is a difference of O(1) quantities: when the minimum is not
  // separated from r1 + r2 at the first precision, retry with more working digits.
  for (long extra : {10L, 40L + digits, 120L + 2 * digits})
    if (auto r = circle_pair_distance(a, b, digits, bits_for(digits + extra))) return r;
  return std::nullopt;
}

namespace {

std::optional<DistanceResult> circle_pair_distance(const core::Torus& a, const core::Torus& b,
                                                   long digits, long prec) {
  const Circle c1(a, prec), c2(b, prec);
  Ball r12, r;
  set_q(r12.v, a.r, prec);
  set_q(r.v, b.r, prec);
  arb_add(r12.v, r12.v, r.v, prec);
  // lower bound over T by the mean-value form; f(t_m) itself is the upper bound
  auto bound = [&](const arb_t tm, const arb_t T, arf_t lower, arf_t upper) {
    Dual whole, at;
    circle_circle(whole, nullptr, c1, c2, T, prec);
    circle_circle(at, nullptr, c1, c2, tm, prec);
    mean_value_lower(lower, whole.v.v, whole.d.v, at.v.v, T, prec);
    arb_get_ubound_arf(upper, at.v.v, prec);
  };
  PeriodicMinimum pm;
  if (!periodic_minimize(bound, r12.v, digits, prec, pm)) return std::nullopt;
  DistanceResult res;
  res.status = Status::Certified;
  set_distance_enclosure(res, pm.enclosure.v, digits);
  for (const auto& tm : pm.minimizers) {
    Ball p[3];
    Dual f;
    circle_circle(f, &p, c1, c2, tm.v, prec);
    // nearest point of K2 to p (double), then both surface points
    const std::array<double, 3> pd = midpoint(p), q = nearest_on_core(pd, b, c2);
    const double fd = arf_get_d(arb_midref(f.v.v), ARF_RND_NEAR);
    std::array<std::array<double, 3>, 2> pr{};
    const double ra = a.r.to_double_approx(), rb = b.r.to_double_approx();
    for (size_t i = 0; i < 3; ++i) {
      const double dir = fd > 0 ? (q[i] - pd[i]) / fd : 0;
      pr[0][i] = pd[i] + ra * dir;
      pr[1][i] = q[i] - rb * dir;
    }
    res.pairs.push_back(pr);
  }
  const size_t groups = pm.minimizers.size();
  res.minimizers = Minimizers::count(static_cast<long>(groups), Minimizers::Proof::Interval);
  res.critical_candidates = static_cast<int>(groups);
  res.method = Method::TorusCirclePair;
  res.note = "disjoint tubes: distance of the core circles minus both tube radii, by branch "
             "and bound over one circle (Arb)";
  note_unproven_ties(res, groups);
  prove_groups(res, pm, c1, c2, 1, prec);
  // Tie regions (symmetry.hpp): the points K1(t) over each group of survivors, which hold
  // every minimizing t; an isometry keeping both tori maps each core circle onto itself.
  add_core_regions(res, pm, c1, c2, prec);
  return res;
}

} // namespace

} // namespace surfcert::certify
