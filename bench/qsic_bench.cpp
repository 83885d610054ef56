// qsic_bench: time per classification in each mode (exact / filtered / float) on random
// ellipsoid pairs (seed 002 §5.1.3 recipe), the filtered mode's fallbacks, and how many
// answers each mode gets right on a degenerate set (fixtures, their congruences, tangent
// configurations perturbed by 2^-40 and 2^-100). The exact mode is the reference: it is
// certified, and the test suite checks it against independent routes.
// Usage: qsic_bench [pairs=100000] [seed=2026]
#include "random_ellipsoids.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <flint/flint.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

using namespace surfcert;
using certify::Mode;
using core::Mat4;
using core::QuadricMatrix;
using core::Rational;

namespace {

struct Stats {
  double median_us = 0, mean_us = 0;
};

Stats summarize(std::vector<double>& t) {
  Stats s;
  if (t.empty()) return s;
  double sum = 0;
  for (double x : t)
    sum += x;
  s.mean_us = sum / static_cast<double>(t.size());
  std::nth_element(t.begin(), t.begin() + static_cast<long>(t.size() / 2), t.end());
  s.median_us = t[t.size() / 2];
  return s;
}

double time_us(const std::chrono::steady_clock::time_point& a,
               const std::chrono::steady_clock::time_point& b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

core::io::Json load(const std::string& rel) {
  std::ifstream in(std::string(SURFCERT_DATA_DIR) + "/" + rel);
  std::stringstream ss;
  ss << in.rdbuf();
  return core::io::parse_json(ss.str(), rel);
}

Mat4 mat(const core::io::Json& m) {
  Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      r[i][j] = *Rational::from_string(m.items()[i].items()[j].text());
  return r;
}

} // namespace

int main(int argc, char** argv) {
  long pairs = argc > 1 ? std::atol(argv[1]) : 100000;
  unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2026;
  // Optional third argument: only time this mode (for profiling), e.g. "filtered".
  std::string only = argc > 3 ? argv[3] : "";
  std::mt19937_64 rng(seed);
  std::vector<std::pair<QuadricMatrix, QuadricMatrix>> input;
  input.reserve(static_cast<size_t>(pairs));
  for (long i = 0; i < pairs; ++i) {
    auto a = bench::random_ellipsoid(rng).quadric;
    auto b = bench::random_ellipsoid(rng).quadric;
    input.emplace_back(a, b);
  }
  const Mode modes[3] = {Mode::Float, Mode::Filtered, Mode::Exact};
  std::vector<double> times[3];
  std::vector<int> answers[3];
  long fallbacks = 0;
  std::fprintf(stderr, "random ellipsoid pairs: %ld (seed %lu)\n", pairs, seed);
  // One pass per mode over the same pairs (a user runs one mode; interleaving the exact mode
  // would evict the fast modes' working set from the caches).
  for (int m = 0; m < 3; ++m) {
    if (!only.empty() && only != certify::to_string(modes[m])) continue;
    std::fprintf(stderr, "mode %s:", certify::to_string(modes[m]));
    for (long i = 0; i < pairs; ++i) {
      const auto& pr = input[static_cast<size_t>(i)];
      auto t0 = std::chrono::steady_clock::now();
      auto r = certify::classify_qsic(pr.first, pr.second, modes[m]);
      auto t1 = std::chrono::steady_clock::now();
      times[m].push_back(time_us(t0, t1));
      answers[m].push_back(r.tu_case);
      if (modes[m] == Mode::Filtered && r.exact_fallback) ++fallbacks;
      if (pairs >= 10 && (i + 1) % (pairs / 10) == 0)
        std::fprintf(stderr, " %ld%%", (i + 1) * 100 / pairs);
    }
    std::fprintf(stderr, "\n");
  }
  // Report data (exact D2..E, special points, relation) for the filtered results, timed apart.
  std::vector<double> report_times;
  for (long i = 0; i < std::min(pairs, 20000L) && only.empty(); ++i) {
    const auto& pr = input[static_cast<size_t>(i)];
    auto r = certify::classify_qsic(pr.first, pr.second, Mode::Filtered);
    auto t0 = std::chrono::steady_clock::now();
    certify::complete_report_data(r, pr.first, pr.second);
    auto t1 = std::chrono::steady_clock::now();
    report_times.push_back(time_us(t0, t1));
  }
  if (!only.empty()) {
    std::vector<double>& t = times[only == "float" ? 0 : only == "filtered" ? 1 : 2];
    Stats x = summarize(t);
    std::printf("%s: median %.2f us, mean %.2f us\n", only.c_str(), x.median_us, x.mean_us);
    return 0;
  }
  long wrong[3] = {0, 0, 0};
  std::vector<long> hist(36, 0);
  for (size_t i = 0; i < answers[2].size(); ++i) {
    hist[static_cast<size_t>(answers[2][i])]++;
    for (int m = 0; m < 2; ++m)
      wrong[m] += answers[m][i] != answers[2][i];
  }
  Stats st[3];
  for (int m = 0; m < 3; ++m)
    st[m] = summarize(times[m]);

  // Degenerate set: fixtures, random integer congruences of them, perturbed tangencies.
  std::vector<std::pair<QuadricMatrix, QuadricMatrix>> degen;
  for (const char* f : {"fixtures/ellipsoid_fixtures.json", "fixtures/canonical_examples.json"}) {
    auto doc = load(f);
    bool ell = std::string(f).find("ellipsoid") != std::string::npos;
    for (const auto& [k, e] : doc.members())
      degen.emplace_back(QuadricMatrix(mat(*e.find(ell ? "E1" : "A"))),
                         QuadricMatrix(mat(*e.find(ell ? "E2" : "B"))));
  }
  size_t base = degen.size();
  std::uniform_int_distribution<long> pe(-2, 2);
  for (size_t i = 0; i < base; ++i) {
    Mat4 p;
    do {
      for (auto& row : p)
        for (auto& v : row)
          v = Rational(pe(rng));
    } while (core::det(p).is_zero());
    degen.emplace_back(degen[i].first.congruent(p), degen[i].second.congruent(p));
  }
  const char* tangent[][2] = {
      {"x^2+y^2+z^2-1", "(x-2-e)^2+y^2+z^2-1"},     {"x^2+y^2+z^2-1", "x^2/4+y^2/(1+e)^2+z^2-1"},
      {"x^2+y^2+z^2-9", "(x-2-e)^2+y^2+z^2-1"},     {"x^2+y^2+z^2-1", "x^2+y^2-(1+e)^2"},
      {"x^2/4+y^2+z^2-1", "(x-3-e)^2+y^2+z^2/4-1"}, {"x^2+y^2+(z-1)^2-1", "x^2+y^2+2z^2+2z-e"}};
  for (const auto& t : tangent)
    for (const char* e :
         {"0", "1/1099511627776", "-1/1099511627776", "1/1267650600228229401496703205376",
          "-1/1267650600228229401496703205376"}) {
      std::string b = t[1];
      std::string eps = std::string("(") + e + ")";
      for (size_t pos; (pos = b.find('e')) != std::string::npos;)
        b.replace(pos, 1, eps);
      degen.emplace_back(core::io::quadric_from_equation(t[0], {"bench", 1, 1, ""}),
                         core::io::quadric_from_equation(b, {"bench", 1, 1, ""}));
    }
  long right[3] = {0, 0, 0};
  long degen_fallbacks = 0;
  for (const auto& [a, b] : degen) {
    int truth = certify::classify_qsic(a, b, Mode::Exact).tu_case;
    for (int m = 0; m < 3; ++m) {
      auto r = certify::classify_qsic(a, b, modes[m]);
      right[m] += r.tu_case == truth;
      if (modes[m] == Mode::Filtered && r.exact_fallback) ++degen_fallbacks;
    }
  }

  std::printf("## QSIC classification benchmark (qsic_bench %ld %lu)\n\n", pairs, seed);
  std::printf("Random ellipsoid pairs: %ld (centres in [-1/2,1/2]^3, semi-axes in [1/10,1], "
              "rational rotations).\n\n",
              pairs);
  std::printf("| mode | median us/pair | mean us/pair | answers differing from exact | exact "
              "fallbacks |\n|---|---|---|---|---|\n");
  std::printf("| float (uncertified) | %.2f | %.2f | %ld | - |\n", st[0].median_us, st[0].mean_us,
              wrong[0]);
  std::printf("| filtered (certified) | %.2f | %.2f | %ld | %ld |\n", st[1].median_us,
              st[1].mean_us, wrong[1], fallbacks);
  std::printf("| exact (certified) | %.2f | %.2f | (reference) | - |\n\n", st[2].median_us,
              st[2].mean_us);
  std::printf("filtered / float median ratio: %.2f\n\n", st[1].median_us / st[0].median_us);
  Stats rep = summarize(report_times);
  std::printf("Report data after a filtered decision (exact f, D2..E, special points, ellipsoid "
              "relation; complete_report_data): median %.2f us, mean %.2f us over %zu pairs.\n\n",
              rep.median_us, rep.mean_us, report_times.size());
  std::printf("Cases among the random pairs (exact):");
  for (size_t c = 1; c < hist.size(); ++c)
    if (hist[c]) std::printf(" %zu: %ld;", c, hist[c]);
  std::printf(
      "\n\nDegenerate set: %zu pairs (35 canonical + 21 ellipsoid fixtures, one random integer "
      "congruence of each, 6 tangent configurations x {exact, +-2^-40, +-2^-100}).\n\n",
      degen.size());
  std::printf("| mode | right | wrong |\n|---|---|---|\n");
  const char* names[3] = {"float", "filtered", "exact"};
  for (int m = 0; m < 3; ++m)
    std::printf("| %s | %ld | %ld |\n", names[m], right[m],
                static_cast<long>(degen.size()) - right[m]);
  std::printf("\nfiltered mode fell back to exact arithmetic on %ld of %zu degenerate pairs.\n",
              degen_fallbacks, degen.size());
  flint_cleanup();
  return 0;
}
