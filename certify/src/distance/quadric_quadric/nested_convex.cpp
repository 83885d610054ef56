#include "surfcert/certify/distance/nested_convex.hpp"
#include "surfcert/core/budget.hpp"

#include <CGAL/Interval_nt.h>
#include <flint/fmpq.h>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

template <class T> using V3 = std::array<T, 3>;

// Boxes examined before giving up: a continuum of minimizers (or a nearly degenerate pair)
// keeps boxes alive around it and would split forever.
constexpr int kBoxBudget = 3000;
// Boxes up to this half-width also get the Krawczyk test on the box enlarged by half.
constexpr double kInflateRadius = 1.0 / 16;
// Smallest half-width split further: below it the pair is degenerate for this method.
constexpr double kMinRadius = 1.0 / (1 << 26);

// ---- two interval types behind one interface: CGAL's double intervals (outward rounding;
// the caller holds CGAL::Protect_FPU_rounding) for the branch and bound, Arb balls at any
// precision for the contraction to the requested digits ----

using DI = CGAL::Interval_nt<false>;

// Arb balls (algebra::Ball) with value semantics; their operators, and the helpers below,
// round at ball_precision(), which a PrecisionScope sets.
using algebra::ball_precision;
using algebra::PrecisionScope;

// The interface: certain signs and comparisons, the symmetric hull [-sup|x|, sup|x|], exact
// midpoints, tight squares, intersections.
bool finite(const DI& x) {
  return std::isfinite(x.inf()) && std::isfinite(x.sup());
}
bool finite(const Ball& x) {
  return arb_is_finite(x.v) != 0;
}
bool is_zero(const DI& x) {
  return x.inf() == 0 && x.sup() == 0;
}
bool is_zero(const Ball& x) {
  return arb_is_zero(x.v) != 0;
}
bool pos(const DI& x) {
  return x.inf() > 0;
}
bool pos(const Ball& x) {
  return arb_is_positive(x.v) != 0;
}
bool neg(const DI& x) {
  return x.sup() < 0;
}
bool gt(const DI& a, const DI& b) {
  return a.inf() > b.sup();
}
bool gt(const Ball& a, const Ball& b) {
  return arb_gt(a.v, b.v) != 0;
}
DI sqrt_(const DI& x) {
  return CGAL::sqrt(x);
}
Ball sqrt_(const Ball& x) {
  Ball r;
  arb_sqrt(r.v, x.v, ball_precision());
  return r;
}
DI sym(const DI& x) {
  const double s = std::max(-x.inf(), x.sup());
  return DI(-s, s);
}
Ball sym(const Ball& x) {
  Ball r;
  arb_get_mag(arb_radref(r.v), x.v);
  return r;
}
DI lower_point(const DI& x) {
  return DI(x.inf());
}
Ball lower_point(const Ball& x) {
  Ball r;
  arb_get_lbound_arf(arb_midref(r.v), x.v, ball_precision());
  return r;
}
DI upper_point(const DI& x) {
  return DI(x.sup());
}
Ball upper_point(const Ball& x) {
  Ball r;
  arb_get_ubound_arf(arb_midref(r.v), x.v, ball_precision());
  return r;
}
// A point of x, whatever the rounding mode (upward under the guards): inf + sup rounds to a
// value between 2 inf and 2 sup (both representable; chart boxes are far from overflow),
// halving is exact, so the result lies in x; only a point is needed (the forms enclose G and
// its derivatives at that point).
DI midpoint(const DI& x) {
  return DI(0.5 * (x.inf() + x.sup()));
}
Ball midpoint(const Ball& x) {
  Ball r;
  arb_get_mid_arb(r.v, x.v);
  return r;
}
DI square(const DI& x) {
  return CGAL::square(x);
}
Ball square(const Ball& x) {
  Ball r;
  if (!arb_contains_zero(x.v)) {
    arb_sqr(r.v, x.v, ball_precision());
    return r;
  }
  arb_get_mag(arb_radref(r.v), x.v); // [0, |x|^2] as a ball
  mag_mul(arb_radref(r.v), arb_radref(r.v), arb_radref(r.v));
  mag_mul_2exp_si(arb_radref(r.v), arb_radref(r.v), -1);
  arf_set_mag(arb_midref(r.v), arb_radref(r.v));
  return r;
}
bool intersect(DI& out, const DI& a, const DI& b) {
  const double lo = std::max(a.inf(), b.inf()), hi = std::min(a.sup(), b.sup());
  if (!(lo <= hi)) return false;
  out = DI(lo, hi);
  return true;
}
bool intersect(Ball& out, const Ball& a, const Ball& b) {
  return arb_intersection(out.v, a.v, b.v, ball_precision()) != 0;
}
bool interior(const DI& X, const DI& K) {
  return X.inf() < K.inf() && K.sup() < X.sup();
}
bool interior(const Ball& X, const Ball& K) {
  return arb_contains_interior(X.v, K.v) != 0;
}
bool disjoint(const DI& a, const DI& b) {
  return a.sup() < b.inf() || b.sup() < a.inf();
}
bool disjoint(const Ball& a, const Ball& b) {
  return arb_overlaps(a.v, b.v) == 0;
}
bool contains(const DI& X, const DI& Y) {
  return X.inf() <= Y.inf() && Y.sup() <= X.sup();
}
bool contains(const Ball& X, const Ball& Y) {
  return arb_contains(X.v, Y.v) != 0;
}

// Outward conversions.
DI to_di(const Ball& x) {
  // The bounds in stack arfs (no Ball temporaries: a context converts ~150 balls).
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  arb_get_lbound_arf(lo, x.v, ball_precision());
  arb_get_ubound_arf(hi, x.v, ball_precision());
  const DI r(arf_get_d(lo, ARF_RND_FLOOR), arf_get_d(hi, ARF_RND_CEIL));
  arf_clear(lo);
  arf_clear(hi);
  return r;
}
Ball to_ab(const DI& x) {
  Ball r;
  arf_t lo, hi;
  arf_init_set_si(lo, 0);
  arf_init_set_si(hi, 0);
  arf_set_d(lo, x.inf());
  arf_set_d(hi, x.sup());
  arb_set_interval_arf(r.v, lo, hi, ball_precision());
  arf_clear(lo);
  arf_clear(hi);
  return r;
}
Ball from_rational(const Rational& q) {
  Ball r;
  arb_set_fmpq(r.v, q.raw(), ball_precision());
  return r;
}

// ---- the directions ----

// The admissible directions n = sum_l coef_l E_l: E the standard basis (an ellipsoid outside),
// or an exact orthogonal basis of the plane orthogonal to the cylinder's axis (D = 2).
struct Frame {
  int D = 3;
  bool standard = true; ///< E is the standard basis
  std::array<V3<Rational>, 3> E;
};

// A chart: coef_a = s and the other k = D - 1 coefficients are the coordinates u. Every real
// u gives a nonzero direction, and the boxes |u_i| <= 1 of the 2D charts cover all directions.
struct Chart {
  int a = 0, s = 1;
  int id() const { return 2 * a + (s > 0 ? 0 : 1); }
};
int free_index(const Chart& ch, int i) {
  return i < ch.a ? i : i + 1;
}

// ---- truncated Taylor arithmetic in the k chart coordinates (degree <= 3) ----

// Monomials u0^i u1^j of degree <= 3 (u1 absent for k = 1) ordered by degree, and the
// product table per truncation degree.
struct Monomials {
  int k = 0;
  int count[4] = {0, 0, 0, 0}; // monomials of degree <= d
  int e[10][2] = {};
  int index[4][4] = {};
  struct Prod {
    int a, b, c;
  };
  std::vector<Prod> prod[4]; // products of total degree <= d
};

Monomials make_monomials(int k) {
  Monomials M;
  M.k = k;
  for (auto& row : M.index)
    for (int& x : row)
      x = -1;
  int n = 0;
  for (int d = 0; d <= 3; ++d) {
    for (int i = d; i >= 0; --i) {
      const int j = d - i;
      if (k == 1 && j > 0) continue;
      M.e[n][0] = i;
      M.e[n][1] = j;
      M.index[i][j] = n++;
    }
    M.count[d] = n;
  }
  for (int d = 0; d <= 3; ++d)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const int i = M.e[a][0] + M.e[b][0], j = M.e[a][1] + M.e[b][1];
        if (i + j <= d) M.prod[d].push_back({a, b, M.index[i][j]});
      }
  return M;
}

const Monomials& monomials(int k) {
  static const Monomials m1 = make_monomials(1), m2 = make_monomials(2);
  return k == 1 ? m1 : m2;
}
int degree(const Monomials& M, int a) {
  return M.e[a][0] + M.e[a][1];
}
int unit_index(const Monomials& M, int j) {
  return j == 0 ? M.index[1][0] : M.index[0][1];
}

// A function of u near a base point b (a point, or a box: then every coefficient encloses the
// Taylor coefficient at every point of the box): coefficient c[a] of (u - b)^e[a].
template <class I> struct TP { I c[10]; };

template <class I>
void tp_mul(TP<I>& out, const TP<I>& A, const TP<I>& B, const Monomials& M, int deg) {
  for (int a = 0; a < M.count[deg]; ++a)
    out.c[a] = I(0);
  for (const auto& t : M.prod[deg])
    if (!is_zero(A.c[t.a]) && !is_zero(B.c[t.b])) out.c[t.c] += A.c[t.a] * B.c[t.b];
}

// f(x) = f0 + f1 x~ + f2 x~^2 + f3 x~^3 truncated at degree deg, x~ = x - x(b).
// The powers x~^2 and x~^3 truncated at degree 3 for a quadratic x~ = L + A without constant
// term (L linear, A quadratic: what tp_quadratic gives) in two variables: L^2 + 2 L A and
// L^3, written out (15 products instead of the 22 of two general products, and squares where
// a coefficient is squared, which are tighter in interval arithmetic).
template <class I> void quadratic_powers(TP<I>& sq, TP<I>& cu, const TP<I>& x, const Monomials& M) {
  const I &l0 = x.c[M.index[1][0]], &l1 = x.c[M.index[0][1]];
  const I &a00 = x.c[M.index[2][0]], &a01 = x.c[M.index[1][1]], &a11 = x.c[M.index[0][2]];
  for (int a = 0; a < M.count[1]; ++a)
    sq.c[a] = cu.c[a] = I(0);
  for (int a = M.count[1]; a < M.count[2]; ++a)
    cu.c[a] = I(0);
  const I l00 = square(l0), l11 = square(l1), l01 = l0 * l1;
  sq.c[M.index[2][0]] = l00;
  sq.c[M.index[1][1]] = I(2) * l01;
  sq.c[M.index[0][2]] = l11;
  sq.c[M.index[3][0]] = I(2) * (l0 * a00);
  sq.c[M.index[2][1]] = I(2) * (l0 * a01 + l1 * a00);
  sq.c[M.index[1][2]] = I(2) * (l0 * a11 + l1 * a01);
  sq.c[M.index[0][3]] = I(2) * (l1 * a11);
  cu.c[M.index[3][0]] = l00 * l0;
  cu.c[M.index[2][1]] = I(3) * (l00 * l1);
  cu.c[M.index[1][2]] = I(3) * (l0 * l11);
  cu.c[M.index[0][3]] = l11 * l1;
}

template <class I>
void tp_func(TP<I>& out, const TP<I>& x, const I (&f)[4], const Monomials& M, int deg) {
  if (deg == 3 && M.k == 2 && is_zero(x.c[M.index[3][0]]) && is_zero(x.c[M.index[2][1]]) &&
      is_zero(x.c[M.index[1][2]]) && is_zero(x.c[M.index[0][3]])) {
    TP<I> sq, cu;
    quadratic_powers(sq, cu, x, M);
    out.c[0] = f[0];
    for (int a = 1; a < M.count[2]; ++a)
      out.c[a] = f[1] * x.c[a] + f[2] * sq.c[a];
    for (int a = M.count[2]; a < M.count[3]; ++a)
      out.c[a] = f[1] * x.c[a] + f[2] * sq.c[a] + f[3] * cu.c[a];
    return;
  }
  TP<I> xt, sq;
  xt.c[0] = I(0);
  for (int a = 1; a < M.count[deg]; ++a)
    xt.c[a] = x.c[a];
  tp_mul(sq, xt, xt, M, deg);
  out.c[0] = f[0];
  for (int a = 1; a < M.count[deg]; ++a)
    out.c[a] = f[1] * xt.c[a] + f[2] * sq.c[a];
  if (deg < 3) return;
  TP<I> cu;
  tp_mul(cu, sq, xt, M, deg);
  for (int a = M.count[2]; a < M.count[3]; ++a)
    out.c[a] += f[3] * cu.c[a];
}

// sqrt(x) (inverse = false) or 1/sqrt(x) (inverse = true), the scalar Taylor coefficients
// f_i = f^(i)(x(b)) / i! left in f. False unless x(b) > 0.
template <class I>
bool tp_sqrt(TP<I>& out, I (&f)[4], const TP<I>& x, bool inverse, const Monomials& M, int deg) {
  if (!pos(x.c[0])) return false;
  const I r = sqrt_(x.c[0]), y = I(1) / r, y2 = y * y, y3 = y * y2, y5 = y3 * y2;
  if (!inverse) {
    f[0] = r;
    f[1] = y * I(0.5);
    f[2] = -y3 * I(0.125);
    f[3] = y5 * I(0.0625);
  } else {
    f[0] = y;
    f[1] = -y3 * I(0.5);
    f[2] = y5 * I(0.375);
    f[3] = -(y5 * y2) * I(0.3125);
  }
  tp_func(out, x, f, M, deg);
  return true;
}

// A quadratic polynomial of the chart coordinates (coefficients of 1, u0, u1, u0^2, u0 u1,
// u1^2) re-expanded at the base point b.
template <class I> void tp_quadratic(TP<I>& out, const I (&q)[6], const I* b, const Monomials& M) {
  const I b1 = M.k == 2 ? b[1] : I(0);
  for (int a = 0; a < M.count[3]; ++a)
    out.c[a] = I(0);
  out.c[0] = q[0] + b[0] * (q[1] + q[3] * b[0] + q[4] * b1) + b1 * (q[2] + q[5] * b1);
  out.c[M.index[1][0]] = q[1] + I(2) * q[3] * b[0] + q[4] * b1;
  out.c[M.index[2][0]] = q[3];
  if (M.k == 1) return;
  out.c[M.index[0][1]] = q[2] + q[4] * b[0] + I(2) * q[5] * b1;
  out.c[M.index[1][1]] = q[4];
  out.c[M.index[0][2]] = q[5];
}

// ---- the function on a chart ----

// On a chart, G(u) = F(n(u)) / |n(u)| = (l(u) + sqrt(Qo(u)) - sqrt(Qi(u))) / sqrt(N(u)) with
// l(u) = n.(c_out - c_in) affine, Qo = n^T W_out n, Qi = n^T W_in n, N = n.n quadratic in u:
// a short expression whose Taylor expansion keeps the strong cancellation between the two
// support functions that separate interval evaluations would lose.
template <class I> struct ChartPoly { I Qo[6], Qi[6], N[6], l[3]; };

template <class I> struct Ctx {
  int D = 3, k = 2;
  I E[3][3];
  I Wi[3][3], Wo[3][3], dc[3]; // the support matrices and c_out - c_in (the Lagrangian bound)
  std::array<ChartPoly<I>, 6> cp;
};

// The chart polynomials in Arb at the current precision (exact rationals rounded once).
// The support matrices as balls at the working precision, from a posed ellipsoid's doubles
// (posed_support_balls) instead of the exact rationals of ConvexQuadric::W.
struct PosedW {
  Ball in[3][3], out[3][3];
};

Ctx<Ball> make_ctx(const ConvexQuadric& inner, const ConvexQuadric& outer, const Frame& f,
                   const PosedW* pw) {
  Ctx<Ball> C;
  C.D = f.D;
  C.k = f.D - 1;
  Ball Wi[3][3], Wo[3][3], dc[3];
  for (size_t i = 0; i < 3; ++i) {
    for (size_t l = 0; l < 3; ++l) {
      C.E[l][i] = from_rational(f.E[l][i]);
      if (l < i) { // W is symmetric
        Wi[i][l] = Wi[l][i];
        Wo[i][l] = Wo[l][i];
        continue;
      }
      Wi[i][l] = pw != nullptr ? pw->in[i][l] : from_rational(inner.W[i][l]);
      Wo[i][l] = pw != nullptr ? pw->out[i][l] : from_rational(outer.W[i][l]);
    }
    dc[i] = from_rational(outer.c[i] - inner.c[i]); // a common translation cancels exactly
  }
  for (size_t i = 0; i < 3; ++i) {
    C.dc[i] = dc[i];
    for (size_t l = 0; l < 3; ++l) {
      C.Wi[i][l] = Wi[i][l];
      C.Wo[i][l] = Wo[i][l];
    }
  }
  for (int a = 0; a < C.D; ++a)
    for (int s : {1, -1}) {
      const Chart ch{a, s};
      ChartPoly<Ball>& P = C.cp[static_cast<size_t>(ch.id())];
      const int slot[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}}; // coefficient of v_x^T M v_y
      if (f.standard) {
        // v_x = sgn_x e_idx_x: the forms are signed entries of W (exact, no products).
        const int idx[3] = {a, free_index(ch, 0), free_index(ch, 1)}, sgn[3] = {s, 1, 1};
        for (int x = 0; x <= C.k; ++x) {
          const auto ix = static_cast<size_t>(idx[x]);
          for (int y = x; y <= C.k; ++y) {
            const auto iy = static_cast<size_t>(idx[y]);
            const Ball two(sgn[x] * sgn[y] * (x == y ? 1 : 2));
            P.Qo[slot[x][y]] = Wo[ix][iy] * two;
            P.Qi[slot[x][y]] = Wi[ix][iy] * two;
            P.N[slot[x][y]] = Ball(x == y ? 1 : 0);
          }
          P.l[x] = dc[ix] * Ball(sgn[x]);
        }
        continue;
      }
      Ball v[3][3]; // v0 = s E_a, v1, v2 = the free basis vectors
      for (size_t i = 0; i < 3; ++i) {
        v[0][i] = C.E[a][i] * Ball(s);
        for (int j = 0; j < C.k; ++j)
          v[j + 1][i] = C.E[free_index(ch, j)][i];
      }
      for (int x = 0; x <= C.k; ++x)
        for (int y = x; y <= C.k; ++y) {
          Ball qo(0), qi(0), nn(0);
          for (size_t i = 0; i < 3; ++i) {
            Ball wo(0), wi(0);
            for (size_t j = 0; j < 3; ++j) {
              wo += Wo[i][j] * v[y][j];
              wi += Wi[i][j] * v[y][j];
            }
            qo += v[x][i] * wo;
            qi += v[x][i] * wi;
            nn += v[x][i] * v[y][i];
          }
          const Ball two(x == y ? 1 : 2);
          P.Qo[slot[x][y]] = qo * two;
          P.Qi[slot[x][y]] = qi * two;
          P.N[slot[x][y]] = nn * two;
        }
      for (int x = 0; x <= C.k; ++x) {
        P.l[x] = Ball(0);
        for (size_t i = 0; i < 3; ++i)
          P.l[x] += v[x][i] * dc[i];
      }
    }
  return C;
}

Ctx<DI> to_di(const Ctx<Ball>& A) {
  Ctx<DI> C;
  C.D = A.D;
  C.k = A.k;
  for (size_t i = 0; i < 3; ++i) {
    C.dc[i] = to_di(A.dc[i]);
    for (size_t l = 0; l < 3; ++l) {
      C.E[i][l] = to_di(A.E[i][l]);
      C.Wi[i][l] = to_di(A.Wi[i][l]);
      C.Wo[i][l] = to_di(A.Wo[i][l]);
    }
  }
  for (size_t c = 0; c < 6; ++c) {
    for (size_t i = 0; i < 6; ++i) {
      C.cp[c].Qo[i] = to_di(A.cp[c].Qo[i]);
      C.cp[c].Qi[i] = to_di(A.cp[c].Qi[i]);
      C.cp[c].N[i] = to_di(A.cp[c].N[i]);
    }
    for (size_t i = 0; i < 3; ++i)
      C.cp[c].l[i] = to_di(A.cp[c].l[i]);
  }
  return C;
}

// num = l + so - si re-expanded at b.
template <class I>
void numerator(TP<I>& num, const TP<I>& so, const TP<I>& si, const ChartPoly<I>& P, const I* b,
               const Monomials& M, int deg) {
  for (int a = 0; a < M.count[deg]; ++a)
    num.c[a] = so.c[a] - si.c[a];
  num.c[0] += P.l[0];
  for (int j = 0; j < M.k; ++j) {
    num.c[0] += P.l[j + 1] * b[j];
    if (deg >= 1) num.c[unit_index(M, j)] += P.l[j + 1];
  }
}

// The Taylor expansion of G at the base b (for a box: enclosures of the Taylor coefficients
// at every point of it) up to degree deg. False if a quadratic form may vanish there.
template <class I> bool g_taylor(TP<I>& G, const Ctx<I>& C, const Chart& ch, const I* b, int deg) {
  const Monomials& M = monomials(C.k);
  const ChartPoly<I>& P = C.cp[static_cast<size_t>(ch.id())];
  TP<I> q, so, si, rn, num;
  I f[4];
  tp_quadratic(q, P.Qo, b, M);
  if (!tp_sqrt(so, f, q, false, M, deg)) return false;
  tp_quadratic(q, P.Qi, b, M);
  if (!tp_sqrt(si, f, q, false, M, deg)) return false;
  tp_quadratic(q, P.N, b, M);
  if (!tp_sqrt(rn, f, q, true, M, deg)) return false;
  numerator(num, so, si, P, b, M, deg);
  tp_mul(G, num, rn, M, deg);
  return finite(G.c[0]);
}

// ---- a box X = m + delta: a Taylor model of G at m (cubic polynomial in u - m with the exact
// Taylor coefficients at m, plus a remainder over the box), and, for the boxes that survive
// it, the expansion over the whole box (derivative enclosures) ----

template <class I> struct BoxForms {
  I m[2];
  TP<I> Tm; // Taylor coefficients of G at m, degree <= 3
  I R;      // symmetric: |G(u) - Tm(u - m)| <= sup R on the box
  TP<I> TX; // expansion over the box (box_derivatives)
  I dp[10]; // enclosures of (u - m)^e over the box (squares in [0, r^2])
  I rp[10]; // symmetric hulls of the same
};

// Per-degree symmetric bounds sum_{|a| = d} |c_a| |u - m|^a of a polynomial part.
template <class I>
void degree_bounds(I (&Bd)[4], const TP<I>& P, const BoxForms<I>& B, const Monomials& M) {
  for (int d = 0; d <= 3; ++d)
    Bd[d] = I(0);
  for (int a = 0; a < M.count[3]; ++a)
    Bd[degree(M, a)] += sym(P.c[a]) * B.rp[a];
}

// Taylor model of sqrt(Q) or 1/sqrt(Q) for Q(m + h) = q0 + L(h) + A(h) (exact: linear L,
// positive semidefinite quadratic A since Q = n^T W n with n affine): the cubic Taylor
// polynomial, and the remainder
//   |f2| |A|^2 + |f3| ((|L| + |A|)^3 - |L|^3) + max|f^(4)| / 24 (|L| + |A|)^4
// (the dropped degree 4+ terms of f2 q~^2 + f3 q~^3, and Lagrange's remainder on the range
// of Q, which is >= q0 - |L| since A >= 0). False if Q may reach 0 on the box.
template <class I>
bool tm_sqrt(TP<I>& out, I& rem, const TP<I>& q, bool inverse, const BoxForms<I>& B,
             const Monomials& M) {
  I Bd[4], f[4];
  degree_bounds(Bd, q, B, M);
  const I &l = Bd[1], &a = Bd[2];
  const I low = lower_point(q.c[0] - l);
  if (!pos(low)) return false;
  if (!tp_sqrt(out, f, q, inverse, M, 3)) return false;
  // max |f^(4)| / 24 at the lowest Q: (5/128) Q^(-7/2) for sqrt, (35/128) Q^(-9/2) for 1/sqrt
  const I y = I(1) / sqrt_(low), y2 = y * y, y4 = y2 * y2;
  const I K = sym(inverse ? y4 * y4 * y * I(35.0 / 128) : y4 * y2 * y * I(5.0 / 128));
  const I s = l + a, s2 = s * s;
  rem = K * s2 * s2 + sym(f[2]) * a * a +
        sym(f[3]) * a * (I(3) * l * l + I(3) * l * a + a * a); // (l+a)^3 - l^3
  return finite(rem);
}

// Product of two Taylor models: the product truncated at degree 3; the remainder bounds the
// dropped terms, |P1| R2, |P2| R1 and R1 R2.
template <class I>
void tm_mul(TP<I>& out, I& rem, const TP<I>& P1, const I& R1, const TP<I>& P2, const I& R2,
            const BoxForms<I>& B, const Monomials& M) {
  tp_mul(out, P1, P2, M, 3);
  I B1[4], B2[4], n1(0), n2(0);
  degree_bounds(B1, P1, B, M);
  degree_bounds(B2, P2, B, M);
  rem = I(0);
  for (int d1 = 0; d1 <= 3; ++d1) {
    n1 += B1[d1];
    n2 += B2[d1];
    for (int d2 = 4 - d1; d2 <= 3; ++d2)
      rem += B1[d1] * B2[d2];
  }
  rem += n1 * R2 + n2 * R1 + R1 * R2;
}

// The Taylor model of G on the box X, and the monomial ranges. False when it cannot be formed
// (a quadratic form may vanish on the box: only large boxes).
template <class I> bool box_value(BoxForms<I>& B, const Ctx<I>& C, const Chart& ch, const I* X) {
  const Monomials& M = monomials(C.k);
  const ChartPoly<I>& P = C.cp[static_cast<size_t>(ch.id())];
  I pw[2][4];
  for (int j = 0; j < C.k; ++j) {
    B.m[j] = midpoint(X[j]);
    const I d = X[j] - B.m[j];
    pw[j][0] = I(1);
    pw[j][1] = d;
    pw[j][2] = square(d);
    pw[j][3] = d * pw[j][2];
  }
  for (int a = 0; a < M.count[3]; ++a) {
    B.dp[a] = pw[0][M.e[a][0]];
    if (C.k == 2 && M.e[a][1] > 0) B.dp[a] = B.dp[a] * pw[1][M.e[a][1]];
    B.rp[a] = sym(B.dp[a]);
  }
  TP<I> q, so, si, rn, num;
  I Rso, Rsi, Rrn;
  tp_quadratic(q, P.Qo, B.m, M);
  if (!tm_sqrt(so, Rso, q, false, B, M)) return false;
  tp_quadratic(q, P.Qi, B.m, M);
  if (!tm_sqrt(si, Rsi, q, false, B, M)) return false;
  tp_quadratic(q, P.N, B.m, M);
  if (!tm_sqrt(rn, Rrn, q, true, B, M)) return false;
  numerator(num, so, si, P, B.m, M, 3);
  tm_mul(B.Tm, B.R, num, Rso + Rsi, rn, Rrn, B, M);
  return finite(B.Tm.c[0]) && finite(B.R);
}

// G over the box: sum_a Tm_a (u - m)^a + R.
template <class I> I value_enclosure(const BoxForms<I>& B, const Monomials& M) {
  I V = B.R;
  for (int a = 0; a < M.count[3]; ++a)
    V += B.Tm.c[a] * B.dp[a];
  return V;
}

// G over a part Y of the box of B, from B's Taylor model (valid on all of that box): the
// polynomial's range over the smaller Y is tighter, and costs a few products instead of a new
// model. After a split, a quarter of the children are cleared this way.
template <class I> I model_on_subbox(const BoxForms<I>& B, const I* Y, const Monomials& M) {
  I pw[2][4];
  for (int j = 0; j < M.k; ++j) {
    const I d = Y[j] - B.m[j];
    pw[j][0] = I(1);
    pw[j][1] = d;
    pw[j][2] = square(d);
    pw[j][3] = d * pw[j][2];
  }
  I V = B.R;
  for (int a = 0; a < M.count[3]; ++a) {
    I p = pw[0][M.e[a][0]];
    if (M.k == 2 && M.e[a][1] > 0) p = p * pw[1][M.e[a][1]];
    V += B.Tm.c[a] * p;
  }
  return V;
}

// The coefficient of (u - m)^a in the third-order Taylor form: at m up to degree 2, over the
// box (Lagrange remainder) for degree 3.
template <class I> const I& coef(const BoxForms<I>& B, const Monomials& M, int a) {
  return degree(M, a) <= 2 ? B.Tm.c[a] : B.TX.c[a];
}

// Intersects the enclosure x with another enclosure y of the same quantity.
template <class I> void refine(I& x, const I& y) {
  if (!finite(y)) return;
  I t;
  if (!finite(x))
    x = y;
  else if (intersect(t, x, y)) // never empty: both contain the same value
    x = t;
}

// dG/du_j over the box: sum_a a_j coef_a (u - m)^(a - e_j), refined by the direct enclosure.
template <class I> I gradient_enclosure(const BoxForms<I>& B, const Monomials& M, int j) {
  I g(0);
  for (int a = 0; a < M.count[3]; ++a) {
    int e[2] = {M.e[a][0], M.e[a][1]};
    if (e[j] == 0) continue;
    const int mult = e[j]--;
    g += coef(B, M, a) * I(mult) * B.dp[M.index[e[0]][e[1]]];
  }
  refine(g, B.TX.c[unit_index(M, j)]);
  return g;
}

// d2G/du_j du_l over the box (degree 2 at m, degree 3 over the box), refined by the direct
// enclosure.
template <class I> void hessian_enclosure(I (&H)[2][2], const BoxForms<I>& B, const Monomials& M) {
  for (int j = 0; j < M.k; ++j)
    for (int l = j; l < M.k; ++l) {
      H[j][l] = I(0);
      for (int a = M.count[1]; a < M.count[3]; ++a) {
        int e[2] = {M.e[a][0], M.e[a][1]};
        if (e[j] == 0) continue;
        int mult = e[j]--;
        if (e[l] == 0) continue;
        mult *= e[l]--;
        H[j][l] += coef(B, M, a) * I(mult) * B.dp[M.index[e[0]][e[1]]];
      }
      const int a2 = j != l ? M.index[1][1] : (j == 0 ? M.index[2][0] : M.index[0][2]);
      refine(H[j][l], B.TX.c[a2] * I(j == l ? 2 : 1));
      H[l][j] = H[j][l];
    }
}

// The Krawczyk operator on the box X: K = m - Y g(m) + (I - Y H(X)) (X - m), Y an approximate
// inverse of the Hessian at m (any matrix is valid). Any zero of the gradient in X lies in K;
// K inside the interior of X proves exactly one (a nonsingular critical point); K disjoint
// from X proves none. False when Y cannot be formed or something is not finite.
template <class I>
bool krawczyk(I* K, const BoxForms<I>& B, const I (&H)[2][2], const I* X, int k) {
  const Monomials& M = monomials(k);
  I Y[2][2];
  const I h00 = B.Tm.c[M.index[2][0]] * I(2);
  if (k == 1) {
    Y[0][0] = I(1) / h00;
  } else {
    const I h11 = B.Tm.c[M.index[0][2]] * I(2), h01 = B.Tm.c[M.index[1][1]];
    const I det = h00 * h11 - h01 * h01;
    Y[0][0] = h11 / det;
    Y[1][1] = h00 / det;
    Y[0][1] = -h01 / det;
    Y[1][0] = Y[0][1];
  }
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      if (!finite(Y[i][j])) return false;
      Y[i][j] = midpoint(Y[i][j]);
    }
  for (int i = 0; i < k; ++i) {
    K[i] = B.m[i];
    for (int j = 0; j < k; ++j) {
      K[i] = K[i] - Y[i][j] * B.Tm.c[unit_index(M, j)];
      I Mij(i == j ? 1 : 0);
      for (int l = 0; l < k; ++l)
        Mij = Mij - Y[i][l] * H[l][j];
      K[i] += Mij * (X[j] - B.m[j]);
    }
    if (!finite(K[i])) return false;
  }
  return true;
}

// Krawczyk from scratch on the box X: the Taylor model, the box expansion, the operator.
template <class I>
bool krawczyk_box(I* K, BoxForms<I>& B, const Ctx<I>& C, const Chart& ch, const I* X) {
  const Monomials& M = monomials(C.k);
  if (!box_value(B, C, ch, X) || !g_taylor(B.TX, C, ch, X, 3)) return false;
  I H[2][2];
  hessian_enclosure(H, B, M);
  return krawczyk(K, B, H, X, C.k);
}

// ---- float search (double): it only chooses where the certificate looks ----

struct FloatPair {
  int D;
  std::array<V3<double>, 3> E{};
  V3<double> dc{};
  std::array<std::array<double, 3>, 3> Win{}, Wout{};
};

// G(u), its gradient and Hessian in double, from the 3D support functions (h = n.c + r,
// grad = c + W n / r, Hess = (W - W n n^T W / r^2) / r with r = sqrt(n^T W n)).
double eval_float(const FloatPair& P, const Chart& ch, const double* u, double* g, double (*H)[2]) {
  const int k = P.D - 1;
  V3<double> n{};
  for (size_t i = 0; i < 3; ++i) {
    n[i] = ch.s * P.E[static_cast<size_t>(ch.a)][i];
    for (int j = 0; j < k; ++j)
      n[i] += u[j] * P.E[static_cast<size_t>(free_index(ch, j))][i];
  }
  double r[2], gr[2][3], Hr[2][3][3];
  for (int s = 0; s < 2; ++s) {
    const auto& W = s == 0 ? P.Wout : P.Win;
    double w[3] = {0, 0, 0}, q = 0;
    for (size_t i = 0; i < 3; ++i) {
      for (size_t j = 0; j < 3; ++j)
        w[i] += W[i][j] * n[j];
      q += n[i] * w[i];
    }
    r[s] = std::sqrt(std::max(q, 1e-300));
    for (size_t i = 0; i < 3; ++i) {
      gr[s][i] = w[i] / r[s];
      for (size_t j = 0; j < 3; ++j)
        Hr[s][i][j] = (W[i][j] - w[i] * w[j] / q) / r[s];
    }
  }
  const double N2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2], N = std::sqrt(N2);
  const double F = r[0] - r[1] + n[0] * P.dc[0] + n[1] * P.dc[1] + n[2] * P.dc[2];
  if (g == nullptr) return F / N;
  double gF[3], gg[3], Hg[3][3];
  for (size_t i = 0; i < 3; ++i) {
    gF[i] = gr[0][i] - gr[1][i] + P.dc[i];
    gg[i] = (gF[i] - F / N2 * n[i]) / N;
  }
  for (size_t i = 0; i < 3; ++i)
    for (size_t l = 0; l < 3; ++l)
      Hg[i][l] = (Hr[0][i][l] - Hr[1][i][l] - (gF[i] * n[l] + gF[l] * n[i]) / N2 -
                  (i == l ? F / N2 : 0) + 3 * F / (N2 * N2) * n[i] * n[l]) /
                 N;
  for (int j = 0; j < k; ++j) {
    const auto& e = P.E[static_cast<size_t>(free_index(ch, j))];
    g[j] = e[0] * gg[0] + e[1] * gg[1] + e[2] * gg[2];
    for (int m = 0; m < k; ++m) {
      const auto& f = P.E[static_cast<size_t>(free_index(ch, m))];
      double s = 0;
      for (size_t i = 0; i < 3; ++i)
        for (size_t l = 0; l < 3; ++l)
          s += f[i] * Hg[i][l] * e[l];
      H[m][j] = s;
    }
  }
  return F / N;
}

struct Point {
  Chart ch;
  double u[2] = {0, 0};
  double G = 0;
};

// Moves to the chart whose base coefficient is the largest (keeps |u| <= 1).
void rechart(Point& x, int D) {
  double coef[3] = {0, 0, 0};
  coef[x.ch.a] = x.ch.s;
  for (int j = 0; j < D - 1; ++j)
    coef[free_index(x.ch, j)] = x.u[j];
  int a = 0;
  for (int l = 1; l < D; ++l)
    if (std::fabs(coef[l]) > std::fabs(coef[a])) a = l;
  x.ch = Chart{a, coef[a] > 0 ? 1 : -1};
  for (int j = 0; j < D - 1; ++j)
    x.u[j] = coef[free_index(x.ch, j)] / std::fabs(coef[a]);
}

// Damped Newton on G from x (gradient steps where the Hessian is not positive definite).
void newton_float(const FloatPair& P, Point& x) {
  const int k = P.D - 1;
  for (int it = 0; it < 40; ++it) {
    double g[2] = {0, 0}, H[2][2] = {{0, 0}, {0, 0}}, step[2] = {0, 0};
    x.G = eval_float(P, x.ch, x.u, g, H);
    const double det = k == 1 ? H[0][0] : H[0][0] * H[1][1] - H[0][1] * H[1][0];
    if (H[0][0] > 0 && det > 0) {
      if (k == 1) {
        step[0] = -g[0] / H[0][0];
      } else {
        step[0] = -(H[1][1] * g[0] - H[0][1] * g[1]) / det;
        step[1] = -(H[0][0] * g[1] - H[1][0] * g[0]) / det;
      }
    } else {
      for (int j = 0; j < k; ++j)
        step[j] = -0.1 * g[j] / (std::fabs(x.G) + 1e-300);
    }
    double len = std::hypot(step[0], step[1]);
    if (!(len == len)) return;
    if (len > 0.5) {
      step[0] *= 0.5 / len;
      step[1] *= 0.5 / len;
      len = 0.5;
    }
    bool moved = false;
    for (double t = 1; t > 1e-6; t /= 2) {
      Point y = x;
      for (int j = 0; j < k; ++j)
        y.u[j] += t * step[j];
      y.G = eval_float(P, y.ch, y.u, nullptr, nullptr);
      if (y.G <= x.G + 1e-15 * std::fabs(x.G)) {
        x = y;
        moved = true;
        break;
      }
    }
    rechart(x, P.D);
    if (!moved || len < 1e-15) return;
  }
}

// ---- branch and bound (double intervals) ----

// A box of a chart: centre and half-width in chart coordinates (dyadic: exact in double).
struct Box {
  Chart ch;
  double mid[2] = {0, 0};
  double rad = 1;
};

void box_intervals(DI* X, const Box& b, int k, double rad) {
  for (int j = 0; j < k; ++j)
    X[j] = DI(b.mid[j] - rad, b.mid[j] + rad); // exact: dyadic
}

// A box with exactly one critical direction (Krawczyk) and an enclosure of G over it.
struct Critical {
  Chart ch;
  DI X[2] = {DI(0), DI(0)}; // X[1] unused on the circle (k = 1)
  DI value = DI(0);
};

// Every box of the charts is dropped (G > U on it, or no critical point in it) or holds
// exactly one critical point (then recorded in crit). U: a certified upper bound of the
// minimum, lowered by the midpoint values met on the way. False when the budget is exhausted
// or a box becomes too small (degenerate minima: continua, or ill-conditioned ones).
bool branch_and_bound(const Ctx<DI>& C, const std::vector<Chart>& charts, DI& U,
                      std::vector<Critical>& crit) {
  const int k = C.k;
  const Monomials& M = monomials(k);
  std::vector<Box> stack;
  for (const Chart& ch : charts) // a 4 x 4 (2D) or 4 (1D) split of each chart
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < (k == 2 ? 4 : 1); ++j) {
        Box b;
        b.ch = ch;
        b.rad = 0.25;
        b.mid[0] = -0.75 + 0.5 * i;
        b.mid[1] = k == 2 ? -0.75 + 0.5 * j : 0;
        stack.push_back(b);
      }
  int examined = 0;
  while (!stack.empty()) {
    core::check_budget();
    const Box b = stack.back();
    stack.pop_back();
    if (++examined > kBoxBudget) return false;
    DI X[2] = {DI(0), DI(0)};
    box_intervals(X, b, k, b.rad);
    bool covered = false; // inside a proven box: its only possible critical point is known
    for (const Critical& c : crit)
      if (c.ch.id() == b.ch.id()) {
        bool in = true;
        for (int j = 0; j < k; ++j)
          in = in && contains(c.X[j], X[j]);
        covered = covered || in;
      }
    if (covered) continue;
    BoxForms<DI> B;
    const bool modelled = box_value(B, C, b.ch, X);
    if (modelled) {
      if (B.Tm.c[0].sup() < U.sup()) U = upper_point(B.Tm.c[0]); // G(m) >= min G
      const DI V = value_enclosure(B, M);
      if (gt(V, U)) continue; // cannot hold the minimum
      if (g_taylor(B.TX, C, b.ch, X, 3)) {
        bool monotone = false; // a gradient component keeps its sign: no critical point
        for (int j = 0; j < k; ++j) {
          const DI g = gradient_enclosure(B, M, j);
          monotone = monotone || pos(g) || neg(g);
        }
        if (monotone) continue;
        DI H[2][2], K[2];
        hessian_enclosure(H, B, M);
        if (krawczyk(K, B, H, X, k)) {
          bool in = true, out = false;
          for (int j = 0; j < k; ++j) {
            in = in && interior(X[j], K[j]);
            out = out || disjoint(X[j], K[j]);
          }
          if (out) continue; // no critical point in the box
          if (in) {
            crit.push_back(Critical{b.ch, {X[0], X[1]}, V});
            continue;
          }
        }
        if (b.rad <= kInflateRadius) {
          // The box enlarged by half: a critical point on (or near) an edge of the box lies
          // well inside it (the first attempt can never succeed for such a point).
          Critical c;
          c.ch = b.ch;
          box_intervals(c.X, b, k, 1.5 * b.rad);
          BoxForms<DI> Bi;
          bool proven = krawczyk_box(K, Bi, C, b.ch, c.X);
          for (int j = 0; j < k && proven; ++j)
            proven = interior(c.X[j], K[j]);
          if (proven) {
            c.value = value_enclosure(Bi, M);
            crit.push_back(c);
            continue;
          }
        }
      }
    }
    if (b.rad <= kMinRadius) return false;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < (k == 2 ? 2 : 1); ++j) {
        Box s = b;
        s.rad = b.rad / 2;
        s.mid[0] = b.mid[0] + (i == 0 ? -s.rad : s.rad);
        if (k == 2) s.mid[1] = b.mid[1] + (j == 0 ? -s.rad : s.rad);
        if (modelled) {
          DI Xs[2] = {DI(0), DI(0)};
          box_intervals(Xs, s, k, s.rad);
          if (gt(model_on_subbox(B, Xs, M), U)) continue; // the parent's model clears it
        }
        stack.push_back(s);
      }
  }
  return true;
}

// ---- the Lagrangian localisation (ellipsoid inside ellipsoid): one proven box instead of the
// branch and bound ----
//
// With p = c_in + W_in x and q = c_out + W_out y (W the support matrices, so p lies in the
// inner solid iff x^T W_in x <= 1 and q outside the interior of the outer one iff
// y^T W_out y >= 1), for any lambda, mu >= 0
//   Lag(x, y) = |p - q|^2 + lambda (x^T W_in x - 1) - mu (y^T W_out y - 1) <= |p - q|^2
// on every such pair (an S-lemma / Lagrangian-duality bound). Lag is a quadratic in
// z = (x, y); when its Hessian 2 Q satisfies Q >= s I with s > 0 (proven by an interval
// Cholesky of Q - s I), Lag(z) >= Lag(z0) + 2 r.(z - z0) + s |z - z0|^2 at any point z0 (r the
// half gradient at z0). Every direction n with |G(n)| <= U gives such a pair with
// |p - q| = |G(n)| <= U (p the inner support point, x = n / h_in(n), and q = p + G(n) n on the
// outer support plane; G < -U is excluded by the sign of G at one direction outside the box,
// see below), so its z lies within Delta of z0, where s Delta^2 - 2 |r| Delta
// <= U^2 - Lag(z0): x, a positive multiple of n, lies in a tiny box, hence n in a tiny chart
// box. The multipliers and z0 come from the float minimizer n0 (x0 = n0 / h_in, y0 = n0 /
// h_out, lambda = G0 h_in, mu = G0 h_out: the KKT point, where Lag(z0) = G0^2); they only
// propose. When Q >= s I holds (the relaxation is tight: one global minimum, ~99% of random
// nested pairs), every direction with G <= U, the minimizer among them, lies in one box X that
// the Krawczyk test proves to hold exactly one critical point of G: that point is the unique
// minimizing direction, and its value is d. A positive lower bound also proves the nesting
// (p = q would give Lag <= 0). False (the caller runs the branch and bound) when a step fails:
// a non-tight relaxation (Q indefinite at the KKT multipliers), several minima (Q singular),
// or a box that does not prove.
bool lagrangian_box(const Ctx<DI>& C, const FloatPair& P, const Point& best, const DI& U,
                    std::vector<Critical>& crit) {
  if (C.D != 3) return false;
  // The float proposal: the unit direction, the KKT point and the multipliers.
  double n[3] = {0, 0, 0};
  n[best.ch.a] = best.ch.s;
  for (int j = 0; j < 2; ++j)
    n[free_index(best.ch, j)] = best.u[j];
  const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n)
    x /= nn;
  auto quad = [&](const std::array<std::array<double, 3>, 3>& W) {
    double q = 0;
    for (size_t i = 0; i < 3; ++i)
      for (size_t l = 0; l < 3; ++l)
        q += n[i] * W[i][l] * n[l];
    return std::sqrt(q);
  };
  const double hi = quad(P.Win), ho = quad(P.Wout);
  const double G0 = ho - hi + n[0] * P.dc[0] + n[1] * P.dc[1] + n[2] * P.dc[2];
  if (!(G0 > 0) || !(hi > 0) || !(ho > 0)) return false;
  double z[6];
  for (size_t i = 0; i < 3; ++i) {
    z[i] = n[i] / hi;
    z[i + 3] = n[i] / ho;
  }
  const double lam = G0 * hi, mu = G0 * ho;

  // Rigorous: Lag(z0) and the half gradient r at z0, Q, all in double intervals.
  const DI Lam(lam), Mu(mu);
  DI w[3], ax[3], by[3]; // w = p - q, ax = W_in x, by = W_out y
  for (size_t i = 0; i < 3; ++i) {
    ax[i] = by[i] = DI(0);
    for (size_t l = 0; l < 3; ++l) {
      ax[i] += C.Wi[i][l] * DI(z[l]);
      by[i] += C.Wo[i][l] * DI(z[l + 3]);
    }
    w[i] = ax[i] - by[i] - C.dc[i];
  }
  DI lag = DI(0), xax(0), yby(0);
  for (size_t i = 0; i < 3; ++i) {
    lag += square(w[i]);
    xax += DI(z[i]) * ax[i];
    yby += DI(z[i + 3]) * by[i];
  }
  lag += Lam * (xax - DI(1)) - Mu * (yby - DI(1));
  DI r2(0); // |r|^2, r = (W_in (w + lambda x), -W_out (w + mu y))
  for (size_t i = 0; i < 3; ++i) {
    DI gx(0), gy(0);
    for (size_t l = 0; l < 3; ++l) {
      gx += C.Wi[i][l] * (w[l] + Lam * DI(z[l]));
      gy += C.Wo[i][l] * (w[l] + Mu * DI(z[l + 3]));
    }
    r2 += square(gx) + square(gy);
  }
  // Q = [[W_in W_in + lambda W_in, -W_in W_out], [-W_out W_in, W_out W_out - mu W_out]].
  DI Q[6][6];
  for (size_t i = 0; i < 3; ++i)
    for (size_t l = 0; l < 3; ++l) {
      DI xx(0), xy(0), yy(0);
      for (size_t m = 0; m < 3; ++m) {
        xx += C.Wi[i][m] * C.Wi[m][l];
        xy += C.Wi[i][m] * C.Wo[m][l];
        yy += C.Wo[i][m] * C.Wo[m][l];
      }
      Q[i][l] = xx + Lam * C.Wi[i][l];
      Q[i + 3][l + 3] = yy - Mu * C.Wo[i][l];
      Q[i][l + 3] = -xy;
      Q[l + 3][i] = -xy;
    }
  // s: the largest of scale 4^-k (k = 1..12) at which a float Cholesky of Q - s I succeeds,
  // halved, then proven by an interval Cholesky (Q - s I positive definite => Q >= s I).
  auto cholesky = [&](auto one, double s) {
    using T = decltype(one);
    auto entry = [&](int i, int j) -> T {
      if constexpr (std::is_same_v<T, DI>)
        return Q[i][j];
      else
        return 0.5 * (Q[i][j].inf() + Q[i][j].sup()); // a float proposal only
    };
    T L[6][6];
    for (int j = 0; j < 6; ++j) {
      T sum = entry(j, j) - T(s);
      for (int k = 0; k < j; ++k)
        sum = sum - L[j][k] * L[j][k];
      if constexpr (std::is_same_v<T, DI>) {
        if (!pos(sum)) return false;
        L[j][j] = sqrt_(sum);
      } else {
        if (!(sum > 0)) return false;
        L[j][j] = std::sqrt(sum);
      }
      for (int i = j + 1; i < 6; ++i) {
        T t = entry(i, j);
        for (int k = 0; k < j; ++k)
          t = t - L[i][k] * L[j][k];
        L[i][j] = t / L[j][j];
      }
    }
    return true;
  };
  double scale = 0;
  for (int j = 0; j < 6; ++j)
    scale = std::max(scale, Q[j][j].sup());
  double s = 0;
  for (int k = 1; k <= 12 && s == 0; ++k)
    if (cholesky(0.0, scale * std::ldexp(1.0, -2 * k))) s = scale * std::ldexp(1.0, -2 * k - 1);
  if (s == 0 || !cholesky(DI(0), s)) return false;
  // Delta <= (|r| + sqrt(|r|^2 + s e)) / s, e = U^2 - Lag(z0).
  const DI S(s), e = square(U) - lag, disc = r2 + S * e;
  if (!(disc.sup() >= 0)) return false; // no pair at <= U: impossible (G(n0) <= U)
  const DI delta = (sqrt_(DI(0, r2.sup())) + sqrt_(DI(0, disc.sup()))) / S;
  const double D = delta.sup();
  // The chart of n0's largest coordinate; x in the box x0 +- Delta.
  int a = 0;
  for (int l = 1; l < 3; ++l)
    if (std::fabs(n[l]) > std::fabs(n[a])) a = l;
  const Chart ch{a, n[a] > 0 ? 1 : -1};
  DI xb[3];
  for (size_t i = 0; i < 3; ++i)
    xb[i] = DI(z[i]) + DI(-D, D);
  const DI base = xb[a] * DI(ch.s);
  if (!pos(base)) return false;
  DI X[2];
  for (int j = 0; j < 2; ++j) {
    const DI u = xb[free_index(ch, j)] / base;              // every direction with G <= U
    const double u0 = n[free_index(ch, j)] / (ch.s * n[a]); // a float centre
    const double rho = 2 * std::max(u.sup() - u0, u0 - u.inf()) + 0x1p-40;
    if (!(rho < 1.0 / 64)) return false;
    X[j] = DI(u0) + DI(-rho, rho);
    if (!contains(X[j], u)) return false;
  }
  // The pair of a direction n is at distance |G(n)|, not G(n): the bound above confines the
  // directions with -U <= G <= U to X, not those with G < -U (the inner solid poking out).
  // Outside X (on the sphere, the complement of a small closed disk: connected) |G| > U, so G
  // has there the sign it has at one point outside X; at -n0 (chart (a, -s), coordinates
  // -u0) G > 0 proves G > U outside X: every direction with G <= U, the minimizers among
  // them, lies in X. (Without it only the float grid, which found no clearly negative value,
  // stood for the directions with G < -U.)
  {
    DI far[2];
    for (int j = 0; j < 2; ++j)
      far[j] = -DI(n[free_index(ch, j)] / (ch.s * n[a])); // any point of the chart would do
    TP<DI> T;
    if (!g_taylor(T, C, Chart{a, -ch.s}, far, 0) || !pos(T.c[0])) return false;
  }
  DI K[2];
  BoxForms<DI> B;
  if (!krawczyk_box(K, B, C, ch, X)) return false;
  for (int j = 0; j < 2; ++j)
    if (!interior(X[j], K[j])) return false;
  crit.push_back(Critical{ch, {X[0], X[1]}, value_enclosure(B, monomials(2))});
  return true;
}

// ---- contraction and the report (Arb, final precision) ----

// A proven box at the final precision: E contracts onto its critical point, V encloses G there.
struct Tight {
  Chart ch;
  Ball X[2], E[2], V;
};

// Largest log2 radius of a box.
double log2_size(const Ball* E, int k) {
  double size = -1e300;
  for (int j = 0; j < k; ++j)
    size = std::max(size, mag_get_d_log2_approx(arb_radref(E[j].v)));
  return size;
}

// A small box around the critical point of G near the box E, to be proven by the caller:
// Newton steps from the Newton point of E's centre (K: Krawczyk's image of E, whose centre
// is that point) until the step is tiny, then the last point with a radius of twice the last
// step (plus a few ulps). A box proven with little margin (the first Krawczyk images barely
// shrink it: the Hessian varies across a large box) has its centre far from the critical
// point, where one Newton step does not get close enough. The points only choose where to
// look (float-like); the caller's Krawczyk test on the box proves. False when a step fails
// or leaves E.
bool newton_box(Ball (&N)[2], const Ctx<Ball>& C, const Chart& ch, const BoxForms<Ball>& B,
                const Ball (&K)[2], const Ball* E) {
  const int k = C.k;
  Ball P[2], step[2];
  for (int j = 0; j < k; ++j) {
    P[j] = midpoint(K[j]); // the Newton point m - Y g(m)
    step[j] = P[j] - B.m[j];
  }
  for (int it = 0; it < 12; ++it) {
    bool tiny = true; // the next step would be below the precision: P is as good as it gets
    for (int j = 0; j < k; ++j)
      tiny = tiny && arf_cmpabs_2exp_si(arb_midref(step[j].v), 20 - ball_precision() / 2) < 0;
    if (tiny) break;
    Ball KP[2];
    BoxForms<Ball> BP;
    if (!krawczyk_box(KP, BP, C, ch, P)) return false; // a point box: its image is the step
    for (int j = 0; j < k; ++j) {
      Ball next = midpoint(KP[j]);
      step[j] = next - P[j];
      P[j] = next;
    }
  }
  for (int j = 0; j < k; ++j) {
    N[j] = P[j];
    arb_get_mag(arb_radref(N[j].v), step[j].v);
    mag_mul_2exp_si(arb_radref(N[j].v), arb_radref(N[j].v), 1);
    mag_add_ui_2exp_si(arb_radref(N[j].v), arb_radref(N[j].v), 1, 40 - ball_precision());
    if (!contains(E[j], N[j])) return false;
  }
  return true;
}

// Contracts the box E of chart ch, which holds the unique critical point of a proven box, onto
// it in double intervals: E = E cap K(E) while that halves the box (every critical point of E
// lies in its Krawczyk image K(E), whatever E). The quadratic convergence takes a proven box
// of width ~2^-4 to ~2^-40 in a few cheap steps, so the Arb contraction to the final digits
// starts next to the point (one or two Arb steps instead of five or six).
void contract_di(DI* E, const Ctx<DI>& C, const Chart& ch) {
  const int k = C.k;
  CGAL::Protect_FPU_rounding<true> guard; // the double intervals round outward
  for (int it = 0; it < 20; ++it) {
    BoxForms<DI> B;
    DI K[2], Z[2];
    if (!krawczyk_box(K, B, C, ch, E)) return;
    double before = 0, after = 0;
    for (int j = 0; j < k; ++j) {
      if (!intersect(Z[j], E[j], K[j])) return; // impossible: the point is in both
      before = std::max(before, E[j].sup() - E[j].inf());
      after = std::max(after, Z[j].sup() - Z[j].inf());
    }
    for (int j = 0; j < k; ++j)
      E[j] = Z[j];
    if (!(after < 0.5 * before)) return;
  }
}

// Contracts E (initially inside the proven box X, holding its unique critical point) onto its
// critical point until the value enclosure V has the relative width tol / 4. Each step intersects E
// with its Krawczyk image; when that barely shrinks (a box proven with little margin), a small
// box around the Newton point inside E is proven instead (same point: E holds only one).
// Quadratic convergence either way. False if it stalls.
bool tighten(Tight& c, const Ctx<Ball>& C, const Ball& tol) {
  const int k = C.k;
  const Monomials& M = monomials(k);
  for (int it = 0; it < 200; ++it) {
    BoxForms<Ball> B;
    if (!box_value(B, C, c.ch, c.E)) return false;
    c.V = value_enclosure(B, M);
    Ball w;
    arb_get_rad_arb(w.v, c.V.v);
    if (finite(c.V) && gt(lower_point(c.V) * tol, w * Ball(8))) return true;
    Ball K[2], H[2][2], Z[2];
    if (!g_taylor(B.TX, C, c.ch, c.E, 3)) return false;
    hessian_enclosure(H, B, M);
    if (!krawczyk(K, B, H, c.E, k)) return false;
    for (int j = 0; j < k; ++j)
      if (!intersect(Z[j], c.E[j], K[j])) return false; // impossible: the point is in both
    const double before = log2_size(c.E, k), after = log2_size(Z, k);
    if (after > before - 1) {
      Ball N[2], KN[2];
      BoxForms<Ball> BN;
      bool ok = newton_box(N, C, c.ch, B, K, c.E);
      ok = ok && krawczyk_box(KN, BN, C, c.ch, N);
      for (int j = 0; j < k && ok; ++j)
        ok = interior(N[j], KN[j]);
      if (ok) {
        for (int j = 0; j < k; ++j)
          c.E[j] = N[j];
        continue;
      }
      if (after > before - 0.2) return false; // stalled: precision exhausted
    }
    for (int j = 0; j < k; ++j)
      c.E[j] = Z[j];
  }
  return false;
}

// The value at the critical point held by E (a contracted box) by the mean-value form
//   G(E) in G(m) + grad G(E) . (E - m),
// G(m) in Arb at the final precision (a point: no Taylor model), the gradient over E in double
// intervals. E comes from contract_di at ~1e-15 and the gradient nearly vanishes on it, so the
// form is ~1e-30 wide: the requested width up to ~25 digits with no Arb contraction. False
// when the width is not met (the caller contracts in Arb).
bool mean_value(Tight& t, const Ctx<Ball>& C, const Ctx<DI>& Cd, const DI* E, const Ball& tol) {
  const int k = C.k;
  const Monomials& M = monomials(k);
  Ball m[2] = {Ball(0), Ball(0)}, dG[2];
  {
    CGAL::Protect_FPU_rounding<true> guard; // the double intervals round outward
    TP<DI> TX;
    if (!g_taylor(TX, Cd, t.ch, E, 1)) return false;
    for (int j = 0; j < k; ++j) {
      const DI mj = midpoint(E[j]);
      m[j] = Ball(mj.inf());
      const DI term = TX.c[unit_index(M, j)] * (E[j] - mj);
      if (!finite(term)) return false;
      dG[j] = to_ab(term);
    }
  }
  TP<Ball> T;
  if (!g_taylor(T, C, t.ch, m, 0)) return false;
  Ball V = T.c[0];
  for (int j = 0; j < k; ++j)
    V += dG[j];
  Ball w;
  arb_get_rad_arb(w.v, V.v);
  if (!finite(V) || !gt(lower_point(V) * tol, w * Ball(8))) return false;
  for (int j = 0; j < k; ++j)
    t.E[j] = to_ab(E[j]);
  t.V = V;
  return true;
}

// True when the enclosure E of chart `from` lies inside the box X of chart `to` (then the
// critical point in E is the unique one of X).
bool inside(const Chart& from, const Ball* E, const Chart& to, const Ball* X, int k) {
  Ball coef[3];
  coef[from.a] = Ball(from.s);
  for (int j = 0; j < k; ++j)
    coef[free_index(from, j)] = E[j];
  const Ball base = coef[to.a] * Ball(to.s);
  if (!pos(base)) return false;
  for (int j = 0; j < k; ++j)
    if (!contains(X[j], coef[free_index(to, j)] / base)) return false;
  return true;
}

// The unit direction of a chart point.
void unit_direction(Ball (&n)[3], const Ctx<Ball>& C, const Chart& ch, const Ball* u) {
  Ball N(0);
  for (size_t i = 0; i < 3; ++i) {
    n[i] = C.E[ch.a][i] * Ball(ch.s);
    for (int j = 0; j < C.k; ++j)
      n[i] += u[j] * C.E[free_index(ch, j)][i];
    N += n[i] * n[i];
  }
  N = sqrt_(N);
  for (auto& x : n)
    x = x / N;
}

// True when the unit directions of two enclosures are certainly different.
bool distinct(const Tight& x, const Tight& y, const Ctx<Ball>& C) {
  Ball n[2][3];
  unit_direction(n[0], C, x.ch, x.E);
  unit_direction(n[1], C, y.ch, y.E);
  for (size_t i = 0; i < 3; ++i)
    if (disjoint(n[0][i], n[1][i])) return true;
  return false;
}

// One order: `inner` (an ellipsoid) strictly inside `outer`.
// (pw: the support matrices from posed doubles; inner.W and outer.W are then not read.)
std::optional<DistanceResult> nested_in(const ConvexQuadric& inner, const ConvexQuadric& outer,
                                        bool inner_is_a, long digits, const PosedW* pw) {
  Frame f;
  if (outer.is_cylinder()) {
    const auto& ax = *outer.axis;
    size_t kk = 0;
    for (size_t i = 1; i < 3; ++i)
      if (core::abs(ax[i]) < core::abs(ax[kk])) kk = i;
    V3<Rational> e{Rational(0), Rational(0), Rational(0)};
    e[kk] = Rational(1);
    auto cross = [](const V3<Rational>& x, const V3<Rational>& y) {
      return V3<Rational>{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
                          x[0] * y[1] - x[1] * y[0]};
    };
    f.D = 2;
    f.standard = false;
    f.E[0] = cross(ax, e);
    f.E[1] = cross(ax, f.E[0]);
    // Nearly unit lengths (exact rational scalings): the charts keep comparable scales, else
    // a chart coordinate may stretch the circle by |axis| and its derivatives explode.
    for (size_t l = 0; l < 2; ++l) {
      double n2 = 0;
      for (const auto& x : f.E[l])
        n2 += x.to_double_approx() * x.to_double_approx();
      const Rational s = Rational::exact_from_double(1 / std::sqrt(n2));
      for (auto& x : f.E[l])
        x = x * s;
    }
  } else {
    for (size_t l = 0; l < 3; ++l)
      for (size_t i = 0; i < 3; ++i)
        f.E[l][i] = Rational(l == i ? 1 : 0);
  }
  const int D = f.D, k = D - 1;
  std::vector<Chart> charts;
  for (int a = 0; a < D; ++a)
    for (int s : {1, -1})
      charts.push_back(Chart{a, s});

  // Float search: a grid of every chart, then Newton from the best points.
  FloatPair P;
  P.D = D;
  for (size_t i = 0; i < 3; ++i) {
    P.dc[i] = (outer.c[i] - inner.c[i]).to_double_approx();
    for (size_t l = 0; l < 3; ++l) {
      P.E[l][i] = f.E[l][i].to_double_approx();
      P.Win[i][l] = inner.Wd[i][l];
      P.Wout[i][l] = outer.Wd[i][l];
    }
  }
  std::vector<Point> grid;
  const int steps = 8;
  double scale = 0;
  for (const Chart& ch : charts)
    for (int i = 0; i <= steps; ++i)
      for (int j = 0; j <= (k == 2 ? steps : 0); ++j) {
        Point x;
        x.ch = ch;
        x.u[0] = -1 + 2.0 * i / steps;
        x.u[1] = k == 2 ? -1 + 2.0 * j / steps : 0;
        x.G = eval_float(P, ch, x.u, nullptr, nullptr);
        scale = std::max(scale, std::fabs(x.G));
        grid.push_back(x);
      }
  // Only the best three seed Newton.
  std::partial_sort(grid.begin(),
                    grid.begin() +
                        std::min<std::ptrdiff_t>(3, static_cast<std::ptrdiff_t>(grid.size())),
                    grid.end(), [](const Point& x, const Point& y) { return x.G < y.G; });
  // Clearly negative somewhere: the inner solid pokes out (wrong order, or not nested).
  if (!(grid.front().G > -1e-9 * scale)) return std::nullopt;
  Point best = grid.front();
  for (size_t i = 0; i < std::min<size_t>(3, grid.size()); ++i) {
    Point x = grid[i];
    newton_float(P, x);
    if (x.G < best.G) best = x;
  }

  // The chart polynomials (Arb, then outward to double intervals), the certified upper bound
  // G(best) (any direction gives G >= min G), and the branch and bound.
  // Once, at the final precision (the exact rationals rounded once), and outward to double
  // intervals for the branch and bound.
  const long pf = bits_for(digits + 10);
  const PrecisionScope scope(pf);
  const Ctx<Ball> C = make_ctx(inner, outer, f, pw);
  const Ctx<DI> Cd = to_di(C);
  DI U;
  std::vector<Critical> crit;
  bool by_lagrangian = false; // one box from the Lagrangian bound, else the branch and bound
  {
    CGAL::Protect_FPU_rounding<true> guard; // the double intervals round outward
    TP<DI> T;
    const DI m[2] = {DI(best.u[0]), DI(best.u[1])};
    if (!g_taylor(T, Cd, best.ch, m, 0)) return std::nullopt;
    U = upper_point(T.c[0]);
    if (!pos(U)) return std::nullopt; // F <= 0 somewhere: not strictly nested
    by_lagrangian = lagrangian_box(Cd, P, best, U, crit);
    if (!by_lagrangian) {
      crit.clear();
      if (!branch_and_bound(Cd, charts, U, crit) || crit.empty()) return std::nullopt;
    }
  }

  // Contract the candidates that can hold the minimum, best first, at the final precision.
  Ball tol;
  arb_ui_pow_ui(tol.v, 10, static_cast<ulong>(digits), pf);
  arb_inv(tol.v, tol.v, pf);
  std::sort(crit.begin(), crit.end(),
            [](const Critical& x, const Critical& y) { return x.value.inf() < y.value.inf(); });
  Ball Ua = to_ab(U);
  std::vector<Tight> done;
  for (const Critical& c : crit) {
    // Ua is always a point (radius 0: to_ab of the point U, or an upper_point), so its
    // midpoint is its value and the ceiling a double above it: the comparison is certain.
    if (c.value.inf() > arf_get_d(arb_midref(Ua.v), ARF_RND_CEIL))
      continue; // above a genuine value
    Tight t;
    t.ch = c.ch;
    for (int j = 0; j < k; ++j)
      t.X[j] = to_ab(c.X[j]);
    bool same = false; // its critical point already contracted from another box
    for (const Tight& o : done)
      same = same || inside(o.ch, o.E, t.ch, t.X, k);
    if (same) continue;
    DI E[2] = {c.X[0], c.X[1]};
    contract_di(E, Cd, c.ch);
    for (int j = 0; j < k; ++j)
      t.E[j] = to_ab(E[j]);
    if (!mean_value(t, C, Cd, E, tol) && !tighten(t, C, tol)) return std::nullopt;
    if (arb_lt(upper_point(t.V).v, Ua.v)) Ua = upper_point(t.V);
    done.push_back(std::move(t));
  }
  if (done.empty()) return std::nullopt;
  // d = min over the critical directions of G, in [min lower, Ua].
  Ball lo = lower_point(done[0].V);
  for (const Tight& t : done)
    if (arb_lt(lower_point(t.V).v, lo.v)) lo = lower_point(t.V);
  // F > 0 everywhere (the inner solid lies in the interior of the outer one) and the requested
  // relative width.
  if (!pos(lo) || !arb_le((Ua - lo).v, (lo * tol).v)) return std::nullopt;
  // lo <= min G <= Ua whenever every enclosure above holds; lo > Ua would be a contradiction
  // (a defect, not a property of the pair), which arb_set_interval_arf answers with abort():
  // refuse instead (the width test above passes it, Ua - lo being negative).
  if (arf_cmp(arb_midref(lo.v), arb_midref(Ua.v)) > 0) return std::nullopt;
  Ball d;
  arb_set_interval_arf(d.v, arb_midref(lo.v), arb_midref(Ua.v), pf);

  // Minimizers: the contracted critical directions whose enclosure meets [lo, Ua]; two of them
  // must be proven the same point (then one is dropped) or different directions.
  std::vector<const Tight*> mins;
  for (const Tight& t : done) {
    if (disjoint(t.V, d)) continue;
    bool same = false;
    for (const Tight* o : mins) {
      if (inside(t.ch, t.E, o->ch, o->X, k) || inside(o->ch, o->E, t.ch, t.X, k)) {
        same = true; // the unique critical point of a proven box, found twice
        break;
      }
      if (!distinct(t, *o, C)) return std::nullopt;
    }
    if (!same) mins.push_back(&t);
  }

  DistanceResult out;
  out.status = Status::Certified;
  set_distance_enclosure(out, d.v, digits);
  out.minimizers = Minimizers::count(static_cast<long>(mins.size()), Minimizers::Proof::Interval);
  out.critical_candidates = static_cast<int>(crit.size());
  out.eliminated_degree = 0;
  out.note = "nested convex solids: the " + std::string(inner_is_a ? "first" : "second") +
             " surface lies strictly inside the other; d = min over unit directions of h_outer "
             "- h_inner (support functions), certified by " +
             (by_lagrangian ? std::string("a Lagrangian (S-lemma) lower bound that puts every "
                                          "near-minimal direction in one Krawczyk-proven box")
                            : std::string("a branch and bound with Krawczyk-proven critical "
                                          "directions")) +
             "; no elimination needed";
  note_unproven_ties(out, mins.size());
  // Tie regions (symmetry.hpp): the unit directions of the proven boxes, pairwise disjoint
  // (`distinct` above), each holding one critical direction; every minimizing direction lies in
  // one of them.
  out.tie_directions = true;
  for (const Tight* t : mins) {
    Ball n[3];
    unit_direction(n, C, t->ch, t->E);
    std::vector<std::array<double, 2>> reg;
    for (const Ball& x : n)
      reg.push_back(outward_interval(x.v));
    out.tie_regions.push_back(std::move(reg));
  }
  for (const Tight* t : mins) {
    Ball m[2], n[3];
    for (int j = 0; j < k; ++j)
      m[j] = midpoint(t->E[j]);
    unit_direction(n, C, t->ch, m);
    // The inner support point c + W n / sqrt(n^T W n), W from the context (approximate output).
    Ball wn[3], nwn(0), pb[3];
    for (size_t l = 0; l < 3; ++l) {
      wn[l] = Ball(0);
      for (size_t j = 0; j < 3; ++j)
        wn[l] += C.Wi[l][j] * n[j];
      nwn += n[l] * wn[l];
    }
    const Ball root = sqrt_(nwn);
    for (size_t l = 0; l < 3; ++l)
      pb[l] = wn[l] / root + from_rational(inner.c[l]);
    // The closest pair: the inner support point and the point at distance d along n.
    std::array<double, 3> pi{}, po{};
    const double dd = arf_get_d(arb_midref(t->V.v), ARF_RND_NEAR);
    for (size_t l = 0; l < 3; ++l) {
      pi[l] = arf_get_d(arb_midref(pb[l].v), ARF_RND_NEAR);
      po[l] = pi[l] + dd * arf_get_d(arb_midref(n[l].v), ARF_RND_NEAR);
    }
    out.pairs.push_back(inner_is_a ? std::array<std::array<double, 3>, 2>{pi, po}
                                   : std::array<std::array<double, 3>, 2>{po, pi});
  }
  return out;
}

} // namespace

std::optional<DistanceResult> nested_convex_distance(const ConvexQuadric& a, const ConvexQuadric& b,
                                                     long digits) {
  // The inner solid is an ellipsoid (an ellipsoid cannot contain a cylinder; two cylinders
  // have lines of closest pairs), the outer one an ellipsoid or an elliptic cylinder; other
  // convex kinds (paraboloids) are not handled here.
  auto outer_ok = [](const ConvexQuadric& q) { return q.is_ellipsoid() || q.is_cylinder(); };
  if (a.is_ellipsoid() && outer_ok(b))
    if (auto r = nested_in(a, b, true, digits, nullptr)) return r;
  if (b.is_ellipsoid() && outer_ok(a))
    if (auto r = nested_in(b, a, false, digits, nullptr)) return r;
  return std::nullopt;
}

std::optional<DistanceResult> nested_posed_ellipsoids(const core::ShapeSpec& a,
                                                      const core::ShapeSpec& b, long digits) {
  // Descriptions without the exact W (never read: nested_in takes the balls of pw).
  const long pf = bits_for(digits + 10);
  ConvexQuadric ca, cb;
  PosedW ab;
  posed_support_balls(ab.in, ca.Wd, a, pf);
  posed_support_balls(ab.out, cb.Wd, b, pf);
  for (size_t i = 0; i < 3; ++i) {
    ca.c[i] = Rational::exact_from_double(a.center[i]);
    cb.c[i] = Rational::exact_from_double(b.center[i]);
    ca.cd[i] = a.center[i];
    cb.cd[i] = b.center[i];
  }
  if (auto r = nested_in(ca, cb, true, digits, &ab)) return r;
  PosedW ba;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      ba.in[i][j] = ab.out[i][j];
      ba.out[i][j] = ab.in[i][j];
    }
  return nested_in(cb, ca, false, digits, &ba);
}

} // namespace surfcert::certify
