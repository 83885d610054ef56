// surfcert::algebra canonical pencils and seeded scrambling (see canonical_pencil.hpp).
#include "surfcert/algebra/canonical_pencil.hpp"

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace surfcert::algebra {

namespace {

// Research qsic-classification §4.5 ("Canonical recipe per case", blocks of §1.7), with the
// Segre characteristic of each case from the §2.1 main table. Case 22's "J1(-3,+)x3" is
// written out. Unicode minus signs of the reference are ASCII here.
const std::vector<CaseRecipe> kCases = {
    {1, "J1(-3,+) J1(-1,+) J1(1,-) J1(3,+)", "[1111]", "<1,(1,2),2,(1,2),1,(1,2),2,(2,1),3>"},
    {2, "J1(-3,+) J1(-1,+) J1(1,+) J1(3,+)", "[1111]", "<0,(0,3),1,(1,2),2,(2,1),3,(3,0),4>"},
    {3, "J1(-3,+) J1(-1,+) C1(i)", "[1111]", "<1,(1,2),2,(2,1),3>"},
    {4, "C1(i) C1(1+2i)", "[1111]", "<2>"},
    {5, "J2(-3,+) J1(-1,+) J1(1,-)", "[211]", "<1,(1,2),2,((1,2)),2,(2,1),3>"},
    {6, "J2(-3,+) J1(-1,-) J1(1,-)", "[211]", "<1,(1,2),2,(2,1),3,((2,1)),3>"},
    {7, "J2(-3,+) J1(-1,+) J1(1,+)", "[211]", "<1,(1,2),2,(2,1),3,((3,0)),3>"},
    {8, "J2(0,+) C1(i)", "[211]", "<2,((1,2)),2>"},
    {9, "J3(-3,+) J1(-1,+)", "[31]", "<1,(1,2),2,(((2,1))),3>"},
    {10, "J2(-3,+) J2(-1,+)", "[22]", "<2,((1,2)),2,((1,2)),2>"},
    {11, "C2(i)", "[22]", "<2>"},
    {12, "J4(0,+)", "[4]", "<2,((((1,2)))),2>"},
    {13, "J1(-3,+) J1(-3,-) J1(-1,+) J1(1,-)", "[(11)11]", "<1,(1,2),2,((1,1)),2,(2,1),3>"},
    {14, "J1(-3,+) J1(-3,+) J1(-1,-) J1(1,+)", "[(11)11]", "<1,(1,2),2,(1,2),1,((1,1)),3>"},
    {15, "J1(-3,+) J1(-3,-) J1(-1,+) J1(1,+)", "[(11)11]", "<1,(1,2),2,(2,1),3,((2,0)),3>"},
    {16, "J1(-3,+) J1(-3,+) J1(-1,+) J1(1,+)", "[(11)11]",
     "<0,(0,3),1,((1,1)),3,(3,0),4> <0,(0,3),1,(1,2),2,((2,0)),4>"},
    {17, "J1(0,+) J1(0,+) C1(i)", "[(11)11]", "<1,((1,1)),3>"},
    {18, "J1(0,+) J1(0,-) C1(i)", "[(11)11]", "<2,((1,1)),2>"},
    {19, "J2(-3,+) J1(-3,+) J1(-1,-)", "[(21)1]", "<1,(1,2),2,(((1,1))),3>"},
    {20, "J2(-3,+) J1(-3,+) J1(-1,+)", "[(21)1]", "<1,(1,2),2,(((2,0))),3>"},
    {21, "J1(-3,+) J1(-3,+) J1(-3,-) J1(-1,+)", "[(111)1]", "<1,(1,2),2,(((1,0))),3>"},
    {22, "J1(-3,+) J1(-3,+) J1(-3,+) J1(-1,+)", "[(111)1]", "<0,(0,3),1,(((1,0))),4>"},
    {23, "J2(-3,+) J1(-1,+) J1(-1,-)", "[2(11)]", "<2,((1,1)),2,((1,2)),2>"},
    {24, "J2(-3,+) J1(-1,-) J1(-1,-)", "[2(11)]", "<1,((1,1)),3,((2,1)),3>"},
    {25, "J2(-3,+) J1(-1,+) J1(-1,+)", "[2(11)]", "<1,((0,3)),1,((1,1)),3>"},
    {26, "J3(0,+) J1(0,-)", "[(31)]", "<2,((((1,1)))),2>"},
    {27, "J3(0,+) J1(0,+)", "[(31)]", "<1,((((1,1)))),3>"},
    {28, "J1(-3,+) J1(-3,-) J1(-1,+) J1(-1,-)", "[(11)(11)]", "<2,((1,1)),2,((1,1)),2>"},
    {29, "J1(-3,+) J1(-3,+) J1(-1,+) J1(-1,+)", "[(11)(11)]", "<0,((0,2)),2,((2,0)),4>"},
    {30, "J1(-3,+) J1(-3,+) J1(-1,+) J1(-1,-)", "[(11)(11)]", "<1,((0,2)),1,((1,1)),3>"},
    {31, "C1(i) C1(i)", "[(11)(11)]", "<2>"},
    {32, "J2(0,+) J1(0,+) J1(0,-)", "[(211)]", "<2,((((0,1)))),2>"},
    {33, "J2(0,+) J1(0,+) J1(0,+)", "[(211)]", "<1,((((0,1)))),3>"},
    {34, "J2(0,+) J2(0,+)", "[(22)]", "<2,((((0,2)))),2>"},
    {35, "J2(0,+) J2(0,-)", "[(22)]", "<2,((((1,1)))),2>"},
};

[[noreturn]] void bad(const std::string& text, const std::string& why) {
  throw std::invalid_argument("recipe '" + text + "': " + why);
}

Rational parse_rational(const std::string& s, const std::string& text) {
  std::string t = s;
  if (!t.empty() && t[0] == '+') t.erase(0, 1);
  if (t.empty()) bad(text, "missing number");
  auto r = Rational::from_string(t);
  if (!r) bad(text, "bad number '" + s + "'");
  return *r;
}

// "a+bi", "a-bi", "bi", "i", "-i", "1+i", "-3/2-2i" -> (a, b).
std::pair<Rational, Rational> parse_complex(const std::string& s, const std::string& text) {
  if (s.empty() || s.back() != 'i') bad(text, "complex value must end with i: '" + s + "'");
  std::string body = s.substr(0, s.size() - 1);
  size_t split = std::string::npos;
  for (size_t k = body.size(); k-- > 1;) {
    if ((body[k] == '+' || body[k] == '-') && body[k - 1] != '/' && body[k - 1] != 'e' &&
        body[k - 1] != 'E') {
      split = k;
      break;
    }
  }
  std::string re = split == std::string::npos ? "0" : body.substr(0, split);
  std::string im = split == std::string::npos ? body : body.substr(split);
  if (im.empty() || im == "+") im = "1";
  if (im == "-") im = "-1";
  Rational a = parse_rational(re, text);
  Rational b = parse_rational(im, text);
  if (b.is_zero()) bad(text, "complex block with zero imaginary part");
  return {a, b};
}

std::string normalise(const std::string& in) {
  std::string s;
  for (size_t k = 0; k < in.size(); ++k) {
    unsigned char c = static_cast<unsigned char>(in[k]);
    // U+2212 minus sign (E2 88 92) and U+00D7 multiplication sign (C3 97).
    if (c == 0xE2 && k + 2 < in.size() && static_cast<unsigned char>(in[k + 1]) == 0x88 &&
        static_cast<unsigned char>(in[k + 2]) == 0x92) {
      s += '-';
      k += 2;
    } else if (c == 0xC3 && k + 1 < in.size() && static_cast<unsigned char>(in[k + 1]) == 0x97) {
      s += 'x';
      k += 1;
    } else {
      s += in[k];
    }
  }
  return s;
}

SmallMat zeros(int n) {
  return SmallMat(static_cast<size_t>(n), std::vector<Rational>(static_cast<size_t>(n)));
}

SmallMat anti_identity(int k) {
  SmallMat f = zeros(k);
  for (int i = 0; i < k; ++i)
    f[i][k - 1 - i] = 1;
  return f;
}

SmallMat upper_anti(int k) {
  SmallMat g = zeros(k);
  for (int i = 0; i + 2 <= k; ++i)
    g[i][k - 2 - i] = 1;
  return g;
}

} // namespace

const std::vector<CaseRecipe>& case_recipes() {
  return kCases;
}

Recipe parse_recipe(const std::string& raw) {
  const std::string text = normalise(raw);
  Recipe out;
  std::istringstream in(text);
  std::string tok;
  while (in >> tok) {
    if (tok.size() < 5 || (tok[0] != 'J' && tok[0] != 'C')) bad(raw, "bad block '" + tok + "'");
    const size_t open = tok.find('(');
    const size_t close = tok.rfind(')');
    if (open == std::string::npos || close == std::string::npos || close < open || open < 2)
      bad(raw, "bad block '" + tok + "'");
    Block b;
    b.complex = tok[0] == 'C';
    const std::string size_txt = tok.substr(1, open - 1);
    if (size_txt.find_first_not_of("0123456789") != std::string::npos)
      bad(raw, "bad block size '" + size_txt + "'");
    b.size = std::stoi(size_txt);
    if (b.size < 1 || b.size > 4) bad(raw, "bad block size '" + size_txt + "'");
    const std::string args = tok.substr(open + 1, close - open - 1);
    if (b.complex) {
      auto [re, im] = parse_complex(args, raw);
      b.theta = re;
      b.im = im;
    } else {
      const size_t comma = args.rfind(',');
      if (comma == std::string::npos) bad(raw, "real block needs (theta,sign): '" + tok + "'");
      b.theta = parse_rational(args.substr(0, comma), raw);
      const std::string sg = args.substr(comma + 1);
      if (sg == "+" || sg == "+1" || sg == "1")
        b.sign = 1;
      else if (sg == "-" || sg == "-1")
        b.sign = -1;
      else
        bad(raw, "bad sign '" + sg + "'");
    }
    int repeat = 1;
    const std::string tail = tok.substr(close + 1);
    if (!tail.empty()) {
      if (tail[0] != 'x' || tail.size() < 2 ||
          tail.find_first_not_of("0123456789", 1) != std::string::npos)
        bad(raw, "bad repeat '" + tail + "'");
      repeat = std::stoi(tail.substr(1));
    }
    for (int k = 0; k < repeat; ++k)
      out.push_back(b);
  }
  int dim = 0;
  for (const Block& b : out)
    dim += b.dimension();
  if (dim != 4) bad(raw, "block sizes add up to " + std::to_string(dim) + ", not 4");
  return out;
}

std::string recipe_to_string(const Recipe& r) {
  std::string s;
  for (const Block& b : r) {
    if (!s.empty()) s += ' ';
    if (b.complex) {
      s += "C" + std::to_string(b.size) + "(" + b.theta.to_string() + (b.im.sign() > 0 ? "+" : "") +
           b.im.to_string() + "i)";
    } else {
      s += "J" + std::to_string(b.size) + "(" + b.theta.to_string() + "," +
           (b.sign > 0 ? "+" : "-") + ")";
    }
  }
  return s;
}

std::pair<SmallMat, SmallMat> real_block(int k, const Rational& theta, int eps) {
  const SmallMat f = anti_identity(k);
  const SmallMat g = upper_anti(k);
  SmallMat a = zeros(k), b = zeros(k);
  const Rational e(eps);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      a[i][j] = e * f[i][j];
      b[i][j] = e * (theta * f[i][j] + g[i][j]);
    }
  return {a, b};
}

std::pair<SmallMat, SmallMat> complex_block(int k, const Rational& re, const Rational& im) {
  // M = (re + im*i) F + G: Re M = re F + G, Im M = im F. R(M) = [[Re, -Im], [-Im, -Re]].
  const SmallMat f = anti_identity(k);
  const SmallMat g = upper_anti(k);
  SmallMat a = zeros(2 * k), b = zeros(2 * k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      // A = R(F): Re F = F, Im F = 0.
      a[i][j] = f[i][j];
      a[k + i][k + j] = -f[i][j];
      const Rational rm = re * f[i][j] + g[i][j];
      const Rational imm = im * f[i][j];
      b[i][j] = rm;
      b[i][k + j] = -imm;
      b[k + i][j] = -imm;
      b[k + i][k + j] = -rm;
    }
  return {a, b};
}

PencilPair direct_sum(const std::vector<std::pair<SmallMat, SmallMat>>& blocks) {
  PencilPair out;
  size_t off = 0;
  for (const auto& [a, b] : blocks) {
    const size_t n = a.size();
    if (off + n > 4 || b.size() != n) throw std::invalid_argument("direct_sum: sizes exceed 4");
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j) {
        out.a[off + i][off + j] = a[i][j];
        out.b[off + i][off + j] = b[i][j];
      }
    off += n;
  }
  if (off != 4) throw std::invalid_argument("direct_sum: sizes add up to " + std::to_string(off));
  return out;
}

PencilPair build_pencil(const Recipe& r) {
  std::vector<std::pair<SmallMat, SmallMat>> blocks;
  for (const Block& b : r)
    blocks.push_back(b.complex ? complex_block(b.size, b.theta, b.im)
                               : real_block(b.size, b.theta, b.sign));
  return direct_sum(blocks);
}

long Rng::uniform(long lo, long hi) {
  // Rejection sampling on the raw 64-bit draws (not std::uniform_int_distribution, whose
  // algorithm the standard leaves to the library): the same seed gives the same numbers on
  // every platform, so a seed printed by a test or written by `generate` replays anywhere.
  const std::uint64_t range = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo) + 1;
  if (range == 0) return static_cast<long>(gen_()); // the whole 64-bit range
  const std::uint64_t limit =
      std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % range;
  std::uint64_t u = gen_();
  while (u >= limit)
    u = gen_();
  return static_cast<long>(static_cast<std::uint64_t>(lo) + u % range);
}

Rational Rng::small_rational(long num_max, long den_max) {
  const long n = uniform(-num_max, num_max);
  const long d = uniform(1, den_max);
  return Rational(n, static_cast<unsigned long>(d));
}

Rational Rng::small_dyadic(long num_max, int max_exp) {
  const long n = uniform(-num_max, num_max);
  const long e = uniform(0, max_exp);
  return Rational(n, 1UL << e);
}

Recipe redraw_eigenvalues(const Recipe& r, Rng& rng, bool dyadic) {
  // Distinct real eigenvalues, sorted.
  std::vector<Rational> reals;
  std::vector<std::pair<Rational, Rational>> complexes;
  for (const Block& b : r) {
    if (b.complex) {
      const std::pair<Rational, Rational> z{b.theta, b.im};
      if (std::find(complexes.begin(), complexes.end(), z) == complexes.end())
        complexes.push_back(z);
    } else if (std::find(reals.begin(), reals.end(), b.theta) == reals.end()) {
      reals.push_back(b.theta);
    }
  }
  std::sort(reals.begin(), reals.end());
  std::vector<Rational> fresh;
  while (fresh.size() < reals.size()) {
    Rational x = dyadic ? rng.small_dyadic(9, 2) : rng.small_rational();
    if (std::find(fresh.begin(), fresh.end(), x) == fresh.end()) fresh.push_back(x);
  }
  std::sort(fresh.begin(), fresh.end());
  std::vector<std::pair<Rational, Rational>> fresh_c;
  while (fresh_c.size() < complexes.size()) {
    std::pair<Rational, Rational> z{Rational(rng.uniform(-4, 4)), Rational(rng.uniform(1, 3))};
    if (std::find(fresh_c.begin(), fresh_c.end(), z) == fresh_c.end()) fresh_c.push_back(z);
  }
  Recipe out = r;
  for (Block& b : out) {
    if (b.complex) {
      const std::pair<Rational, Rational> z{b.theta, b.im};
      const size_t k =
          static_cast<size_t>(std::find(complexes.begin(), complexes.end(), z) - complexes.begin());
      b.theta = fresh_c[k].first;
      b.im = fresh_c[k].second;
    } else {
      const size_t k =
          static_cast<size_t>(std::find(reals.begin(), reals.end(), b.theta) - reals.begin());
      b.theta = fresh[k];
    }
  }
  return out;
}

Mat4 random_invertible(Rng& rng, long lo, long hi) {
  for (;;) {
    Mat4 p;
    for (auto& row : p)
      for (auto& x : row)
        x = Rational(rng.uniform(lo, hi));
    if (!core::det(p).is_zero()) return p;
  }
}

PencilPair congruence(const PencilPair& ab, const Mat4& p) {
  const Mat4 pt = core::transpose(p);
  return {pt * ab.a * p, pt * ab.b * p};
}

std::optional<PencilPair> change_basis(const PencilPair& ab, long p, long q, long r, long t) {
  if (p * t - q * r == 0) return std::nullopt;
  PencilPair out{core::scaled(ab.a, Rational(p)) + core::scaled(ab.b, Rational(q)),
                 core::scaled(ab.a, Rational(r)) + core::scaled(ab.b, Rational(t))};
  if (core::is_zero(out.a) || core::is_zero(out.b)) return std::nullopt;
  return out;
}

PencilPair random_basis_change(const PencilPair& ab, Rng& rng) {
  for (;;) {
    const long p = rng.uniform(-2, 2), q = rng.uniform(-2, 2), r = rng.uniform(-2, 2),
               t = rng.uniform(-2, 2);
    if (auto out = change_basis(ab, p, q, r, t)) return *out;
  }
}

PencilPair scrambled_pencil(const Recipe& r, Rng& rng, bool dyadic) {
  const PencilPair canon = build_pencil(redraw_eigenvalues(r, rng, dyadic));
  const PencilPair cong = congruence(canon, random_invertible(rng, -2, 2));
  return random_basis_change(cong, rng);
}

} // namespace surfcert::algebra
