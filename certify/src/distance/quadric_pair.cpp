#include "surfcert/certify/distance/quadric_pair.hpp"

#include "surfcert/algebra/solution_cover.hpp"
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"

#include <arb.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace surfcert::certify {

using algebra::MPoly;
using core::Rational;

namespace {

using V3 = std::array<MPoly, 3>;

MPoly dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The offset system for one choice of roles (source S1: f, target S2: g), over Z.
struct Offset {
  const core::QuadricMatrix* source = nullptr;
  const core::QuadricMatrix* target = nullptr;
  bool source_is_a = true;
  MPoly f, g, g1, g2; // g(p + mu N) = g + mu g1 + mu^2 g2 / 2
  V3 N;               // grad f
  std::array<std::array<Rational, 3>, 3> hess_f;
  std::array<MPoly, 3> system; // f, C, G
};

Offset build_offset(const core::QuadricMatrix& src, const core::QuadricMatrix& tgt,
                    const std::array<long, 3>& l) {
  Offset o;
  o.source = &src;
  o.target = &tgt;
  o.f = algebra::quadric_poly(src.matrix());
  o.g = algebra::quadric_poly(tgt.matrix());
  V3 X, Y;
  for (int i = 0; i < 3; ++i) {
    o.N[static_cast<size_t>(i)] = o.f.derivative(i);
    X[static_cast<size_t>(i)] = o.g.derivative(i);
  }
  for (size_t i = 0; i < 3; ++i) {
    Y[i] = MPoly(0);
    for (size_t j = 0; j < 3; ++j) {
      Y[i] = Y[i] + X[i].derivative(static_cast<int>(j)) * o.N[j]; // Hess(g) N
      MPoly h = o.N[i].derivative(static_cast<int>(j));            // constant
      fmpz_t c;
      fmpz_init(c);
      fmpz_mpoly_get_coeff_fmpz_ui(c, h.raw(), std::array<ulong, 3>{0, 0, 0}.data(), MPoly::ctx());
      fmpq_set_fmpz_frac(o.hess_f[i][j].raw_mut(), c, core::Integer(1).raw());
      fmpz_clear(c);
    }
  }
  const MPoly C = dot(o.N, cross(X, Y));
  const V3 nx = cross(o.N, X), ny = cross(o.N, Y);
  MPoly P, Q;
  for (size_t i = 0; i < 3; ++i) {
    P = P + MPoly(l[i]) * nx[i];
    Q = Q + MPoly(l[i]) * ny[i];
  }
  o.g1 = dot(X, o.N);
  o.g2 = dot(o.N, Y);
  const MPoly G = MPoly(2) * o.g * Q * Q - MPoly(2) * o.g1 * P * Q + o.g2 * P * P;
  o.system = {o.f, C, G};
  return o;
}

// Discriminant of the characteristic polynomial of the quadratic block: nonzero iff the three
// eigenvalues are distinct (no axis of revolution, which would give the system a curve of
// spurious solutions when this quadric is the target).
bool distinct_eigenvalues(const core::QuadricMatrix& q) {
  auto m = [&](int i, int j) { return q(i, j); };
  Rational a = -(m(0, 0) + m(1, 1) + m(2, 2));
  Rational b = m(0, 0) * m(1, 1) - m(0, 1) * m(0, 1) + m(0, 0) * m(2, 2) - m(0, 2) * m(0, 2) +
               m(1, 1) * m(2, 2) - m(1, 2) * m(1, 2);
  Rational c = -(m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(1, 2)) -
                 m(0, 1) * (m(0, 1) * m(2, 2) - m(1, 2) * m(0, 2)) +
                 m(0, 2) * (m(0, 1) * m(1, 2) - m(1, 1) * m(0, 2)));
  Rational disc = Rational(18) * a * b * c - Rational(4) * a * a * a * c + a * a * b * b -
                  Rational(4) * b * b * b - Rational(27) * c * c;
  return !disc.is_zero();
}

bool is_plane(const core::QuadricMatrix& q) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!q(i, j).is_zero()) return false;
  return true;
}

// Balls of the kept box, and of its centre (exact rationals).
struct BoxBalls {
  Ball x[3];
  Rational centre[3];
};

void load_box(BoxBalls& bb, const algebra::SolutionCover& c, const std::array<size_t, 3>& box,
              long prec) {
  algebra::box_balls(c, box, bb.x[0].v, bb.x[1].v, bb.x[2].v, prec);
  for (size_t k = 0; k < 3; ++k)
    bb.centre[k] = (c.roots[k][box[k]].lo + c.roots[k][box[k]].hi) * Rational(1, 2);
}

std::array<const arb_struct*, 3> pt(const Ball (&x)[3]) {
  return {x[0].v, x[1].v, x[2].v};
}

// Real roots of a2 mu^2 + a1 mu + a0 = 0 (balls); false when their reality is not certain.
// Roots are written to r (0, 1 or 2 of them).
bool quadratic_roots(const arb_t a2, const arb_t a1, const arb_t a0, Ball (&r)[2], int& n,
                     long prec) {
  n = 0;
  Ball disc, t, sq;
  arb_mul(disc.v, a1, a1, prec);
  arb_mul(t.v, a2, a0, prec);
  arb_mul_2exp_si(t.v, t.v, 2);
  arb_sub(disc.v, disc.v, t.v, prec);
  if (arb_is_negative(disc.v)) return true; // no real root
  if (!arb_is_positive(disc.v)) return false;
  arb_sqrt(sq.v, disc.v, prec);
  // Stable forms: mu = -2 a0 / (a1 + s sqrt(disc)) for the root that stays finite, and
  // (-a1 - s sqrt(disc)) / (2 a2) for the other when a2 != 0 (s = sign of a1).
  Ball den;
  if (arb_is_nonnegative(a1))
    arb_add(den.v, a1, sq.v, prec);
  else
    arb_sub(den.v, a1, sq.v, prec);
  if (arb_contains_zero(den.v)) return false; // a1 = 0 = a0: degenerate, not decided here
  arb_div(r[0].v, a0, den.v, prec);
  arb_mul_2exp_si(r[0].v, r[0].v, 1);
  arb_neg(r[0].v, r[0].v);
  n = 1;
  if (arb_is_zero(a2)) return true;
  if (arb_contains_zero(a2)) return false;
  arb_neg(r[1].v, den.v);
  arb_div(r[1].v, r[1].v, a2, prec);
  arb_mul_2exp_si(r[1].v, r[1].v, -1);
  n = 2;
  return true;
}

void norm3(arb_t out, const Ball (&v)[3], long prec) {
  Ball t;
  arb_zero(out);
  for (const auto& c : v) {
    arb_sqr(t.v, c.v, prec);
    arb_add(out, out, t.v, prec);
  }
  arb_sqrtpos(out, out, prec);
}

// Lower bound (arf) of |mu| |N| over the real roots mu of g(p + mu N) = 0, p in the box:
// every closest pair whose S1 point lies in the box is at least this far apart. +inf when no
// real root exists. Uses the exact point-quadric sextic when grad f may vanish in the box.
void box_lower(arf_t out, const Offset& o, const BoxBalls& bb, long prec, long digits) {
  Ball N[3], a0, a1, a2, nrm;
  for (size_t i = 0; i < 3; ++i)
    algebra::evaluate(N[i].v, o.N[i], pt(bb.x), prec);
  if (arb_contains_zero(N[0].v) && arb_contains_zero(N[1].v) && arb_contains_zero(N[2].v)) {
    // Possibly a singular point of S1 (a cone's vertex): its closest points on S2 are the
    // feet from it, so bound dist(centre, S2) - half diagonal.
    PointQuadricResult pq = point_quadric_critical({bb.centre[0], bb.centre[1], bb.centre[2]},
                                                   *o.target, std::max<long>(digits, 15) + 5);
    if (!pq.ok || pq.criticals.empty()) {
      arf_zero(out);
      return;
    }
    Ball d, h, r;
    arb_set_str(d.v, pq.criticals.front().lower.c_str(), prec);
    for (const auto& x : bb.x) {
      arb_get_rad_arb(r.v, x.v);
      arb_sqr(r.v, r.v, prec);
      arb_add(h.v, h.v, r.v, prec);
    }
    arb_sqrt(h.v, h.v, prec);
    arb_sub(d.v, d.v, h.v, prec);
    arb_get_lbound_arf(out, d.v, prec);
    if (arf_sgn(out) < 0) arf_zero(out);
    return;
  }
  norm3(nrm.v, N, prec);
  algebra::evaluate(a0.v, o.g, pt(bb.x), prec);
  algebra::evaluate(a1.v, o.g1, pt(bb.x), prec);
  algebra::evaluate(a2.v, o.g2, pt(bb.x), prec);
  arb_mul_2exp_si(a2.v, a2.v, -1);
  Ball disc, t;
  arb_mul(disc.v, a1.v, a1.v, prec);
  arb_mul(t.v, a2.v, a0.v, prec);
  arb_mul_2exp_si(t.v, t.v, 2);
  arb_sub(disc.v, disc.v, t.v, prec);
  if (arb_is_negative(disc.v)) {
    arf_pos_inf(out); // the normal lines from this box miss S2
    return;
  }
  Ball m;
  if (!arb_contains_zero(a2.v)) {
    Ball sq, r1, r2;
    arb_sqrtpos(sq.v, disc.v, prec);
    arb_sub(r1.v, sq.v, a1.v, prec);
    arb_neg(r2.v, a1.v);
    arb_sub(r2.v, r2.v, sq.v, prec);
    arb_div(r1.v, r1.v, a2.v, prec);
    arb_div(r2.v, r2.v, a2.v, prec);
    arb_abs(r1.v, r1.v);
    arb_abs(r2.v, r2.v);
    arb_min(m.v, r1.v, r2.v, prec);
    arb_mul_2exp_si(m.v, m.v, -1);
  } else {
    // |a0| <= |a1| t + |a2| t^2 at t = |mu|: t >= 2 A0 / (A1 + sqrt(A1^2 + 4 A2 A0)).
    arf_t A0, A1, A2;
    arf_init(A0);
    arf_init(A1);
    arf_init(A2);
    arb_get_abs_lbound_arf(A0, a0.v, prec);
    arb_get_abs_ubound_arf(A1, a1.v, prec);
    arb_get_abs_ubound_arf(A2, a2.v, prec);
    Ball b0, b1, b2, s;
    arb_set_arf(b0.v, A0);
    arb_set_arf(b1.v, A1);
    arb_set_arf(b2.v, A2);
    arb_mul(s.v, b2.v, b0.v, prec);
    arb_mul_2exp_si(s.v, s.v, 2);
    arb_addmul(s.v, b1.v, b1.v, prec);
    arb_sqrt(s.v, s.v, prec);
    arb_add(s.v, s.v, b1.v, prec);
    arb_mul_2exp_si(b0.v, b0.v, 1);
    if (arf_is_zero(A0))
      arb_zero(m.v);
    else
      arb_div(m.v, b0.v, s.v, prec);
    arf_clear(A0);
    arf_clear(A1);
    arf_clear(A2);
  }
  arb_mul(m.v, m.v, nrm.v, prec);
  arb_get_lbound_arf(out, m.v, prec);
  if (arf_sgn(out) < 0) arf_zero(out);
}

struct Pair {
  Ball d; // the distance of a genuine pair (p on S1, q on S2)
  std::array<double, 3> p{}, q{};
};

// A genuine pair near the box: p on S1 on the gradient line through the centre, q on S2 on
// the normal line at p. nullopt when a root's reality is not certain at this precision.
std::optional<Pair> box_upper(const Offset& o, const BoxBalls& bb, long prec) {
  Ball c[3], n[3], b0, b1, b2, t;
  for (size_t k = 0; k < 3; ++k)
    arb_set_fmpq(c[k].v, bb.centre[k].raw(), prec);
  for (size_t k = 0; k < 3; ++k)
    algebra::evaluate(n[k].v, o.N[k], pt(c), prec);
  algebra::evaluate(b0.v, o.f, pt(c), prec);
  Ball tmp;
  for (size_t i = 0; i < 3; ++i) {
    arb_addmul(b1.v, n[i].v, n[i].v, prec);
    for (size_t j = 0; j < 3; ++j) {
      arb_mul(tmp.v, n[i].v, n[j].v, prec);
      Ball h;
      arb_set_fmpq(h.v, o.hess_f[i][j].raw(), prec);
      arb_addmul(b2.v, tmp.v, h.v, prec);
    }
  }
  arb_mul_2exp_si(b2.v, b2.v, -1);
  Ball tr[2];
  int nt = 0;
  if (!quadratic_roots(b2.v, b1.v, b0.v, tr, nt, prec) || nt == 0) return std::nullopt;
  Pair best;
  bool have = false;
  Ball p[3], N[3], a0, a1, a2, nrm;
  for (size_t k = 0; k < 3; ++k) {
    arb_set(p[k].v, c[k].v);
    arb_addmul(p[k].v, tr[0].v, n[k].v, prec); // the root nearest 0
  }
  for (size_t k = 0; k < 3; ++k)
    algebra::evaluate(N[k].v, o.N[k], pt(p), prec);
  norm3(nrm.v, N, prec);
  algebra::evaluate(a0.v, o.g, pt(p), prec);
  algebra::evaluate(a1.v, o.g1, pt(p), prec);
  algebra::evaluate(a2.v, o.g2, pt(p), prec);
  arb_mul_2exp_si(a2.v, a2.v, -1);
  Ball mu[2];
  int nm = 0;
  if (!quadratic_roots(a2.v, a1.v, a0.v, mu, nm, prec)) return std::nullopt;
  for (int r = 0; r < nm; ++r) {
    Ball d;
    arb_abs(d.v, mu[r].v);
    arb_mul(d.v, d.v, nrm.v, prec);
    if (have) {
      arf_t u1, u2;
      arf_init(u1);
      arf_init(u2);
      arb_get_ubound_arf(u1, d.v, prec);
      arb_get_ubound_arf(u2, best.d.v, prec);
      bool better = arf_cmp(u1, u2) < 0;
      arf_clear(u1);
      arf_clear(u2);
      if (!better) continue;
    }
    arb_set(best.d.v, d.v);
    double m = arf_get_d(arb_midref(mu[r].v), ARF_RND_NEAR);
    for (size_t k = 0; k < 3; ++k) {
      best.p[k] = arf_get_d(arb_midref(p[k].v), ARF_RND_NEAR);
      best.q[k] = best.p[k] + m * arf_get_d(arb_midref(N[k].v), ARF_RND_NEAR);
    }
    have = true;
  }
  if (!have) return std::nullopt;
  return best;
}

void set_decimal(std::string& s, const arf_t x, bool upper, long digits) {
  s = decimal_bound(x, upper, digits + 2);
}

} // namespace

DistanceResult quadric_pair_distance(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                     long digits) {
  DistanceResult out;
  // Roles: a plane is always the source (as the target its Hessian vanishes and C with it);
  // prefer a target with three distinct eigenvalues.
  std::vector<std::pair<bool, int>> orders; // (source is a, preference)
  for (bool src_a : {true, false}) {
    const core::QuadricMatrix& tgt = src_a ? b : a;
    if (is_plane(tgt)) continue;
    orders.emplace_back(src_a, distinct_eigenvalues(tgt) ? 0 : 1);
  }
  std::stable_sort(orders.begin(), orders.end(),
                   [](const auto& u, const auto& v) { return u.second < v.second; });
  const std::array<std::array<long, 3>, 2> ls{{{3, -5, 7}, {2, 7, -11}}};
  std::optional<Offset> off;
  algebra::SolutionCover cover;
  std::string why;
  const Rational width0(1, 16);
  for (const auto& ord : orders) {
    for (const auto& l : ls) {
      Offset o = build_offset(ord.first ? a : b, ord.first ? b : a, l);
      o.source_is_a = ord.first;
      cover = algebra::cover_real_solutions(o.system, width0);
      if (cover.ok) {
        off = std::move(o);
        break;
      }
      why = cover.note;
    }
    if (off) break;
  }
  if (!off) {
    out.status = Status::Undecided;
    out.note = "not supported yet: the offset system has a curve of solutions in every tried "
               "position (" +
               why + "; e.g. surfaces of revolution sharing an axis)";
    return out;
  }
  const Offset& o = *off;
  out.eliminated_degree = static_cast<int>(cover.eliminant_degree[0]);
  out.system_degrees = {o.system[0].total_degree(), o.system[1].total_degree(),
                        o.system[2].total_degree()};
  out.bivariate_degrees = {cover.bivariate_degree[0], cover.bivariate_degree[1]};
  out.univariate_degrees = {cover.eliminant_degree[0], cover.eliminant_degree[1],
                            cover.eliminant_degree[2]};
  out.squarefree_degrees = {cover.squarefree_degree[0], cover.squarefree_degree[1],
                            cover.squarefree_degree[2]};
  out.critical_candidates = static_cast<int>(cover.boxes.size());

  const bool compact =
      a.kind() == core::QuadricKind::Ellipsoid || b.kind() == core::QuadricKind::Ellipsoid;
  const long target_bits = static_cast<long>(digits * 3.33) + 24;
  // Widths are relative to the size of the solutions (a power of two >= every coordinate), so
  // scaling the scene by 10^8 costs no extra rounds.
  Rational magnitude(1);
  for (const auto& rs : cover.roots)
    for (const auto& r : rs)
      while (core::abs(r.lo) > magnitude || core::abs(r.hi) > magnitude)
        magnitude = magnitude * Rational(2);
  long bits = 8;
  arf_t L, U, lb, tol;
  arf_init(L);
  arf_init(U);
  arf_init(lb);
  arf_init(tol);
  std::vector<Pair> best_pairs;
  bool done = false;
  for (int round = 0; round < 40 && !done; ++round) {
    Rational width = magnitude;
    fmpq_div_2exp(width.raw_mut(), width.raw(), static_cast<ulong>(bits));
    algebra::refine_cover(cover, width);
    const long prec = algebra::precision_for_width(width) + 64;
    std::vector<arf_struct> lows(cover.boxes.size());
    for (auto& x : lows)
      arf_init(&x);
    arf_pos_inf(L);
    for (size_t i = 0; i < cover.boxes.size(); ++i) {
      BoxBalls bb;
      load_box(bb, cover, cover.boxes[i], prec);
      box_lower(&lows[i], o, bb, prec, digits);
      if (arf_cmp(&lows[i], L) < 0) arf_set(L, &lows[i]);
    }
    // Upper bounds from the boxes that may hold the minimum.
    arf_pos_inf(U);
    best_pairs.clear();
    std::vector<std::optional<Pair>> ups(cover.boxes.size());
    for (size_t i = 0; i < cover.boxes.size(); ++i) {
      if (arf_is_pos_inf(&lows[i])) continue;
      BoxBalls bb;
      load_box(bb, cover, cover.boxes[i], prec);
      ups[i] = box_upper(o, bb, prec);
      if (!ups[i]) continue;
      arb_get_ubound_arf(lb, ups[i]->d.v, prec);
      if (arf_cmp(lb, U) < 0) arf_set(U, lb);
    }
    // Drop the boxes that cannot hold the minimum; the others are the minimizer candidates.
    std::vector<std::array<size_t, 3>> kept;
    for (size_t i = 0; i < cover.boxes.size(); ++i)
      if (arf_cmp(&lows[i], U) <= 0) {
        kept.push_back(cover.boxes[i]);
        if (ups[i]) best_pairs.push_back(std::move(*ups[i]));
      }
    if (!arf_is_pos_inf(U)) cover.boxes = std::move(kept);
    for (auto& x : lows)
      arf_clear(&x);
    // Done when (U - L) <= 2^-target_bits L.
    if (!arf_is_pos_inf(U) && arf_sgn(L) > 0) {
      arf_sub(tol, U, L, prec, ARF_RND_UP);
      arf_mul_2exp_si(lb, L, -target_bits);
      if (arf_cmp(tol, lb) <= 0) done = true;
    }
    if (bits >= 2 * target_bits + 256) break;
    bits = std::min(2 * bits, 2 * target_bits + 256);
  }
  if (arf_is_pos_inf(U) || arf_sgn(L) < 0) {
    out.status = Status::Undecided;
    out.note = "no certified pair of points found at the working precision";
    arf_clear(L);
    arf_clear(U);
    arf_clear(lb);
    arf_clear(tol);
    return out;
  }
  set_decimal(out.lower, L, false, digits);
  set_decimal(out.upper, U, true, digits);
  out.approx = 0.5 * (arf_get_d(L, ARF_RND_NEAR) + arf_get_d(U, ARF_RND_NEAR));
  for (const auto& bp : best_pairs)
    out.pairs.push_back(o.source_is_a ? std::array<std::array<double, 3>, 2>{bp.p, bp.q}
                                      : std::array<std::array<double, 3>, 2>{bp.q, bp.p});
  out.minimizers = std::to_string(cover.boxes.size());
  if (!compact) {
    out.status = Status::Undecided;
    out.note = "neither surface is bounded: the minimum over the critical pairs is enclosed, "
               "but the infimum may lie at infinity";
    out.lower = "0";
  } else if (!done) {
    out.status = Status::Undecided;
    out.note = "the enclosure did not reach the requested width";
  } else {
    out.status = Status::Certified;
    if (cover.boxes.size() > 1)
      out.note = "several critical pairs at distances that agree to the requested precision: "
                 "listed as minimizers (their equality is not proven)";
  }
  arf_clear(L);
  arf_clear(U);
  arf_clear(lb);
  arf_clear(tol);
  return out;
}

} // namespace surfcert::certify
