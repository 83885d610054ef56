#include "surfcert/algebra/pencil.hpp"

#include "surfcert/algebra/pencil_poly.hpp"
#include "surfcert/algebra/real_roots.hpp"

#include <flint/fmpq_mat.h>
#include <flint/fmpz_poly_factor.h>

#include <algorithm>
#include <optional>
#include <stdexcept>

namespace surfcert::algebra {

using core::Integer;
using core::Mat4;

bool proportional(const Mat4& a, const Mat4& b) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      if (!a[i][j].is_zero()) {
        Rational c = b[i][j] / a[i][j];
        for (size_t k = 0; k < 4; ++k)
          for (size_t l = 0; l < 4; ++l)
            if (b[k][l] != c * a[k][l]) return false;
        return true;
      }
  return core::is_zero(b);
}

namespace {

// The pencil with denominators cleared by one common factor L (so lambda is unchanged):
// a = L*A, b = L*B are integer matrices and det(l*a - b) = L^4 det(l*A - B).
struct IntegerPencil {
  Mat4T<Integer> a, b;
  Integer l{1};

  IntegerPencil(const Mat4& ra, const Mat4& rb) {
    for (const Mat4* m : {&ra, &rb})
      for (const auto& row : *m)
        for (const auto& v : row)
          fmpz_lcm(l.raw_mut(), l.raw(), fmpq_denref(v.raw()));
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        Integer t;
        fmpz_divexact(t.raw_mut(), l.raw(), fmpq_denref(ra[i][j].raw()));
        a[i][j] = t * ra[i][j].num();
        fmpz_divexact(t.raw_mut(), l.raw(), fmpq_denref(rb[i][j].raw()));
        b[i][j] = t * rb[i][j].num();
      }
  }

  // q*L*(s*A - B) = p*a - q*b for s = p/q (q > 0): the member up to a positive factor, with
  // integer entries (its rank and inertia are the member's; no gcd of the posed doubles'
  // ~150-digit denominators in the elimination).
  Mat4 member_multiple(const Rational& s) const {
    const Integer p = s.num(), q = s.den();
    Mat4 m;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        m[i][j] = Rational(p * a[i][j] - q * b[i][j]);
    return m;
  }

  // Number of positive eigenvalues of s*A - B, s = p/q: q*L*(s*A - B) = p*a - q*b has the
  // same inertia (positive factor). `sign_det` = sign of f(s) (also the sign of det(p*a - q*b)).
  // Fast route: Jacobi's rule on the leading principal minors (negative eigenvalues = sign
  // changes of 1, d1, d2, d3, d4) when none of them vanishes; otherwise Descartes on the
  // integer characteristic polynomial. Both exact.
  int index_at(const Rational& s, int sign_det) const {
    Integer p = s.num(), q = s.den();
    Mat4T<Integer> m;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i; j < 4; ++j) {
        fmpz_mul(m[i][j].raw_mut(), p.raw(), a[i][j].raw());
        fmpz_submul(m[i][j].raw_mut(), q.raw(), b[i][j].raw());
        if (j != i) m[j][i] = m[i][j];
      }
    if (sign_det != 0) {
      Integer d2, d3, t;
      fmpz_mul(d2.raw_mut(), m[0][0].raw(), m[1][1].raw());
      fmpz_submul(d2.raw_mut(), m[0][1].raw(), m[1][0].raw());
      // d3 by cofactors along the last row of the leading 3x3 block.
      fmpz_mul(t.raw_mut(), m[0][1].raw(), m[1][2].raw());
      fmpz_submul(t.raw_mut(), m[0][2].raw(), m[1][1].raw());
      fmpz_mul(d3.raw_mut(), m[2][0].raw(), t.raw());
      fmpz_mul(t.raw_mut(), m[0][0].raw(), m[1][2].raw());
      fmpz_submul(t.raw_mut(), m[0][2].raw(), m[1][0].raw());
      fmpz_submul(d3.raw_mut(), m[2][1].raw(), t.raw());
      fmpz_addmul(d3.raw_mut(), m[2][2].raw(), d2.raw());
      int sg[5] = {1, m[0][0].sign(), d2.sign(), d3.sign(), sign_det};
      if (sg[1] != 0 && sg[2] != 0 && sg[3] != 0) {
        int neg = 0;
        for (int k = 0; k < 4; ++k)
          neg += sg[k] != sg[k + 1];
        return 4 - neg;
      }
    }
    auto c = charpoly_coeffs(m);
    int sg[4];
    for (size_t k = 0; k < 4; ++k)
      sg[k] = c[k].sign();
    return inertia_from_charpoly_signs(sg).p;
  }
};

// f = det(l*A - B) from the integer pencil: coefficients c_i / L^4.
UPolyQ char_poly_of(const IntegerPencil& ip, std::array<Integer, 5>* int_coeffs = nullptr) {
  auto c = pencil_char_coeffs(ip.a, ip.b);
  Integer l2 = ip.l * ip.l, l4 = l2 * l2;
  UPolyQ f;
  UPolyZ z = UPolyZ::from_coeffs(std::vector<Integer>(c.begin(), c.end()));
  fmpq_poly_set_fmpz_poly(f.raw_mut(), z.raw());
  fmpq_poly_scalar_div_fmpz(f.raw_mut(), f.raw(), l4.raw()); // one content gcd, not five
  if (int_coeffs) *int_coeffs = c;
  return f;
}

} // namespace

UPolyQ pencil_char_poly(const Mat4& a, const Mat4& b) {
  return char_poly_of(IntegerPencil(a, b));
}

std::string root_pattern_from_multiplicities(const PencilFacts& f) {
  std::vector<int> m;
  for (const auto& r : f.real_roots)
    m.push_back(r.multiplicity);
  std::sort(m.rbegin(), m.rend());
  if (f.complex_double_pair) return "R8";
  if (m.empty()) return "R2";
  if (m == std::vector<int>{1, 1, 1, 1}) return "R1";
  if (m == std::vector<int>{1, 1}) return "R3";
  if (m == std::vector<int>{2, 1, 1}) return "R4";
  if (m == std::vector<int>{2}) return "R5";
  if (m == std::vector<int>{2, 2}) return "R6";
  if (m == std::vector<int>{3, 1}) return "R7";
  if (m == std::vector<int>{4}) return "R9";
  throw std::logic_error("impossible root multiplicities for a quartic");
}

void fill_quartic_invariants(PencilFacts& facts) {
  IntegerPencil ip(facts.a, facts.b);
  std::array<Integer, 5> c;
  facts.f = char_poly_of(ip, &c);
  // D_k is homogeneous of degree 2, 4, 6 (E: 3) in the coefficients and c_i = L^4 f_i, so
  // D_k(f) = D_k(c) / L^(4 deg): integer arithmetic, one division each.
  auto inv = quartic_invariants(c);
  Integer l4 = ip.l * ip.l * ip.l * ip.l, l8 = l4 * l4, l12 = l8 * l4;
  facts.d2 = Rational(inv.d2, l8);
  facts.d3 = Rational(inv.d3, l8 * l8);
  facts.d4 = Rational(inv.d4, l12 * l12);
  facts.e = Rational(inv.e, l12);
  std::string rp =
      root_pattern_from_signs(inv.d2.sign(), inv.d3.sign(), inv.d4.sign(), inv.e.sign());
  // Two routes to the same label: Yang's sign conditions and the multiplicities found by the
  // square-free factorisation. A disagreement is our bug.
  if (!facts.root_pattern.empty() && facts.root_pattern != rp)
    throw std::logic_error("root pattern " + rp + " from D2..E contradicts " + facts.root_pattern);
  facts.root_pattern = rp;
}

std::string root_pattern_from_signs(int sd2, int sd3, int sd4, int se) {
  if (sd4 > 0) return (sd3 > 0 && sd2 > 0) ? "R1" : "R2";
  if (sd4 < 0) return "R3";
  if (sd3 > 0) return "R4";
  if (sd3 < 0) return "R5";
  if (sd2 > 0) return se == 0 ? "R6" : "R7";
  if (sd2 < 0) return "R8";
  return "R9";
}

namespace {

Mat4 member(const Rational& t, const Mat4& a, const Mat4& b) {
  Mat4 m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = t * a[i][j] - b[i][j];
  return m;
}

struct QMat {
  fmpq_mat_t m;
  QMat() { fmpq_mat_init(m, 4, 4); }
  explicit QMat(const Mat4& x) : QMat() {
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        fmpq_set(fmpq_mat_entry(m, static_cast<slong>(i), static_cast<slong>(j)), x[i][j].raw());
  }
  QMat(const QMat&) = delete;
  QMat& operator=(const QMat&) = delete;
  ~QMat() { fmpq_mat_clear(m); }
};

// X = A^-1 B (A invertible).
void a_inv_b(QMat& x, const Mat4& a, const Mat4& b) {
  QMat qa(a), qb(b);
  if (!fmpq_mat_solve_fraction_free(x.m, qa.m, qb.m))
    throw std::logic_error("A is singular after re-basing");
}

// g2 X^2 + g1 X + g0 I == 0 ?
bool quadratic_annihilates(const QMat& x, const UPolyZ& g) {
  QMat x2, acc;
  fmpq_mat_mul(x2.m, x.m, x.m);
  fmpq_t c;
  fmpq_init(c);
  fmpz_poly_get_coeff_fmpz(fmpq_numref(c), g.raw(), 2);
  fmpz_one(fmpq_denref(c));
  fmpq_mat_scalar_mul_fmpz(acc.m, x2.m, fmpq_numref(c));
  QMat t;
  fmpz_poly_get_coeff_fmpz(fmpq_numref(c), g.raw(), 1);
  fmpq_mat_scalar_mul_fmpz(t.m, x.m, fmpq_numref(c));
  fmpq_mat_add(acc.m, acc.m, t.m);
  fmpz_poly_get_coeff_fmpz(fmpq_numref(c), g.raw(), 0);
  for (slong i = 0; i < 4; ++i)
    fmpq_add(fmpq_mat_entry(acc.m, i, i), fmpq_mat_entry(acc.m, i, i), c);
  bool zero = fmpq_mat_is_zero(acc.m);
  fmpq_clear(c);
  return zero;
}

// (X - theta I)^2 == 0 ?
bool nilpotent_square_zero(const QMat& x, const Rational& theta) {
  QMat n, n2;
  fmpq_mat_set(n.m, x.m);
  for (slong i = 0; i < 4; ++i)
    fmpq_sub(fmpq_mat_entry(n.m, i, i), fmpq_mat_entry(n.m, i, i), theta.raw());
  fmpq_mat_mul(n2.m, n.m, n.m);
  return fmpq_mat_is_zero(n2.m);
}

// Inertia of theta*A - B at theta = a + b sqrt(d) (root of the irreducible quadratic g):
// the charpoly coefficients c_k(l) of l*A - B as polynomials, reduced mod g, evaluated in
// Q(sqrt d) with exact signs.
Inertia inertia_at_quadratic(const Mat4& a, const Mat4& b, const UPolyZ& g,
                             const QuadraticNumber& theta) {
  Mat4T<UPolyQ> m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = UPolyQ::linear(a[i][j], -b[i][j]);
  auto c = charpoly_coeffs(m);
  UPolyQ gq;
  fmpq_poly_set_fmpz_poly(gq.raw_mut(), g.raw());
  int s[4];
  for (size_t k = 0; k < 4; ++k) {
    UPolyQ r = c[k].rem(gq); // alpha + beta*l
    Rational alpha = r.coeff(0), beta = r.coeff(1);
    QuadraticNumber v{alpha + beta * theta.a, beta * theta.b, theta.d};
    s[k] = v.sign();
  }
  return inertia_from_charpoly_signs(s);
}

// The real root of the quadratic g = c2 l^2 + c1 l + c0 lying in (lo, hi).
void locate_in_quadratic(const UPolyZ& g, const Rational& lo, const Rational& hi, RootFacts& r) {
  Rational c2(g.coeff(2)), c1(g.coeff(1)), c0(g.coeff(0));
  Rational disc = c1 * c1 - Rational(4) * c2 * c0;
  // disc is an integer here (g has integer coefficients).
  Integer dn = disc.num();
  Integer s;
  fmpz_sqrt(s.raw_mut(), dn.raw());
  Rational mid = -c1 / (Rational(2) * c2);
  if (s * s == dn) {
    Rational r1 = (-c1 - Rational(s)) / (Rational(2) * c2),
             r2 = (-c1 + Rational(s)) / (Rational(2) * c2);
    r.rational_value = (lo < r1 && r1 < hi) ? r1 : r2;
    return;
  }
  // Irrational: theta = mid + sgn * sqrt(disc) / (2 c2); the side of `mid` tells the sign.
  Rational l = lo, h = hi;
  int side;
  if (h <= mid)
    side = -1;
  else if (mid <= l)
    side = 1;
  else
    side = (g.sign_at(mid) == g.sign_at(h)) ? -1 : 1; // the root is in (l, mid) or (mid, h)
  Rational coef = Rational(1) / (Rational(2) * c2);
  if (c2.sign() < 0) coef = -coef;
  r.quadratic = QuadraticNumber{mid, side > 0 ? coef : -coef, dn};
}

} // namespace

PencilFacts analyze_pencil_exact(const Mat4& a0, const Mat4& b0) {
  PencilFacts out;
  out.a = a0;
  out.b = b0;
  if (proportional(a0, b0) || proportional(b0, a0)) {
    out.kind = PencilKind::Coincident;
    return out;
  }
  std::optional<IntegerPencil> ip(std::in_place, a0, b0);
  std::array<Integer, 5> fi;
  out.f = char_poly_of(*ip, &fi);
  if (out.f.is_zero()) {
    out.kind = PencilKind::Degenerate;
    return out;
  }
  if (out.f.degree() < 4) {
    // lambda = infinity is a root: move it to a finite place (research §1.1).
    for (long k = 0;; ++k) {
      long t = (k % 2 == 0) ? k / 2 : -(k + 1) / 2; // 0, -1, 1, -2, 2, ...
      if (!out.f.evaluate(Rational(t)).is_zero()) {
        out.rebased = true;
        out.rebase_t = t;
        out.a = member(Rational(t), a0, b0);
        out.b = core::scaled(a0, Rational(-1));
        break;
      }
    }
    // The rebased pencil's polynomial from f's, not from its matrices (a second Laplace
    // expansion was ~10% of an exact classification; most natural quadrics are singular):
    // det(l (tA - B) + A) = det((lt + 1) A - l B) = sum_k f_k (lt + 1)^k l^(4 - k). With
    // fi = L^4 f (L > 0, the old pencil's common denominator) this is an integer polynomial, a
    // positive multiple of the new det: what fi is used for below (its primitive part, its
    // signs). out.f is it divided by L^4: the same canonical polynomial as the expansion's.
    const Integer l4 = ip->l * ip->l * ip->l * ip->l;
    UPolyZ g, term, lin, lpow;
    fmpz_poly_set_coeff_si(lin.raw_mut(), 1, out.rebase_t); // l t + 1
    fmpz_poly_set_coeff_si(lin.raw_mut(), 0, 1);
    for (size_t k = 0; k < 5; ++k) {
      if (fi[k].is_zero()) continue;
      fmpz_poly_pow(term.raw_mut(), lin.raw(), k);
      fmpz_poly_shift_left(term.raw_mut(), term.raw(), static_cast<slong>(4 - k));
      fmpz_poly_scalar_mul_fmpz(term.raw_mut(), term.raw(), fi[k].raw());
      fmpz_poly_add(g.raw_mut(), g.raw(), term.raw());
    }
    for (size_t k = 0; k < 5; ++k)
      fmpz_poly_get_coeff_fmpz(fi[k].raw_mut(), g.raw(), static_cast<slong>(k));
    fmpq_poly_set_fmpz_poly(out.f.raw_mut(), g.raw());
    fmpq_poly_scalar_div_fmpz(out.f.raw_mut(), out.f.raw(), l4.raw());
    ip.emplace(out.a, out.b); // the rebased integer matrices (indices, members)
  }
  // D2, D3, D4, E are report data: fill_quartic_invariants computes them on demand.

  // Square-free decomposition f = c * prod g_m^m; isolate the real roots of prod g_m.
  UPolyZ fz = UPolyZ::from_coeffs(std::vector<Integer>(fi.begin(), fi.end())).primitive_part();
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  fmpz_poly_factor_squarefree(fac, fz.raw());
  std::vector<UPolyZ> parts;
  std::vector<int> exps;
  UPolyZ sqfree;
  fmpz_poly_set_si(sqfree.raw_mut(), 1);
  for (slong i = 0; i < fac->num; ++i) {
    UPolyZ g;
    fmpz_poly_set(g.raw_mut(), fac->p + i);
    g = g.primitive_part();
    if (g.degree() < 1) continue;
    fmpz_poly_mul(sqfree.raw_mut(), sqfree.raw(), g.raw());
    parts.push_back(g);
    exps.push_back(static_cast<int>(fac->exp[i]));
  }
  fmpz_poly_factor_clear(fac);

  // Every square-free factor linear (the multiple roots of a degenerate pencil are rational,
  // and so, often, is the rest): the roots are known exactly, no isolation (45% of an exact
  // analysis of pipes posed in doubles, whose coefficients have hundreds of bits).
  const bool all_linear =
      std::all_of(parts.begin(), parts.end(), [](const UPolyZ& g) { return g.degree() == 1; });
  RootSeparation sep;
  if (all_linear) {
    std::vector<Rational> roots;
    for (const UPolyZ& g : parts)
      roots.push_back(Rational(-g.coeff(0), g.coeff(1)));
    sep = separate_rational_roots(std::move(roots));
  } else {
    sep = isolate_real_roots(sqfree);
  }
  out.isolation_fallback = sep.used_fallback;
  out.samples = sep.separators;
  int real_with_mult = 0;
  for (size_t i = 0; i + 1 < sep.separators.size(); ++i) {
    RootFacts r;
    r.lo = sep.separators[i];
    r.hi = sep.separators[i + 1];
    for (size_t j = 0; j < parts.size(); ++j)
      if (parts[j].sign_at(r.lo) != parts[j].sign_at(r.hi)) {
        r.multiplicity = exps[j];
        r.factor = parts[j];
        break;
      }
    if (r.factor.degree() == 1)
      r.rational_value = Rational(-r.factor.coeff(0), r.factor.coeff(1));
    else if (r.multiplicity >= 2) // then deg <= 2 (4 = sum of m * deg)
      locate_in_quadratic(r.factor, r.lo, r.hi, r);
    real_with_mult += r.multiplicity;
    out.real_roots.push_back(std::move(r));
  }
  out.complex_roots = 4 - real_with_mult;
  for (size_t j = 0; j < parts.size(); ++j)
    if (exps[j] == 2 && parts[j].degree() == 2 && count_real_roots(parts[j]) == 0)
      out.complex_double_pair = true;

  out.root_pattern = root_pattern_from_multiplicities(out);

  // Index on every interval between real roots.
  // sign(det(p*a - q*b)) = sign f(s): evaluate the integer f (not its primitive part, whose
  // sign may be flipped).
  UPolyZ fint = UPolyZ::from_coeffs(std::vector<Integer>(fi.begin(), fi.end()));
  for (const auto& s : out.samples)
    out.indices.push_back(ip->index_at(s, fint.sign_at(s)));
  for (size_t i = 0; i < out.indices.size(); ++i)
    if (out.indices[i] == 0 || out.indices[i] == 4) out.definite_member = true;

  std::optional<QMat> x; // A^-1 B, computed only when a test needs it
  auto need_x = [&]() -> const QMat& {
    if (!x) {
      x.emplace();
      a_inv_b(*x, out.a, out.b);
    }
    return *x;
  };
  for (size_t i = 0; i < out.real_roots.size(); ++i) {
    RootFacts& r = out.real_roots[i];
    r.index_left = out.indices[i];
    r.index_right = out.indices[i + 1];
    if (r.multiplicity == 1) {
      r.rank = 3;
      r.sigma =
          Inertia{std::min(r.index_left, r.index_right), 4 - std::max(r.index_left, r.index_right)};
    } else if (r.rational_value) {
      const Mat4 m = ip->member_multiple(*r.rational_value);
      // The rank from the same exact characteristic polynomial as the inertia: a symmetric
      // matrix's nonzero eigenvalues are its rank, and Descartes' counts are exact for a
      // real-rooted polynomial (a separate elimination, rank_exact, was ~5% of this call).
      r.sigma = inertia_descartes(m);
      r.rank = r.sigma.rank();
      if (r.multiplicity == 4 && r.rank == 2)
        out.quadruple_n2_zero = nilpotent_square_zero(need_x(), *r.rational_value);
    } else {
      // Conjugate real double roots: f = c g^2; rank 2 iff A^-1 B is annihilated by g.
      bool split = quadratic_annihilates(need_x(), r.factor);
      out.minimal_poly_split = split;
      r.rank = split ? 2 : 3;
      r.sigma = inertia_at_quadratic(out.a, out.b, r.factor, *r.quadratic);
    }
  }
  if (out.complex_double_pair) {
    for (size_t j = 0; j < parts.size(); ++j)
      if (exps[j] == 2 && parts[j].degree() == 2)
        out.minimal_poly_split = quadratic_annihilates(need_x(), parts[j]);
  }
  return out;
}

RootFacts simplest_root_form(RootFacts r) {
  if (r.rational_value || r.quadratic || r.factor.degree() < 2 || !(r.lo < r.hi)) return r;
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  fmpz_poly_factor(fac, r.factor.raw());
  std::optional<UPolyZ> holder; // the irreducible factor holding the root
  for (slong i = 0; i < fac->num && !holder; ++i) {
    UPolyZ g;
    fmpz_poly_set(g.raw_mut(), fac->p + i);
    if (g.degree() < 1) continue;
    const int sl = g.sign_at(r.lo), sh = g.sign_at(r.hi);
    if (sl != 0 && sh != 0 && sl != sh) holder = std::move(g);
  }
  fmpz_poly_factor_clear(fac);
  if (!holder || holder->degree() == r.factor.degree()) return r; // irreducible already
  const UPolyZ g = holder->primitive_part();                      // positive leading coefficient
  r.factor = g;
  if (g.degree() == 1)
    r.rational_value = Rational(-g.coeff(0), g.coeff(1));
  else if (g.degree() == 2)
    locate_in_quadratic(g, r.lo, r.hi, r);
  return r;
}

} // namespace surfcert::algebra
