#include "surfcert/certify/distance/convex_distance.hpp"

#include "surfcert/certify/distance/mp_float.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

template <class T> using V3 = std::array<T, 3>;

const char* const kSeparatedNote =
    "disjoint convex solids: certified by a separating direction (support-function duality, "
    "Arb); unique closest pair (strict convexity); no elimination needed";

// What a certified separated pair reports besides its enclosure and pair.
void set_separated_facts(DistanceResult& out) {
  out.status = Status::Certified;
  out.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
  out.critical_candidates = 1;
  out.eliminated_degree = 0;
  out.note = kSeparatedNote;
}

template <class T> using M3 = std::array<std::array<T, 3>, 3>;

// Conversions from exact rationals to the search scalar (the search is float: it only chooses
// the direction that the Arb evaluation certifies).
template <class T> T from_rational(const Rational& r);
template <> double from_rational<double>(const Rational& r) {
  return r.to_double_approx();
}
template <> Mp from_rational<Mp>(const Rational& r) {
  return mp_from(r);
}
void to_ball(arb_t b, double x) {
  arb_set_d(b, x);
} // exact
void to_ball(arb_t b, const Mp& x) {
  mp_to_ball(b, x);
}

template <class T> T dot(const V3<T>& a, const V3<T>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <class T> V3<T> normalized(const V3<T>& a) {
  using std::sqrt;
  const T r = sqrt(dot(a, a));
  return {a[0] / r, a[1] / r, a[2] / r};
}

template <class T> struct Solid {
  ConvexQuadric::Kind kind;
  M3<T> W; // P = A^+ for a paraboloid
  V3<T> c, a, b, Pb;
  T e, ab;
};
template <class T> V3<T> vec_in(const std::array<Rational, 3>& v) {
  return {from_rational<T>(v[0]), from_rational<T>(v[1]), from_rational<T>(v[2])};
}
template <class T> Solid<T> solid_in(const ConvexQuadric& s) {
  Solid<T> o;
  o.kind = s.kind;
  o.c = vec_in<T>(s.c);
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      o.W[i][j] = from_rational<T>(s.W[i][j]);
  if (s.is_paraboloid()) {
    o.a = vec_in<T>(*s.axis);
    o.b = vec_in<T>(s.b);
    o.Pb = vec_in<T>(s.Pb);
    o.e = from_rational<T>(s.e);
    o.ab = from_rational<T>(s.ab);
  }
  return o;
}

// Paraboloid (see convex_quadric.hpp): h(m), the support point and the Hessian
// (a.b) [P / l - (P m a^T + a (P m)^T) / l^2 + q a a^T / l^3], l = m.a, q = m^T P m.
// False outside the admissible half-space (h = +inf there).
template <class T>
bool paraboloid_eval(const Solid<T>& s, const V3<T>& m, T& h, V3<T>& p, M3<T>& H) {
  const T l = dot(m, s.a);
  if (!(l / s.ab > T(0))) return false;
  V3<T> pm{T(0), T(0), T(0)};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      pm[i] += s.W[i][j] * m[j];
  const T sc = s.ab / l, q = dot(m, pm);
  V3<T> y;
  for (size_t i = 0; i < 3; ++i)
    y[i] = sc * pm[i] - s.Pb[i];
  const T t = -(sc * dot(m, y) + dot(s.b, y) + s.e) / (T(2) * s.ab);
  for (size_t i = 0; i < 3; ++i)
    p[i] = y[i] + t * s.a[i];
  h = dot(m, p);
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      H[i][j] = s.ab * (s.W[i][j] / l - (pm[i] * s.a[j] + s.a[i] * pm[j]) / (l * l) +
                        q * s.a[i] * s.a[j] / (l * l * l));
  return true;
}

// h(m), the support point p(m) and the Hessian of h at m: (W - Wm Wm^T / q) / sqrt(q) for an
// ellipsoid or cylinder. False when m is not admissible (paraboloid half-space).
template <class T> bool support_eval(const Solid<T>& s, const V3<T>& m, T& h, V3<T>& p, M3<T>& H) {
  using std::sqrt;
  if (s.kind == ConvexQuadric::Kind::Paraboloid) return paraboloid_eval(s, m, h, p, H);
  V3<T> wm{T(0), T(0), T(0)};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      wm[i] += s.W[i][j] * m[j];
  const T q = dot(m, wm), r = sqrt(q);
  h = dot(m, s.c) + r;
  for (size_t i = 0; i < 3; ++i) {
    p[i] = s.c[i] + wm[i] / r;
    for (size_t j = 0; j < 3; ++j)
      H[i][j] = (s.W[i][j] - wm[i] * wm[j] / q) / r;
  }
  return true;
}

// phi(n) = -h_A(n) - h_B(-n) (the separation of the slab with normal n), its gradient
// w = p_B(-n) - p_A(n) and Hessian -(H_A(n) + H_B(-n)); phi is concave.
template <class T> struct Dual {
  bool finite = true;
  T phi;
  V3<T> w, pa, pb;
  M3<T> H;
};
template <class T> Dual<T> dual(const Solid<T>& a, const Solid<T>& b, const V3<T>& n) {
  Dual<T> d;
  T ha, hb;
  M3<T> Ha, Hb;
  d.finite =
      support_eval(a, n, ha, d.pa, Ha) && support_eval(b, V3<T>{-n[0], -n[1], -n[2]}, hb, d.pb, Hb);
  if (!d.finite) return d; // phi = -inf: no slab with this normal
  d.phi = -ha - hb;
  for (size_t i = 0; i < 3; ++i) {
    d.w[i] = d.pb[i] - d.pa[i];
    for (size_t j = 0; j < 3; ++j)
      d.H[i][j] = -(Ha[i][j] + Hb[i][j]);
  }
  return d;
}

// The admissible directions: all of R^3, or the plane orthogonal to a cylinder's axis, given
// by an exact basis (rational vectors) and its float orthonormalisation.
struct Directions {
  std::vector<V3<Rational>> exact;
};

template <class T> std::vector<V3<T>> float_basis(const Directions& dirs) {
  std::vector<V3<T>> out;
  for (const auto& e : dirs.exact)
    out.push_back(
        normalized(V3<T>{from_rational<T>(e[0]), from_rational<T>(e[1]), from_rational<T>(e[2])}));
  return out;
}

// Orthonormal tangent vectors of the admissible unit sphere at n.
template <class T> int tangents(const std::vector<V3<T>>& basis, const V3<T>& n, V3<T> (&t)[2]) {
  using std::abs;
  if (basis.size() == 3) {
    size_t k = 0;
    for (size_t i = 1; i < 3; ++i)
      if (abs(n[i]) < abs(n[k])) k = i;
    V3<T> e{T(0), T(0), T(0)};
    e[k] = T(1);
    const T en = dot(e, n);
    t[0] = normalized(V3<T>{e[0] - en * n[0], e[1] - en * n[1], e[2] - en * n[2]});
    t[1] = {n[1] * t[0][2] - n[2] * t[0][1], n[2] * t[0][0] - n[0] * t[0][2],
            n[0] * t[0][1] - n[1] * t[0][0]};
    return 2;
  }
  const T a = dot(n, basis[0]), b = dot(n, basis[1]);
  t[0] = normalized(V3<T>{-b * basis[0][0] + a * basis[1][0], -b * basis[0][1] + a * basis[1][1],
                          -b * basis[0][2] + a * basis[1][2]});
  return 1;
}

// One (regularised) Newton step for the maximum of phi on the admissible unit sphere: the
// tangent Hessian of phi(n)/|n| at a unit n is T^T H T - phi I, negative definite when
// phi > 0; far from the optimum (phi <= 0) |w| replaces phi, a damped gradient step.
template <class T>
V3<T> newton_direction(const std::vector<V3<T>>& basis, const V3<T>& n, const Dual<T>& d,
                       bool regularise) {
  using std::sqrt;
  V3<T> t[2];
  const int k = tangents(basis, n, t);
  T g[2], H[2][2];
  const T wn = T(sqrt(dot(d.w, d.w)));
  const T shift = regularise && !(d.phi > T(0)) ? wn : d.phi;
  for (int i = 0; i < k; ++i) {
    g[i] = dot(t[i], d.w);
    for (int j = 0; j < k; ++j) {
      V3<T> ht{T(0), T(0), T(0)};
      for (size_t r = 0; r < 3; ++r)
        for (size_t c = 0; c < 3; ++c)
          ht[r] += d.H[r][c] * t[j][c];
      H[i][j] = dot(t[i], ht) - (i == j ? shift : T(0));
    }
  }
  T y[2] = {T(0), T(0)};
  if (k == 1) {
    y[0] = -g[0] / H[0][0];
  } else {
    const T det = H[0][0] * H[1][1] - H[0][1] * H[1][0];
    y[0] = -(H[1][1] * g[0] - H[0][1] * g[1]) / det;
    y[1] = -(H[0][0] * g[1] - H[1][0] * g[0]) / det;
  }
  V3<T> step{T(0), T(0), T(0)};
  for (int i = 0; i < k; ++i)
    for (size_t r = 0; r < 3; ++r)
      step[r] += y[i] * t[i][r];
  return step;
}

// Float search (double): damped Newton with backtracking on phi. Returns false when the best
// direction found clearly does not separate (then nothing is certified here).
bool search_double(const Solid<double>& a, const Solid<double>& b, const V3<double>& ca,
                   const V3<double>& cb, const std::vector<V3<double>>& basis, V3<double>& n) {
  // Start: the best (largest finite phi) of the centre-to-centre direction (a paraboloid's
  // "centre" is its vertex), the basis directions and the paraboloid axes, all projected onto
  // the admissible directions.
  auto project = [&](const V3<double>& s) {
    if (basis.size() == 3) return s;
    V3<double> p{0, 0, 0};
    for (const auto& e : basis) {
      const double x = dot(s, e);
      for (size_t i = 0; i < 3; ++i)
        p[i] += x * e[i];
    }
    return p;
  };
  std::vector<V3<double>> starts{V3<double>{cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2]}};
  for (const auto& e : basis)
    starts.push_back(e);
  for (const Solid<double>* s : {&a, &b})
    if (s->kind == ConvexQuadric::Kind::Paraboloid) starts.push_back(s->a);
  bool found = false;
  Dual<double> d;
  for (const auto& s0 : starts)
    for (double sg : {1.0, -1.0}) {
      V3<double> p = project(s0);
      if (!(dot(p, p) > 0)) continue;
      p = normalized(V3<double>{sg * p[0], sg * p[1], sg * p[2]});
      Dual<double> dp = dual(a, b, p);
      if (dp.finite && (!found || dp.phi > d.phi)) {
        found = true;
        n = p;
        d = dp;
      }
    }
  if (!found) return false;
  for (int it = 0; it < 100; ++it) {
    V3<double> step = newton_direction(basis, n, d, true);
    double len = std::sqrt(dot(step, step));
    if (!(len == len)) return false; // nan: degenerate Hessian
    if (len > 1) {
      for (auto& x : step)
        x /= len;
      len = 1;
    }
    bool moved = false;
    for (double t = 1; t > 1e-12; t /= 2) {
      const V3<double> m =
          normalized(V3<double>{n[0] + t * step[0], n[1] + t * step[1], n[2] + t * step[2]});
      Dual<double> dm = dual(a, b, m);
      const double slack = 1e-15 * (std::abs(d.phi) + std::sqrt(dot(d.w, d.w)));
      if (dm.finite && dm.phi >= d.phi - slack) {
        n = m;
        d = dm;
        moved = true;
        break;
      }
    }
    if (!moved || len < 1e-14) break;
  }
  // Clearly negative: the solids overlap or nest (no separating direction exists). A separation
  // below double resolution (gaps of 2^-100) still goes on to the exact certificate.
  const double scale = 1 + std::sqrt(dot(d.pa, d.pa)) + std::sqrt(dot(d.pb, d.pb));
  return d.phi > -1e-9 * scale;
}

// Plain Newton steps in MPFR from the double direction (quadratic convergence), at the
// default MPFR precision set by the caller (MpPrecision).
V3<Mp> refine_mpfr(const ConvexQuadric& ca, const ConvexQuadric& cb, const Directions& dirs,
                   const V3<double>& n0) {
  const Solid<Mp> a = solid_in<Mp>(ca), b = solid_in<Mp>(cb);
  const std::vector<V3<Mp>> basis = float_basis<Mp>(dirs);
  V3<Mp> n{Mp(n0[0]), Mp(n0[1]), Mp(n0[2])};
  if (basis.size() == 2) {
    // Project onto the admissible plane at this precision: the double direction is off it by
    // ~1e-17, and the tangent steps would never remove that (the extended phi is not flat
    // across the plane), capping the accuracy near 30 digits.
    const Mp x = dot(n, basis[0]), y = dot(n, basis[1]);
    for (size_t i = 0; i < 3; ++i)
      n[i] = x * basis[0][i] + y * basis[1][i];
    n = normalized(n);
  }
  const long bits = static_cast<long>(Mp::default_precision() * 3.33);
  for (long good = 50; good < 2 * bits; good *= 2) {
    const Dual<Mp> d = dual(a, b, n);
    if (!d.finite) break;
    const V3<Mp> step = newton_direction(basis, n, d, false);

    n = normalized(V3<Mp>{n[0] + step[0], n[1] + step[1], n[2] + step[2]});
  }
  return n;
}

// The exact direction used for the certificate: the float n written in the exact basis
// (coefficients are the exact values of the float numbers), so it is admissible exactly.
template <class T>
void exact_direction(Ball (&nb)[3], const Directions& dirs, const V3<T>& n, long prec) {
  for (auto& x : nb)
    arb_zero(x.v);
  if (dirs.exact.size() == 3) {
    for (size_t i = 0; i < 3; ++i)
      to_ball(nb[i].v, n[i]);
    return;
  }
  Ball coef, t;
  for (const auto& e : dirs.exact) {
    // coefficient <n, e> / |e|^2 in float (any value is admissible; this one is accurate)
    T ee = T(0), ne = T(0);
    for (size_t i = 0; i < 3; ++i) {
      const T ei = from_rational<T>(e[i]);
      ee += ei * ei;
      ne += n[i] * ei;
    }
    to_ball(coef.v, T(ne / ee));
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(t.v, e[i].raw(), prec);
      arb_addmul(nb[i].v, coef.v, t.v, prec);
    }
  }
}

// From h_A(n), h_B(-n) and the support points (balls at the exact direction n):
// L = -(h_A + h_B) / |n| and U = |p_B - p_A|; true when L > 0 and (U - L) <= 10^-digits L,
// with the enclosure [L, U] and the pair (ball midpoints) written to out.
bool enclose_at_direction(DistanceResult& out, const Ball& ha, const Ball& hb, const Ball (&pa)[3],
                          const Ball (&pb)[3], const Ball (&n)[3], long digits, long prec) {
  Ball len, L, U, tmp;
  for (size_t i = 0; i < 3; ++i) {
    arb_addmul(len.v, n[i].v, n[i].v, prec);
    arb_sub(tmp.v, pb[i].v, pa[i].v, prec);
    arb_addmul(U.v, tmp.v, tmp.v, prec);
  }
  arb_sqrt(len.v, len.v, prec);
  arb_sqrt(U.v, U.v, prec);
  arb_add(L.v, ha.v, hb.v, prec);
  arb_neg(L.v, L.v);
  arb_div(L.v, L.v, len.v, prec);
  Ball d;
  if (!relative_enclosure(d.v, L.v, U.v, digits, prec)) return false;
  set_distance_enclosure(out, d.v, digits);
  std::array<std::array<double, 3>, 2> pr{};
  for (size_t i = 0; i < 3; ++i) {
    pr[0][i] = arf_get_d(arb_midref(pa[i].v), ARF_RND_NEAR);
    pr[1][i] = arf_get_d(arb_midref(pb[i].v), ARF_RND_NEAR);
  }
  out.pairs.push_back(pr);
  return true;
}

// L(n), U(n) at the exact direction; true when L > 0 and (U - L) <= 10^-digits L, with the
// enclosure [L, U] and the pair written to out.
bool certify_direction(const ConvexQuadric& a, const ConvexQuadric& b, const Ball (&n)[3],
                       long digits, DistanceResult& out) {
  const long prec = bits_for(digits + 10);
  Ball ha, hb, tmp, mn[3], pa[3], pb[3];
  for (size_t i = 0; i < 3; ++i)
    arb_neg(mn[i].v, n[i].v);
  support_ball(ha.v, &pa, a, n, prec);
  support_ball(hb.v, &pb, b, mn, prec);
  // A cylinder's support set is the whole line p + t axis (on the surface): slide its point
  // to the foot of the perpendicular from the other support point (a genuine pair still).
  if (a.is_cylinder() || b.is_cylinder()) {
    const auto& ax = a.is_cylinder() ? *a.axis : *b.axis;
    Ball axb[3], wa, aa, t;
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(axb[i].v, ax[i].raw(), prec);
      arb_sub(tmp.v, pb[i].v, pa[i].v, prec);
      arb_addmul(wa.v, tmp.v, axb[i].v, prec);
      arb_addmul(aa.v, axb[i].v, axb[i].v, prec);
    }
    arb_div(t.v, wa.v, aa.v, prec);
    auto& moved = a.is_cylinder() ? pa : pb;
    const int sign = a.is_cylinder() ? 1 : -1;
    for (size_t i = 0; i < 3; ++i) {
      arb_mul(tmp.v, t.v, axb[i].v, prec);
      if (sign > 0)
        arb_add(moved[i].v, moved[i].v, tmp.v, prec);
      else
        arb_sub(moved[i].v, moved[i].v, tmp.v, prec);
    }
  }
  return enclose_at_direction(out, ha, hb, pa, pb, n, digits, prec);
}

bool cross_is_zero(const V3<Rational>& x, const V3<Rational>& y) {
  return x[1] * y[2] == x[2] * y[1] && x[2] * y[0] == x[0] * y[2] && x[0] * y[1] == x[1] * y[0];
}

// The admissible directions of the pair: the plane orthogonal to a cylinder's axis (an exact
// rational basis u = axis x e_k, v = axis x u, k the smallest axis component so u != 0), or
// R^3.
Directions admissible_directions(const ConvexQuadric& a, const ConvexQuadric& b) {
  Directions dirs;
  if (a.is_cylinder() || b.is_cylinder()) {
    const auto& ax = a.is_cylinder() ? *a.axis : *b.axis;
    const auto fr = core::plane_frame(ax);
    dirs.exact = {fr[0], fr[1]};
  } else {
    dirs.exact = {V3<Rational>{Rational(1), Rational(0), Rational(0)},
                  V3<Rational>{Rational(0), Rational(1), Rational(0)},
                  V3<Rational>{Rational(0), Rational(0), Rational(1)}};
  }
  return dirs;
}

// ---- two ellipsoids posed in doubles (core::ShapeSpec: centre, radii, quaternion) ----
//
// The ellipsoid is c + R D S^2 with D = diag(radii) and R = Rq / s the quaternion's rotation
// (Rq its undivided polynomial matrix, s = |q|^2, so Rq^T Rq = s^2 I exactly). With
// m = D Rq^T n: h(n) = n.c + |m| / s and p(n) = c + Rq D m / (s |m|), the same numbers as
// n.c + sqrt(n^T W n) and c + W n / sqrt(n^T W n) with W = R D^2 R^T (convex_quadric.hpp),
// evaluated in Arb straight from the doubles (exact as balls) without forming rationals.

// The doubles scaled by one power of two so that the largest magnitude is near 1 (the search
// is scale-free; tiny or huge shapes would otherwise underflow or overflow W): the float
// solid W = R D^2 R^T, and the centre.
Solid<double> posed_solid(const core::ShapeSpec& sp, int shift) {
  Solid<double> o;
  o.kind = ConvexQuadric::Kind::Ellipsoid;
  double R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  if (sp.rotated) {
    const double w = sp.quaternion[0], x = sp.quaternion[1], y = sp.quaternion[2],
                 z = sp.quaternion[3], s = w * w + x * x + y * y + z * z;
    const double q[3][3] = {
        {w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
        {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
        {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        R[i][j] = q[i][j] / s;
  }
  double r2[3];
  for (size_t k = 0; k < 3; ++k) {
    // A semi-axis far below the largest magnitude (1e-300 against 1) would underflow W to 0
    // and the support point to 0/0: the search sees it as 2^-200 instead (it moves the
    // proposed direction by about that much; the certificate uses the exact radii).
    const double r = std::max(std::ldexp(sp.radii[k], shift), std::ldexp(1.0, -200));
    r2[k] = r * r;
    o.c[k] = std::ldexp(sp.center[k], shift);
  }
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      o.W[i][j] = 0;
      for (size_t k = 0; k < 3; ++k)
        o.W[i][j] += R[i][k] * R[j][k] * r2[k];
    }
  return o;
}

// The pose as balls at precision prec: RD = Rq D (row-major, Rq's columns scaled by the
// radii), s = |q|^2 and the centre (the doubles exactly). Contiguous arb_struct arrays, so that
// every sum of products is one arb_dot (exact accumulation, one rounding: a fraction of the
// cost of chained arb_addmul).
struct PosedBalls {
  arb_struct rd[9], c[3];
  Ball s;
  PosedBalls() {
    for (auto& x : rd)
      arb_init(&x);
    for (auto& x : c)
      arb_init(&x);
  }
  ~PosedBalls() {
    for (auto& x : rd)
      arb_clear(&x);
    for (auto& x : c)
      arb_clear(&x);
  }
  PosedBalls(const PosedBalls&) = delete;
  PosedBalls& operator=(const PosedBalls&) = delete;
};

// Contiguous balls: arb_dot reads arrays of arb_struct.
template <size_t N> struct Balls {
  arb_struct v[N];
  Balls() {
    for (auto& x : v)
      arb_init(&x);
  }
  ~Balls() {
    for (auto& x : v)
      arb_clear(&x);
  }
  Balls(const Balls&) = delete;
  Balls& operator=(const Balls&) = delete;
};

void posed_balls(PosedBalls& e, const core::ShapeSpec& sp, long prec) {
  for (size_t k = 0; k < 3; ++k)
    arb_set_d(&e.c[k], sp.center[k]);
  if (!sp.rotated) {
    for (size_t i = 0; i < 3; ++i)
      for (size_t k = 0; k < 3; ++k)
        i == k ? arb_set_d(&e.rd[3 * i + k], sp.radii[k]) : arb_zero(&e.rd[3 * i + k]);
    arb_one(e.s.v);
    return;
  }
  // p[i][j] = q_i q_j with q = (w, x, y, z): the diagonal of Rq is ww +- xx +- yy +- zz, the
  // rest 2 (q_i q_j -+ w q_k). (Ten products and sums: cheaper than arb_dot on such short
  // vectors.)
  Ball q[4], pr[4][4];
  for (size_t i = 0; i < 4; ++i)
    arb_set_d(q[i].v, sp.quaternion[i]);
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i; j < 4; ++j)
      arb_mul(pr[i][j].v, q[i].v, q[j].v, prec);
  auto diag = [&](arb_t out, int sx, int sy, int sz) {
    arb_set(out, pr[0][0].v);
    (sx > 0 ? arb_add : arb_sub)(out, out, pr[1][1].v, prec);
    (sy > 0 ? arb_add : arb_sub)(out, out, pr[2][2].v, prec);
    (sz > 0 ? arb_add : arb_sub)(out, out, pr[3][3].v, prec);
  };
  Balls<9> rq;
  diag(e.s.v, 1, 1, 1);
  diag(&rq.v[0], 1, -1, -1);
  diag(&rq.v[4], -1, 1, -1);
  diag(&rq.v[8], -1, -1, 1);
  auto off = [&](arb_t out, const Ball& a, const Ball& b, int sign) {
    (sign > 0 ? arb_add : arb_sub)(out, a.v, b.v, prec);
    arb_mul_2exp_si(out, out, 1);
  };
  off(&rq.v[1], pr[1][2], pr[0][3], -1); // 2 (xy - wz)
  off(&rq.v[3], pr[1][2], pr[0][3], 1);  // 2 (xy + wz)
  off(&rq.v[2], pr[1][3], pr[0][2], 1);  // 2 (xz + wy)
  off(&rq.v[6], pr[1][3], pr[0][2], -1); // 2 (xz - wy)
  off(&rq.v[5], pr[2][3], pr[0][1], -1); // 2 (yz - wx)
  off(&rq.v[7], pr[2][3], pr[0][1], 1);  // 2 (yz + wx)
  Ball r;
  for (size_t k = 0; k < 3; ++k) {
    arb_set_d(r.v, sp.radii[k]);
    for (size_t i = 0; i < 3; ++i)
      arb_mul(&e.rd[3 * i + k], &rq.v[3 * i + k], r.v, prec);
  }
}

// h(n) and the support point p(n) of the posed ellipsoid, for the exact direction n (balls):
// m = D Rq^T n = RD^T n, h = n.c + |m| / s, p = c + RD m / (s |m|).
void posed_support(Ball& h, Ball (&p)[3], const PosedBalls& e, const arb_struct* n, long prec) {
  Balls<3> m;
  Ball mm, len, t;
  for (size_t k = 0; k < 3; ++k)
    arb_dot(&m.v[k], nullptr, 0, e.rd + k, 3, n, 1, 3, prec);
  arb_dot(mm.v, nullptr, 0, m.v, 1, m.v, 1, 3, prec);
  arb_sqrt(len.v, mm.v, prec); // |m| > 0: n != 0 and Rq, D invertible (else not finite)
  arb_div(t.v, len.v, e.s.v, prec);
  arb_dot(h.v, t.v, 0, n, 1, e.c, 1, 3, prec);
  arb_mul(t.v, e.s.v, len.v, prec);
  arb_inv(t.v, t.v, prec);
  for (size_t k = 0; k < 3; ++k)
    arb_mul(&m.v[k], &m.v[k], t.v, prec);
  for (size_t i = 0; i < 3; ++i)
    arb_dot(p[i].v, &e.c[i], 0, e.rd + 3 * i, 1, m.v, 1, 3, prec);
}

} // namespace

std::optional<DistanceResult> separated_convex_distance(const ConvexQuadric& a,
                                                        const ConvexQuadric& b, long digits) {
  // An ellipsoid (bounded, strictly convex) makes the minimum attained and its pair unique;
  // two paraboloids may have no minimizer. Two cylinders with parallel axes are accepted (the
  // directions orthogonal to the common axis are admissible for both; the caller reports the
  // line of closest pairs); crossed cylinders have their closed form (cylinder_pair.hpp).
  const bool parallel_cylinders =
      a.is_cylinder() && b.is_cylinder() && cross_is_zero(*a.axis, *b.axis);
  // A paraboloid is strictly convex too: with it the pair is unique, and a certified L = U
  // shows the minimum is attained (unbounded solids may otherwise only approach each other).
  const bool strictly_convex =
      a.is_ellipsoid() || b.is_ellipsoid() || a.is_paraboloid() || b.is_paraboloid();
  if (!strictly_convex && !parallel_cylinders) return std::nullopt;
  const Directions dirs = admissible_directions(a, b);
  const Solid<double> sa = solid_in<double>(a), sb = solid_in<double>(b);
  const std::vector<V3<double>> basis = float_basis<double>(dirs);
  V3<double> n{};
  if (!search_double(sa, sb, a.cd, b.cd, basis, n)) return std::nullopt;

  DistanceResult out;
  set_separated_facts(out);
  const long prec = bits_for(digits + 10);
  Ball nb[3];
  if (digits <= 15) {
    exact_direction(nb, dirs, n, prec);
    if (certify_direction(a, b, nb, digits, out)) return out;
  }
  // More digits (or an ill-conditioned pair): Newton in MPFR, then certify again.
  {
    // Every MPFR temporary of the refinement and of the exact-direction conversion must carry
    // the working precision (Boost gives new values the default precision).
    const MpPrecision scope(bits_for(digits));
    const V3<Mp> nm = refine_mpfr(a, b, dirs, n);
    exact_direction(nb, dirs, nm, prec);
  }
  if (certify_direction(a, b, nb, digits, out)) return out;
  return std::nullopt;
}

std::optional<DistanceResult> separated_convex_distance_float(const ConvexQuadric& a,
                                                              const ConvexQuadric& b) {
  if (!a.is_ellipsoid() && !b.is_ellipsoid()) return std::nullopt;
  const Directions dirs = admissible_directions(a, b);
  const Solid<double> sa = solid_in<double>(a), sb = solid_in<double>(b);
  const std::vector<V3<double>> basis = float_basis<double>(dirs);
  V3<double> n{};
  if (!search_double(sa, sb, a.cd, b.cd, basis, n)) return std::nullopt;
  const Dual<double> d = dual(sa, sb, n);
  if (!d.finite || !(d.phi > 0)) return std::nullopt;
  DistanceResult out;
  out.status = Status::Uncertified;
  // One pair if the float separation holds (strict convexity), which nothing proved here.
  out.minimizers = Minimizers::undecided(1);
  out.critical_candidates = 1;
  V3<double> pa = d.pa, pb = d.pb;
  if (a.is_cylinder() || b.is_cylinder()) { // slide along the cylinder's line of support
    const auto& ax = a.is_cylinder() ? *a.axis : *b.axis;
    const V3<double> u = normalized(
        V3<double>{ax[0].to_double_approx(), ax[1].to_double_approx(), ax[2].to_double_approx()});
    const double t = dot(d.w, u);
    for (size_t i = 0; i < 3; ++i)
      (a.is_cylinder() ? pa : pb)[i] += (a.is_cylinder() ? t : -t) * u[i];
  }
  const double dist =
      std::sqrt((pb[0] - pa[0]) * (pb[0] - pa[0]) + (pb[1] - pa[1]) * (pb[1] - pa[1]) +
                (pb[2] - pa[2]) * (pb[2] - pa[2]));
  out.estimate = Estimate{dist}; // one float value, never an enclosure
  out.pairs.push_back({pa, pb});
  out.note = "float mode: double-precision separating-direction search, NOT certified (the "
             "distance of the float pair, in result.estimate; no ball arithmetic)";
  return out;
}

namespace {

// Float: (p - c)^T W^-1 (p - c) < 0.99 for the ellipsoid (W = R D^2 R^T, c) of s (Cramer's
// rule; false when W is not clearly invertible).
bool centre_inside(const V3<double>& p, const Solid<double>& s) {
  const auto& W = s.W;
  const double c00 = W[1][1] * W[2][2] - W[1][2] * W[2][1],
               c01 = W[1][2] * W[2][0] - W[1][0] * W[2][2],
               c02 = W[1][0] * W[2][1] - W[1][1] * W[2][0];
  const double det = W[0][0] * c00 + W[0][1] * c01 + W[0][2] * c02;
  if (!(det > 0) || !std::isfinite(det)) return false;
  const double d[3] = {p[0] - s.c[0], p[1] - s.c[1], p[2] - s.c[2]};
  // adj(W) d (W symmetric: the adjugate is symmetric too)
  const double c11 = W[0][0] * W[2][2] - W[0][2] * W[2][0],
               c12 = W[0][1] * W[2][0] - W[0][0] * W[2][1],
               c22 = W[0][0] * W[1][1] - W[0][1] * W[1][0];
  const double v[3] = {c00 * d[0] + c01 * d[1] + c02 * d[2], c01 * d[0] + c11 * d[1] + c12 * d[2],
                       c02 * d[0] + c12 * d[1] + c22 * d[2]};
  const double q = (d[0] * v[0] + d[1] * v[1] + d[2] * v[2]) / det;
  return q < 0.99;
}

} // namespace

std::optional<DistanceResult> separated_posed_ellipsoids(const core::ShapeSpec& a,
                                                         const core::ShapeSpec& b, long digits,
                                                         bool* no_separation) {
  if (no_separation != nullptr) *no_separation = false;
  // The float search on data scaled by 2^shift (largest magnitude near 1).
  double big = 0;
  for (const core::ShapeSpec* sp : {&a, &b})
    for (size_t k = 0; k < 3; ++k)
      big = std::max({big, std::fabs(sp->center[k]), sp->radii[k]});
  int e = 0;
  std::frexp(big, &e);
  const Solid<double> sa = posed_solid(a, -e), sb = posed_solid(b, -e);
  // A centre clearly inside the other solid: the solids overlap, no plane separates them, and
  // the search below would fail after all its iterations (the nested pairs' common case). A
  // float test only routes: a wrong guess leaves the pair to the next routes, as a failed
  // search does.
  if (centre_inside(sa.c, sb) || centre_inside(sb.c, sa)) {
    if (no_separation != nullptr) *no_separation = true;
    return std::nullopt;
  }
  const std::vector<V3<double>> basis{V3<double>{1, 0, 0}, V3<double>{0, 1, 0},
                                      V3<double>{0, 0, 1}};
  V3<double> n{};
  if (!search_double(sa, sb, sa.c, sb.c, basis, n)) {
    if (no_separation != nullptr) *no_separation = true;
    return std::nullopt;
  }
  // The certificate at the exact direction n (its doubles), in Arb from the exact doubles.
  Balls<3> nb, mn;
  Ball nball[3];
  for (size_t i = 0; i < 3; ++i) {
    if (!std::isfinite(n[i])) return std::nullopt;
    arb_set_d(&nb.v[i], n[i]);
    arb_neg(&mn.v[i], &nb.v[i]);
    arb_set_d(nball[i].v, n[i]);
  }
  DistanceResult out;
  set_separated_facts(out);
  // One machine word first, then two, when they leave a wide margin (Arb keeps them inline: no
  // allocation), then the usual working precision (a small gap against the solids' size).
  const long full = bits_for(digits + 10);
  for (long prec : {std::min(64L, full), std::min(128L, full), full}) {
    PosedBalls ea, eb;
    Ball ha, hb, pa[3], pb[3];
    posed_balls(ea, a, prec);
    posed_balls(eb, b, prec);
    posed_support(ha, pa, ea, nb.v, prec);
    posed_support(hb, pb, eb, mn.v, prec);
    if (enclose_at_direction(out, ha, hb, pa, pb, nball, digits, prec)) return out;
    if (prec == full) break;
  }
  return std::nullopt;
}

} // namespace surfcert::certify
