// verify_peers: the oracle in action (issue 13). Peers a user would otherwise trust answer
// collision and distance queries; their answers become verify claims, and surfcert's verdicts
// say which are right (confirmed), provably wrong (refuted, with the kind of counterexample)
// or not decided (undecided).
//
// Peers: FCL 0.7 (libccd and its own GJK "indep", DistanceRequest::distance_tolerance at its
// default 1e-6 and at 1e-12; FCL works on solids: a negative or -1 distance means collision)
// and surfcert's own float mode (Mode::Float: the convex search's double answer).
// Claims made from each answer: solids_collide (FCL: distance < 0; float: solid estimate 0);
// when the peer reports the bodies apart, the distance (abs_tol = the peer's tolerance; float
// mode: 1e-9) and the closest points (the same abs_tol).
// Families:
//   random   seed 002 §5.1.3 random ellipsoid pairs (bench/random_ellipsoids.hpp);
//   tangent  ellipsoid A = (x+1)^2 + 4y^2 + 9z^2 = 1 (tip at the origin) and the flat
//            ellipsoid B with semi-axes (2^-8, 1/2, 1/3) centred at (2^-8 + g, 0, 0): gap g =
//            +2^-k (apart, closest pair (0,0,0)-(g,0,0), distance g) and -2^-k (crossing),
//            k = 10..60. Every coordinate is a double, so the peers see the exact pair.
// Open CASCADE 7.6 (when built): GeomAPI_ExtremaSurfaceSurface's surface distance and nearest
// points (claimed within 1e-7, its Precision::Confusion), and GeomAPI_IntSS's curves (tolerance
// 1e-7, each line sampled at 401 points, claimed within 1e-3; "random, curves": the first
// curve_pairs random pairs, each peer answering there too).
// Degenerate families (every coordinate a double; labels kept only when the exact classifier
// confirms them): nested (random poses, seed + 1), isolated point (exact external and internal
// tangencies), internal tangency at 2^-k both sides, double conic (tangent along a circle)
// exact and at 2^-k both sides; their claims include `relation` where an answer asserts one.
// Usage: verify_peers [pairs=100] [seed=2026] [curve_pairs=30] [nested_pairs=50]. Prints a
// markdown table; progress on stderr (VERIFY_PEERS_SHOW=text: the verdicts other than
// confirmed in the families whose name contains text).
#include "random_ellipsoids.hpp"

#include "surfcert/app/verify.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/budget.hpp"

#ifdef SURFCERT_HAVE_FCL
#include "fcl_peer.hpp"

#include <sys/wait.h>
#include <unistd.h>
#endif
#ifdef SURFCERT_HAVE_OCCT
#include "occt_distance_peer.hpp"
#include "occt_peer.hpp"
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

using namespace surfcert;
using bench::EllipsoidParams;
using core::io::Json;

namespace {

struct Pair {
  core::QuadricMatrix a, b;
  EllipsoidParams ea, eb;
};

// The axis-aligned ellipsoid of p (identity rotation), exactly.
core::QuadricMatrix axis_aligned(const EllipsoidParams& p) {
  core::Mat4 m;
  core::Rational c33(-1);
  for (size_t i = 0; i < 3; ++i) {
    const core::Rational r = core::Rational::exact_from_double(p.radii[i]);
    const core::Rational c = core::Rational::exact_from_double(p.centre[i]);
    const core::Rational w = core::Rational(1) / (r * r);
    m[i][i] = w;
    m[i][3] = m[3][i] = -w * c;
    c33 += w * c * c;
  }
  m[3][3] = c33;
  return core::QuadricMatrix(m);
}

EllipsoidParams params(std::array<double, 3> centre, std::array<double, 3> radii) {
  EllipsoidParams p;
  p.centre = centre, p.radii = radii;
  for (size_t i = 0; i < 3; ++i)
    p.rotation[i][i] = 1;
  return p;
}

Json num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return Json::number_text(buf);
}

Json point(const std::array<double, 3>& p) {
  Json o = Json::array();
  for (double x : p)
    o.push_back(num(x));
  return o;
}

// One peer's answer as claims (appended to `claims`; `owner` records the peer per claim).
struct Answer {
  bool collide_known = true;
  bool solid = false;                                    ///< the distance is between solids (FCL)
  std::vector<std::vector<std::array<double, 3>>> curve; ///< a curve claim when curve_known
  bool curve_known = false;
  double curve_tol = 1e-3;
  bool collide = false;
  bool apart_known = false; ///< the peer reported a distance for disjoint bodies
  double distance = 0;
  std::array<double, 3> p{}, q{};
  double tol = 0;
  std::string relation; ///< a relation claim when non-empty (the one the answer asserts)
};

void add_claims(const Answer& ans, const std::string& peer, Json& claims,
                std::vector<std::string>& owner) {
  if (ans.curve_known) {
    Json c = Json::object();
    c.set("kind", Json::string("curve"));
    Json v = Json::array();
    for (const auto& l : ans.curve) {
      Json pl = Json::array();
      for (const auto& p : l)
        pl.push_back(point(p));
      v.push_back(pl);
    }
    c.set("value", v);
    c.set("abs_tol", num(ans.curve_tol));
    claims.push_back(c), owner.push_back(peer);
  }
  if (ans.collide_known) {
    Json c = Json::object();
    c.set("kind", Json::string("solids_collide"));
    c.set("value", Json::boolean(ans.collide));
    claims.push_back(c), owner.push_back(peer);
  }
  if (!ans.relation.empty()) {
    Json c = Json::object();
    c.set("kind", Json::string("relation"));
    c.set("value", Json::string(ans.relation));
    claims.push_back(c), owner.push_back(peer);
  }
  if (!ans.apart_known) return;
  Json d = Json::object();
  d.set("kind", Json::string("distance"));
  d.set("value", num(ans.distance));
  d.set("abs_tol", num(ans.tol));
  if (ans.solid) d.set("solid", Json::boolean(true));
  claims.push_back(d), owner.push_back(peer);
  Json cp = Json::object();
  cp.set("kind", Json::string("closest_points"));
  Json v = Json::array();
  v.push_back(point(ans.p));
  v.push_back(point(ans.q));
  cp.set("value", v);
  cp.set("abs_tol", num(ans.tol));
  claims.push_back(cp), owner.push_back(peer);
}

// What kind of counterexample refuted a claim.
std::string refutation_kind(const Json& v) {
  const std::string kind = v.find("kind")->text();
  const Json& ce = *v.find("counterexample");
  if (kind == "solids_collide" || kind == "relation") return "relation";
  if (kind == "distance") return "enclosure";
  if (kind == "curve")
    return ce.find("missed_branch")    ? "missed branch"
           : ce.find("point_on_curve") ? "curve point off the claim"
           : ce.find("surface")        ? "claimed point off a surface"
                                       : "relation";
  if (ce.find("surface")) return "point off surface";
  if (ce.find("closer_pair")) return "closer pair";
  if (ce.find("pairs")) return "closer (enclosure)";
  return "below minimum";
}

struct Tally {
  long claims = 0, confirmed = 0, refuted = 0, undecided = 0, no_answer = 0;
  std::map<std::string, long> kinds;
};

#ifdef SURFCERT_HAVE_FCL
// FCL in a child process: its libccd solver aborts on an assertion for some exactly tangent
// pairs (doSimplex2 "A is not in region 1"), which would end the whole run. `aborted` tells
// such a pair (then no answer).
bench::FclResult fcl_guarded(const EllipsoidParams& a, const EllipsoidParams& b,
                             const bench::FclOptions& o, bool& aborted) {
  aborted = false;
  struct Wire {
    double distance;
    std::array<double, 3> p1, p2;
    bool ok;
  } w{};
  int fd[2];
  if (pipe(fd) != 0) return bench::fcl_distance(a, b, o);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    const bench::FclResult r = bench::fcl_distance(a, b, o);
    w = {r.distance, r.p1, r.p2, r.ok};
    const ssize_t wrote = write(fd[1], &w, sizeof w);
    _exit(wrote == static_cast<ssize_t>(sizeof w) ? 0 : 1);
  }
  close(fd[1]);
  const ssize_t got = pid > 0 ? read(fd[0], &w, sizeof w) : -1;
  close(fd[0]);
  int st = 0;
  if (pid > 0) waitpid(pid, &st, 0);
  bench::FclResult r;
  if (pid < 0 || got != static_cast<ssize_t>(sizeof w) || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
    aborted = pid > 0;
    return r; // ok = false
  }
  r.distance = w.distance, r.p1 = w.p1, r.p2 = w.p2, r.ok = w.ok;
  return r;
}
#endif

// What a family asks of the peers: OCCT IntSS curves (curve claims), and relation claims
// where an answer asserts one (FCL or surfcert float reporting the solids apart: separated).
struct FamilyOptions {
  bool curves = false;
  bool relations = false;
};

std::vector<std::pair<std::string, Answer>> peer_answers(const Pair& pr,
                                                         [[maybe_unused]] FamilyOptions fo) {
  std::vector<std::pair<std::string, Answer>> out;
#ifdef SURFCERT_HAVE_FCL
  for (auto solver : {bench::FclSolver::Libccd, bench::FclSolver::Indep})
    for (double tol : {1e-6, 1e-12}) {
      bench::FclOptions o;
      o.solver = solver, o.tolerance = tol;
      bool aborted = false;
      const bench::FclResult r = fcl_guarded(pr.ea, pr.eb, o, aborted);
      const std::string name = std::string("FCL ") + bench::fcl_solver_name(solver) +
                               (tol == 1e-6 ? " tol 1e-6" : " tol 1e-12");
      Answer a;
      if (!r.ok) {
        out.emplace_back(name, Answer{}); // counted as no answer below (collide false)
        out.back().second.tol = aborted ? -2 : -1;
        continue;
      }
      a.collide = r.distance < 0;
      a.apart_known = r.distance >= 0;
      a.solid = true;
      a.distance = r.distance, a.p = r.p1, a.q = r.p2, a.tol = tol;
      if (fo.relations && a.apart_known) a.relation = "separated";
      out.emplace_back(name, a);
    }
#endif
#ifdef SURFCERT_HAVE_OCCT
  {
    // Surfaces: the distance (0 for crossing surfaces) and nearest points, within OCCT's
    // Precision::Confusion (1e-7); and GeomAPI_IntSS's curves (tolerance 1e-7), sampled at 400
    // chords per line, claimed within 1e-3.
    const bench::OcctDistanceResult d = bench::occt_distance(pr.ea, pr.eb);
    Answer a;
    a.collide_known = false, a.tol = 1e-7;
    if (d.ok)
      a.apart_known = true, a.distance = d.distance, a.p = d.p1, a.q = d.p2;
    else
      a.tol = -1;
    out.emplace_back("OCCT ExtremaSurfaceSurface", a);
    if (fo.curves) {
      const bench::OcctResult c = bench::occt_intersect(pr.ea, pr.eb, 1e-7, 400);
      Answer ac;
      ac.collide_known = false, ac.tol = 0;
      if (c.ok)
        ac.curve_known = true, ac.curve = c.polylines;
      else
        ac.tol = -1;
      out.emplace_back("OCCT IntSS curve", ac);
    }
  }
#endif
  // surfcert's float mode: the solid estimate decides collision, the surface estimate and its
  // approximate pair give the distance claims.
  const certify::DistanceResult s =
      certify::surface_distance(pr.a, pr.b, 15, true, certify::Mode::Float);
  Answer a;
  a.tol = 1e-9;
  if (!s.estimate) {
    a.tol = -1; // no float answer (the float search does not apply): no claim
  } else {
    a.collide = s.estimate->value <= 0;
    if (!a.collide) {
      const certify::DistanceResult d =
          certify::surface_distance(pr.a, pr.b, 15, false, certify::Mode::Float);
      if (fo.relations) a.relation = "separated";
      if (d.estimate && !d.pairs.empty()) {
        a.apart_known = true;
        a.distance = d.estimate->value, a.p = d.pairs[0][0], a.q = d.pairs[0][1];
      }
    }
  }
  out.emplace_back("surfcert float", a);
  return out;
}

void run_family(const std::string& family, const std::vector<Pair>& pairs, FamilyOptions fo,
                std::map<std::pair<std::string, std::string>, Tally>& table,
                std::vector<std::string>& order) {
  long done = 0;
  const char* show = std::getenv("VERIFY_PEERS_SHOW");
  for (const Pair& pr : pairs) {
    Json claims = Json::array();
    std::vector<std::string> owner;
    for (const auto& [peer, ans] : peer_answers(pr, fo)) {
      auto key = std::make_pair(family, peer);
      if (std::find(order.begin(), order.end(), peer) == order.end()) order.push_back(peer);
      Tally& t = table[key];
      if (ans.tol < 0) {
        ++t.no_answer;
        if (ans.tol == -2) ++t.kinds["no answer: aborted (assertion)"];
        continue;
      }
      add_claims(ans, peer, claims, owner);
    }
    if (owner.empty()) continue;
    Json line = Json::object();
    line.set("claims", claims);
    core::BudgetScope budget(20000.0); // 20 s per pair at most
    const Json env = app::verify_claims(pr.a, pr.b, line, "", certify::Mode::Filtered);
    const Json& vs = *env.find("result")->find("verdicts");
    for (size_t i = 0; i < vs.size(); ++i) {
      Tally& t = table[{family, owner[i]}];
      const Json& v = vs.items()[i];
      const std::string verdict = v.find("verdict")->text();
      ++t.claims;
      if (verdict == "confirmed") ++t.confirmed;
      if (verdict == "undecided") ++t.undecided;
      if (verdict == "refuted")
        ++t.refuted, ++t.kinds[v.find("kind")->text() + ": " + refutation_kind(v)];
      // VERIFY_PEERS_SHOW=text: every verdict other than confirmed in the families whose
      // name contains the text, with the pair (index in the family) and the claim, on stderr.
      if (show && verdict != "confirmed" && family.find(show) != std::string::npos)
        std::fprintf(stderr, "[%s #%ld] %s: claim %s\n  -> %s\n", family.c_str(), done,
                     owner[i].c_str(), core::io::dump(claims.items()[i]).c_str(),
                     core::io::dump(v).c_str());
    }
    if (++done % 10 == 0) std::fprintf(stderr, "%s: %ld/%zu\n", family.c_str(), done, pairs.size());
  }
}

} // namespace

// The exact classifier's components of the pair (nullopt when it does not certify a
// morphology): the isolated-point and double-curve families keep only the constructions whose
// label it confirms, never the label the construction was meant to have.
std::optional<certify::Morphology> exact_morphology(const Pair& p) {
  const certify::QsicResult r = certify::classify_qsic(p.a, p.b, certify::Mode::Exact);
  if (r.status != certify::Status::Certified || !r.morphology) return std::nullopt;
  return *r.morphology;
}

bool one_isolated_point(const certify::Morphology& m) {
  return m.isolated_points == 1 && m.loops + m.lines + m.conics + m.cubics == 0;
}

bool one_double_conic(const certify::Morphology& m) {
  return m.double_components == 1 && m.conics == 1 &&
         m.loops + m.lines + m.cubics + m.isolated_points == 0;
}

Pair axis_pair(const EllipsoidParams& ea, const EllipsoidParams& eb) {
  return {axis_aligned(ea), axis_aligned(eb), ea, eb};
}

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 100;
  const unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2026;
  const int curve_pairs = argc > 3 ? std::atoi(argv[3]) : 30;
  const int nested_pairs = argc > 4 ? std::atoi(argv[4]) : 50;
  std::vector<Pair> random_pairs, tangent_apart, tangent_crossing;
  std::mt19937_64 rng(seed);
  for (int i = 0; i < n; ++i) {
    bench::RandomEllipsoid e1 = bench::random_ellipsoid(rng), e2 = bench::random_ellipsoid(rng);
    random_pairs.push_back({e1.quadric, e2.quadric, e1.params, e2.params});
  }
  const EllipsoidParams ea = params({-1, 0, 0}, {1, 0.5, 1.0 / 3});
  for (int k = 10; k <= 60; ++k)
    for (int side : {1, -1}) {
      const double g = side * std::ldexp(1.0, -k), rb = std::ldexp(1.0, -8);
      const EllipsoidParams eb = params({rb + g, 0, 0}, {rb, 0.5, 1.0 / 3});
      (side > 0 ? tangent_apart : tangent_crossing).push_back(axis_pair(ea, eb));
    }

  // Nested: a big random ellipsoid A (semi-axes 1/2..1) and a small one B (semi-axes
  // 1/20..1/5, random rotation) whose centre is off A's by less than (min radius of A - max
  // radius of B) / 2 per coordinate: B's bounding ball lies strictly inside A's inscribed ball.
  std::vector<Pair> nested;
  {
    std::mt19937_64 nrng(seed + 1);
    std::uniform_int_distribution<long> c(-500, 500), ra(50, 100), rb(5, 20), q(-9, 9);
    for (int i = 0; i < nested_pairs; ++i) {
      long radii_a[3], radii_b[3], ca[3], cb[3], qa[4], qb[4];
      for (long& v : radii_a)
        v = ra(nrng);
      for (long& v : radii_b)
        v = rb(nrng);
      for (long* qq : {qa, qb})
        do
          for (int j = 0; j < 4; ++j)
            qq[j] = q(nrng);
        while (qq[0] == 0 && qq[1] == 0 && qq[2] == 0 && qq[3] == 0);
      const long room =
          (*std::min_element(radii_a, radii_a + 3) - *std::max_element(radii_b, radii_b + 3)) * 10 /
              2 -
          1; // thousandths
      std::uniform_int_distribution<long> off(-room, room);
      for (int j = 0; j < 3; ++j)
        ca[j] = c(nrng), cb[j] = ca[j] + off(nrng);
      const bench::RandomEllipsoid a =
          bench::ellipsoid_from(radii_a, qa[0], qa[1], qa[2], qa[3], ca);
      const bench::RandomEllipsoid b =
          bench::ellipsoid_from(radii_b, qb[0], qb[1], qb[2], qb[3], cb);
      nested.push_back({a.quadric, b.quadric, a.params, b.params});
    }
  }

  // Isolated points (one real point, exact tangency): external, axis-aligned ellipsoids with
  // x semi-axes a and b centred at 0 and (a + b, 0, 0) (the plane x = a separates them), and
  // internal: A = (x+1)^2 + 4y^2 + 4z^2 = 1 (tip at the origin, curvature radius 1/4 there)
  // and B with semi-axes (2^-8, 2^-9, 2^-9) centred at (-2^-8 + g, 0, 0) (curvature radius
  // 2^-10 at its tip): g = 0 touches at the origin only, g = -2^-k nests B at gap 2^-k,
  // g = +2^-k pokes B's tip out by 2^-k.
  const double e8 = std::ldexp(1.0, -8), e9 = std::ldexp(1.0, -9);
  const EllipsoidParams big = params({-1, 0, 0}, {1, 0.5, 0.5});
  auto inner = [&](double g) { return params({-e8 + g, 0, 0}, {e8, e9, e9}); };
  std::vector<Pair> iso_candidates = {
      axis_pair(params({0, 0, 0}, {1, 1, 1}), params({1.5, 0, 0}, {0.5, 0.5, 0.5})),
      axis_pair(params({0, 0, 0}, {1, 0.5, 1.0 / 3}), params({1.5, 0, 0}, {0.5, 1, 0.25})),
      axis_pair(ea, params({e8, 0, 0}, {e8, 0.5, 1.0 / 3})),
      axis_pair(params({0, 0, 0}, {0.75, 0.25, 0.5}), params({0.8125, 0, 0}, {0.0625, 2, 1})),
      axis_pair(big, inner(0)),
      axis_pair(params({0, 0, 0}, {1, 1, 1}), params({0.5, 0, 0}, {0.5, 0.25, 0.25})),
  };
  std::vector<Pair> internal_nested, internal_crossing;
  for (int k = 10; k <= 60; ++k) {
    internal_nested.push_back(axis_pair(big, inner(-std::ldexp(1.0, -k))));
    internal_crossing.push_back(axis_pair(big, inner(std::ldexp(1.0, -k))));
  }

  // Double curves (a conic counted twice: tangent along a circle): spheres and ellipsoids of
  // revolution with equal equators, and a sphere of radius 2^-8 -+ 2^-k inside the ellipsoid
  // (2^-8, 2^-8, 2^-7): nested at gap 2^-k along the whole equator, or crossing in two circles.
  std::vector<Pair> dbl_candidates = {
      axis_pair(params({0, 0, 0}, {1, 1, 1}), params({0, 0, 0}, {1, 1, 2})),
      axis_pair(params({0, 0, 0}, {1, 1, 1}), params({0, 0, 0}, {1, 1, 0.5})),
      axis_pair(params({0.25, -0.5, 0}, {e8, e8, e8}), params({0.25, -0.5, 0}, {e8, e8, 2 * e8})),
      axis_pair(params({0, 0, 0}, {0.5, 0.75, 1}), params({0, 0, 0}, {0.5, 0.75, 0.25})),
  };
  std::vector<Pair> dbl_nested, dbl_crossing;
  const EllipsoidParams prolate = params({0, 0, 0}, {e8, e8, 2 * e8});
  for (int k = 10; k <= 60; ++k) {
    const double g = std::ldexp(1.0, -k);
    dbl_nested.push_back(axis_pair(params({0, 0, 0}, {e8 - g, e8 - g, e8 - g}), prolate));
    dbl_crossing.push_back(axis_pair(params({0, 0, 0}, {e8 + g, e8 + g, e8 + g}), prolate));
  }
  auto keep = [](const std::vector<Pair>& cands, bool (*label)(const certify::Morphology&),
                 const char* what) {
    std::vector<Pair> out;
    for (size_t i = 0; i < cands.size(); ++i) {
      const std::optional<certify::Morphology> m = exact_morphology(cands[i]);
      if (m && label(*m))
        out.push_back(cands[i]);
      else
        std::fprintf(stderr, "%s candidate %zu dropped: exact label %s\n", what, i,
                     m ? m->id : "(none)");
    }
    return out;
  };
  const std::vector<Pair> isolated = keep(iso_candidates, one_isolated_point, "isolated point");
  const std::vector<Pair> dbl = keep(dbl_candidates, one_double_conic, "double conic");

  std::map<std::pair<std::string, std::string>, Tally> table;
  std::vector<std::string> order;
  std::vector<std::string> families;
  auto run = [&](const std::string& family, const std::vector<Pair>& pairs, FamilyOptions fo) {
    families.push_back(family);
    run_family(family, pairs, fo, table, order);
  };
  run("random (seed 002 §5.1.3)", random_pairs, {});
  if (random_pairs.size() > static_cast<size_t>(curve_pairs))
    random_pairs.erase(random_pairs.begin() + curve_pairs, random_pairs.end());
  run("random, curves", random_pairs, {true, false});
  run("tangent apart (gap 2^-k)", tangent_apart, {});
  run("tangent crossing (overlap 2^-k)", tangent_crossing, {});
  run("nested (random poses)", nested, {false, true});
  run("isolated point (exact tangency)", isolated, {true, true});
  run("internal tangent, nested (gap 2^-k)", internal_nested, {false, true});
  run("internal tangent, crossing (2^-k out)", internal_crossing, {false, true});
  run("double conic (exact)", dbl, {true, true});
  run("double conic, nested (gap 2^-k)", dbl_nested, {false, true});
  run("double conic, crossing (2^-k out)", dbl_crossing, {false, true});
  std::printf("verify_peers: %d random pairs (seed %lu), %d nested (seed %lu), %zu of %zu "
              "isolated-point and %zu of %zu double-conic constructions kept by the exact "
              "classifier; gaps k = 10..60 each side\n\n",
              n, seed, nested_pairs, seed + 1, isolated.size(), iso_candidates.size(), dbl.size(),
              dbl_candidates.size());
  std::printf("| family | peer | claims | confirmed | refuted | undecided | no answer | "
              "refuted by |\n|---|---|---:|---:|---:|---:|---:|---|\n");
  for (const std::string& family : families)
    for (size_t i = 0; i < order.size(); ++i) {
      auto it = table.find({family, order[i]});
      if (it == table.end()) continue;
      const Tally& t = it->second;
      std::string kinds;
      for (const auto& [k, c] : t.kinds)
        kinds += (kinds.empty() ? "" : "; ") + k + " " + std::to_string(c);
      std::printf("| %s | %s | %ld | %ld | %ld | %ld | %ld | %s |\n", family.c_str(),
                  order[i].c_str(), t.claims, t.confirmed, t.refuted, t.undecided, t.no_answer,
                  kinds.c_str());
    }
  return 0;
}
