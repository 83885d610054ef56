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
// Usage: verify_peers [pairs=100] [seed=2026] [curve_pairs=30]. Prints a markdown table;
// progress on stderr.
#include "random_ellipsoids.hpp"

#include "surfcert/app/verify.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/budget.hpp"

#ifdef SURFCERT_HAVE_FCL
#include "fcl_peer.hpp"
#endif
#ifdef SURFCERT_HAVE_OCCT
#include "occt_distance_peer.hpp"
#include "occt_peer.hpp"
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
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

std::vector<std::pair<std::string, Answer>> peer_answers(const Pair& pr,
                                                         [[maybe_unused]] bool curves) {
  std::vector<std::pair<std::string, Answer>> out;
#ifdef SURFCERT_HAVE_FCL
  for (auto solver : {bench::FclSolver::Libccd, bench::FclSolver::Indep})
    for (double tol : {1e-6, 1e-12}) {
      bench::FclOptions o;
      o.solver = solver, o.tolerance = tol;
      const bench::FclResult r = bench::fcl_distance(pr.ea, pr.eb, o);
      const std::string name = std::string("FCL ") + bench::fcl_solver_name(solver) +
                               (tol == 1e-6 ? " tol 1e-6" : " tol 1e-12");
      Answer a;
      if (!r.ok) {
        out.emplace_back(name, Answer{}); // counted as no answer below (collide false)
        out.back().second.tol = -1;
        continue;
      }
      a.collide = r.distance < 0;
      a.apart_known = r.distance >= 0;
      a.solid = true;
      a.distance = r.distance, a.p = r.p1, a.q = r.p2, a.tol = tol;
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
    if (curves) {
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
      if (d.estimate && !d.pairs.empty()) {
        a.apart_known = true;
        a.distance = d.estimate->value, a.p = d.pairs[0][0], a.q = d.pairs[0][1];
      }
    }
  }
  out.emplace_back("surfcert float", a);
  return out;
}

void run_family(const std::string& family, const std::vector<Pair>& pairs, bool curves,
                std::map<std::pair<std::string, std::string>, Tally>& table,
                std::vector<std::string>& order) {
  long done = 0;
  for (const Pair& pr : pairs) {
    Json claims = Json::array();
    std::vector<std::string> owner;
    for (const auto& [peer, ans] : peer_answers(pr, curves)) {
      auto key = std::make_pair(family, peer);
      if (std::find(order.begin(), order.end(), peer) == order.end()) order.push_back(peer);
      Tally& t = table[key];
      if (ans.tol < 0) {
        ++t.no_answer;
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
    }
    if (++done % 10 == 0) std::fprintf(stderr, "%s: %ld/%zu\n", family.c_str(), done, pairs.size());
  }
}

} // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 100;
  const unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2026;
  const int curve_pairs = argc > 3 ? std::atoi(argv[3]) : 30;
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
      (side > 0 ? tangent_apart : tangent_crossing)
          .push_back({axis_aligned(ea), axis_aligned(eb), ea, eb});
    }
  std::map<std::pair<std::string, std::string>, Tally> table;
  std::vector<std::string> order;
  run_family("random (seed 002 §5.1.3)", random_pairs, false, table, order);
  if (random_pairs.size() > static_cast<size_t>(curve_pairs))
    random_pairs.erase(random_pairs.begin() + curve_pairs, random_pairs.end());
  run_family("random, curves", random_pairs, true, table, order);
  run_family("tangent apart (gap 2^-k)", tangent_apart, false, table, order);
  run_family("tangent crossing (overlap 2^-k)", tangent_crossing, false, table, order);
  std::printf("verify_peers: %d random pairs (seed %lu); tangency k = 10..60 each side\n\n", n,
              seed);
  std::printf("| family | peer | claims | confirmed | refuted | undecided | no answer | "
              "refuted by |\n|---|---|---:|---:|---:|---:|---:|---|\n");
  for (const std::string family : {"random (seed 002 §5.1.3)", "random, curves",
                                   "tangent apart (gap 2^-k)", "tangent crossing (overlap 2^-k)"})
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
