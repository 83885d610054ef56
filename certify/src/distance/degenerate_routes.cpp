// The routes for a quadric whose real points are a plane or a line (degenerate_locus.hpp),
// tried before every other route of their pair kinds (registry: route.hpp): the offset system
// has a curve of solutions for them and the point-quadric sextic finds no critical point.
// - double_plane_reduction: a double plane (v . X)^2 = 0 is the plane v . X = 0: the query is
//   answered for the plane (any partner kind: quadric, torus, canal, implicit surface), the
//   route that answered it in "reduced_by";
// - line_locus: a quadric whose real points form a line (x^2 + y^2 = 0) against a quadric:
//   the line's distance, exactly (line_quadric_distance). A plane partner is left to the plane
//   routes (exact for any quadric). Against a ring torus: the line's distance through the core
//   circle (line_torus_distance: contact decided exactly, the minimum over exact critical
//   points).
// Neither models a solid: a solid query falls through to the other routes.
#include "surfcert/certify/distance/route.hpp"
#include "surfcert/certify/distance/route_tables.hpp"

#include "surfcert/certify/affine.hpp"
#include "surfcert/certify/distance/degenerate_locus.hpp"

namespace surfcert::certify {

namespace {

const core::QuadricMatrix* quadric(const core::Surface& s) {
  return std::get_if<core::QuadricMatrix>(&s);
}
bool double_plane(const core::Surface& s) {
  const auto* m = quadric(s);
  return m != nullptr && real_locus(*m).kind == RealLocus::Kind::Plane;
}
bool line(const core::Surface& s) {
  const auto* m = quadric(s);
  return m != nullptr && real_locus(*m).kind == RealLocus::Kind::Line;
}

bool double_plane_apply(const Query& q) {
  return !q.solid && (double_plane(q.a) || double_plane(q.b));
}
Outcome double_plane_run(Query& q) {
  const bool first = double_plane(q.a);
  const core::QuadricMatrix& dp = *quadric(first ? q.a : q.b);
  const core::QuadricMatrix plane(plane_as_quadric(real_locus(dp).plane));
  DistanceResult r = first ? surface_distance(core::Surface(plane), q.b, q.digits, false, q.mode)
                           : surface_distance(q.a, core::Surface(plane), q.digits, false, q.mode);
  if (r.reduced_by == Method::None) r.reduced_by = r.method;
  r.method = Method::DoublePlaneReduction;
  r.note = "a double plane (rank 1, semidefinite: exact): its real points are one plane, "
           "answered as that plane" +
           std::string(r.note.empty() ? "" : "; " + r.note);
  return Outcome::answer(std::move(r));
}

bool line_apply(const Query& q) {
  if (q.solid) return false;
  const auto *a = quadric(q.a), *b = quadric(q.b);
  return a != nullptr && b != nullptr && !a->is_plane() && !b->is_plane() &&
         (line(q.a) || line(q.b));
}
// A line route's result as the answer of method line_locus (not applicable when none).
template <class Result> Outcome line_answer(std::optional<Result> r) {
  if (!r) return Outcome::not_applicable();
  r->method = Method::LineLocus;
  r->note = "a quadric whose real points form a line (rank 2, semidefinite: exact), answered "
            "as that line" +
            std::string(r->note.empty() ? "" : "; " + r->note);
  return Outcome::answer(std::move(*r));
}
Outcome line_run(Query& q) {
  const bool first = line(q.a);
  const RealLocus l = real_locus(*quadric(first ? q.a : q.b));
  return line_answer(line_quadric_distance(l, *quadric(first ? q.b : q.a), first, q.digits));
}

// Quadric-torus pairs come in canonical order: the quadric first.
bool line_torus_apply(const Query& q) {
  return !q.solid && std::holds_alternative<core::Torus>(q.b) && line(q.a);
}
Outcome line_torus_run(Query& q) {
  return line_answer(
      line_torus_distance(real_locus(*quadric(q.a)), std::get<core::Torus>(q.b), true, q.digits));
}

} // namespace

void add_degenerate_quadric_routes(std::vector<Route>& t) {
  const char* plane_proves = "a double plane (rank-1 semidefinite quadric): the distance to its "
                             "plane, by the plane's routes";
  for (PairKind k : {PairKind::QuadricQuadric, PairKind::QuadricTorus, PairKind::QuadricCanal,
                     PairKind::QuadricImplicit})
    t.push_back({Method::DoublePlaneReduction, k, kAllModes, plane_proves, double_plane_apply,
                 double_plane_run});
  t.push_back({Method::LineLocus, PairKind::QuadricQuadric, kAllModes,
               "a quadric whose real points form a line (rank-2 semidefinite) and a quadric: "
               "the line's distance through the exact shadow of the quadric along it (closed "
               "forms against a line, a point or a half-plane shadow)",
               line_apply, line_run});
  t.push_back({Method::LineLocus, PairKind::QuadricTorus, kAllModes,
               "a quadric whose real points form a line (rank-2 semidefinite) and a torus: the "
               "torus quartic along the line decides contact exactly, else the least distance "
               "to the core circle over the exact critical points, minus r",
               line_torus_apply, line_torus_run});
}

} // namespace surfcert::certify
