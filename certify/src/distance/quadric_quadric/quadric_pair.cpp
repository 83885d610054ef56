#include "surfcert/certify/distance/quadric_pair.hpp"

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/plane_chart.hpp"
#include "surfcert/algebra/solution_cover.hpp"
#include "surfcert/certify/conic_pair.hpp"
#include "surfcert/certify/distance/at_infinity.hpp"
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/contact_sampling.hpp"
#include "surfcert/certify/distance/critical_signs.hpp"
#include "surfcert/certify/distance/offset_minimum.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/certify/distance/quadratic_forms.hpp"
#include "surfcert/certify/distance/revolution.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/core/torus.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>

namespace surfcert::certify {

using core::Poly3;
using core::Rational;

namespace {

using V3 = std::array<core::Poly3, 3>;
using core::cross;
using core::dot;

// The offset system for one choice of roles (source S1: f, target S2: g), over Z.
struct Offset {
  const core::QuadricMatrix* source = nullptr;
  const core::QuadricMatrix* target = nullptr;
  bool source_is_a = true;
  Poly3 f, g, g1, g2; // g(p + mu N) = g + mu g1 + mu^2 g2 / 2
  V3 N;               // grad f
  std::array<std::array<Rational, 3>, 3> hess_f;
  std::array<Poly3, 3> system; // f, C, G
};

// Two generic integer combinations of three equations (fixed, so runs are reproducible).
constexpr std::array<std::array<long, 3>, 2> kGenericMix{{{3, -5, 7}, {2, 7, -11}}};

// Two generic combinations l . w (l in kGenericMix) of the components of w: with a third
// equation they cut out, generically, the points where w = 0 (for w a cross product: where
// two vectors are parallel).
std::array<Poly3, 2> generic_mixes(const V3& w) {
  std::array<Poly3, 2> s;
  for (size_t k = 0; k < 2; ++k)
    for (size_t i = 0; i < 3; ++i)
      s[k] = s[k] + Poly3(kGenericMix[k][i]) * w[i];
  return s;
}

Offset build_offset_poly(Poly3 f, const core::QuadricMatrix& tgt, const std::array<long, 3>& l) {
  Offset o;
  o.target = &tgt;
  o.f = std::move(f);
  o.g = algebra::quadric_poly(tgt.matrix());
  V3 X, Y;
  for (int i = 0; i < 3; ++i) {
    o.N[static_cast<size_t>(i)] = o.f.derivative(i);
    X[static_cast<size_t>(i)] = o.g.derivative(i);
  }
  for (size_t i = 0; i < 3; ++i) {
    Y[i] = Poly3(0);
    for (size_t j = 0; j < 3; ++j) {
      Y[i] = Y[i] + X[i].derivative(static_cast<int>(j)) * o.N[j];            // Hess(g) N
      o.hess_f[i][j] = o.N[i].derivative(static_cast<int>(j)).coeff(0, 0, 0); // constant
    }
  }
  const Poly3 C = dot(o.N, cross(X, Y));
  const V3 nx = cross(o.N, X), ny = cross(o.N, Y);
  Poly3 P, Q;
  for (size_t i = 0; i < 3; ++i) {
    P = P + Poly3(l[i]) * nx[i];
    Q = Q + Poly3(l[i]) * ny[i];
  }
  o.g1 = dot(X, o.N);
  o.g2 = dot(o.N, Y);
  const Poly3 G = Poly3(2) * o.g * Q * Q - Poly3(2) * o.g1 * P * Q + o.g2 * P * P;
  o.system = {o.f, C, G};
  return o;
}

Offset build_offset(const core::QuadricMatrix& src, const core::QuadricMatrix& tgt,
                    const std::array<long, 3>& l) {
  Offset o = build_offset_poly(algebra::quadric_poly(src.matrix()), tgt, l);
  o.source = &src;
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

// Balls of the kept box, and of its centre (exact rationals).
// The target quadric g = 0 seen from the source: along the normal line p + mu N of S1,
// g(p + mu N) = g + mu g1 + mu^2 g2 / 2 with g1 = grad g . N and g2 = N^T Hess(g) N.
class QuadricTarget : public MinimumTarget {
public:
  QuadricTarget(const SourceQuadric& s, const Offset& o, long digits)
      : src_(s), o_(o), digits_(digits) {}

  // Lower bound of |mu| |N| over the real roots mu, p in the box; the exact point-quadric
  // sextic bounds dist(centre, S2) - half diagonal when grad f may vanish in the box (a
  // singular point of S1, whose closest points are feet from it).
  void lower(arf_t out, const Ball (&box)[3], const Rational (&centre)[3],
             long prec) const override {
    Ball N[3], a0, a1, a2, nrm;
    for (size_t i = 0; i < 3; ++i)
      algebra::evaluate(N[i].v, src_.N[i], ball_point(box), prec);
    if (arb_contains_zero(N[0].v) && arb_contains_zero(N[1].v) && arb_contains_zero(N[2].v)) {
      PointQuadricResult pq =
          point_quadric_critical({centre[0], centre[1], centre[2]}, *o_.target, point_digits());
      if (!pq.ok || pq.criticals.empty()) {
        arf_zero(out);
        return;
      }
      Ball d, h, r; // front().lower: the least certified lower bound (sorted by it)
      arb_set_str(d.v, pq.criticals.front().lower.c_str(), prec);
      for (const auto& x : box) {
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
    ball_norm(nrm.v, N, prec);
    algebra::evaluate(a0.v, o_.g, ball_point(box), prec);
    algebra::evaluate(a1.v, o_.g1, ball_point(box), prec);
    algebra::evaluate(a2.v, o_.g2, ball_point(box), prec);
    arb_mul_2exp_si(a2.v, a2.v, -1);
    Ball disc, t;
    arb_mul(disc.v, a1.v, a1.v, prec);
    arb_mul(t.v, a2.v, a0.v, prec);
    arb_mul_2exp_si(t.v, t.v, 2);
    arb_sub(disc.v, disc.v, t.v, prec);
    if (arb_is_negative(disc.v)) {
      arf_pos_inf(out); // the normal lines from this box miss S2: no closest pair here
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
      const bool no_root = !arf_is_zero(A0) && arf_is_zero(A1) && arf_is_zero(A2);
      if (no_root) {
        // a1 = a2 = 0 on the whole box (exact balls: an exact rational box where the normal line
        // runs along a null direction of the target, e.g. a cylinder's axis) and a0 != 0: no
        // root mu, no pair here. (2 A0 / 0 would be Arb's indeterminate, a NaN bound.)
        arf_clear(A0);
        arf_clear(A1);
        arf_clear(A2);
        arf_pos_inf(out);
        return;
      }
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

  // The points of S2 on the normal line at the certified point p: genuine pairs. Where grad f
  // may vanish at an exact p (a singular point of S1, e.g. an exact rational apex: no normal
  // line), the nearest critical foot of p on S2 (the point-quadric sextic).
  std::optional<CandidatePair> upper(const Ball (&p)[3], long prec) const override {
    Ball N[3], a0, a1, a2, nrm;
    for (size_t k = 0; k < 3; ++k)
      algebra::evaluate(N[k].v, src_.N[k], ball_point(p), prec);
    if (arb_contains_zero(N[0].v) && arb_contains_zero(N[1].v) && arb_contains_zero(N[2].v))
      if (auto fp = foot_pair(p, prec)) return fp;
    ball_norm(nrm.v, N, prec);
    algebra::evaluate(a0.v, o_.g, ball_point(p), prec);
    algebra::evaluate(a1.v, o_.g1, ball_point(p), prec);
    algebra::evaluate(a2.v, o_.g2, ball_point(p), prec);
    arb_mul_2exp_si(a2.v, a2.v, -1);
    Ball mu[2];
    int nm = 0;
    if (!ball_quadratic_roots(a2.v, a1.v, a0.v, mu, nm, prec) || nm == 0) return std::nullopt;
    std::optional<CandidatePair> best;
    for (int r = 0; r < nm; ++r) {
      CandidatePair c;
      arb_abs(c.d.v, mu[r].v);
      arb_mul(c.d.v, c.d.v, nrm.v, prec);
      if (best) {
        arf_t u1, u2;
        arf_init(u1);
        arf_init(u2);
        arb_get_ubound_arf(u1, c.d.v, prec);
        arb_get_ubound_arf(u2, best->d.v, prec);
        bool better = arf_cmp(u1, u2) < 0;
        arf_clear(u1);
        arf_clear(u2);
        if (!better) continue;
      }
      double m = arf_get_d(arb_midref(mu[r].v), ARF_RND_NEAR);
      for (size_t k = 0; k < 3; ++k) {
        c.p[k] = arf_get_d(arb_midref(p[k].v), ARF_RND_NEAR);
        c.q[k] = c.p[k] + m * arf_get_d(arb_midref(N[k].v), ARF_RND_NEAR);
      }
      best = std::move(c);
    }
    return best;
  }

private:
  // Enclosures of the point-quadric distances as narrow as the refinement loop's target (its
  // 3.33 digits + 24 bits, about digits + 8 decimal digits), or the loop never closes on them.
  long point_digits() const { return std::max<long>(digits_, 15) + 10; }

  // The least critical distance from an exact point p (every radius 0) to S2, as the distance
  // of a genuine pair (each enclosure holds the distance to an actual foot point on S2);
  // nullopt when p is not exact or the sextic is not decided.
  std::optional<CandidatePair> foot_pair(const Ball (&p)[3], long prec) const {
    std::array<Rational, 3> x;
    for (size_t k = 0; k < 3; ++k) {
      if (!arb_is_exact(p[k].v)) return std::nullopt;
      arf_get_fmpq(x[k].raw_mut(), arb_midref(p[k].v));
    }
    const PointQuadricResult pq = point_quadric_critical(x, *o_.target, point_digits());
    if (!pq.ok) return std::nullopt;
    std::optional<CandidatePair> best;
    for (const auto& cd : pq.criticals) {
      CandidatePair c;
      Ball hi;
      arb_set_str(c.d.v, cd.lower.c_str(), prec);
      arb_set_str(hi.v, cd.upper.c_str(), prec);
      arb_union(c.d.v, c.d.v, hi.v, prec);
      if (best) { // keep the least upper bound (any entry is a valid one)
        algebra::Arf u, ub;
        arb_get_ubound_arf(u.v, c.d.v, prec);
        arb_get_ubound_arf(ub.v, best->d.v, prec);
        if (arf_cmp(u.v, ub.v) >= 0) continue;
      }
      for (size_t k = 0; k < 3; ++k)
        c.p[k] = x[k].to_double_approx();
      c.q = cd.foot;
      best = std::move(c);
    }
    return best;
  }

  const SourceQuadric& src_;
  const Offset& o_;
  long digits_;
};

// The restriction of a meridian conic m(X, Z) (x = X, y = Z) to the axis X = 0 has no double
// root: every point of the meridian on the axis is a smooth point, where the normal is the
// axis itself (m is even in X), so a critical pair from it runs along the axis. A double root
// is a singular point (a cone's apex), whose closest points may form a circle.
bool axis_points_smooth(const core::QuadricMatrix& m) {
  const Rational &a = m(1, 1), &b = m(1, 3), &c = m(3, 3);
  if (!a.is_zero()) return !(b * b - a * c).is_zero();
  return !b.is_zero() || !c.is_zero(); // linear: a simple root; nonzero constant: no point
}

// The real points of a meridian conic m on the axis X = 0: the roots of
// m11 Z^2 + 2 m13 Z + m33 (balls). False when the whole axis lies on m.
bool axis_points(const core::QuadricMatrix& m, std::vector<Ball>& z, long prec) {
  const Rational &a = m(1, 1), &b = m(1, 3), &c = m(3, 3);
  z.clear();
  if (a.is_zero()) {
    if (b.is_zero()) return !c.is_zero();
    z.emplace_back();
    arb_set_fmpq(z.back().v, (-c / (Rational(2) * b)).raw(), prec);
    return true;
  }
  const Rational disc = b * b - a * c;
  if (disc.sign() < 0) return true;
  Ball sq, bb, aa;
  arb_set_fmpq(sq.v, disc.raw(), prec);
  arb_sqrt(sq.v, sq.v, prec);
  arb_set_fmpq(bb.v, b.raw(), prec);
  arb_set_fmpq(aa.v, a.raw(), prec);
  for (int sgn : {1, -1}) {
    z.emplace_back();
    arb_mul_si(z.back().v, sq.v, sgn, prec);
    arb_sub(z.back().v, z.back().v, bb.v, prec);
    arb_div(z.back().v, z.back().v, aa.v, prec);
  }
  return true;
}

// No axial pair can be a closest pair: every pair of axis points of the two meridians is
// proven farther apart than `upper` (an upper bound of the minimum), or one meridian has no
// point on the axis. Applies when the source's axis points are smooth (axis_points_smooth):
// then a critical pair from an axis point of the source runs along the axis.
bool axial_pairs_exceed(const core::QuadricMatrix& src, const core::QuadricMatrix& tgt,
                        const std::string& upper) {
  const long prec = 256 + 4 * static_cast<long>(upper.size());
  std::vector<Ball> za, zb;
  if (!axis_points(src, za, prec) || !axis_points(tgt, zb, prec)) return false;
  Ball u, d;
  arb_set_str(u.v, upper.c_str(), prec);
  for (const auto& p : za)
    for (const auto& q : zb) {
      arb_sub(d.v, p.v, q.v, prec);
      arb_abs(d.v, d.v);
      if (!arb_gt(d.v, u.v)) return false;
    }
  return true;
}

// Where the minimizing source points of a meridian cover lie, decided exactly: a box is on
// the axis when its X interval isolates the root 0 of its factor of the X eliminant (then
// every solution in the box has X = 0 exactly), and off it when the interval excludes 0 or
// its factor does not vanish at 0. Boxes on the axis are set aside when no axial pair can be
// a closest pair (axial_pairs_exceed: their lower bound from the target may be uninformative,
// e.g. an axis parallel to a cylinder's meridian lines).
enum class AxisPlacement { On, Off, Mixed };

AxisPlacement axis_placement(const algebra::SolutionCover& cover, bool axial_excluded) {
  bool on = false, off = false;
  for (const auto& box : cover.boxes) {
    const auto& r = cover.roots[0][box[0]];
    const bool holds_zero =
        r.lo.sign() <= 0 && r.hi.sign() >= 0 && cover.factors[0][r.factor].coeff(0).is_zero();
    if (holds_zero && axial_excluded) continue;
    (holds_zero ? on : off) = true;
  }
  if (on && off) return AxisPlacement::Mixed;
  return on ? AxisPlacement::On : AxisPlacement::Off;
}

// r^2 of a cylinder of revolution from its meridian conic mu X^2 + lambda Z^2 + 2 beta Z + fc
// (X in x, Z in y: meridian_conic with height_var 1): lambda = beta = 0, r^2 = -fc / mu >= 0.
std::optional<Rational> cylinder_radius2(const core::QuadricMatrix& m) {
  if (!m(1, 1).is_zero() || !m(1, 3).is_zero() || m(0, 0).is_zero()) return std::nullopt;
  const Rational r2 = -m(3, 3) / m(0, 0);
  if (r2.sign() < 0) return std::nullopt; // r^2 = 0: the axis itself (a real line)
  return r2;
}

// Two cylinders of revolution about one axis (meridians X^2 = Ra and X^2 = Rb, Ra != Rb): every
// point of the meridian system is critical (parallel lines), so the offset systems have a
// curve of solutions. The distance is |sqrt Ra - sqrt Rb|, realised on every ray orthogonal to
// the axis (a continuum), computed as |Ra - Rb| / (sqrt Ra + sqrt Rb): an exact numerator, so
// nearby radii lose no digits to cancellation.
std::optional<DistanceResult> coaxial_cylinders(const core::QuadricMatrix& ma,
                                                const core::QuadricMatrix& mb, const Axis& ax,
                                                long digits) {
  const auto ra = cylinder_radius2(ma), rb = cylinder_radius2(mb);
  if (!ra || !rb || *ra == *rb) return std::nullopt;
  const long prec = bits_for(digits) + 64;
  Ball sa, sb, num, d;
  arb_set_fmpq(sa.v, ra->raw(), prec);
  arb_sqrt(sa.v, sa.v, prec);
  arb_set_fmpq(sb.v, rb->raw(), prec);
  arb_sqrt(sb.v, sb.v, prec);
  Rational diff = *ra - *rb;
  if (diff.sign() < 0) diff = -diff;
  arb_set_fmpq(num.v, diff.raw(), prec);
  arb_add(d.v, sa.v, sb.v, prec);
  arb_div(d.v, num.v, d.v, prec);
  DistanceResult out;
  out.status = Status::Certified;
  set_distance_enclosure(out, d.v, digits);
  out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
  out.method = Method::ParallelSections;
  out.critical_candidates = 0;
  // One pair, for display: on a unit ray u orthogonal to the axis.
  std::array<double, 3> ad{}, p0{};
  for (size_t i = 0; i < 3; ++i) {
    ad[i] = ax.direction[i].to_double_approx();
    p0[i] = ax.point[i].to_double_approx();
  }
  std::array<double, 3> u =
      std::fabs(ad[0]) <= std::fabs(ad[1]) && std::fabs(ad[0]) <= std::fabs(ad[2])
          ? std::array<double, 3>{0, ad[2], -ad[1]}
      : std::fabs(ad[1]) <= std::fabs(ad[2]) ? std::array<double, 3>{ad[2], 0, -ad[0]}
                                             : std::array<double, 3>{ad[1], -ad[0], 0};
  const double un = std::hypot(u[0], u[1], u[2]);
  const double ha = std::sqrt(ra->to_double_approx()), hb = std::sqrt(rb->to_double_approx());
  std::array<std::array<double, 3>, 2> pr{};
  for (size_t i = 0; i < 3; ++i) {
    pr[0][i] = p0[i] + ha * u[i] / un;
    pr[1][i] = p0[i] + hb * u[i] / un;
  }
  out.pairs.push_back(pr);
  out.note = "coaxial cylinders of revolution: the distance is the difference of the radii, "
             "realised on every ray orthogonal to the axis (one pair shown)";
  return out;
}

// Two quadrics of revolution about one axis: the distance between the surfaces is the 2D
// distance between their meridian conics (rotate a pair into one half-plane: the distance
// does not grow; the conics are symmetric in X, so the 2D minimum over the whole conics is
// attained by a same-side pair too). The meridians, as cylinders over the (x, y) plane, give
// the same offset system with z absent: f = 0, G = 0 in two unknowns (C vanishes), covered
// in the plane and refined by the same loop. Minimizers: circles unless every minimizing
// source point lies exactly on the axis (axis_placement, exact); when the cover still holds
// both kinds of boxes (a circle of minimizers a hair off the axis, closer than an axial
// pair by less than the enclosure's width), the digits are raised (x4, up to 1000) until the
// boxes separate; if they never do, the minimizers are reported as undecided.
// nullopt: not a coaxial pair (the 3D system applies).
std::optional<DistanceResult> coaxial_pair_distance(const core::QuadricMatrix& a,
                                                    const core::QuadricMatrix& b, long digits) {
  std::optional<Axis> ax = revolution_axis(a);
  if (!ax) ax = revolution_axis(b);
  if (!ax) return std::nullopt;
  auto ma = meridian_conic(a, *ax, 1), mb = meridian_conic(b, *ax, 1);
  if (!ma || !mb) return std::nullopt;
  const std::array<long, 3> l{3, -5, 7};
  const bool compact = a.kind() == core::QuadricKind::Ellipsoid ||
                       b.kind() == core::QuadricKind::Ellipsoid || minimum_attained(a, b);
  for (bool src_a : {true, false}) {
    const core::QuadricMatrix& src = src_a ? *ma : *mb;
    const core::QuadricMatrix& tgt = src_a ? *mb : *ma;
    if (tgt.is_plane()) continue;
    Offset o = build_offset(src, tgt, l);
    o.source_is_a = src_a;
    if (o.system[2].is_zero()) continue;
    const algebra::SolutionCover cover0 =
        algebra::cover_real_solutions_2d(o.system[0], o.system[2], Rational(1, 16));
    if (!cover0.ok) continue;
    SourceQuadric s(src);
    DistanceResult out;
    AxisPlacement place = AxisPlacement::Mixed;
    for (long dg = digits;; dg = std::min(4 * dg, 1000L)) {
      out = DistanceResult();
      algebra::SolutionCover cover = cover0;
      QuadricTarget t(s, o, dg);
      minimize_over_cover(cover, s, t, dg, src_a, compact, out);
      const bool axial_excluded = out.status == Status::Certified && axis_points_smooth(src) &&
                                  axial_pairs_exceed(src, tgt, out.upper());
      place = axis_placement(cover, axial_excluded);
      if (out.status != Status::Certified || place != AxisPlacement::Mixed || dg >= 1000) break;
    }
    if (place == AxisPlacement::On && !axis_points_smooth(src)) place = AxisPlacement::Mixed;
    // Back to 3D: (X, Z) in the meridian half-plane of a unit vector u orthogonal to the axis
    // (approximate points, for display).
    std::array<double, 3> ad{ax->direction[0].to_double_approx(),
                             ax->direction[1].to_double_approx(),
                             ax->direction[2].to_double_approx()};
    const double an = std::hypot(ad[0], ad[1], ad[2]);
    for (auto& x : ad)
      x /= an;
    std::array<double, 3> u =
        std::fabs(ad[0]) < 0.9 ? std::array<double, 3>{1, 0, 0} : std::array<double, 3>{0, 1, 0};
    const double ua = u[0] * ad[0] + u[1] * ad[1] + u[2] * ad[2];
    for (size_t i = 0; i < 3; ++i)
      u[i] -= ua * ad[i];
    const double un = std::hypot(u[0], u[1], u[2]);
    // X and -X give the same circle: list one pair per circle (a display choice; the
    // minimizer kind above is decided exactly).
    std::vector<std::array<std::array<double, 3>, 2>> uniq;
    for (auto pr : out.pairs) {
      for (auto& pt : pr)
        pt[0] = std::fabs(pt[0]);
      bool dup = false;
      for (const auto& u2 : uniq)
        dup = dup || (u2[0][0] == pr[0][0] && u2[0][1] == pr[0][1] && u2[1][0] == pr[1][0] &&
                      u2[1][1] == pr[1][1]);
      if (!dup) uniq.push_back(pr);
    }
    out.pairs = uniq;
    for (auto& pr : out.pairs)
      for (auto& pt : pr) {
        const double X = pt[0], Z = pt[1];
        for (size_t i = 0; i < 3; ++i)
          pt[i] = ax->point[i].to_double_approx() + X * u[i] / un + Z * ad[i];
      }
    if (out.status == Status::Certified) {
      if (place == AxisPlacement::Off) {
        out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
        out.ties = Ties::None;
        out.tie_regions.clear();
        out.note = "coaxial surfaces of revolution: circles of closest pairs (proven off the "
                   "axis; one pair per circle shown)";
      } else if (place == AxisPlacement::On) {
        out.note = "coaxial surfaces of revolution: the closest points lie on the axis (proven "
                   "exactly)" +
                   (out.note.empty() ? std::string() : "; " + out.note);
      } else {
        out.minimizers = Minimizers::undecided(static_cast<long>(out.pairs.size()));
        out.ties = Ties::None;
        out.tie_regions.clear();
        out.note = "coaxial surfaces of revolution: the distance is certified, but whether the "
                   "closest points lie on the axis or form circles was not decided";
      }
    }
    return out;
  }
  // The meridian system degenerates (a curve of solutions): coaxial cylinders have the closed
  // form; otherwise the 3D routes take the pair.
  return coaxial_cylinders(*ma, *mb, *ax, digits);
}

} // namespace

namespace {
DistanceResult quadric_pair_distance_in_place(const core::QuadricMatrix& a,
                                              const core::QuadricMatrix& b, long digits);
} // namespace

// Non-generic positions: when every role and combination leaves a curve of solutions, the
// pair is moved by a fixed rational rotation (integer quaternion (2, 3, 5, 7), |q|^2 = 87)
// and tried once more (distances are invariant; the reported points are rotated back).
namespace {

DistanceResult quadric_pair_distance_unit(const core::QuadricMatrix& a,
                                          const core::QuadricMatrix& b, long digits);

// The result for the pair scaled by 2^-k, read for the pair itself: lengths times 2^k (the
// enclosure exactly, points and position regions in double, regions rounded outward).
DistanceResult scaled_back(DistanceResult r, long k) {
  if (r.distance) r.distance = r.distance->scaled_2exp(k);
  if (r.estimate) r.estimate->value = std::ldexp(r.estimate->value, static_cast<int>(k));
  for (auto& pr : r.pairs)
    for (auto& pt : pr)
      for (double& x : pt)
        x = std::ldexp(x, static_cast<int>(k));
  if (!r.tie_directions)
    for (auto& reg : r.tie_regions)
      for (auto& iv : reg) {
        iv[0] = std::nextafter(std::ldexp(iv[0], static_cast<int>(k)), -HUGE_VAL);
        iv[1] = std::nextafter(std::ldexp(iv[1], static_cast<int>(k)), HUGE_VAL);
      }
  return r;
}

} // namespace

namespace {

// log2 of the largest over the smallest nonzero |entry| of a quadric's quadratic part (how far
// apart its semi-axes are: radii 1e-40 and 1e40 give 2^531; unchanged by scaling x or the
// equation, and by moving the quadric), to a few bits.
long entry_spread_bits(const core::QuadricMatrix& q) {
  long lo = LONG_MAX, hi = LONG_MIN;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      const Rational& v = q(i, j);
      if (v.is_zero()) continue;
      const long e = static_cast<long>(fmpz_bits(fmpq_numref(v.raw()))) -
                     static_cast<long>(fmpz_bits(fmpq_denref(v.raw())));
      lo = std::min(lo, e), hi = std::max(hi, e);
    }
  return hi >= lo ? hi - lo : 0;
}

} // namespace

DistanceResult quadric_pair_distance(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                     long digits) {
  // Semi-axes spanning more than 2^(kOffsetMaxSpreadBits / 2) in one quadric (an ellipsoid
  // with radii 1e-40, 1e40 and 1: entries 2^-266 ... 2^266): its offset system's eliminants
  // carry that spread to powers, and their isolation ran on (radii 1e-100 and 1e100 against
  // a rotated copy: never seen to end, in every mode; 1e-20: 2.4 s, 1e-40: more than 90 s).
  // Not attempted: undecided, at once.
  const long spread = std::max(entry_spread_bits(a), entry_spread_bits(b));
  if (spread > kOffsetMaxSpreadBits) {
    DistanceResult out;
    out.status = Status::Undecided;
    out.note = "the sizes within a quadric span 2^" + std::to_string(spread) + " (more than 2^" +
               std::to_string(kOffsetMaxSpreadBits) +
               "): the offset system is beyond the elimination's reach, not attempted";
    return out;
  }
  // Solved at unit size: the cover of the offset system's real solutions starts from boxes of
  // a fixed width (1/16) and its isolation is tuned for unit-size data, so the same nested
  // pair 1e-8 across needed ~15,000 candidate boxes (29 s) where at unit size it needs 10. A
  // power of two changes nothing else: the answer scales exactly.
  const auto la = core::length_order(a), lb = core::length_order(b);
  if (la || lb) {
    const long k = std::max(la.value_or(LONG_MIN), lb.value_or(LONG_MIN));
    if (k < -4 || k > 4) {
      const int kk = static_cast<int>(std::clamp(k, -100000L, 100000L));
      return scaled_back(quadric_pair_distance_unit(a.rescaled(kk), b.rescaled(kk), digits), kk);
    }
  }
  return quadric_pair_distance_unit(a, b, digits);
}

namespace {

DistanceResult quadric_pair_distance_unit(const core::QuadricMatrix& a,
                                          const core::QuadricMatrix& b, long digits) {
  DistanceResult out = quadric_pair_distance_in_place(a, b, digits);
  if (out.status != Status::Undecided || !out.offset_curve_of_solutions) return out;
  const long w = 2, x = 3, y = 5, z = 7, n = w * w + x * x + y * y + z * z;
  const long R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                        {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                        {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  core::Mat4 P; // X = R^T X' : the moved surface is {X' : Q(R^T X') = 0}
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      P[i][j] = Rational(R[j][i], static_cast<unsigned long>(n));
  P[3][3] = Rational(1);
  DistanceResult moved = quadric_pair_distance_in_place(a.congruent(P), b.congruent(P), digits);
  if (moved.status == Status::Undecided) return out;
  for (auto& pr : moved.pairs)
    for (auto& pt : pr) { // back: X = R^T X'
      std::array<double, 3> q{};
      for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j)
          q[i] += static_cast<double>(R[j][i]) / static_cast<double>(n) * pt[j];
      pt = q;
    }
  moved.note += (moved.note.empty() ? "" : "; ") +
                std::string("solved after a rational rotation (non-generic position)");
  return moved;
}

} // namespace

namespace {

// The common ruling direction of two cylinders (any kind: elliptic, hyperbolic, parabolic,
// plane pairs): d != 0 with (d, 0) in the kernel of both 4x4 matrices, i.e. both surfaces
// invariant under translation along d; nullopt unless that kernel is exactly one line.
std::optional<std::array<Rational, 3>> common_ruling(const core::QuadricMatrix& a,
                                                     const core::QuadricMatrix& b) {
  const auto k = common_kernel(a, b, 3);
  if (k.size() != 1) return std::nullopt;
  return std::array<Rational, 3>{k[0][0], k[0][1], k[0][2]};
}

// A proven common point of the quadrics a, b and the plane n.x = 0 in the box X: the
// Krawczyk operator K(X) = m - Y F(m) + (I - Y J(X)) (X - m), Y a float inverse of the
// Jacobian at the midpoint m, lands in the interior of X, so X holds a zero (Brouwer, with Y
// nonsingular). Fails at a tangency (J singular there); transversal crossings, however close
// to tangent, pass once X is small against their separation. w receives m (display).
bool common_point_in_box(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                         const std::array<Rational, 3>& n, const Ball (&X)[3], long prec,
                         std::array<double, 3>& w) {
  Ball m[4], r[3], F[3], J[3][3];
  for (size_t i = 0; i < 3; ++i) {
    arb_get_mid_arb(m[i].v, X[i].v);
    arb_sub(r[i].v, X[i].v, m[i].v, prec); // X - m
  }
  arb_one(m[3].v);
  Ball x4[4];
  for (size_t i = 0; i < 3; ++i)
    arb_set(x4[i].v, X[i].v);
  arb_one(x4[3].v);
  Ball t, u, q;
  const core::QuadricMatrix* quads[2] = {&a, &b};
  for (size_t k = 0; k < 2; ++k) {
    const core::QuadricMatrix& Q = *quads[k];
    arb_zero(F[k].v);
    for (int i = 0; i < 4; ++i) {
      // (Q m)_i and, for i < 3, 2 (Q X)_i: the gradient's entry over X.
      arb_zero(t.v);
      arb_zero(u.v);
      for (int j = 0; j < 4; ++j) {
        arb_set_fmpq(q.v, Q(i, j).raw(), prec);
        arb_addmul(t.v, q.v, m[j].v, prec);
        arb_addmul(u.v, q.v, x4[j].v, prec);
      }
      arb_addmul(F[k].v, t.v, m[i].v, prec);
      if (i < 3) arb_mul_2exp_si(J[k][i].v, u.v, 1);
    }
  }
  arb_zero(F[2].v);
  for (size_t i = 0; i < 3; ++i) {
    arb_set_fmpq(J[2][i].v, n[i].raw(), prec);
    arb_addmul(F[2].v, J[2][i].v, m[i].v, prec);
  }
  // Y: the inverse of J's midpoint matrix, in doubles (any Y works; a good one contracts).
  double M[3][3];
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      M[i][j] = arf_get_d(arb_midref(J[i][j].v), ARF_RND_NEAR);
  const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                     M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                     M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
  if (!std::isfinite(det) || det == 0) return false;
  double Yd[3][3];
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      // adj(M)_ij = cofactor of M_ji
      const size_t r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      Yd[i][j] = (M[r0][c0] * M[r1][c1] - M[r0][c1] * M[r1][c0]) / det;
      if (!std::isfinite(Yd[i][j])) return false;
    }
  for (size_t i = 0; i < 3; ++i) {
    Ball K, y, c;
    arb_set(K.v, m[i].v);
    for (size_t j = 0; j < 3; ++j) {
      arb_set_d(y.v, Yd[i][j]);
      arb_submul(K.v, y.v, F[j].v, prec);
    }
    for (size_t j = 0; j < 3; ++j) {
      // (I - Y J(X))_ij
      arb_set_si(c.v, i == j ? 1 : 0);
      for (size_t k = 0; k < 3; ++k) {
        arb_set_d(y.v, Yd[i][k]);
        arb_submul(c.v, y.v, J[k][j].v, prec);
      }
      arb_addmul(K.v, c.v, r[j].v, prec);
    }
    // In the interior: then Y (and every matrix of J(X)) is nonsingular (Rump), so the fixed
    // point of x - Y F(x) that K(X) in X gives (Brouwer) is a zero of F.
    if (!arb_contains_interior(X[i].v, K.v)) return false;
  }
  for (size_t i = 0; i < 3; ++i)
    w[i] = arf_get_d(arb_midref(m[i].v), ARF_RND_NEAR);
  return true;
}

// A proven common point of the sections of a and b in the plane n.x = 0 among the boxes of
// their solution cover: a rational solution (a box of exact points: a tangency of circles, say)
// checked by exact substitution, or a box where the Krawczyk test succeeds after refinement
// (transversal crossings, however near to tangent: the box narrows to 2^-640).
bool sections_meet(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                   const std::array<Rational, 3>& n, algebra::SolutionCover& meet,
                   std::array<double, 3>& w) {
  const core::Poly3 fa = algebra::quadric_poly(a.matrix()), fb = algebra::quadric_poly(b.matrix());
  // The root of coordinate k in a box, when rational: a collapsed interval, or the root of a
  // linear factor of the eliminant.
  auto rational_root = [&meet](size_t k, size_t i) -> std::optional<Rational> {
    const algebra::RootInterval& r = meet.roots[k][i];
    if (r.lo == r.hi) return r.lo;
    const algebra::UPolyZ& f = meet.factors[k][r.factor];
    if (f.degree() != 1) return std::nullopt;
    return -Rational(f.coeff(0)) / Rational(f.coeff(1));
  };
  for (const auto& bx : meet.boxes) {
    const auto x = rational_root(0, bx[0]), y = rational_root(1, bx[1]),
               z = rational_root(2, bx[2]);
    if (!x || !y || !z) continue;
    if (fa.evaluate(*x, *y, *z).is_zero() && fb.evaluate(*x, *y, *z).is_zero()) {
      w = {x->to_double_approx(), y->to_double_approx(), z->to_double_approx()};
      return true;
    }
  }
  for (long bits = 20; bits <= 640 && !meet.boxes.empty(); bits *= 2) {
    algebra::refine_cover(meet,
                          Rational::exact_from_double(std::ldexp(1.0, -static_cast<int>(bits))));
    const long prec = 2 * bits + 64;
    for (const auto& bx : meet.boxes) {
      Ball X[3];
      algebra::box_balls(meet, bx, X[0].v, X[1].v, X[2].v, prec);
      // Widened by 2^-bits: an exact coordinate (the plane's, say) is a ball of radius 0, whose
      // interior is empty; any box holding a zero will do.
      for (Ball& x : X)
        arb_add_error_2exp_si(x.v, -bits);
      if (common_point_in_box(a, b, n, X, prec, w)) return true;
    }
  }
  return false;
}

// Two cylinders with a common ruling direction d: translating a pair along d gives a pair at
// the same distance, so the offset system has lines of solutions and the generic route fails.
// The problem is planar: the closest pairs of the cross-sections in the plane d.x = 0 (two
// conics), then every translate along d. The source is cut by that plane (third equation) and
// the offset condition G (its P and Q are multiples of l.d, so l.d != 0 is required; the
// coplanarity equation C vanishes identically). The minimum is attained when a section is
// bounded (definite form in the plane) or when the two sections have no common point at
// infinity (a minimizing sequence escaping to infinity would approach one common asymptotic
// direction): exact resultant of the two binary forms. Otherwise the infimum may lie at
// infinity (y = x^2 and y = x^2 + 1) and the answer stays undecided.
std::optional<DistanceResult> parallel_cylinders(const core::QuadricMatrix& a,
                                                 const core::QuadricMatrix& b, long digits) {
  if (a.is_plane() || b.is_plane()) return std::nullopt;
  const auto d = common_ruling(a, b);
  if (!d) return std::nullopt;
  const auto fr = core::plane_frame(*d);
  const RMat3 A = quadratic_block(a), B = quadratic_block(b);
  const Rational a11 = bilinear(A, fr[0], fr[0]), a12 = bilinear(A, fr[0], fr[1]),
                 a22 = bilinear(A, fr[1], fr[1]);
  const Rational b11 = bilinear(B, fr[0], fr[0]), b12 = bilinear(B, fr[0], fr[1]),
                 b22 = bilinear(B, fr[1], fr[1]);
  const bool bounded_section =
      (a11 * a22 - a12 * a12).sign() > 0 || (b11 * b22 - b12 * b12).sign() > 0;
  const Rational res = restricted_resultant(A, B, fr[0], fr[1]);
  // Two parabolic sections with one axis direction e (rank-1 forms, common double root): each
  // goes to infinity along one half-direction only, -sign(trace) sign(b.e) e (on the parabola
  // far out, 2 t b.e balances the positive transversal term), so opposite openings cannot
  // approach each other (y = x^2 and y = -x^2 - 1: attained at the vertices).
  const auto opening = [&fr](const core::QuadricMatrix& q, const Rational& q11, const Rational& q12,
                             const Rational& q22) {
    if (!(q11 * q22 - q12 * q12).is_zero()) return 0;
    std::array<Rational, 2> e{q12, -q11};
    if (e[0].is_zero() && e[1].is_zero()) e = {q22, -q12};
    Rational be;
    for (int i = 0; i < 3; ++i)
      be += q(i, 3) * (e[0] * fr[0][static_cast<size_t>(i)] + e[1] * fr[1][static_cast<size_t>(i)]);
    return -(q11 + q22).sign() * be.sign(); // +1 / -1 along e; 0: no single opening
  };
  bool opposite = false, widths_differ = false;
  if (!bounded_section && res.is_zero()) {
    // The kernels are parallel iff the forms are proportional (both rank 1, common root).
    const int oa = opening(a, a11, a12, a22), ob = opening(b, b11, b12, b22);
    if (oa != 0 && ob != 0) {
      // Orient b's kernel like a's: e_b = (b12, -b11) or (b22, -b12), parallel to e_a.
      std::array<Rational, 2> ea{a12, -a11}, eb{b12, -b11};
      if (ea[0].is_zero() && ea[1].is_zero()) ea = {a22, -a12};
      if (eb[0].is_zero() && eb[1].is_zero()) eb = {b22, -b12};
      // ea = k eb (parallel coefficient vectors): the sign of k is that of their plain dot
      // product, whatever the (orthogonal, not unit) frame's metric.
      const int same = (ea[0] * eb[0] + ea[1] * eb[1]).sign();
      opposite = oa * ob * same < 0;
      // The same opening: with the forms proportional (B = kappa A on the section plane) the
      // parabolas t = -mu s^2 / (2 beta) have one width iff beta_b = kappa beta_a (beta = b.e,
      // e the common axis direction). Different widths separate far out (at height t the
      // half-widths grow like sqrt(t) with different factors), so the minimum is attained.
      const Rational kappa = !a11.is_zero() ? b11 / a11 : !a12.is_zero() ? b12 / a12 : b22 / a22;
      Rational beta_a, beta_b;
      for (int i = 0; i < 3; ++i) {
        const Rational e3 =
            ea[0] * fr[0][static_cast<size_t>(i)] + ea[1] * fr[1][static_cast<size_t>(i)];
        beta_a += a(i, 3) * e3;
        beta_b += b(i, 3) * e3;
      }
      widths_differ = !opposite && !(beta_b == kappa * beta_a);
    }
  }
  const bool attained = bounded_section || !res.is_zero() || opposite || widths_differ;
  Poly3 plane;
  for (size_t i = 0; i < 3; ++i)
    plane = plane + Poly3((*d)[i]) * Poly3::variable(static_cast<int>(i));
  // Contact: the pencil of two parallel cylinders is degenerate (their rulings meet in a
  // common singular point at infinity), so the projective classification says nothing and it
  // is decided here. No real common point of the two sections (an exact solution cover with no
  // box, or the sections' resultant read exactly): disjoint. Otherwise a sign change, a
  // rational common point, a Krawczyk box or the resultant proves contact; or it stays open.
  {
    algebra::SolutionCover meet = algebra::cover_real_solutions(
        {algebra::quadric_poly(a.matrix()), algebra::quadric_poly(b.matrix()), plane},
        Rational(1, 16));
    if (!meet.ok) return std::nullopt; // a common component of the sections
    // The sections as plane conics (chart of the plane d.x = 0): whether they have a real
    // common point, decided exactly (conic_pair.hpp) unless they share a component or a sign
    // stays open. No common point: the cover's boxes are phantoms, and the distance follows.
    std::optional<bool> exact;
    if (!meet.boxes.empty()) {
      core::Mat4 pm;
      for (size_t i = 0; i < 3; ++i)
        pm[i][3] = pm[3][i] = (*d)[i] / Rational(2);
      if (const auto chart = algebra::plane_chart(pm))
        exact = conics_meet(algebra::restrict_form(a.matrix(), *chart),
                            algebra::restrict_form(b.matrix(), *chart));
    }
    if (!meet.boxes.empty() && !(exact && !*exact)) {
      DistanceResult out;
      out.method = Method::ParallelSections;
      std::array<double, 3> w{};
      std::vector<std::array<double, 3>> near; // the candidate common points of the sections
      for (const auto& bx : meet.boxes) {
        Ball x[3];
        algebra::box_balls(meet, bx, x[0].v, x[1].v, x[2].v, 128);
        near.push_back({arf_get_d(arb_midref(x[0].v), ARF_RND_NEAR),
                        arf_get_d(arb_midref(x[1].v), ARF_RND_NEAR),
                        arf_get_d(arb_midref(x[2].v), ARF_RND_NEAR)});
      }
      // Contact: the common ruling through a common point of the sections is a line of
      // common points (the pair shown is an approximate common point).
      auto contact = [&out, &w](const char* how) {
        out.status = Status::Certified;
        out.distance = Enclosure::zero();
        out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
        out.pairs.push_back({w, w});
        out.note = std::string("two cylinders with a common ruling direction meet (") + how +
                   "; the pair is an approximate common point)";
      };
      if (meet_by_sign_change(a, b, w, near)) {
        contact("a connected piece of one has certified points on both sides of the other");
      } else if (const bool located = sections_meet(a, b, *d, meet, w);
                 located || (exact && *exact)) {
        if (!located) w = near.front(); // a box of the cover (display only)
        contact("along a common ruling: a common point of their sections proven exactly, by a "
                "rational point, a Krawczyk test or a real root of the sections' resultant");
      } else {
        out.status = Status::Undecided;
        out.note = "two cylinders with a common ruling direction whose sections may meet or "
                   "touch: not decided";
      }
      return out;
    }
  }
  const std::array<std::array<long, 3>, 3> ls{{{3, -5, 7}, {2, 7, -11}, {1, 1, 1}}};
  for (bool src_a : {true, false})
    for (const auto& l : ls) {
      Rational ld;
      for (size_t i = 0; i < 3; ++i)
        ld += Rational(l[i]) * (*d)[i];
      if (ld.is_zero()) continue;
      Offset o = build_offset(src_a ? a : b, src_a ? b : a, l);
      o.source_is_a = src_a;
      algebra::SolutionCover cover =
          algebra::cover_real_solutions({o.f, o.system[2], plane}, Rational(1, 16));
      if (!cover.ok) continue;
      DistanceResult out;
      out.critical_candidates = static_cast<int>(cover.boxes.size());
      SourceQuadric src(*o.source);
      QuadricTarget tgt(src, o, digits);
      minimize_over_cover(cover, src, tgt, digits, o.source_is_a, attained, out);
      const std::string line = "two cylinders with a common ruling direction: the cross-sections "
                               "in a plane orthogonal to it, solved exactly; every minimizing "
                               "pair extends to a line of pairs parallel to the rulings";
      out.note = out.note.empty() ? line : line + "; " + out.note;
      if (out.status == Status::Certified)
        out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact); // lines of pairs
      out.method = Method::ParallelSections;
      return out;
    }
  return std::nullopt;
}

DistanceResult quadric_pair_distance_in_place(const core::QuadricMatrix& a,
                                              const core::QuadricMatrix& b, long digits) {
  DistanceResult out;
  // Roles: a plane is always the source (as the target its Hessian vanishes and C with it);
  // prefer a target with three distinct eigenvalues.
  if (auto d = coaxial_pair_distance(a, b, digits)) return *d;
  std::vector<std::pair<bool, int>> orders; // (source is a, preference)
  for (bool src_a : {true, false}) {
    const core::QuadricMatrix& tgt = src_a ? b : a;
    if (tgt.is_plane()) continue;
    orders.emplace_back(src_a, distinct_eigenvalues(tgt) ? 0 : 1);
  }
  std::stable_sort(orders.begin(), orders.end(),
                   [](const auto& u, const auto& v) { return u.second < v.second; });
  const auto& ls = kGenericMix;
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
    if (auto pc = parallel_cylinders(a, b, digits)) return *pc;
    out.status = Status::Undecided;
    out.offset_curve_of_solutions = true;
    out.note = "not supported yet: the offset system has a curve of solutions in every tried "
               "position (" +
               why + "; e.g. surfaces of revolution sharing an axis)";
    return out;
  }
  const Offset& o = *off;
  out.critical_candidates = static_cast<int>(cover.boxes.size());

  const bool compact = a.kind() == core::QuadricKind::Ellipsoid ||
                       b.kind() == core::QuadricKind::Ellipsoid || minimum_attained(a, b);
  SourceQuadric src(*o.source);
  QuadricTarget tgt(src, o, digits);
  minimize_over_cover(cover, src, tgt, digits, o.source_is_a, compact, out);
  return out;
}

} // namespace

namespace {

// A sphere as the target: the distance from p is ||p - c| - rho| (closed form, Arb), a valid
// lower bound over a box and the distance of a genuine pair at a certified point.
class SphereTarget : public MinimumTarget {
public:
  SphereTarget(std::array<Rational, 3> c, Rational r2) : c_(std::move(c)), r2_(std::move(r2)) {}
  void lower(arf_t out, const Ball (&box)[3], const Rational (&)[3], long prec) const override {
    Ball d;
    dist(d.v, box, prec);
    arb_get_lbound_arf(out, d.v, prec);
    if (arf_sgn(out) < 0) arf_zero(out);
  }
  std::optional<CandidatePair> upper(const Ball (&p)[3], long prec) const override {
    CandidatePair cp;
    dist(cp.d.v, p, prec);
    double n = 0, rho = std::sqrt(r2_.to_double_approx());
    for (size_t i = 0; i < 3; ++i) {
      cp.p[i] = arf_get_d(arb_midref(p[i].v), ARF_RND_NEAR);
      n += (cp.p[i] - c_[i].to_double_approx()) * (cp.p[i] - c_[i].to_double_approx());
    }
    n = std::sqrt(n);
    for (size_t i = 0; i < 3; ++i)
      cp.q[i] =
          c_[i].to_double_approx() + (n > 0 ? rho * (cp.p[i] - c_[i].to_double_approx()) / n : 0);
    return cp;
  }

private:
  void dist(arb_t out, const Ball (&p)[3], long prec) const {
    Ball w[3], r;
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(w[i].v, c_[i].raw(), prec);
      arb_sub(w[i].v, p[i].v, w[i].v, prec);
    }
    ball_norm(out, w, prec);
    arb_set_fmpq(r.v, r2_.raw(), prec);
    arb_sqrt(r.v, r.v, prec);
    arb_sub(out, out, r.v, prec);
    arb_abs(out, out);
  }
  std::array<Rational, 3> c_;
  Rational r2_;
};

// A plane n.x = delta as the target: the distance of a point is |n.x - delta| / |n|.
class PlaneTarget : public MinimumTarget {
public:
  PlaneTarget(std::array<Rational, 3> n, Rational delta)
      : n_(std::move(n)), delta_(std::move(delta)) {}
  void lower(arf_t out, const Ball (&box)[3], const Rational (&)[3], long prec) const override {
    Ball d;
    dist(d.v, box, prec);
    arb_get_lbound_arf(out, d.v, prec);
    if (arf_sgn(out) < 0) arf_zero(out);
  }
  std::optional<CandidatePair> upper(const Ball (&p)[3], long prec) const override {
    CandidatePair cp;
    dist(cp.d.v, p, prec);
    Ball l;
    value(l.v, p, prec);
    const double nn = n_[0].to_double_approx() * n_[0].to_double_approx() +
                      n_[1].to_double_approx() * n_[1].to_double_approx() +
                      n_[2].to_double_approx() * n_[2].to_double_approx();
    const double ld = arf_get_d(arb_midref(l.v), ARF_RND_NEAR);
    for (size_t i = 0; i < 3; ++i) {
      cp.p[i] = arf_get_d(arb_midref(p[i].v), ARF_RND_NEAR);
      cp.q[i] = cp.p[i] - ld * n_[i].to_double_approx() / nn; // the foot on the plane
    }
    return cp;
  }

private:
  void value(arb_t out, const Ball (&p)[3], long prec) const {
    Ball t;
    arb_set_fmpq(out, delta_.raw(), prec);
    arb_neg(out, out);
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(t.v, n_[i].raw(), prec);
      arb_addmul(out, t.v, p[i].v, prec);
    }
  }
  void dist(arb_t out, const Ball (&p)[3], long prec) const {
    Ball nn, t;
    value(out, p, prec);
    arb_abs(out, out);
    for (const auto& x : n_) {
      arb_set_fmpq(t.v, x.raw(), prec);
      arb_addmul(nn.v, t.v, t.v, prec);
    }
    arb_sqrt(nn.v, nn.v, prec);
    arb_div(out, out, nn.v, prec);
  }
  std::array<Rational, 3> n_;
  Rational delta_;
};

// The sign (+1 or -1) of f's leading form when it is definite on the unit cube's faces
// (certified by bisection in Arb): then f has that sign far out (|f| grows like |x|^deg) and the
// zero set is bounded. 0: not proven definite.
int leading_form_sign(const core::Poly3& f) {
  const int d = f.total_degree();
  if (d < 2 || d % 2 != 0) return 0;
  core::Poly3 top;
  for (const auto& [e, c] : f.terms())
    if (e[0] + e[1] + e[2] == d) top.add_term(e, c);
  const long prec = 128;
  int sign = 0;
  struct Sq {
    int axis, side;
    Rational a0, a1, b0, b1;
  };
  std::vector<Sq> live;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1})
      live.push_back({axis, side, Rational(-1), Rational(1), Rational(-1), Rational(1)});
  for (int round = 0; round < 14 && !live.empty(); ++round) {
    std::vector<Sq> next;
    for (const Sq& q : live) {
      Ball X[3], lo, hi, v, t;
      for (int k = 0, free = 0; k < 3; ++k) {
        if (k == q.axis) {
          arb_set_si(X[k].v, q.side);
          continue;
        }
        const Rational& l = free == 0 ? q.a0 : q.b0;
        const Rational& h = free == 0 ? q.a1 : q.b1;
        arb_set_fmpq(lo.v, l.raw(), prec);
        arb_set_fmpq(hi.v, h.raw(), prec);
        arb_union(X[k].v, lo.v, hi.v, prec);
        ++free;
      }
      for (const auto& [e, c] : top.terms()) {
        arb_set_fmpq(t.v, c.raw(), prec);
        for (size_t k = 0; k < 3; ++k) {
          Ball pw;
          arb_pow_ui(pw.v, X[k].v, static_cast<ulong>(e[k]), prec);
          arb_mul(t.v, t.v, pw.v, prec);
        }
        arb_add(v.v, v.v, t.v, prec);
      }
      const int sg = arb_is_positive(v.v) ? 1 : arb_is_negative(v.v) ? -1 : 0;
      if (sg != 0) {
        if (sign != 0 && sg != sign) return 0;
        sign = sg;
        continue;
      }
      const Rational am = (q.a0 + q.a1) * Rational(1, 2), bm = (q.b0 + q.b1) * Rational(1, 2);
      next.push_back({q.axis, q.side, q.a0, am, q.b0, bm});
      next.push_back({q.axis, q.side, am, q.a1, q.b0, bm});
      next.push_back({q.axis, q.side, q.a0, am, bm, q.b1});
      next.push_back({q.axis, q.side, am, q.a1, bm, q.b1});
    }
    if (next.size() > 20000) return 0;
    live = std::move(next);
  }
  return live.empty() ? sign : 0;
}

// Contact of q and the bounded surface f = 0 (s: the sign of f's definite leading form), from
// q's side: on each component of q, s f grows at infinity, so its least value there is
// attained at a critical point of f on q (singular points of q are critical too). Hence a
// strict sign s of f at every critical point proves q apart from f = 0 (Apart), and a certified
// point of q where s f < 0 proves a crossing (Meet) when that point's component of q is
// unbounded (components_unbounded): f has the sign s far out along it.
enum class QuadricSide { Meet, Apart, Unknown };

QuadricSide quadric_side_contact(const core::QuadricMatrix& q, const core::Poly3& f, int s) {
  const SourceQuadric qs(q);
  const auto inside = [s](const CriticalSigns& c) { return s > 0 ? c.neg_point : c.pos_point; };
  const auto outside_only = [s](const CriticalSigns& c) {
    return c.finite && c.all_signed && c.boxes > 0 && (s > 0 ? !c.any_neg : !c.any_pos);
  };
  const CriticalSigns cs =
      critical_signs(qs, f, [&](const CriticalSigns& c) { return inside(c) || outside_only(c); });
  if (outside_only(cs)) return QuadricSide::Apart;
  return inside(cs) && components_unbounded(q) ? QuadricSide::Meet : QuadricSide::Unknown;
}

// Contact from the signs of h at its critical points on a CONNECTED bounded surface S
// (critical_signs): h takes its extreme values there, so both signs at certified points prove
// the surfaces meet, one sign everywhere proves h never vanishes on S. True when `out` holds
// the answer (they meet, or undecided); false when they are proven apart.
bool contact_answered(const CriticalSigns& cs, const std::string& h, const std::string& S,
                      DistanceResult& out) {
  if (!cs.finite) {
    out.status = Status::Undecided;
    out.note = "contact not decided: the critical points of " + h + " on " + S + " form a curve";
    return true;
  }
  const bool meet = cs.pos_point && cs.neg_point;
  const bool decided = meet || (cs.all_signed && !(cs.any_pos && cs.any_neg) && cs.boxes > 0);
  if (!decided) {
    out.status = Status::Undecided;
    out.note = "contact not decided: a critical value of " + h + " on " + S +
               " is not separated from 0 (touching?)";
    return true;
  }
  if (!meet) return false;
  out.status = Status::Certified;
  out.distance = Enclosure::zero();
  out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
  out.note = "the surfaces meet (" + h + " takes both signs at certified points of " + S + ")";
  return true;
}

// The offset system of f (the source) against the quadric q (the target), in the first generic
// position where its real solutions are finitely many: the minimum over them into `out`.
// Otherwise `out` says the system has a curve of solutions in every tried position.
void offset_route(const core::Poly3& f, const core::QuadricMatrix& q, SourceQuadric& src,
                  long digits, bool implicit_first, DistanceResult& out) {
  for (const auto& l : kGenericMix) {
    Offset o = build_offset_poly(f, q, l);
    o.source_is_a = implicit_first;
    algebra::SolutionCover cover = algebra::cover_real_solutions(o.system, Rational(1, 16));
    if (!cover.ok) continue;
    QuadricTarget tgt(src, o, digits);
    minimize_over_cover(cover, src, tgt, digits, implicit_first, true, out);
    return;
  }
  out.status = Status::Undecided;
  out.offset_curve_of_solutions = true;
  out.note = "not supported yet: the offset system has a curve of solutions";
}

// A bounded implicit surface f = 0 (definite leading form) against any quadric g = 0 (planes
// included; not an ellipsoid). Contact: the extreme values of g on each compact component of
// {f = 0} are critical values (f = 0, grad f x grad g = 0; singular points of f satisfy it
// too), so one strict sign at every critical point means g never vanishes there. Both signs
// prove nothing: f = 0 may be disconnected (x^4 + y^4 + z^4 - 8 x^2 + 15 = 0 is two blobs
// about x = +-2, and g = x is positive on one, negative on the other, 1.73 away from both);
// a crossing is proven from the quadric's side (quadric_side_contact). Disjoint: the offset
// system with f as the source (a plane: the points of f = 0 whose normal is parallel to the
// plane's) over the exact solution cover; the minimum is attained since f = 0 is bounded.
DistanceResult bounded_implicit_quadric(const core::Poly3& f, const core::QuadricMatrix& q,
                                        long digits, bool implicit_first) {
  DistanceResult out;
  const int lead = leading_form_sign(f);
  if (lead == 0) {
    out.status = Status::Undecided;
    out.note = "not supported yet: an implicit surface of degree > 2 against a quadric other "
               "than an ellipsoid, unless the implicit surface is proven bounded (definite "
               "leading form)";
    return out;
  }
  const Poly3 g = algebra::quadric_poly(q.matrix());
  SourceQuadric src(f);
  const CriticalSigns cs = critical_signs(src, g);
  const bool apart = cs.finite && cs.all_signed && !(cs.any_pos && cs.any_neg) && cs.boxes > 0;
  const QuadricSide side = apart ? QuadricSide::Apart : quadric_side_contact(q, f, lead);
  if (side != QuadricSide::Apart) {
    if (side == QuadricSide::Meet) {
      out.status = Status::Certified;
      out.distance = Enclosure::zero();
      out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
      out.note = "the surfaces meet (a certified point of the quadric lies inside the bounded "
                 "implicit surface, and its component of the quadric is unbounded)";
      return out;
    }
    out.status = Status::Undecided;
    out.note = !cs.finite ? "contact not decided: the critical points of the quadric's equation "
                            "on the bounded implicit surface form a curve"
                          : "contact not decided: a critical value of the quadric's equation on "
                            "the bounded implicit surface is not separated from 0 (touching?), "
                            "or it takes both signs on a surface not proven connected";
    return out;
  }
  if (q.is_plane()) {
    const std::array<Rational, 3> n{q(0, 3), q(1, 3), q(2, 3)};
    const Rational delta = -q(3, 3) * Rational(1, 2);
    const V3 nv{Poly3(n[0]), Poly3(n[1]), Poly3(n[2])};
    const auto s = generic_mixes(cross(src.N, nv));
    algebra::SolutionCover cover = algebra::cover_real_solutions({f, s[0], s[1]}, Rational(1, 16));
    if (!cover.ok) {
      out.status = Status::Undecided;
      out.note = "not supported yet: a curve of points whose normal is parallel to the plane's";
      return out;
    }
    PlaneTarget tgt(n, delta);
    minimize_over_cover(cover, src, tgt, digits, implicit_first, true, out);
    return out;
  }
  offset_route(f, q, src, digits, implicit_first, out);
  return out;
}

} // namespace

DistanceResult implicit_quadric_distance(const core::Poly3& f, const core::QuadricMatrix& q,
                                         long digits, bool implicit_first) {
  DistanceResult out;
  if (refuse_beyond_offset_degree(f, out)) return out;
  if (q.kind() != core::QuadricKind::Ellipsoid)
    return bounded_implicit_quadric(f, q, digits, implicit_first);
  // Contact: the sign of f at the critical points of f on the ellipsoid (connected, bounded:
  // f takes its extreme values there). Both signs at certified points: they cross.
  SourceQuadric ell(q);
  if (contact_answered(critical_signs(ell, f), "f", "the ellipsoid", out)) return out;
  if (q.is_sphere()) {
    // Normal lines of S1 through the centre: f = 0, l.((p - c) x grad f) = 0 for two l.
    std::array<Rational, 3> c;
    const Rational k = q(0, 0);
    Rational c2;
    for (size_t i = 0; i < 3; ++i) {
      c[i] = -q(static_cast<int>(i), 3) / k;
      c2 += c[i] * c[i];
    }
    const Rational r2 = c2 - q(3, 3) / k;
    V3 w; // p - c
    for (size_t i = 0; i < 3; ++i)
      w[i] = Poly3::variable(static_cast<int>(i)) - Poly3(c[i]);
    const V3 gfv{f.derivative(0), f.derivative(1), f.derivative(2)};
    const auto s = generic_mixes(cross(w, gfv));
    algebra::SolutionCover cover = algebra::cover_real_solutions({f, s[0], s[1]}, Rational(1, 16));
    if (!cover.ok) {
      out.status = Status::Undecided;
      out.note = "not supported yet: a curve of normal lines through the sphere's centre";
      return out;
    }
    SourceQuadric src(f);
    SphereTarget tgt(c, r2);
    minimize_over_cover(cover, src, tgt, digits, implicit_first, true, out);
    return out;
  }
  // The offset system with the implicit surface as the source, the ellipsoid as the target.
  SourceQuadric src(f);
  offset_route(f, q, src, digits, implicit_first, out);
  return out;
}

} // namespace surfcert::certify
