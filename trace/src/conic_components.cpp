// surfcert::trace::conic_branches: conic components as plane ∩ quadric (see conics.hpp).
//
// Route: at each real multiple root theta of det(l*A - B) with rank(theta*A - B) <= 2 the
// member M = theta*A - B is split into its planes: for a rational theta from the exact member
// (exact_planes: completing the square, each coefficient rounded once), else (theta in Q(sqrt d)
// or irrational) by a 4x4 Jacobi eigen-decomposition of M in double (rank 2, inertia (1,1):
// p, q = sqrt(l1) v1 +- sqrt(-l2) v2, so X^T M X = (p.X)(q.X); rank 1: the eigenvector, a double
// plane). Each affine plane is given an orthonormal frame, the input quadric whose restriction's
// constant term is less sensitive to the plane's rounding is restricted to it (on the plane the
// restrictions of A and B are proportional), and the 2D conic is analysed:
// a real ellipse is sampled uniformly in its angle parameter with step sqrt(8 h / r_max)
// (chord error <= r_max dt^2 / 8 <= h, h = tolerance * scene size, the scene being the
// bounding box of the conics produced); a hyperbola or parabola (non-ellipsoid inputs only) is
// sampled the same way inside a clipping box and returned as open branches. In a box, each
// conic (and line) is also sampled where it crosses the planes of the box's faces and between
// those crossings, so that no arc the box keeps falls between two samples. Empty, imaginary
// and degenerate conics (a point: a tangent plane; a line pair) are skipped, as are planes at
// infinity and planes already used. Each sample is corrected by Gauss-Newton onto
// {plane = 0, Q = 0} (transversal even along a double conic, where grad f x grad g vanishes).
#include "surfcert/trace/conics.hpp"

#include "surfcert/algebra/eigen4.hpp"
#include "surfcert/algebra/form_restriction.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace surfcert::trace {

namespace {

using M4 = std::array<std::array<double, 4>, 4>;
using V4 = std::array<double, 4>;
using V3 = std::array<double, 3>;

constexpr double kPi = 3.14159265358979323846;

M4 to_double(const core::Mat4& m) {
  M4 r{};
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      r[i][j] = m[i][j].to_double_approx();
  return r;
}

// The quadric's matrix in doubles: a matrix posed in doubles as given (its symmetric part),
// without converting its exact rationals back (a correctly rounded conversion of each of the 16
// entries through MPFR was a quarter of a cone-plane pair's conic tracing).
M4 to_double(const core::QuadricMatrix& q) {
  const core::DoubleMat4* d = q.shape() ? nullptr : q.double_matrix();
  if (!d) return to_double(q.matrix());
  M4 r{};
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      const double x = (*d)[i][j], y = (*d)[j][i];
      r[i][j] = x == y ? x : 0.5 * x + 0.5 * y;
    }
  return r;
}

double max_abs(const M4& m) {
  double s = 0;
  for (const auto& row : m)
    for (double v : row)
      s = std::max(s, std::fabs(v));
  return s;
}

M4 normalised(M4 m) {
  double s = max_abs(m);
  if (s > 0)
    for (auto& row : m)
      for (double& v : row)
        v /= s;
  return m;
}

V3 sub(const V3& a, const V3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const V3& a) {
  return std::sqrt(dot(a, a));
}
V3 axpy(const V3& x, double s, const V3& d) {
  return {x[0] + s * d[0], x[1] + s * d[1], x[2] + s * d[2]};
}

V4 column(const M4& v, size_t k) {
  return {v[0][k], v[1][k], v[2][k], v[3][k]};
}

/// The member theta*A - B of the facts' basis in double, normalised (exact where possible:
/// for theta = u + s sqrt(d) the rational part u*A - B and s*A are formed exactly).
std::optional<M4> member_at(const algebra::PencilFacts& facts, const algebra::RootFacts& r) {
  M4 m{};
  if (r.rational_value) {
    core::Mat4 e = core::scaled(facts.a, *r.rational_value) + core::scaled(facts.b, -1);
    m = to_double(e);
  } else if (r.quadratic) {
    core::Mat4 e = core::scaled(facts.a, r.quadratic->a) + core::scaled(facts.b, -1);
    M4 f = to_double(core::scaled(facts.a, r.quadratic->b));
    M4 ed = to_double(e);
    double sd = std::sqrt(r.quadratic->d.to_double_approx());
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        m[i][j] = ed[i][j] + sd * f[i][j];
  } else {
    double th = ((r.lo + r.hi) * core::Rational(1, 2)).to_double_approx();
    M4 ad = to_double(facts.a), bd = to_double(facts.b);
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        m[i][j] = th * ad[i][j] - bd[i][j];
  }
  if (max_abs(m) == 0 || !std::isfinite(max_abs(m))) return std::nullopt;
  return normalised(m);
}

/// alpha + beta sqrt(s) (alpha, beta, s >= 0 rational) to double precision relative to the
/// result: where the two terms cancel, as (alpha^2 - beta^2 s) / (alpha - beta sqrt(s)), whose
/// numerator is exact and whose denominator does not cancel.
double plus_root(const core::Rational& alpha, const core::Rational& beta, const core::Rational& s,
                 double root) {
  const double a = alpha.to_double_approx(), b = beta.to_double_approx() * root;
  if (alpha.sign() * beta.sign() >= 0) return a + b;
  return (alpha * alpha - beta * beta * s).to_double_approx() / (a - b);
}

/// The planes of a rank-2 member of inertia (1,1) (or the plane of a rank-1 member), from the
/// exact member e. Completing the square at the largest diagonal entry e_kk: e_kk X^T e X =
/// (e_k.X)^2 - (R_j.X)^2 / S, where R = e_kk e - e_k e_k^T has rank 1 and S = -R_jj > 0 at
/// inertia (1,1) (exact rationals), so the planes are e_k sqrt(S) +- R_j, each coefficient
/// rounded once (plus_root: no cancellation, so a plane at infinity comes out exactly at
/// infinity and two planes 1e-10 apart keep their normals to the last bits). The eigenvectors
/// of the rounded member tilt such planes by the rounding noise over the gap between its
/// eigenvalues: two circles 2.8e-10 apart (a sphere in a cylinder of radius 1 - 1e-20) came
/// out in planes tilted by 4.5e-9, or not at all. Rank 1: the row of the largest diagonal
/// entry. Nullopt when no diagonal entry is non-zero or the doubles overflow or vanish (the
/// eigen route then).
std::optional<std::vector<V4>> exact_planes(const core::Mat4& e, int rank) {
  auto largest_diagonal = [](const auto& m) {
    size_t k = 4;
    double best = 0;
    for (size_t i = 0; i < 4; ++i)
      if (!m[i][i].is_zero() && (k == 4 || std::fabs(m[i][i].to_double_approx()) > best)) {
        k = i;
        best = std::fabs(m[i][i].to_double_approx());
      }
    return k;
  };
  auto usable = [](const V4& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }) &&
           std::any_of(v.begin(), v.end(), [](double x) { return x != 0; });
  };
  const size_t k = largest_diagonal(e);
  if (k == 4) return std::nullopt;
  if (rank == 1) {
    V4 v{};
    for (size_t i = 0; i < 4; ++i)
      v[i] = e[k][i].to_double_approx();
    return usable(v) ? std::optional<std::vector<V4>>(std::vector<V4>{v}) : std::nullopt;
  }
  core::Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t c = 0; c < 4; ++c)
      r[i][c] = e[k][k] * e[i][c] - e[k][i] * e[k][c];
  const size_t j = largest_diagonal(r);
  if (j == 4 || r[j][j].sign() >= 0) return std::nullopt; // not two real planes
  const core::Rational S = -r[j][j];
  const double root = std::sqrt(S.to_double_approx());
  std::vector<V4> planes;
  for (int sg : {1, -1}) {
    V4 p{};
    for (size_t i = 0; i < 4; ++i)
      p[i] = plus_root(sg > 0 ? r[j][i] : -r[j][i], e[k][i], S, root);
    if (!usable(p)) return std::nullopt;
    planes.push_back(p);
  }
  return planes;
}

double quad_form(const M4& q, const V4& x) {
  double s = 0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      s += x[i] * q[i][j] * x[j];
  return s;
}

double eval(const M4& q, const V3& p) {
  return quad_form(q, {p[0], p[1], p[2], 1.0});
}

V3 grad(const M4& q, const V3& p) {
  V4 x{p[0], p[1], p[2], 1.0};
  V3 g{};
  for (size_t i = 0; i < 3; ++i) {
    double s = 0;
    for (size_t j = 0; j < 4; ++j)
      s += q[i][j] * x[j];
    g[i] = 2 * s;
  }
  return g;
}

/// A conic of a plane, parametrised: ellipse c + r1 cos t e1 + r2 sin t e2; hyperbola
/// branch c + sgn (r1 cosh t e1) + r2 sinh t e2; parabola c + t e1 + (k t^2) e2 (c = vertex).
struct PlaneConic {
  enum Type { Ellipse, Hyperbola, Parabola, Line } type = Ellipse;
  V3 c{}, e1{}, e2{};
  double r1 = 0, r2 = 0, k = 0;
  double t_max = 0; ///< clipping for the open types
  V3 n{};
  double d = 0;          ///< the plane n.x + d = 0, |n| = 1
  const M4* q = nullptr; ///< quadric used for the correction (normalised)
  bool doubled = false;

  V3 at(double t, double sgn = 1) const {
    switch (type) {
    case Ellipse:
      return axpy(axpy(c, r1 * std::cos(t), e1), r2 * std::sin(t), e2);
    case Hyperbola:
      return axpy(axpy(c, sgn * r1 * std::cosh(t), e1), r2 * std::sinh(t), e2);
    case Parabola:
      return axpy(axpy(c, t, e1), k * t * t, e2);
    case Line:
      return axpy(c, t, e1);
    }
    return c;
  }
  /// Widens [lo, hi] to hold the conic over its parameter range (the ellipse whole; the open
  /// types, with sgn = 1, for |t| <= t_max): per coordinate the ends and the critical point.
  void extend(V3& lo, V3& hi) const {
    for (size_t i = 0; i < 3; ++i) {
      auto add = [&](double x) {
        lo[i] = std::min(lo[i], x);
        hi[i] = std::max(hi[i], x);
      };
      const double a = r1 * e1[i], b = r2 * e2[i];
      switch (type) {
      case Ellipse: // c + a cos t + b sin t
        add(c[i] - std::hypot(a, b));
        add(c[i] + std::hypot(a, b));
        break;
      case Hyperbola: { // c + a cosh t + b sinh t: critical where tanh t = -b / a
        for (double t : {-t_max, t_max})
          add(c[i] + a * std::cosh(t) + b * std::sinh(t));
        if (std::fabs(b) < std::fabs(a)) {
          const double t = std::atanh(-b / a);
          if (std::fabs(t) <= t_max) add(c[i] + a * std::cosh(t) + b * std::sinh(t));
        }
        break;
      }
      case Parabola: { // c + e1 t + k e2 t^2: critical at t = -e1 / (2 k e2)
        for (double t : {-t_max, t_max})
          add(c[i] + e1[i] * t + k * e2[i] * t * t);
        if (k * e2[i] != 0) {
          const double t = -e1[i] / (2 * k * e2[i]);
          if (std::fabs(t) <= t_max) add(c[i] + e1[i] * t + k * e2[i] * t * t);
        }
        break;
      }
      case Line:
        break;
      }
    }
  }
  /// Bound on |gamma''| over the parameter range.
  double second_derivative_bound() const {
    switch (type) {
    case Ellipse:
      return std::max(r1, r2);
    case Hyperbola:
      return std::hypot(r1 * std::cosh(t_max), r2 * std::sinh(t_max));
    case Parabola:
      return 2 * std::fabs(k);
    case Line:
      return 0;
    }
    return 1;
  }
};

/// Restriction of the 4x4 form q to the frame (e1, e2, x0) of a plane: a 3x3 conic in (u, v, 1).
std::array<std::array<double, 3>, 3> restrict_to_plane(const M4& q, const V3& e1, const V3& e2,
                                                       const V3& x0) {
  const std::array<V4, 3> t = {V4{e1[0], e1[1], e1[2], 0.0}, V4{e2[0], e2[1], e2[2], 0.0},
                               V4{x0[0], x0[1], x0[2], 1.0}};
  return algebra::restrict_form(q, t);
}

/// The real conic of the plane p.X = 0 with the quadric qa (or qb): an ellipse, a parabola,
/// a hyperbola (two entries), or the affine lines of a degenerate one (two crossing, two
/// parallel, one; every section with SectionKinds::LinesOnly, none with ProperOnly). Empty when
/// the plane is at infinity or the conic is imaginary or a point.
std::vector<PlaneConic> conics_in_plane(const V4& p, const M4& qa, const M4& qb, bool doubled,
                                        SectionKinds kinds) {
  const bool lines_only = kinds == SectionKinds::LinesOnly;
  const bool proper_only = kinds == SectionKinds::ProperOnly;
  std::vector<PlaneConic> out;
  V3 n{p[0], p[1], p[2]};
  double nn = norm(n), pn = std::hypot(nn, p[3]);
  if (pn == 0 || nn <= 1e-12 * pn) return out; // plane at infinity: its conic has no affine point
  V3 un{n[0] / nn, n[1] / nn, n[2] / nn};
  double d = p[3] / nn;
  V3 x0{-d * un[0], -d * un[1], -d * un[2]};
  size_t small = 0;
  for (size_t i = 1; i < 3; ++i)
    if (std::fabs(un[i]) < std::fabs(un[small])) small = i;
  V3 ax{0, 0, 0};
  ax[small] = 1;
  V3 e1 = cross(un, ax);
  double l1 = norm(e1);
  e1 = {e1[0] / l1, e1[1] / l1, e1[2] / l1};
  V3 e2 = cross(un, e1);

  auto ca = restrict_to_plane(qa, e1, e2, x0), cb = restrict_to_plane(qb, e1, e2, x0);
  auto fro = [](const std::array<std::array<double, 3>, 3>& c) {
    double s = 0;
    for (const auto& r : c)
      for (double v : r)
        s = std::max(s, std::fabs(v));
    return s;
  };
  // The better conditioned restriction: on the plane the two are proportional, but the
  // plane is rounded, and its constant term moves with the plane's offset by |grad q . n| per
  // unit (plus the evaluation's rounding). Next to a cone's apex the cone's conic is exact to
  // the last bits where a sphere's (gradient ~1 there) is noise: the circle of radius 1e-20
  // at z = -1e-20 of a sphere through the apex came out imaginary from the sphere.
  // A restriction that is rounding noise (the plane lies on that quadric: a plane of a plane
  // pair restricted to the pair) is never chosen.
  const V4 xh{x0[0], x0[1], x0[2], 1.0};
  // The sum of |terms| of q(x0): the scale of the constant term's rounding.
  auto eval_terms = [&xh](const M4& q) {
    double e = 0;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        e += std::fabs(xh[i] * q[i][j] * xh[j]);
    return e;
  };
  auto const_error = [&](const M4& q, const std::array<std::array<double, 3>, 3>& c) {
    const double cs_q = fro(c), reach = 1 + norm(x0);
    if (!(cs_q > 1e-12 * max_abs(q) * reach * reach)) return HUGE_VAL;
    double slope = 0;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 4; ++j)
        slope += 2 * q[i][j] * xh[j] * un[i];
    return (std::fabs(slope) * (std::fabs(d) + 1e-300) + eval_terms(q)) / cs_q;
  };
  const double ea = const_error(qa, ca), eb = const_error(qb, cb);
  bool use_a = ea != eb ? ea < eb : fro(ca) >= fro(cb); // both noise: the larger
  auto c = use_a ? ca : cb;
  double cs = fro(c);
  // The constant term's own cancellation (a tangent plane's point conic: c0 ~ 1e-16 of terms
  // ~1), in the units of the normalised conic.
  const double c0_terms = cs > 0 ? eval_terms(use_a ? qa : qb) / cs : 0.0;
  if (cs == 0) return out; // the plane lies on both quadrics (not a regular pencil)
  for (auto& r : c)
    for (double& v : r)
      v /= cs;

  // Eigen-decomposition of the 2x2 quadratic part.
  double a11 = c[0][0], a12 = c[0][1], a22 = c[1][1];
  double mean = 0.5 * (a11 + a22), diff = 0.5 * (a11 - a22);
  double rad = std::hypot(diff, a12);
  double mu1 = mean + rad, mu2 = mean - rad;
  std::array<double, 2> w1, w2;
  if (rad == 0) {
    w1 = {1, 0};
  } else if (diff >= 0) {
    double x = diff + rad, y = a12, l = std::hypot(x, y);
    w1 = {x / l, y / l};
  } else {
    double x = a12, y = rad - diff, l = std::hypot(x, y);
    w1 = {x / l, y / l};
  }
  w2 = {-w1[1], w1[0]};
  auto to3 = [&](const std::array<double, 2>& w) {
    return V3{w[0] * e1[0] + w[1] * e2[0], w[0] * e1[1] + w[1] * e2[1],
              w[0] * e1[2] + w[1] * e2[2]};
  };
  auto plane_point = [&](double u, double v) { return axpy(axpy(x0, u, e1), v, e2); };
  std::array<double, 2> l{c[0][2], c[1][2]};
  double c0 = c[2][2];
  double lw1 = l[0] * w1[0] + l[1] * w1[1], lw2 = l[0] * w2[0] + l[1] * w2[1];
  const double eps = 1e-11;
  double mumax = std::max(std::fabs(mu1), std::fabs(mu2));

  PlaneConic base;
  base.n = un;
  base.d = d;
  base.q = use_a ? &qa : &qb;
  base.doubled = doubled;

  auto line = [&](double u, double v, const std::array<double, 2>& dir) {
    PlaneConic ln = base;
    ln.type = PlaneConic::Line;
    ln.c = plane_point(u, v);
    ln.e1 = to3(dir);
    ln.t_max = 1e3 * (1 + norm(ln.c));
    out.push_back(ln);
  };
  auto linear = [&]() -> std::vector<PlaneConic>& {
    // The restriction is (nearly) linear, 2 l.(u, v) + c0 = 0: the conic is the line at
    // infinity and one affine line (a plane x = 1 through z = xy: the line z = y), or nothing
    // when l vanishes too (the plane lies on the quadric's asymptotic cone).
    // (l must stand above its own rounding, ~|x0| |q| ulps.)
    const double ll = std::hypot(l[0], l[1]);
    const double l_terms = cs > 0 ? (1 + norm(x0)) * max_abs(use_a ? qa : qb) / cs : 0.0;
    if (!(ll > 1e-13 * (std::fabs(c0) + mumax)) || !(ll > 0x1p-40 * l_terms) || !std::isfinite(ll))
      return out;
    const double f = -c0 / (2 * ll * ll);
    line(f * l[0], f * l[1], {-l[1] / ll, l[0] / ll});
    return out;
  };
  if (std::fabs(mu1) > eps * mumax && std::fabs(mu2) > eps * mumax && mumax > eps) {
    // Central conic: centre m (in eigen coordinates s1 = -lw1/mu1, s2 = -lw2/mu2).
    double s1 = -lw1 / mu1, s2 = -lw2 / mu2;
    double cc = c0 + lw1 * s1 + lw2 * s2;                                   // value at the centre
    double mag = std::fabs(c0) + std::fabs(lw1 * s1) + std::fabs(lw2 * s2); // cancellation
    double u = s1 * w1[0] + s2 * w2[0], v = s1 * w1[1] + s2 * w2[1];
    V3 centre = plane_point(u, v);
    // lines_only with a centre beyond 1e6 reaches: a noise quadratic part; the section is
    // one line and the line at infinity (a hyperbolic paraboloid's tangent plane 2^20 out,
    // rescaled, drew its "crossing lines" 1e11 out).
    if (lines_only && std::hypot(s1, s2) > 1e6 * (1 + norm(x0))) return linear();
    // lines_only: the certified morphology has lines and no proper conic, so a centre value
    // the rounding left at 2e-16 of a conic of size 1 (four lines, posed) is not a hyperbola.
    // (The constant's own rounding too: 64 ulps of its terms.)
    // proper_only: the affine curve has no lines (certified), so opposite signs of mu1, mu2
    // make a hyperbola even where cc is small against its terms (one 2^-20 across, 0.4 from
    // the origin: 1e-11 of them). Where cc is within the rounding's reach (2^-40 of its terms,
    // 2^-46 of the constant's) its sign, which says which axis is real, is noise (a plane
    // 1e-6 from a cone's apex 12345 out: cc ~ 1e-20 of its terms, and a hyperbola drawn with
    // the wrong real axis put a branch on both nappes): nothing is drawn there, and the
    // certified count judges (a retry in another frame may read it).
    const bool crossing_lines_excluded = proper_only && (mu1 > 0) != (mu2 > 0);
    if (crossing_lines_excluded &&
        !(std::fabs(cc) > 0x1p-40 * mag && std::fabs(cc) > 0x1p-46 * c0_terms))
      return out;
    if (!crossing_lines_excluded && (lines_only || std::fabs(cc) <= 1e-10 * mag ||
                                     std::fabs(cc) <= 0x1p-46 * c0_terms || cc == 0)) {
      // A point (tangent plane, mu1 mu2 > 0) or two lines crossing at the centre:
      // mu1 s1^2 + mu2 s2^2 = 0, s2 / s1 = +-sqrt(-mu1 / mu2) (open, clipped by the caller).
      if ((mu1 > 0) == (mu2 > 0)) return out;
      const double r = std::sqrt(-mu1 / mu2);
      const double reach = 1e3 * (1 + norm(centre));
      for (double sg : {1.0, -1.0}) {
        PlaneConic ln = base;
        ln.type = PlaneConic::Line;
        ln.c = centre;
        V3 dir = axpy(to3(w1), sg * r, to3(w2));
        const double dn = norm(dir);
        ln.e1 = {dir[0] / dn, dir[1] / dn, dir[2] / dn};
        ln.t_max = reach;
        out.push_back(ln);
      }
      return out;
    }
    if ((mu1 > 0) == (mu2 > 0)) {
      if ((mu1 > 0) == (cc > 0)) return out; // imaginary ellipse
      PlaneConic e = base;
      e.type = PlaneConic::Ellipse;
      e.c = centre;
      e.e1 = to3(w1);
      e.e2 = to3(w2);
      e.r1 = std::sqrt(-cc / mu1);
      e.r2 = std::sqrt(-cc / mu2);
      out.push_back(e);
      return out;
    }
    // Hyperbola: the real axis is the eigenvector with -cc/mu > 0.
    PlaneConic h = base;
    h.type = PlaneConic::Hyperbola;
    h.c = centre;
    if (-cc / mu1 > 0) {
      h.e1 = to3(w1);
      h.e2 = to3(w2);
      h.r1 = std::sqrt(-cc / mu1);
      h.r2 = std::sqrt(cc / mu2);
    } else {
      h.e1 = to3(w2);
      h.e2 = to3(w1);
      h.r1 = std::sqrt(-cc / mu2);
      h.r2 = std::sqrt(cc / mu1);
    }
    double reach = 8 * std::max(h.r1, h.r2);
    h.t_max = std::min(std::acosh(reach / h.r1), std::asinh(reach / h.r2));
    out.push_back(h);
    h.r1 = -h.r1; // the other branch (sgn folded into r1)
    out.push_back(h);
    return out;
  }
  if (mumax <= eps) return proper_only ? out : linear();
  // Parabola: mu s^2 + 2 ls s + 2 lt t + c0 = 0 (s along the non-null eigenvector).
  bool first = std::fabs(mu1) >= std::fabs(mu2);
  double mu = first ? mu1 : mu2, ls = first ? lw1 : lw2, lt = first ? lw2 : lw1;
  auto ws = first ? w1 : w2, wt = first ? w2 : w1;
  // proper_only: no parallel lines (certified), so a linear term within the rounding's reach
  // leaves nothing to draw (imaginary parallel lines meeting at a real point at infinity: a
  // parabola drawn from that noise moved the automatic box, generate --case 27 --seed 58
  // pair 5).
  const bool flat = std::fabs(lt) <= 1e-13 * (std::fabs(mu) + std::fabs(ls) + std::fabs(c0));
  if (proper_only && flat) return out;
  if (lines_only || flat) {
    // Below 1e-13 the linear term is the rounding's (at 1e-10 a plane 1e-10 off a cone's
    // generator, its apex at (1/3, 0, -1), lost its parabola): mu s^2 + 2 ls s + c0 = 0, two
    // parallel lines along wt (a plane through a hyperboloid along an asymptotic direction),
    // one (a double root: a tangent plane along a ruling) or none.
    const double disc = ls * ls - mu * c0, mag = ls * ls + std::fabs(mu * c0);
    if (disc < -1e-13 * mag) return out;
    if (disc <= 1e-13 * mag) {
      line(-ls / mu * ws[0], -ls / mu * ws[1], wt);
      return out;
    }
    // The roots without cancellation: q = -(ls + sign(ls) sqrt(disc)), s = q / mu, c0 / q.
    const double qv = -(ls + std::copysign(std::sqrt(disc), ls));
    for (double sr : {qv / mu, c0 / qv})
      line(sr * ws[0], sr * ws[1], wt);
    return out;
  }
  // t = -(mu s^2 + 2 ls s + c0) / (2 lt); vertex at s* = -ls/mu.
  double sv = -ls / mu;
  double tv = -(mu * sv * sv + 2 * ls * sv + c0) / (2 * lt);
  PlaneConic pc = base;
  pc.type = PlaneConic::Parabola;
  pc.c = plane_point(sv * ws[0] + tv * wt[0], sv * ws[1] + tv * wt[1]);
  pc.e1 = to3(ws);
  pc.e2 = to3(wt);
  pc.k = -mu / (2 * lt);
  double focal = 1 / (4 * std::fabs(pc.k));
  pc.t_max = 16 * focal;
  out.push_back(pc);
  return out;
}

/// Gauss-Newton (minimum norm) onto {n.x + d = 0, Q(x) = 0}, until the point is within
/// 1e-15 (|x| + size) of both, geometrically (|r1|, |Q| / |grad Q|), or 6 steps. (A fixed step
/// size test, |dx| <= 1e-17 (1 + |x|), sat below the rounding noise: every sample took all 6
/// steps, a third of the time of a conic pair.) finish_points measures every point against the
/// exact surfaces afterwards and refines any left too far.
void correct(const PlaneConic& pc, V3& x, double size) {
  for (int it = 0; it < 6; ++it) {
    double r1 = dot(pc.n, x) + pc.d;
    double r2 = eval(*pc.q, x);
    V3 g = grad(*pc.q, x);
    double cc = dot(g, g);
    const double near = 1e-15 * (norm(x) + size);
    if (std::fabs(r1) <= near && r2 * r2 <= near * near * cc) return;
    // J = [n; g]; dx = -J^T (J J^T)^{-1} r
    double a = dot(pc.n, pc.n), b = dot(pc.n, g);
    double det = a * cc - b * b;
    if (!(det > 1e-300)) return;
    double y1 = (cc * r1 - b * r2) / det, y2 = (-b * r1 + a * r2) / det;
    V3 dx{-(y1 * pc.n[0] + y2 * g[0]), -(y1 * pc.n[1] + y2 * g[1]), -(y1 * pc.n[2] + y2 * g[2])};
    x = axpy(x, 1.0, dx);
    if (norm(dx) <= 1e-17 * (1 + norm(x))) return;
  }
}

// Normals parallel (to 1e-12) and offsets equal (to 1e-12 relative). Not the angle between
// the homogeneous 4-vectors: far from the origin their offsets dominate them, and two distinct
// planes (x - y = 3e5, x + y = -1e5) would compare equal.
bool same_plane(const V4& p, const V4& q) {
  const double np = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  const double nq = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
  if (np == 0 || nq == 0) return false;
  const double s = p[0] * q[0] + p[1] * q[1] + p[2] * q[2] < 0 ? -1 : 1;
  for (size_t i = 0; i < 3; ++i)
    if (std::fabs(p[i] / np - s * q[i] / nq) > 1e-12) return false;
  const double dp = p[3] / np, dq = s * q[3] / nq;
  return std::fabs(dp - dq) <= 1e-12 * std::max(std::fabs(dp), std::fabs(dq));
}

// The branches of the collected conics: open ones sampled past the box, every one at the
// tolerance's spacing, each point corrected onto the surfaces (defined below).
std::vector<Branch> sampled_branches(std::vector<PlaneConic> conics, const TraceOptions& opt);

} // namespace

std::vector<Branch> conic_branches(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                   const algebra::PencilFacts& facts, const TraceOptions& opt,
                                   SectionKinds kinds) {
  std::vector<Branch> out;
  if (facts.kind != algebra::PencilKind::Regular) return out;
  const M4 qa = normalised(to_double(a)), qb = normalised(to_double(b));

  std::vector<V4> planes_used;
  std::vector<PlaneConic> conics;
  for (const auto& r : facts.real_roots) {
    if (r.multiplicity < 2 || r.rank > 2 || r.rank < 1) continue;
    std::vector<V4> planes;
    const bool doubled = r.rank == 1;
    if (r.rank == 2 && (r.sigma.p != 1 || r.sigma.n != 1))
      continue; // (2,0) / (0,2): a pair of complex conjugate planes
    if (r.rational_value) {
      const core::Mat4 e = core::scaled(facts.a, *r.rational_value) + core::scaled(facts.b, -1);
      if (auto exact = exact_planes(e, r.rank)) planes = std::move(*exact);
    }
    if (planes.empty()) {
      // The eigen route: the member rounded (an irrational root, or no non-zero diagonal).
      auto m = member_at(facts, r);
      if (!m) continue;
      V4 w;
      M4 v;
      algebra::jacobi4(*m, w, v);
      std::array<size_t, 4> idx{0, 1, 2, 3};
      std::sort(idx.begin(), idx.end(), [&](size_t i, size_t j) { return w[i] > w[j]; });
      if (r.rank == 2) {
        double l1 = w[idx[0]], l2 = w[idx[3]];
        if (!(l1 > 0 && l2 < 0)) continue;
        // The member is rounded (and its root, when irrational): its two zero eigenvalues come
        // out as noise. Where l1 or |l2| is not far above that noise (and 2^-52 of the other),
        // the planes' directions are noise too: a sphere in a cylinder of radius 1 - 1e-20,
        // rotated, had its two circles (planes 2.8e-10 apart) drawn in planes tilted by
        // 4.5e-9, certified. No conics then (undecided).
        const double noise =
            std::max(std::fabs(w[idx[1]]), std::fabs(w[idx[2]])) + 0x1p-52 * std::max(l1, -l2);
        if (!(std::min(l1, -l2) > 4 * noise)) continue;
        V4 v1 = column(v, idx[0]), v2 = column(v, idx[3]);
        double s1 = std::sqrt(l1), s2 = std::sqrt(-l2);
        V4 p{}, q{};
        for (size_t i = 0; i < 4; ++i) {
          p[i] = s1 * v1[i] + s2 * v2[i];
          q[i] = s1 * v1[i] - s2 * v2[i];
        }
        planes = {p, q};
      } else { // rank 1: a double plane
        size_t k = std::fabs(w[idx[0]]) >= std::fabs(w[idx[3]]) ? idx[0] : idx[3];
        planes = {column(v, k)};
      }
    }
    for (const V4& p : planes) {
      bool seen = false;
      for (const V4& u : planes_used)
        seen = seen || same_plane(p, u);
      if (seen) continue;
      planes_used.push_back(p);
      for (auto& pc : conics_in_plane(p, qa, qb, doubled, kinds))
        conics.push_back(pc);
    }
  }
  // A line lies in two planes of the pencil's plane pairs (four lines: each in a plane of
  // either pair): the second copy is dropped, else each line was drawn twice.
  for (size_t i = 0; i < conics.size(); ++i) {
    if (conics[i].type != PlaneConic::Line) continue;
    for (size_t j = 0; j < i; ++j) {
      const PlaneConic& u = conics[j];
      if (u.type != PlaneConic::Line) continue;
      const V3 off = sub(conics[i].c, u.c);
      const double along = dot(off, u.e1), size = 1 + norm(u.c) + norm(conics[i].c);
      const V3 across = axpy(off, -along, u.e1);
      if (norm(cross(conics[i].e1, u.e1)) <= 1e-12 && norm(across) <= 1e-12 * size) {
        conics.erase(conics.begin() + static_cast<long>(i));
        --i;
        break;
      }
    }
  }
  return sampled_branches(std::move(conics), opt);
}

std::vector<Branch> section_branches(const core::Mat4& plane, const core::QuadricMatrix& other,
                                     const TraceOptions& opt) {
  const M4 q = normalised(to_double(other));
  // The plane n . x + d = 0 written as a quadric holds n / 2 in its last column.
  const V4 p{(core::Rational(2) * plane[0][3]).to_double_approx(),
             (core::Rational(2) * plane[1][3]).to_double_approx(),
             (core::Rational(2) * plane[2][3]).to_double_approx(), plane[3][3].to_double_approx()};
  return sampled_branches(conics_in_plane(p, q, q, false, SectionKinds::Any), opt);
}

namespace {

// The parameters where the conic crosses the planes of the box's faces (closed forms: a cos t +
// b sin t = f for the ellipse, a quadratic in e^t for the hyperbola, in t for the parabola)
// and the midpoints between consecutive ones, merged into the sorted samples ts within
// [lo, hi] (the ellipse's wrapping around too). The samples of the whole conic, spaced for its
// size, could all miss a short arc the box keeps near an edge (generate --case 23 --seed 50
// pair 2 in a given box: an arc of 0.4 between two exact crossings, nothing drawn), or step
// over a crossing a hair from tangency; the clipping then finds every crossing between an
// inside and an outside sample.
void with_face_parameters(const PlaneConic& pc, const Box& box, double lo, double hi,
                          std::vector<double>& ts) {
  std::vector<double> cross;
  auto keep = [&](double t) {
    if (pc.type == PlaneConic::Ellipse) {
      t = std::fmod(t - lo, 2 * kPi);
      if (t < 0) t += 2 * kPi;
      t += lo;
    }
    if (std::isfinite(t) && t >= lo && t <= hi) cross.push_back(t);
  };
  for (size_t k = 0; k < 3; ++k)
    for (double f : {box.min[k], box.max[k]}) {
      const double g = f - pc.c[k];
      if (pc.type == PlaneConic::Ellipse) {
        const double a = pc.r1 * pc.e1[k], b = pc.r2 * pc.e2[k], r = std::hypot(a, b);
        if (!(r > 0) || std::fabs(g) > r) continue;
        const double phi = std::atan2(b, a), w = std::acos(g / r);
        keep(phi + w);
        keep(phi - w);
      } else {
        // Hyperbola: a (u + 1/u) / 2 + b (u - 1/u) / 2 = g, u = e^t: (a + b) u^2 - 2 g u +
        // (a - b) = 0. Parabola: k e2 t^2 + e1 t - g = 0.
        double qa, qb, qc;
        if (pc.type == PlaneConic::Hyperbola) {
          const double a = pc.r1 * pc.e1[k], b = pc.r2 * pc.e2[k];
          qa = a + b, qb = -2 * g, qc = a - b;
        } else if (pc.type == PlaneConic::Parabola) {
          qa = pc.k * pc.e2[k], qb = pc.e1[k], qc = -g;
        } else { // Line: e1 t = g
          qa = 0, qb = pc.e1[k], qc = -g;
        }
        std::vector<double> roots;
        if (qa == 0) {
          if (qb != 0) roots.push_back(-qc / qb);
        } else {
          const double disc = qb * qb - 4 * qa * qc;
          if (disc < 0) continue;
          const double sq = std::sqrt(disc), m = -0.5 * (qb + std::copysign(sq, qb));
          if (m != 0) roots.push_back(qc / m);
          roots.push_back(m / qa);
        }
        for (double u : roots)
          if (pc.type == PlaneConic::Parabola || pc.type == PlaneConic::Line)
            keep(u);
          else if (u > 0)
            keep(std::log(u));
      }
    }
  if (cross.empty()) return;
  std::sort(cross.begin(), cross.end());
  // A midpoint only where no sample lies between two crossings (a sample at a parabola's vertex
  // 7e-11 from a cone's apex, where the correction does not converge, was left off the curve).
  const bool ellipse = pc.type == PlaneConic::Ellipse;
  auto sampled_between = [&ts](double u, double v) {
    const auto it = std::upper_bound(ts.begin(), ts.end(), u);
    return it != ts.end() && *it < v;
  };
  const size_t m = cross.size();
  std::vector<double> mids;
  for (size_t i = 0; i <= m; ++i) {
    double u = i == 0 ? lo : cross[i - 1], v = i == m ? hi : cross[i];
    if (ellipse && i == 0) continue; // the wrap-around arc is the one after the last crossing
    if (ellipse && i == m) v = cross[0] + 2 * kPi;
    bool between = sampled_between(u, std::min(v, hi));
    if (ellipse && v > hi) between = between || sampled_between(lo - 1, v - 2 * kPi);
    if (between) continue;
    double mid = 0.5 * (u + v);
    if (ellipse && mid >= lo + 2 * kPi) mid -= 2 * kPi;
    if (mid >= lo && mid <= hi) mids.push_back(mid);
  }
  cross.insert(cross.end(), mids.begin(), mids.end());
  ts.insert(ts.end(), cross.begin(), cross.end());
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
  if (pc.type == PlaneConic::Ellipse)
    while (!ts.empty() && ts.back() >= lo + 2 * kPi)
      ts.pop_back(); // the closing sample is the first one
}

// An ellipse's or a parabola's parameters: uniform, the step from the largest |gamma''| (a
// chord error |gamma''| dt^2 / 8 <= h; a parabola's is constant); an ellipse's at least 16
// (the closing sample is the first), a parabola's at least 8 steps from -t_max to t_max.
std::vector<double> uniform_parameters(const PlaneConic& pc, double h, int cap) {
  const bool ellipse = pc.type == PlaneConic::Ellipse;
  const double bound = pc.second_derivative_bound();
  const double dt = bound > 0 ? std::sqrt(8 * h / bound) : 1.0;
  const double span = ellipse ? 2 * kPi : 2 * pc.t_max, t0 = ellipse ? 0 : -pc.t_max;
  long n = static_cast<long>(std::ceil(span / dt));
  n = std::max(n, ellipse ? 16L : 8L);
  n = std::min(n, static_cast<long>(ellipse ? cap : cap - 1));
  const long count = ellipse ? n : n + 1;
  std::vector<double> ts(static_cast<size_t>(count));
  for (long i = 0; i < count; ++i)
    ts[static_cast<size_t>(i)] = t0 + span * static_cast<double>(i) / static_cast<double>(n);
  return ts;
}

// A hyperbola's parameters on [-t_max, t_max], outward from the vertex, symmetric about it.
// Each step keeps the chord within h of the arc by either of two bounds, the longer step
// taken: (1) in the parameter, |gamma''| dt^2 / 8 <= h with |gamma''| = |gamma - c| at the
// step's outer end, where it is largest; (2) along the curve, an arc length L <= min(
// sqrt(8 h / kappa), 0.2 / kappa, 200 h) (the walker's step, valid while kappa L is small),
// kappa the curvature at the inner end, where it is largest (it falls away from the vertex),
// and the parameter step L / |gamma'| with the speed at the outer end of a first guess (the
// speed grows outward, so the arc is at most L). Far out (1) shrinks like 1 / sqrt(|gamma|)
// while the branch straightens: the uniform step of the largest |gamma''| put ~150 samples on
// a unit hyperbola's branch in a box of 6 (sinh, cosh and the correction of each were ~15% of
// a cone-plane pair). The first samples at +-dt/2, none at the vertex (a narrow turn next to
// a cone's apex, where a sample's correction may not converge). At least 8 steps, at most cap
// points.
std::vector<double> hyperbola_parameters(const PlaneConic& pc, double h, int cap) {
  const double tm = pc.t_max, r1 = std::fabs(pc.r1), r2 = std::fabs(pc.r2);
  // cosh and sinh from one exp (an estimate for the step: sinh's cancellation near 0 leaves an
  // absolute error ~1e-16, nothing here); inf beyond ~710 gives the floor step.
  auto accel_speed = [&](double t) {
    const double e = std::exp(t), ie = 1 / e;
    const double c = 0.5 * (e + ie), sh = 0.5 * (e - ie);
    return std::make_pair(std::sqrt(r1 * r1 * c * c + r2 * r2 * sh * sh),
                          std::sqrt(r1 * r1 * sh * sh + r2 * r2 * c * c));
  };
  auto accel = [&](double t) { return accel_speed(t).first; };
  auto speed = [&](double t) { return accel_speed(t).second; };
  const double dt_floor = 2 * tm / std::max(cap - 1, 8); // never more than cap points
  const double dt_ceiling = tm / 4;                      // at least 8 steps
  std::vector<double> half;
  for (double t = 0; t < tm;) {
    const auto [a0, v] = accel_speed(t);
    double dp = std::sqrt(8 * h / a0);
    dp = std::sqrt(8 * h / accel(std::min(t + dp, tm)));
    const double kappa = r1 * r2 / (v * v * v);
    double len = 200 * h;
    if (kappa > 0) len = std::min({len, std::sqrt(8 * h / kappa), 0.2 / kappa});
    double dg = len / v;
    dg = len / speed(std::min(t + dg, tm));
    double dt = std::max(std::isfinite(dp) ? dp : 0.0, std::isfinite(dg) ? dg : 0.0);
    dt = std::clamp(dt, dt_floor, dt_ceiling);
    if (!(dt > 0)) break; // t_max 0 or not finite
    t = std::min(t + (half.empty() ? 0.5 * dt : dt), tm);
    half.push_back(t);
  }
  if (half.empty()) return {0.0};
  std::vector<double> ts;
  ts.reserve(2 * half.size());
  for (size_t i = half.size(); i-- > 0;)
    ts.push_back(-half[i]);
  ts.insert(ts.end(), half.begin(), half.end());
  return ts;
}

std::vector<Branch> sampled_branches(std::vector<PlaneConic> conics, const TraceOptions& opt) {
  std::vector<Branch> out;
  if (conics.empty()) return out;
  if (opt.box) {
    // Open conics reach beyond the box: every point at parameter t_max is farther from the
    // conic's centre than the box's farthest corner. Either coordinate of the parametrisation
    // alone may carry it there (|c + t e1 + k t^2 e2 - c| >= max(|t|, |k| t^2)): the smaller
    // parameter is taken. (t_max = reach for a parabola of focal length 3.5e-7 in a box 256
    // wide put its ends 1e11 out; the scene, and with it the sampling step, followed, and
    // its nine samples left nothing in the box: undecided.)
    const Box& bx = *opt.box;
    const V3 bc{(bx.min[0] + bx.max[0]) / 2, (bx.min[1] + bx.max[1]) / 2,
                (bx.min[2] + bx.max[2]) / 2};
    for (auto& pc : conics) {
      const double reach = 1.01 * (norm(sub(pc.c, bc)) + bx.diagonal());
      if (pc.type == PlaneConic::Hyperbola)
        pc.t_max = std::max(pc.t_max, std::min(std::acosh(std::max(1.0, reach / std::fabs(pc.r1))),
                                               std::asinh(reach / std::fabs(pc.r2))));
      else if (pc.type == PlaneConic::Parabola)
        pc.t_max = std::max(pc.t_max, std::min(reach, std::sqrt(reach / std::fabs(pc.k))));
      else if (pc.type == PlaneConic::Line)
        pc.t_max = std::max(pc.t_max, reach);
    }
  }

  // Scene size: bounding-box diagonal of the conics (in closed form: 257 samples of each
  // parametrisation, a sinh and a cosh each, were 6% of a plane section's instructions).
  V3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const auto& pc : conics)
    pc.extend(lo, hi); // a line has no size of its own
  double scene = norm(sub(hi, lo));
  if (!(scene > 0) || !std::isfinite(scene)) scene = 1;
  const double h = opt.tolerance * opt.chord_scale * scene;
  const int cap = std::max(8, opt.max_points_per_branch);

  for (const auto& pc : conics) {
    Branch br;
    br.kind = pc.type == PlaneConic::Line ? "line" : pc.doubled ? "double_conic" : "conic";
    br.plane = std::array<double, 4>{pc.n[0], pc.n[1], pc.n[2], pc.d};
    bool ellipse = pc.type == PlaneConic::Ellipse;
    if (pc.type == PlaneConic::Line) { // straight: a few points, cut to the box by the caller
      // Geometric spacing away from the crossing point (dense near it, where the box is).
      std::vector<double> ts{0.0};
      for (double t = 1e-3 * (1 + norm(pc.c)); t < pc.t_max; t *= 1.25) {
        ts.push_back(t);
        ts.insert(ts.begin(), -t);
      }
      // The line through two corrected points away from the crossing (near it the surfaces
      // may be singular, as at a cone's apex, and the correction would not converge there);
      // every sample is then exactly on that line.
      if (opt.box) with_face_parameters(pc, *opt.box, -pc.t_max, pc.t_max, ts);
      const double far = 1 + norm(pc.c);
      V3 p1 = pc.at(-far), p2 = pc.at(far);
      correct(pc, p1, far);
      correct(pc, p2, far);
      const V3 mid{(p1[0] + p2[0]) / 2, (p1[1] + p2[1]) / 2, (p1[2] + p2[2]) / 2};
      const V3 dir = sub(p2, p1);
      const double dl = norm(dir);
      for (double t : ts)
        br.points.push_back(axpy(mid, t / dl, dir));
      br.closed = false;
      out.push_back(std::move(br));
      continue;
    }
    br.closed = ellipse;
    const double span = ellipse ? 2 * kPi : 2 * pc.t_max;
    const double t0 = ellipse ? 0 : -pc.t_max;
    std::vector<double> ts = pc.type == PlaneConic::Hyperbola ? hyperbola_parameters(pc, h, cap)
                                                              : uniform_parameters(pc, h, cap);
    if (opt.box) with_face_parameters(pc, *opt.box, t0, t0 + span, ts);
    br.points.reserve(ts.size());
    for (double t : ts) {
      V3 x;
      if (pc.type == PlaneConic::Hyperbola) {
        // at(t) with cosh and sinh from one exp (a sinh and a cosh per sample were ~8% of a
        // cone-plane pair); the correction below puts the sample on the curve either way.
        const double e = std::exp(t), ie = 1 / e;
        x = axpy(axpy(pc.c, pc.r1 * 0.5 * (e + ie), pc.e1), pc.r2 * 0.5 * (e - ie), pc.e2);
      } else {
        x = pc.at(t);
      }
      correct(pc, x, scene);
      br.points.push_back(x);
    }
    out.push_back(std::move(br));
  }
  return out;
}

} // namespace

} // namespace surfcert::trace
