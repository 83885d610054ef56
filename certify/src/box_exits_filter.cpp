// The interval filter on one face of box_exits (see box_exits_filter.hpp).
#include "box_exits_filter.hpp"

#include <CGAL/FPU.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace surfcert::certify::detail {

IConic::IConic(const FaceForm& m)
    : c00(enclose(m[0][0])), c01(enclose(m[0][1])), c11(enclose(m[1][1])), c02(enclose(m[0][2])),
      c12(enclose(m[1][2])), c22(enclose(m[2][2])) {}

IConic::IConic(const IMat4& m, size_t i, size_t j, size_t k, const Interval& c)
    : c00(m[i][i]), c01(m[i][j]), c11(m[j][j]), c02(m[i][k] * c + m[i][3]),
      c12(m[j][k] * c + m[j][3]), c22((m[k][k] * c + m[k][3] + m[3][k]) * c + m[3][3]) {}

Interval IConic::over(double mu, double mv, const Interval& du, const Interval& dv) const {
  const Interval u(mu), v(mv);
  const Interval fu = c00 * u + c01 * v + c02, fv = c01 * u + c11 * v + c12;
  const Interval f = (fu + c02) * u + (fv + c12) * v + c22; // the form at the midpoint
  return f + Interval(2) * (fu * du + fv * dv + c01 * du * dv) + c00 * CGAL::square(du) +
         c11 * CGAL::square(dv);
}

namespace {

struct Cell {
  double u0, u1, v0, v1;
};

// The rectangle grown outwards to doubles (cells cover it), and its 1/64 on each side.
struct Rect {
  Interval u0, u1, v0, v1; ///< enclosures of the rectangle's rational bounds
  Cell whole;
  double small_u, small_v;
  Rect(const core::Rational& u_lo, const core::Rational& u_hi, const core::Rational& v_lo,
       const core::Rational& v_hi)
      : u0(enclose(u_lo)), u1(enclose(u_hi)), v0(enclose(v_lo)),
        v1(enclose(v_hi)), whole{u0.inf(), u1.sup(), v0.inf(), v1.sup()},
        small_u((u1.sup() - u0.inf()) / 64), small_v((v1.sup() - v0.inf()) / 64) {}
};

// The cell's midpoint and its offsets from it (rounded outwards); false when not finite or the
// cell cannot be split any more.
bool centre(const Cell& c, double& mu, double& mv, Interval& du, Interval& dv) {
  mu = 0.5 * c.u0 + 0.5 * c.u1, mv = 0.5 * c.v0 + 0.5 * c.v1;
  du = Interval(c.u0, c.u1) - Interval(mu);
  dv = Interval(c.v0, c.v1) - Interval(mv);
  return std::isfinite(du.inf()) && std::isfinite(du.sup()) && std::isfinite(dv.inf()) &&
         std::isfinite(dv.sup());
}

bool may_vanish(const IConic& q, double mu, double mv, const Interval& du, const Interval& dv) {
  return q.over(mu, mv, du, dv).do_overlap(Interval(0));
}

void split(const Cell& c, double mu, double mv, std::vector<Cell>& todo) {
  if (c.u1 - c.u0 >= c.v1 - c.v0) {
    todo.push_back({c.u0, mu, c.v0, c.v1});
    todo.push_back({mu, c.u1, c.v0, c.v1});
  } else {
    todo.push_back({c.u0, c.u1, c.v0, mv});
    todo.push_back({c.u0, c.u1, mv, c.v1});
  }
}

double mid(const Interval& x) {
  return 0.5 * x.inf() + 0.5 * x.sup();
}

// The conic's value and half-gradient (fu, fv) in doubles (Newton's proposals only).
struct DConic {
  double c00, c01, c11, c02, c12, c22;
  explicit DConic(const IConic& q)
      : c00(mid(q.c00)), c01(mid(q.c01)), c11(mid(q.c11)), c02(mid(q.c02)), c12(mid(q.c12)),
        c22(mid(q.c22)) {}
  void eval(double u, double v, double& f, double& fu, double& fv) const {
    fu = c00 * u + c01 * v + c02;
    fv = c01 * u + c11 * v + c12;
    f = (fu + c02) * u + (fv + c12) * v + c22;
  }
};

// Newton in doubles on the two conics from (u, v); false when it does not settle. A proposal
// only (the Krawczyk test decides): on a pair posed far out the conics' rounded coefficients
// leave the last steps wandering at ~1e-11 of the coordinates, which is close enough.
bool newton(const DConic& a, const DConic& b, double& u, double& v) {
  // Rounding to nearest here (the callers round upwards for the intervals): the converged
  // point is then usually the double nearest the crossing, which is what gets reported.
  CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);
  double last = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 30; ++it) {
    double fa, au, av, fb, bu, bv;
    a.eval(u, v, fa, au, av);
    b.eval(u, v, fb, bu, bv);
    const double det = 2 * (au * bv - av * bu); // the Jacobian is 2 [[au, av], [bu, bv]]
    if (!(std::abs(det) > 0)) return false;
    const double du = (fa * bv - fb * av) / det, dv = (au * fb - bu * fa) / det;
    u -= du, v -= dv;
    if (!std::isfinite(u) || !std::isfinite(v)) return false;
    last = std::max(std::abs(du), std::abs(dv));
    if (last <= 0x1p-50 * (std::abs(u) + std::abs(v)) + 1e-300) return true;
  }
  return last <= 0x1p-20 * (std::abs(u) + std::abs(v));
}

// The Krawczyk operator of the system (a, b) = 0 on the box X = (xu, xv) around the point
// (pu, pv) inside it, with Y the inverse of the Jacobian at p in doubles (any matrix will do:
// the test's conclusion holds for every Y): K = p - Y F(p) + (I - Y J(X)) (X - p). True when
// K lies in X's interior: then X holds exactly one root of the exact conics (their entries lie
// in the enclosures), every Jacobian over X is nonsingular, and the root lies in K (ku, kv).
// Rounding upwards required.
bool krawczyk(const IConic& a, const IConic& b, double pu, double pv, const Interval& xu,
              const Interval& xv, Interval& ku, Interval& kv) {
  const Interval u(pu), v(pv);
  const Interval zero(0);
  // F at p, enclosed.
  const Interval fa = a.over(pu, pv, zero, zero), fb = b.over(pu, pv, zero, zero);
  // J over X: 2 [[a_u, a_v], [b_u, b_v]], half-gradients linear in (u, v).
  const Interval au = a.c00 * xu + a.c01 * xv + a.c02, av = a.c01 * xu + a.c11 * xv + a.c12;
  const Interval bu = b.c00 * xu + b.c01 * xv + b.c02, bv = b.c01 * xu + b.c11 * xv + b.c12;
  // Y: the inverse of the Jacobian at p (doubles).
  const double ja = 2 * (mid(a.c00) * pu + mid(a.c01) * pv + mid(a.c02));
  const double jb = 2 * (mid(a.c01) * pu + mid(a.c11) * pv + mid(a.c12));
  const double jc = 2 * (mid(b.c00) * pu + mid(b.c01) * pv + mid(b.c02));
  const double jd = 2 * (mid(b.c01) * pu + mid(b.c11) * pv + mid(b.c12));
  const double det = ja * jd - jb * jc;
  if (!(std::abs(det) > 0) || !std::isfinite(det)) return false;
  const Interval y00(jd / det), y01(-jb / det), y10(-jc / det), y11(ja / det);
  const Interval two(2);
  const Interval j00 = two * au, j01 = two * av, j10 = two * bu, j11 = two * bv;
  // M = I - Y J(X).
  const Interval m00 = Interval(1) - (y00 * j00 + y01 * j10), m01 = -(y00 * j01 + y01 * j11);
  const Interval m10 = -(y10 * j00 + y11 * j10), m11 = Interval(1) - (y10 * j01 + y11 * j11);
  const Interval du = xu - u, dv = xv - v;
  ku = u - (y00 * fa + y01 * fb) + m00 * du + m01 * dv;
  kv = v - (y10 * fa + y11 * fb) + m10 * du + m11 * dv;
  return ku.inf() > xu.inf() && ku.sup() < xu.sup() && kv.inf() > xv.inf() && kv.sup() < xv.sup();
}

struct Root {
  Interval xu, xv; ///< the box where it is the only root
  Interval eu, ev; ///< its tight enclosure (inside X)
  double pu, pv;   ///< Newton's converged point (the reported one when inside the enclosure)
};

bool inside(const Interval& a, const Interval& b) {
  return b.inf() <= a.inf() && a.sup() <= b.sup();
}

// A candidate cell (small, both forms may vanish on it): a root near it proved unique in a box
// X holding the cell, with a tight enclosure; false when not proved.
bool prove_root(const IConic& a, const IConic& b, const DConic& da, const DConic& db, const Cell& c,
                double face_size, Root& out) {
  double pu = 0.5 * c.u0 + 0.5 * c.u1, pv = 0.5 * c.v0 + 0.5 * c.v1;
  if (!newton(da, db, pu, pv)) return false;
  out.pu = pu, out.pv = pv;
  const double wu = c.u1 - c.u0, wv = c.v1 - c.v0;
  // A root far from the cell says nothing about the cell.
  if (pu < c.u0 - 2 * wu || pu > c.u1 + 2 * wu || pv < c.v0 - 2 * wv || pv > c.v1 + 2 * wv)
    return false;
  // X: centred at p, holding the cell with a margin of a quarter of its size.
  const double ru = std::max(pu - c.u0, c.u1 - pu) + 0.25 * wu;
  const double rv = std::max(pv - c.v0, c.v1 - pv) + 0.25 * wv;
  out.xu = Interval(pu) + Interval(-ru, ru);
  out.xv = Interval(pv) + Interval(-rv, rv);
  if (!inside(Interval(c.u0, c.u1), out.xu) || !inside(Interval(c.v0, c.v1), out.xv)) return false;
  Interval ku, kv;
  if (!krawczyk(a, b, pu, pv, out.xu, out.xv, ku, kv)) return false;
  // The tight enclosure: a box of 2^-49 (then 2^-46) of the scale around p, proved by the same
  // test; it lies in X, so its root is X's root. (A pair posed far out of its own size has
  // coefficients whose rounding leaves its crossings known to less than that: not read here,
  // the exact route refines them.)
  const double scale = std::max({face_size, std::abs(pu), std::abs(pv)});
  for (double e : {0x1p-49 * scale, 0x1p-46 * scale}) {
    const Interval tu = Interval(pu) + Interval(-e, e), tv = Interval(pv) + Interval(-e, e);
    if (!inside(tu, out.xu) || !inside(tv, out.xv)) return false;
    if (krawczyk(a, b, pu, pv, tu, tv, out.eu, out.ev)) return true;
  }
  return false;
}

enum class Place { Inside, Outside, Unknown };

// Where the enclosure x lies against the open interval (lo, hi) (enclosures of the bounds).
Place against(const Interval& x, const Interval& lo, const Interval& hi) {
  if (x.sup() < lo.inf() || x.inf() > hi.sup()) return Place::Outside;
  if (x.inf() > lo.sup() && x.sup() < hi.inf()) return Place::Inside;
  return Place::Unknown;
}

} // namespace

bool no_common_point(const IConic& a, const IConic& b, const core::Rational& u_lo,
                     const core::Rational& u_hi, const core::Rational& v_lo,
                     const core::Rational& v_hi, int budget) {
  CGAL::Protect_FPU_rounding<true> guard;
  const Rect r(u_lo, u_hi, v_lo, v_hi);
  std::vector<Cell> todo{r.whole};
  // A cell 1/64 of the face on both sides where both forms may vanish most likely holds a
  // crossing: the caller's next route then, without spending the rest of the budget splitting
  // around it (depth first, the search narrows onto it; a face with a crossing used all 256
  // cells, 10% of a plane section's time).
  while (!todo.empty()) {
    if (budget-- <= 0) return false;
    const Cell c = todo.back();
    todo.pop_back();
    double mu, mv;
    Interval du, dv;
    if (!centre(c, mu, mv, du, dv)) return false;
    if (!may_vanish(a, mu, mv, du, dv) || !may_vanish(b, mu, mv, du, dv)) continue;
    if (c.u1 - c.u0 <= r.small_u && c.v1 - c.v0 <= r.small_v) return false;
    if (!(c.u0 < mu && mu < c.u1) || !(c.v0 < mv && mv < c.v1)) return false; // no split left
    split(c, mu, mv, todo);
  }
  return true;
}

std::optional<std::vector<FacePoint>>
face_crossings(const IConic& a, const IConic& b, const core::Rational& u_lo,
               const core::Rational& u_hi, const core::Rational& v_lo, const core::Rational& v_hi) {
  CGAL::Protect_FPU_rounding<true> guard;
  const Rect r(u_lo, u_hi, v_lo, v_hi);
  const DConic da(a), db(b);
  std::vector<Cell> todo{r.whole};
  std::vector<Root> roots;
  // A cell is a candidate for a root once it is 1/64 of the face on both sides (as in
  // no_common_point); one whose root is not proved is split down to 1/1024 before giving up
  // (two crossings a few cells apart). Budgets: cells, and root proofs (two conics meet in at
  // most 4 points; some proofs fail before a smaller cell's succeeds).
  int budget = 1024, proofs = 16;
  const double tiny_u = r.small_u / 16, tiny_v = r.small_v / 16;
  const double face_size = std::max(r.whole.u1 - r.whole.u0, r.whole.v1 - r.whole.v0);
  while (!todo.empty()) {
    if (budget-- <= 0) return std::nullopt;
    const Cell c = todo.back();
    todo.pop_back();
    double mu, mv;
    Interval du, dv;
    if (!centre(c, mu, mv, du, dv)) return std::nullopt;
    if (!may_vanish(a, mu, mv, du, dv) || !may_vanish(b, mu, mv, du, dv)) continue;
    const Interval cu(c.u0, c.u1), cv(c.v0, c.v1);
    bool covered = false;
    for (const Root& rt : roots)
      covered = covered || (inside(cu, rt.xu) && inside(cv, rt.xv));
    if (covered) continue; // its only possible common point is that root
    const bool can_split = (c.u0 < mu && mu < c.u1) && (c.v0 < mv && mv < c.v1);
    if (c.u1 - c.u0 <= r.small_u && c.v1 - c.v0 <= r.small_v) {
      Root rt;
      if (proofs-- > 0 && prove_root(a, b, da, db, c, face_size, rt)) {
        roots.push_back(rt);
        continue;
      }
      if (c.u1 - c.u0 <= tiny_u && c.v1 - c.v0 <= tiny_v) return std::nullopt;
    }
    if (!can_split) return std::nullopt;
    split(c, mu, mv, todo);
  }
  // The same root proved from two cells: its enclosure lies in the other's box. Two roots are
  // distinct when their enclosures are disjoint; anything else is not decided here.
  std::vector<Root> distinct;
  for (const Root& rt : roots) {
    bool same = false;
    for (const Root& d : distinct) {
      if ((inside(rt.eu, d.xu) && inside(rt.ev, d.xv)) ||
          (inside(d.eu, rt.xu) && inside(d.ev, rt.xv))) {
        same = true;
        break;
      }
      if (rt.eu.do_overlap(d.eu) && rt.ev.do_overlap(d.ev)) return std::nullopt;
    }
    if (!same) distinct.push_back(rt);
  }
  std::vector<FacePoint> out;
  for (const Root& rt : distinct) {
    const Place pu = against(rt.eu, r.u0, r.u1), pv = against(rt.ev, r.v0, r.v1);
    if (pu == Place::Outside || pv == Place::Outside) continue;          // a root beyond the face
    if (pu != Place::Inside || pv != Place::Inside) return std::nullopt; // near an edge
    FacePoint fp;
    // Newton's point when the enclosure holds it (usually the double nearest the crossing: a
    // rational crossing such as (1/2, sqrt(3)/2) reads 0.5, not an enclosure's midpoint ulps off).
    fp.u = rt.eu.inf() <= rt.pu && rt.pu <= rt.eu.sup() ? rt.pu : mid(rt.eu);
    fp.v = rt.ev.inf() <= rt.pv && rt.pv <= rt.ev.sup() ? rt.pv : mid(rt.ev);
    fp.radius = std::max(0.5 * (rt.eu.sup() - rt.eu.inf()), 0.5 * (rt.ev.sup() - rt.ev.inf()));
    out.push_back(fp);
  }
  // In increasing u, as the exact route lists a face's crossings in its usual chart (the roots
  // of the resultant in x = u, isolated in increasing order): the same answer in the same order.
  std::sort(out.begin(), out.end(), [](const FacePoint& p, const FacePoint& q) {
    return p.u < q.u || (p.u == q.u && p.v < q.v);
  });
  return out;
}

std::optional<std::vector<FacePoint>> line_face_crossings(const IConic& line, const IConic& conic,
                                                          const core::Rational& u_lo,
                                                          const core::Rational& u_hi,
                                                          const core::Rational& v_lo,
                                                          const core::Rational& v_hi) {
  CGAL::Protect_FPU_rounding<true> guard;
  const Rect r(u_lo, u_hi, v_lo, v_hi);
  // The line 2 lu u + 2 lv v + l1 = 0. Parametrised by the coordinate along which it runs
  // more (its other coordinate a multiple of it that does not blow up): by u when |lv| >= |lu|,
  // v = m u + n; else by v, u = m v + n (the conic's roles of u and v swapped).
  const Interval &lu = line.c02, &lv = line.c12, &l1 = line.c22;
  const bool by_u = std::abs(mid(lv)) >= std::abs(mid(lu));
  const Interval& lead = by_u ? lv : lu; // divides
  const Interval& other = by_u ? lu : lv;
  if (lead.do_overlap(Interval(0))) return std::nullopt;
  const Interval m = -other / lead, n = -l1 / (Interval(2) * lead);
  // The conic in (t, s) with t the parameter and s the other coordinate.
  const Interval &q_tt = by_u ? conic.c00 : conic.c11, &q_ss = by_u ? conic.c11 : conic.c00;
  const Interval &q_t = by_u ? conic.c02 : conic.c12, &q_s = by_u ? conic.c12 : conic.c02;
  const Interval& q_ts = conic.c01;
  // Along s = m t + n: A t^2 + 2 B t + C.
  const Interval a = q_tt + m * (Interval(2) * q_ts + q_ss * m);
  const Interval b = (q_ts + q_ss * m) * n + q_t + q_s * m;
  const Interval c = (q_ss * n + Interval(2) * q_s) * n + conic.c22;
  const Interval disc = CGAL::square(b) - a * c;
  if (!std::isfinite(disc.inf()) || !std::isfinite(disc.sup())) return std::nullopt;
  std::vector<FacePoint> out;
  if (disc.sup() < 0) return out; // no real common point
  if (!(disc.inf() > 0) || a.do_overlap(Interval(0))) return std::nullopt;
  // t = (-B +- sqrt(disc)) / A. When B's sign is certain, the root whose numerator adds two
  // terms of one sign is computed so, and the other as C / (A t1) (their product is C / A):
  // both formulas are exact identities, so either gives an enclosure; these avoid the
  // cancellation that widens the first.
  const Interval sq = CGAL::sqrt(disc);
  std::array<Interval, 2> t{(-b + sq) / a, (-b - sq) / a}; // line_conic_crossings' order
  if (b.inf() > 0) {
    t[1] = (-b - sq) / a;
    t[0] = c / (a * t[1]);
  } else if (b.sup() < 0) {
    t[0] = (-b + sq) / a;
    t[1] = c / (a * t[0]);
  }
  const double face_size = std::max(r.whole.u1 - r.whole.u0, r.whole.v1 - r.whole.v0);
  std::array<FacePoint, 2> found;
  size_t count = 0;
  for (const Interval& ti : t) {
    if (!std::isfinite(ti.inf()) || !std::isfinite(ti.sup())) return std::nullopt;
    const Interval si = m * ti + n;
    const Interval& u = by_u ? ti : si;
    const Interval& v = by_u ? si : ti;
    const Place pu = against(u, r.u0, r.u1), pv = against(v, r.v0, r.v1);
    if (pu == Place::Outside || pv == Place::Outside) continue;          // beyond the face
    if (pu != Place::Inside || pv != Place::Inside) return std::nullopt; // near an edge
    FacePoint fp;
    fp.u = mid(u);
    fp.v = mid(v);
    fp.radius = std::max(0.5 * (u.sup() - u.inf()), 0.5 * (v.sup() - v.inf()));
    const double scale = std::max({face_size, std::abs(fp.u), std::abs(fp.v)});
    if (!(fp.radius <= 0x1p-46 * scale)) return std::nullopt; // too wide to report
    found[count++] = fp;
  }
  // line_conic_crossings parametrises by u unless lv = 0 exactly (an enclosure [0, 0]), and
  // lists (-B + sqrt) / A first: its larger parameter first when A > 0. A's sign does not
  // depend on the parametrisation (the conic's form at the line's direction, up to a square),
  // so the two points are put in that order by the coordinate it parametrises by.
  if (count == 2) {
    const bool exact_by_u = !(lv.inf() == 0 && lv.sup() == 0);
    const bool larger_first = a.inf() > 0;
    const double key0 = exact_by_u ? found[0].u : found[0].v;
    const double key1 = exact_by_u ? found[1].u : found[1].v;
    if ((key0 < key1) == larger_first) std::swap(found[0], found[1]);
  }
  out.assign(found.begin(), found.begin() + static_cast<long>(count));
  return out;
}

} // namespace surfcert::certify::detail
