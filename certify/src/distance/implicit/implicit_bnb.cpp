#include "surfcert/certify/distance/implicit_bnb.hpp"
#include "surfcert/core/budget.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/certify/distance/ball.hpp"

#include <CGAL/Interval_nt.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <queue>
#include <string>
#include <vector>

namespace surfcert::certify {

namespace {

using DI = CGAL::Interval_nt<false>;
using Box = std::array<DI, 3>;
using D3 = std::array<double, 3>;
using Rational = core::Rational;

constexpr long kPairBudget = 1500000;  // pairs popped over all rounds
constexpr size_t kClusterPairs = 4000; // final pairs clustered per round
constexpr int kRounds = 5;             // resolution h = extent / 64 / 8^round
constexpr int kWitnessTries = 60;

// ---- polynomials compiled for evaluation ----

struct Poly {
  std::vector<std::array<int, 3>> e;
  std::vector<Rational> q; // exact coefficients
  std::vector<DI> c;       // outward double enclosures of q
  std::vector<double> d;   // nearest doubles (float proposals only)
  int deg = -1;
  D3 shift{}; // the terms are in y = x - shift (exact doubles): sharper interval extensions
};

DI enclose(const Rational& r) {
  Ball b;
  arb_set_fmpq(b.v, r.raw(), 128);
  const auto iv = outward_interval(b.v);
  return DI(iv[0], iv[1]);
}

Poly compile(const core::Poly3& p) {
  Poly out;
  for (const auto& [e, c] : p.terms()) {
    out.e.push_back(e);
    out.q.push_back(c);
    out.c.push_back(enclose(c));
    out.d.push_back(c.to_double_approx());
    out.deg = std::max(out.deg, e[0] + e[1] + e[2]);
  }
  return out;
}

DI ipow(const DI& x, int k) {
  if (k == 0) return DI(1);
  if (k == 1) return x;
  if (k % 2 == 0) return CGAL::square(ipow(x, k / 2));
  return x * ipow(x, k - 1);
}

DI eval(const Poly& p, const Box& x) {
  if (p.e.empty()) return DI(0);
  const Box b{x[0] - DI(p.shift[0]), x[1] - DI(p.shift[1]), x[2] - DI(p.shift[2])};
  std::array<std::vector<DI>, 3> pw;
  for (size_t i = 0; i < 3; ++i)
    for (int k = 0; k <= p.deg; ++k)
      pw[i].push_back(ipow(b[i], k));
  DI s(0);
  for (size_t t = 0; t < p.e.size(); ++t)
    s += p.c[t] * pw[0][static_cast<size_t>(p.e[t][0])] * pw[1][static_cast<size_t>(p.e[t][1])] *
         pw[2][static_cast<size_t>(p.e[t][2])];
  return s;
}

double evald(const Poly& p, const D3& x0) {
  const D3 x{x0[0] - p.shift[0], x0[1] - p.shift[1], x0[2] - p.shift[2]};
  double s = 0;
  for (size_t t = 0; t < p.e.size(); ++t) {
    double m = p.d[t];
    for (size_t i = 0; i < 3; ++i)
      for (int k = 0; k < p.e[t][i]; ++k)
        m *= x[i];
    s += m;
  }
  return s;
}

// Arb evaluation at a ball point x (3 balls).
void evala(arb_t out, const Poly& p, const arb_struct* x0, long prec) {
  Ball m, pw;
  arb_struct x[3];
  for (size_t i = 0; i < 3; ++i) {
    arb_init(x + i);
    arb_set_d(pw.v, p.shift[i]); // exact
    arb_sub(x + i, x0 + i, pw.v, prec);
  }
  arb_zero(out);
  for (size_t t = 0; t < p.e.size(); ++t) {
    arb_set_fmpq(m.v, p.q[t].raw(), prec);
    for (size_t i = 0; i < 3; ++i) {
      if (p.e[t][i] == 0) continue;
      arb_pow_ui(pw.v, x + i, static_cast<ulong>(p.e[t][i]), prec);
      arb_mul(m.v, m.v, pw.v, prec);
    }
    arb_add(out, out, m.v, prec);
  }
  for (size_t i = 0; i < 3; ++i)
    arb_clear(x + i);
}

struct Surf {
  Poly f;
  std::array<Poly, 3> g;
  std::array<Poly, 6> h; // Hessian entries 00 01 02 11 12 22
  double T = 0;          // zero set inside [-T, T]^3
};

size_t hidx(size_t i, size_t j) {
  static const size_t k[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  return k[i][j];
}

// f(y + shift) as a polynomial in y (exact).
core::Poly3 shifted(const core::Poly3& p, const D3& shift) {
  std::array<core::Poly3, 3> l;
  for (size_t i = 0; i < 3; ++i)
    l[i] = core::Poly3::variable(static_cast<int>(i)) +
           core::Poly3(Rational::exact_from_double(shift[i]));
  return p.substitute(l);
}

Surf make_surf(const core::Poly3& p0, const D3& shift = {}) {
  Surf s;
  const core::Poly3 p = shifted(p0, shift);
  s.f = compile(p);
  std::array<core::Poly3, 3> g;
  for (int i = 0; i < 3; ++i) {
    g[static_cast<size_t>(i)] = p.derivative(i);
    s.g[static_cast<size_t>(i)] = compile(g[static_cast<size_t>(i)]);
  }
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = i; j < 3; ++j)
      s.h[hidx(i, j)] = compile(g[i].derivative(static_cast<int>(j)));
  s.f.shift = shift;
  for (Poly& q : s.g)
    q.shift = shift;
  for (Poly& q : s.h)
    q.shift = shift;
  return s;
}

D3 centre(const Box& b) {
  return {0.5 * (b[0].inf() + b[0].sup()), 0.5 * (b[1].inf() + b[1].sup()),
          0.5 * (b[2].inf() + b[2].sup())};
}

Box point_box(const D3& p) {
  return {DI(p[0]), DI(p[1]), DI(p[2])};
}

// Enclosure of grad f over the box b: the centred form grad f(m) + H(b) (b - m) intersected
// with the natural extension (the monomial form alone cancels badly for quartics).
Box grad_range(const Surf& s, const Box& b) {
  const D3 m = centre(b);
  std::array<DI, 6> h;
  for (size_t k = 0; k < 6; ++k)
    h[k] = eval(s.h[k], b);
  Box out;
  for (size_t i = 0; i < 3; ++i) {
    DI c = eval(s.g[i], point_box(m));
    for (size_t j = 0; j < 3; ++j)
      c += h[hidx(i, j)] * (b[j] - DI(m[j]));
    const DI n = eval(s.g[i], b);
    const double lo = std::max(c.inf(), n.inf()), hi = std::min(c.sup(), n.sup());
    out[i] = lo <= hi ? DI(lo, hi) : c;
  }
  return out;
}

D3 gradd(const Surf& s, const D3& x) {
  return {evald(s.g[0], x), evald(s.g[1], x), evald(s.g[2], x)};
}

// ---- 1. boundedness ----

// A bound T with the zero set inside [-T, T]^3, or nullopt when the leading form is not proven
// definite.
std::optional<double> bounding_radius(const Poly& f) {
  const int d = f.deg;
  if (d < 2 || d % 2 != 0) return std::nullopt;
  Poly lead;
  std::vector<DI> A(static_cast<size_t>(d), DI(0)); // sum of |coefficients| of degree k < d
  for (size_t t = 0; t < f.e.size(); ++t) {
    const int k = f.e[t][0] + f.e[t][1] + f.e[t][2];
    if (k == d) {
      lead.e.push_back(f.e[t]);
      lead.c.push_back(f.c[t]);
      lead.deg = d;
    } else {
      A[static_cast<size_t>(k)] += CGAL::abs(f.c[t]);
    }
  }
  int sign = 0;
  double cmin = HUGE_VAL;
  long work = 0;
  std::vector<Box> stack;
  for (size_t a = 0; a < 3; ++a)
    for (double s : {-1.0, 1.0}) {
      Box b{DI(-1, 1), DI(-1, 1), DI(-1, 1)};
      b[a] = DI(s);
      stack.push_back(b);
    }
  while (!stack.empty()) {
    core::check_budget();
    Box b = stack.back();
    stack.pop_back();
    if (++work > 200000) return std::nullopt;
    const DI v = eval(lead, b);
    const int sg = v.inf() > 0 ? 1 : (v.sup() < 0 ? -1 : 0);
    if (sg != 0) {
      if (sign != 0 && sg != sign) return std::nullopt;
      sign = sg;
      cmin = std::min(cmin, sg > 0 ? v.inf() : -v.sup());
      continue;
    }
    size_t k = 0;
    double w = -1;
    for (size_t i = 0; i < 3; ++i)
      if (b[i].sup() - b[i].inf() > w) {
        w = b[i].sup() - b[i].inf();
        k = i;
      }
    if (w < 1.0 / 4096) return std::nullopt;
    const double m = 0.5 * (b[k].inf() + b[k].sup());
    Box c1 = b, c2 = b;
    c1[k] = DI(b[k].inf(), m);
    c2[k] = DI(m, b[k].sup());
    stack.push_back(c1);
    stack.push_back(c2);
  }
  if (sign == 0 || !(cmin > 0)) return std::nullopt;
  // On |x|_inf = rho: |lead| >= cmin rho^d (homogeneous), |degree-k part| <= A_k rho^k. With n
  // nonzero A_k, rho > (n A_k / cmin)^(1/(d-k)) for every k makes each A_k rho^k < cmin rho^d /
  // n, so f != 0 there and for every larger rho: the zero set lies in the cube. Scale-correct
  // (the bound scales with the surface), unlike sum A_k / cmin.
  int n = 0;
  for (const DI& a : A)
    n += a.sup() > 0 ? 1 : 0;
  double rho = 1.0 / 1024;
  for (size_t k = 0; k < A.size(); ++k) {
    if (!(A[k].sup() > 0)) continue;
    const double q = (DI(n) * A[k] / DI(cmin)).sup();
    // std::pow is not correctly rounded: a relative margin far above its error.
    const double r = std::pow(q, 1.0 / static_cast<double>(d - static_cast<int>(k)));
    rho = std::max(rho, (DI(r) * DI(1.0009765625)).sup());
  }
  return rho;
}

// ---- 2. octree nodes (lazy, shared between pairs) ----

double width(const Box& b) {
  double w = 0;
  for (const DI& x : b)
    w = std::max(w, x.sup() - x.inf());
  return w;
}

struct Node {
  Box b;
  Box grad;
  D3 m{};                  // centre
  DI fm;                   // f(m)
  D3 gm{};                 // float gradient at m (a choice of direction only)
  int child[2] = {-2, -2}; // -2: not built, -1: no zero of f
  int point = -2;          // certified surface point (index into Tree::points), -1: failed
};

struct Tree {
  const Surf* s = nullptr;
  std::vector<Node> nodes;
  std::vector<Box> points;

  // Index of a node for b, or -1 when 0 is not in f(b) (mean-value and natural forms).
  int make(const Box& b) {
    Node n;
    n.b = b;
    n.grad = grad_range(*s, b);
    const D3 m = centre(b);
    n.m = m;
    n.fm = eval(s->f, point_box(m));
    n.gm = gradd(*s, m);
    DI mv = n.fm;
    for (size_t i = 0; i < 3; ++i)
      mv += n.grad[i] * (b[i] - DI(m[i]));
    if (!mv.do_overlap(DI(0))) return -1;
    if (!eval(s->f, b).do_overlap(DI(0))) return -1;
    nodes.push_back(n);
    return static_cast<int>(nodes.size() - 1);
  }

  void split(int i) {
    Node& n = nodes[static_cast<size_t>(i)];
    if (n.child[0] != -2) return;
    size_t k = 0;
    double w = -1;
    for (size_t j = 0; j < 3; ++j)
      if (n.b[j].sup() - n.b[j].inf() > w) {
        w = n.b[j].sup() - n.b[j].inf();
        k = j;
      }
    const double m = 0.5 * (n.b[k].inf() + n.b[k].sup());
    Box c1 = n.b, c2 = n.b;
    c1[k] = DI(n.b[k].inf(), m);
    c2[k] = DI(m, n.b[k].sup());
    const int a = make(c1);
    const int b = make(c2);
    nodes[static_cast<size_t>(i)].child[0] = a;
    nodes[static_cast<size_t>(i)].child[1] = b;
  }

  // A certified point of f = 0 near the node's centre (float Newton proposes it, 1-D interval
  // Newton along the gradient line proves it), or nullptr.
  const Box* point(int i) {
    Node& n = nodes[static_cast<size_t>(i)];
    if (n.point == -2) {
      n.point = -1;
      D3 p = centre(n.b);
      for (int it = 0; it < 12; ++it) {
        const D3 gr = gradd(*s, p);
        const double gg = gr[0] * gr[0] + gr[1] * gr[1] + gr[2] * gr[2];
        if (!(gg > 0) || !std::isfinite(gg)) return nullptr;
        const double v = evald(s->f, p) / gg;
        for (size_t k = 0; k < 3; ++k)
          p[k] -= v * gr[k];
      }
      const D3 dir = gradd(*s, p);
      const double nn = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      if (!(nn > 0) || !std::isfinite(nn)) return nullptr;
      const double e = 4 * std::fabs(evald(s->f, p)) / (nn * nn) + 1e-13 * s->T / nn;
      const DI tt(-e, e);
      Box seg;
      for (size_t k = 0; k < 3; ++k)
        seg[k] = DI(p[k]) + tt * DI(dir[k]);
      DI der(0);
      for (size_t k = 0; k < 3; ++k)
        der += eval(s->g[k], seg) * DI(dir[k]);
      if (der.do_overlap(DI(0))) return nullptr;
      const DI nt = -eval(s->f, point_box(p)) / der;
      if (!(nt.inf() > -e && nt.sup() < e)) return nullptr;
      Box q;
      for (size_t k = 0; k < 3; ++k)
        q[k] = DI(p[k]) + nt * DI(dir[k]);
      points.push_back(q);
      nodes[static_cast<size_t>(i)].point = static_cast<int>(points.size() - 1);
    }
    const Node& m = nodes[static_cast<size_t>(i)];
    return m.point >= 0 ? &points[static_cast<size_t>(m.point)] : nullptr;
  }
};

DI box_distance(const Box& a, const Box& b) {
  DI s(0);
  for (size_t i = 0; i < 3; ++i) {
    const double g = std::max(
        {0.0, (DI(a[i].inf()) - DI(b[i].sup())).inf(), (DI(b[i].inf()) - DI(a[i].sup())).inf()});
    s += CGAL::square(DI(g));
  }
  return CGAL::sqrt(s);
}

// Enclosure of n.p over the points p of f = 0 in the node's box: with delta = p - m and xi on
// the segment [m, p] (inside the box), f(m) + grad f(xi).delta = 0, so for any s != 0
//   n.delta = ((s n - grad f(xi)).delta - f(m)) / s,
// second order in the box width when s n is close to grad f (s = n.grad f(m)).
std::optional<DI> linear_range(const Node& nd, const D3& n) {
  const double s = n[0] * nd.gm[0] + n[1] * nd.gm[1] + n[2] * nd.gm[2];
  if (!(std::fabs(s) > 0) || !std::isfinite(s)) return std::nullopt;
  DI acc = -nd.fm;
  DI base(0);
  for (size_t i = 0; i < 3; ++i) {
    acc += (DI(s) * DI(n[i]) - nd.grad[i]) * (nd.b[i] - DI(nd.m[i]));
    base += DI(n[i]) * DI(nd.m[i]);
  }
  return base + acc / DI(s);
}

// Lower bound of |p - q| over p in A on f = 0, q in B on g = 0: the box distance, or
// n.(p - q) / |n| with n the direction between the centres (second order near critical pairs).
double pair_lower_bound(const Node& a, const Node& b) {
  double lb = box_distance(a.b, b.b).inf();
  const D3 n{a.m[0] - b.m[0], a.m[1] - b.m[1], a.m[2] - b.m[2]};
  const auto ea = linear_range(a, n), eb = linear_range(b, n);
  if (ea && eb) {
    const DI nn =
        CGAL::sqrt(CGAL::square(DI(n[0])) + CGAL::square(DI(n[1])) + CGAL::square(DI(n[2])));
    if (nn.inf() > 0) {
      const DI l = (*ea - *eb) / nn;
      if (std::isfinite(l.inf())) lb = std::max(lb, l.inf());
    }
  }
  return lb;
}

// False when no pair in A x B has p - q parallel to the gradient (or a zero gradient).
bool may_be_critical(const Box& a, const Box& b, const Box& grad) {
  const Box d{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3, k = (i + 2) % 3;
    if (!(d[j] * grad[k] - d[k] * grad[j]).do_overlap(DI(0))) return false;
  }
  return true;
}

Box hull(const Box& a, const Box& b) {
  Box h;
  for (size_t i = 0; i < 3; ++i)
    h[i] = DI(std::min(a[i].inf(), b[i].inf()), std::max(a[i].sup(), b[i].sup()));
  return h;
}

bool touch(const Box& a, const Box& b) {
  for (size_t i = 0; i < 3; ++i)
    if (!a[i].do_overlap(b[i])) return false;
  return true;
}

// ---- small dense float linear algebra (proposals only) ----

template <size_t N> bool solve(std::array<std::array<double, N>, N> a, std::array<double, N>& x) {
  for (size_t c = 0; c < N; ++c) {
    size_t p = c;
    for (size_t r = c + 1; r < N; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    if (!(std::fabs(a[p][c]) > 0)) return false;
    std::swap(a[p], a[c]);
    std::swap(x[p], x[c]);
    for (size_t r = c + 1; r < N; ++r) {
      const double f = a[r][c] / a[c][c];
      for (size_t k = c; k < N; ++k)
        a[r][k] -= f * a[c][k];
      x[r] -= f * x[c];
    }
  }
  for (size_t c = N; c-- > 0;) {
    for (size_t k = c + 1; k < N; ++k)
      x[c] -= a[c][k] * x[k];
    x[c] /= a[c][c];
  }
  return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

template <size_t N>
bool invert(const std::array<std::array<double, N>, N>& a,
            std::array<std::array<double, N>, N>& inv) {
  for (size_t c = 0; c < N; ++c) {
    std::array<double, N> e{};
    e[c] = 1;
    if (!solve<N>(a, e)) return false;
    for (size_t r = 0; r < N; ++r)
      inv[r][c] = e[r];
  }
  return true;
}

// ---- 3. the Lagrange system ----

using V8 = std::array<double, 8>;
using M8 = std::array<std::array<double, 8>, 8>;

void lagrange_float(const Surf& a, const Surf& b, const V8& x, V8& F, M8& J) {
  const D3 p{x[0], x[1], x[2]}, q{x[3], x[4], x[5]};
  const D3 gf = gradd(a, p), gg = gradd(b, q);
  J = M8{};
  for (size_t i = 0; i < 3; ++i) {
    F[i] = p[i] - q[i] - x[6] * gf[i];
    F[3 + i] = p[i] - q[i] + x[7] * gg[i];
    for (size_t j = 0; j < 3; ++j) {
      J[i][j] = (i == j ? 1 : 0) - x[6] * evald(a.h[hidx(i, j)], p);
      J[3 + i][3 + j] = -(i == j ? 1 : 0) + x[7] * evald(b.h[hidx(i, j)], q);
    }
    J[i][3 + i] = -1;
    J[3 + i][i] = 1;
    J[i][6] = -gf[i];
    J[3 + i][7] = gg[i];
    J[6][i] = gf[i];
    J[7][3 + i] = gg[i];
  }
  F[6] = evald(a.f, p);
  F[7] = evald(b.f, q);
}

bool newton_float(const Surf& a, const Surf& b, V8& x) {
  V8 F;
  M8 J;
  for (int it = 0; it < 40; ++it) {
    lagrange_float(a, b, x, F, J);
    V8 d = F;
    if (!solve<8>(J, d)) return false;
    double n = 0, s = 0;
    for (size_t i = 0; i < 8; ++i) {
      x[i] -= d[i];
      n = std::max(n, std::fabs(d[i]));
      s = std::max(s, std::fabs(x[i]));
    }
    if (n <= 1e-15 * (1 + s)) return true;
  }
  lagrange_float(a, b, x, F, J);
  double r = 0;
  for (double v : F)
    r = std::max(r, std::fabs(v));
  return r < 1e-9;
}

using algebra::BallVec;
struct ArbMat {
  arb_mat_t m;
  ArbMat(slong r, slong c) { arb_mat_init(m, r, c); }
  ArbMat(const ArbMat&) = delete;
  ArbMat& operator=(const ArbMat&) = delete;
  ~ArbMat() { arb_mat_clear(m); }
};

// F(x) (8 balls) and J(x) at the ball vector x.
void lagrange_arb(const Surf& a, const Surf& b, arb_srcptr x, arb_ptr F, arb_mat_t J, long prec) {
  BallVec gf(3), gg(3);
  Ball t, u;
  for (size_t i = 0; i < 3; ++i) {
    evala(gf.v + i, a.g[i], x, prec);
    evala(gg.v + i, b.g[i], x + 3, prec);
  }
  if (F != nullptr) {
    for (slong i = 0; i < 3; ++i) {
      arb_sub(t.v, x + i, x + 3 + i, prec);
      arb_mul(u.v, x + 6, gf.v + i, prec);
      arb_sub(F + i, t.v, u.v, prec);
      arb_mul(u.v, x + 7, gg.v + i, prec);
      arb_add(F + 3 + i, t.v, u.v, prec);
    }
    evala(F + 6, a.f, x, prec);
    evala(F + 7, b.f, x + 3, prec);
  }
  if (J == nullptr) return;
  arb_mat_zero(J);
  for (slong i = 0; i < 3; ++i) {
    for (slong j = 0; j < 3; ++j) {
      evala(t.v, a.h[hidx(static_cast<size_t>(i), static_cast<size_t>(j))], x, prec);
      arb_mul(t.v, t.v, x + 6, prec);
      arb_neg(arb_mat_entry(J, i, j), t.v);
      if (i == j) arb_add_ui(arb_mat_entry(J, i, j), arb_mat_entry(J, i, j), 1, prec);
      evala(t.v, b.h[hidx(static_cast<size_t>(i), static_cast<size_t>(j))], x + 3, prec);
      arb_mul(arb_mat_entry(J, 3 + i, 3 + j), t.v, x + 7, prec);
      if (i == j)
        arb_sub_ui(arb_mat_entry(J, 3 + i, 3 + j), arb_mat_entry(J, 3 + i, 3 + j), 1, prec);
    }
    arb_set_si(arb_mat_entry(J, i, 3 + i), -1);
    arb_set_si(arb_mat_entry(J, 3 + i, i), 1);
    arb_neg(arb_mat_entry(J, i, 6), gf.v + i);
    arb_set(arb_mat_entry(J, 3 + i, 7), gg.v + i);
    arb_set(arb_mat_entry(J, 6, i), gf.v + i);
    arb_set(arb_mat_entry(J, 7, 3 + i), gg.v + i);
  }
}

bool strictly_inside(const arb_t k, const arb_t x, long prec) {
  arf_t kl, ku, xlo_up, xhi_down, r;
  arf_init(kl);
  arf_init(ku);
  arf_init(xlo_up);
  arf_init(xhi_down);
  arf_init(r);
  arb_get_lbound_arf(kl, k, prec);
  arb_get_ubound_arf(ku, k, prec);
  arf_set_mag(r, arb_radref(x));
  arf_sub(xlo_up, arb_midref(x), r, prec, ARF_RND_CEIL);    // >= the lower end of x
  arf_add(xhi_down, arb_midref(x), r, prec, ARF_RND_FLOOR); // <= the upper end of x
  const bool ok = arb_is_finite(k) && arf_cmp(kl, xlo_up) > 0 && arf_cmp(ku, xhi_down) < 0;
  arf_clear(kl);
  arf_clear(ku);
  arf_clear(xlo_up);
  arf_clear(xhi_down);
  arf_clear(r);
  return ok;
}

// Krawczyk on X (8 balls) about the point xh (8 exact balls, inside X): true when K(X) lies in
// the interior of X (then X holds exactly one zero, and it lies in K, written to k).
bool krawczyk(const Surf& a, const Surf& b, arb_srcptr X, arb_srcptr xh, arb_ptr k, long prec) {
  BallVec F(8), dx(8), t(8);
  ArbMat J(8, 8), Jm(8, 8), Y(8, 8), M(8, 8);
  lagrange_arb(a, b, xh, F.v, Jm.m, prec);
  lagrange_arb(a, b, X, nullptr, J.m, prec);
  for (slong i = 0; i < 8; ++i)
    for (slong j = 0; j < 8; ++j)
      arb_set_arf(arb_mat_entry(Jm.m, i, j), arb_midref(arb_mat_entry(Jm.m, i, j)));
  if (!arb_mat_inv(Y.m, Jm.m, prec)) return false;
  for (slong i = 0; i < 8; ++i)
    for (slong j = 0; j < 8; ++j)
      arb_set_arf(arb_mat_entry(Y.m, i, j), arb_midref(arb_mat_entry(Y.m, i, j)));
  arb_mat_mul(M.m, Y.m, J.m, prec);
  arb_mat_neg(M.m, M.m);
  for (slong i = 0; i < 8; ++i)
    arb_add_ui(arb_mat_entry(M.m, i, i), arb_mat_entry(M.m, i, i), 1, prec);
  for (slong i = 0; i < 8; ++i)
    arb_sub(dx.v + i, X + i, xh + i, prec);
  for (slong i = 0; i < 8; ++i) {
    arb_set(k + i, xh + i);
    for (slong j = 0; j < 8; ++j) {
      arb_submul(k + i, arb_mat_entry(Y.m, i, j), F.v + j, prec);
      arb_addmul(k + i, arb_mat_entry(M.m, i, j), dx.v + j, prec);
    }
  }
  for (slong i = 0; i < 8; ++i)
    if (!strictly_inside(k + i, X + i, prec)) return false;
  return true;
}

void set_interval(arb_t x, double lo, double hi, long prec) {
  arf_t l, h;
  arf_init(l);
  arf_init(h);
  arf_set_d(l, lo);
  arf_set_d(h, hi);
  arb_set_interval_arf(x, l, h, prec);
  arf_clear(l);
  arf_clear(h);
}

void distance_ball(arb_t d, arb_srcptr k, long prec) {
  Ball t;
  arb_zero(d);
  for (slong i = 0; i < 3; ++i) {
    arb_sub(t.v, k + i, k + 3 + i, prec);
    arb_addmul(d, t.v, t.v, prec);
  }
  arb_sqrt(d, d, prec);
}

struct Critical {
  std::array<DI, 8> X; // the Krawczyk box (unique critical pair inside)
  V8 x;                // float approximation
  Ball d;              // distance enclosure
};

// Krawczyk for one cluster (hulls ha, hb); nullopt when not proven.
std::optional<Critical> prove_cluster(const Surf& a, const Surf& b, const Box& ha, const Box& hb) {
  // lambda, mu ranges of every critical pair in ha x hb (needs nonzero gradients: smoothness).
  DI ga(0), gb(0), la(0), lb(0);
  const Box fa = grad_range(a, ha), gb3 = grad_range(b, hb);
  for (size_t i = 0; i < 3; ++i) {
    const DI fi = fa[i], gi = gb3[i];
    ga += CGAL::square(fi);
    gb += CGAL::square(gi);
    la += (ha[i] - hb[i]) * fi;
    lb += (ha[i] - hb[i]) * gi;
  }
  if (!(ga.inf() > 0) || !(gb.inf() > 0)) {
    return std::nullopt;
  }
  const DI lam = la / ga, mu = -lb / gb;
  const D3 ca = centre(ha), cb = centre(hb);
  V8 x{ca[0],
       ca[1],
       ca[2],
       cb[0],
       cb[1],
       cb[2],
       0.5 * (lam.inf() + lam.sup()),
       0.5 * (mu.inf() + mu.sup())};
  if (!newton_float(a, b, x)) {
    return std::nullopt;
  }
  std::array<DI, 8> X;
  for (size_t i = 0; i < 3; ++i) {
    X[i] = ha[i];
    X[3 + i] = hb[i];
  }
  X[6] = lam;
  X[7] = mu;
  for (size_t i = 0; i < 8; ++i) {
    const double r = 0.125 * (X[i].sup() - X[i].inf()) + 1e-12 * (1 + std::fabs(x[i]));
    X[i] = DI(std::min(X[i].inf(), x[i]) - r, std::max(X[i].sup(), x[i]) + r);
  }
  const long prec = 128;
  BallVec Xa(8), xh(8), k(8);
  for (size_t i = 0; i < 8; ++i) {
    set_interval(Xa.v + i, X[i].inf(), X[i].sup(), prec);
    arb_set_d(xh.v + i, x[i]);
  }
  if (!krawczyk(a, b, Xa.v, xh.v, k.v, prec)) {
    return std::nullopt;
  }
  Critical c;
  c.X = X;
  c.x = x;
  distance_ball(c.d.v, k.v, prec);
  return c;
}

// Refines the critical pair of c at `digits` (Newton in Arb, Krawczyk on a tiny box inside c.X).
bool refine(const Surf& a, const Surf& b, Critical& c, long digits) {
  for (long prec = bits_for(digits); prec <= 4 * bits_for(digits) + 256; prec *= 2) {
    BallVec x(8), F(8), X(8), k(8);
    ArbMat J(8, 8);
    for (slong i = 0; i < 8; ++i)
      arb_set_d(x.v + i, c.x[static_cast<size_t>(i)]);
    for (long bits = 40; bits < 2 * prec; bits *= 2) {
      lagrange_arb(a, b, x.v, F.v, J.m, prec);
      ArbMat rhs(8, 1), sol(8, 1);
      for (slong i = 0; i < 8; ++i)
        arb_set(arb_mat_entry(rhs.m, i, 0), F.v + i);
      if (!arb_mat_solve(sol.m, J.m, rhs.m, prec)) return false;
      for (slong i = 0; i < 8; ++i) {
        arb_sub(x.v + i, x.v + i, arb_mat_entry(sol.m, i, 0), prec);
        arb_set_arf(x.v + i, arb_midref(x.v + i));
      }
    }
    Ball eps;
    for (slong i = 0; i < 8; ++i) {
      arb_abs(eps.v, x.v + i);
      arb_add_ui(eps.v, eps.v, 1, prec);
      arb_mul_2exp_si(eps.v, eps.v, -(prec - 48));
      arb_set(X.v + i, x.v + i);
      arb_add_error(X.v + i, eps.v);
      // X must lie inside the box where uniqueness was proven.
      Ball lo;
      set_interval(lo.v, c.X[static_cast<size_t>(i)].inf(), c.X[static_cast<size_t>(i)].sup(),
                   prec);
      if (!arb_contains(lo.v, X.v + i)) return false;
    }
    if (!krawczyk(a, b, X.v, x.v, k.v, prec)) continue;
    distance_ball(c.d.v, k.v, prec);
    Ball d;
    if (relative_enclosure(d.v, c.d.v, c.d.v, digits, prec)) {
      for (size_t i = 0; i < 8; ++i)
        c.x[i] = arf_get_d(arb_midref(k.v + i), ARF_RND_NEAR);
      return true;
    }
  }
  return false;
}

// ---- 4. contact witness: a common zero of f and g with one coordinate fixed ----

std::optional<D3> contact_witness(const Surf& a, const Surf& b, D3 p) {
  for (int it = 0; it < 30; ++it) {
    const D3 gf = gradd(a, p), gg = gradd(b, p);
    const double f = evald(a.f, p), g = evald(b.f, p);
    // minimum-norm step: d = J^T (J J^T)^-1 (f, g)
    const double a11 = gf[0] * gf[0] + gf[1] * gf[1] + gf[2] * gf[2];
    const double a12 = gf[0] * gg[0] + gf[1] * gg[1] + gf[2] * gg[2];
    const double a22 = gg[0] * gg[0] + gg[1] * gg[1] + gg[2] * gg[2];
    const double det = a11 * a22 - a12 * a12;
    if (!(std::fabs(det) > 0)) return std::nullopt;
    const double u = (a22 * f - a12 * g) / det, v = (a11 * g - a12 * f) / det;
    for (size_t i = 0; i < 3; ++i)
      p[i] -= u * gf[i] + v * gg[i];
  }
  const D3 gf = gradd(a, p), gg = gradd(b, p);
  const D3 t{gf[1] * gg[2] - gf[2] * gg[1], gf[2] * gg[0] - gf[0] * gg[2],
             gf[0] * gg[1] - gf[1] * gg[0]};
  size_t k = 0;
  for (size_t i = 1; i < 3; ++i)
    if (std::fabs(t[i]) > std::fabs(t[k])) k = i;
  const size_t i0 = (k + 1) % 3, i1 = (k + 2) % 3;
  for (double e : {1e-12, 1e-9, 1e-6}) {
    const double r = e * (1 + std::fabs(p[i0]) + std::fabs(p[i1]));
    Box U = point_box(p);
    U[i0] = DI(p[i0]) + DI(-r, r);
    U[i1] = DI(p[i1]) + DI(-r, r);
    // J(U) and Y = inverse of the float Jacobian at p
    const DI j00 = eval(a.g[i0], U), j01 = eval(a.g[i1], U);
    const DI j10 = eval(b.g[i0], U), j11 = eval(b.g[i1], U);
    const double m00 = gf[i0], m01 = gf[i1], m10 = gg[i0], m11 = gg[i1];
    const double dt = m00 * m11 - m01 * m10;
    if (!(std::fabs(dt) > 0)) return std::nullopt;
    const DI y00(m11 / dt), y01(-m01 / dt), y10(-m10 / dt), y11(m00 / dt);
    const Box P = point_box(p);
    const DI F0 = eval(a.f, P), F1 = eval(b.f, P);
    const DI d0 = U[i0] - DI(p[i0]), d1 = U[i1] - DI(p[i1]);
    const DI k0 = DI(p[i0]) - (y00 * F0 + y01 * F1) + (DI(1) - y00 * j00 - y01 * j10) * d0 +
                  (DI(0) - y00 * j01 - y01 * j11) * d1;
    const DI k1 = DI(p[i1]) - (y10 * F0 + y11 * F1) + (DI(0) - y10 * j00 - y11 * j10) * d0 +
                  (DI(1) - y10 * j01 - y11 * j11) * d1;
    if (k0.inf() > U[i0].inf() && k0.sup() < U[i0].sup() && k1.inf() > U[i1].inf() &&
        k1.sup() < U[i1].sup())
      return p;
  }
  return std::nullopt;
}

struct Pair {
  double lb;
  int a, b;
  bool operator>(const Pair& o) const { return lb > o.lb; }
};

DistanceResult undecided(DistanceResult out, const std::string& why) {
  out.status = Status::Undecided;
  out.note = why;
  return out;
}

} // namespace

core::Poly3 torus_polynomial(const core::Torus& t) {
  std::array<core::Poly3, 3> u;
  core::Poly3 s2, dot;
  Rational a2;
  for (size_t i = 0; i < 3; ++i) {
    u[i] = core::Poly3::variable(static_cast<int>(i)) - core::Poly3(t.centre[i]);
    s2 = s2 + u[i] * u[i];
    dot = dot + u[i].scaled(t.axis[i]);
    a2 += t.axis[i] * t.axis[i];
  }
  const Rational R2 = t.R * t.R;
  const core::Poly3 first = s2 + core::Poly3(R2 - t.r * t.r);
  return first * first - (s2 - (dot * dot).scaled(Rational(1) / a2)).scaled(Rational(4) * R2);
}

namespace {

// The hull of the boxes alive after splitting the root until 3000 boxes (or 90 levels): it
// holds the zero set (boxes where 0 is not in f are dropped).
Box tight_hull(Tree& t, int root) {
  std::vector<int> level{root};
  for (int d = 0; d < 90 && level.size() < 3000; ++d) {
    std::vector<int> next;
    for (int i : level) {
      // A level holds up to 8 x 3000 boxes: tens of ms for a quartic, so the budget is
      // checked per box (the tree owns everything: nothing leaks on the throw).
      core::check_budget();
      t.split(i);
      for (int c : t.nodes[static_cast<size_t>(i)].child)
        if (c >= 0) next.push_back(c);
    }
    if (next.empty()) break;
    level = std::move(next);
  }
  Box hb = t.nodes[static_cast<size_t>(level[0])].b;
  for (int i : level)
    hb = hull(hb, t.nodes[static_cast<size_t>(i)].b);
  return hb;
}

// clip > 0: g need not be bounded; its zero set is taken inside the cube |x|_inf <= Ta + clip
// (Ta: f's bounding radius). Every point of g outside that cube is farther than clip from
// f = 0, so a certified minimum whose upper bound is below clip is the global one (checked at
// the end; otherwise *clip_short receives that upper bound and the answer is undecided).
DistanceResult pair_distance(const core::Poly3& f, const core::Poly3& g, long digits, double clip,
                             double* clip_short) {
  DistanceResult out;
  out.method = Method::ImplicitBnb;
  out.mode = Mode::Filtered;
  CGAL::Protect_FPU_rounding<true> guard;
  Surf sa = make_surf(f), sb = make_surf(g);
  const auto ta = bounding_radius(sa.f);
  const auto tb = clip > 0 ? ta : bounding_radius(sb.f); // clipped: set below
  if (!ta || !tb)
    return undecided(out, "could not prove bounded (leading form not proven definite)");
  sa.T = *ta;
  sb.T = *tb;
  Tree A, B;
  A.s = &sa;
  B.s = &sb;
  const int ra = A.make({DI(-sa.T, sa.T), DI(-sa.T, sa.T), DI(-sa.T, sa.T)});
  if (ra < 0) return undecided(out, "a surface has no real point (proven)");
  // The size of the surfaces (hull of the boxes alive after splitting) sets the resolution of
  // the rounds; it decides nothing.
  const auto tight = [](Tree& t, int root) {
    const Box hb = tight_hull(t, root);
    return std::make_pair(width(hb), centre(hb));
  };
  const auto [wa0, ca0] = tight(A, ra);
  // Clipped: g within the cube of half-width hw = (size of f)/2 + clip around f's hull, which
  // holds f's zero set; every point of g outside is farther than clip from f = 0 (outward
  // interval arithmetic for the cube's faces).
  const double hw = clip > 0 ? (DI(wa0) / 2 + DI(clip)).sup() : 0;
  Box bbox{DI(-sb.T, sb.T), DI(-sb.T, sb.T), DI(-sb.T, sb.T)};
  if (clip > 0)
    for (size_t i = 0; i < 3; ++i)
      bbox[i] = DI((DI(ca0[i]) - DI(hw)).inf(), (DI(ca0[i]) + DI(hw)).sup());
  const int rb = B.make(bbox);
  if (rb < 0) {
    if (clip > 0 && clip_short) *clip_short = 4 * clip; // widen the cube
    return undecided(out, clip > 0 ? "no point of the unbounded surface near the bounded one "
                                     "(clipping cube too small)"
                                   : "a surface has no real point (proven)");
  }
  const auto [wb0, cb0] = tight(B, rb);
  const double extent = std::max(wa0, wb0);
  // Each polynomial re-expanded about the centre of its surface: far from the origin the
  // monomial form overestimates badly (a translated quartic).
  auto round_centre = [](const D3& c) {
    D3 r{};
    for (size_t i = 0; i < 3; ++i)
      r[i] = std::ldexp(std::nearbyint(std::ldexp(c[i], 20)), -20);
    return r;
  };
  Surf sa2 = make_surf(f, round_centre(ca0)), sb2 = make_surf(g, round_centre(cb0));
  sa2.T = sa.T;
  sb2.T = sb.T;
  if (clip > 0) { // the whole clipping cube, seen from g's new centre
    const D3 cr = round_centre(cb0);
    double off = 0;
    for (size_t i = 0; i < 3; ++i)
      off = std::max(off, CGAL::abs(DI(ca0[i]) - DI(cr[i])).sup());
    sb2.T = (DI(hw) + DI(off)).sup();
  }
  sa = std::move(sa2);
  sb = std::move(sb2);
  A = Tree{};
  B = Tree{};
  A.s = &sa;
  B.s = &sb;
  if (A.make({DI(-sa.T, sa.T), DI(-sa.T, sa.T), DI(-sa.T, sa.T)}) != ra ||
      B.make({DI(-sb.T, sb.T), DI(-sb.T, sb.T), DI(-sb.T, sb.T)}) != rb)
    return undecided(out, "a surface has no real point (proven)");

  double ub = HUGE_VAL;
  std::array<D3, 2> ub_pair{};
  auto try_ub = [&](int ia, int ib) {
    const Box* p = A.point(ia);
    const Box* q = B.point(ib);
    if (p == nullptr || q == nullptr) return;
    DI s(0);
    for (size_t i = 0; i < 3; ++i)
      s += CGAL::square((*p)[i] - (*q)[i]);
    const double u = CGAL::sqrt(s).sup();
    if (u < ub) {
      ub = u;
      ub_pair = {centre(*p), centre(*q)};
    }
  };

  std::priority_queue<Pair, std::vector<Pair>, std::greater<>> queue;
  queue.push({box_distance(A.nodes[0].b, B.nodes[0].b).inf(), ra, rb});
  std::vector<Critical> found;
  // Records a proven critical pair (unless its point lies in an earlier Krawczyk box: the same
  // pair by uniqueness) and lowers the upper bound.
  auto accept = [&](std::optional<Critical> c) {
    if (!c || !arb_is_positive(c->d.v)) return false;
    bool dup = false;
    for (const Critical& o : found) {
      bool inside = true;
      for (size_t i = 0; i < 8; ++i)
        inside = inside && c->x[i] >= o.X[i].inf() && c->x[i] <= o.X[i].sup();
      dup = dup || inside;
    }
    if (!dup) {
      arf_t u;
      arf_init(u);
      arb_get_ubound_arf(u, c->d.v, 64);
      ub = std::min(ub, arf_get_d(u, ARF_RND_CEIL));
      arf_clear(u);
      found.push_back(std::move(*c));
    }
    return true;
  };
  long popped = 0;
  int witness_tries = 0;
  bool contact_possible = false;
  double h = extent / 32;
  for (int round = 0; round < kRounds; ++round, h /= 8) {
    std::vector<Pair> fin;
    while (!queue.empty()) {
      core::check_budget();
      const Pair pr = queue.top();
      queue.pop();
      if (pr.lb > ub) continue;
      if (++popped > kPairBudget) {
        // Clipped and a genuine pair no closer than the margin: the cube's faces may hold the
        // minimum over the cube (no critical pair there); widen past that pair's distance.
        if (clip > 0 && clip_short && ub < HUGE_VAL && ub >= clip) *clip_short = ub;
        return undecided(out, "box budget exhausted");
      }
      const Box& ba = A.nodes[static_cast<size_t>(pr.a)].b;
      const Box& bb = B.nodes[static_cast<size_t>(pr.b)].b;
      const double wa = width(ba), wb = width(bb);
      if (std::max(wa, wb) <= extent / 8) try_ub(pr.a, pr.b);
      if (pr.lb <= 0 && std::max(wa, wb) <= extent / 8 && witness_tries < kWitnessTries) {
        ++witness_tries;
        const Box ov = {DI(std::max(ba[0].inf(), bb[0].inf()), std::min(ba[0].sup(), bb[0].sup())),
                        DI(std::max(ba[1].inf(), bb[1].inf()), std::min(ba[1].sup(), bb[1].sup())),
                        DI(std::max(ba[2].inf(), bb[2].inf()), std::min(ba[2].sup(), bb[2].sup()))};
        if (const auto w = contact_witness(sa, sb, centre(ov))) {
          out.status = Status::Certified;
          out.distance = Enclosure::zero();
          out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
          out.pairs.push_back({*w, *w});
          out.note = "the surfaces cross: a common point proven by 2-D Krawczyk with one "
                     "coordinate fixed (transversal, so a curve of contact); the pair is that "
                     "witness";
          return out;
        }
      }
      if (wa <= h && wb <= h) {
        fin.push_back(pr);
        continue;
      }
      const bool split_a = wa >= wb;
      Tree& T = split_a ? A : B;
      const int id = split_a ? pr.a : pr.b;
      T.split(id);
      for (int c : T.nodes[static_cast<size_t>(id)].child) {
        if (c < 0) continue;
        const int ia = split_a ? c : pr.a, ib = split_a ? pr.b : c;
        const Node& na = A.nodes[static_cast<size_t>(ia)];
        const Node& nb = B.nodes[static_cast<size_t>(ib)];
        const double l = pair_lower_bound(na, nb);
        if (l > ub) continue;
        if (!may_be_critical(na.b, nb.b, na.grad) || !may_be_critical(na.b, nb.b, nb.grad))
          continue;
        queue.push({l, ia, ib});
      }
    }
    // cluster the final pairs (touching boxes on both sides)
    std::vector<Pair> live;
    for (const Pair& p : fin)
      if (p.lb <= ub) live.push_back(p);
    if (live.empty()) break;
    {
      // all candidates in one small region: one Krawczyk box for all of them
      Box ha = A.nodes[static_cast<size_t>(live[0].a)].b;
      Box hb = B.nodes[static_cast<size_t>(live[0].b)].b;
      for (const Pair& p : live) {
        ha = hull(ha, A.nodes[static_cast<size_t>(p.a)].b);
        hb = hull(hb, B.nodes[static_cast<size_t>(p.b)].b);
      }
      if (std::max(width(ha), width(hb)) <= extent / 4 && box_distance(ha, hb).inf() > 0 &&
          accept(prove_cluster(sa, sb, ha, hb)))
        break;
    }
    if (live.size() > kClusterPairs) {
      if (round + 1 == kRounds) {
        return undecided(out, "too many candidate pairs (a continuum of minimizers?)");
      }
      for (const Pair& p : live)
        queue.push(p);
      continue;
    }
    std::vector<size_t> parent(live.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto findp = [&](size_t i) {
      while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
      return i;
    };
    for (size_t i = 0; i < live.size(); ++i)
      for (size_t j = i + 1; j < live.size(); ++j)
        if (touch(A.nodes[static_cast<size_t>(live[i].a)].b,
                  A.nodes[static_cast<size_t>(live[j].a)].b) &&
            touch(B.nodes[static_cast<size_t>(live[i].b)].b,
                  B.nodes[static_cast<size_t>(live[j].b)].b))
          parent[findp(i)] = findp(j);
    std::vector<std::vector<size_t>> clusters(live.size());
    for (size_t i = 0; i < live.size(); ++i)
      clusters[findp(i)].push_back(i);
    contact_possible = false;
    for (const auto& cl : clusters) {
      if (cl.empty()) continue;
      Box ha = A.nodes[static_cast<size_t>(live[cl[0]].a)].b;
      Box hb = B.nodes[static_cast<size_t>(live[cl[0]].b)].b;
      double clb = HUGE_VAL;
      for (size_t i : cl) {
        ha = hull(ha, A.nodes[static_cast<size_t>(live[i].a)].b);
        hb = hull(hb, B.nodes[static_cast<size_t>(live[i].b)].b);
        clb = std::min(clb, live[i].lb);
      }
      if (clb > ub) continue;
      if (accept(prove_cluster(sa, sb, ha, hb))) continue;
      if (clb <= 0) contact_possible = true;
      for (size_t i : cl)
        queue.push(live[i]); // refine further next round
    }
    if (queue.empty()) break;
  }
  out.critical_candidates = static_cast<int>(found.size());
  if (!queue.empty()) {
    if (clip > 0 && clip_short && ub < HUGE_VAL && ub >= clip) *clip_short = ub;
    if (ub < HUGE_VAL) { // ub: the interval distance of two boxes proven to hold surface points
      Arf u;
      arf_set_d(u.v, ub);
      out.distance = Enclosure::up_to(u.v, digits);
      out.pairs.push_back(ub_pair);
    }
    return undecided(out, contact_possible
                              ? "contact not decided (touching or meeting without a witness)"
                              : "could not isolate the minimum (singular points, a continuum "
                                "of minimizers or a degenerate critical pair)");
  }
  if (found.empty()) return undecided(out, "no critical pair proven");
  // candidates: those whose enclosure may hold the minimum; refine them at `digits`
  auto candidates = [&]() {
    arf_t best, l;
    arf_init(best);
    arf_init(l);
    arf_pos_inf(best);
    for (const Critical& c : found) {
      arb_get_ubound_arf(l, c.d.v, ARF_PREC_EXACT);
      if (arf_cmp(l, best) < 0) arf_set(best, l);
    }
    std::vector<size_t> idx;
    for (size_t i = 0; i < found.size(); ++i) {
      arb_get_lbound_arf(l, found[i].d.v, ARF_PREC_EXACT);
      if (arf_cmp(l, best) <= 0) idx.push_back(i);
    }
    arf_clear(best);
    arf_clear(l);
    return idx;
  };
  std::vector<size_t> idx = candidates();
  for (size_t i : idx)
    if (!refine(sa, sb, found[i], digits))
      return undecided(out, "could not refine a proven critical pair to the requested digits");
  std::vector<Critical> kept;
  for (size_t i : idx)
    kept.push_back(std::move(found[i]));
  found = std::move(kept);
  idx = candidates();
  const long prec = 2 * bits_for(digits) + 64;
  Ball lo, hi, d;
  arb_pos_inf(lo.v);
  arb_pos_inf(hi.v);
  for (size_t i : idx) {
    arf_t l, u;
    arf_init(l);
    arf_init(u);
    arb_get_lbound_arf(l, found[i].d.v, prec);
    arb_get_ubound_arf(u, found[i].d.v, prec);
    Ball bl, bu;
    arb_set_arf(bl.v, l);
    arb_set_arf(bu.v, u);
    if (!arb_is_finite(lo.v) || arb_lt(bl.v, lo.v)) arb_set(lo.v, bl.v);
    if (!arb_is_finite(hi.v) || arb_lt(bu.v, hi.v)) arb_set(hi.v, bu.v);
    arf_clear(l);
    arf_clear(u);
    out.pairs.push_back({D3{found[i].x[0], found[i].x[1], found[i].x[2]},
                         D3{found[i].x[3], found[i].x[4], found[i].x[5]}});
  }
  if (!relative_enclosure(d.v, lo.v, hi.v, digits, prec))
    return undecided(out, "the candidate minima are not separated to the requested digits");
  if (clip > 0) {
    // The global minimum is inside the cube only when it is below clip (outward: the upper
    // end of the enclosure against clip, both as Arb numbers).
    Ball c;
    arb_set_d(c.v, clip);
    if (!arb_lt(d.v, c.v)) { // every point of the ball d below clip
      if (clip_short) *clip_short = arf_get_d(arb_midref(d.v), ARF_RND_UP);
      return undecided(out, "the minimum over the clipping cube is not below its margin");
    }
  }
  out.status = Status::Certified;
  set_distance_enclosure(out, d.v, digits);
  out.minimizers = Minimizers::count(static_cast<long>(idx.size()), Minimizers::Proof::Interval);
  note_unproven_ties(out, idx.size());
  // Tie regions (symmetry.hpp): the f-point part of each minimizer's Krawczyk box. Every
  // global minimizer is a critical pair in one of these boxes; when the f-parts are pairwise
  // disjoint, no region holds the f-point of two minimizers (the other's box would meet it).
  if (idx.size() > 1) {
    std::vector<std::vector<std::array<double, 2>>> regs;
    for (size_t i : idx) {
      std::vector<std::array<double, 2>> r;
      for (size_t k = 0; k < 3; ++k)
        r.push_back({found[i].X[k].inf(), found[i].X[k].sup()});
      regs.push_back(std::move(r));
    }
    bool disjoint = true;
    for (size_t i = 0; i < regs.size(); ++i)
      for (size_t j = i + 1; j < regs.size(); ++j) {
        bool meet = true;
        for (size_t k = 0; k < 3; ++k)
          meet = meet && regs[i][k][0] <= regs[j][k][1] && regs[j][k][0] <= regs[i][k][1];
        disjoint = disjoint && !meet;
      }
    if (disjoint) out.tie_regions = std::move(regs);
  }
  return out;
}

} // namespace

namespace {

// The working frame x = c + 2^k y: c a dyadic point near the surfaces, 2^k their size, so the
// branch and bound (whose float guidance and padding are tuned for unit-size surfaces, and
// whose Lagrange multipliers scale with the size and the coefficients) sees unit-size
// surfaces near the origin whatever the input's scale or position. Exact: c and 2^k are dyadic,
// the polynomials are substituted and divided by their largest |coefficient| over Q, distances
// scale by 2^k, points map back by x = c + 2^k y.
struct Frame {
  std::array<double, 3> c{};
  long k = 0;
};

std::optional<Box> zero_hull(const core::Poly3& p) {
  Surf s = make_surf(p);
  const auto t = bounding_radius(s.f);
  if (!t) return std::nullopt;
  s.T = *t;
  Box h{DI(-s.T, s.T), DI(-s.T, s.T), DI(-s.T, s.T)};
  // Each hull holds the zero set, so it can root the next, finer pass (a far-off surface's
  // first hull is coarse: the cube around the origin is much larger than the surface).
  for (int pass = 0; pass < 6; ++pass) {
    // Re-expanded about the current hull's centre (far from the origin the monomial form
    // cancels badly and no box is ever excluded).
    Surf sc = pass == 0 ? std::move(s) : make_surf(p, centre(h));
    sc.T = 0.5 * width(h);
    s = std::move(sc);
    Tree tr;
    tr.s = &s;
    const int root = tr.make(h);
    if (root < 0) return std::nullopt;
    const Box next = tight_hull(tr, root);
    const bool shrunk = width(next) < 0.5 * width(h);
    h = next;
    if (!shrunk) break;
  }
  return h;
}

core::Poly3 in_frame(const core::Poly3& p, const Frame& fr) {
  std::array<core::Poly3, 3> l;
  const Rational sc = Rational::exact_from_double(std::ldexp(1.0, static_cast<int>(fr.k)));
  for (size_t i = 0; i < 3; ++i)
    l[i] = core::Poly3::variable(static_cast<int>(i)).scaled(sc) +
           core::Poly3(Rational::exact_from_double(fr.c[i]));
  const core::Poly3 out = p.substitute(l);
  Rational big;
  for (const auto& [e, c] : out.terms())
    if (core::abs(c) > big) big = core::abs(c);
  return big.is_zero() ? out : out.scaled(Rational(1) / big);
}

DistanceResult from_frame(DistanceResult r, const Frame& fr) {
  const double s = std::ldexp(1.0, static_cast<int>(fr.k));
  if (r.distance) r.distance = r.distance->scaled_2exp(fr.k);
  for (auto& pr : r.pairs)
    for (auto& pt : pr)
      for (size_t i = 0; i < 3; ++i)
        pt[i] = fr.c[i] + s * pt[i];
  for (auto& reg : r.tie_regions)
    for (size_t i = 0; i < reg.size() && i < 3; ++i) {
      reg[i][0] = std::nextafter(fr.c[i] + s * reg[i][0], -HUGE_VAL);
      reg[i][1] = std::nextafter(fr.c[i] + s * reg[i][1], HUGE_VAL);
    }
  return r;
}

// The frame of the hull h: centre rounded to 2^(k-20), 2^k >= the hull's largest width.
Frame frame_of(const Box& h) {
  Frame fr;
  const double w = std::max(width(h), 1e-300);
  fr.k = static_cast<long>(std::ceil(std::log2(w)));
  const D3 c = centre(h);
  for (size_t i = 0; i < 3; ++i)
    fr.c[i] = std::ldexp(std::nearbyint(std::ldexp(c[i], static_cast<int>(20 - fr.k))),
                         static_cast<int>(fr.k - 20));
  return fr;
}

} // namespace

DistanceResult implicit_pair_distance(const core::Poly3& f, const core::Poly3& g, long digits) {
  std::optional<Box> hf, hg;
  {
    CGAL::Protect_FPU_rounding<true> guard;
    hf = zero_hull(f);
    hg = zero_hull(g);
  }
  if (!hf || !hg) return pair_distance(f, g, digits, 0, nullptr); // it says why
  const Frame fr = frame_of(hull(*hf, *hg));
  return from_frame(pair_distance(in_frame(f, fr), in_frame(g, fr), digits + 1, 0, nullptr), fr);
}

DistanceResult bounded_unbounded_distance(const core::Poly3& f, const core::Poly3& g, long digits) {
  std::optional<Box> hf;
  {
    CGAL::Protect_FPU_rounding<true> guard;
    hf = zero_hull(f);
  }
  if (!hf) return pair_distance(f, g, digits, 1, nullptr); // it says why
  const Frame fr = frame_of(*hf);
  const core::Poly3 F = in_frame(f, fr), G = in_frame(g, fr);
  // The first margin: the bounded surface's size (1 in the frame); then past the genuine pair
  // found, or a wider cube when the unbounded surface was not reached.
  double clip = 1, need = 0;
  for (int attempt = 0; attempt < 4; ++attempt) {
    need = 0;
    DistanceResult r = pair_distance(F, G, digits + 1, clip, &need);
    if (r.status == Status::Certified || need <= 0) {
      if (r.status == Status::Certified && !r.distance->is_zero())
        r.note += std::string(r.note.empty() ? "" : "; ") +
                  "the unbounded surface taken within a cube around the bounded one, wide "
                  "enough that every point outside is farther than the minimum";
      return from_frame(std::move(r), fr);
    }
    clip = 2 * need + 1;
  }
  return undecided(DistanceResult{}, "the minimum over the clipping cube is not below its margin");
}

// Branch and bound over pairs of boxes plus Krawczyk on the Lagrange system for two bounded
// implicit surfaces (implicit_bnb.hpp). Double intervals (CGAL, outward rounding under
// Protect_FPU_rounding) drive the branch and bound; Arb balls decide the Krawczyk tests and the
// final enclosure. Float Newton iterations only propose points; they never decide.

} // namespace surfcert::certify
