#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/distance/ball.hpp"

#include "surfcert/certify/distance/route.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace surfcert::certify {

using core::io::Json;

const char* to_string(Ties t) {
  switch (t) {
  case Ties::Proven:
    return "proven";
  case Ties::Unproven:
    return "unproven";
  default:
    return "";
  }
}

const char* const kUnprovenTiesNote =
    "several minimizing pairs at distances that agree to the requested precision: "
    "listed as minimizers (their equality is not proven)";

void note_unproven_ties(DistanceResult& out, size_t count) {
  if (count < 2) return;
  out.note += std::string(out.note.empty() ? "" : "; ") + kUnprovenTiesNote;
  out.ties = Ties::Unproven;
}

void set_distance_enclosure(DistanceResult& out, const arb_t d, long digits) {
  out.distance = Enclosure::from_ball(d, digits);
}

namespace {

// A double as printf's "%.17g" writes it (std::to_chars with a precision is specified to give
// the same text, without printf's format parsing and locale machinery).
std::string g17(double x) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 17);
  return std::string(buf, r.ptr);
}

// What every answer goes through last, whatever route produced it:
// - a minimizer count that is not proven (several candidates whose equality is unproven, or
//   a route that says its count is not proven) becomes "undecided", the candidate count kept
//   apart in minimizer_candidates: a count is reported only when proven;
// - the width contract: a certified enclosure satisfies upper - lower <= 10^-digits lower on
//   the printed decimals, or the answer is not certified.
void finalize(DistanceResult& r, long digits) {
  if (r.status == Status::Certified && r.minimizers.is_count()) {
    const long n = r.minimizers.value();
    if ((n > 1 && r.ties == Ties::Unproven) || r.count_unproven) {
      r.minimizers = Minimizers::undecided(n);
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
// A tiny distance computed as a difference of O(1) quantities loses digits to cancellation:
// up to three retries, each doubling the working digits (capped at 1000).
template <class F> DistanceResult with_width_contract(F&& compute, long digits) {
  DistanceResult r = compute(digits);
  auto short_of_width = [digits](const DistanceResult& x) {
    if (x.status == Status::Certified)
      return x.distance && !x.distance->is_zero() && !x.distance->meets_width(digits);
    return x.status == Status::Undecided && x.width_short;
  };
  long working = digits;
  for (int retry = 0; retry < 3 && short_of_width(r) && working < 1000; ++retry) {
    working = std::min(2 * working + 10, 1000L);
    DistanceResult finer = compute(working);
    if (finer.status == Status::Undecided && finer.width_short && finer.distance &&
        finer.distance->meets_width(digits)) {
      // Everything but the width was proven at `working` digits, and the enclosure (which
      // holds) meets the width asked for: certified at the requested digits.
      finer.status = Status::Certified;
      finer.width_short = false;
      finer.note = "certified to " + std::to_string(digits) + " digits with " +
                   std::to_string(working) + " working digits (cancellation in a small distance)";
    }
    if (finer.status == Status::Certified && finer.distance &&
        (finer.distance->is_zero() || finer.distance->meets_width(digits))) {
      r = std::move(finer);
      break;
    }
    if (finer.status != Status::Certified && !finer.width_short) { // another reason
      r.budget_exhausted = r.budget_exhausted || finer.budget_exhausted;
      break;
    }
  }
  finalize(r, digits);
  return r;
}

} // namespace

DistanceResult surface_distance(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                long digits, bool solid, Mode mode) {
  return surface_distance(core::Surface(a), core::Surface(b), digits, solid, mode);
}

DistanceResult surface_distance(const core::Surface& a, const core::Surface& b, long digits,
                                bool solid, Mode mode) {
  return with_width_contract([&](long dg) { return run_distance_routes(a, b, dg, solid, mode); },
                             digits);
}

Json distance_envelope_json(const DistanceResult& r, long digits, Detail detail) {
  Json o = Json::object();
  o.set("status", Json::string(to_string(r.status)));
  if (r.budget_exhausted) o.set("reason", Json::string("budget"));
  if (!r.note.empty()) o.set("note", Json::string(r.note));
  // A lean answer says so (Full, the default, adds nothing: the contract's bytes).
  const bool full = detail == Detail::Full;
  if (!full) o.set("detail", Json::string(to_string(Detail::Value)));
  Json res = Json::object();
  if (r.distance) { // a proven enclosure (certified, or what an undecided answer established)
    Json d = Json::object();
    d.set("lower", Json::string(r.distance->lower()));
    d.set("upper", Json::string(r.distance->upper()));
    d.set("approx", Json::string(g17(r.distance->approx())));
    res.set("distance", std::move(d));
  }
  if (r.estimate) { // a float answer: never in "distance"
    Json e = Json::object();
    e.set("value", Json::string(g17(r.estimate->value)));
    e.set("certified", Json::boolean(false));
    res.set("estimate", std::move(e));
  }
  if (!r.minimizers.empty()) {
    res.set("minimizers", Json::string(r.minimizers.str()));
    res.set("minimizers_proof", Json::string(r.minimizers.proof_str()));
  }
  if (r.minimizer_candidates() > 0)
    res.set("minimizer_candidates", Json::number(r.minimizer_candidates()));
  Json pairs = Json::array();
  for (const auto& pr : r.pairs) {
    // Display points: one that is not finite (an overflowing double) is left out, never
    // written as "nan" (not JSON) or allowed to fail the answer.
    bool finite = true;
    for (const auto& p : pr)
      for (double x : p)
        finite = finite && std::isfinite(x);
    if (!finite) continue;
    Json pj = Json::array();
    for (const auto& p : pr) {
      Json a3 = Json::array();
      for (double x : p)
        a3.push_back(Json::number_text(g17(x)));
      pj.push_back(std::move(a3));
    }
    pairs.push_back(std::move(pj));
  }
  res.set("pairs", std::move(pairs));
  res.set("pair_points_approximate", Json::boolean(true));
  if (full) { // the certificate data: how many critical points, the eliminated system's degrees
    res.set("critical_candidates", Json::number(r.critical_candidates));
    res.set("eliminated_degree", Json::number(r.eliminated_degree));
  }
  if (full && !r.system_degrees.empty()) {
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
    res.set("degrees", std::move(deg));
  }
  res.set("digits", Json::number(digits));
  res.set("solid", Json::boolean(r.solid));
  res.set("mode", Json::string(to_string(r.mode)));
  if (r.method != Method::None) res.set("method", Json::string(to_string(r.method)));
  if (r.reduced_by != Method::None) res.set("reduced_by", Json::string(to_string(r.reduced_by)));
  if (r.ties != Ties::None) res.set("ties", Json::string(to_string(r.ties)));
  o.set("result", std::move(res));
  return o;
}

} // namespace surfcert::certify
