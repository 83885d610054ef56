#include "surfcert/certify/distance/sphere_gap.hpp"

#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"

#include "surfcert/algebra/arb.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

// The ball [lower, upper] of a critical distance.
void critical_ball(arb_t out, const CriticalDistance& c, long prec) {
  Ball lo, hi;
  arb_set_str(lo.v, c.lower.c_str(), prec);
  arb_set_str(hi.v, c.upper.c_str(), prec);
  arb_union(out, lo.v, hi.v, prec);
}

} // namespace

DistanceResult sphere_quadric_gap(const std::array<Rational, 3>& c, const Rational& r2,
                                  const core::QuadricMatrix& other, long digits,
                                  bool sphere_first) {
  DistanceResult out;
  // Critical distances from the centre to the other quadric.
  //
  // The answer is d_min - r (the quadric outside the ball) or r - d_max (a compact quadric
  // inside it), with d_min = [min lower, min upper] and d_max = [max lower, max upper] taken
  // over EVERY candidate: a valid enclosure of the true extreme whatever order the double
  // midpoints propose. Which side holds is decided against these enclosures, too. The
  // subtraction cancels when the gap is small against the critical distances, so the
  // candidates are re-enclosed at more digits (the roots are exact: only the enclosures
  // narrow) until (a) the side is decided and (b) the written enclosure of the gap meets
  // upper - lower <= 10^-digits lower; failing either within the budget is undecided. Then,
  // within a smaller budget, until (c) the minimizers separate from the other candidates or are
  // proven tied (the same exact rational squared distance); otherwise the candidates left
  // overlapping the extreme are all listed, ties "unproven".
  const bool compact = other.kind() == core::QuadricKind::Ellipsoid;
  const long first = digits + 5;
  const long width_cap = std::max<long>(10 * first, digits + 2000); // cancellation budget
  const long tie_cap = 2 * digits + 40;                             // separation budget
  const int max_rounds = 12;
  long work = first;
  for (int round = 0;; ++round) {
    PointQuadricResult pq = point_quadric_critical(c, other, work);
    out.eliminated_degree = pq.sextic_degree;
    out.critical_candidates = static_cast<int>(pq.criticals.size());
    if (!pq.ok || pq.criticals.empty()) {
      out.status = Status::Undecided;
      out.note = pq.ok ? "no critical point found" : pq.note;
      return out;
    }
    const size_t n = pq.criticals.size();
    const long prec = bits_for(work + 10);
    const bool last = round + 1 >= max_rounds;
    Ball r;
    arb_set_fmpq(r.v, r2.raw(), prec);
    arb_sqrt(r.v, r.v, prec);
    std::vector<Ball> balls(n);
    arf_t minlo, minhi, maxlo, maxhi, bound;
    arf_init(minlo);
    arf_init(minhi);
    arf_init(maxlo);
    arf_init(maxhi);
    arf_init(bound);
    for (size_t i = 0; i < n; ++i) {
      critical_ball(balls[i].v, pq.criticals[i], prec);
      arb_get_lbound_arf(bound, balls[i].v, prec);
      if (i == 0 || arf_cmp(bound, minlo) < 0) arf_set(minlo, bound);
      if (i == 0 || arf_cmp(bound, maxlo) > 0) arf_set(maxlo, bound);
      arb_get_ubound_arf(bound, balls[i].v, prec);
      if (i == 0 || arf_cmp(bound, minhi) < 0) arf_set(minhi, bound);
      if (i == 0 || arf_cmp(bound, maxhi) > 0) arf_set(maxhi, bound);
    }
    Ball dmin, dmax;
    arb_set_interval_arf(dmin.v, minlo, minhi, prec);
    arb_set_interval_arf(dmax.v, maxlo, maxhi, prec);
    arf_clear(minlo);
    arf_clear(minhi);
    arf_clear(maxlo);
    arf_clear(maxhi);
    arf_clear(bound);
    int side = 0; // +1: the quadric lies outside the ball; -1: inside
    if (arb_gt(dmin.v, r.v))
      side = 1;
    else if (compact && arb_lt(dmax.v, r.v))
      side = -1;
    if (side == 0) {
      // Not meeting (the topology said so), the quadric lies on one side: only precision is
      // missing.
      if (!last && work < width_cap) {
        work = std::min(2 * work, width_cap);
        continue;
      }
      out.status = Status::Undecided;
      out.note = "could not separate the critical distances from the radius at " +
                 std::to_string(work) + " digits";
      return out;
    }
    const arb_struct* opt = side > 0 ? dmin.v : dmax.v;
    Ball d;
    if (side > 0)
      arb_sub(d.v, dmin.v, r.v, prec);
    else
      arb_sub(d.v, r.v, dmax.v, prec);
    DistanceResult trial;
    set_distance_enclosure(trial, d.v, digits);
    if (!trial.distance->meets_width(digits)) {
      if (!last && work < width_cap) {
        // Proposal: the gap loses log10(extreme / gap) digits to cancellation.
        long need = 2 * work;
        if (arb_is_positive(d.v)) {
          arf_t g;
          arf_init(g);
          arb_get_lbound_arf(g, d.v, prec);
          const slong lost =
              arf_abs_bound_lt_2exp_si(arb_midref(opt)) - arf_abs_bound_lt_2exp_si(g) + 2;
          arf_clear(g);
          need = std::max(work + 10, digits + 5 + static_cast<long>(lost * 0.302) + 1);
        }
        work = std::min(need, width_cap);
        continue;
      }
      out.status = Status::Undecided;
      out.note = "the distance is much smaller than the critical distances (cancellation): "
                 "its enclosure did not reach the requested width at " +
                 std::to_string(work) + " digits";
      return out;
    }
    // Candidates that may attain the extreme: those whose enclosure meets it.
    std::vector<size_t> S;
    for (size_t i = 0; i < n; ++i)
      if (arb_overlaps(balls[i].v, opt)) S.push_back(i);
    // Exact squared distances compare exactly: drop those beaten by another exact one.
    const Rational* ext = nullptr;
    for (size_t i : S)
      if (pq.criticals[i].d2_exact &&
          (ext == nullptr || (side > 0 ? pq.criticals[i].d2 < *ext : pq.criticals[i].d2 > *ext)))
        ext = &pq.criticals[i].d2;
    if (ext != nullptr) {
      std::vector<size_t> kept;
      for (size_t i : S)
        if (!pq.criticals[i].d2_exact || pq.criticals[i].d2 == *ext) kept.push_back(i);
      S.swap(kept);
    }
    bool all_exact = true;
    for (size_t i : S)
      all_exact = all_exact && pq.criticals[i].d2_exact; // then all equal *ext
    if (S.size() > 1 && !all_exact && !last && work < tie_cap) {
      work = std::min(2 * work, tie_cap);
      continue;
    }
    // Final: the enclosure, and one pair per remaining candidate.
    out.distance = trial.distance;
    bool continuum = false;
    const double rr = std::sqrt(r2.to_double_approx());
    for (size_t i : S) {
      const CriticalDistance& cd = pq.criticals[i];
      continuum = continuum || cd.continuum;
      // The pair: the foot point on the quadric, the sphere point on the ray from the centre.
      std::array<double, 3> f = cd.foot, s{};
      double nf = 0;
      for (size_t j = 0; j < 3; ++j)
        nf += (f[j] - c[j].to_double_approx()) * (f[j] - c[j].to_double_approx());
      nf = std::sqrt(nf);
      for (size_t j = 0; j < 3; ++j)
        s[j] = c[j].to_double_approx() + rr * (f[j] - c[j].to_double_approx()) / nf;
      out.pairs.push_back(sphere_first ? std::array<std::array<double, 3>, 2>{s, f}
                                       : std::array<std::array<double, 3>, 2>{f, s});
    }
    const auto proof = all_exact ? Minimizers::Proof::Exact : Minimizers::Proof::Interval;
    out.minimizers = continuum ? Minimizers::continuum(proof)
                               : Minimizers::count(static_cast<long>(S.size()), proof);
    out.status = Status::Certified;
    if (!continuum && S.size() > 1 && all_exact) {
      out.ties = Ties::Proven;
      out.note += std::string(out.note.empty() ? "" : "; ") + "the " + std::to_string(S.size()) +
                  " minimizing pairs are at exactly the same distance (proven: the same exact "
                  "rational squared distance from the centre to the foot points)";
    } else if (continuum && !all_exact) {
      // A circle, or isolated points: not proven which.
      out.minimizers = Minimizers::undecided(static_cast<long>(S.size()));
      // A circle of feet overlapping point candidates not proven equal to it: "infinite"
      // holds only if the circle attains the minimum, which is not proven (a note that
      // prove_ties, which drops the generic tie note for continua, leaves in place).
      out.note += std::string(out.note.empty() ? "" : "; ") +
                  "a circle of foot points and other critical points agree to the requested "
                  "precision: which of them attain the extreme (and so the minimizer count) is "
                  "not proven";
      out.ties = Ties::Unproven;
    } else if (!all_exact) {
      // Candidates left overlapping the extreme after the separation budget: all listed,
      // their equality unproven.
      note_unproven_ties(out, S.size());
    }
    return out;
  }
}

} // namespace surfcert::certify
