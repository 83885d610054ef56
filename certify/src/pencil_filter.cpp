// Interval filter and float analysis of a pencil. Compiled with -frounding-math
// -ffp-contract=off (see the top-level CMakeLists): CGAL::Interval_nt relies on them.
#include "surfcert/certify/pencil_filter.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/eigen4.hpp"
#include "surfcert/algebra/pencil_poly.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/certify/enclosure.hpp"

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>

namespace surfcert::certify {

using algebra::Inertia;
using algebra::Mat4T;
using algebra::PencilFacts;
using algebra::RootFacts;
using core::Mat4;
using core::Rational;

namespace {

using I = CGAL::Interval_nt<false>; // requires rounding towards +infinity (Protect_FPU_rounding)

// -1, 0, +1 when certain, 2 when the interval straddles zero without being {0}.
int isign(const I& x) {
  if (x.inf() > 0) return 1;
  if (x.sup() < 0) return -1;
  if (x.inf() == 0 && x.sup() == 0) return 0;
  return 2;
}

// Candidate separators for the k real roots of the quartic fd (k = 0, 2 or 4): +-B outside
// the roots and critical points between them. Returns their number, 0 on failure.
size_t separator_candidates(const double* fd, int k, double* seps) {
  if (k == 0) {
    seps[0] = 0.0;
    return 1;
  }
  std::vector<double> c(fd, fd + 5);
  auto inner = algebra::critical_point_separators(c, static_cast<size_t>(k));
  if (inner.size() != static_cast<size_t>(k - 1)) return 0;
  double bound = 0;
  for (int i = 0; i < 4; ++i)
    bound = std::max(bound, std::fabs(fd[i] / fd[4]));
  bound = 2 * (1 + bound);
  size_t n = 0;
  seps[n++] = -bound;
  for (double x : inner)
    seps[n++] = x;
  seps[n++] = bound;
  return n;
}

I horner(const std::array<I, 5>& f, double x) {
  I r = f[4];
  for (int i = 3; i >= 0; --i)
    r = r * x + f[static_cast<size_t>(i)];
  return r;
}

} // namespace

std::optional<PencilFacts> analyze_pencil_filtered(const core::QuadricMatrix& qa,
                                                   const core::QuadricMatrix& qb) {
  std::optional<PencilFacts> out(std::in_place);
  if (!analyze_pencil_filtered(qa, qb, *out)) out.reset();
  return out;
}

bool analyze_pencil_filtered(const core::QuadricMatrix& qa, const core::QuadricMatrix& qb,
                             PencilFacts& out) {
  CGAL::Protect_FPU_rounding<true> guard; // interval arithmetic needs rounding upwards
  // Enclosures of the exact matrices; for shapes posed in doubles, straight from the doubles
  // (the exact rationals are not formed unless this filter fails).
  const Mat4T<I> a = enclose(qa), b = enclose(qb);
  auto f = algebra::pencil_char_coeffs(a, b);
  if (isign(f[4]) == 2 || isign(f[4]) == 0) return false; // det A ~ 0: exact path re-bases
  auto q = algebra::quartic_invariants(f);
  int s4 = isign(q.d4);
  if (s4 == 0 || s4 == 2) return false; // possibly a multiple root: exact path
  int k;
  if (s4 < 0) {
    k = 2;
  } else {
    int s3 = isign(q.d3), s2 = isign(q.d2);
    if (s3 == 2 || s2 == 2) return false;
    k = (s3 > 0 && s2 > 0) ? 4 : 0;
  }
  // Separators: the critical points of f (roots of the cubic f', found in double) separate
  // consecutive real roots (Rolle); +-B with a Cauchy bound B lie outside all roots. Whatever
  // their accuracy, they are only candidates: k+1 points with certain, alternating signs of f
  // prove one root per gap (k is certain from D2, D3, D4).
  double fd[5];
  for (size_t i = 0; i < 5; ++i)
    fd[i] = CGAL::to_double(f[i]);
  double seps[5];
  size_t nsep = separator_candidates(fd, k, seps);
  if (nsep == 0) return false;
  int prev = 0;
  int fsign[5] = {0, 0, 0, 0, 0};
  for (size_t i = 0; i < nsep; ++i) {
    if (!std::isfinite(seps[i]) || (i > 0 && !(seps[i - 1] < seps[i]))) return false;
    int sg = isign(horner(f, seps[i]));
    if (sg == 0 || sg == 2 || (i > 0 && sg == prev)) return false;
    fsign[i] = sg; // = sign det(s*A - B), reused by Jacobi's rule below
    prev = sg;
  }
  // Indices: Descartes on the interval charpoly of s*A - B (all signs must be certain).
  // The caller holds a and b: the facts of a filtered answer do not copy them (see
  // complete_report_data), to keep the fast path free of big-number copies.
  out.indices.reserve(nsep);
  out.samples.reserve(nsep);
  for (size_t si = 0; si < nsep; ++si) {
    double s = seps[si];
    Mat4T<I> m;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j)
        m[i][j] = m[j][i] = a[i][j] * s - b[i][j];
    // Jacobi's rule: with leading minors d1, d2, d3 certainly nonzero and d4 = f(s) (its sign
    // is certain from above), the negative eigenvalues are the sign changes of 1, d1..d4.
    I d2 = m[0][0] * m[1][1] - m[0][1] * m[0][1];
    I d3 = m[2][0] * (m[0][1] * m[1][2] - m[0][2] * m[1][1]) -
           m[2][1] * (m[0][0] * m[1][2] - m[0][2] * m[1][0]) + m[2][2] * d2;
    int lead[5] = {1, isign(m[0][0]), isign(d2), isign(d3), fsign[si]};
    bool certain = true;
    for (int t = 1; t < 4; ++t)
      certain = certain && (lead[t] == 1 || lead[t] == -1);
    if (certain) {
      int neg = 0;
      for (int t = 0; t < 4; ++t)
        neg += lead[t] != lead[t + 1];
      out.indices.push_back(4 - neg);
      out.samples.push_back(Rational::exact_from_double(s));
      continue;
    }
    auto c = algebra::charpoly_coeffs(m); // a leading minor may vanish: Descartes instead
    int sg[4];
    for (size_t t = 0; t < 4; ++t) {
      sg[t] = isign(c[t]);
      if (sg[t] == 2) return false;
    }
    out.indices.push_back(algebra::inertia_from_charpoly_signs(sg).p);
    out.samples.push_back(Rational::exact_from_double(s));
  }
  for (int idx : out.indices)
    if (idx == 0 || idx == 4) out.definite_member = true;
  out.real_roots.reserve(static_cast<size_t>(k));
  for (int i = 0; i < k; ++i) {
    RootFacts r;
    r.lo = out.samples[static_cast<size_t>(i)];
    r.hi = out.samples[static_cast<size_t>(i) + 1];
    r.index_left = out.indices[static_cast<size_t>(i)];
    r.index_right = out.indices[static_cast<size_t>(i) + 1];
    r.sigma =
        Inertia{std::min(r.index_left, r.index_right), 4 - std::max(r.index_left, r.index_right)};
    out.real_roots.push_back(std::move(r));
  }
  out.complex_roots = 4 - k;
  out.root_pattern = k == 4 ? "R1" : (k == 2 ? "R3" : "R2");
  return true;
}

void complete_exact_invariants(PencilFacts& facts) {
  algebra::fill_quartic_invariants(facts);
  facts.invariants_filled = true;
}

// ---------------------------------------------------------------------------------------------
// Float mode (uncertified).

namespace {

// num/den in double (cheap; the float mode is uncertified anyway).

// Eigenvalues of a symmetric 4x4 matrix (cyclic Jacobi, algebra/eigen4.hpp).
std::array<double, 4> eigenvalues(const Mat4T<double>& m) {
  std::array<double, 4> w{};
  algebra::Mat4d v{};
  algebra::jacobi4(m, w, v);
  return w;
}

Inertia float_inertia(const Mat4T<double>& m, double tol) {
  auto ev = eigenvalues(m);
  double scale = 0;
  for (double e : ev)
    scale = std::max(scale, std::fabs(e));
  Inertia r;
  for (double e : ev) {
    if (e > tol * scale)
      ++r.p;
    else if (e < -tol * scale)
      ++r.n;
  }
  return r;
}

Mat4T<double> member(double t, const Mat4T<double>& a, const Mat4T<double>& b) {
  Mat4T<double> m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = t * a[i][j] - b[i][j];
  return m;
}

// X = A^-1 B by Gaussian elimination with partial pivoting.
Mat4T<double> solve(Mat4T<double> a, Mat4T<double> b) {
  for (size_t c = 0; c < 4; ++c) {
    size_t p = c;
    for (size_t r = c + 1; r < 4; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    std::swap(a[c], a[p]);
    std::swap(b[c], b[p]);
    for (size_t r = 0; r < 4; ++r) {
      if (r == c || a[c][c] == 0) continue;
      double f = a[r][c] / a[c][c];
      for (size_t k = 0; k < 4; ++k) {
        a[r][k] -= f * a[c][k];
        b[r][k] -= f * b[c][k];
      }
    }
  }
  for (size_t r = 0; r < 4; ++r)
    for (size_t k = 0; k < 4; ++k)
      b[r][k] /= a[r][r];
  return b;
}

Mat4T<double> mul(const Mat4T<double>& x, const Mat4T<double>& y) {
  Mat4T<double> r{};
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      for (size_t k = 0; k < 4; ++k)
        r[i][j] += x[i][k] * y[k][j];
  return r;
}

double max_abs(const Mat4T<double>& x) {
  double s = 0;
  for (const auto& row : x)
    for (double v : row)
      s = std::max(s, std::fabs(v));
  return s;
}

} // namespace

PencilFacts analyze_pencil_float(const core::QuadricMatrix& qa, const core::QuadricMatrix& qb,
                                 FloatInvariants& inv, double tol) {
  // Like seed 002: plain doubles of the given matrices, the root pattern from D2, D3, D4, E
  // with an absolute zero tolerance, then float indices. Nothing here is certified. The facts
  // do not copy the exact matrices (a float answer never needs them).
  PencilFacts out;
  Mat4T<double> a = approx(qa), b = approx(qb);
  auto f = algebra::pencil_char_coeffs(a, b);
  double fs = 0;
  for (double c : f)
    fs = std::max(fs, std::fabs(c));
  if (fs <= tol) {
    out.kind = algebra::PencilKind::Degenerate;
    return out;
  }
  if (std::fabs(f[4]) <= tol * fs) {
    // Re-base as the exact path does: a' = t a - b, b' = -a.
    for (long k = 0;; ++k) {
      long t = (k % 2 == 0) ? k / 2 : -(k + 1) / 2;
      double v = f[4];
      for (int i = 3; i >= 0; --i)
        v = v * static_cast<double>(t) + f[static_cast<size_t>(i)];
      if (std::fabs(v) > tol * fs || k > 20) {
        auto na = member(static_cast<double>(t), a, b);
        for (auto& row : a)
          for (auto& x : row)
            x = -x;
        b = a;  // b' = -a
        a = na; // a' = t a - b
        out.rebased = true;
        out.rebase_t = t;
        break;
      }
    }
    f = algebra::pencil_char_coeffs(a, b);
  }
  std::array<double, 5> fn;
  for (size_t i = 0; i < 5; ++i)
    fn[i] = f[i];
  auto q = algebra::quartic_invariants(fn);
  for (size_t i = 0; i < 5; ++i)
    inv.f[i] = f[i];
  inv.d2 = q.d2;
  inv.d3 = q.d3;
  inv.d4 = q.d4;
  inv.e = q.e;
  auto z = [&](double x) { return std::fabs(x) <= tol ? 0 : (x > 0 ? 1 : -1); };
  out.root_pattern = algebra::root_pattern_from_signs(z(q.d2), z(q.d3), z(q.d4), z(q.e));
  const std::string& rp = out.root_pattern;
  if (rp == "R1" || rp == "R2" || rp == "R3") {
    // All roots simple: separators as in the filter, indices by Descartes on float charpolys.
    int k = rp == "R1" ? 4 : (rp == "R3" ? 2 : 0);
    double seps[5];
    size_t nsep = separator_candidates(fn.data(), k, seps);
    if (nsep == 0) { // fall through to the clustering route below with the same pattern
    } else {
      for (size_t si = 0; si < nsep; ++si) {
        auto m = member(seps[si], a, b);
        auto c = algebra::charpoly_coeffs(m);
        double scale = 0;
        for (const auto& row : m)
          for (double v : row)
            scale = std::max(scale, std::fabs(v));
        int sg[4];
        for (size_t t = 0; t < 4; ++t) {
          double tolk = tol * std::pow(std::max(scale, 1e-300), static_cast<double>(4 - t));
          sg[t] = std::fabs(c[t]) <= tolk ? 0 : (c[t] > 0 ? 1 : -1);
        }
        out.indices.push_back(algebra::inertia_from_charpoly_signs(sg).p);
        out.samples.push_back(Rational::exact_from_double(seps[si]));
      }
      for (int idx : out.indices)
        if (idx == 0 || idx == 4) out.definite_member = true;
      for (int i = 0; i < k; ++i) {
        RootFacts r;
        auto ui = static_cast<size_t>(i);
        r.lo = out.samples[ui];
        r.hi = out.samples[ui + 1];
        r.index_left = out.indices[ui];
        r.index_right = out.indices[ui + 1];
        r.sigma = Inertia{std::min(r.index_left, r.index_right),
                          4 - std::max(r.index_left, r.index_right)};
        out.real_roots.push_back(std::move(r));
      }
      out.complex_roots = 4 - k;
      return out;
    }
  }
  std::array<double, 5> fnorm;
  for (size_t i = 0; i < 5; ++i)
    fnorm[i] = f[i] / fs;
  // Root multiplicities the pattern implies (real ones listed with their multiplicity).
  std::vector<int> mults; // multiplicities of the real roots, in increasing root order later
  int complex_roots = 0;
  if (rp == "R1")
    mults = {1, 1, 1, 1};
  else if (rp == "R2")
    complex_roots = 4;
  else if (rp == "R3")
    mults = {1, 1}, complex_roots = 2;
  else if (rp == "R4")
    mults = {2, 1, 1};
  else if (rp == "R5")
    mults = {2}, complex_roots = 2;
  else if (rp == "R6")
    mults = {2, 2};
  else if (rp == "R7")
    mults = {3, 1};
  else if (rp == "R8")
    complex_roots = 4, out.complex_double_pair = true;
  else
    mults = {4};
  // Approximate roots: cluster the float roots closest to the real axis.
  std::vector<double> coeffs(fnorm.begin(), fnorm.end());
  int nreal = 0;
  for (int m : mults)
    nreal += m;
  auto r = algebra::approx_real_roots(coeffs, static_cast<size_t>(nreal));
  // Group sorted real roots into clusters whose sizes are the multiplicities: try every order
  // of the multiplicity list and keep the grouping with the smallest spread.
  std::vector<int> best;
  double best_spread = INFINITY;
  std::sort(mults.begin(), mults.end());
  do {
    double spread = 0;
    size_t pos = 0;
    for (int m : mults) {
      spread += r[pos + static_cast<size_t>(m) - 1] - r[pos];
      pos += static_cast<size_t>(m);
    }
    if (spread < best_spread) {
      best_spread = spread;
      best = mults;
    }
  } while (std::next_permutation(mults.begin(), mults.end()));
  std::vector<double> roots;
  size_t pos = 0;
  for (int m : best) {
    double s = 0;
    for (int i = 0; i < m; ++i)
      s += r[pos + static_cast<size_t>(i)];
    roots.push_back(s / m);
    pos += static_cast<size_t>(m);
  }
  std::vector<double> seps;
  if (roots.empty()) {
    seps.push_back(0.0);
  } else {
    double span = std::max(1.0, roots.back() - roots.front());
    seps.push_back(roots.front() - span);
    for (size_t i = 0; i + 1 < roots.size(); ++i)
      seps.push_back(0.5 * (roots[i] + roots[i + 1]));
    seps.push_back(roots.back() + span);
  }
  for (double s : seps) {
    out.indices.push_back(float_inertia(member(s, a, b), tol).p);
    out.samples.push_back(Rational::exact_from_double(s));
  }
  for (int idx : out.indices)
    if (idx == 0 || idx == 4) out.definite_member = true;
  Mat4T<double> x = solve(a, b);
  for (size_t i = 0; i < roots.size(); ++i) {
    RootFacts rf;
    rf.multiplicity = best[i];
    rf.lo = out.samples[i];
    rf.hi = out.samples[i + 1];
    rf.index_left = out.indices[i];
    rf.index_right = out.indices[i + 1];
    if (rf.multiplicity == 1) {
      rf.rank = 3;
      rf.sigma = Inertia{std::min(rf.index_left, rf.index_right),
                         4 - std::max(rf.index_left, rf.index_right)};
    } else {
      rf.sigma = float_inertia(member(roots[i], a, b), tol);
      rf.rank = rf.sigma.rank();
      if (rf.multiplicity == 4 && rf.rank == 2) {
        auto n = x;
        for (size_t d = 0; d < 4; ++d)
          n[d][d] -= roots[i];
        out.quadruple_n2_zero = max_abs(mul(n, n)) <= tol * std::max(1.0, max_abs(x) * max_abs(x));
      }
    }
    out.real_roots.push_back(std::move(rf));
  }
  if (out.complex_double_pair) {
    // g = l^2 - s l + p from the clustered complex roots; test g(X) = 0.
    auto zc = algebra::approx_complex_roots(coeffs);
    double re = 0, absq = 0;
    for (auto c : zc) {
      re += c.real();
      absq += std::norm(c);
    }
    double s = re / 2, p = absq / 4; // sum and product of the two distinct conjugate roots
    auto x2 = mul(x, x);
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        x2[i][j] += -s * x[i][j] + (i == j ? p : 0.0);
    out.minimal_poly_split = max_abs(x2) <= tol * std::max(1.0, max_abs(x) * max_abs(x));
  }
  out.complex_roots = complex_roots;
  return out;
}

} // namespace surfcert::certify
