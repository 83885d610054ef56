#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/distance/ball.hpp"

#include "surfcert/certify/distance/canal_distance.hpp"
#include "surfcert/certify/distance/capsule_pair.hpp"
#include "surfcert/certify/distance/common_apex.hpp"
#include "surfcert/certify/distance/cone_distance.hpp"
#include "surfcert/certify/distance/contact_sampling.hpp"
#include "surfcert/certify/distance/convex_distance.hpp"
#include "surfcert/certify/distance/cylinder_pair.hpp"
#include "surfcert/certify/distance/implicit_bnb.hpp"
#include "surfcert/certify/distance/nested_convex.hpp"
#include "surfcert/certify/distance/parametric_distance.hpp"
#include "surfcert/certify/distance/plane_quadric.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/certify/distance/quadric_pair.hpp"
#include "surfcert/certify/distance/solid_relation.hpp"
#include "surfcert/certify/distance/sphere_family.hpp"
#include "surfcert/certify/distance/symmetry.hpp"
#include "surfcert/certify/distance/torus_distance.hpp"
#include "surfcert/certify/distance/torus_pair.hpp"

#include "surfcert/algebra/mpoly.hpp"

#include <arb.h>
#include <flint/fmpq_mat.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace surfcert::certify {

using core::Rational;
using core::io::Json;

namespace {

// The ball [lower, upper] of a critical distance.
void critical_ball(arb_t out, const CriticalDistance& c, long prec) {
  Ball lo, hi;
  arb_set_str(lo.v, c.lower.c_str(), prec);
  arb_set_str(hi.v, c.upper.c_str(), prec);
  arb_union(out, lo.v, hi.v, prec);
}

// True when the conics at infinity x^T A3 x = 0 and x^T B3 x = 0 have a common component
// (gcd of the two ternary quadratic forms, FLINT): then a real curve of the QSIC may lie
// entirely at infinity.
bool conics_at_infinity_share_component(const core::QuadricMatrix& a,
                                        const core::QuadricMatrix& b) {
  auto form = [](const core::QuadricMatrix& q) {
    core::Mat4 m = q.matrix();
    for (size_t i = 0; i < 4; ++i)
      m[i][3] = m[3][i] = Rational(0);
    return algebra::quadric_poly(m); // homogeneous quadratic part in (x, y, z)
  };
  algebra::MPoly fa = form(a), fb = form(b);
  if (fa.is_zero() || fb.is_zero()) return true; // a plane: its "conic" is the whole line
  return !algebra::gcd(fa, fb).is_constant();
}

// Ellipsoid (x - c)^T M (x - c) = 1 and plane n.x = delta: the ellipsoid's support in the
// direction n is n.c + sqrt(n^T M^-1 n), so the distance is
// (|n.c - delta| - sqrt(n^T M^-1 n)) / |n| when positive, and 0 (they meet) otherwise; the
// comparison is exact (squares of rationals), the value enclosed with Arb.
void ellipsoid_plane(DistanceResult& out, const core::QuadricMatrix& e,
                     const core::QuadricMatrix& p, bool ellipsoid_first, long digits) {
  core::Mat4 m = e.matrix();
  if (m[0][0].sign() < 0) m = core::scaled(m, Rational(-1)); // positive definite block
  // E3^-1 by FLINT (3x3 rational).
  fmpq_mat_t A, Ainv;
  fmpq_mat_init(A, 3, 3);
  fmpq_mat_init(Ainv, 3, 3);
  for (slong i = 0; i < 3; ++i)
    for (slong j = 0; j < 3; ++j)
      fmpq_set(fmpq_mat_entry(A, i, j), m[static_cast<size_t>(i)][static_cast<size_t>(j)].raw());
  fmpq_mat_inv(Ainv, A);
  std::array<std::array<Rational, 3>, 3> inv;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      fmpq_set(inv[i][j].raw_mut(),
               fmpq_mat_entry(Ainv, static_cast<slong>(i), static_cast<slong>(j)));
  fmpq_mat_clear(A);
  fmpq_mat_clear(Ainv);
  std::array<Rational, 3> c, n;
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j)
      c[i] -= inv[i][j] * m[j][3];
    n[i] = Rational(2) * p(static_cast<int>(i), 3);
  }
  Rational delta = -p(3, 3), k = -m[3][3], nc, ninvn, nn;
  for (size_t i = 0; i < 3; ++i) {
    k += c[i] * m[i][i] * c[i];
    for (size_t j = 0; j < 3; ++j)
      if (j != i) k += c[i] * m[i][j] * c[j];
    nc += n[i] * c[i];
    nn += n[i] * n[i];
    for (size_t j = 0; j < 3; ++j)
      ninvn += n[i] * inv[i][j] * n[j];
  }
  Rational support2 = k * ninvn; // (n^T M^-1 n) with M = E3 / k
  Rational gap = core::abs(nc - delta);
  out.critical_candidates = 2;
  out.eliminated_degree = 2;
  out.minimizers = "1";
  out.status = Status::Certified;
  if (gap * gap <= support2) { // exact: the plane meets the ellipsoid
    out.distance = Enclosure::zero();
    out.minimizers = gap * gap == support2 ? "1" : "infinite";
    out.note =
        gap * gap == support2 ? "the plane touches the ellipsoid" : "the plane cuts the ellipsoid";
    return;
  }
  const long prec = bits_for(digits + 10);
  Ball sup, g, nrm, d;
  arb_set_fmpq(sup.v, support2.raw(), prec);
  arb_sqrt(sup.v, sup.v, prec);
  arb_set_fmpq(g.v, gap.raw(), prec);
  arb_set_fmpq(nrm.v, nn.raw(), prec);
  arb_sqrt(nrm.v, nrm.v, prec);
  arb_sub(d.v, g.v, sup.v, prec);
  arb_div(d.v, d.v, nrm.v, prec);
  set_distance_enclosure(out, d.v, digits);
  // The closest points (approximate): x* = c + s M^-1 n / sqrt(n^T M^-1 n) toward the plane.
  double sgn = (delta - nc).sign() > 0 ? 1 : -1, sq = std::sqrt(support2.to_double_approx());
  std::array<double, 3> x{}, f{};
  double kk = k.to_double_approx(), nd = 0, nn_d = nn.to_double_approx();
  for (size_t i = 0; i < 3; ++i) {
    double mi = 0;
    for (size_t j = 0; j < 3; ++j)
      mi += kk * inv[i][j].to_double_approx() * n[j].to_double_approx();
    x[i] = c[i].to_double_approx() + sgn * mi / sq;
  }
  for (size_t i = 0; i < 3; ++i)
    nd += n[i].to_double_approx() * x[i];
  for (size_t i = 0; i < 3; ++i)
    f[i] = x[i] - (nd - delta.to_double_approx()) / nn_d * n[i].to_double_approx();
  out.pairs.push_back(ellipsoid_first ? std::array<std::array<double, 3>, 2>{x, f}
                                      : std::array<std::array<double, 3>, 2>{f, x});
}

} // namespace

const char* const kUnprovenTiesNote =
    "several minimizing pairs at distances that agree to the requested precision: "
    "listed as minimizers (their equality is not proven)";

void note_unproven_ties(DistanceResult& out, size_t count) {
  if (count < 2) return;
  out.note += std::string(out.note.empty() ? "" : "; ") + kUnprovenTiesNote;
  out.ties = "unproven";
}

void set_distance_enclosure(DistanceResult& out, const arb_t d, long digits) {
  out.distance = Enclosure::from_ball(d, digits);
}

namespace {

DistanceResult quadric_distance(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                long digits, bool solid, Mode mode) {
  DistanceResult out;
  out.solid = solid;
  // Two elliptic cylinders (closed form when crossed, duality when parallel), in every mode:
  // the offset system has a curve of solutions for them.
  if (a.kind() != core::QuadricKind::Ellipsoid && b.kind() != core::QuadricKind::Ellipsoid &&
      !a.is_plane() && !b.is_plane())
    if (const auto ya = convex_quadric(a); ya && ya->is_cylinder())
      if (const auto yb = convex_quadric(b); yb && yb->is_cylinder())
        if (auto r = cylinder_pair_distance(*ya, *yb, digits)) {
          r->solid = solid;
          return *r;
        }
  // Disjoint convex solids (ellipsoids, elliptic cylinders and paraboloids): a separating
  // direction certifies the distance without elimination; anything it cannot prove falls
  // through. First, since it is the cheapest certificate.
  const auto ca = mode != Mode::Exact ? convex_quadric(a) : std::nullopt;
  const auto cb = ca ? convex_quadric(b) : std::nullopt;
  if (ca && cb) {
    if (mode == Mode::Float)
      if (auto r = separated_convex_distance_float(*ca, *cb)) {
        r->solid = solid;
        r->method = "convex_duality_float";
        return *r;
      }
    if (auto r = separated_convex_distance(*ca, *cb, digits)) {
      r->solid = solid;
      r->method = "convex_duality";
      return *r;
    }
    // Nested (an ellipsoid strictly inside the other solid): the same duality, minimized.
    if (auto r = nested_convex_distance(*ca, *cb, digits)) {
      if (solid && ca->is_ellipsoid() && cb->is_ellipsoid()) {
        out.status = Status::Certified;
        out.distance = Enclosure::zero();
        out.minimizers = "infinite";
        out.note = "solid distance: one solid contains the other";
        out.method = "nested_convex_duality";
        return out;
      }
      r->solid = solid;
      if (r->method.empty()) r->method = "nested_convex_duality";
      return *r;
    }
  }
  // An ellipsoid and a cone: the minimum over the cone's generator lines.
  if (ca && ca->is_ellipsoid() && !cb)
    if (auto r = ellipsoid_cone_distance(*ca, b, digits, true)) {
      r->solid = solid;
      return *r;
    }
  if (mode != Mode::Exact && !ca)
    if (auto e = convex_quadric(b); e && e->is_ellipsoid())
      if (auto r = ellipsoid_cone_distance(*e, a, digits, false)) {
        r->solid = solid;
        return *r;
      }
  const bool a_sphere = a.is_sphere(), b_sphere = b.is_sphere();
  if (!a_sphere && !b_sphere && (a.is_plane() || b.is_plane()) &&
      (a.kind() == core::QuadricKind::Ellipsoid || b.kind() == core::QuadricKind::Ellipsoid)) {
    ellipsoid_plane(out, a.is_plane() ? b : a, a.is_plane() ? a : b, !a.is_plane(), digits);
    return out;
  }
  // A plane and any other quadric (spheres go below): decided exactly on the parallel levels.
  if ((a.is_plane() || b.is_plane()) && !a_sphere && !b_sphere) {
    DistanceResult r =
        plane_quadric_distance(a.is_plane() ? a : b, a.is_plane() ? b : a, digits, a.is_plane());
    r.solid = solid;
    return r;
  }
  const core::QuadricMatrix& sph = a_sphere ? a : b;
  const core::QuadricMatrix& other = a_sphere ? b : a;

  // Do the surfaces meet? The certified topology decides.
  QsicResult t = classify_qsic(a, b, mode == Mode::Exact ? Mode::Exact : Mode::Filtered);
  if (t.status != Status::Certified) {
    out.status = Status::Undecided;
    out.note = "topology not certified";
    return out;
  }
  if (t.pencil == algebra::PencilKind::Degenerate)
    if (auto r = common_apex_contact(a, b)) {
      r->solid = solid;
      r->mode = mode;
      return *r;
    }
  if (t.pencil == algebra::PencilKind::Coincident) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = "infinite";
    out.note = "the surfaces coincide";
    return out;
  }
  if (t.morphology && t.morphology->connected_components > 0) {
    // The classification is projective: the real points may all lie at infinity (translated
    // paraboloids meet only there). Contact needs an affine point: a real curve has one
    // unless the conics at infinity share a component; otherwise an affine special point, or
    // a traced point, is the witness.
    complete_report_data(t, a, b);
    const auto& m = *t.morphology;
    const bool curve = m.loops + m.conics + m.lines + m.cubics > 0;
    const bool bounded = a.kind() == core::QuadricKind::Ellipsoid ||
                         b.kind() == core::QuadricKind::Ellipsoid; // no point at infinity
    bool affine = bounded || (curve && !conics_at_infinity_share_component(a, b));
    std::array<double, 3> w{};
    bool have = false;
    for (const auto& sp : t.special_points)
      if (!sp.at_infinity && !have) {
        w = sp.approx;
        have = affine = true;
      }
    if (curve && !have && affine) {
      // Affine contact is proven already (exact); a displayed pair comes from certified
      // points of the surfaces on both sides of each other (approximate common point).
      have = meet_by_sign_change(a, b, w);
    }
    if (affine) {
      out.status = Status::Certified;
      out.distance = Enclosure::zero();
      out.minimizers = curve ? "infinite" : std::to_string(m.isolated_points);
      if (have) out.pairs.push_back({w, w});
      out.note = "the surfaces meet (certified topology: " + std::string(m.id) + ")";
      return out;
    }
    if (curve && meet_by_sign_change(a, b, w)) {
      out.status = Status::Certified;
      out.distance = Enclosure::zero();
      out.minimizers = "infinite";
      out.pairs.push_back({w, w});
      out.note = "the surfaces meet (certified topology: " + std::string(m.id) +
                 "; an affine common point proven by certified points of a connected surface "
                 "on both sides of the other; the pair is an approximate common point)";
      return out;
    }
    if (curve || !t.special_points_complete) {
      out.status = Status::Undecided;
      out.note =
          "the real intersection (" + std::string(m.id) + ") may lie at infinity only; not decided";
      return out;
    }
    // Every real common point is at infinity: the affine surfaces are disjoint.
  }
  if (solid && a.kind() == core::QuadricKind::Ellipsoid &&
      b.kind() == core::QuadricKind::Ellipsoid) {
    complete_report_data(t, a, b);
    if (t.ellipsoid_relation == "nested") {
      out.status = Status::Certified;
      out.distance = Enclosure::zero();
      out.minimizers = "infinite";
      out.note = "solid distance: one solid contains the other";
      return out;
    }
  }

  if (!a_sphere && !b_sphere) {
    DistanceResult d = quadric_pair_distance(a, b, digits);
    d.solid = solid;
    return d;
  }
  // Centre and squared radius of the sphere k(|x|^2) - 2k c.x + k|c|^2 - k r^2.
  std::array<Rational, 3> c;
  Rational k = sph(0, 0), c2;
  for (int i = 0; i < 3; ++i) {
    c[static_cast<size_t>(i)] = -sph(i, 3) / k;
    c2 += c[static_cast<size_t>(i)] * c[static_cast<size_t>(i)];
  }
  Rational r2 = c2 - sph(3, 3) / k;

  // A plane (no quadratic part): 2 b.x + c0 = 0, the distance from the centre in closed form.
  bool plane = true;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      plane = plane && other(i, j).is_zero();
  if (plane) {
    const long prec = bits_for(digits + 10);
    Rational num = other(3, 3), n2;
    for (int i = 0; i < 3; ++i) {
      num += Rational(2) * other(i, 3) * c[static_cast<size_t>(i)];
      n2 += Rational(4) * other(i, 3) * other(i, 3);
    }
    Ball dc, r, d, gap;
    Rational q = num * num / n2; // squared distance from the centre to the plane
    if (q <= r2) {               // the topology said the surfaces do not meet: q > r2
      out.status = Status::Undecided;
      out.note = "the plane meets the ball although the topology said no contact";
      return out;
    }
    arb_set_fmpq(dc.v, q.raw(), prec);
    arb_sqrt(dc.v, dc.v, prec);
    arb_set_fmpq(r.v, r2.raw(), prec);
    arb_sqrt(r.v, r.v, prec);
    // dc - r = (q - r2) / (dc + r): the exact numerator keeps a tiny gap from cancelling.
    arb_set_fmpq(gap.v, (q - r2).raw(), prec);
    arb_add(d.v, dc.v, r.v, prec);
    arb_div(d.v, gap.v, d.v, prec);
    set_distance_enclosure(out, d.v, digits);
    out.minimizers = "1";
    out.critical_candidates = 1;
    out.eliminated_degree = 1;
    std::array<double, 3> f{}, s{};
    double tf = num.to_double_approx() / n2.to_double_approx(),
           rr = std::sqrt(r2.to_double_approx());
    double dcd = std::sqrt(q.to_double_approx());
    for (size_t i = 0; i < 3; ++i) {
      double ni = 2 * other(static_cast<int>(i), 3).to_double_approx();
      f[i] = c[i].to_double_approx() - tf * ni; // foot on the plane
      s[i] = c[i].to_double_approx() + rr * (f[i] - c[i].to_double_approx()) / dcd; // on the sphere
    }
    out.pairs.push_back(a_sphere ? std::array<std::array<double, 3>, 2>{s, f}
                                 : std::array<std::array<double, 3>, 2>{f, s});
    out.status = Status::Certified;
    return out;
  }
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
      out.pairs.push_back(a_sphere ? std::array<std::array<double, 3>, 2>{s, f}
                                   : std::array<std::array<double, 3>, 2>{f, s});
    }
    out.minimizers = continuum ? "infinite" : std::to_string(S.size());
    out.status = Status::Certified;
    if (!continuum && S.size() > 1 && all_exact) {
      out.ties = "proven";
      out.note += std::string(out.note.empty() ? "" : "; ") + "the " + std::to_string(S.size()) +
                  " minimizing pairs are at exactly the same distance (proven: the same exact "
                  "rational squared distance from the centre to the foot points)";
    } else if (continuum && !all_exact) {
      // A circle of feet overlapping point candidates not proven equal to it: "infinite"
      // holds only if the circle attains the minimum, which is not proven (a note that
      // prove_ties, which drops the generic tie note for continua, leaves in place).
      out.note += std::string(out.note.empty() ? "" : "; ") +
                  "a circle of foot points and other critical points agree to the requested "
                  "precision: which of them attain the extreme (and so the minimizer count) is "
                  "not proven";
      out.ties = "unproven";
    } else if (!all_exact) {
      // Candidates left overlapping the extreme after the separation budget: all listed,
      // their equality unproven.
      note_unproven_ties(out, S.size());
    }
    return out;
  }
}

} // namespace

namespace {

bool is_count(const std::string& m) {
  return !m.empty() && std::all_of(m.begin(), m.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// What every answer goes through last, whatever route produced it:
// - a minimizer count that is not proven (several candidates whose equality is unproven, or
//   a route that says its count is not proven) becomes "undecided", the candidate count kept
//   apart in minimizer_candidates: a count is reported only when proven;
// - the width contract: a certified enclosure satisfies upper - lower <= 10^-digits lower on
//   the printed decimals, or the answer is not certified.
void finalize(DistanceResult& r, long digits) {
  if (r.status == Status::Certified && is_count(r.minimizers)) {
    const long n = std::stol(r.minimizers);
    if ((n > 1 && r.ties == "unproven") || r.count_unproven) {
      r.minimizer_candidates = n;
      r.minimizers = "undecided";
      r.note += std::string(r.note.empty() ? "" : "; ") +
                "the number of minimizers is not proven (" + std::to_string(n) + " candidate" +
                (n == 1 ? "" : "s") + " not separated from the minimum)";
    }
  }
  if (r.status == Status::Certified && r.distance && !r.distance->is_zero() &&
      !r.distance->meets_width(digits)) {
    r.status = Status::Undecided;
    r.note += std::string(r.note.empty() ? "" : "; ") + "the enclosure is wider than --digits " +
              std::to_string(digits) + " asks (kept as what was established)";
  }
}

// Computes, and when a certified enclosure misses the width contract, computes once more
// with more digits (a route's own refinement stopped short, e.g. cancellation in d - r).
template <class F> DistanceResult with_width_contract(F&& compute, long digits) {
  DistanceResult r = compute(digits);
  if (r.status == Status::Certified && r.distance && !r.distance->is_zero() &&
      !r.distance->meets_width(digits) && digits < 1000) {
    DistanceResult finer = compute(std::min(2 * digits + 10, 1000L));
    if (finer.status == Status::Certified && finer.distance &&
        (finer.distance->is_zero() || finer.distance->meets_width(digits)))
      r = std::move(finer);
  }
  finalize(r, digits);
  return r;
}

} // namespace

DistanceResult surface_distance(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                long digits, bool solid, Mode mode) {
  return with_width_contract(
      [&](long dg) {
        DistanceResult r = quadric_distance(a, b, dg, solid, mode);
        r.mode = mode;
        if (r.method.empty() && !r.univariate_degrees.empty()) r.method = "offset_system";
        if (r.ties == "unproven") prove_ties(r, core::Surface(a), core::Surface(b));
        return r;
      },
      digits);
}

namespace {

DistanceResult any_surface_distance(const core::Surface& a, const core::Surface& b, long digits,
                                    bool solid, Mode mode) {
  DistanceResult out;
  out.solid = solid;
  out.mode = mode;
  const auto* pa = std::get_if<core::ParametricSurface>(&a);
  const auto* pb = std::get_if<core::ParametricSurface>(&b);
  if (pa || pb) {
    out = pa ? parametric_distance(*pa, b, digits, true, mode, solid)
             : parametric_distance(*pb, a, digits, false, mode, solid);
    out.mode = mode;
    return out;
  }
  const auto* qa = std::get_if<core::QuadricMatrix>(&a);
  const auto* qb = std::get_if<core::QuadricMatrix>(&b);
  if (qa && qb) return surface_distance(*qa, *qb, digits, solid, mode);
  if (!qa && !qb) {
    const auto* ta = std::get_if<core::Torus>(&a);
    const auto* tb = std::get_if<core::Torus>(&b);
    const auto* ca = std::get_if<core::CanalSurface>(&a);
    const auto* cb = std::get_if<core::CanalSurface>(&b);
    if (ca && cb)
      if (auto r = capsule_pair_distance(*ca, *cb, digits)) {
        r->solid = solid;
        r->mode = mode;
        return *r;
      }
    if (ta && tb) { // every mode: the circle bound is the only route for two tori
      if (auto r = torus_pair_distance(*ta, *tb, digits)) {
        r->solid = solid;
        r->mode = mode;
        return *r;
      }
      // The generic branch and bound on the two quartics (decides pairs the circle bound
      // leaves open when their closest pair is isolated).
      out = implicit_pair_distance(torus_polynomial(*ta), torus_polynomial(*tb), digits);
      if (out.status != Status::Certified) {
        out = DistanceResult();
        out.status = Status::Undecided;
        out.note = "two tori whose tubes may meet, nest, or have a continuum of minimizers: "
                   "not supported yet";
      }
      out.solid = solid;
      out.mode = mode;
      return out;
    }
    const auto* ia = std::get_if<core::ImplicitSurface>(&a);
    const auto* ib = std::get_if<core::ImplicitSurface>(&b);
    if (ia && ib) { // two implicit surfaces: the generic branch and bound (bounded, smooth)
      out = implicit_pair_distance(ia->f, ib->f, digits);
      out.solid = solid;
      out.mode = mode;
      return out;
    }
    if ((ia && tb) || (ta && ib)) {
      // The generic branch and bound first (fast when the implicit surface is bounded), then
      // the offset system with the implicit source (slow beyond cubics, but any degree).
      out = ia ? implicit_pair_distance(ia->f, torus_polynomial(*tb), digits)
               : implicit_pair_distance(torus_polynomial(*ta), ib->f, digits);
      if (out.status != Status::Certified) { // an unbounded implicit surface, clipped
        out =
            bounded_unbounded_distance(torus_polynomial(ia ? *tb : *ta), (ia ? ia : ib)->f, digits);
        if (ia)
          for (auto& pr : out.pairs)
            std::swap(pr[0], pr[1]);
      }
      if (out.status != Status::Certified)
        out = ia ? implicit_torus_distance(ia->f, *tb, digits, true)
                 : implicit_torus_distance(ib->f, *ta, digits, false);
      out.solid = solid;
      out.mode = mode;
      if (out.method.empty() && !out.univariate_degrees.empty()) out.method = "offset_system";
      return out;
    }
    if ((ca || ta) && (cb || tb))
      if (auto r = sphere_family_distance(a, b, digits)) {
        r->solid = solid;
        r->mode = mode;
        return *r;
      }
    out.status = Status::Undecided;
    out.note = "not supported yet: distance between two non-quadric surfaces (" +
               core::surface_kind(a) + ", " + core::surface_kind(b) + ")";
    return out;
  }
  const core::QuadricMatrix& q = qa ? *qa : *qb;
  const core::Surface& other = qa ? b : a;
  if (const auto* t = std::get_if<core::Torus>(&other))
    out = mode == Mode::Exact ? quadric_torus_distance_exact(q, *t, digits, qa != nullptr)
                              : quadric_torus_distance(q, *t, digits, qa != nullptr);
  else if (const auto* im = std::get_if<core::ImplicitSurface>(&other)) {
    // A quadric against a bounded implicit surface: the generic branch and bound first
    // (milliseconds to seconds; the offset system of a quartic against an ellipsoid runs for
    // minutes), the offset route when it cannot decide (unbounded or singular surfaces,
    // tangential contact, flat minima).
    const core::Poly3 qp = q.to_poly();
    if (q.kind() == core::QuadricKind::Ellipsoid) {
      out = qa ? implicit_pair_distance(qp, im->f, digits)
               : implicit_pair_distance(im->f, qp, digits);
      if (out.status != Status::Certified) { // an unbounded implicit surface, clipped
        out = bounded_unbounded_distance(qp, im->f, digits);
        if (!qa)
          for (auto& pr : out.pairs)
            std::swap(pr[0], pr[1]);
      }
    } else if (!q.is_plane() || im->f.total_degree() > core::kMaxOffsetDegree) {
      // an unbounded quadric (a plane only beyond the plane route's degrees): clipped near
      // the bounded implicit surface
      out = bounded_unbounded_distance(im->f, qp, digits);
      if (qa)
        for (auto& pr : out.pairs)
          std::swap(pr[0], pr[1]);
    }
    if (out.status != Status::Certified) {
      out = DistanceResult();
      out = implicit_quadric_distance(im->f, q, digits, qa == nullptr);
    }
  } else
    out = quadric_canal_distance(q, std::get<core::CanalSurface>(other), digits, qa != nullptr);
  out.solid = solid;
  out.mode = mode;
  if (out.method.empty() && !out.univariate_degrees.empty()) out.method = "offset_system";
  return out;
}

} // namespace

namespace {
DistanceResult surface_distance_unchecked(const core::Surface& a, const core::Surface& b,
                                          long digits, bool solid, Mode mode);
} // namespace

DistanceResult surface_distance(const core::Surface& a, const core::Surface& b, long digits,
                                bool solid, Mode mode) {
  return with_width_contract(
      [&](long dg) { return surface_distance_unchecked(a, b, dg, solid, mode); }, digits);
}

namespace {

DistanceResult surface_distance_unchecked(const core::Surface& a, const core::Surface& b,
                                          long digits, bool solid, Mode mode) {
  DistanceResult r = any_surface_distance(a, b, digits, solid, mode);
  const bool two_quadrics = std::holds_alternative<core::QuadricMatrix>(a) &&
                            std::holds_alternative<core::QuadricMatrix>(b);
  const bool parametric = std::holds_alternative<core::ParametricSurface>(a) ||
                          std::holds_alternative<core::ParametricSurface>(b);
  // Left undecided (tubes that may meet, a canal that may cross a torus, ...): a sign change
  // of one surface's equation along the other, connected one proves contact.
  std::array<double, 3> w{};
  double residual = 0;
  if (r.status == Status::Undecided && !two_quadrics && !parametric &&
      surfaces_meet_by_sign_change(a, b, w, &residual)) {
    const std::string why = r.note;
    r = DistanceResult();
    r.status = Status::Certified;
    r.mode = mode;
    r.distance = Enclosure::zero();
    r.minimizers = "infinite";
    const bool located = residual <= 1e-9 * (1 + std::hypot(w[0], w[1], w[2]));
    if (located) r.pairs.push_back({w, w});
    r.method = "sign_change_contact";
    r.note = std::string("the surfaces meet: certified points of a connected surface on both "
                         "sides of the other") +
             (located ? " (the pair is an approximate common point)"
                      : " (no approximate common point located: no pair listed)") +
             (why.empty() ? std::string() : "; the other routes said: " + why);
  }
  // Two quadrics went through the overload above, which already tried.
  if (r.ties == "unproven" && !two_quadrics) prove_ties(r, a, b);
  // The parametric route handled solid itself (passed to the implicit surface's routes).
  if (solid && !two_quadrics && !parametric) apply_solid_option(r, a, b);
  return r;
}

} // namespace

Json distance_envelope_json(const DistanceResult& r, long digits) {
  Json o = Json::object();
  o.set("status", Json::string(to_string(r.status)));
  if (!r.note.empty()) o.set("note", Json::string(r.note));
  Json res = Json::object();
  if (r.distance) { // a proven enclosure (certified, or what an undecided answer established)
    Json d = Json::object();
    d.set("lower", Json::string(r.distance->lower()));
    d.set("upper", Json::string(r.distance->upper()));
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", r.distance->approx());
    d.set("approx", Json::string(buf));
    res.set("distance", d);
  }
  if (r.estimate) { // a float answer: never in "distance"
    Json e = Json::object();
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", r.estimate->value);
    e.set("value", Json::string(buf));
    e.set("certified", Json::boolean(false));
    res.set("estimate", e);
  }
  if (!r.minimizers.empty()) res.set("minimizers", Json::string(r.minimizers));
  if (r.minimizer_candidates > 0)
    res.set("minimizer_candidates", Json::number(r.minimizer_candidates));
  Json pairs = Json::array();
  for (const auto& pr : r.pairs) {
    Json pj = Json::array();
    for (const auto& p : pr) {
      Json a3 = Json::array();
      for (double x : p) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", x);
        a3.push_back(Json::number_text(buf));
      }
      pj.push_back(a3);
    }
    pairs.push_back(pj);
  }
  res.set("pairs", pairs);
  res.set("pair_points_approximate", Json::boolean(true));
  res.set("critical_candidates", Json::number(r.critical_candidates));
  res.set("eliminated_degree", Json::number(r.eliminated_degree));
  if (!r.system_degrees.empty()) {
    Json deg = Json::object();
    auto arr = [](const std::vector<long>& v) {
      Json a = Json::array();
      for (long x : v)
        a.push_back(Json::number(x));
      return a;
    };
    deg.set("system", arr(r.system_degrees));
    deg.set("bivariate", arr(r.bivariate_degrees));
    deg.set("univariate", arr(r.univariate_degrees));
    deg.set("squarefree", arr(r.squarefree_degrees));
    res.set("degrees", deg);
  }
  res.set("digits", Json::number(digits));
  res.set("solid", Json::boolean(r.solid));
  res.set("mode", Json::string(to_string(r.mode)));
  if (!r.method.empty()) res.set("method", Json::string(r.method));
  if (!r.ties.empty()) res.set("ties", Json::string(r.ties));
  o.set("result", res);
  return o;
}

} // namespace surfcert::certify
