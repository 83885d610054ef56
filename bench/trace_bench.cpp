// trace_bench: the tracer benchmark side by side with Open CASCADE, in one run.
//
// For N random ellipsoid pairs (random_ellipsoids.hpp, fixed seed): our side is the certified
// topology (classify_qsic, filtered mode) followed by the tracer (run_our_tracer, tolerance
// tol), timed together per pair; the peer is GeomAPI_IntSS on the same ellipsoids as rational
// B-spline surfaces (occt_peer.hpp), run on every k-th pair only because it costs tens of ms
// per pair. Reports mean/median times, the OCCT/ours time ratio (also per pair), and how often
// the branch counts of OCCT and of our tracer differ from the certified count.
// Built only with OCCT (CMake option SURFCERT_BENCH_OCCT); compiles without it (our side only).
// Usage: trace_bench [pairs=100000] [occt_every=ceil(pairs/5000)] [seed=2026] [tol=2e-4]
#include "our_tracer.hpp"
#include "random_ellipsoids.hpp"
#include "surfcert/certify/qsic.hpp"
#ifdef SURFCERT_HAVE_OCCT
#include "occt_peer.hpp"
#endif

#include <flint/flint.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace surfcert;

namespace {

// OCCT pairs in a default run: 5,000 x ~45 ms (measured mean, OCCT 7.6.3, this 2-core
// machine) is ~4 minutes, keeping a 100,000-pair run under ~10 minutes with room for our
// tracer's own pass (default k = 20 for 100,000 pairs).
constexpr long kDefaultOcctPairs = 5000;

/// Curve branches of the certified morphology: quartic loops (a figure-eight or a cuspidal
/// loop is one), conics (a double conic is one), lines and cubics; isolated points are not
/// branches (see certified_isolated_points). -1 when there is no morphology (degenerate pencil).
int certified_branches(const certify::QsicResult& r) {
  if (!r.morphology) return -1;
  const auto& m = *r.morphology;
  return m.loops + m.conics + m.lines + m.cubics;
}

int certified_isolated_points(const certify::QsicResult& r) {
  return r.morphology ? r.morphology->isolated_points : 0;
}

struct Stats {
  double mean = 0, median = 0;
  size_t n = 0;
};

Stats summarize(std::vector<double> t) {
  Stats s;
  s.n = t.size();
  if (t.empty()) return s;
  double sum = 0;
  for (double x : t)
    sum += x;
  s.mean = sum / static_cast<double>(t.size());
  std::nth_element(t.begin(), t.begin() + static_cast<long>(t.size() / 2), t.end());
  s.median = t[t.size() / 2];
  return s;
}

struct PairRecord {
  int tu_case = 0;
  int certified = -1;    ///< certified curve branches
  int isolated = 0;      ///< certified isolated points
  double our_us = 0;     ///< topology + tracer
  int our_branches = -1; ///< -1: tracer not available
  bool occt_run = false;
  bool occt_ok = false;
  int occt_branches = 0;
  int occt_closed = 0;
  int occt_glued = 0;
  double occt_us = 0;
};

struct Disagreement {
  long compared = 0, equal = 0, fewer = 0, more = 0, failed = 0;
};

void progress(const char* what, long i, long n) {
  if (n >= 10 && (i + 1) % (n / 10) == 0) std::fprintf(stderr, " %ld%%", (i + 1) * 100 / n);
  if (i + 1 == n) std::fprintf(stderr, " done (%s)\n", what);
}

} // namespace

int main(int argc, char** argv) {
  long pairs = argc > 1 ? std::atol(argv[1]) : 100000;
  if (pairs < 1) pairs = 1;
  long every = argc > 2 ? std::atol(argv[2]) : (pairs + kDefaultOcctPairs - 1) / kDefaultOcctPairs;
  if (every < 1) every = 1;
  unsigned long seed = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 2026;
  double tol = argc > 4 ? std::atof(argv[4]) : 2e-4;

  std::mt19937_64 rng(seed);
  std::vector<std::pair<bench::RandomEllipsoid, bench::RandomEllipsoid>> input;
  input.reserve(static_cast<size_t>(pairs));
  for (long i = 0; i < pairs; ++i) {
    auto a = bench::random_ellipsoid(rng);
    auto b = bench::random_ellipsoid(rng);
    input.emplace_back(std::move(a), std::move(b));
  }
  std::vector<PairRecord> rec(static_cast<size_t>(pairs));
  std::fprintf(stderr, "trace_bench: %ld random ellipsoid pairs (seed %lu), tolerance %g\n", pairs,
               seed, tol);

  // Pass 1: our side on every pair (a pass of its own so OCCT does not evict its caches).
  std::fprintf(stderr, "surfcert (topology + curves):");
  bool tracer_available = false;
  long topology_fallbacks = 0, start_fallbacks = 0;
  for (long i = 0; i < pairs; ++i) {
    const auto& [ea, eb] = input[static_cast<size_t>(i)];
    PairRecord& r = rec[static_cast<size_t>(i)];
    auto t0 = std::chrono::steady_clock::now();
    auto q = certify::classify_qsic(ea.quadric, eb.quadric, certify::Mode::Filtered);
    bool exact_starts = false;
    int ours = bench::run_our_tracer(ea.quadric, eb.quadric, q, tol, &exact_starts);
    topology_fallbacks += q.exact_fallback;
    start_fallbacks += exact_starts;
    auto t1 = std::chrono::steady_clock::now();
    r.our_us = std::chrono::duration<double, std::micro>(t1 - t0).count();
    r.tu_case = q.tu_case;
    r.certified = q.status == certify::Status::Certified ? certified_branches(q) : -1;
    r.isolated = certified_isolated_points(q);
    r.our_branches = ours;
    if (ours >= 0) tracer_available = true;
    progress("surfcert", i, pairs);
  }

  // Pass 2: OCCT on every k-th pair.
  bool have_occt = false;
  std::string occt_name = "Open CASCADE (not built)";
  long occt_exceptions = 0;
#ifdef SURFCERT_HAVE_OCCT
  have_occt = true;
  occt_name = bench::occt_version();
  long occt_n = (pairs + every - 1) / every;
  std::fprintf(stderr, "%s GeomAPI_IntSS on every %ld-th pair (%ld pairs):", occt_name.c_str(),
               every, occt_n);
  for (long j = 0; j < occt_n; ++j) {
    size_t i = static_cast<size_t>(j * every);
    auto o = bench::occt_intersect(input[i].first.params, input[i].second.params, tol);
    PairRecord& r = rec[i];
    r.occt_run = true;
    r.occt_ok = o.ok;
    r.occt_branches = o.branches;
    r.occt_closed = o.closed_branches;
    r.occt_glued = o.glued_branches;
    r.occt_us = o.seconds * 1e6;
    if (!o.error.empty() && occt_exceptions++ < 5)
      std::fprintf(stderr, "\n  pair %zu: OCCT threw %s\n", i, o.error.c_str());
    progress("OCCT", j, occt_n);
  }
#endif

  // Figures.
  std::vector<double> ours_all, ours_sub, occt_all, ratio;
  Disagreement occ, glued, our;
  long uncertified = 0;
  std::map<int, std::map<int, long>> occt_by_certified; // certified -> OCCT count (-1 failed)
  std::map<int, long> open_lines_by_certified;
  for (const auto& r : rec) {
    ours_all.push_back(r.our_us);
    if (r.certified < 0) {
      ++uncertified;
      continue;
    }
    if (r.our_branches >= 0) {
      ++our.compared;
      if (r.our_branches == r.certified)
        ++our.equal;
      else if (r.our_branches < r.certified)
        ++our.fewer;
      else
        ++our.more;
    }
    if (!r.occt_run) continue;
    ++occ.compared;
    ours_sub.push_back(r.our_us);
    if (!r.occt_ok) {
      ++occ.failed;
      ++glued.compared;
      ++glued.failed;
      occt_by_certified[r.certified][-1]++;
      continue;
    }
    occt_all.push_back(r.occt_us);
    if (r.our_us > 0) ratio.push_back(r.occt_us / r.our_us);
    occt_by_certified[r.certified][r.occt_branches]++;
    open_lines_by_certified[r.certified] += r.occt_branches - r.occt_closed;
    if (r.occt_branches == r.certified)
      ++occ.equal;
    else if (r.occt_branches < r.certified)
      ++occ.fewer;
    else
      ++occ.more;
    ++glued.compared;
    if (r.occt_glued == r.certified)
      ++glued.equal;
    else if (r.occt_glued < r.certified)
      ++glued.fewer;
    else
      ++glued.more;
  }
  Stats so = summarize(ours_all), ss = summarize(ours_sub), sc = summarize(occt_all),
        sr = summarize(ratio);

  std::printf("## Tracer benchmark: surfcert vs %s (trace_bench %ld %ld %lu %g)\n\n",
              occt_name.c_str(), pairs, every, seed, tol);
  std::printf("Random ellipsoid pairs: %ld (centres in [-1/2,1/2]^3, semi-axes in [1/10,1], "
              "rational rotations), tolerance %g.\n",
              pairs, tol);
  if (have_occt)
    std::printf("OCCT (GeomAPI_IntSS on the ellipsoids as rational B-spline surfaces) ran on every "
                "%ld-th pair: %ld pairs.\n",
                every, occ.compared);
  else
    std::printf("OCCT: not built (SURFCERT_BENCH_OCCT off); surfcert side only.\n");
  if (!tracer_available)
    std::printf("surfcert tracer: not yet available in this build (run_our_tracer returns -1); "
                "surfcert times below are the certified topology only.\n");
  std::printf("\n| side | pairs | mean us/pair | median us/pair |\n|---|---|---|---|\n");
  std::printf("| surfcert topology (filtered) + curves, all pairs | %zu | %.2f | %.2f |\n", so.n,
              so.mean, so.median);
  if (have_occt) {
    std::printf("| surfcert, the OCCT pairs | %zu | %.2f | %.2f |\n", ss.n, ss.mean, ss.median);
    std::printf("| OCCT GeomAPI_IntSS (successful runs) | %zu | %.2f | %.2f |\n\n", sc.n, sc.mean,
                sc.median);
    std::printf("Time ratio OCCT / surfcert on the same pairs: mean %.1f, median %.1f "
                "(per-pair ratio: median %.1f over %zu pairs).\n\n",
                ss.mean > 0 ? sc.mean / ss.mean : 0.0, ss.median > 0 ? sc.median / ss.median : 0.0,
                sr.median, sr.n);
  } else {
    std::printf("\n");
  }
  std::printf("Branch counts against the certified count (loops + conics + lines + cubics; "
              "isolated points apart):\n\n");
  std::printf(
      "| solver | pairs compared | equal | fewer | more | failed |\n|---|---|---|---|---|---|\n");
  if (have_occt) {
    std::printf("| OCCT (NbLines) | %ld | %ld | %ld | %ld | %ld |\n", occ.compared, occ.equal,
                occ.fewer, occ.more, occ.failed);
    std::printf("| OCCT, lines with coincident ends joined (diagnostic) | %ld | %ld | %ld | %ld | "
                "%ld |\n",
                glued.compared, glued.equal, glued.fewer, glued.more, glued.failed);
  }
  if (tracer_available)
    std::printf("| surfcert tracer | %ld | %ld | %ld | %ld | 0 |\n", our.compared, our.equal,
                our.fewer, our.more);
  else
    std::printf("| surfcert tracer | n/a (not yet available) | | | | |\n");
  if (uncertified)
    std::printf("\n%ld pairs had no certified morphology (excluded).\n", uncertified);
  if (have_occt) {
    std::printf("\nOCCT branch counts by certified count (\"failed\": IsDone() false or an "
                "exception, %ld exceptions):\n\n",
                occt_exceptions);
    for (const auto& [c, h] : occt_by_certified) {
      std::printf("- certified %d:", c);
      for (const auto& [k, v] : h)
        if (k < 0)
          std::printf(" failed: %ld;", v);
        else
          std::printf(" %d: %ld;", k, v);
      std::printf(" (open OCCT lines: %ld)\n", open_lines_by_certified[c]);
    }
  }
  if (have_occt) {
    int shown = 0;
    for (size_t i = 0; i < rec.size(); ++i) {
      const auto& r = rec[i];
      if (!r.occt_run || r.certified < 0 || (r.occt_ok && r.occt_glued == r.certified)) continue;
      if (shown++ == 0)
        std::printf("\nPairs where OCCT differs even with coincident ends joined (first 10; pair "
                    "index i = the i-th pair drawn from the seed):\n\n");
      if (shown <= 10)
        std::printf("- pair %zu: Tu case %d, certified %d, OCCT %s %d lines (%d closed, %d after "
                    "joining)\n",
                    i, r.tu_case, r.certified, r.occt_ok ? "" : "FAILED", r.occt_branches,
                    r.occt_closed, r.occt_glued);
    }
  }
  long iso = 0;
  for (const auto& r : rec)
    iso += r.isolated;
  std::printf("\nCertified isolated points over all pairs: %ld.\n", iso);
  std::printf("Exact fallbacks on our side: topology (interval filter undecided) %ld pairs; exact "
              "extreme points (float start points missed a branch) %ld pairs.\n",
              topology_fallbacks, start_fallbacks);
  flint_cleanup();
  return 0;
}
