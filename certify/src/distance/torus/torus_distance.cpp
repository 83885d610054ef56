#include "surfcert/certify/distance/torus_distance.hpp"

#include "surfcert/certify/distance/quadric_pair.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/solution_cover.hpp"
#include "surfcert/certify/distance/critical_signs.hpp"
#include "surfcert/certify/distance/offset_minimum.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/certify/distance/quadratic_forms.hpp"
#include "surfcert/certify/distance/revolution.hpp"
#include "surfcert/certify/distance/torus_fast.hpp"
#include "surfcert/certify/qsic.hpp"

#include <cmath>
#include <optional>

namespace surfcert::certify {

using core::Poly3;
using core::Rational;

namespace {

using V3 = std::array<core::Poly3, 3>;
using core::cross;
using core::dot;

// The torus as polynomials: W = p - c, the axis A; T > 0 outside the solid torus, < 0 inside
// the tube.
struct TorusPolys {
  const core::Torus* torus = nullptr;
  V3 W, A;
  Poly3 T;
  Rational R2; ///< R^2
};

TorusPolys torus_polys(const core::Torus& t) {
  TorusPolys o;
  o.torus = &t;
  for (size_t i = 0; i < 3; ++i) {
    o.W[i] = Poly3::variable(static_cast<int>(i)) - Poly3(t.centre[i]);
    o.A[i] = Poly3(t.axis[i]);
  }
  o.R2 = t.R * t.R;
  const Poly3 u = dot(o.W, o.W), s = dot(o.W, o.A), A2 = dot(o.A, o.A);
  const Poly3 K(o.R2 - t.r * t.r);
  o.T = A2 * (u + K) * (u + K) - Poly3(Rational(4) * o.R2) * (A2 * u - s * s);
  return o;
}

// dist(p, K) for a ball point p (closed form), and the nearest point of K (approximate).
void circle_distance(arb_t out, const core::Torus& t, const Ball (&p)[3], long prec,
                     std::array<double, 3>* nearest = nullptr) {
  Ball w[3], a[3], an, h, w2, rho, tmp, R;
  for (size_t i = 0; i < 3; ++i) {
    arb_set_fmpq(tmp.v, t.centre[i].raw(), prec);
    arb_sub(w[i].v, p[i].v, tmp.v, prec);
    arb_set_fmpq(a[i].v, t.axis[i].raw(), prec);
  }
  ball_norm(an.v, a, prec);
  for (size_t i = 0; i < 3; ++i) {
    arb_addmul(h.v, w[i].v, a[i].v, prec);
    arb_addmul(w2.v, w[i].v, w[i].v, prec);
  }
  arb_div(h.v, h.v, an.v, prec); // signed height over the plane of K
  arb_sqr(tmp.v, h.v, prec);
  arb_sub(rho.v, w2.v, tmp.v, prec);
  arb_sqrtpos(rho.v, rho.v, prec); // distance to the axis
  arb_set_fmpq(R.v, t.R.raw(), prec);
  arb_sub(out, rho.v, R.v, prec);
  arb_sqr(out, out, prec);
  arb_addmul(out, h.v, h.v, prec);
  arb_sqrtpos(out, out, prec);
  if (nearest) {
    double hd = arf_get_d(arb_midref(h.v), ARF_RND_NEAR),
           rd = arf_get_d(arb_midref(rho.v), ARF_RND_NEAR),
           and_ = arf_get_d(arb_midref(an.v), ARF_RND_NEAR), Rd = t.R.to_double_approx();
    for (size_t i = 0; i < 3; ++i) {
      double wi = arf_get_d(arb_midref(w[i].v), ARF_RND_NEAR),
             ai = arf_get_d(arb_midref(a[i].v), ARF_RND_NEAR) / and_;
      double radial = rd > 0 ? (wi - hd * ai) / rd : 0;
      (*nearest)[i] = t.centre[i].to_double_approx() + Rd * radial;
    }
  }
}

// |dist(p, K) - r|: the distance from p to the torus, for every p in the box of balls.
void torus_point_distance(arb_t out, const core::Torus& t, const Ball (&p)[3], long prec) {
  Ball r;
  circle_distance(out, t, p, prec);
  arb_set_fmpq(r.v, t.r.raw(), prec);
  arb_sub(out, out, r.v, prec);
  arb_abs(out, out);
}

class TorusTarget : public MinimumTarget {
public:
  explicit TorusTarget(const core::Torus& t) : t_(t) {}
  void lower(arf_t out, const Ball (&box)[3], const Rational (&)[3], long prec) const override {
    Ball d;
    torus_point_distance(d.v, t_, box, prec);
    arb_get_lbound_arf(out, d.v, prec);
    if (arf_sgn(out) < 0) arf_zero(out);
  }
  std::optional<CandidatePair> upper(const Ball (&p)[3], long prec) const override {
    CandidatePair c;
    std::array<double, 3> k{};
    Ball D;
    circle_distance(D.v, t_, p, prec, &k);
    Ball r;
    arb_set_fmpq(r.v, t_.r.raw(), prec);
    arb_sub(c.d.v, D.v, r.v, prec);
    arb_abs(c.d.v, c.d.v);
    double Dd = arf_get_d(arb_midref(D.v), ARF_RND_NEAR), rd = t_.r.to_double_approx();
    for (size_t i = 0; i < 3; ++i) {
      c.p[i] = arf_get_d(arb_midref(p[i].v), ARF_RND_NEAR);
      c.q[i] = Dd > 0 ? k[i] + rd * (c.p[i] - k[i]) / Dd : k[i];
    }
    return c;
  }

private:
  const core::Torus& t_;
};

// The point of K nearest a point c off the axis, to double precision: the radial direction
// u = w - (w.a / a.a) a (w = c - centre) exact over Q, divided by its largest component before
// rounding. (Read from balls, rho^2 = |w|^2 - h^2 cancelled: a sphere's centre 1e-20 off the
// axis gave a "closest" torus point 1.9 off the torus.)
std::array<double, 3> nearest_on_circle(const core::Torus& t, const std::array<Rational, 3>& c,
                                        const Rational& wa, const Rational& aa) {
  std::array<Rational, 3> u;
  Rational big;
  for (size_t i = 0; i < 3; ++i) {
    u[i] = c[i] - t.centre[i] - wa * t.axis[i] / aa;
    if (core::abs(u[i]) > big) big = core::abs(u[i]);
  }
  std::array<double, 3> v{}, k{};
  for (size_t i = 0; i < 3; ++i)
    v[i] = (u[i] / big).to_double_approx();
  const double n = std::hypot(v[0], v[1], v[2]), R = t.R.to_double_approx();
  for (size_t i = 0; i < 3; ++i)
    k[i] = t.centre[i].to_double_approx() + R * v[i] / n;
  return k;
}

// ---- sphere vs torus (closed form) ----------------------------------------------------------

DistanceResult sphere_torus(const core::QuadricMatrix& s, const core::Torus& t, long digits,
                            bool sphere_first) {
  DistanceResult out;
  std::array<Rational, 3> c;
  Rational k = s(0, 0), c2;
  for (int i = 0; i < 3; ++i) {
    c[static_cast<size_t>(i)] = -s(i, 3) / k;
    c2 += c[static_cast<size_t>(i)] * c[static_cast<size_t>(i)];
  }
  const Rational rs2 = c2 - s(3, 3) / k;
  // Exact: is the centre on the axis (a circle of nearest points) or on K (a circle too)?
  Rational ww, wa, aa;
  for (size_t i = 0; i < 3; ++i) {
    Rational w = c[i] - t.centre[i];
    ww += w * w;
    wa += w * t.axis[i];
    aa += t.axis[i] * t.axis[i];
  }
  const Rational rho2 = ww - wa * wa / aa;
  const bool on_axis = rho2.is_zero(), on_circle = wa.is_zero() && rho2 == t.R * t.R;
  out.critical_candidates = on_axis ? 2 : 4;
  out.eliminated_degree = 2;
  for (long prec = 128;; prec *= 2) {
    Ball p[3], Dn, Df, r, R, rs, dmin, dmax, d;
    for (size_t i = 0; i < 3; ++i)
      arb_set_fmpq(p[i].v, c[i].raw(), prec);
    circle_distance(Dn.v, t, p, prec);
    // Farthest point of K: sqrt((rho + R)^2 + h^2) = sqrt(D_near^2 + 4 R rho).
    Ball rho, tmp;
    arb_set_fmpq(rho.v, rho2.raw(), prec);
    arb_sqrtpos(rho.v, rho.v, prec);
    arb_set_fmpq(R.v, t.R.raw(), prec);
    arb_mul(tmp.v, R.v, rho.v, prec);
    arb_mul_2exp_si(tmp.v, tmp.v, 2);
    arb_sqr(Df.v, Dn.v, prec);
    arb_add(Df.v, Df.v, tmp.v, prec);
    arb_sqrtpos(Df.v, Df.v, prec);
    arb_set_fmpq(r.v, t.r.raw(), prec);
    arb_set_fmpq(rs.v, rs2.raw(), prec);
    arb_sqrt(rs.v, rs.v, prec);
    arb_sub(dmin.v, Dn.v, r.v, prec);
    arb_abs(dmin.v, dmin.v);
    arb_add(dmax.v, Df.v, r.v, prec);
    const char* which = nullptr;
    if (arb_gt(dmin.v, rs.v)) {
      arb_sub(d.v, dmin.v, rs.v, prec);
      which = "near";
    } else if (arb_lt(dmax.v, rs.v)) {
      arb_sub(d.v, rs.v, dmax.v, prec);
      which = "far";
    } else if (arb_lt(dmin.v, rs.v) && arb_gt(dmax.v, rs.v)) {
      out.status = Status::Certified;
      out.distance = Enclosure::zero();
      out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
      out.note = "the sphere meets the torus (its radius lies strictly between the smallest and "
                 "largest distances from its centre to the torus)";
      return out;
    } else if (prec > 4096 + 4 * digits) {
      out.status = Status::Undecided;
      out.note = "the sphere may touch the torus: not separated at the working precision";
      return out;
    } else {
      continue;
    }
    arf_t lo, hi;
    arf_init(lo);
    arf_init(hi);
    arb_get_lbound_arf(lo, d.v, prec);
    arb_get_ubound_arf(hi, d.v, prec);
    // Relative width reached?
    arf_t w;
    arf_init(w);
    arf_sub(w, hi, lo, prec, ARF_RND_UP);
    arf_mul_2exp_si(lo, lo, -static_cast<long>(static_cast<double>(digits) * 3.33) - 4);
    const bool enough = arf_cmp(w, lo) <= 0;
    arb_get_lbound_arf(lo, d.v, prec);
    if (enough) {
      out.status = Status::Certified;
      out.distance = Enclosure::from_bounds(lo, hi, digits);
      out.minimizers = (on_axis || on_circle) ? Minimizers::continuum(Minimizers::Proof::Exact)
                                              : Minimizers::count(1, Minimizers::Proof::Exact);
      if (!on_axis && !on_circle) { // the pair, approximately
        std::array<double, 3> kk = nearest_on_circle(t, c, wa, aa);
        const std::array<double, 3> cd{c[0].to_double_approx(), c[1].to_double_approx(),
                                       c[2].to_double_approx()};
        const double rr = t.r.to_double_approx(), rsd = std::sqrt(rs2.to_double_approx());
        if (std::string(which) == "far") // the farthest point of K, opposite the nearest
          for (size_t i = 0; i < 3; ++i)
            kk[i] = 2 * t.centre[i].to_double_approx() - kk[i];
        std::array<double, 3> tq{}, sq{};
        const double n = std::hypot(cd[0] - kk[0], cd[1] - kk[1], cd[2] - kk[2]);
        const double sg = std::string(which) == "far" ? -1 : 1;
        for (size_t i = 0; i < 3; ++i)
          tq[i] = kk[i] + sg * rr * (cd[i] - kk[i]) / n;
        const double m = std::hypot(tq[0] - cd[0], tq[1] - cd[1], tq[2] - cd[2]);
        for (size_t i = 0; i < 3; ++i)
          sq[i] = cd[i] + rsd * (tq[i] - cd[i]) / m;
        out.pairs.push_back(sphere_first ? std::array<std::array<double, 3>, 2>{sq, tq}
                                         : std::array<std::array<double, 3>, 2>{tq, sq});
      }
      arf_clear(lo);
      arf_clear(hi);
      arf_clear(w);
      return out;
    }
    arf_clear(lo);
    arf_clear(hi);
    arf_clear(w);
  }
}

// ---- plane vs torus (closed form, exact contact test) ------------------------------------------

// Plane n.x = delta. dist(plane, K) |n| = alpha - sqrt(beta) with alpha = |n.c - delta| and
// beta = R^2 |n x a|^2 / |a|^2 (K crosses the plane when alpha^2 < beta); the torus meets the
// plane iff alpha - sqrt(beta) <= sqrt(gamma), gamma = r^2 |n|^2, decided exactly by squaring
// twice (X = alpha^2 - beta - gamma >= 0 and X^2 vs 4 beta gamma).
DistanceResult plane_torus(const core::QuadricMatrix& pl, const core::Torus& t, long digits,
                           bool plane_first) {
  DistanceResult out;
  std::array<Rational, 3> n;
  Rational nn, na, aa, nc;
  for (size_t i = 0; i < 3; ++i) {
    n[i] = Rational(2) * pl(static_cast<int>(i), 3);
    nn += n[i] * n[i];
    na += n[i] * t.axis[i];
    aa += t.axis[i] * t.axis[i];
    nc += n[i] * t.centre[i];
  }
  const Rational delta = -pl(3, 3);
  const Rational alpha = core::abs(nc - delta);
  const Rational beta = t.R * t.R * (nn * aa - na * na) / aa, gamma = t.r * t.r * nn;
  out.critical_candidates = 2;
  out.eliminated_degree = 2;
  const Rational X = alpha * alpha - beta - gamma;
  const bool circle = beta.is_zero(); // plane orthogonal to the axis
  if (alpha * alpha < beta || X.sign() < 0 || X * X < Rational(4) * beta * gamma) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
    out.note = "the plane cuts the torus";
    return out;
  }
  if (X * X == Rational(4) * beta * gamma) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = circle ? Minimizers::continuum(Minimizers::Proof::Exact)
                            : Minimizers::count(1, Minimizers::Proof::Exact);
    out.note = "the plane touches the torus";
    return out;
  }
  const long prec = static_cast<long>(static_cast<double>(digits) * 3.33) + 128;
  Ball a, b, nr, r, d;
  arb_set_fmpq(a.v, alpha.raw(), prec);
  arb_set_fmpq(b.v, beta.raw(), prec);
  arb_sqrt(b.v, b.v, prec);
  arb_set_fmpq(nr.v, nn.raw(), prec);
  arb_sqrt(nr.v, nr.v, prec);
  arb_set_fmpq(r.v, t.r.raw(), prec);
  arb_sub(d.v, a.v, b.v, prec);
  arb_div(d.v, d.v, nr.v, prec);
  arb_sub(d.v, d.v, r.v, prec);
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  arb_get_lbound_arf(lo, d.v, prec);
  arb_get_ubound_arf(hi, d.v, prec);
  out.distance = Enclosure::from_bounds(lo, hi, digits);
  arf_clear(lo);
  arf_clear(hi);
  out.status = Status::Certified;
  out.minimizers = circle ? Minimizers::continuum(Minimizers::Proof::Exact)
                          : Minimizers::count(1, Minimizers::Proof::Exact);
  if (!circle) { // approximate pair: the point of K nearest the plane, then along -n
    double s = (nc - delta).sign() > 0 ? 1 : -1, nd = std::sqrt(nn.to_double_approx()),
           ad = std::sqrt(aa.to_double_approx());
    std::array<double, 3> m{}, k{}, tq{}, pq{};
    double mn = 0, dot = na.to_double_approx() / ad;
    for (size_t i = 0; i < 3; ++i) {
      m[i] = n[i].to_double_approx() - dot * t.axis[i].to_double_approx() / ad;
      mn += m[i] * m[i];
    }
    mn = std::sqrt(mn);
    for (size_t i = 0; i < 3; ++i) {
      k[i] = t.centre[i].to_double_approx() - s * t.R.to_double_approx() * m[i] / mn;
      tq[i] = k[i] - s * t.r.to_double_approx() * n[i].to_double_approx() / nd;
      pq[i] = tq[i] - s * out.approx() * n[i].to_double_approx() / nd;
    }
    out.pairs.push_back(plane_first ? std::array<std::array<double, 3>, 2>{pq, tq}
                                    : std::array<std::array<double, 3>, 2>{tq, pq});
  }
  return out;
}

// ---- a quadric of revolution sharing the torus axis ----------------------------------------

// dist(S, T) for S coaxial with T: m = dist(K, S) is the 2D distance from (R, 0) to the
// meridian conic (every circle point is alike), found by the exact point-quadric sextic on
// the conic seen as a cylinder; S meets T iff m <= r (S always has points outside the solid
// torus: on the axis, or at infinity), else d = m - r along a circle of pairs.
DistanceResult coaxial_torus(const core::QuadricMatrix& meridian, const core::Torus& t, long digits,
                             bool quadric_first) {
  DistanceResult out;
  PointQuadricResult pq =
      point_quadric_critical({t.R, Rational(0), Rational(0)}, meridian, digits + 5);
  out.eliminated_degree = pq.sextic_degree;
  out.critical_candidates = static_cast<int>(pq.criticals.size());
  if (!pq.ok || pq.criticals.empty()) {
    out.status = Status::Undecided;
    out.note =
        "coaxial surface of revolution: " + (pq.ok ? std::string("no critical point") : pq.note);
    return out;
  }
  const long prec = static_cast<long>(static_cast<double>(digits) * 3.33) + 128;
  // [front.lower, front.upper] contains the least critical distance (criticals are sorted by
  // certified lower bounds), whichever candidate attains it; its foot is display only.
  Ball m, lo, r, d;
  arb_set_str(m.v, pq.criticals.front().lower.c_str(), prec);
  arb_set_str(lo.v, pq.criticals.front().upper.c_str(), prec);
  arb_union(m.v, m.v, lo.v, prec);
  arb_set_fmpq(r.v, t.r.raw(), prec);
  if (arb_lt(m.v, r.v)) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
    out.note = "the coaxial surface of revolution enters the tube: it meets the torus";
    return out;
  }
  if (!arb_gt(m.v, r.v)) {
    out.status = Status::Undecided;
    out.note = "coaxial surface of revolution touching the torus? (not separated)";
    return out;
  }
  arb_sub(d.v, m.v, r.v, prec);
  arf_t l, h;
  arf_init(l);
  arf_init(h);
  arb_get_lbound_arf(l, d.v, prec);
  arb_get_ubound_arf(h, d.v, prec);
  out.distance = Enclosure::from_bounds(l, h, digits);
  arf_clear(l);
  arf_clear(h);
  out.status = Status::Certified;
  out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
  out.note = "coaxial surfaces of revolution: a circle of closest pairs (one shown)";
  // One representative pair, approximately: the meridian foot (X, Z) in the half-plane of a
  // unit vector u orthogonal to the axis.
  const auto& f = pq.criticals.front().foot;
  std::array<double, 3> ad{t.axis[0].to_double_approx(), t.axis[1].to_double_approx(),
                           t.axis[2].to_double_approx()};
  double an = std::hypot(ad[0], ad[1], ad[2]);
  for (auto& x : ad)
    x /= an;
  std::array<double, 3> u =
      std::fabs(ad[0]) < 0.9 ? std::array<double, 3>{1, 0, 0} : std::array<double, 3>{0, 1, 0};
  double ua = u[0] * ad[0] + u[1] * ad[1] + u[2] * ad[2];
  for (size_t i = 0; i < 3; ++i)
    u[i] -= ua * ad[i];
  double un = std::hypot(u[0], u[1], u[2]);
  std::array<double, 3> p{}, k{}, qq{};
  for (size_t i = 0; i < 3; ++i) {
    u[i] /= un;
    p[i] = t.centre[i].to_double_approx() + std::fabs(f[0]) * u[i] + f[2] * ad[i];
    k[i] = t.centre[i].to_double_approx() + t.R.to_double_approx() * u[i];
  }
  double pk = std::hypot(p[0] - k[0], p[1] - k[1], p[2] - k[2]);
  for (size_t i = 0; i < 3; ++i)
    qq[i] = k[i] + t.r.to_double_approx() * (p[i] - k[i]) / pk;
  out.pairs.push_back(quadric_first ? std::array<std::array<double, 3>, 2>{p, qq}
                                    : std::array<std::array<double, 3>, 2>{qq, p});
  return out;
}

// ---- float helpers for approximate witness points (never used in a decision) -------------

double qval(const core::QuadricMatrix& q, const std::array<double, 4>& X,
            std::array<double, 3>* g) {
  double v = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      v += q(i, j).to_double_approx() * X[static_cast<size_t>(i)] * X[static_cast<size_t>(j)];
  if (g)
    for (int i = 0; i < 3; ++i) {
      double s = 0;
      for (int j = 0; j < 4; ++j)
        s += 2 * q(i, j).to_double_approx() * X[static_cast<size_t>(j)];
      (*g)[static_cast<size_t>(i)] = s;
    }
  return v;
}

std::array<double, 3> float_project(const core::QuadricMatrix& q, std::array<double, 3> x) {
  for (int it = 0; it < 30; ++it) {
    std::array<double, 3> g{};
    double v = qval(q, {x[0], x[1], x[2], 1}, &g), n2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
    if (n2 == 0) break;
    for (size_t i = 0; i < 3; ++i)
      x[i] -= v / n2 * g[i];
  }
  return x;
}

double float_tube(const core::Torus& t, const std::array<double, 3>& x) { // dist(x, K) - r
  double w[3], a[3], an = 0, h = 0, w2 = 0;
  for (size_t i = 0; i < 3; ++i) {
    w[i] = x[i] - t.centre[i].to_double_approx();
    a[i] = t.axis[i].to_double_approx();
    an += a[i] * a[i];
  }
  an = std::sqrt(an);
  for (size_t i = 0; i < 3; ++i) {
    h += w[i] * a[i] / an;
    w2 += w[i] * w[i];
  }
  double rho = std::sqrt(std::max(0.0, w2 - h * h));
  return std::hypot(rho - t.R.to_double_approx(), h) - t.r.to_double_approx();
}

// ---- contact of a quadric and the torus --------------------------------------------------------

enum class Contact { Disjoint, Meet, Unknown };

// Sign of the torus quartic over S1 at the critical points of T restricted to S1 (see header).
Contact quadric_torus_contact(const SourceQuadric& src, const TorusPolys& tp, bool ellipsoid,
                              std::array<double, 3>& witness, std::string& why) {
  // Certified points of S1 inside (T < 0) and outside (T > 0) the solid torus; points inside
  // and outside (S1 connected: an ellipsoid), or a point inside when every component of S1
  // reaches infinity, mean the surface crosses the torus. Not "any quadric but an ellipsoid":
  // x^2 + y^2 + z^2 = 0 is a single point, inside the solid torus on its core circle at
  // distance r from the torus, and was certified as meeting it.
  const bool unbounded = components_unbounded(*src.quadric);
  const auto crosses = [ellipsoid, unbounded](const CriticalSigns& s) {
    return s.neg_point && ((ellipsoid && s.pos_point) || unbounded);
  };
  const auto disjoint = [ellipsoid](const CriticalSigns& s) {
    return s.all_signed && (!s.any_neg || (ellipsoid && !s.any_pos));
  };
  const CriticalSigns cs =
      critical_signs(src, tp.T, [&](const CriticalSigns& s) { return crosses(s) || disjoint(s); });
  if (!cs.finite) {
    why = "the critical points of the torus equation on the quadric form a curve";
    return Contact::Unknown;
  }
  if (crosses(cs)) {
    witness = *cs.neg_point;
    if (cs.pos_point) { // bisection on S1 between the two points (float; the witness is
                        // approximate)
      std::array<double, 3> a = *cs.neg_point, b = *cs.pos_point;
      for (int it = 0; it < 80; ++it) {
        std::array<double, 3> m{};
        for (size_t i = 0; i < 3; ++i)
          m[i] = 0.5 * (a[i] + b[i]);
        m = float_project(*src.quadric, m);
        (float_tube(tp.torus[0], m) < 0 ? a : b) = m;
      }
      witness = a;
    }
    return Contact::Meet;
  }
  // T > 0 at every critical point, or (ellipsoid) T < 0 at every one: inside the tube.
  if (disjoint(cs)) return Contact::Disjoint;
  why = "a critical value of the torus equation on the quadric is not separated from 0 "
        "(touching?)";
  return Contact::Unknown;
}

} // namespace

namespace {

// The offset system from a source S1 to the torus (normal line coplanar with the axis and
// meeting the core circle), minimised over its exact solution cover.
void offset_to_torus(const SourceQuadric& src, const core::Torus& t, const TorusPolys& tp,
                     long digits, bool source_first, DistanceResult& out) {
  const Poly3 na = dot(src.N, tp.A), s = dot(tp.W, tp.A);
  const Poly3 F2 = dot(src.N, cross(tp.W, tp.A));
  V3 u;
  for (size_t i = 0; i < 3; ++i)
    u[i] = na * tp.W[i] - s * src.N[i];
  const Poly3 F3 = dot(u, u) - Poly3(tp.R2) * na * na;
  algebra::SolutionCover cover = algebra::cover_real_solutions({src.f, F2, F3}, Rational(1, 16));
  if (!cover.ok) {
    out.status = Status::Undecided;
    out.note = "not supported yet: the offset system has a curve of solutions (" + cover.note +
               "; e.g. a surface of revolution sharing the torus axis)";
    return;
  }
  TorusTarget tgt(t);
  minimize_over_cover(cover, src, tgt, digits, source_first, true, out);
}

} // namespace

DistanceResult quadric_torus_distance(const core::QuadricMatrix& q, const core::Torus& t,
                                      long digits, bool quadric_first) {
  // An ellipsoid outside the solid torus: the elimination-free certificate (torus_fast.hpp).
  // Spheres and coaxial ellipsoids of revolution keep their closed forms (exact, and a circle
  // of minimizers is what the fast path refuses).
  if (q.kind() == core::QuadricKind::Ellipsoid && !q.is_sphere() &&
      !meridian_conic(q, Axis{t.centre, t.axis}, 2))
    if (const auto e = convex_quadric(q); e && e->is_ellipsoid())
      if (auto fast = ellipsoid_torus_fast(*e, t, digits, quadric_first)) return *fast;
  return quadric_torus_distance_exact(q, t, digits, quadric_first);
}

DistanceResult quadric_torus_distance_exact(const core::QuadricMatrix& q, const core::Torus& t,
                                            long digits, bool quadric_first) {
  if (q.is_sphere()) return sphere_torus(q, t, digits, quadric_first);
  if (q.is_plane()) return plane_torus(q, t, digits, quadric_first);
  if (auto mer = meridian_conic(q, Axis{t.centre, t.axis}, 2))
    return coaxial_torus(*mer, t, digits, quadric_first);
  DistanceResult out;
  const TorusPolys tp = torus_polys(t);
  SourceQuadric src(q);
  std::array<double, 3> witness{};
  std::string why;
  const bool ellipsoid = q.kind() == core::QuadricKind::Ellipsoid;
  Contact c = quadric_torus_contact(src, tp, ellipsoid, witness, why);
  if (c == Contact::Unknown) {
    out.status = Status::Undecided;
    out.note = "contact not decided: " + why;
    return out;
  }
  if (c == Contact::Meet) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
    out.note = "the quadric meets the torus (certified points of the quadric inside and outside "
               "the solid torus); the pair is an approximate common point (float bisection)";
    out.pairs.push_back({witness, witness});
    return out;
  }
  offset_to_torus(src, t, tp, digits, quadric_first, out);
  return out;
}

DistanceResult implicit_torus_distance(const core::Poly3& f, const core::Torus& t, long digits,
                                       bool implicit_first) {
  DistanceResult out;
  if (refuse_beyond_offset_degree(f, out)) return out;
  const TorusPolys tp = torus_polys(t);
  SourceQuadric src(f);
  // Contact: T's least value on each component of f = 0 is a critical value (T grows at
  // infinity), so T > 0 at every critical point of T on f = 0 (singular points of f included:
  // the cross product vanishes there) proves the surface outside the solid torus. Anything else
  // is left to the caller's contact proofs.
  const CriticalSigns cs =
      critical_signs(src, tp.T, [](const CriticalSigns& s) { return s.all_signed && !s.any_neg; });
  const bool outside = cs.finite && cs.all_signed && !cs.any_neg && cs.boxes > 0;
  if (!outside) {
    out.status = Status::Undecided;
    out.note = "contact not decided: the implicit surface may meet or enter the solid torus";
    return out;
  }
  offset_to_torus(src, t, tp, digits, implicit_first, out);
  return out;
}

} // namespace surfcert::certify
