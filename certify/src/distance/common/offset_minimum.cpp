#include "surfcert/certify/distance/offset_minimum.hpp"

#include "surfcert/algebra/real_roots.hpp"

#include <flint/fmpz_poly_factor.h>

#include <algorithm>
#include <string>
#include <vector>

namespace surfcert::certify {

using core::Poly3;
using core::Rational;

std::array<const arb_struct*, 3> ball_point(const Ball (&x)[3]) {
  return {x[0].v, x[1].v, x[2].v};
}

void ball_norm(arb_t out, const Ball (&v)[3], long prec) {
  Ball t;
  arb_zero(out);
  for (const auto& c : v) {
    arb_sqr(t.v, c.v, prec);
    arb_add(out, out, t.v, prec);
  }
  arb_sqrtpos(out, out, prec);
}

bool ball_quadratic_roots(const arb_t a2, const arb_t a1, const arb_t a0, Ball (&r)[2], int& n,
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
  // Stable forms: t = -2 a0 / (a1 + s sqrt(disc)) for the root of smaller magnitude, and
  // (-a1 - s sqrt(disc)) / (2 a2) for the other when a2 != 0 (s = sign of a1).
  Ball den;
  if (arb_is_nonnegative(a1))
    arb_add(den.v, a1, sq.v, prec);
  else
    arb_sub(den.v, a1, sq.v, prec);
  if (arb_contains_zero(den.v)) return false;
  arb_div(r[0].v, a0, den.v, prec);
  arb_mul_2exp_si(r[0].v, r[0].v, 1);
  arb_neg(r[0].v, r[0].v);
  n = 1;
  // r[0] is a root for every a2 in its ball, 0 included (then the equation is linear and r[0]
  // its root -a0 / a1: den != 0 rules out s = -sign(a1) there). So an a2 that may be 0 costs
  // only the other root (at infinity when a2 = 0), not r[0]: a point exactly where a2 = 0
  // (a normal line parallel to a cone's generator) is common at symmetric minimizers, and no
  // precision can prove a2 != 0 there.
  if (arb_contains_zero(a2)) return true;
  arb_neg(r[1].v, den.v);
  arb_div(r[1].v, r[1].v, a2, prec);
  arb_mul_2exp_si(r[1].v, r[1].v, -1);
  n = 2;
  return true;
}

SourceQuadric::SourceQuadric(core::Poly3 f_any) : f(std::move(f_any)) {
  for (size_t i = 0; i < 3; ++i)
    N[i] = f.derivative(static_cast<int>(i));
}

namespace {

// A point of f = 0 on the line c + t n (n = grad f(c)): the real root t of the exact
// univariate polynomial closest to 0 (isolated exactly, enclosed by a ball).
bool project_general(const Poly3& f, const std::array<Poly3, 3>& N, const Rational (&c)[3],
                     Ball (&p)[3], long prec) {
  Rational n[3];
  for (size_t i = 0; i < 3; ++i)
    n[i] = N[i].evaluate(c[0], c[1], c[2]);
  algebra::UPolyQ u; // f(c + t n), term by term
  f.for_each_term([&](const Poly3::Exponent& e, const Rational& co) {
    algebra::UPolyQ t(co);
    for (size_t j = 0; j < 3; ++j) {
      algebra::UPolyQ lin = algebra::UPolyQ::from_coeffs({c[j], n[j]});
      for (int m = 0; m < e[j]; ++m)
        t = t * lin;
    }
    u = u + t;
  });
  if (u.degree() <= 0) return false;
  algebra::UPolyZ z = u.primitive_integer();
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  fmpz_poly_factor_squarefree(fac, z.raw());
  algebra::UPolyZ sq;
  fmpz_poly_one(sq.raw_mut());
  for (slong i = 0; i < fac->num; ++i)
    fmpz_poly_mul(sq.raw_mut(), sq.raw(), fac->p + i);
  fmpz_poly_factor_clear(fac);
  algebra::RootSeparation s = algebra::isolate_real_roots(sq);
  if (s.num_roots() == 0) return false;
  std::optional<std::pair<Rational, Rational>> best;
  Rational w(1);
  fmpq_div_2exp(w.raw_mut(), w.raw(), static_cast<ulong>(prec));
  for (size_t i = 0; i + 1 < s.separators.size(); ++i) {
    Rational lo = s.separators[i], hi = s.separators[i + 1];
    algebra::refine_root(sq, lo, hi, w);
    const Rational mag = core::abs(lo + hi);
    if (!best || mag < core::abs(best->first + best->second)) best = std::make_pair(lo, hi);
  }
  Ball t, hi;
  arb_set_fmpq(t.v, best->first.raw(), prec);
  arb_set_fmpq(hi.v, best->second.raw(), prec);
  arb_union(t.v, t.v, hi.v, prec);
  for (size_t i = 0; i < 3; ++i) {
    Ball ci, ni;
    arb_set_fmpq(ci.v, c[i].raw(), prec);
    arb_set_fmpq(ni.v, n[i].raw(), prec);
    arb_mul(p[i].v, t.v, ni.v, prec);
    arb_add(p[i].v, p[i].v, ci.v, prec);
  }
  return true;
}

} // namespace

SourceQuadric::SourceQuadric(const core::QuadricMatrix& q)
    : quadric(&q), f(algebra::quadric_poly(q.matrix())) {
  for (size_t i = 0; i < 3; ++i)
    N[i] = f.derivative(static_cast<int>(i));
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      hess[i][j] = N[i].derivative(static_cast<int>(j)).coeff(0, 0, 0); // a constant
    }
}

bool SourceQuadric::project(const Rational (&c)[3], Ball (&p)[3], long prec) const {
  if (project_on_normal(c, p, prec)) return true;
  // c itself on S1 (then t = 0 is the root nearest c), decided exactly: the fallback where the
  // normal line gives no certified root, as at a singular point of S1 (grad f(c) = 0: no line
  // at all), where box centres sit exactly at symmetric inputs (an exact rational apex).
  if (!f.evaluate(c[0], c[1], c[2]).is_zero()) return false;
  for (size_t k = 0; k < 3; ++k)
    arb_set_fmpq(p[k].v, c[k].raw(), prec);
  return true;
}

bool SourceQuadric::project_on_normal(const Rational (&c)[3], Ball (&p)[3], long prec) const {
  if (f.total_degree() > 2) return project_general(f, N, c, p, prec);
  // f(c + t n) = f(c) + t |n|^2 + t^2 n^T H n / 2 with n = grad f(c): exact coefficients.
  Ball cb[3], n[3], b0, b1, b2, tmp, h;
  for (size_t k = 0; k < 3; ++k)
    arb_set_fmpq(cb[k].v, c[k].raw(), prec);
  for (size_t k = 0; k < 3; ++k)
    algebra::evaluate(n[k].v, N[k], ball_point(cb), prec);
  algebra::evaluate(b0.v, f, ball_point(cb), prec);
  for (size_t i = 0; i < 3; ++i) {
    arb_addmul(b1.v, n[i].v, n[i].v, prec);
    for (size_t j = 0; j < 3; ++j) {
      arb_mul(tmp.v, n[i].v, n[j].v, prec);
      arb_set_fmpq(h.v, hess[i][j].raw(), prec);
      arb_addmul(b2.v, tmp.v, h.v, prec);
    }
  }
  arb_mul_2exp_si(b2.v, b2.v, -1);
  Ball tr[2];
  int nt = 0;
  if (!ball_quadratic_roots(b2.v, b1.v, b0.v, tr, nt, prec) || nt == 0) return false;
  for (size_t k = 0; k < 3; ++k) {
    arb_set(p[k].v, cb[k].v);
    arb_addmul(p[k].v, tr[0].v, n[k].v, prec);
  }
  return true;
}

int certified_sign_near(const SourceQuadric& src, const Poly3& h, const algebra::SolutionCover& c,
                        const std::array<size_t, 3>& box, long prec, std::array<double, 3>* at) {
  Rational centre[3];
  for (size_t k = 0; k < 3; ++k)
    centre[k] = (c.roots[k][box[k]].lo + c.roots[k][box[k]].hi) * Rational(1, 2);
  Ball p[3], v;
  if (!src.project(centre, p, prec)) return 0;
  algebra::evaluate(v.v, h, ball_point(p), prec);
  const int s = arb_is_positive(v.v) ? 1 : arb_is_negative(v.v) ? -1 : 0;
  if (s != 0 && at)
    for (size_t k = 0; k < 3; ++k)
      (*at)[k] = arf_get_d(arb_midref(p[k].v), ARF_RND_NEAR);
  return s;
}

namespace {

bool upper_less(const Ball& a, const Ball& b, long prec) {
  arf_t u1, u2;
  arf_init(u1);
  arf_init(u2);
  arb_get_ubound_arf(u1, a.v, prec);
  arb_get_ubound_arf(u2, b.v, prec);
  bool r = arf_cmp(u1, u2) < 0;
  arf_clear(u1);
  arf_clear(u2);
  return r;
}

// Tie regions (symmetry.hpp) from the kept boxes: every closest source point solves the system,
// so lies in a kept box; a box whose three intervals each meet no other root interval of
// their eliminant holds at most one solution (each coordinate is then that interval's root).
// Boxes failing the test leave the tie unproven (no regions).
void add_tie_regions(DistanceResult& out, const algebra::SolutionCover& cover) {
  if (cover.boxes.size() < 2) return;
  for (const auto& b : cover.boxes)
    for (size_t k = 0; k < 3; ++k) {
      const auto& r = cover.roots[k][b[k]];
      for (size_t m = 0; m < cover.roots[k].size(); ++m)
        if (m != b[k] && !(cover.roots[k][m].hi < r.lo || cover.roots[k][m].lo > r.hi)) return;
    }
  for (const auto& b : cover.boxes) {
    Ball x[3];
    algebra::box_balls(cover, b, x[0].v, x[1].v, x[2].v, 128);
    std::vector<std::array<double, 2>> reg;
    for (const Ball& c : x)
      reg.push_back(outward_interval(c.v));
    out.tie_regions.push_back(std::move(reg));
  }
  out.tie_directions = false;
}

} // namespace

void minimize_over_cover(algebra::SolutionCover& cover, const SourceQuadric& src,
                         const MinimumTarget& tgt, long digits, bool source_is_a, bool compact,
                         DistanceResult& out) {
  // The degrees of the eliminated polynomials (compare seed 000 Table 1), from the cover.
  const size_t dims = static_cast<size_t>(cover.dims);
  out.eliminated_degree = static_cast<int>(cover.eliminant_degree[0]);
  out.system_degrees.clear();
  out.univariate_degrees.clear();
  out.squarefree_degrees.clear();
  for (size_t k = 0; k < dims; ++k) {
    out.system_degrees.push_back(cover.system[k].total_degree());
    out.univariate_degrees.push_back(cover.eliminant_degree[k]);
    out.squarefree_degrees.push_back(cover.squarefree_degree[k]);
  }
  out.bivariate_degrees = {cover.bivariate_degree[0], cover.bivariate_degree[1]};
  const long target_bits = static_cast<long>(static_cast<double>(digits) * 3.33) + 24;
  // Widths are relative to the size of the solutions (a power of two >= every coordinate), so
  // a scene scaled by 10^8 needs no extra rounds.
  Rational magnitude(1);
  for (const auto& rs : cover.roots)
    for (const auto& r : rs)
      while (core::abs(r.lo) > magnitude || core::abs(r.hi) > magnitude)
        magnitude = magnitude * Rational(2);
  long bits = 8;
  Arf L, U, lb, tol;
  std::vector<CandidatePair> best;
  bool done = false, counted = false;
  for (int round = 0; round < 40 && !done; ++round) {
    if (bits >= 32 && !counted) bits = 32; // one round exactly at 2^-32 for the count
    Rational width = magnitude;
    fmpq_div_2exp(width.raw_mut(), width.raw(), static_cast<ulong>(bits));
    algebra::refine_cover(cover, width);
    const long prec = algebra::precision_for_width(width) + 64;
    std::vector<Arf> lows(cover.boxes.size());
    std::vector<std::optional<CandidatePair>> ups(cover.boxes.size());
    arf_pos_inf(L.v);
    arf_pos_inf(U.v);
    for (size_t i = 0; i < cover.boxes.size(); ++i) {
      Ball box[3];
      Rational centre[3];
      algebra::box_balls(cover, cover.boxes[i], box[0].v, box[1].v, box[2].v, prec);
      for (size_t k = 0; k < 3; ++k) {
        const auto& r = cover.roots[k][cover.boxes[i][k]];
        centre[k] = (r.lo + r.hi) * Rational(1, 2);
      }
      tgt.lower(lows[i].v, box, centre, prec);
      // A NaN bound (an Arb indeterminate) bounds nothing: 0, never a box silently left out of L
      // (arf_cmp with NaN is 0, so a NaN would neither lower L nor drop the box).
      if (arf_is_nan(lows[i].v)) arf_zero(lows[i].v);
      if (arf_cmp(lows[i].v, L.v) < 0) arf_set(L.v, lows[i].v);
      if (arf_is_pos_inf(lows[i].v)) continue;
      Ball p[3];
      if (src.project(centre, p, prec)) ups[i] = tgt.upper(p, prec);
      if (!ups[i]) continue;
      arb_get_ubound_arf(lb.v, ups[i]->d.v, prec);
      if (arf_cmp(lb.v, U.v) < 0) arf_set(U.v, lb.v);
    }
    if (!arf_is_pos_inf(U.v) && arf_sgn(L.v) > 0) {
      arf_sub(tol.v, U.v, L.v, prec, ARF_RND_UP);
      arf_mul_2exp_si(lb.v, L.v, -target_bits);
      if (arf_cmp(tol.v, lb.v) <= 0) done = true;
    }
    // Drop the boxes that cannot hold the minimum; the others are the minimizer candidates.
    // Not before 2^-32 (the boxes counted as critical candidates are the real ones by then)
    // unless already done (exact rational solutions give boxes of width 0).
    if (!counted && (bits >= 32 || done)) { // phantom boxes are gone by 2^-32
      out.critical_candidates = static_cast<int>(cover.boxes.size());
      counted = true;
    }
    if (!arf_is_pos_inf(U.v) && (bits >= 32 || done)) {
      std::vector<std::array<size_t, 3>> kept;
      best.clear();
      for (size_t i = 0; i < cover.boxes.size(); ++i)
        if (arf_cmp(lows[i].v, U.v) <= 0) {
          kept.push_back(cover.boxes[i]);
          if (ups[i]) best.push_back(std::move(*ups[i]));
        }
      cover.boxes = std::move(kept);
    }
    if (bits >= 2 * target_bits + 256) break;
    bits = std::min(2 * bits, 2 * target_bits + 256);
  }
  if (!counted) out.critical_candidates = static_cast<int>(cover.boxes.size());
  if (arf_is_pos_inf(U.v) || arf_sgn(L.v) < 0) {
    out.status = Status::Undecided;
    out.note = "no certified pair of points found at the working precision";
    return;
  }
  out.distance = Enclosure::from_bounds(L.v, U.v, digits);
  std::sort(best.begin(), best.end(), [&](const CandidatePair& a, const CandidatePair& b) {
    return upper_less(a.d, b.d, 128);
  });
  for (const auto& bp : best)
    out.pairs.push_back(source_is_a ? std::array<std::array<double, 3>, 2>{bp.p, bp.q}
                                    : std::array<std::array<double, 3>, 2>{bp.q, bp.p});
  out.minimizers =
      Minimizers::count(static_cast<long>(cover.boxes.size()), Minimizers::Proof::Interval);
  if (!compact) {
    out.status = Status::Undecided;
    out.note = "neither surface is bounded: the minimum over the critical pairs is enclosed, "
               "but the infimum may lie at infinity";
    out.distance = Enclosure::up_to(U.v, digits);
  } else if (!done) {
    out.status = Status::Undecided;
    out.note = "the enclosure did not reach the requested width";
    out.width_short = true;
  } else {
    out.status = Status::Certified;
    note_unproven_ties(out, cover.boxes.size());
    add_tie_regions(out, cover);
  }
}

bool refuse_beyond_offset_degree(const core::Poly3& f, DistanceResult& out) {
  if (f.total_degree() <= core::kMaxOffsetDegree) return false;
  out.status = Status::Undecided;
  out.note = "the exact offset system is not attempted beyond degree " +
             std::to_string(core::kMaxOffsetDegree) +
             " (its resultants grow too large); the branch and bound did not decide";
  return true;
}

} // namespace surfcert::certify
