// The routes for two quadrics (registry: route.hpp), in the order they are tried: closed forms
// and convex dualities first (cheap certificates, each declining what it cannot prove), then
// the certified QSIC topology (contact, coincidence, a common apex; it records that the affine
// surfaces are disjoint), then a sphere against any quadric (the exact point-quadric sextic)
// and the offset system for the rest.
#include "surfcert/certify/distance/route.hpp"
#include "surfcert/certify/distance/route_tables.hpp"

#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/common_apex.hpp"
#include "surfcert/certify/distance/cone_distance.hpp"
#include "surfcert/certify/distance/contact_sampling.hpp"
#include "surfcert/certify/distance/convex_distance.hpp"
#include "surfcert/certify/distance/cylinder_pair.hpp"
#include "surfcert/certify/distance/nested_convex.hpp"
#include "surfcert/certify/distance/plane_pair_distance.hpp"
#include "surfcert/certify/distance/plane_quadric.hpp"
#include "surfcert/certify/distance/point_quadric.hpp"
#include "surfcert/certify/distance/quadric_pair.hpp"
#include "surfcert/certify/distance/sphere_gap.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/certify/affine.hpp"
#include "surfcert/certify/qsic.hpp"

#include <flint/fmpq_mat.h>

#include <algorithm>
#include <cmath>

namespace surfcert::certify {

using core::Rational;

namespace {

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
  core::Poly3 fa = form(a), fb = form(b);
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
  out.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
  out.status = Status::Certified;
  if (gap * gap <= support2) { // exact: the plane meets the ellipsoid
    out.distance = Enclosure::zero();
    out.minimizers = gap * gap == support2 ? Minimizers::count(1, Minimizers::Proof::Exact)
                                           : Minimizers::continuum(Minimizers::Proof::Exact);
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

const core::QuadricMatrix& qa(const Query& q) {
  return std::get<core::QuadricMatrix>(q.a);
}
const core::QuadricMatrix& qb(const Query& q) {
  return std::get<core::QuadricMatrix>(q.b);
}
bool is_ellipsoid(const core::QuadricMatrix& m) {
  return m.kind() == core::QuadricKind::Ellipsoid;
}
Outcome answer_or_not(std::optional<DistanceResult> r) {
  return r ? Outcome::answer(std::move(*r)) : Outcome::not_applicable();
}

// Two elliptic cylinders (closed form when crossed, duality when parallel), in every mode:
// the offset system has a curve of solutions for them.
bool cylinders_apply(const Query& q) {
  const auto &a = qa(q), &b = qb(q);
  return !is_ellipsoid(a) && !is_ellipsoid(b) && !a.is_plane() && !b.is_plane();
}
Outcome cylinders_run(Query& q) {
  const auto ya = convex_quadric(qa(q));
  if (!ya || !ya->is_cylinder()) return Outcome::not_applicable();
  const auto yb = convex_quadric(qb(q));
  if (!yb || !yb->is_cylinder()) return Outcome::not_applicable();
  return answer_or_not(cylinder_pair_distance(*ya, *yb, q.digits));
}

// Disjoint convex solids (ellipsoids, elliptic cylinders and paraboloids): a separating
// direction certifies the distance without elimination; anything it cannot prove falls
// through. First, since it is the cheapest certificate.
bool convex_apply(const Query& q) {
  return convex_kind(qa(q)) && convex_kind(qb(q));
}
Outcome convex_float_run(Query& q) {
  auto r = separated_convex_distance_float(*convex_quadric(qa(q)), *convex_quadric(qb(q)));
  return r ? Outcome::estimate(std::move(*r)) : Outcome::not_applicable();
}
// An ellipsoid or sphere posed in doubles (what the fast certificate reads directly).
const core::ShapeSpec* posed_ellipsoid(const core::QuadricMatrix& m) {
  const core::ShapeSpec* sp = m.shape();
  return sp != nullptr &&
                 (sp->type == core::ShapeType::Sphere || sp->type == core::ShapeType::Ellipsoid)
             ? sp
             : nullptr;
}
Outcome convex_run(Query& q) {
  // Two shapes posed in doubles: the certificate straight from the doubles first (no exact
  // rationals); whatever it cannot prove goes on to the exact description below.
  const core::ShapeSpec *sa = posed_ellipsoid(qa(q)), *sb = posed_ellipsoid(qb(q));
  if (sa != nullptr && sb != nullptr) {
    bool no_separation = false;
    if (auto r = separated_posed_ellipsoids(*sa, *sb, q.digits, &no_separation))
      return Outcome::answer(std::move(*r));
    if (no_separation) return Outcome::not_applicable(); // nested or overlapping: next routes
  }
  return answer_or_not(
      separated_convex_distance(*convex_quadric(qa(q)), *convex_quadric(qb(q)), q.digits));
}
// Solid distance when one solid contains the other: 0, reached on a continuum.
DistanceResult solid_nested() {
  DistanceResult out;
  out.status = Status::Certified;
  out.distance = Enclosure::zero();
  out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
  out.note = "solid distance: one solid contains the other";
  return out;
}
// Nested (an ellipsoid strictly inside the other solid): the same duality, minimized.
Outcome nested_run(Query& q) {
  // Two ellipsoids posed in doubles: their support matrices in Arb from the doubles.
  const core::ShapeSpec *sa = posed_ellipsoid(qa(q)), *sb = posed_ellipsoid(qb(q));
  if (sa != nullptr && sb != nullptr) {
    auto r = nested_posed_ellipsoids(*sa, *sb, q.digits);
    if (!r) return Outcome::not_applicable();
    if (q.solid) return Outcome::answer(solid_nested());
    return Outcome::answer(std::move(*r));
  }
  const auto ca = convex_quadric(qa(q)), cb = convex_quadric(qb(q));
  auto r = nested_convex_distance(*ca, *cb, q.digits);
  if (!r) return Outcome::not_applicable();
  if (q.solid && ca->is_ellipsoid() && cb->is_ellipsoid()) return Outcome::answer(solid_nested());
  return Outcome::answer(std::move(*r));
}

// An ellipsoid and a cone: the minimum over the cone's generator lines.
bool cone_apply(const Query& q) {
  const auto ca = convex_kind(qa(q)), cb = convex_kind(qb(q));
  const auto ellipsoid = ConvexQuadric::Kind::Ellipsoid;
  return (ca == ellipsoid && !cb) || (cb == ellipsoid && !ca);
}
Outcome cone_run(Query& q) {
  const auto ca = convex_quadric(qa(q));
  if (ca && ca->is_ellipsoid())
    return answer_or_not(ellipsoid_cone_distance(*ca, qb(q), q.digits, true));
  return answer_or_not(ellipsoid_cone_distance(*convex_quadric(qb(q)), qa(q), q.digits, false));
}

bool ellipsoid_plane_apply(const Query& q) {
  const auto &a = qa(q), &b = qb(q);
  return !a.is_sphere() && !b.is_sphere() && (a.is_plane() || b.is_plane()) &&
         (is_ellipsoid(a) || is_ellipsoid(b));
}
Outcome ellipsoid_plane_run(Query& q) {
  const auto &a = qa(q), &b = qb(q);
  DistanceResult out;
  ellipsoid_plane(out, a.is_plane() ? b : a, a.is_plane() ? a : b, !a.is_plane(), q.digits);
  return Outcome::answer(std::move(out));
}

// A plane and any other quadric (spheres go below): decided exactly on the parallel levels.
bool plane_apply(const Query& q) {
  const auto &a = qa(q), &b = qb(q);
  return (a.is_plane() || b.is_plane()) && !a.is_sphere() && !b.is_sphere();
}
Outcome plane_run(Query& q) {
  const auto &a = qa(q), &b = qb(q);
  return Outcome::answer(
      plane_quadric_distance(a.is_plane() ? a : b, a.is_plane() ? b : a, q.digits, a.is_plane()));
}

// A rational plane pair and another quadric (plane_pair_distance.hpp): the nearer plane.
// A posed shape is never a plane pair (no exact matrix formed for it here).
bool splits_into_planes(const core::QuadricMatrix& q) {
  return q.shape() == nullptr && !q.is_plane() && rational_plane_pair(q.matrix()).has_value();
}
bool plane_pair_apply(const Query& q) {
  if (q.solid) return false;
  const auto &a = qa(q), &b = qb(q);
  return splits_into_planes(a) || splits_into_planes(b);
}
Outcome plane_pair_run(Query& q) {
  const auto &a = qa(q), &b = qb(q);
  const bool pair_is_a = splits_into_planes(a);
  return answer_or_not(
      plane_pair_distance(pair_is_a ? a : b, pair_is_a ? b : a, pair_is_a, q.digits, q.mode));
}

bool always(const Query&) {
  return true;
}

// The minimizers of distance 0 between two quadrics proven to meet at an affine point and
// bounded by no ellipsoid. The morphology counts projective components: its curve may lie at
// infinity only (the cone x^2 + y^2 = z^2 and x^2 + y^2 = z^2 - z share their conic at
// infinity and meet at the apex alone) and its isolated points may be at infinity (x^2 + y^2 = z
// and x^2 + y^2 = -z: the origin and (0 : 0 : 1 : 0)). `curve_affine`: a real curve of the
// intersection is proven to have affine points (no common component of the conics at
// infinity), so they are infinitely many. Otherwise the affine reading of the topology
// (affine_topology, exact) decides: a continuum when the affine curve has a piece (a loop or
// an unbounded branch), else its isolated points; undecided (`candidates`) when it does not.
Minimizers affine_minimizers(QsicResult& t, const core::QuadricMatrix& a,
                             const core::QuadricMatrix& b, bool curve_affine, long candidates) {
  if (curve_affine) return Minimizers::continuum(Minimizers::Proof::Exact);
  const AffineTopology at = affine_topology(t, a, b);
  if (at.computed && at.loops && at.unbounded_branches) {
    if (*at.loops + *at.unbounded_branches > 0)
      return Minimizers::continuum(Minimizers::Proof::Exact);
    if (at.isolated_points && *at.isolated_points > 0)
      return Minimizers::count(*at.isolated_points, Minimizers::Proof::Exact);
  }
  return Minimizers::undecided(candidates);
}

// Do the surfaces meet? The certified topology decides; when it proves the affine surfaces
// disjoint, the query records it (the sphere and offset routes need it).
Outcome topology_run(Query& query) {
  const auto &a = qa(query), &b = qb(query);
  const bool solid = query.solid;
  const Mode mode = query.mode;
  DistanceResult out;
  // Do the surfaces meet? The certified topology decides.
  QsicResult t = classify_qsic(a, b, mode == Mode::Exact ? Mode::Exact : Mode::Filtered);
  if (t.status != Status::Certified) {
    out.status = Status::Undecided;
    out.note = "topology not certified";
    return Outcome::answer(std::move(out));
  }
  if (t.pencil == algebra::PencilKind::Degenerate)
    if (auto r = common_apex_contact(a, b)) {
      return Outcome::answer(std::move(*r));
    }
  if (t.pencil == algebra::PencilKind::Coincident) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
    out.note = "the surfaces coincide";
    return Outcome::answer(std::move(out));
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
    const bool curve_affine = curve && !conics_at_infinity_share_component(a, b);
    bool affine = bounded || curve_affine;
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
      // An ellipsoid has no point at infinity: the projective counts are the affine ones.
      long affine_points = 0;
      for (const auto& sp : t.special_points)
        affine_points += sp.at_infinity ? 0 : 1;
      out.minimizers =
          !bounded ? affine_minimizers(t, a, b, curve_affine, std::max(1L, affine_points))
          : curve
              ? Minimizers::continuum(Minimizers::Proof::Exact)
              : Minimizers::count(static_cast<long>(m.isolated_points), Minimizers::Proof::Exact);
      if (have) out.pairs.push_back({w, w});
      out.note = "the surfaces meet (certified topology: " + std::string(m.id) + ")";
      if (solid && !curve && a.kind() == core::QuadricKind::Ellipsoid &&
          b.kind() == core::QuadricKind::Ellipsoid) {
        // Touching ellipsoids: their solids meet in the touching points only when they lie
        // outside each other; one inside the other, in the whole inner solid (the exact
        // relation decides).
        if (t.ellipsoid_relation == "internally_touching") {
          out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
          out.note += "; solid distance: one solid contains the other, their surfaces touching";
        } else if (t.ellipsoid_relation == "externally_touching") {
          out.note += "; solid distance: the solids meet only where the surfaces touch";
        } else {
          out.minimizers = Minimizers::undecided(out.minimizers.value());
          out.note += "; solid distance: which solid contains which was not decided";
        }
      }
      return Outcome::answer(std::move(out));
    }
    if (curve && meet_by_sign_change(a, b, w)) {
      out.status = Status::Certified;
      out.distance = Enclosure::zero();
      // The common point found may be isolated (the curve at infinity): the affine reading.
      out.minimizers = affine_minimizers(t, a, b, false, 1);
      out.pairs.push_back({w, w});
      out.note = "the surfaces meet (certified topology: " + std::string(m.id) +
                 "; an affine common point proven by certified points of a connected surface "
                 "on both sides of the other; the pair is an approximate common point)";
      return Outcome::answer(std::move(out));
    }
    if (curve) {
      // The sampling missed it (a circle of radius 1e-15 about the axis of two paraboloids
      // sharing their conic at infinity): the affine reading of the topology (exact) proves an
      // affine loop or unbounded branch of the curve, hence infinitely many common points.
      const AffineTopology at = affine_topology(t, a, b);
      if (at.computed && at.loops && at.unbounded_branches &&
          *at.loops + *at.unbounded_branches > 0) {
        out.status = Status::Certified;
        out.distance = Enclosure::zero();
        out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
        out.note = "the surfaces meet (certified topology: " + std::string(m.id) +
                   "; its affine reading has a loop or an unbounded branch; no pair located)";
        return Outcome::answer(std::move(out));
      }
    }
    if (curve || !t.special_points_complete) {
      out.status = Status::Undecided;
      out.note =
          "the real intersection (" + std::string(m.id) + ") may lie at infinity only; not decided";
      return Outcome::answer(std::move(out));
    }
    // Every real common point is at infinity: the affine surfaces are disjoint.
  }
  if (solid && a.kind() == core::QuadricKind::Ellipsoid &&
      b.kind() == core::QuadricKind::Ellipsoid) {
    complete_report_data(t, a, b);
    if (t.ellipsoid_relation == "nested") {
      out.status = Status::Certified;
      out.distance = Enclosure::zero();
      out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
      out.note = "solid distance: one solid contains the other";
      return Outcome::answer(std::move(out));
    }
  }

  query.disjoint_proven = true;
  return Outcome::not_applicable();
}

bool offset_apply(const Query& q) {
  return q.disjoint_proven && !qa(q).is_sphere() && !qb(q).is_sphere();
}
Outcome offset_run(Query& q) {
  DistanceResult d = quadric_pair_distance(qa(q), qb(q), q.digits);
  if (d.method == Method::None) d.method = Method::OffsetSystem;
  return Outcome::answer(std::move(d));
}

// Centre and squared radius of a sphere k(|x|^2) - 2k c.x + k|c|^2 - k r^2 = 0, exactly.
std::pair<std::array<Rational, 3>, Rational> sphere_centre(const core::QuadricMatrix& s) {
  std::array<Rational, 3> c;
  Rational k = s(0, 0), c2;
  for (int i = 0; i < 3; ++i) {
    c[static_cast<size_t>(i)] = -s(i, 3) / k;
    c2 += c[static_cast<size_t>(i)] * c[static_cast<size_t>(i)];
  }
  return {c, c2 - s(3, 3) / k};
}

// Two disjoint spheres in closed form: D = |c1 - c2| against the radii. Apart (D^2 > r1^2 +
// r2^2, exact: disjoint spheres are either apart, D > r1 + r2, or nested, D < |r1 - r2|):
// d = D - r1 - r2; nested: d = |r1 - r2| - D. One pair on the line of centres, a continuum
// when they are concentric. The irrational square roots are enclosed by Arb at growing
// precision until the enclosure meets the width (a radius of 1e-200 next to 1 needs none of
// the point-quadric machinery, whose candidates would differ by 1e-200).
Outcome two_spheres(const core::QuadricMatrix& s1, const core::QuadricMatrix& s2, long digits,
                    bool s1_first) {
  const auto [c1, q1] = sphere_centre(s1);
  const auto [c2, q2] = sphere_centre(s2);
  Rational D2;
  for (size_t i = 0; i < 3; ++i)
    D2 += (c1[i] - c2[i]) * (c1[i] - c2[i]);
  const bool apart = D2 > q1 + q2;
  const bool first_outer = q1 > q2; // nested: which sphere holds the other
  DistanceResult out;
  for (long prec = bits_for(digits + 10);; prec *= 2) {
    Ball D, r1, r2, d;
    arb_set_fmpq(D.v, D2.raw(), prec);
    arb_sqrt(D.v, D.v, prec);
    arb_set_fmpq(r1.v, q1.raw(), prec);
    arb_sqrt(r1.v, r1.v, prec);
    arb_set_fmpq(r2.v, q2.raw(), prec);
    arb_sqrt(r2.v, r2.v, prec);
    if (apart) {
      arb_sub(d.v, D.v, r1.v, prec);
      arb_sub(d.v, d.v, r2.v, prec);
    } else {
      arb_sub(d.v, first_outer ? r1.v : r2.v, first_outer ? r2.v : r1.v, prec);
      arb_sub(d.v, d.v, D.v, prec);
    }
    out.distance = Enclosure::from_ball(d.v, digits);
    if (out.distance->meets_width(digits) || prec > (1L << 20)) break;
  }
  out.status = out.distance->meets_width(digits) ? Status::Certified : Status::Undecided;
  out.width_short = out.status != Status::Certified;
  out.minimizers = D2.is_zero() ? Minimizers::continuum(Minimizers::Proof::Exact)
                                : Minimizers::count(1, Minimizers::Proof::Exact);
  out.critical_candidates = 1;
  // The pair on the line of centres (doubles, display): u from c1 to c2 (any axis when
  // concentric).
  // sqrt of a rational as a double through Arb: the square may overflow a double (r = 1e300).
  auto sqrt_d = [](const Rational& q) {
    Ball x;
    arb_set_fmpq(x.v, q.raw(), 128);
    arb_sqrt(x.v, x.v, 128);
    return arf_get_d(arb_midref(x.v), ARF_RND_NEAR);
  };
  std::array<double, 3> u{1, 0, 0}, p1{}, p2{};
  const double Dd = sqrt_d(D2);
  if (Dd > 0)
    for (size_t i = 0; i < 3; ++i)
      u[i] = (c2[i].to_double_approx() - c1[i].to_double_approx()) / Dd;
  const double r1d = sqrt_d(q1), r2d = sqrt_d(q2);
  // Apart: c1 + r1 u and c2 - r2 u; nested: both toward the side the inner centre is offset
  // to (from the outer centre), i.e. +u when the first is outer, -u otherwise.
  const double s1d = apart || first_outer ? 1 : -1, s2d = apart ? -1 : (first_outer ? 1 : -1);
  for (size_t i = 0; i < 3; ++i) {
    p1[i] = c1[i].to_double_approx() + s1d * r1d * u[i];
    p2[i] = c2[i].to_double_approx() + s2d * r2d * u[i];
  }
  out.pairs.push_back(s1_first ? std::array<std::array<double, 3>, 2>{p1, p2}
                               : std::array<std::array<double, 3>, 2>{p2, p1});
  out.note = apart ? "two spheres apart: |c1 - c2| - r1 - r2 (closed form)"
                   : "a sphere inside a sphere: |r1 - r2| - |c1 - c2| (closed form)";
  return Outcome::answer(std::move(out));
}

bool sphere_apply(const Query& q) {
  return q.disjoint_proven && (qa(q).is_sphere() || qb(q).is_sphere());
}
Outcome sphere_run(Query& query) {
  const auto &a = qa(query), &b = qb(query);
  const long digits = query.digits;
  const bool a_sphere = a.is_sphere();
  const core::QuadricMatrix& sph = a_sphere ? a : b;
  const core::QuadricMatrix& other = a_sphere ? b : a;
  DistanceResult out;
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
      return Outcome::answer(std::move(out));
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
    out.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
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
    return Outcome::answer(std::move(out));
  }
  if (other.is_sphere()) return two_spheres(sph, other, digits, a_sphere);
  return Outcome::answer(sphere_quadric_gap(c, r2, other, digits, a_sphere));
}
} // namespace

void add_quadric_pair_routes(std::vector<Route>& t) {
  const PairKind k = PairKind::QuadricQuadric;
  t.push_back({Method::CylinderClosedForm, k, kAllModes,
               "two elliptic cylinders: crossed in closed form, parallel by duality",
               cylinders_apply, cylinders_run});
  t.push_back({Method::ConvexDualityFloat, k, kFloatMode,
               "nothing: a float separating-direction search (an estimate)", convex_apply,
               convex_float_run});
  t.push_back({Method::ConvexDuality, k, kFloatMode | kFilteredMode,
               "disjoint convex solids: L(n) <= d <= U(n) at one exact direction", convex_apply,
               convex_run});
  t.push_back({Method::NestedConvexDuality, k, kFloatMode | kFilteredMode,
               "an ellipsoid inside an ellipsoid or elliptic cylinder: a Lagrangian (S-lemma) "
               "lower bound localising the minimizer in one Krawczyk box, else min_n h_B - h_A "
               "by branch and bound",
               convex_apply, nested_run});
  t.push_back({Method::ConeGeneratorBound, k, kFloatMode | kFilteredMode,
               "an ellipsoid and a cone apart: min over the generator lines", cone_apply,
               cone_run});
  t.push_back({Method::EllipsoidPlaneClosedForm, k, kAllModes,
               "an ellipsoid and a plane: support function, exact comparison",
               ellipsoid_plane_apply, ellipsoid_plane_run});
  t.push_back({Method::PlaneClosedForm, k, kAllModes,
               "a plane and any quadric: the met levels {m(s) <= 0} exactly", plane_apply,
               plane_run});
  t.push_back({Method::QsicTopology, k, kAllModes,
               "contact, coincidence or a common apex from the certified QSIC topology", always,
               topology_run});
  t.push_back({Method::SpherePointQuadric, k, kAllModes,
               "a sphere and a quadric: the gap d - r (or r - d) over the exact point-quadric "
               "critical distances",
               sphere_apply, sphere_run});
  t.push_back({Method::PlanePairMin, k, kFilteredMode | kExactMode,
               "a rational plane pair and a quadric: the nearer of its two planes, compared "
               "exactly on their enclosures",
               plane_pair_apply, plane_pair_run});
  t.push_back({Method::OffsetSystem, k, kAllModes,
               "two quadrics: every critical pair covered exactly (resultants), refined",
               offset_apply, offset_run});
}

} // namespace surfcert::certify
