// The routes for pairs with a torus, a canal surface, an implicit or a parametric surface
// (registry: route.hpp), per pair kind in the order they are tried; the registry has put the
// pair in canonical order (quadric < torus < canal < implicit < parametric), so a route reads
// its first surface as the lower kind and reports pairs in that order. A route that cannot
// prove an answer declines with what it established; the contact fallback
// (sign_change_contact) closes every table.
#include "surfcert/certify/distance/route.hpp"
#include "surfcert/certify/distance/route_tables.hpp"

#include "surfcert/certify/distance/canal_distance.hpp"
#include "surfcert/certify/distance/capsule_pair.hpp"
#include "surfcert/certify/distance/contact_sampling.hpp"
#include "surfcert/certify/distance/implicit_bnb.hpp"
#include "surfcert/certify/distance/parametric_distance.hpp"
#include "surfcert/certify/distance/quadric_pair.hpp"
#include "surfcert/certify/distance/sphere_family.hpp"
#include "surfcert/certify/distance/torus_distance.hpp"
#include "surfcert/certify/distance/torus_pair.hpp"

#include <cmath>

namespace surfcert::certify {

namespace {

template <class T> const T& first(const Query& q) {
  return std::get<T>(q.a);
}
template <class T> const T& second(const Query& q) {
  return std::get<T>(q.b);
}
bool always(const Query&) {
  return true;
}
Outcome optional_answer(std::optional<DistanceResult> r) {
  return r ? Outcome::certified_or_declined(std::move(*r)) : Outcome::not_applicable();
}
void swap_pairs(DistanceResult& r) {
  for (auto& pr : r.pairs)
    std::swap(pr[0], pr[1]);
}
Outcome offset_declined_or_answer(DistanceResult r) {
  if (r.method == Method::None && !r.univariate_degrees.empty()) r.method = Method::OffsetSystem;
  return Outcome::certified_or_declined(std::move(r));
}

// --- parametric: the implicit equation, found exactly, and its routes (same mode, solid) ---
Outcome parametric_run(Query& q) {
  if (std::holds_alternative<core::ParametricSurface>(q.a)) {
    DistanceResult r;
    r.status = Status::Undecided;
    r.note = "not supported yet: two parametric surfaces";
    return Outcome::answer(std::move(r));
  }
  return Outcome::answer(parametric_distance(second<core::ParametricSurface>(q), q.a, q.digits,
                                             false, q.mode, q.solid));
}

// --- quadric and torus ---
Outcome quadric_torus_run(Query& q) {
  return Outcome::certified_or_declined(quadric_torus_distance(
      first<core::QuadricMatrix>(q), second<core::Torus>(q), q.digits, true));
}
Outcome quadric_torus_exact_run(Query& q) {
  return Outcome::certified_or_declined(quadric_torus_distance_exact(
      first<core::QuadricMatrix>(q), second<core::Torus>(q), q.digits, true));
}

// --- quadric and canal surface ---
Outcome quadric_canal_run(Query& q) {
  return Outcome::certified_or_declined(quadric_canal_distance(
      first<core::QuadricMatrix>(q), second<core::CanalSurface>(q), q.digits, true));
}

// --- quadric and implicit surface: the generic branch and bound first (milliseconds to
// seconds; the offset system of a quartic against an ellipsoid runs for minutes), clipped
// when one surface is unbounded, the offset system when they cannot decide (unbounded or
// singular surfaces, tangential contact, flat minima) ---
bool ellipsoid_first(const Query& q) {
  return first<core::QuadricMatrix>(q).kind() == core::QuadricKind::Ellipsoid;
}
Outcome ellipsoid_implicit_bnb_run(Query& q) {
  return Outcome::certified_or_declined(implicit_pair_distance(
      first<core::QuadricMatrix>(q).to_poly(), second<core::ImplicitSurface>(q).f, q.digits));
}
Outcome ellipsoid_implicit_clipped_run(Query& q) { // an unbounded implicit surface, clipped
  return Outcome::certified_or_declined(bounded_unbounded_distance(
      first<core::QuadricMatrix>(q).to_poly(), second<core::ImplicitSurface>(q).f, q.digits));
}
// An unbounded quadric (a plane only beyond the plane route's degrees) clipped near the
// bounded implicit surface.
bool quadric_clipped_applies(const Query& q) {
  const auto& m = first<core::QuadricMatrix>(q);
  return m.kind() != core::QuadricKind::Ellipsoid &&
         (!m.is_plane() ||
          second<core::ImplicitSurface>(q).f.total_degree() > core::kMaxOffsetDegree);
}
Outcome quadric_clipped_run(Query& q) {
  DistanceResult r = bounded_unbounded_distance(second<core::ImplicitSurface>(q).f,
                                                first<core::QuadricMatrix>(q).to_poly(), q.digits);
  swap_pairs(r);
  return Outcome::certified_or_declined(std::move(r));
}
Outcome quadric_implicit_offset_run(Query& q) {
  return offset_declined_or_answer(implicit_quadric_distance(
      second<core::ImplicitSurface>(q).f, first<core::QuadricMatrix>(q), q.digits, false));
}

// --- two tori: the circle bound, then the branch and bound on the two quartics (decides
// pairs the circle bound leaves open when their closest pair is isolated) ---
Outcome torus_pair_run(Query& q) {
  return optional_answer(
      torus_pair_distance(first<core::Torus>(q), second<core::Torus>(q), q.digits));
}
Outcome torus_pair_bnb_run(Query& q) {
  DistanceResult r = implicit_pair_distance(torus_polynomial(first<core::Torus>(q)),
                                            torus_polynomial(second<core::Torus>(q)), q.digits);
  if (r.status != Status::Certified)
    r.note = "two tori whose tubes may meet, nest, or have a continuum of minimizers: not "
             "decided (" +
             r.note + ")";
  return Outcome::certified_or_declined(std::move(r));
}

// --- torus and implicit surface: branch and bound, clipped, then the offset system with the
// implicit source ---
Outcome torus_implicit_bnb_run(Query& q) {
  return Outcome::certified_or_declined(implicit_pair_distance(
      torus_polynomial(first<core::Torus>(q)), second<core::ImplicitSurface>(q).f, q.digits));
}
Outcome torus_implicit_clipped_run(Query& q) {
  return Outcome::certified_or_declined(bounded_unbounded_distance(
      torus_polynomial(first<core::Torus>(q)), second<core::ImplicitSurface>(q).f, q.digits));
}
Outcome torus_implicit_offset_run(Query& q) {
  return offset_declined_or_answer(implicit_torus_distance(second<core::ImplicitSurface>(q).f,
                                                           first<core::Torus>(q), q.digits, false));
}

// --- canal surfaces and tori as unions of balls ---
Outcome capsule_pair_run(Query& q) {
  return optional_answer(
      capsule_pair_distance(first<core::CanalSurface>(q), second<core::CanalSurface>(q), q.digits));
}
Outcome sphere_family_run(Query& q) {
  return optional_answer(sphere_family_distance(q.a, q.b, q.digits));
}

// --- two implicit surfaces: the generic branch and bound (bounded, smooth) ---
Outcome implicit_pair_run(Query& q) {
  return Outcome::certified_or_declined(implicit_pair_distance(
      first<core::ImplicitSurface>(q).f, second<core::ImplicitSurface>(q).f, q.digits));
}

// --- the contact fallback: a sign change of one surface's equation along the other,
// connected one, proves contact (and, the zero set separating a connected surface, a
// continuum of common points) ---
Outcome contact_run(Query& q) {
  std::array<double, 3> w{};
  double residual = 0;
  bool continuum = false;
  if (!surfaces_meet_by_sign_change(q.a, q.b, w, &residual, &continuum))
    return Outcome::not_applicable();
  DistanceResult r;
  r.status = Status::Certified;
  r.distance = Enclosure::zero();
  // A cone seen on either side on its two nappes only: maybe the apex alone is common (a
  // cone and z^3 + z = 0 meet at the apex only), the count is not proven.
  r.minimizers =
      continuum ? Minimizers::continuum(Minimizers::Proof::Interval) : Minimizers::undecided(1);
  // Display only: list the float-polished common point when it is one.
  const bool located = residual <= 1e-9 * (1 + std::hypot(w[0], w[1], w[2]));
  if (located) r.pairs.push_back({w, w});
  r.note = std::string("the surfaces meet: certified points of a connected surface on both "
                       "sides of the other") +
           (located ? " (the pair is an approximate common point)"
                    : " (no approximate common point located: no pair listed)") +
           (continuum ? ""
                      : "; both sides were seen on the two nappes of a cone only: the common "
                        "points may be its apex alone, their number is not proven");
  return Outcome::answer(std::move(r));
}

} // namespace

void add_surface_pair_routes(std::vector<Route>& t) {
  using K = PairKind;
  const char* contact = "contact: certified points of one connected surface on both sides";
  const char* balls =
      "unions of balls: min dist(C1(s), C2(t)) - r1 - r2 by branch and bound + Krawczyk";
  t.push_back({Method::ParametricReduction, K::Parametric, kAllModes,
               "the implicit equation's routes, lower bound; an upper bound witnessed by an "
               "exact image point",
               always, parametric_run});
  t.push_back({Method::TorusDistance, K::QuadricTorus, kFloatMode | kFilteredMode,
               "a quadric and a torus: circle bound or offset system", always, quadric_torus_run});
  t.push_back({Method::TorusDistance, K::QuadricTorus, kExactMode,
               "a quadric and a torus: the exact offset system", always, quadric_torus_exact_run});
  t.push_back({Method::CanalDistance, K::QuadricCanal, kAllModes,
               "a quadric and a canal surface: min over the spine of point-quadric distances",
               always, quadric_canal_run});
  t.push_back({Method::ImplicitBnb, K::QuadricImplicit, kAllModes,
               "an ellipsoid and a bounded implicit surface: box pairs + Krawczyk", ellipsoid_first,
               ellipsoid_implicit_bnb_run});
  t.push_back({Method::ImplicitBnb, K::QuadricImplicit, kAllModes,
               "an ellipsoid and an unbounded implicit surface clipped to a proven margin",
               ellipsoid_first, ellipsoid_implicit_clipped_run});
  t.push_back({Method::ImplicitBnb, K::QuadricImplicit, kAllModes,
               "an unbounded quadric clipped near a bounded implicit surface",
               quadric_clipped_applies, quadric_clipped_run});
  t.push_back({Method::OffsetSystem, K::QuadricImplicit, kAllModes,
               "the offset system with the implicit source (degree <= 6)", always,
               quadric_implicit_offset_run});
  t.push_back({Method::TorusCirclePair, K::TorusTorus, kAllModes,
               "two tori: circle-circle distance by branch and bound, coaxial closed form", always,
               torus_pair_run});
  t.push_back({Method::ImplicitBnb, K::TorusTorus, kAllModes,
               "two tori as quartics: box pairs + Krawczyk", always, torus_pair_bnb_run});
  t.push_back(
      {Method::SphereFamilyBnb, K::TorusCanal, kAllModes, balls, always, sphere_family_run});
  t.push_back({Method::ImplicitBnb, K::TorusImplicit, kAllModes,
               "a torus and a bounded implicit surface: box pairs + Krawczyk", always,
               torus_implicit_bnb_run});
  t.push_back({Method::ImplicitBnb, K::TorusImplicit, kAllModes,
               "a torus and an unbounded implicit surface clipped to a proven margin", always,
               torus_implicit_clipped_run});
  t.push_back({Method::OffsetSystem, K::TorusImplicit, kAllModes,
               "the offset system with the implicit source (degree <= 6)", always,
               torus_implicit_offset_run});
  t.push_back({Method::CapsuleClosedForm, K::CanalCanal, kAllModes,
               "two capsules: segment-segment distance (exact square) minus the radii", always,
               capsule_pair_run});
  t.push_back(
      {Method::SphereFamilyBnb, K::CanalCanal, kAllModes, balls, always, sphere_family_run});
  t.push_back({Method::ImplicitBnb, K::ImplicitImplicit, kAllModes,
               "two bounded implicit surfaces: box pairs + Krawczyk", always, implicit_pair_run});
  // Every non-quadric table ends with the contact fallback (the registry tries a kind's
  // routes in table order, so appending them last keeps them last).
  for (K k : {K::QuadricTorus, K::QuadricCanal, K::QuadricImplicit, K::TorusTorus, K::TorusCanal,
              K::TorusImplicit, K::CanalCanal, K::CanalImplicit, K::ImplicitImplicit})
    t.push_back({Method::SignChangeContact, k, kAllModes, contact, always, contact_run});
}

} // namespace surfcert::certify
