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
#include <complex>
#include <optional>

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
  double inner[3];
  const size_t ninner = algebra::critical_point_separators(fd, 4, static_cast<size_t>(k), inner);
  if (ninner != static_cast<size_t>(k - 1)) return 0;
  double bound = 0;
  for (int i = 0; i < 4; ++i)
    bound = std::max(bound, std::fabs(fd[i] / fd[4]));
  bound = 2 * (1 + bound);
  size_t n = 0;
  seps[n++] = -bound;
  for (size_t i = 0; i < ninner; ++i)
    seps[n++] = inner[i];
  seps[n++] = bound;
  return n;
}

I horner(const std::array<I, 5>& f, double x) {
  I r = f[4];
  for (int i = 3; i >= 0; --i)
    r = r * x + f[static_cast<size_t>(i)];
  return r;
}

// The index (number of positive eigenvalues) of the member s*A - B, whose determinant has the
// certain sign fsign (+-1): Jacobi's rule on the leading minors when they are certainly
// nonzero, else Descartes on the interval characteristic polynomial. False when a sign it
// needs is not certain.
bool index_at(const Mat4T<I>& a, const Mat4T<I>& b, double s, int fsign, int& index) {
  // The leading 3x3 block of s*A - B first: Jacobi's rule needs no more.
  Mat4T<I> m;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = i; j < 3; ++j)
      m[i][j] = m[j][i] = a[i][j] * s - b[i][j];
  // Jacobi's rule: with leading minors d1, d2, d3 certainly nonzero and d4 = f(s) (its sign
  // is certain), the negative eigenvalues are the sign changes of 1, d1..d4.
  I d2 = m[0][0] * m[1][1] - m[0][1] * m[0][1];
  I d3 = m[2][0] * (m[0][1] * m[1][2] - m[0][2] * m[1][1]) -
         m[2][1] * (m[0][0] * m[1][2] - m[0][2] * m[1][0]) + m[2][2] * d2;
  int lead[5] = {1, isign(m[0][0]), isign(d2), isign(d3), fsign};
  bool certain = true;
  for (int t = 1; t < 4; ++t)
    certain = certain && (lead[t] == 1 || lead[t] == -1);
  if (certain) {
    int neg = 0;
    for (int t = 0; t < 4; ++t)
      neg += lead[t] != lead[t + 1];
    index = 4 - neg;
    return true;
  }
  for (size_t i = 0; i < 4; ++i) // a leading minor may vanish: Descartes instead
    m[i][3] = m[3][i] = a[i][3] * s - b[i][3];
  auto c = algebra::charpoly_coeffs(m);
  int sg[4];
  for (size_t t = 0; t < 4; ++t) {
    sg[t] = isign(c[t]);
    if (sg[t] == 2) return false;
  }
  index = algebra::inertia_from_charpoly_signs(sg).p;
  return true;
}

// The simple root in the gap `gap` of the facts' samples: its interval, the indices on both
// sides and the inertia they imply. Re-based because det A = 0, l = 0 is a root exactly
// (f(0) = det(-b') = det A), the one of the gap around 0 (a separator at 0 would have had no
// certain sign); reported exact, as the exact path's linear factor l reports it.
RootFacts simple_root(const PencilFacts& out, size_t gap) {
  RootFacts r;
  r.lo = out.samples[gap];
  r.hi = out.samples[gap + 1];
  r.index_left = out.indices[gap];
  r.index_right = out.indices[gap + 1];
  r.sigma =
      Inertia{std::min(r.index_left, r.index_right), 4 - std::max(r.index_left, r.index_right)};
  if (out.rebased && r.lo.sign() < 0 && r.hi.sign() > 0) {
    r.rational_value = Rational(0);
    fmpz_poly_set_coeff_si(r.factor.raw_mut(), 1, 1);
  }
  return r;
}

// Whether q is a plane n . x + d = 0 with n != 0 exactly (its matrix of rank 2), read without
// forming exact rationals where that can be avoided: no posed shape is a plane; a matrix of
// doubles is read through its exact symmetric part (d_ij + d_ji = 0 exactly iff d_ji = -d_ij).
bool proper_plane(const core::QuadricMatrix& q) {
  if (q.shape()) return false;
  if (const core::DoubleMat4* d = q.double_matrix()) {
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        if ((*d)[i][j] != -(*d)[j][i]) return false;
    for (size_t i = 0; i < 3; ++i)
      if ((*d)[i][3] != -(*d)[3][i]) return true;
    return false;
  }
  const Mat4& m = q.matrix();
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      if (!m[i][j].is_zero()) return false;
  for (size_t i = 0; i < 3; ++i)
    if (!m[i][3].is_zero()) return true;
  return false;
}

// The root's exact value v and its primitive linear factor with a positive leading
// coefficient: den * l - num.
void set_rational_root(RootFacts& r, const Rational& v) {
  r.rational_value = v;
  fmpz_poly_set_coeff_fmpz(r.factor.raw_mut(), 1, fmpq_denref(v.raw()));
  fmpz_t num;
  fmpz_init(num);
  fmpz_neg(num, fmpq_numref(v.raw()));
  fmpz_poly_set_coeff_fmpz(r.factor.raw_mut(), 0, num);
  fmpz_clear(num);
}

// Whether q is singular at a point at infinity (d, 0), exactly: det q = 0 and det of its
// quadratic part = 0 (with rank 2 the quadratic part's kernel d has b . d = 0 whenever det q = 0,
// b q's linear part; with rank <= 1 its kernel meets b's orthogonal plane): a cylinder of any
// kind (or something of lower rank). For a posed shape by construction (its local form lacks a
// square term and it is singular), otherwise from the exact 3x3 determinant.
bool singular_at_infinity(const core::QuadricMatrix& q) {
  if (!q.singular()) return false;
  if (const core::ShapeSpec* sp = q.shape()) {
    const core::LocalForm lf = core::local_form(sp->type);
    return lf.q_sign[0] == 0 || lf.q_sign[1] == 0 || lf.q_sign[2] == 0;
  }
  const Mat4& m = q.matrix();
  const Rational d = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return d.is_zero();
}

// A plane against a quadric singular at a point v at infinity (a cylinder): v lies on the plane's
// quadric (n . x + d) w = 0 too, so the pencil's member with that singular point has a multiple
// root (f'(phi) = c v^T P v = 0 for a member of rank 3, adj = c v v^T), as has the plane's: with
// f of degree 4 and not identically zero, f = c (l - theta)^2 (l - phi)^2 exactly, both
// parameters exact (0 and -1/t in the re-based basis). Read here: c = f's leading coefficient,
// whose sign is certain; separators around theta and phi with sign f = sign c; the indices by
// index_at; the plane's root rank 2, inertia (1, 1); phi's member rank 3 (its charpoly's linear
// coefficient certainly nonzero, its determinant 0 exactly) with the inertia Descartes reads
// from its other coefficients' certain signs. False (the exact path) when a sign is not
// certain, or when g's enclosure at phi excludes 0 (the premise does not hold: never expected).
bool two_double_roots_facts(const Mat4T<I>& a, const Mat4T<I>& b, const I& g2, const I& g1,
                            const I& g0, const Rational& theta, const Rational& phi,
                            PencilFacts& out) {
  if (theta == phi) return false;
  const int sc = isign(g2);
  if (sc != 1 && sc != -1) return false;
  const I ph = enclose(phi);
  const int at_phi = isign((g2 * ph + g1) * ph + g0);
  if (at_phi != 2 && at_phi != 0) return false; // g(phi) != 0: not the premise's pencil
  const Rational& r1 = theta < phi ? theta : phi;
  const Rational& r2 = theta < phi ? phi : theta;
  // Separators: dyadics, exactly checked around the two roots.
  const double d1 = r1.to_double_approx(), d2 = r2.to_double_approx();
  const double w = std::max({1.0, std::fabs(d1), std::fabs(d2)});
  std::array<double, 3> seps{d1 - w, 0.5 * d1 + 0.5 * d2, d2 + w};
  if (!std::isfinite(seps[0]) || !std::isfinite(seps[2])) return false;
  const std::array<Rational, 3> rs{Rational::exact_from_double(seps[0]),
                                   Rational::exact_from_double(seps[1]),
                                   Rational::exact_from_double(seps[2])};
  if (!(rs[0] < r1 && r1 < rs[1] && rs[1] < r2 && r2 < rs[2])) return false;
  out.indices.reserve(3);
  out.samples.reserve(3);
  for (size_t i = 0; i < 3; ++i) {
    int index = 0;
    if (!index_at(a, b, seps[i], sc, index)) return false;
    out.indices.push_back(index);
    out.samples.push_back(rs[i]);
  }
  for (int idx : out.indices)
    if (idx == 0 || idx == 4) out.definite_member = true;
  // phi's member in intervals: inertia from its charpoly, det = 0 exactly.
  Mat4T<I> m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = a[i][j] * ph - b[i][j];
  const auto c = algebra::charpoly_coeffs(m);
  int sg[4] = {0, isign(c[1]), isign(c[2]), isign(c[3])};
  if (sg[1] != 1 && sg[1] != -1) return false; // rank 3 not certain
  if (sg[2] == 2 || sg[3] == 2) return false;
  const Inertia phi_sigma = algebra::inertia_from_charpoly_signs(sg);
  if (phi_sigma.rank() != 3) return false;
  for (size_t i = 0; i < 2; ++i) {
    RootFacts r;
    const Rational& v = i == 0 ? r1 : r2;
    r.lo = out.samples[i];
    r.hi = out.samples[i + 1];
    r.index_left = out.indices[i];
    r.index_right = out.indices[i + 1];
    r.multiplicity = 2;
    const bool plane_root = v == theta;
    r.rank = plane_root ? 2 : 3;
    r.sigma = plane_root ? Inertia{1, 1} : phi_sigma;
    set_rational_root(r, v);
    out.real_roots.push_back(std::move(r));
  }
  out.complex_roots = 0;
  out.root_pattern = "R6";
  return true;
}

// A separator candidate between consecutive roots lo < hi of a pencil's polynomial: 0 when it
// lies between them (kept a quarter of the gap from each), else on the side of the root of
// smaller magnitude, within half of 1 + its size. A midpoint or critical point beside a root
// near 1e17 (a cone or cylinder posed in doubles) lies at ~1e17, where the index of s A - B is
// not certain in intervals beside A's tiny eigenvalue. A candidate only: the callers prove it.
double moderate_separator(double lo, double hi) {
  const double gap = hi - lo;
  if (lo < 0 && hi > 0) return std::min(std::max(0.0, lo + 0.25 * gap), hi - 0.25 * gap);
  if (std::fabs(lo) <= std::fabs(hi)) return lo + 0.5 * std::min(gap, 1 + std::fabs(lo));
  return hi - 0.5 * std::min(gap, 1 + std::fabs(hi));
}

// The index of s A - B at s beyond every root of det(l A - B) (above them, or below), A
// nonsingular exactly: A's inertia above and -A's below (no root is crossed on the way to
// infinity, where (s A - B) / s tends to A). Read exactly (LDL^T), once, where the intervals
// cannot tell at such an s. The caller must have proved every root lies on the other side.
class IndexBeyondRoots {
public:
  explicit IndexBeyondRoots(const core::QuadricMatrix& a) : a_(a) {}
  bool index(bool above, int& out) {
    if (!read_) inertia_ = algebra::inertia_ldlt(a_.matrix()), read_ = true;
    if (inertia_.p + inertia_.n != 4) return false; // never: det A != 0
    out = above ? inertia_.p : inertia_.n;
    return true;
  }

private:
  const core::QuadricMatrix& a_;
  Inertia inertia_{};
  bool read_ = false;
};

// The pencil l*a - b with a plane among its members, at l = theta (rational, exact): that
// member has rank 2, so f = (l - theta)^2 g(l) exactly, g = f / (l - theta)^2 a quadratic
// (synthetic division in intervals, theta enclosed). The facts follow when these signs are
// certain: g(theta) != 0 (theta exactly double), the discriminant of g (two simple real roots
// or none), g at separators around theta and g's float roots (one sign change in each gap of a
// root of g; sign f = sign g away from theta); the indices as for simple roots. The double
// root's rank is 2 and its inertia (1, 1) (a plane's matrix [[0, n/2], [n^T/2, d]], n != 0, has
// one positive and one negative eigenvalue; so has any nonzero multiple). False: the exact path.
bool plane_member_facts(const Mat4T<I>& a, const Mat4T<I>& b, const std::array<I, 5>& f,
                        const Rational& theta, const std::optional<Rational>& phi, PencilFacts& out,
                        const core::QuadricMatrix* a_exact = nullptr) {
  const I th = enclose(theta);
  const I g2 = f[4], g1 = f[3] + I(2) * th * g2, g0 = f[2] + I(2) * th * g1 - th * th * g2;
  const int s2 = isign(g2);
  if (s2 != 1 && s2 != -1) return false;
  const int at_theta = isign((g2 * th + g1) * th + g0);
  if (at_theta != 1 && at_theta != -1) return false; // theta may be a root of g too
  // The other quadric singular at infinity (phi given): g = g2 (l - phi)^2 exactly.
  if (phi) return two_double_roots_facts(a, b, g2, g1, g0, theta, *phi, out);
  const int sd = isign(g1 * g1 - I(4) * g2 * g0);
  if (sd != 1 && sd != -1) return false; // g may have a double root
  const double td = CGAL::to_double(th);
  // The points to separate: theta and g's float roots, in increasing order.
  std::vector<double> pts{td};
  if (sd > 0) {
    const double c2 = CGAL::to_double(g2), c1 = CGAL::to_double(g1), c0 = CGAL::to_double(g0);
    const double disc = c1 * c1 - 4 * c2 * c0;
    if (!(disc > 0)) return false;
    const double qq = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
    if (!(qq != 0)) return false;
    pts.push_back(qq / c2);
    pts.push_back(c0 / qq);
  }
  std::sort(pts.begin(), pts.end());
  double w = 1;
  for (double x : pts)
    w = std::max(w, 1 + std::fabs(x));
  // (moderate_separator: a cylinder posed in doubles puts a root of g near 1e17, and a
  // midpoint at ~5e16 left the index uncertain.)
  std::vector<double> seps{pts.front() - w};
  for (size_t i = 1; i < pts.size(); ++i)
    seps.push_back(moderate_separator(pts[i - 1], pts[i]));
  seps.push_back(pts.back() + w);
  for (size_t i = 0; i < seps.size(); ++i)
    if (!std::isfinite(seps[i]) || (i > 0 && !(seps[i - 1] < seps[i]))) return false;
  // theta in its gap, strictly (exact comparisons), and g's sign at every separator certain.
  size_t theta_gap = seps.size();
  for (size_t i = 0; i + 1 < seps.size(); ++i)
    if (Rational::exact_from_double(seps[i]) < theta &&
        theta < Rational::exact_from_double(seps[i + 1]))
      theta_gap = i;
  if (theta_gap == seps.size()) return false;
  std::vector<int> gsign(seps.size());
  for (size_t i = 0; i < seps.size(); ++i) {
    const double x = seps[i];
    gsign[i] = isign((g2 * x + g1) * x + g0);
    if (gsign[i] != 1 && gsign[i] != -1) return false;
  }
  // g's two real roots (sd > 0) in the two other gaps: a sign change in each; theta's gap then
  // holds none, and shows no change.
  for (size_t i = 0; i + 1 < seps.size(); ++i)
    if ((gsign[i] != gsign[i + 1]) != (i != theta_gap)) return false;
  out.indices.reserve(seps.size());
  out.samples.reserve(seps.size());
  std::optional<IndexBeyondRoots> beyond;
  if (a_exact) beyond.emplace(*a_exact);
  for (size_t i = 0; i < seps.size(); ++i) {
    int index = 0;
    // At an outer separator (theta and g's roots are proved inside them) A's inertia decides
    // when the intervals cannot (A nonsingular: given only when not re-based).
    const bool outer = i == 0 || i + 1 == seps.size();
    if (!index_at(a, b, seps[i], gsign[i], index) &&
        !(outer && beyond && beyond->index(i != 0, index)))
      return false;
    out.indices.push_back(index);
    out.samples.push_back(Rational::exact_from_double(seps[i]));
  }
  for (int idx : out.indices)
    if (idx == 0 || idx == 4) out.definite_member = true;
  for (size_t i = 0; i + 1 < seps.size(); ++i) {
    RootFacts r = simple_root(out, i);
    if (i == theta_gap) { // the plane's root: exact, double, rank 2, inertia (1, 1)
      r.multiplicity = 2;
      r.rank = 2;
      r.sigma = Inertia{1, 1};
      set_rational_root(r, theta);
    }
    out.real_roots.push_back(std::move(r));
  }
  out.complex_roots = sd > 0 ? 0 : 2;
  out.root_pattern = sd > 0 ? "R4" : "R5";
  return true;
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
  Mat4T<I> a = enclose(qa), b = enclose(qb);
  auto f = algebra::pencil_char_coeffs(a, b);
  // det A's enclosure straddling 0 while det A != 0 exactly: a cone, a cylinder posed in
  // doubles, whose rounding leaves det A tiny (1e-17 of its entries' scale) but nonzero. The
  // exact path does not re-base then (its pencil has a root near infinity, simple); the exact
  // determinant, enclosed, gives f[4] its certain sign, and the analysis below proceeds as for
  // any quartic (every such pair once went to the exact path: ~60% of a cone-plane pair posed in
  // doubles). The same for det B = f[0] (a root near 0).
  if (isign(f[4]) == 2 && !qa.singular()) f[4] = enclose(core::det(qa.matrix()));
  if (isign(f[0]) == 2 && !qb.singular()) f[0] = enclose(core::det(qb.matrix()));
  if (isign(f[4]) == 2 || isign(f[4]) == 0) {
    // det A = 0 (a cone, a cylinder, a plane ...: most natural quadrics; every such pair once
    // went to the exact path): re-based here as the exact path does, to a' = t A - B, b' = -A
    // with the first t of 0, -1, 1, -2, 2, ... where f(t) = det(tA - B) != 0, so that the facts
    // are the exact path's (the same basis, the same t). Every t skipped must be a proven zero
    // of f: det A itself and f(0) = det B exactly (QuadricMatrix::singular, asked only here);
    // any other f(t) whose sign is not certain leaves the pencil to the exact path.
    if (!qa.singular()) return false; // det A != 0, not certain in intervals
    std::optional<long> base;
    for (long k = 0; k < 16 && !base; ++k) {
      const long t = (k % 2 == 0) ? k / 2 : -(k + 1) / 2; // the exact path's order
      const int sg = isign(horner(f, static_cast<double>(t)));
      if (sg == 1 || sg == -1)
        base = t;
      else if (sg == 2 && !(t == 0 && qb.singular())) // sg == 0: the enclosure is {0}, a proof
        return false;
    }
    if (!base) return false;
    const double t = static_cast<double>(*base); // a small integer: exact in double
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        const I ta = a[i][j] * t - b[i][j];
        b[i][j] = -a[i][j];
        a[i][j] = ta;
      }
    f = algebra::pencil_char_coeffs(a, b);
    // Re-based at t = 0 with det B != 0 exactly (a plane or a cone against a cone posed in
    // doubles, whose det B is tiny): the new leading coefficient is det(-B) = det B, the new
    // constant det(A) = 0 (A singular: the re-basing's premise), both exact.
    if (*base == 0 && isign(f[4]) == 2) f[4] = enclose(core::det(qb.matrix()));
    if (isign(f[0]) == 2) f[0] = I(0);
    if (isign(f[4]) == 2 || isign(f[4]) == 0) return false; // f(t) != 0 was certain; wider now
    out.rebased = true;
    out.rebase_t = *base;
  }
  // A plane among the members (a plane section: a plane against any quadric): its root is
  // double by construction, which D4 cannot show in intervals; read as f = (l - theta)^2 g.
  // Not re-based, b is the member at l = 0; re-based, -A is, and B sits at l = -1/t (t != 0:
  // t = 0 was skipped, det B being 0).
  // With the other quadric singular at a point at infinity (a cylinder; necessarily singular,
  // so the pencil is re-based), its own parameter is a second double root: 0 for A, -1/t for B
  // (t != 0 only when det B = 0 was proved).
  if (!out.rebased && proper_plane(qb))
    return plane_member_facts(a, b, f, Rational(0), std::nullopt, out, &qa);
  if (out.rebased && proper_plane(qa)) {
    std::optional<Rational> phi;
    if (out.rebase_t != 0 && singular_at_infinity(qb)) phi = Rational(-1) / Rational(out.rebase_t);
    return plane_member_facts(a, b, f, Rational(0), phi, out);
  }
  if (out.rebased && proper_plane(qb)) {
    std::optional<Rational> phi;
    if (singular_at_infinity(qa)) phi = Rational(0);
    return plane_member_facts(a, b, f, Rational(-1) / Rational(out.rebase_t), phi, out);
  }
  // D4 first: D3 and D2 matter only when D4 > 0 (E never here).
  const algebra::detail::QuarticTerms<I> q(f);
  int s4 = isign(q.D4());
  if (s4 == 0 || s4 == 2) return false; // possibly a multiple root: exact path
  int k;
  if (s4 < 0) {
    k = 2;
  } else {
    int s3 = isign(q.D3()), s2 = isign(q.D2());
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
  int fsign[5] = {0, 0, 0, 0, 0};
  // k + 1 candidates with certain, alternating signs of f (and fsign set), else false.
  auto proves = [&](size_t n) {
    if (n != static_cast<size_t>(k) + 1) return false;
    int prev = 0;
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(seps[i]) || (i > 0 && !(seps[i - 1] < seps[i]))) return false;
      const int sg = isign(horner(f, seps[i]));
      if (sg == 0 || sg == 2 || (i > 0 && sg == prev)) return false;
      fsign[i] = sg; // = sign det(s*A - B), reused by Jacobi's rule below
      prev = sg;
    }
    return true;
  };
  // Second candidates, from the k real-looking roots (Aberth, in doubles): in each gap the
  // point nearer the root of smaller magnitude (within half of 1 + its magnitude), and the
  // same just outside the extreme roots. The closed-form cubic of f' loses its small roots
  // when f's leading coefficient is tiny, and a critical point between a root near 1 and one
  // near 1e17 (a cone or cylinder posed in doubles) lies at ~1e17, where the index of
  // s A - B is not certain in intervals beside A's tiny eigenvalue.
  auto from_roots = [&]() -> size_t {
    std::vector<double> r;
    for (const auto& z : algebra::approx_complex_roots(std::vector<double>(fd, fd + 5)))
      if (std::isfinite(z.real()) && std::fabs(z.imag()) <= 1e-7 * (1 + std::abs(z)))
        r.push_back(z.real());
    if (r.size() != static_cast<size_t>(k) || k == 0) return 0;
    std::sort(r.begin(), r.end());
    size_t n = 0;
    seps[n++] = r.front() - 0.5 * (1 + std::fabs(r.front()));
    for (size_t i = 0; i + 1 < r.size(); ++i)
      seps[n++] = moderate_separator(r[i], r[i + 1]);
    seps[n++] = r.back() + 0.5 * (1 + std::fabs(r.back()));
    return n;
  };
  const size_t nsep = static_cast<size_t>(k) + 1;
  // Indices: Descartes on the interval charpoly of s*A - B (all signs must be certain).
  // The caller holds a and b: the facts of a filtered answer do not copy them (see
  // complete_report_data), to keep the fast path free of big-number copies.
  IndexBeyondRoots beyond(qa);
  auto indices = [&]() {
    out.indices.clear();
    out.samples.clear();
    out.indices.reserve(nsep);
    out.samples.reserve(nsep);
    for (size_t si = 0; si < nsep; ++si) {
      int index = 0;
      // Beyond every root (the outer candidates: k roots and k + 1 alternating signs put all
      // of them in between) A's inertia decides when the intervals cannot (not re-based:
      // f[4] = det A is certainly nonzero).
      const bool outer = k > 0 && (si == 0 || si + 1 == nsep);
      if (!index_at(a, b, seps[si], fsign[si], index) &&
          !(outer && !out.rebased && beyond.index(si != 0, index)))
        return false;
      out.indices.push_back(index);
      out.samples.push_back(Rational::exact_from_double(seps[si]));
    }
    return true;
  };
  if (!(proves(separator_candidates(fd, k, seps)) && indices()) &&
      !(proves(from_roots()) && indices()))
    return false;
  for (int idx : out.indices)
    if (idx == 0 || idx == 4) out.definite_member = true;
  out.real_roots.reserve(static_cast<size_t>(k));
  for (int i = 0; i < k; ++i) {
    out.real_roots.push_back(simple_root(out, static_cast<size_t>(i)));
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

// Eigenvalues of a symmetric 4x4 matrix (cyclic Jacobi, algebra/eigen4.hpp; values only).
std::array<double, 4> eigenvalues(const Mat4T<double>& m) {
  return algebra::jacobi4_eigenvalues(m);
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

// The index (positive eigenvalues) of a member at a separator: between roots the member is
// regular, so no eigenvalue is zero and none is tested against a tolerance. (A zero test on
// the charpoly's coefficients relative to |member|^4, as before, called a regular but
// ill-conditioned member singular: the node family in a translated pose has entries ~200 and
// a smallest eigenvalue ~1e-5 of them between two roots 0.03 apart.)
int separator_index(const Mat4T<double>& m) {
  int p = 0;
  for (double e : eigenvalues(m))
    p += e > 0 ? 1 : 0;
  return p;
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

using cd = std::complex<double>;

// f^(d)(x) / d! for f = sum c[i] x^i: the d-th Taylor coefficient of f at x.
cd taylor_coeff(const std::array<double, 5>& c, int d, cd x) {
  static const double binom[5][5] = {
      {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
  cd r = 0;
  for (int i = 4; i >= d; --i)
    r = r * x + binom[i][d] * c[static_cast<size_t>(i)];
  return r;
}

// D2, D3, D4, E of the quartic f as symmetric functions of its roots z_i (lead a):
// D2 = a^2 sum_{i<j} (z_i - z_j)^2, D3 = a^4/2 sum over triples of the product of their three
// squared differences, D4 = a^6 prod_{i<j} (z_i - z_j)^2, E = -8 a^3 e3(z - mean z). These are
// the monomial formulas of pencil_poly.hpp (the same polynomials of the coefficients) without
// their cancellation: the monomial terms reach ~|f|^6 and cancel down to a product of squared
// root differences, which for clustered roots is below their rounding error.
algebra::QuarticInvariants<double> invariants_from_roots(double a, const std::vector<cd>& z) {
  cd sq[4][4];
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      sq[i][j] = (z[i] - z[j]) * (z[i] - z[j]);
  cd s2 = 0, s3 = 0, s4 = 1, e3 = 0;
  const cd mean = (z[0] + z[1] + z[2] + z[3]) / 4.0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i + 1; j < 4; ++j) {
      s2 += sq[i][j];
      s4 *= sq[i][j];
      for (size_t k = j + 1; k < 4; ++k) {
        s3 += sq[i][j] * sq[j][k] * sq[i][k];
        e3 += (z[i] - mean) * (z[j] - mean) * (z[k] - mean);
      }
    }
  const double a2 = a * a;
  algebra::QuarticInvariants<double> q;
  q.d2 = a2 * s2.real();
  q.d3 = 0.5 * a2 * a2 * s3.real();
  q.d4 = a2 * a2 * a2 * s4.real();
  q.e = -8 * a2 * a * e3.real();
  return q;
}

// The root structure of f read from its float roots: which roots form one multiple root.
struct RootClusters {
  std::string pattern;                      // "R1".."R9", empty when no reading fits
  std::vector<std::pair<double, int>> real; // real roots (centre, multiplicity), increasing
  int complex_roots = 0;
  cd complex_double{0, 0}; // R8: the refined centre of one of the two double complex roots
};

// A block of m >= 2 float roots is one m-fold root when f is within relative `tol` of a
// polynomial with an m-fold root at the block's centre c: the Taylor coefficients t_0..t_{m-1}
// of f at c, against all of them, are at most tol (the backward error of the multiple root).
// f is the balanced polynomial (analyze_pencil_float): its roots are O(1) when A and B are.
// c starts at the block's mean and is refined by Newton on f^(m-1), of which it is a simple
// root: near an m-fold root f is rounding noise in a band of width ~eps^(1/m) (1e-5 for a
// triple root), so the mean alone can be off by 1e-6 while the test needs c to working
// precision. Returns the backward error (infinity when c cannot be found) and c.
double block_backward_error(const std::array<double, 5>& f, const std::vector<cd>& z,
                            const std::vector<size_t>& block, cd& centre) {
  const int m = static_cast<int>(block.size());
  cd mean = 0;
  for (size_t i : block)
    mean += z[i];
  mean /= static_cast<double>(m);
  double radius = 0;
  for (size_t i : block)
    radius = std::max(radius, std::abs(z[i] - mean));
  cd c = mean;
  for (int it = 0; it < 8; ++it) {
    const cd v = taylor_coeff(f, m - 1, c), dv = static_cast<double>(m) * taylor_coeff(f, m, c);
    if (v == cd(0) || dv == cd(0)) break;
    const cd step = v / dv;
    if (!std::isfinite(step.real()) || !std::isfinite(step.imag())) break;
    c -= step;
  }
  // The float roots of an m-fold root scatter in a band of width ~eps^(1/m), not necessarily
  // around it (both of a double root's float roots can sit 3e-8 to one side): Newton may move
  // that far (1e-4 covers a quadruple root), further means it went elsewhere.
  if (!(std::abs(c - mean) <= 2 * radius + 1e-4 * std::max(1.0, std::abs(mean)))) c = mean;
  centre = c;
  // The block must be the roots near c: a spread-out block centred on another multiple root
  // (0.875 and 1.125 around a double root at 1) passes the Taylor test with the wrong roots.
  for (size_t i = 0; i < z.size(); ++i)
    if (std::find(block.begin(), block.end(), i) == block.end() &&
        !(std::abs(z[i] - c) > 2 * radius))
      return INFINITY;
  double low = 0, all = 0;
  for (int j = 0; j <= 4; ++j) {
    const double t = std::abs(taylor_coeff(f, j, c));
    all += t;
    if (j < m) low += t;
  }
  return all > 0 ? low / all : INFINITY;
}

// The coarsest grouping of the four float roots into multiple roots that the backward-error
// test accepts (among the 15 set partitions; ties by the smallest error) and that reads as a
// real quartic's root pattern. The all-simple grouping always passes the test.
RootClusters cluster_roots(const std::array<double, 5>& f, const std::vector<cd>& z, double tol) {
  RootClusters best;
  size_t best_blocks = 5;
  double best_err = INFINITY;
  int label[4] = {0, 0, 0, 0};
  // Restricted growth strings label[0..3] enumerate the set partitions of {0, 1, 2, 3}.
  for (label[1] = 0; label[1] <= 1; ++label[1])
    for (label[2] = 0; label[2] <= std::max(label[0], label[1]) + 1; ++label[2])
      for (label[3] = 0; label[3] <= std::max({label[0], label[1], label[2]}) + 1; ++label[3]) {
        const int nb = std::max({label[0], label[1], label[2], label[3]}) + 1;
        std::vector<std::vector<size_t>> blocks(static_cast<size_t>(nb));
        for (size_t i = 0; i < 4; ++i)
          blocks[static_cast<size_t>(label[i])].push_back(i);
        double err = 0;
        RootClusters rc;
        int complex_single = 0, complex_double = 0;
        bool ok = true;
        for (const auto& blk : blocks) {
          cd c = z[blk[0]];
          double radius = 0;
          if (blk.size() > 1) {
            const double e = block_backward_error(f, z, blk, c);
            if (!(e <= tol)) {
              ok = false;
              break;
            }
            err = std::max(err, e);
            for (size_t i : blk)
              radius = std::max(radius, std::abs(z[i] - c));
          }
          // Real when the centre is as near the axis as the block's own spread (a block that
          // holds a conjugate pair), or a simple root within rounding of it.
          const bool real = std::fabs(c.imag()) <= radius + 1e-10 * std::max(1.0, std::abs(c));
          if (real)
            rc.real.emplace_back(c.real(), static_cast<int>(blk.size()));
          else if (blk.size() == 1)
            ++complex_single;
          else if (blk.size() == 2)
            ++complex_double, rc.complex_double = c;
          else
            ok = false;
        }
        if (!ok) continue;
        std::sort(rc.real.begin(), rc.real.end());
        std::vector<int> m;
        for (const auto& r : rc.real)
          m.push_back(r.second);
        std::sort(m.rbegin(), m.rend());
        if (complex_double == 2 && m.empty())
          rc.pattern = "R8";
        else if (complex_double != 0)
          continue;
        else if (complex_single == 4 && m.empty())
          rc.pattern = "R2";
        else if (complex_single == 2 && m == std::vector<int>{1, 1})
          rc.pattern = "R3";
        else if (complex_single == 2 && m == std::vector<int>{2})
          rc.pattern = "R5";
        else if (complex_single != 0)
          continue;
        else if (m == std::vector<int>{1, 1, 1, 1})
          rc.pattern = "R1";
        else if (m == std::vector<int>{2, 1, 1})
          rc.pattern = "R4";
        else if (m == std::vector<int>{2, 2})
          rc.pattern = "R6";
        else if (m == std::vector<int>{3, 1})
          rc.pattern = "R7";
        else if (m == std::vector<int>{4})
          rc.pattern = "R9";
        else
          continue;
        rc.complex_roots = complex_single + 2 * complex_double;
        const size_t n = blocks.size();
        if (n < best_blocks || (n == best_blocks && err < best_err)) {
          best = std::move(rc);
          best_blocks = n;
          best_err = err;
        }
      }
  return best;
}

} // namespace

PencilFacts analyze_pencil_float(const core::QuadricMatrix& qa, const core::QuadricMatrix& qb,
                                 FloatInvariants& inv, double tol) {
  // Like seed 002: plain doubles of the given matrices, the root pattern from D2, D3, D4, E
  // with an absolute zero tolerance, then float indices. Nothing here is certified. The facts
  // do not copy the exact matrices (a float answer never needs them).
  PencilFacts out;
  Mat4T<double> a = approx(qa), b = approx(qb);
  {
    // Coincident quadrics (B = tA, or A = 0 or B = 0 exactly): B - tA within tol of zero for
    // the least-squares t, as the exact path's proportionality test.
    double aa = 0, ab = 0, bb = 0;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        aa += a[i][j] * a[i][j];
        ab += a[i][j] * b[i][j];
        bb += b[i][j] * b[i][j];
      }
    // The residual itself, not bb - ab^2/aa: that difference cancels to rounding (~eps bb),
    // the size of tol^2 bb. A = 0 is proportional to B too.
    double res = 0;
    const double t = aa > 0 ? ab / aa : 0;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        res += (b[i][j] - t * a[i][j]) * (b[i][j] - t * a[i][j]);
    if (aa == 0 || bb == 0 || res <= tol * tol * bb) {
      out.kind = algebra::PencilKind::Coincident;
      return out;
    }
  }
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
  // The root pattern from the float roots themselves: clusters that are multiple roots within
  // relative tolerance `tol` (cluster_roots). Not from the signs of D2, D3, D4, E with an
  // absolute tolerance as seed 002 does: those are polynomials of degree up to 12 in the roots,
  // so any fixed zero threshold calls a pencil whose four roots lie within ~0.3 of one another
  // (B near a multiple of A) degenerate, and their monomial formulas, evaluated in double,
  // cancel terms of ~|f|^6 down to products of squared root differences: at gap 2^-10 from a
  // node the computed sign of D4 was noise. D2..E are still reported, computed from the roots.
  // The roots are clustered on the balanced pencil (A, sigma B), sigma = |A| / |B| (max
  // entries), whose roots are sigma times f's: a small ellipsoid inside a large one puts three
  // roots of f within 1e-3 of 0 and one near 1, which are within 1e-9 of a double root
  // relative to f's coefficients, though no perturbation of A and B that small merges them.
  std::array<double, 5> fn, fr;
  double na = 0, nb = 0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      na = std::max(na, std::fabs(a[i][j]));
      nb = std::max(nb, std::fabs(b[i][j]));
    }
  double sigma = na > 0 && nb > 0 ? na / nb : 1;
  if (!std::isfinite(std::pow(sigma, 4)) || std::pow(sigma, 4) == 0) sigma = 1;
  double frs = 0;
  for (size_t i = 0; i < 5; ++i) {
    fn[i] = f[i];
    fr[i] = f[i] * std::pow(sigma, static_cast<double>(4 - i)); // det(l A - sigma B)
    frs = std::max(frs, std::fabs(fr[i]));
  }
  for (size_t i = 0; i < 5; ++i)
    fr[i] /= frs;
  const std::vector<cd> zbal =
      algebra::approx_complex_roots(std::vector<double>(fr.begin(), fr.end()));
  std::vector<cd> zroots;
  for (cd x : zbal)
    zroots.push_back(x / sigma);
  auto q = invariants_from_roots(f[4], zroots);
  for (size_t i = 0; i < 5; ++i)
    inv.f[i] = f[i];
  inv.d2 = q.d2;
  inv.d3 = q.d3;
  inv.d4 = q.d4;
  inv.e = q.e;
  RootClusters clusters = cluster_roots(fr, zbal, tol);
  for (auto& r : clusters.real)
    r.first /= sigma;
  clusters.complex_double /= sigma;

  // No grouping reads as a real quartic's pattern only on non-finite or wild float roots: the
  // seed's signs then.
  auto z = [&](double x) { return std::fabs(x) <= tol ? 0 : (x > 0 ? 1 : -1); };
  out.root_pattern = !clusters.pattern.empty()
                         ? clusters.pattern
                         : algebra::root_pattern_from_signs(z(q.d2), z(q.d3), z(q.d4), z(q.e));
  const std::string& rp = out.root_pattern;
  if (rp == "R1" || rp == "R2" || rp == "R3") {
    // All roots simple: separators as in the filter, indices from the eigenvalues' signs.
    int k = rp == "R1" ? 4 : (rp == "R3" ? 2 : 0);
    double seps[5];
    size_t nsep = separator_candidates(fn.data(), k, seps);
    if (nsep == 0) { // fall through to the clustering route below with the same pattern
    } else {
      for (size_t si = 0; si < nsep; ++si) {
        out.indices.push_back(separator_index(member(seps[si], a, b)));
        out.samples.push_back(Rational::exact_from_double(seps[si]));
      }
      for (int idx : out.indices)
        if (idx == 0 || idx == 4) out.definite_member = true;
      // The float roots themselves (the report's real_roots[].approx): the clusters' when they
      // read the pattern, else the k real-most float roots of the balanced polynomial.
      std::vector<double> froots;
      if (clusters.real.size() == static_cast<size_t>(k)) {
        for (const auto& [centre, m] : clusters.real)
          froots.push_back(centre);
      } else if (k > 0) {
        froots = algebra::approx_real_roots(std::vector<double>(fr.begin(), fr.end()),
                                            static_cast<size_t>(k));
        for (double& x : froots)
          x /= sigma;
        std::sort(froots.begin(), froots.end());
      }
      for (int i = 0; i < k; ++i) {
        RootFacts r;
        auto ui = static_cast<size_t>(i);
        if (ui < froots.size()) r.float_value = froots[ui];
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
  // Multiple roots: the real clusters' centres and multiplicities (when the seed's signs
  // decided the pattern, group the real-most float roots by the smallest spread instead).
  std::vector<int> best;
  std::vector<double> roots;
  if (!clusters.pattern.empty()) {
    for (const auto& [centre, m] : clusters.real) {
      roots.push_back(centre);
      best.push_back(m);
    }
  } else {
    std::vector<int> mults;
    if (rp == "R1")
      mults = {1, 1, 1, 1};
    else if (rp == "R3")
      mults = {1, 1};
    else if (rp == "R4")
      mults = {2, 1, 1};
    else if (rp == "R5")
      mults = {2};
    else if (rp == "R6")
      mults = {2, 2};
    else if (rp == "R7")
      mults = {3, 1};
    else if (rp == "R9")
      mults = {4};
    int nreal = 0;
    for (int m : mults)
      nreal += m;
    auto r = algebra::approx_real_roots(std::vector<double>(fr.begin(), fr.end()),
                                        static_cast<size_t>(nreal));
    for (double& x : r)
      x /= sigma;
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
    size_t pos = 0;
    for (int m : best) {
      double s = 0;
      for (int i = 0; i < m; ++i)
        s += r[pos + static_cast<size_t>(i)];
      roots.push_back(s / m);
      pos += static_cast<size_t>(m);
    }
  }
  int complex_roots = 4;
  for (int m : best)
    complex_roots -= m;
  if (rp == "R8") out.complex_double_pair = true;
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
    out.indices.push_back(separator_index(member(s, a, b)));
    out.samples.push_back(Rational::exact_from_double(s));
  }
  for (int idx : out.indices)
    if (idx == 0 || idx == 4) out.definite_member = true;
  Mat4T<double> x = solve(a, b);
  for (size_t i = 0; i < roots.size(); ++i) {
    RootFacts rf;
    rf.multiplicity = best[i];
    rf.float_value = roots[i];
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
    // g = l^2 - s l + p from the double complex root c (refined: the means of the float roots
    // are off by ~1e-8, enough to fail the test); test g(X) = 0.
    double s = 0, p = 0; // sum and product of the two distinct conjugate roots
    if (!clusters.pattern.empty()) {
      s = 2 * clusters.complex_double.real(), p = std::norm(clusters.complex_double);
    } else {
      for (auto c : zroots) {
        s += c.real() / 2;
        p += std::norm(c) / 4;
      }
    }
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
