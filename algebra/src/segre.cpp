#include "surfcert/algebra/segre.hpp"

#include <algorithm>

namespace surfcert::algebra {

std::string segre_text(std::vector<std::vector<int>> groups) {
  for (auto& g : groups)
    std::sort(g.rbegin(), g.rend());
  auto total = [](const std::vector<int>& g) {
    int s = 0;
    for (int x : g)
      s += x;
    return s;
  };
  std::stable_sort(groups.begin(), groups.end(), [&](const auto& x, const auto& y) {
    if (total(x) != total(y)) return total(x) > total(y);
    if (x.size() != y.size()) return x.size() < y.size();
    return x > y;
  });
  std::string s = "[";
  for (const auto& g : groups) {
    if (g.size() > 1) s += "(";
    for (int x : g)
      s += std::to_string(x);
    if (g.size() > 1) s += ")";
  }
  return s + "]";
}

// Jordan block sizes of a root of multiplicity m and rank r of theta*A - B (4x4).
static std::vector<int> blocks_from_rank(int m, int r, bool n2_zero) {
  int nblocks = 4 - r; // geometric multiplicity
  if (nblocks <= 1) return {m};
  if (nblocks == m) return std::vector<int>(static_cast<size_t>(m), 1);
  if (m == 3) return {2, 1}; // 2 blocks
  if (m == 4 && nblocks == 2) return n2_zero ? std::vector<int>{2, 2} : std::vector<int>{3, 1};
  return {2, 1, 1}; // m = 4, 3 blocks
}

std::string segre_from_facts(const PencilFacts& facts) {
  bool all_simple = !facts.complex_double_pair;
  for (const auto& r : facts.real_roots)
    all_simple = all_simple && r.multiplicity == 1;
  if (all_simple) return "[1111]"; // the common case, without building groups
  std::vector<std::vector<int>> groups;
  for (const auto& r : facts.real_roots)
    groups.push_back(blocks_from_rank(r.multiplicity, r.rank, facts.quadruple_n2_zero));
  if (facts.complex_double_pair) {
    for (int k = 0; k < 2; ++k)
      groups.push_back(facts.minimal_poly_split ? std::vector<int>{1, 1} : std::vector<int>{2});
  } else {
    for (int k = 0; k < facts.complex_roots; ++k)
      groups.push_back({1});
  }
  return segre_text(groups);
}

namespace {

using PMat = std::vector<std::vector<UPolyQ>>;

UPolyQ det_poly(const PMat& m) {
  size_t n = m.size();
  if (n == 1) return m[0][0];
  UPolyQ s;
  for (size_t j = 0; j < n; ++j) {
    PMat sub;
    for (size_t i = 1; i < n; ++i) {
      std::vector<UPolyQ> row;
      for (size_t k = 0; k < n; ++k)
        if (k != j) row.push_back(m[i][k]);
      sub.push_back(row);
    }
    UPolyQ t = m[0][j] * det_poly(sub);
    s = (j % 2 == 0) ? s + t : s - t;
  }
  return s;
}

// Monic gcd of all k x k minors of the 4x4 polynomial matrix m.
UPolyQ minors_gcd(const PMat& m, int k) {
  UPolyQ g;
  std::vector<int> rows, cols;
  for (int mask_r = 0; mask_r < 16; ++mask_r) {
    if (__builtin_popcount(static_cast<unsigned>(mask_r)) != k) continue;
    for (int mask_c = 0; mask_c < 16; ++mask_c) {
      if (__builtin_popcount(static_cast<unsigned>(mask_c)) != k) continue;
      PMat sub;
      for (size_t i = 0; i < 4; ++i) {
        if (!(mask_r >> i & 1)) continue;
        std::vector<UPolyQ> row;
        for (size_t j = 0; j < 4; ++j)
          if (mask_c >> j & 1) row.push_back(m[i][j]);
        sub.push_back(row);
      }
      UPolyQ d = det_poly(sub);
      fmpq_poly_gcd(g.raw_mut(), g.raw(), d.raw()); // FLINT returns the monic gcd
    }
  }
  return g;
}

int multiplicity_in(const UPolyQ& q, const UPolyZ& p) {
  UPolyZ z = q.primitive_integer();
  int e = 0;
  while (z.degree() >= p.degree()) {
    UPolyZ quo, rem;
    fmpz_poly_divrem(quo.raw_mut(), rem.raw_mut(), z.raw(), p.raw());
    if (!rem.is_zero()) break;
    z = quo;
    ++e;
  }
  return e;
}

} // namespace

std::string segre_by_invariant_factors(const core::Mat4& a, const core::Mat4& b) {
  PMat m(4, std::vector<UPolyQ>(4));
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = UPolyQ::linear(a[i][j], -b[i][j]);
  UPolyQ d[5];
  d[0] = UPolyQ(1);
  for (int k = 1; k <= 4; ++k)
    d[k] = minors_gcd(m, k);
  UPolyQ inv[5]; // inv[k] = d_k / d_(k-1)
  for (int k = 1; k <= 4; ++k)
    fmpq_poly_div(inv[k].raw_mut(), d[k].raw(), d[k - 1].raw());
  // Irreducible factors of f = d_4 (up to a constant).
  UPolyZ fz = d[4].primitive_integer();
  std::vector<std::vector<int>> groups;
  for (const IrreducibleFactor& fac : irreducible_factors(fz)) {
    const UPolyZ& p = fac.poly;
    std::vector<int> g;
    for (int k = 4; k >= 1; --k) {
      int e = multiplicity_in(inv[k], p);
      if (e > 0) g.push_back(e);
    }
    for (long r = 0; r < p.degree(); ++r)
      groups.push_back(g); // every root of p alike
  }
  // The degree of f may be < 4 (root at infinity): the missing blocks belong to l = infinity,
  // with exponents given by the degree drops of the invariant factors (reversed pencil).
  long deg = fz.degree();
  if (deg < 4) {
    // Apply the same computation to the reversed pencil A - l B at its root l = 0.
    PMat r(4, std::vector<UPolyQ>(4));
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        r[i][j] = UPolyQ::linear(-b[i][j], a[i][j]);
    UPolyQ e[5];
    e[0] = UPolyQ(1);
    for (int k = 1; k <= 4; ++k)
      e[k] = minors_gcd(r, k);
    UPolyZ lin = UPolyZ::from_coeffs({Integer(0), Integer(1)});
    std::vector<int> g;
    for (int k = 4; k >= 1; --k) {
      UPolyQ q;
      fmpq_poly_div(q.raw_mut(), e[k].raw(), e[k - 1].raw());
      int x = multiplicity_in(q, lin);
      if (x > 0) g.push_back(x);
    }
    groups.push_back(g);
  }
  return segre_text(groups);
}

} // namespace surfcert::algebra
