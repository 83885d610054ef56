// The relation of two ellipsoids (ellipsoid_relation.hpp). Compiled with -frounding-math
// -ffp-contract=off (top-level CMakeLists): CGAL::Interval_nt relies on them.
#include "surfcert/certify/ellipsoid_relation.hpp"

#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/certify/enclosure.hpp"

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <boost/container/small_vector.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace surfcert::certify {

using algebra::PencilKind;
using core::Mat4;
using core::Rational;

namespace {

using I = CGAL::Interval_nt<false>; // requires rounding towards +infinity (Protect_FPU_rounding)

// -1 or +1 when certain, 0 when the interval may hold 0 or is not finite.
int certain_sign(const I& x) {
  if (!std::isfinite(x.inf()) || !std::isfinite(x.sup())) return 0;
  if (x.inf() > 0) return 1;
  if (x.sup() < 0) return -1;
  return 0;
}

// det of the 4x4 matrix m and of its leading 3x3 block, by cofactors (T: I or Rational).
template <class T> T det3(const T m[4][4]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

template <class T> T det4(const T m[4][4]) {
  // Laplace expansion along the first two rows: 2x2 minors of rows 0-1 times the
  // complementary minors of rows 2-3.
  auto s = [&](int r, int i, int j) { return m[r][i] * m[r + 1][j] - m[r][j] * m[r + 1][i]; };
  return s(0, 0, 1) * s(2, 2, 3) - s(0, 0, 2) * s(2, 1, 3) + s(0, 0, 3) * s(2, 1, 2) +
         s(0, 1, 2) * s(2, 0, 3) - s(0, 1, 3) * s(2, 0, 2) + s(0, 2, 3) * s(2, 0, 1);
}

// The enclosure of a quadric's exact matrix (enclosure.hpp: from the doubles of a posed
// shape without forming its rationals).
struct Enclosed {
  I m[4][4];
  explicit Enclosed(const core::QuadricMatrix& q) {
    const IMat4 e = enclose(q);
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        m[i][j] = e[i][j];
  }
};

// Sign of the (0, 0) entry: from the enclosure, exact when it holds 0.
int corner_sign(const core::QuadricMatrix& q, const Enclosed& e) {
  if (int s = certain_sign(e.m[0][0])) return s;
  return q(0, 0).sign();
}

// Whether X^T M X = 0 is a real ellipsoid: its quadratic block Q definite and, with Q
// normalised positive definite, det M = det Q (c - b^T Q^-1 b) < 0 (the centre inside).
// Intervals first (leading minors of sa Q: sa m1, m2, sa m3 > 0; det M < 0); when they do not
// decide, the exact classification of the quadric.
bool real_ellipsoid(const core::QuadricMatrix& q, const Enclosed& e) {
  if (q.shape()) return q.kind() == core::QuadricKind::Ellipsoid; // known from the shape type
  const int sa = corner_sign(q, e);
  if (sa == 0) return false; // a zero diagonal entry: Q is not definite
  const auto& m = e.m;
  const I m2 = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const int s[] = {certain_sign(m2), sa * certain_sign(det3(m)), -certain_sign(det4(m))};
  bool all = true;
  for (int x : s) {
    if (x < 0) return false;
    all = all && x > 0;
  }
  if (all) return true;
  return q.kind() == core::QuadricKind::Ellipsoid;
}

// Sign of the real root i of f from the facts alone; 0 when they do not decide it.
// sd_a = sign det A (the leading coefficient of f), sf0 = sign f(0) = sign det(-B) (nonzero:
// B is an ellipsoid). Root i is the only root of f in (samples[i], samples[i+1]) and every
// root j < i lies left of samples[i], so sign f(samples[i]) = sd_a (-1)^(multiplicities of the
// roots j >= i); when samples[i] < 0 < samples[i+1] and root i has odd multiplicity, it is
// positive exactly when f(0) has that sign too (0 lies left of it).
int root_sign_from_facts(const algebra::PencilFacts& f, size_t i, int sd_a, int sf0) {
  const auto& rt = f.real_roots[i];
  if (rt.rational_value) return rt.rational_value->sign();
  if (rt.quadratic) return rt.quadratic->sign();
  if (rt.lo.sign() >= 0) return 1;
  if (rt.hi.sign() <= 0) return -1;
  if (f.samples.size() != f.real_roots.size() + 1) return 0;
  const Rational& s = f.samples[i];
  const Rational& t = f.samples[i + 1];
  if (s.sign() >= 0) return 1;
  if (t.sign() <= 0) return -1;
  if (rt.multiplicity % 2 == 0) return 0;
  int m_right = 0;
  for (size_t j = i; j < f.real_roots.size(); ++j)
    m_right += f.real_roots[j].multiplicity;
  const int s_left = m_right % 2 == 0 ? sd_a : -sd_a;
  return sf0 == s_left ? 1 : -1;
}

// Sign of the real root in (lo, hi) of the square-free g (g(lo) g(hi) < 0): the exact route.
int root_sign_exact(const algebra::UPolyZ& g, const Rational& lo, const Rational& hi) {
  if (lo.sign() >= 0) return 1;
  if (hi.sign() <= 0) return -1;
  int s0 = g.sign_at(Rational(0));
  if (s0 == 0) return 0;
  return s0 == g.sign_at(lo) ? 1 : -1;
}

// The square-free part of f = det(lA - B), primitive over Z.
algebra::UPolyZ squarefree_char_poly(const Mat4& a, const Mat4& b) {
  algebra::UPolyZ fz = algebra::pencil_char_poly(a, b).primitive_integer();
  algebra::UPolyZ g, fd, h;
  fmpz_poly_derivative(fd.raw_mut(), fz.raw());
  fmpz_poly_gcd(h.raw_mut(), fz.raw(), fd.raw());
  fmpz_poly_div(g.raw_mut(), fz.raw(), h.raw());
  return g;
}

// (-det M)^3 / q^4 (q = leading 3x3 minor of the normalised M, positive definite block) is
// proportional to the squared volume of the ellipsoid X^T M X <= 0. True when a's is smaller:
// (-dA)^3 qB^4 < (-dB)^3 qA^4 (both sides multiplied by qA^4 qB^4 > 0); det and q^4 do not
// depend on the sign normalisation (4x4 determinant, even power).
bool a_smaller(const core::QuadricMatrix& qa_, const Enclosed& ea, const core::QuadricMatrix& qb_,
               const Enclosed& eb) {
  {
    const I da = -det4(ea.m), db = -det4(eb.m), qa = det3(ea.m), qb = det3(eb.m);
    const I qa2 = qa * qa, qb2 = qb * qb;
    const I lhs = da * da * da * (qb2 * qb2), rhs = db * db * db * (qa2 * qa2);
    if (int s = certain_sign(rhs - lhs)) return s > 0;
  }
  const Mat4 &a = qa_.matrix(), &b = qb_.matrix();
  const Rational da = -core::det(a), db = -core::det(b);
  const Rational qa = core::leading_minor(a, 3), qb = core::leading_minor(b, 3);
  const Rational qa2 = qa * qa, qb2 = qb * qb;
  return da * da * da * (qb2 * qb2) < db * db * db * (qa2 * qa2);
}

// Float facts (an estimate): the roots of the float f (in the basis the facts use) grouped by
// the facts' multiplicities in increasing order, each group's mean mapped back through a
// re-basing (l = t + 1/l'; the float analysis re-bases when det A is small against the other
// coefficients). The facts' separators are only rough bounds (midpoints between the roots).
std::vector<int> float_root_signs(const QsicResult& r) {
  const auto& f = r.facts;
  std::vector<double> c(r.float_invariants->f, r.float_invariants->f + 5);
  double scale = 0;
  for (double x : c)
    scale = std::max(scale, std::fabs(x));
  if (!(scale > 0) || !std::isfinite(scale) || c[4] == 0) return {};
  for (double& x : c)
    x /= scale;
  size_t total = 0;
  for (const auto& rt : f.real_roots)
    total += static_cast<size_t>(rt.multiplicity);
  const std::vector<double> z = algebra::approx_real_roots(c, total);
  if (z.size() != total) return {};
  std::vector<int> signs;
  size_t pos = 0;
  for (const auto& rt : f.real_roots) {
    double x = 0;
    for (int i = 0; i < rt.multiplicity; ++i)
      x += z[pos++];
    x /= rt.multiplicity;
    if (f.rebased) x = static_cast<double>(f.rebase_t) + 1 / x;
    signs.push_back(x >= 0 ? 1 : -1);
  }
  return signs;
}

} // namespace

void ellipsoid_relation(QsicResult& r, const core::QuadricMatrix& a, const core::QuadricMatrix& b) {
  if (r.pencil == PencilKind::Degenerate) return;
  if (r.pencil == PencilKind::Regular && r.facts.real_roots.size() > 4) return;
  CGAL::Protect_FPU_rounding<true> guard; // interval arithmetic needs rounding upwards
  const Enclosed ea(a), eb(b);
  if (!real_ellipsoid(a, ea) || !real_ellipsoid(b, eb)) return;
  if (r.pencil == PencilKind::Coincident) {
    r.ellipsoid_relation = "coincident";
    return;
  }
  // Normalise each matrix so that its quadratic block is positive definite (interior < 0);
  // the roots of the normalised det(lA - B) are eps * (roots of f), eps = sa * sb.
  // Two ellipsoids: det A != 0, so the facts are in the given basis (never re-based).
  const int sa = corner_sign(a, ea), sb = corner_sign(b, eb);
  const int eps = sa * sb;
  // At most four roots: held inline (no allocation per pair on the filtered path).
  boost::container::small_vector<int, 4> signs;
  if (r.mode == Mode::Float) {
    if (!r.float_invariants) return;
    const std::vector<int> fs = float_root_signs(r);
    if (fs.size() != r.facts.real_roots.size()) return; // no estimate
    signs.assign(fs.begin(), fs.end());
  } else {
    // Exact facts of two ellipsoids are never re-based (det A != 0).
    if (r.facts.rebased) return;
    // sign det A (f's leading coefficient) and sign f(0) = sign det(-B) = sign det B: both -1,
    // exactly. A real ellipsoid's matrix, normalised so that its quadratic block Q is positive
    // definite, has det = det Q (c - b^T Q^-1 b) with det Q > 0 and c - b^T Q^-1 b < 0 (the
    // centre inside); the normalisation (a factor -1) leaves a 4x4 determinant unchanged. (Two
    // interval determinants and their exact fallback decided this before, always the same.)
    const int sd_a = -1, sf0 = -1;
    bool need_exact = false;
    for (size_t i = 0; i < r.facts.real_roots.size(); ++i) {
      int s = root_sign_from_facts(r.facts, i, sd_a, sf0);
      need_exact = need_exact || s == 0;
      signs.push_back(s);
    }
    if (need_exact) {
      const algebra::UPolyZ g = squarefree_char_poly(a.matrix(), b.matrix());
      for (size_t i = 0; i < signs.size(); ++i)
        if (signs[i] == 0)
          signs[i] = root_sign_exact(g, r.facts.real_roots[i].lo, r.facts.real_roots[i].hi);
    }
  }
  int negative_distinct = 0;
  bool negative_double = false;
  for (size_t i = 0; i < signs.size(); ++i) {
    if (eps * signs[i] < 0) {
      ++negative_distinct;
      if (r.facts.real_roots[i].multiplicity >= 2) negative_double = true;
    }
  }
  const int c = r.tu_case;
  bool nested_possible = false;
  if (negative_distinct >= 2) {
    r.ellipsoid_relation = "separated";
  } else if (negative_double) {
    r.ellipsoid_relation = "externally_touching";
  } else if (c == 2 || c == 16 || c == 22) {
    r.ellipsoid_relation = "nested";
    nested_possible = true;
  } else if (c == 7 || c == 15 || c == 20 || c == 21 || c == 25 || c == 30 || c == 33) {
    r.ellipsoid_relation = "internally_touching";
    nested_possible = true;
  } else {
    r.ellipsoid_relation = "overlapping";
  }
  if (nested_possible) r.containment = a_smaller(a, ea, b, eb) ? "a_inside_b" : "b_inside_a";
}

} // namespace surfcert::certify
