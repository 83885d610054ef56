#include "surfcert/certify/distance/route.hpp"
#include "surfcert/certify/distance/route_tables.hpp"

#include "surfcert/algebra/inertia.hpp"
#include "surfcert/certify/distance/solid_relation.hpp"
#include "surfcert/certify/distance/symmetry.hpp"
#include "surfcert/core/budget.hpp"

#include <utility>

namespace surfcert::certify {

const char* to_string(PairKind k) {
  switch (k) {
  case PairKind::QuadricQuadric:
    return "quadric-quadric";
  case PairKind::QuadricTorus:
    return "quadric-torus";
  case PairKind::QuadricCanal:
    return "quadric-canal";
  case PairKind::QuadricImplicit:
    return "quadric-implicit";
  case PairKind::TorusTorus:
    return "torus-torus";
  case PairKind::TorusCanal:
    return "torus-canal";
  case PairKind::TorusImplicit:
    return "torus-implicit";
  case PairKind::CanalCanal:
    return "canal-canal";
  case PairKind::CanalImplicit:
    return "canal-implicit";
  case PairKind::ImplicitImplicit:
    return "implicit-implicit";
  case PairKind::Parametric:
    return "parametric";
  }
  return "?";
}

int surface_rank(const core::Surface& s) {
  if (std::holds_alternative<core::QuadricMatrix>(s)) return 0;
  if (std::holds_alternative<core::Torus>(s)) return 1;
  if (std::holds_alternative<core::CanalSurface>(s)) return 2;
  if (std::holds_alternative<core::ImplicitSurface>(s)) return 3;
  return 4; // parametric
}

PairKind pair_kind(const core::Surface& a, const core::Surface& b) {
  static const PairKind table[4][4] = {
      {PairKind::QuadricQuadric, PairKind::QuadricTorus, PairKind::QuadricCanal,
       PairKind::QuadricImplicit},
      {PairKind::QuadricTorus, PairKind::TorusTorus, PairKind::TorusCanal, PairKind::TorusImplicit},
      {PairKind::QuadricCanal, PairKind::TorusCanal, PairKind::CanalCanal, PairKind::CanalImplicit},
      {PairKind::QuadricImplicit, PairKind::TorusImplicit, PairKind::CanalImplicit,
       PairKind::ImplicitImplicit}};
  const int ra = surface_rank(a), rb = surface_rank(b);
  if (ra == 4 || rb == 4) return PairKind::Parametric;
  return table[ra][rb];
}

const std::vector<Route>& distance_routes() {
  static const std::vector<Route> table = [] {
    std::vector<Route> t;
    add_degenerate_quadric_routes(t);
    add_quadric_pair_routes(t);
    add_surface_pair_routes(t);
    return t;
  }();
  return table;
}

namespace {

unsigned mode_bit(Mode m) {
  switch (m) {
  case Mode::Float:
    return kFloatMode;
  case Mode::Exact:
    return kExactMode;
  default:
    return kFilteredMode;
  }
}

// Whether the quadric p^T M p = 0 has no real affine point, exactly: M semidefinite (else it
// takes both signs) and its kernel, where the points of a semidefinite form lie, inside the
// plane at infinity w = 0 (rank M = rank of M's first three columns + 1): x^2+y^2+z^2 = -1,
// x^2 + y^2 = -1.
bool no_real_point(const core::QuadricMatrix& q) {
  if (q.kind() == core::QuadricKind::ImaginaryEllipsoid) return true;
  const core::Mat4& m = q.matrix();
  const algebra::Inertia in = algebra::inertia_ldlt(m);
  if (!in.semidefinite() || in.rank() == 0) return false;
  core::Mat4 cols = m;
  for (auto& row : cols)
    row[3] = core::Rational(0);
  return algebra::rank_exact(m) == algebra::rank_exact(cols) + 1;
}

} // namespace

DistanceResult run_distance_routes(const core::Surface& a0, const core::Surface& b0, long digits,
                                   bool solid, Mode mode) {
  // Canonical order: the routes read their first surface as the lower kind.
  const bool swapped = surface_rank(a0) > surface_rank(b0);
  const core::Surface& a = swapped ? b0 : a0;
  const core::Surface& b = swapped ? a0 : b0;
  Query q{a, b, digits, solid, mode};
  const PairKind kind = pair_kind(a, b);
  // A quadric with no real point has no distance to anything: said, not searched for (the
  // routes answered "no critical point found").
  for (const core::Surface* s : {&a0, &b0})
    if (const auto* m = std::get_if<core::QuadricMatrix>(s); m && no_real_point(*m)) {
      DistanceResult e;
      e.status = Status::Undecided;
      e.no_real_point = true;
      e.note = std::string("surface ") + (s == &a0 ? "a" : "b") +
               " has no real point (proven exactly: its matrix is semidefinite with its kernel "
               "at infinity): there is no distance";
      e.solid = solid;
      e.mode = mode;
      return e;
    }

  DistanceResult r;
  bool answered = false;
  std::optional<DistanceResult> established; // the latest declined result, enclosure preferred
  std::string tried;
  bool out_of_time = false;
  for (const Route& route : distance_routes()) {
    if (route.kind != kind || (route.modes & mode_bit(mode)) == 0 || !route.applies(q)) continue;
    Outcome o;
    try {
      core::check_budget();
      o = route.run(q);
    } catch (const core::BudgetExceeded&) {
      // Past the query's budget: stop; what earlier routes established is the answer.
      tried += std::string(tried.empty() ? "" : ", ") + to_string(route.id) + " (stopped)";
      out_of_time = true;
      break;
    }
    if (o.kind == Outcome::Kind::NotApplicable) continue;
    // The route's id names the method, unless the route solved an offset system inside (a
    // finer name, kept for the JSON contract).
    if (o.result.method == Method::None)
      o.result.method = o.result.univariate_degrees.empty() ? route.id : Method::OffsetSystem;
    if (o.kind == Outcome::Kind::Declined) {
      tried += std::string(tried.empty() ? "" : ", ") + to_string(route.id);
      o.result.status = Status::Undecided;
      if (!established || o.result.distance || !established->distance)
        established = std::move(o.result);
      continue;
    }
    r = std::move(o.result);
    if (o.kind == Outcome::Kind::Estimate) { // a float answer: never an enclosure
      r.status = Status::Uncertified;
      r.distance.reset();
    } else if (r.status == Status::Uncertified) { // an Answer must be proven or undecided
      r.status = Status::Undecided;
      r.estimate.reset();
    }
    answered = true;
    break;
  }
  if (!answered) {
    if (established) {
      r = std::move(*established);
      r.note += std::string(r.note.empty() ? "" : "; ") +
                (out_of_time ? "the time budget ran out (tried: "
                             : "no route proved an answer (tried: ") +
                tried + ")";
    } else {
      r = DistanceResult();
      r.status = Status::Undecided;
      r.note = out_of_time
                   ? "the time budget ran out before any route answered (tried: " + tried + ")"
                   : std::string("not supported yet: no route for this pair (") + to_string(kind) +
                         ": " + core::surface_kind(a0) + ", " + core::surface_kind(b0) + ")";
    }
    r.budget_exhausted = out_of_time;
  }
  r.solid = solid;
  r.mode = mode;
  if (swapped)
    for (auto& pr : r.pairs)
      std::swap(pr[0], pr[1]);
  if (r.ties == Ties::Unproven) prove_ties(r, a0, b0);
  // The parametric route passes solid on itself. Two quadrics handle it in their routes for
  // two ellipsoids (nested: 0) and for convex solids proven disjoint by a separating
  // direction (the surface distance); the solids of any other pair of quadrics are not
  // modelled there (a unit sphere inside the cylinder x^2 + y^2 = 4 was certified at the
  // surface distance 1, and verify read it as 'separated'): apply_solid_option says so.
  auto is_ellipsoid = [](const core::Surface& s) {
    const auto* m = std::get_if<core::QuadricMatrix>(&s);
    return m != nullptr && m->kind() == core::QuadricKind::Ellipsoid;
  };
  // (A plane against an ellipsoid or a plane goes to apply_solid_option, which keeps it.)
  const bool quadric_solids_modelled =
      kind == PairKind::QuadricQuadric &&
      ((is_ellipsoid(a0) && is_ellipsoid(b0)) || r.method == Method::ConvexDuality);
  if (solid && kind != PairKind::Parametric && !quadric_solids_modelled)
    apply_solid_option(r, a0, b0);
  return r;
}

} // namespace surfcert::certify
