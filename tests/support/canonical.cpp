// surfcert::testing canonical pencils and seeded scrambling (see canonical.hpp).
#include "support/canonical.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace surfcert::testing {

namespace {

// Signature sequence entries: an interval index I as {0, I, 0}, a root as {m, p, n} (m >= 1),
// so that lexicographic comparison of equal positions compares like with like (§1.4).
using SeqEntry = std::array<int, 3>;
using Seq = std::vector<SeqEntry>;

Seq complemented(const Seq& s) {
  Seq out;
  for (const SeqEntry& e : s)
    out.push_back(e[0] == 0 ? SeqEntry{0, 4 - e[1], 0} : SeqEntry{e[0], e[2], e[1]});
  return out;
}

Seq reversed(const Seq& s) {
  return Seq(s.rbegin(), s.rend());
}

// <I0, s1, I1, s2, ..., sk, Ik> -> <I1, s2, ..., sk, Ik, bar(s1), 4 - I1>.
Seq rotated(const Seq& s) {
  Seq out(s.begin() + 2, s.end());
  out.push_back(SeqEntry{s[1][0], s[1][2], s[1][1]});
  out.push_back(SeqEntry{0, 4 - s[2][1], 0});
  return out;
}

std::string seq_text(const Seq& s) {
  std::string t = "<";
  for (size_t k = 0; k < s.size(); ++k) {
    if (k) t += ',';
    const SeqEntry& e = s[k];
    if (e[0] == 0) {
      t += std::to_string(e[1]);
    } else {
      t += std::string(static_cast<size_t>(e[0]), '(') + std::to_string(e[1]) + "," +
           std::to_string(e[2]) + std::string(static_cast<size_t>(e[0]), ')');
    }
  }
  return t + ">";
}

} // namespace

std::string signature_normal_form(const algebra::PencilFacts& facts) {
  Seq s;
  s.push_back(SeqEntry{0, facts.indices.at(0), 0});
  for (size_t i = 0; i < facts.real_roots.size(); ++i) {
    const algebra::RootFacts& r = facts.real_roots[i];
    s.push_back(SeqEntry{r.multiplicity, r.sigma.p, r.sigma.n});
    s.push_back(SeqEntry{0, facts.indices.at(i + 1), 0});
  }
  const size_t k = facts.real_roots.size();
  Seq best = s;
  Seq cur = s;
  for (size_t rot = 0; rot < std::max<size_t>(k, 1); ++rot) {
    for (int rev = 0; rev < 2; ++rev)
      for (int comp = 0; comp < 2; ++comp) {
        Seq c = rev ? reversed(cur) : cur;
        if (comp) c = complemented(c);
        best = std::min(best, c);
      }
    if (k > 0) cur = rotated(cur);
  }
  return seq_text(best);
}

int case_from_table(const std::string& segre, const std::string& sequence) {
  for (const CaseRecipe& c : case_recipes()) {
    if (segre != c.segre) continue;
    std::istringstream in(c.sequences);
    std::string one;
    while (in >> one)
      if (one == sequence) return c.tu_case;
  }
  return 0;
}

std::uint64_t test_seed() {
  const char* env = std::getenv("SURFCERT_TEST_SEED");
  if (env != nullptr && *env != '\0') {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(env, &end, 10);
    if (end != nullptr && *end == '\0') return static_cast<std::uint64_t>(v);
  }
  return 20261122ULL;
}

Mat4 random_symmetric(Rng& rng, long lo, long hi) {
  for (;;) {
    Mat4 m;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) {
        m[i][j] = Rational(rng.uniform(lo, hi));
        m[j][i] = m[i][j];
      }
    if (!core::is_zero(m)) return m;
  }
}

std::string mat_to_string(const Mat4& m) {
  std::string s = "[";
  for (int i = 0; i < 4; ++i) {
    s += i == 0 ? "[" : ",\n [";
    for (int j = 0; j < 4; ++j) {
      if (j) s += ", ";
      s += m[i][j].to_string();
    }
    s += "]";
  }
  return s + "]";
}

std::string pencil_to_string(const Mat4& a, const Mat4& b) {
  return "A = " + mat_to_string(a) + "\nB = " + mat_to_string(b) + "\n";
}

} // namespace surfcert::testing
