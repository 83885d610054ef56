// surfcert::certify::Route and the route registry: how a distance query is answered.
//
// A query (two surfaces, digits, solid, mode) is first put in canonical order (quadric <
// torus < canal < implicit < parametric; the reported pairs are swapped back at the end), then
// the routes registered for its pair kind are tried in table order. Each route has
//   - an id: the JSON "method" of its answers (unless it names a finer one),
//   - the modes it runs in (the exact mode runs only routes whose certificates are exact
//     algebra or exact-input ball arithmetic with no float search; the float mode adds routes
//     whose answer is an Estimate),
//   - `applies`: an exact, cheap test on the input (kinds, ranks, exact facts recorded by
//     earlier routes of the same query), never a float judgement,
//   - `run`, returning an Outcome:
//       NotApplicable  the route has nothing to say (the next one is tried);
//       Declined       it could not prove an answer; what it established (an enclosure, its
//                      reason in the note) is kept, and the next route is tried;
//       Answer         the query's answer: certified, or undecided when no later route can
//                      help (e.g. the topology of two quadrics is not certified);
//       Estimate       a float answer (status uncertified, result.estimate): float mode only.
// What every answer goes through afterwards is done once, in the registry, for every route:
// orientation, the solid option for closed non-quadric surfaces, the contact fallback for
// non-quadric pairs left undecided (a sign change of one surface's equation along the other),
// the tie proof (symmetry.hpp), the width contract and the minimizer-count rule (distance.hpp).
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

#include <string>
#include <vector>

namespace surfcert::certify {

enum class PairKind {
  QuadricQuadric,
  QuadricTorus,
  QuadricCanal,
  QuadricImplicit,
  TorusTorus,
  TorusCanal,
  TorusImplicit,
  CanalCanal,
  CanalImplicit,
  ImplicitImplicit,
  Parametric ///< one or both surfaces parametric: reduced to the implicit equation
};

const char* to_string(PairKind k);

/// The pair kind of two surfaces in canonical order (rank(a) <= rank(b)).
PairKind pair_kind(const core::Surface& a, const core::Surface& b);

/// 0 quadric, 1 torus, 2 canal, 3 implicit, 4 parametric: the canonical order.
int surface_rank(const core::Surface& s);

struct Query {
  const core::Surface& a; ///< canonical order: surface_rank(a) <= surface_rank(b)
  const core::Surface& b;
  long digits = 15;
  bool solid = false;
  Mode mode = Mode::Filtered;
  /// Exact facts established by earlier routes of this query, for later ones' `applies`.
  /// Two quadrics: their affine surfaces are proven disjoint (certified topology).
  bool disjoint_proven = false;
};

struct Outcome {
  enum class Kind { NotApplicable, Declined, Answer, Estimate };
  Kind kind = Kind::NotApplicable;
  DistanceResult result;

  static Outcome not_applicable() { return {}; }
  static Outcome declined(DistanceResult r) { return {Kind::Declined, std::move(r)}; }
  static Outcome answer(DistanceResult r) { return {Kind::Answer, std::move(r)}; }
  /// A float answer: must carry result.estimate and no enclosure (checked by the registry).
  static Outcome estimate(DistanceResult r) { return {Kind::Estimate, std::move(r)}; }
  /// Answer when certified, Declined otherwise.
  static Outcome certified_or_declined(DistanceResult r) {
    return r.status == Status::Certified ? answer(std::move(r)) : declined(std::move(r));
  }
};

/// Modes a route runs in (bit set).
enum RouteModes : unsigned { kFloatMode = 1, kFilteredMode = 2, kExactMode = 4, kAllModes = 7 };

struct Route {
  Method id; ///< the JSON "method" of its answers (method.hpp)
  PairKind kind;
  unsigned modes;
  const char* proves; ///< what an answer of this route proves (the README's table)
  bool (*applies)(const Query&);
  Outcome (*run)(Query&);
};

/// The registry: every route, grouped by pair kind, in the order they are tried.
const std::vector<Route>& distance_routes();

/// Runs the registry on a query (canonical order, routes, post-processing; see above). The
/// width contract and the count rule are applied by surface_distance around it.
DistanceResult run_distance_routes(const core::Surface& a, const core::Surface& b, long digits,
                                   bool solid, Mode mode);

} // namespace surfcert::certify
