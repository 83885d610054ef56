#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/distance/ball.hpp"

#include "surfcert/certify/distance/route.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>
#include <utility>
#include <vector>

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
//   the printed decimals, or the answer is not certified;
// - an answer that is not certified states no proven count: its minimum is not proven, so
//   neither is the number of pairs that realise it (an undecided enclosure of an infimum that
//   may lie at infinity, a float search's single pair); the candidates are kept, and one
//   without any count says "undecided" too.
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
  if (r.status != Status::Certified && r.minimizers.is_count())
    r.minimizers = Minimizers::undecided(r.minimizers.value());
  else if (r.status == Status::Uncertified && !r.minimizers.empty() &&
           !r.minimizers.is_undecided()) // a float route proves nothing, not even a continuum
    r.minimizers = Minimizers::undecided(0);
  // An answer that is not certified and says nothing of its minimizers (a budget stop before
  // any route answered, a route that declined without a count) says "undecided" as every
  // other one does: "minimizers" is in every answer that is not certified.
  if ((r.status == Status::Undecided || r.status == Status::Uncertified) && r.minimizers.empty())
    r.minimizers = Minimizers::undecided(0);
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

void append_distance_envelope(std::string& out, const DistanceResult& r, long digits,
                              Detail detail) {
  using core::io::append_json_string;
  // Members in the order distance_envelope_json has always set them.
  auto key = [&out](const char* k) {
    out += '"';
    out += k; // plain ASCII keys: nothing to escape
    out += "\":";
  };
  auto str = [&out](std::string_view v) { append_json_string(out, v); };
  auto boolean = [&out](bool b) { out += b ? "true" : "false"; };
  out += '{';
  key("status");
  str(to_string(r.status));
  if (r.budget_exhausted || r.no_real_point) {
    out += ',';
    key("reason");
    str(r.budget_exhausted ? "budget" : "no_real_point");
  }
  if (!r.note.empty()) {
    out += ',';
    key("note");
    str(r.note);
  }
  // A lean answer says so (Full, the default, adds nothing: the contract's bytes).
  const bool full = detail == Detail::Full;
  if (!full) {
    out += ',';
    key("detail");
    str(to_string(Detail::Value));
  }
  out += ',';
  key("result");
  out += '{';
  if (r.distance) { // a proven enclosure (certified, or what an undecided answer established)
    key("distance");
    out += '{';
    key("lower");
    str(r.distance->lower());
    out += ',';
    key("upper");
    str(r.distance->upper());
    out += ',';
    key("approx");
    str(r.distance->approx_text());
    out += "},";
  }
  if (r.estimate) { // a float answer: never in "distance"
    key("estimate");
    out += '{';
    key("value");
    str(g17(r.estimate->value));
    out += ',';
    key("certified");
    boolean(false);
    out += "},";
  }
  if (!r.minimizers.empty()) {
    key("minimizers");
    str(r.minimizers.str());
    out += ',';
    key("minimizers_proof");
    str(r.minimizers.proof_str());
    out += ',';
  }
  if (r.minimizer_candidates() > 0) {
    key("minimizer_candidates");
    out += std::to_string(r.minimizer_candidates());
    out += ',';
  }
  key("pairs");
  out += '[';
  bool first_pair = true;
  for (const auto& pr : r.pairs) {
    // Display points: one that is not finite (an overflowing double) is left out, never
    // written as "nan" (not JSON) or allowed to fail the answer.
    bool finite = true;
    for (const auto& p : pr)
      for (double x : p)
        finite = finite && std::isfinite(x);
    if (!finite) continue;
    out += first_pair ? "[" : ",[";
    first_pair = false;
    for (size_t i = 0; i < pr.size(); ++i) {
      out += i ? ",[" : "[";
      for (size_t j = 0; j < pr[i].size(); ++j) {
        if (j) out += ',';
        out += g17(pr[i][j]); // finite: a JSON number
      }
      out += ']';
    }
    out += ']';
  }
  out += "],";
  key("pair_points_approximate");
  boolean(true);
  if (full) { // the certificate data: how many critical points, the eliminated system's degrees
    out += ',';
    key("critical_candidates");
    out += std::to_string(r.critical_candidates);
    out += ',';
    key("eliminated_degree");
    out += std::to_string(r.eliminated_degree);
  }
  if (full && !r.system_degrees.empty()) {
    auto arr = [&out](const std::vector<long>& v) {
      out += '[';
      for (size_t i = 0; i < v.size(); ++i) {
        if (i) out += ',';
        out += std::to_string(v[i]);
      }
      out += ']';
    };
    const std::pair<const char*, const std::vector<long>*> degrees[] = {
        {"system", &r.system_degrees},
        {"bivariate", &r.bivariate_degrees},
        {"univariate", &r.univariate_degrees},
        {"squarefree", &r.squarefree_degrees}};
    out += ',';
    key("degrees");
    out += '{';
    for (size_t k = 0; k < std::size(degrees); ++k) {
      if (k) out += ',';
      key(degrees[k].first);
      arr(*degrees[k].second);
    }
    out += '}';
  }
  out += ',';
  key("digits");
  out += std::to_string(digits);
  out += ',';
  key("solid");
  boolean(r.solid);
  out += ',';
  key("mode");
  str(to_string(r.mode));
  if (r.method != Method::None) {
    out += ',';
    key("method");
    str(to_string(r.method));
  }
  if (r.reduced_by != Method::None) {
    out += ',';
    key("reduced_by");
    str(to_string(r.reduced_by));
  }
  if (r.ties != Ties::None) {
    out += ',';
    key("ties");
    str(to_string(r.ties));
  }
  out += "}}";
}

Json distance_envelope_json(const DistanceResult& r, long digits, Detail detail) {
  // One writer of the envelope: its text, read back (the document and the batch's direct text
  // are the same bytes by construction).
  std::string text;
  append_distance_envelope(text, r, digits, detail);
  return core::io::parse_json(text, "distance envelope");
}

} // namespace surfcert::certify
