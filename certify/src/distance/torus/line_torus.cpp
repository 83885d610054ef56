// line_torus_distance (degenerate_locus.hpp): a line x(t) = p + t d against a ring torus
// (centre c, axis a, radii R > r), through the core circle K.
//
// With w = p - c, the squared distance from x(t) to c is Q(t) = |w + t d|^2, its squared height
// over K's plane H(t) = ((w + t d).a)^2 / |a|^2 and its squared distance from the axis
// P(t) = Q - H (all three quadratics over Q), so dist(x(t), K)^2 = F(t) = Q + R^2 - 2 R sqrt(P).
// - P = 0 identically: the line is the axis; F = Q + R^2 is least at the foot of c (exact),
//   F >= R^2 > r^2, and the nearest torus points form a circle (a continuum).
// - Otherwise the torus quartic along the line, T(t) = (Q + R^2 - r^2)^2 - 4 R^2 P (leading
//   coefficient |d|^4 != 0: no line lies on a torus), has a real root iff the line meets the
//   torus (a ring torus's quartic vanishes exactly on the tube); its distinct real roots,
//   counted exactly (Sturm on its irreducible factors), are the meeting points. Tangency is a
//   double root: decided exactly, never by a float.
// - No real root of T: the line lies outside the solid tube (F > r^2 everywhere), so
//   d(L, torus) = min_t sqrt(F(t)) - r. F is continuous and tends to infinity, so its minimum
//   is attained. Where P(t) > 0, F is smooth and F' = Q' - R P' / sqrt(P) = 0 implies
//   G = Q'^2 P - R^2 P'^2 = 0 (a polynomial of degree <= 4, nonzero when P is not: see
//   below). Where P(t0) = 0 (the line crosses the axis, P = k (t - t0)^2 with k > 0), F(t) -
//   F(t0) = Q'(t0)(t - t0) - 2 R sqrt(k) |t - t0| + O((t - t0)^2) is negative on one side: t0
//   is no minimum and is left out (it is an exact rational root of G). The minimum is the least
//   value of F over the remaining real roots of G, isolated exactly (its irreducible factors
//   have distinct roots), refined, and F enclosed in Arb balls over the root intervals; a
//   spurious root (Q' sqrt(P) = -R P') only adds a value >= the minimum. Candidates whose
//   enclosures stay above the least upper bound are excluded; each remaining one is one
//   minimizer (an off-axis point has one nearest point on K, hence on the torus); several left
//   are reported as ties (their regions handed to the symmetry proof).
// G != 0 when P != 0: if P > 0 is irreducible over R, P divides R^2 P'^2 only when P' = 0, and
// then G = Q'^2 P != 0 (Q' has leading coefficient 2 |d|^2); if P = k (t - t0)^2, G = 0 would
// need Q'^2 = 4 R^2 k, a constant.
#include "surfcert/certify/distance/degenerate_locus.hpp"
#include "surfcert/core/rational_vec3.hpp"

#include "surfcert/certify/distance/ball.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/upoly.hpp"

#include <arb_poly.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace surfcert::certify {

using algebra::UPolyQ;
using algebra::UPolyZ;
using core::dot;
using core::Rational;

namespace {

using Vec3 = std::array<Rational, 3>;
using Point = std::array<double, 3>;

Point approx(const Vec3& v) {
  return {v[0].to_double_approx(), v[1].to_double_approx(), v[2].to_double_approx()};
}
UPolyQ quadratic(const Rational& c0, const Rational& c1, const Rational& c2) {
  return UPolyQ::from_coeffs({c0, c1, c2});
}
UPolyQ derivative(const UPolyQ& p) {
  UPolyQ d;
  fmpq_poly_derivative(d.raw_mut(), p.raw());
  return d;
}

// The line, the torus and the quadratics Q, H, P of the header comment.
struct Setup {
  Point p, d, c, n; // doubles, for the display pairs (n: the unit axis, approximately)
  double Rd = 0, rd = 0;
  UPolyQ Q, P;
  Rational R, R2;
};

// The display point of the torus nearest to x (x off the axis and outside the tube; on the
// axis, one point of the circle of nearest points).
Point nearest_torus_point(const Setup& s, const Point& x) {
  double v[3], h = 0;
  for (int i = 0; i < 3; ++i) {
    v[i] = x[i] - s.c[i];
    h += v[i] * s.n[i];
  }
  double rad[3], rn = 0;
  for (int i = 0; i < 3; ++i) {
    rad[i] = v[i] - h * s.n[i];
    rn += rad[i] * rad[i];
  }
  rn = std::sqrt(rn);
  if (!(rn > 1e-300)) { // on the axis: any radial direction
    const double e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (std::fabs(s.n[i]) < std::fabs(s.n[k])) k = i;
    const double dn = e[k][0] * s.n[0] + e[k][1] * s.n[1] + e[k][2] * s.n[2];
    rn = 0;
    for (int i = 0; i < 3; ++i) {
      rad[i] = e[k][i] - dn * s.n[i];
      rn += rad[i] * rad[i];
    }
    rn = std::sqrt(rn);
  }
  Point k, y;
  double kx = 0;
  for (int i = 0; i < 3; ++i) {
    k[i] = s.c[i] + s.Rd * rad[i] / rn;
    kx += (x[i] - k[i]) * (x[i] - k[i]);
  }
  kx = std::sqrt(kx);
  for (int i = 0; i < 3; ++i)
    y[i] = kx > 0 ? k[i] + s.rd * (x[i] - k[i]) / kx : k[i];
  return y;
}

void add_pair(DistanceResult& out, const Point& on_line, const Point& on_torus, bool line_first) {
  out.pairs.push_back(line_first ? std::array<Point, 2>{on_line, on_torus}
                                 : std::array<Point, 2>{on_torus, on_line});
}
Point at(const Setup& s, double t) {
  return {s.p[0] + t * s.d[0], s.p[1] + t * s.d[1], s.p[2] + t * s.d[2]};
}

// The ball holding [lo, hi] (exact rationals).
void interval_ball(arb_t x, const Rational& lo, const Rational& hi, long prec) {
  const Rational mid = (lo + hi) / Rational(2), rad = (hi - lo) / Rational(2);
  arb_set_fmpq(x, mid.raw(), prec);
  Ball e;
  arb_set_fmpq(e.v, rad.raw(), prec);
  arb_add_error(x, e.v);
}

void evaluate(arb_t y, const UPolyQ& f, const arb_t x, long prec) {
  arb_poly_t a;
  arb_poly_init(a);
  arb_poly_set_fmpq_poly(a, f.raw(), prec);
  arb_poly_evaluate(y, a, x, prec);
  arb_poly_clear(a);
}

// F(t) = Q + R^2 - 2 R sqrt(P) over the ball t (P >= 0 on the reals: sqrtpos).
void objective(arb_t F, const Setup& s, const arb_t t, long prec) {
  Ball q, pp, R2, Rb;
  evaluate(q.v, s.Q, t, prec);
  evaluate(pp.v, s.P, t, prec);
  arb_sqrtpos(pp.v, pp.v, prec);
  arb_set_fmpq(R2.v, s.R2.raw(), prec);
  arb_set_fmpq(Rb.v, s.R.raw(), prec);
  arb_mul(pp.v, pp.v, Rb.v, prec);
  arb_mul_2exp_si(pp.v, pp.v, 1);
  arb_add(F, q.v, R2.v, prec);
  arb_sub(F, F, pp.v, prec);
}

// d = sqrt(F) - r as an enclosure; true when it meets the width at `digits`.
bool distance_from(DistanceResult& out, const arb_t F, const Rational& r, long digits, long prec) {
  Ball d, rb;
  arb_sqrtpos(d.v, F, prec);
  arb_set_fmpq(rb.v, r.raw(), prec);
  arb_sub(d.v, d.v, rb.v, prec);
  set_distance_enclosure(out, d.v, digits);
  return arb_is_positive(d.v) && out.distance->meets_width(digits);
}

// Precision steps: from bits_for(digits + 10), doubling, up to this many bits (the caller's
// width contract retries beyond).
constexpr long kMaxPrecision = 1L << 16;

// One candidate root of G: exact (lo == hi) or the only root of the irreducible f in (lo, hi).
struct Candidate {
  UPolyZ f;
  Rational lo, hi;
  bool exact = false;
};

DistanceResult certified_result(long candidates, long degree) {
  DistanceResult out;
  out.status = Status::Certified;
  out.method = Method::LineLocus;
  out.critical_candidates = static_cast<int>(candidates);
  out.eliminated_degree = static_cast<int>(degree);
  return out;
}

} // namespace

std::optional<DistanceResult> line_torus_distance(const RealLocus& line, const core::Torus& tor,
                                                  bool line_first, long digits) {
  if (line.kind != RealLocus::Kind::Line) return std::nullopt;
  const Vec3& d = line.direction;
  const Vec3 w = {line.point[0] - tor.centre[0], line.point[1] - tor.centre[1],
                  line.point[2] - tor.centre[2]};
  const Vec3& a = tor.axis;
  const Rational A = dot(d, d), B = dot(w, d), C = dot(w, w), al = dot(w, a), be = dot(d, a),
                 N = dot(a, a);
  Setup s;
  s.p = approx(line.point);
  s.d = approx(d);
  s.c = approx(tor.centre);
  const double nn = std::sqrt(N.to_double_approx());
  s.n = {a[0].to_double_approx() / nn, a[1].to_double_approx() / nn, a[2].to_double_approx() / nn};
  s.Rd = tor.R.to_double_approx();
  s.rd = tor.r.to_double_approx();
  s.R = tor.R;
  s.R2 = tor.R * tor.R;
  s.Q = quadratic(C, Rational(2) * B, A);
  const UPolyQ H = quadratic(al * al / N, Rational(2) * al * be / N, be * be / N);
  s.P = s.Q - H;
  const long prec0 = bits_for(digits + 10);

  if (s.P.is_zero()) {
    // The axis: F = Q + R^2, least at t = -B / A, exactly.
    const Rational t = -B / A, F = C - B * B / A + s.R2;
    DistanceResult out = certified_result(1, 0);
    for (long prec = prec0;; prec *= 2) {
      Ball Fb;
      arb_set_fmpq(Fb.v, F.raw(), prec);
      if (distance_from(out, Fb.v, tor.r, digits, prec) || 2 * prec > kMaxPrecision) break;
    }
    out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
    const Point x = at(s, t.to_double_approx());
    add_pair(out, x, nearest_torus_point(s, x), line_first);
    out.note = "the line is the torus's axis: every point of the core circle is at the same "
               "distance from the axis point nearest the centre (exact squared distance), a "
               "circle of nearest points";
    return out;
  }

  // Contact: the torus quartic along the line, exactly.
  const UPolyQ shifted = s.Q + UPolyQ(s.R2 - tor.r * tor.r);
  const UPolyQ T = shifted * shifted - UPolyQ(Rational(4) * s.R2) * s.P;
  long meets = 0;
  std::vector<double> meeting;
  for (const auto& f : algebra::irreducible_factors(T.primitive_integer())) {
    const algebra::RootSeparation sep = algebra::isolate_real_roots(f.poly);
    meets += static_cast<long>(sep.num_roots());
    for (size_t i = 0; i + 1 < sep.separators.size(); ++i) {
      Rational lo = sep.separators[i], hi = sep.separators[i + 1];
      algebra::refine_root(f.poly, lo, hi, Rational(1, 1UL << 50));
      meeting.push_back(((lo + hi) / Rational(2)).to_double_approx());
    }
  }
  if (meets > 0) {
    DistanceResult out = certified_result(meets, T.degree());
    out.distance = Enclosure::zero();
    out.minimizers = Minimizers::count(meets, Minimizers::Proof::Exact);
    std::sort(meeting.begin(), meeting.end());
    for (double t : meeting) {
      const Point x = at(s, t);
      add_pair(out, x, x, line_first);
    }
    // One meeting point is a tangency: T > 0 far out on both sides, so a simple root would
    // come with a second sign change.
    const bool tangent = meets == 1;
    out.note = tangent ? "the line touches the torus at one point (a double real root of the "
                         "torus quartic along the line, exactly)"
                       : "the line meets the torus at " + std::to_string(meets) + " point" +
                             (meets == 1 ? "" : "s") +
                             " (the distinct real roots of the torus quartic along the line, "
                             "counted exactly)";
    return out;
  }

  // Apart: the least value of F over the real roots of G.
  const UPolyQ dQ = derivative(s.Q), dP = derivative(s.P);
  const UPolyQ G = dQ * dQ * s.P - UPolyQ(s.R2) * dP * dP;
  std::vector<Candidate> cand;
  for (const auto& f : algebra::irreducible_factors(G.primitive_integer())) {
    if (f.poly.degree() == 1) {
      Candidate c;
      c.lo = -Rational(f.poly.coeff(0)) / Rational(f.poly.coeff(1));
      c.hi = c.lo;
      c.exact = true;
      if (s.P.evaluate(c.lo).is_zero()) continue; // the line crosses the axis there: no minimum
      c.f = f.poly;
      cand.push_back(std::move(c));
      continue;
    }
    const algebra::RootSeparation sep = algebra::isolate_real_roots(f.poly);
    for (size_t i = 0; i + 1 < sep.separators.size(); ++i) {
      Candidate c;
      c.f = f.poly;
      c.lo = sep.separators[i];
      c.hi = sep.separators[i + 1];
      cand.push_back(std::move(c));
    }
  }
  DistanceResult out = certified_result(static_cast<long>(cand.size()), G.degree());
  if (cand.empty()) { // cannot happen: F attains its minimum at a root of G
    out.status = Status::Undecided;
    out.note = "the line misses the torus (exact), but no critical point of the distance to "
               "the core circle was found";
    return out;
  }
  std::vector<size_t> tied;
  std::vector<Ball> values(cand.size());
  for (long prec = prec0;; prec *= 2) {
    Rational width(1); // 2^-prec
    fmpq_div_2exp(width.raw_mut(), width.raw(), static_cast<ulong>(prec));
    arf_t lo, hi;
    arf_init(lo);
    arf_init(hi);
    arf_pos_inf(lo);
    arf_pos_inf(hi);
    for (size_t i = 0; i < cand.size(); ++i) {
      Candidate& c = cand[i];
      Ball t;
      if (c.exact) {
        arb_set_fmpq(t.v, c.lo.raw(), prec);
      } else {
        if (c.hi - c.lo > width) algebra::refine_root(c.f, c.lo, c.hi, width);
        interval_ball(t.v, c.lo, c.hi, prec);
      }
      objective(values[i].v, s, t.v, prec);
      arf_t l, u;
      arf_init(l);
      arf_init(u);
      arb_get_lbound_arf(l, values[i].v, prec);
      arb_get_ubound_arf(u, values[i].v, prec);
      if (arf_cmp(l, lo) < 0) arf_set(lo, l);
      if (arf_cmp(u, hi) < 0) arf_set(hi, u);
      arf_clear(l);
      arf_clear(u);
    }
    // The minimum lies in [lo, hi]; the candidates whose enclosures reach below hi remain.
    Ball Fmin;
    arb_set_interval_arf(Fmin.v, lo, hi, prec);
    tied.clear();
    for (size_t i = 0; i < cand.size(); ++i) {
      arf_t l;
      arf_init(l);
      arb_get_lbound_arf(l, values[i].v, prec);
      if (arf_cmp(l, hi) <= 0) tied.push_back(i);
      arf_clear(l);
    }
    arf_clear(lo);
    arf_clear(hi);
    const bool width_ok = distance_from(out, Fmin.v, tor.r, digits, prec);
    // Several left: more precision separates distinct values (equal ones stay tied).
    const bool settled = width_ok && (tied.size() == 1 || prec >= 4 * prec0);
    if (settled || 2 * prec > kMaxPrecision) break;
  }
  out.minimizers = Minimizers::count(static_cast<long>(tied.size()), Minimizers::Proof::Interval);
  for (size_t i : tied) {
    const Candidate& c = cand[i];
    const Point x = at(s, ((c.lo + c.hi) / Rational(2)).to_double_approx());
    add_pair(out, x, nearest_torus_point(s, x), line_first);
  }
  out.note = "a line missing the torus (no real root of the torus quartic along it, exact): the "
             "distance from the core circle minus r, least over the critical points of the "
             "squared distance (roots of a degree-" +
             std::to_string(G.degree()) + " polynomial, isolated exactly, values in Arb balls)";
  if (tied.size() > 1) {
    note_unproven_ties(out, tied.size());
    // Regions (symmetry.hpp): boxes around the line points over each tied root interval.
    // Every minimizer is one of them; a box meets the line in (an outward rounding of) its
    // interval, so pairwise disjoint boxes hold one tied root each, the only possible minimizer
    // there. Boxes that are not disjoint are not handed on (the tie stays unproven).
    const long prec = 128;
    std::vector<std::vector<std::array<double, 2>>> regions;
    for (size_t i : tied) {
      Ball t;
      interval_ball(t.v, cand[i].lo, cand[i].hi, prec);
      std::vector<std::array<double, 2>> reg;
      for (size_t k = 0; k < 3; ++k) {
        Ball x, dk;
        arb_set_fmpq(x.v, line.point[k].raw(), prec);
        arb_set_fmpq(dk.v, d[k].raw(), prec);
        arb_addmul(x.v, dk.v, t.v, prec);
        reg.push_back(outward_interval(x.v));
      }
      regions.push_back(std::move(reg));
    }
    bool disjoint = true;
    for (size_t i = 0; i < regions.size(); ++i)
      for (size_t j = i + 1; j < regions.size(); ++j) {
        bool apart = false;
        for (size_t k = 0; k < 3; ++k)
          apart =
              apart || regions[i][k][1] < regions[j][k][0] || regions[j][k][1] < regions[i][k][0];
        disjoint = disjoint && apart;
      }
    if (disjoint) out.tie_regions = std::move(regions);
  }
  return out;
}

} // namespace surfcert::certify
