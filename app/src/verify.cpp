#include "surfcert/app/verify.hpp"

#include "surfcert/app/claim_geometry.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include "surfcert/algebra/inertia.hpp"

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/morphology.hpp"
#include "surfcert/core/budget.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace surfcert::app {

using certify::DistanceResult;
using certify::Mode;
using certify::QsicResult;
using certify::Status;
using core::InputError;
using core::Rational;
using core::io::Json;
using core::io::json_path_child;
using core::io::json_path_index;

namespace {

const std::vector<std::string> kRelations = {"separated", "touching", "overlapping", "nested",
                                             "coincident"};
const std::vector<std::string> kComponentKeys = {"loops",
                                                 "isolated_points",
                                                 "lines",
                                                 "conics",
                                                 "cubics",
                                                 "double_components",
                                                 "connected_components"};

struct Claim {
  std::string kind, path;
  std::string relation, inside;  // relation (inside: "", "a", "b")
  bool collide = false;          // solids_collide
  bool touching_collides = true; // solids_collide: does a touching contact count
  std::string morphology;        // morphology
  long tu_case = 0;              // tu_case
  std::vector<std::pair<std::string, long>> components; // components (only the keys given)
  Rational value, abs_tol, rel_tol;                     // distance (abs_tol: also the others)
  bool solid = false;
  std::vector<std::vector<RPoint>> polylines; // closest_points: one of two points; curve
};

std::string found(const Json& v) {
  return v.is_string() ? "\"" + v.text() + "\"" : core::io::type_name(v.type());
}

InputError bad(const Json& v, const std::string& source, const std::string& path,
               const std::string& expected) {
  return InputError(core::io::json_location(v, source, path), expected, found(v));
}

// A point [x, y, z] of three numbers (read exactly).
RPoint read_point(const Json& v, const std::string& source, const std::string& path) {
  if (!v.is_array() || v.size() != 3) throw bad(v, source, path, "a point [x, y, z]");
  return {core::io::read_number(v.items()[0], source, json_path_index(path, 0)),
          core::io::read_number(v.items()[1], source, json_path_index(path, 1)),
          core::io::read_number(v.items()[2], source, json_path_index(path, 2))};
}

// A JSON value that must be a non-negative integer (component counts, tu_case).
long read_count(const Json& v, const std::string& source, const std::string& path, long max) {
  Rational r = core::io::read_number(v, source, path);
  if (!r.is_integer() || r < Rational(0) || r > Rational(max))
    throw InputError(core::io::json_location(v, source, path),
                     "an integer from 0 to " + std::to_string(max), r.to_string());
  return static_cast<long>(r.to_double_approx());
}

Claim read_claim(const Json& c, const std::string& source, const std::string& path,
                 bool two_quadrics) {
  if (!c.is_object()) throw bad(c, source, path, "a claim object {\"kind\", \"value\", ...}");
  Claim out;
  out.path = path;
  const Json* kind = c.find("kind");
  const std::string kpath = json_path_child(path, "kind");
  const char* kinds =
      "a claim kind: \"relation\", \"solids_collide\", \"morphology\", \"tu_case\", "
      "\"components\", \"distance\", \"closest_points\" or \"curve\"";
  if (!kind) throw InputError(core::io::json_location(c, source, kpath), kinds, "none");
  if (!kind->is_string()) throw bad(*kind, source, kpath, kinds);
  out.kind = kind->text();
  std::set<std::string> fields = {"kind", "value"};
  if (out.kind == "relation")
    fields.insert("inside");
  else if (out.kind == "solids_collide")
    fields.insert("touching_collides");
  else if (out.kind == "distance")
    fields.insert({"abs_tol", "rel_tol", "solid"});
  else if (out.kind == "closest_points" || out.kind == "curve")
    fields.insert("abs_tol");
  else if (out.kind != "morphology" && out.kind != "tu_case" && out.kind != "components")
    throw bad(*kind, source, kpath, kinds);
  core::io::check_fields(c, fields, source, path);
  const Json* v = c.find("value");
  const std::string vpath = json_path_child(path, "value");
  if (!v) throw InputError(core::io::json_location(c, source, vpath), "a claimed value", "none");
  // The classification claims are about the intersection curve of two quadrics.
  if (!two_quadrics && (out.kind == "morphology" || out.kind == "tu_case" ||
                        out.kind == "components" || out.kind == "curve"))
    throw bad(*kind, source, kpath, "a claim on two quadrics (\"a\" or \"b\" is not a quadric)");
  auto read_bool = [&](const Json& j, const std::string& p) {
    if (!j.is_bool()) throw bad(j, source, p, "true or false");
    return j.as_bool();
  };
  if (out.kind == "relation") {
    const char* rels = "a relation: \"separated\", \"touching\", \"overlapping\", \"nested\" or "
                       "\"coincident\"";
    if (!v->is_string() ||
        std::find(kRelations.begin(), kRelations.end(), v->text()) == kRelations.end())
      throw bad(*v, source, vpath, rels);
    out.relation = v->text();
    if (const Json* in = c.find("inside")) {
      const std::string ipath = json_path_child(path, "inside");
      if (!in->is_string() || (in->text() != "a" && in->text() != "b"))
        throw bad(*in, source, ipath, "\"a\" or \"b\" (the surface inside the other)");
      if (out.relation != "nested" && out.relation != "touching")
        throw bad(*in, source, ipath, "no \"inside\" (only nested or touching has one)");
      out.inside = in->text();
    }
  } else if (out.kind == "solids_collide") {
    out.collide = read_bool(*v, vpath);
    if (const Json* t = c.find("touching_collides"))
      out.touching_collides = read_bool(*t, json_path_child(path, "touching_collides"));
  } else if (out.kind == "morphology") {
    if (!v->is_string() || (!certify::morphology_by_id(v->text()) &&
                            v->text() != "degenerate_pencil" && v->text() != "coincident_quadrics"))
      throw bad(*v, source, vpath,
                "a morphology id (README, the 35 cases), \"degenerate_pencil\" or "
                "\"coincident_quadrics\"");
    out.morphology = v->text();
  } else if (out.kind == "tu_case") {
    out.tu_case = read_count(*v, source, vpath, 35);
    if (out.tu_case < 1)
      throw InputError(core::io::json_location(*v, source, vpath), "a Tu case from 1 to 35", "0");
  } else if (out.kind == "components") {
    if (!v->is_object() || v->size() == 0)
      throw bad(*v, source, vpath, "an object of component counts, e.g. {\"loops\": 2}");
    for (const auto& [key, n] : v->members()) {
      const std::string p = json_path_child(vpath, key);
      if (std::find(kComponentKeys.begin(), kComponentKeys.end(), key) == kComponentKeys.end())
        throw InputError(core::io::json_location(n, source, p),
                         "a component count: loops, isolated_points, lines, conics, cubics, "
                         "double_components or connected_components",
                         "\"" + key + "\"");
      out.components.emplace_back(key, read_count(n, source, p, 1000));
    }
  } else if (out.kind == "closest_points") {
    if (!v->is_array() || v->size() != 2)
      throw bad(*v, source, vpath, "two points [[x, y, z], [x, y, z]] (on a, on b)");
    out.polylines.push_back({read_point(v->items()[0], source, json_path_index(vpath, 0)),
                             read_point(v->items()[1], source, json_path_index(vpath, 1))});
  } else if (out.kind == "curve") {
    if (!v->is_array())
      throw bad(*v, source, vpath, "an array of polylines [[[x, y, z], ...], ...] ([]: empty)");
    for (size_t i = 0; i < v->size(); ++i) {
      const Json& line = v->items()[i];
      const std::string lpath = json_path_index(vpath, i);
      if (!line.is_array() || line.size() == 0)
        throw bad(line, source, lpath, "a polyline: a non-empty array of points [x, y, z]");
      out.polylines.emplace_back();
      for (size_t j = 0; j < line.size(); ++j)
        out.polylines.back().push_back(
            read_point(line.items()[j], source, json_path_index(lpath, j)));
    }
  }
  if (out.kind == "distance" || out.kind == "closest_points" || out.kind == "curve") {
    if (out.kind == "distance") out.value = core::io::read_number(*v, source, vpath);
    for (const char* key : {"abs_tol", "rel_tol"})
      if (const Json* t = c.find(key)) {
        const std::string p = json_path_child(path, key);
        Rational r = core::io::read_number(*t, source, p);
        if (r.sign() < 0)
          throw InputError(core::io::json_location(*t, source, p), "a non-negative tolerance",
                           r.to_decimal_approx(6));
        (std::string(key) == "abs_tol" ? out.abs_tol : out.rel_tol) = r;
      }
    if (const Json* s = c.find("solid")) out.solid = read_bool(*s, json_path_child(path, "solid"));
  }
  return out;
}

Json str(const std::string& s) {
  return Json::string(s);
}

Json enclosure_json(const certify::Enclosure& e) {
  Json o = Json::object();
  o.set("lower", str(e.lower()));
  o.set("upper", str(e.upper()));
  return o;
}

Json pairs_json(const DistanceResult& d) {
  auto num = [](double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return Json::number_text(buf);
  };
  Json ps = Json::array();
  for (const auto& pq : d.pairs) {
    Json pair = Json::array();
    for (const auto& p : pq) {
      Json pt = Json::array();
      for (double x : p)
        pt.push_back(num(x));
      pair.push_back(pt);
    }
    ps.push_back(pair);
  }
  return ps;
}

// What the certified machinery says about how the two surfaces lie: the relations still
// possible (one when decided) and, for nested or internal touching, which surface is inside
// ("a", "b"; "none" for an external touching; "" when not established).
struct RelationFacts {
  std::set<std::string> possible;
  std::string inside;
  Json established = Json::object();
};

// The engine's answers, computed once per verify line and shared by its claims.
class Oracle {
public:
  Oracle(const core::Surface& a, const core::Surface& b, Mode mode) : a_(a), b_(b), mode_(mode) {}

  const core::Surface& a() const { return a_; }
  const core::Surface& b() const { return b_; }
  const core::QuadricMatrix* qa() const { return std::get_if<core::QuadricMatrix>(&a_); }
  const core::QuadricMatrix* qb() const { return std::get_if<core::QuadricMatrix>(&b_); }

  // The certified classification (nullptr unless both are quadrics and it is certified).
  const QsicResult* qsic() {
    if (!qsic_done_ && qa() && qb()) {
      QsicResult r = certify::classify_qsic(*qa(), *qb(), mode_);
      if (r.status == Status::Certified) {
        certify::complete_report_data(r, *qa(), *qb());
        qsic_ = std::move(r);
      }
      qsic_done_ = true;
    }
    return qsic_ ? &*qsic_ : nullptr;
  }

  const DistanceResult& distance(bool solid, long digits) {
    auto key = std::make_pair(solid, digits);
    auto it = dist_.find(key);
    if (it == dist_.end())
      it = dist_.emplace(key, certify::surface_distance(a_, b_, digits, solid, mode_)).first;
    return it->second;
  }

  // A certified enclosure that is exactly 0 (true), proven positive (false), or nullopt.
  std::optional<bool> is_zero(bool solid) {
    const DistanceResult& d = distance(solid, 15);
    if (d.status != Status::Certified || !d.distance) return std::nullopt;
    if (d.distance->is_zero()) return true;
    if (arf_sgn(d.distance->lower_arf()) > 0) return false;
    return std::nullopt;
  }

  const RelationFacts& relation() {
    if (relation_) return *relation_;
    RelationFacts f;
    if (const QsicResult* r = qsic()) {
      // Two quadrics: a coincident pencil is certified; two ellipsoids have their relation
      // decided from the exact pencil roots (qsic.cpp).
      const std::string& er = r->ellipsoid_relation;
      if (r->pencil == algebra::PencilKind::Coincident)
        f.possible = {"coincident"};
      else if (er == "externally_touching")
        f.possible = {"touching"}, f.inside = "none";
      else if (er == "internally_touching" || er == "nested")
        f.possible = {er == "nested" ? "nested" : "touching"},
        f.inside = r->containment == "a_inside_b" ? "a" : "b";
      else if (er == "separated" || er == "overlapping")
        f.possible = {er};
      if (!er.empty()) f.established.set("ellipsoid_relation", str(er));
    }
    // Both real surfaces: a semidefinite matrix (a double plane x^2 = 0, the line
    // x^2 + y^2 = 0, a point) makes every common component double or isolated without any
    // tangency (the unit sphere against x^2 = 0, or against the z axis x^2 + y^2 = 0 that
    // pierces it, were certified 'touching'); such pairs go to the distances below.
    auto real_surface = [](const core::QuadricMatrix* m) {
      return !algebra::inertia_ldlt(m->matrix()).semidefinite();
    };
    if (const QsicResult* r = qsic(); f.possible.empty() && r && r->morphology &&
                                      r->pencil == algebra::PencilKind::Regular &&
                                      (qa()->kind() == core::QuadricKind::Ellipsoid ||
                                       qb()->kind() == core::QuadricKind::Ellipsoid) &&
                                      real_surface(qa()) && real_surface(qb())) {
      // An ellipsoid and another quadric: the certified morphology counts the affine real
      // components (morphology.hpp). A simple curve component (multiplicity 1) is met
      // transversally at its generic points, so the surfaces cross: overlapping. When every
      // real component is an isolated point or a double component, the surfaces meet without
      // crossing (along a double conic B = l A + m P^2, so B keeps one sign on A): touching.
      // No real component: the surfaces do not meet (the distances below decide).
      const certify::Morphology& m = *r->morphology;
      const int simple = m.loops + m.lines + m.conics + m.cubics - m.double_components;
      if (simple + m.double_components + m.isolated_points > 0) {
        f.possible = {simple > 0 ? "overlapping" : "touching"};
        f.established.set("morphology", str(m.id));
        f.established.set("surfaces_cross", Json::boolean(simple > 0));
      }
    }
    if (f.possible.empty()) {
      // Otherwise from the certified distances: the surfaces meet iff their distance is
      // exactly 0; apart, the solids are nested iff the solid distance is exactly 0.
      f.possible.insert(kRelations.begin(), kRelations.end());
      std::optional<bool> meet = is_zero(false);
      if (meet) f.established.set("surfaces_meet", Json::boolean(*meet));
      if (meet && *meet) f.possible = {"touching", "overlapping", "coincident"};
      if (meet && !*meet) {
        f.possible = {"separated", "nested"};
        std::optional<bool> solids_meet = is_zero(true);
        if (solids_meet) {
          f.established.set("solids_meet", Json::boolean(*solids_meet));
          f.possible = {*solids_meet ? "nested" : "separated"};
        }
      }
    }
    if (f.possible.size() == 1) {
      f.established.set("relation", str(*f.possible.begin()));
      if (f.inside == "a" || f.inside == "b") f.established.set("inside", str(f.inside));
      if (f.inside == "none") f.established.set("inside", Json::null()); // external touching
    } else {
      Json p = Json::array();
      for (const auto& s : f.possible)
        p.push_back(str(s));
      f.established.set("possible_relations", p);
    }
    relation_ = std::move(f);
    return *relation_;
  }

private:
  const core::Surface& a_;
  const core::Surface& b_;
  Mode mode_;
  bool qsic_done_ = false;
  std::optional<QsicResult> qsic_;
  std::map<std::pair<bool, long>, DistanceResult> dist_;
  std::optional<RelationFacts> relation_;
};

const char* const kBudgetNote = "the time budget ran out";

// The most boxes a curve claim's coverage proof examines before answering undecided.
constexpr long kMaxCoverageBoxes = 2000000;

// The most pieces the claimed segments of a curve claim are cut into (to prove each within tol
// of the curve) before answering undecided.
constexpr long kMaxSegmentPieces = 20000;

struct Verdict {
  std::string verdict = "undecided";
  std::optional<Json> counterexample, established;
  std::string note;
  bool out_of_time = false; ///< undecided because the budget ran out (a flag, not the note)
};

Verdict decide_relation(const Claim& c, Oracle& o) {
  const RelationFacts& f = o.relation();
  Verdict v;
  if (!f.possible.count(c.relation)) {
    v.verdict = "refuted";
    v.counterexample = f.established;
  } else if (f.possible.size() > 1) {
    v.established = f.established;
  } else if (c.inside.empty() || c.inside == f.inside) {
    v.verdict = "confirmed";
  } else if (f.inside.empty()) {
    v.established = f.established;
    v.note = "which surface is inside the other is not established";
  } else {
    v.verdict = "refuted";
    v.counterexample = f.established;
  }
  return v;
}

Verdict decide_collide(const Claim& c, Oracle& o) {
  const RelationFacts& f = o.relation();
  // The collide answers every still-possible relation gives; decided when they agree.
  std::set<bool> answers;
  for (const auto& r : f.possible) {
    if (r == "separated")
      answers.insert(false);
    else if (r != "touching" || f.inside == "a" || f.inside == "b")
      answers.insert(true);
    else if (f.inside == "none")
      answers.insert(c.touching_collides);
    else
      answers.insert({c.touching_collides, true}); // external or internal: not known
  }
  Verdict v;
  Json facts = f.established;
  if (answers.size() != 1) {
    v.established = facts;
    return v;
  }
  facts.set("solids_collide", Json::boolean(*answers.begin()));
  if (*answers.begin() == c.collide)
    v.verdict = "confirmed";
  else
    v.verdict = "refuted", v.counterexample = facts;
  return v;
}

Verdict decide_classification(const Claim& c, Oracle& o) {
  Verdict v;
  const QsicResult* r = o.qsic();
  if (!r || (r->pencil == algebra::PencilKind::Regular && !r->morphology)) {
    v.note = "the classification of the intersection is not certified";
    return v;
  }
  const certify::Morphology* m =
      r->pencil == algebra::PencilKind::Regular ? r->morphology : nullptr;
  Json facts = Json::object();
  facts.set("morphology",
            str(m                                              ? m->id
                : r->pencil == algebra::PencilKind::Coincident ? "coincident_quadrics"
                                                               : "degenerate_pencil"));
  facts.set("tu_case", m ? Json::number(m->tu_case) : Json::null());
  bool holds = true;
  if (m) {
    const std::map<std::string, int> counts = {{"loops", m->loops},
                                               {"isolated_points", m->isolated_points},
                                               {"lines", m->lines},
                                               {"conics", m->conics},
                                               {"cubics", m->cubics},
                                               {"double_components", m->double_components},
                                               {"connected_components", m->connected_components}};
    Json comps = Json::object();
    for (const auto& key : kComponentKeys)
      comps.set(key, Json::number(counts.at(key)));
    facts.set("components", comps);
    for (const auto& [key, n] : c.components)
      holds = holds && counts.at(key) == n;
  } else if (c.kind == "components") {
    // A degenerate or coincident pencil lies outside the 35 cases: no counts to compare.
    v.established = facts;
    v.note = "the pencil is outside the 35-case classification: no component counts";
    return v;
  }
  if (c.kind == "morphology") holds = facts.find("morphology")->text() == c.morphology;
  if (c.kind == "tu_case") holds = m && m->tu_case == c.tu_case;
  if (holds)
    v.verdict = "confirmed";
  else
    v.verdict = "refuted", v.counterexample = facts;
  return v;
}

// Working digits that resolve a tolerance tol around v: about log10(max(|v|, tol) / tol) + 3,
// between 15 and kMaxVerifyDigits (the cap for an exact claim).
long digits_for(const Rational& v, const Rational& tol) {
  if (tol.is_zero()) return kMaxVerifyDigits;
  Rational ratio = std::max(core::abs(v), tol) / tol, ten(1);
  long k = 0;
  while (ten < ratio && k < kMaxVerifyDigits)
    ten *= Rational(10), ++k;
  return std::clamp(k + 3, 15L, kMaxVerifyDigits);
}

Verdict decide_distance(const Claim& c, Oracle& o) {
  const Rational tol = std::max(c.abs_tol, c.rel_tol * core::abs(c.value));
  const Rational lo = c.value - tol, hi = c.value + tol;
  Json claimed = Json::object();
  claimed.set("lower", str(lo.to_string()));
  claimed.set("upper", str(hi.to_string()));
  Verdict v;
  std::vector<long> schedule = {15, digits_for(c.value, tol), kMaxVerifyDigits};
  long last = 0;
  for (long digits : schedule) {
    if (digits <= last) continue;
    last = digits;
    const DistanceResult& d = o.distance(c.solid, digits);
    if (d.budget_exhausted) {
      v.note = kBudgetNote;
      v.out_of_time = true;
    }
    // Any enclosure is proven (enclosure.hpp), certified or not; its printed bounds are
    // rounded outward, so comparing them exactly is sound and is what the caller can check.
    if (!d.distance) {
      if (!d.note.empty() && v.note.empty()) v.note = d.note;
      break;
    }
    const certify::Enclosure& e = *d.distance;
    Json evidence = Json::object();
    evidence.set("distance", enclosure_json(e));
    evidence.set("solid", Json::boolean(c.solid));
    evidence.set("digits", Json::number(digits));
    evidence.set("claimed_interval", claimed);
    const Rational L = *Rational::from_string(e.lower());
    const std::optional<Rational> U =
        e.upper_finite() ? Rational::from_string(e.upper()) : std::nullopt;
    if (U && lo <= L && *U <= hi) {
      v.verdict = "confirmed";
      v.established.reset();
      return v;
    }
    if ((U && *U < lo) || L > hi) {
      v.verdict = "refuted";
      evidence.set("pairs", pairs_json(d));
      evidence.set("pairs_approximate", Json::boolean(true));
      v.counterexample = evidence;
      v.established.reset();
      return v;
    }
    v.established = evidence;
    if (d.budget_exhausted) break;
  }
  if (v.note.empty() && v.established)
    v.note = "the certified enclosure straddles the claimed interval at " + std::to_string(last) +
             " digits";
  return v;
}

Json rpoint_json(const RPoint& p) {
  Json o = Json::array();
  for (const auto& x : p)
    o.push_back(str(x.to_string()));
  return o;
}

Json bounds_json(const DistanceBounds& d) {
  Json o = Json::object();
  o.set("lower", str(d.lower));
  o.set("upper", str(d.upper));
  return o;
}

Json witness_json(const SurfaceWitness& w) {
  Json o = Json::array();
  o.push_back(rpoint_json(w.from));
  o.push_back(rpoint_json(w.to));
  return o;
}

RPoint rpoint(const std::array<double, 3>& p) {
  return {Rational::exact_from_double(p[0]), Rational::exact_from_double(p[1]),
          Rational::exact_from_double(p[2])};
}

std::array<double, 3> dpoint(const RPoint& p) {
  return {p[0].to_double_approx(), p[1].to_double_approx(), p[2].to_double_approx()};
}

// Is x within tol of the surface? true: a witness segment within tol (printed under
// `facts`); false: a certified lower bound above tol (the counterexample `off`); nullopt.
std::optional<bool> point_near_surface(const core::Surface& s, const RPoint& x, const Rational& tol,
                                       const std::string& name, Json& facts,
                                       std::optional<Json>& off) {
  if (auto w = surface_witness(s, x, tol * tol)) {
    facts.set(name + "_surface_witness", witness_json(*w));
    return true;
  }
  for (long digits : {15L, 40L}) {
    const std::optional<DistanceBounds> d = point_surface_distance(s, x, digits);
    if (!d) return std::nullopt;
    facts.set(name + "_distance_to_surface", bounds_json(*d));
    if (d->hi <= tol) return true;
    if (tol < d->lo) {
      Json ce = Json::object();
      ce.set("surface", str(name));
      ce.set("claimed", rpoint_json(x));
      ce.set("distance_to_surface", bounds_json(*d));
      ce.set("abs_tol", str(tol.to_string()));
      off = ce;
      return false;
    }
  }
  return std::nullopt;
}

// closest_points: p on a and q on b each within tol of their surface, and |p - q| within tol
// of the certified minimum distance (README, JSON contract).
Verdict decide_closest_points(const Claim& c, Oracle& o) {
  const Rational& t = c.abs_tol;
  const RPoint& p = c.polylines[0][0];
  const RPoint& q = c.polylines[0][1];
  Verdict v;
  Json facts = Json::object();
  std::optional<Json> off;
  const std::optional<bool> pa = point_near_surface(o.a(), p, t, "a", facts, off);
  if (pa && !*pa) return v.verdict = "refuted", v.counterexample = off, v;
  const std::optional<bool> qb = point_near_surface(o.b(), q, t, "b", facts, off);
  if (qb && !*qb) return v.verdict = "refuted", v.counterexample = off, v;
  const Rational d2 = dist2(p, q);
  facts.set("claimed_distance_squared", str(d2.to_string()));
  std::optional<bool> distance_ok;
  long last = 0;
  for (long digits :
       {15L, digits_for(Rational::exact_from_double(std::sqrt(d2.to_double_approx())), t),
        kMaxVerifyDigits}) {
    if (digits <= last) continue;
    last = digits;
    const DistanceResult& d = o.distance(false, digits);
    if (d.budget_exhausted) v.note = kBudgetNote, v.out_of_time = true;
    if (!d.distance || !d.distance->upper_finite()) break;
    const Rational L = *Rational::from_string(d.distance->lower());
    const Rational U = *Rational::from_string(d.distance->upper());
    facts.set("distance", enclosure_json(*d.distance));
    facts.set("digits", Json::number(digits));
    if (!d.minimizers.empty()) facts.set("minimizers", str(d.minimizers.str()));
    if (sqrt_plus_less(U * U, t, d2)) { // U + t < |p - q|: a closer pair exists
      Json ce = facts;
      ce.set("pairs", pairs_json(d));
      ce.set("pairs_approximate", Json::boolean(true));
      // A checkable closer pair: witness segments on a and b (sign changes of their
      // equations) every point pair of which is closer than |p - q| - tol.
      for (const auto& pair : d.pairs) {
        auto wa = surface_witness(o.a(), rpoint(pair[0]), Rational(1));
        auto wb = surface_witness(o.b(), rpoint(pair[1]), Rational(1));
        if (!wa || !wb) continue;
        Rational ub2;
        for (const RPoint* x : {&wa->from, &wa->to})
          for (const RPoint* y : {&wb->from, &wb->to})
            ub2 = std::max(ub2, dist2(*x, *y));
        if (!sqrt_plus_less(ub2, t, d2)) continue;
        Json closer = Json::object();
        closer.set("a_segment", witness_json(*wa));
        closer.set("b_segment", witness_json(*wb));
        closer.set("distance_squared_upper", str(ub2.to_string()));
        ce.set("closer_pair", closer);
        break;
      }
      v.verdict = "refuted", v.counterexample = ce;
      return v;
    }
    if (sqrt_plus_less(d2, t, L * L)) { // |p - q| + tol < L: closer than the minimum
      v.verdict = "refuted", v.counterexample = facts;
      return v;
    }
    if (!sqrt_plus_less(L * L, t, d2) && !sqrt_plus_less(d2, t, U * U)) {
      distance_ok = true;
      break;
    }
    if (d.budget_exhausted) break;
  }
  if (pa && qb && distance_ok) {
    v.verdict = "confirmed";
    return v;
  }
  v.established = facts;
  if (v.note.empty())
    v.note = !pa || !qb ? "a claimed point is not proven within tol of its surface, nor farther"
                        : "the certified distance does not decide |p - q| within tol";
  return v;
}

using DPoint = std::array<double, 3>;

double dnorm2(const DPoint& a, const DPoint& b) {
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

// Approximate distance (doubles) from x to the claimed polylines (their segments, or the
// point of a one-point polyline): only to choose which traced point to certify.
double approx_dist_to_claim(const DPoint& x, const std::vector<std::vector<DPoint>>& lines) {
  double best = HUGE_VAL;
  for (const auto& l : lines)
    for (size_t k = 0; k < l.size(); ++k) {
      const DPoint& s = l[k];
      const DPoint& e = l[k + 1 < l.size() ? k + 1 : k];
      const DPoint u = {e[0] - s[0], e[1] - s[1], e[2] - s[2]};
      const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
      double lam =
          uu > 0 ? ((x[0] - s[0]) * u[0] + (x[1] - s[1]) * u[1] + (x[2] - s[2]) * u[2]) / uu : 0;
      lam = std::clamp(lam, 0.0, 1.0);
      best = std::min(best, dnorm2(x, {s[0] + lam * u[0], s[1] + lam * u[1], s[2] + lam * u[2]}));
    }
  return std::sqrt(best);
}

// First-order estimate |f(x)| / |grad f(x)| of the distance from x to a quadric (doubles).
double approx_residual_distance(const core::QuadricMatrix& q, const DPoint& x) {
  double f = q(3, 3).to_double_approx(), g2 = 0;
  for (int i = 0; i < 3; ++i) {
    double r = q(i, 3).to_double_approx();
    for (int j = 0; j < 3; ++j)
      r += q(i, j).to_double_approx() * x[static_cast<size_t>(j)];
    f += x[static_cast<size_t>(i)] * (r + q(i, 3).to_double_approx());
    g2 += 4 * r * r;
  }
  return g2 > 0 ? std::abs(f) / std::sqrt(g2) : HUGE_VAL;
}

Json curve_witness_json(const CurveWitness& w) {
  Json o = Json::object();
  o.set("centre", rpoint_json(w.centre));
  o.set("half_width", str(w.half_width.to_string()));
  o.set("fixed_axis", Json::number(w.fixed_axis));
  return o;
}

// Is the certified curve point w (within rho = 2 half_width of its centre) farther than tol
// from every claimed segment? Decided exactly: every segment is farther than tol + rho from
// the centre.
bool witness_far_from_claim(const CurveWitness& w, const Claim& c, const Rational& tol) {
  const Rational reach = tol + Rational(2) * w.half_width, reach2 = reach * reach;
  for (const auto& l : c.polylines)
    for (size_t k = 0; k < l.size(); ++k)
      if (segment_dist2(w.centre, l[k], l[k + 1 < l.size() ? k + 1 : k]) <= reach2) return false;
  return true;
}

// curve: the claimed polylines against the certified intersection curve (README, JSON
// contract). Refuted by a claimed point certified farther than tol from a or b, or by a
// certified point of the curve farther than tol from every claimed segment (a missed branch);
// confirmation would need a proof that the claim covers the whole curve, which the float
// tracer cannot give: otherwise undecided with what was established.
Verdict decide_curve(const Claim& c, Oracle& o) {
  const core::QuadricMatrix& A = *o.qa();
  const core::QuadricMatrix& B = *o.qb();
  const Rational& t = c.abs_tol;
  const double td = t.to_double_approx();
  Verdict v;
  Json facts = Json::object();
  if (c.polylines.empty()) {
    // An empty curve: decided by the certified relation when it is (the surfaces meet or not).
    const RelationFacts& f = o.relation();
    const bool apart = std::all_of(f.possible.begin(), f.possible.end(),
                                   [](const auto& r) { return r == "separated" || r == "nested"; });
    const bool meet = std::none_of(f.possible.begin(), f.possible.end(),
                                   [](const auto& r) { return r == "separated" || r == "nested"; });
    if (apart) return v.verdict = "confirmed", v;
    if (meet) return v.verdict = "refuted", v.counterexample = f.established, v;
  }
  std::vector<std::vector<DPoint>> lines;
  struct Far {
    double est;
    size_t line, index;
  };
  std::vector<Far> far;
  size_t points = 0;
  for (size_t i = 0; i < c.polylines.size(); ++i) {
    lines.emplace_back();
    for (size_t j = 0; j < c.polylines[i].size(); ++j) {
      lines.back().push_back(dpoint(c.polylines[i][j]));
      const double e = std::max(approx_residual_distance(A, lines.back().back()),
                                approx_residual_distance(B, lines.back().back()));
      if (e > 0.5 * td) far.push_back({e, i, j});
      ++points;
    }
  }
  // A claimed point off a surface (the farthest by the float estimate are certified first).
  std::sort(far.begin(), far.end(), [](const Far& x, const Far& y) { return x.est > y.est; });
  for (size_t k = 0; k < far.size() && k < 8; ++k) {
    const RPoint& x = c.polylines[far[k].line][far[k].index];
    for (const auto& [name, s] :
         {std::pair<std::string, const core::Surface*>{"a", &o.a()}, {"b", &o.b()}}) {
      core::check_budget();
      Json scratch = Json::object();
      std::optional<Json> off;
      if (auto near = point_near_surface(*s, x, t, name, scratch, off); near && !*near) {
        off->set("polyline", Json::number(static_cast<long>(far[k].line)));
        off->set("index", Json::number(static_cast<long>(far[k].index)));
        v.verdict = "refuted", v.counterexample = off;
        return v;
      }
    }
  }
  // Claimed points proven within tol of the curve (a certified curve point nearby).
  long proven = 0;
  for (const auto& l : c.polylines)
    for (const RPoint& x : l) {
      core::check_budget();
      const auto w = curve_witness(A, B, dpoint(x));
      if (!w) continue;
      const Rational rho = Rational(2) * w->half_width;
      if (rho <= t && dist2(x, w->centre) <= (t - rho) * (t - rho)) ++proven;
    }
  facts.set("claimed_polylines", Json::number(static_cast<long>(c.polylines.size())));
  facts.set("claimed_points", Json::number(static_cast<long>(points)));
  facts.set("points_proven_near_curve", Json::number(proven));
  // A missed branch: the traced point of each branch farthest from the claim, certified on
  // the curve and proven farther than tol from every claimed segment.
  const QsicResult* top = o.qsic();
  if (top) {
    if (top->morphology) facts.set("morphology", str(top->morphology->id));
    const trace::CurveResult cr = trace::trace_curve(A, B, *top, trace::TraceOptions{});
    facts.set("traced_branches", Json::number(static_cast<long>(cr.branches.size())));
    facts.set("traced_branches_match_topology", Json::boolean(cr.matches_topology));
    long near_branches = 0;
    for (size_t bi = 0; bi < cr.branches.size(); ++bi) {
      core::check_budget();
      const trace::Branch& br = cr.branches[bi];
      std::vector<std::pair<double, size_t>> order;
      for (size_t k = 0; k < br.points.size(); ++k)
        order.emplace_back(approx_dist_to_claim(br.points[k], lines), k);
      std::sort(order.rbegin(), order.rend());
      if (order.empty() || order.front().first <= td) {
        ++near_branches;
        continue;
      }
      // The farthest few (a singular point may defeat the certificate).
      for (size_t k = 0; k < order.size() && k < 4 && order[k].first > td; ++k) {
        const auto w = curve_witness(A, B, br.points[order[k].second]);
        if (!w || !witness_far_from_claim(*w, c, t)) continue;
        Json ce = Json::object();
        ce.set("missed_branch", Json::number(static_cast<long>(bi)));
        ce.set("branch_kind", str(br.kind));
        ce.set("point_on_curve", curve_witness_json(*w));
        ce.set("abs_tol", str(t.to_string()));
        v.verdict = "refuted", v.counterexample = ce;
        return v;
      }
    }
    facts.set("traced_branches_within_tol_approx", Json::number(near_branches)); // float distances
  } else {
    facts.set("morphology", Json::null());
  }
  // Coverage: a subdivision of a box holding the curve (one surface is an ellipsoid) proves
  // every curve point within tol of a claimed segment.
  std::optional<DBox> box = ellipsoid_bounding_box(A);
  if (std::optional<DBox> bb = ellipsoid_bounding_box(B)) {
    if (box)
      for (size_t i = 0; i < 3; ++i)
        (*box)[i] = {std::max((*box)[i][0], (*bb)[i][0]), std::min((*box)[i][1], (*bb)[i][1])};
    else
      box = bb;
  }
  if (box && (*box)[0][0] <= (*box)[0][1] && (*box)[1][0] <= (*box)[1][1] &&
      (*box)[2][0] <= (*box)[2][1]) {
    const Coverage cov = prove_coverage(A, B, c.polylines, t, *box, kMaxCoverageBoxes);
    facts.set("coverage_proven", Json::boolean(cov.proven));
    facts.set("coverage_boxes", Json::number(cov.boxes));
    if (cov.stuck)
      if (const auto w = curve_witness(A, B, *cov.stuck); w && witness_far_from_claim(*w, c, t)) {
        Json ce = Json::object();
        ce.set("point_on_curve", curve_witness_json(*w));
        ce.set("abs_tol", str(t.to_string()));
        v.verdict = "refuted", v.counterexample = ce;
        return v;
      }
  } else if (!box) {
    facts.set("coverage_proven", Json::boolean(false));
  }
  // Every point of every claimed segment within tol of the curve (tried when the vertices
  // are): each piece [s, e] has a certified curve point within tol - |e - s| / 2 of its
  // midpoint, or is halved (at most kMaxSegmentPieces pieces in all). A segment's first
  // unproven midpoint is also tested against the surfaces: farther than tol from a or b
  // refutes the claim.
  long segments = 0, segments_proven = 0, pieces = 0;
  for (size_t li = 0; li < c.polylines.size(); ++li) {
    const auto& l = c.polylines[li];
    for (size_t k = 0; k + 1 < std::max<size_t>(l.size(), 2); ++k) {
      ++segments;
      if (proven != static_cast<long>(points)) continue;
      std::vector<std::pair<RPoint, RPoint>> todo = {{l[k], l[k + 1 < l.size() ? k + 1 : k]}};
      bool ok = true, tested = false;
      while (ok && !todo.empty()) {
        core::check_budget();
        const auto [s0, e0] = todo.back();
        todo.pop_back();
        const RPoint m = {(s0[0] + e0[0]) / Rational(2), (s0[1] + e0[1]) / Rational(2),
                          (s0[2] + e0[2]) / Rational(2)};
        const auto w = curve_witness(A, B, dpoint(m));
        const Rational rho = w ? Rational(2) * w->half_width : Rational(0);
        if (w && rho <= t &&
            sqrt_sum_within(dist2(m, w->centre), dist2(s0, e0) / Rational(4), t - rho))
          continue;
        for (const auto& [name, sf] :
             {std::pair<std::string, const core::Surface*>{"a", &o.a()}, {"b", &o.b()}}) {
          if (tested) break;
          Json scratch = Json::object();
          std::optional<Json> off;
          if (auto near = point_near_surface(*sf, m, t, name, scratch, off); near && !*near) {
            off->set("polyline", Json::number(static_cast<long>(li)));
            off->set("segment", Json::number(static_cast<long>(k)));
            v.verdict = "refuted", v.counterexample = off;
            return v;
          }
        }
        tested = true;
        // Pieces shorter than tol/64 are not cut further: their midpoint is then not proven.
        if (++pieces > kMaxSegmentPieces || Rational(4096) * dist2(s0, e0) < t * t) ok = false;
        todo.push_back({s0, m});
        todo.push_back({m, e0});
      }
      if (ok) ++segments_proven;
    }
  }
  facts.set("claimed_segments", Json::number(segments));
  facts.set("segments_proven_near_curve", Json::number(segments_proven));
  if (facts.find("coverage_proven") && facts.find("coverage_proven")->as_bool() &&
      proven == static_cast<long>(points) && segments_proven == segments) {
    v.verdict = "confirmed";
    return v;
  }
  v.established = facts;
  v.note = facts.find("coverage_boxes")
               ? "coverage of the curve by the claim, or every claimed point, is not proven"
               : "coverage of the whole curve is only proven when a or b is an ellipsoid";
  return v;
}

} // namespace

namespace {

// Every claim of `query` ("claims" at `path`), read and validated.
std::vector<Claim> read_claims(const core::Surface& a, const core::Surface& b, const Json& query,
                               const std::string& source, const std::string& path) {
  const std::string cpath = json_path_child(path, "claims");
  const Json* claims = query.find("claims");
  if (!claims)
    throw InputError(core::io::json_location(query, source, cpath), "an array of claims", "none");
  if (!claims->is_array() || claims->size() == 0)
    throw InputError(core::io::json_location(*claims, source, cpath), "a non-empty array of claims",
                     claims->is_array() ? "[]" : core::io::type_name(claims->type()));
  const bool two_quadrics = std::holds_alternative<core::QuadricMatrix>(a) &&
                            std::holds_alternative<core::QuadricMatrix>(b);
  std::vector<Claim> parsed;
  for (size_t i = 0; i < claims->size(); ++i)
    parsed.push_back(
        read_claim(claims->items()[i], source, json_path_index(cpath, i), two_quadrics));
  return parsed;
}

} // namespace

void check_claims(const core::Surface& a, const core::Surface& b, const Json& query,
                  const std::string& source, const std::string& path) {
  read_claims(a, b, query, source, path);
}

Json verify_claims(const core::Surface& a, const core::Surface& b, const Json& line,
                   const std::string& source, Mode mode, const std::string& path) {
  // Every claim is read before anything is computed.
  const std::vector<Claim> parsed = read_claims(a, b, line, source, path);
  Oracle oracle(a, b, mode);
  Json verdicts = Json::array();
  bool all_decided = true, budget_out = false;
  for (const Claim& c : parsed) {
    Verdict v;
    try {
      if (c.kind == "relation")
        v = decide_relation(c, oracle);
      else if (c.kind == "solids_collide")
        v = decide_collide(c, oracle);
      else if (c.kind == "distance")
        v = decide_distance(c, oracle);
      else if (c.kind == "closest_points")
        v = decide_closest_points(c, oracle);
      else if (c.kind == "curve")
        v = decide_curve(c, oracle);
      else
        v = decide_classification(c, oracle);
    } catch (const core::BudgetExceeded&) {
      v = Verdict{};
      v.note = kBudgetNote;
      v.out_of_time = true;
    }
    // A verdict left undecided after the budget ran out says so (a distance computed past it
    // returns what it had, without throwing).
    if (v.verdict == "undecided" && v.note.empty() && core::budget_exhausted()) {
      v.note = kBudgetNote;
      v.out_of_time = true;
    }
    all_decided = all_decided && v.verdict != "undecided";
    budget_out = budget_out || v.out_of_time;
    Json j = Json::object();
    j.set("kind", str(c.kind));
    j.set("verdict", str(v.verdict));
    if (v.counterexample) j.set("counterexample", *v.counterexample);
    if (v.established && v.verdict == "undecided") j.set("established", *v.established);
    if (!v.note.empty()) j.set("note", str(v.note));
    verdicts.push_back(j);
  }
  Json result = Json::object();
  result.set("verdicts", verdicts);
  Json out = Json::object();
  out.set("status", str(all_decided ? "certified" : "undecided"));
  if (budget_out) out.set("reason", str("budget")); // as the other ops past their budget
  out.set("result", result);
  return out;
}

} // namespace surfcert::app
