// cubic_in_box and cubic_arc_points: the arcs of an exact twisted cubic (see conics.hpp).
//
// The cubic (s : t) -> X(s, t) is read on the circle (s, t) = (cos u, sin u), u in
// (-pi/2, pi/2] (once around P^1(R)). The parameters where it meets infinity (X_3 = 0) or a
// face plane of the box (X_k - c X_3 = 0) are the real roots of binary cubics with rational
// coefficients, isolated exactly (algebra::isolate_real_roots) and rounded; between two
// consecutive ones the point stays on one side of every face plane, so each such interval is
// inside the box or outside. The inside ones are sampled (chord error below `chord`); their
// ends are the cubic's points at the face roots' parameters (to 2^-110) computed exactly,
// rounded, and put onto their face planes. Floating point, like all of surfcert::trace:
// intersect_curve checks the pieces against the exact crossings with the faces.
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/upoly.hpp"
#include "surfcert/trace/conics.hpp"

#include <flint/fmpz_poly.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace surfcert::trace {

namespace {

using core::Rational;
using Form = std::array<Rational, 4>; // c[k] s^(3-k) t^k

// A root of a binary cubic on the circle: u, and tan u to ~2^-110 of its size (a rational
// in the root's isolating interval; none at s = 0, u = pi / 2).
struct CircleRoot {
  double u;
  std::optional<Rational> tan_u;
};

struct Break {
  double u;
  int axis = -1; ///< the face plane x_axis = value (-1: a point at infinity)
  double value = 0;
  std::optional<Rational> tan_u; ///< see CircleRoot
};

// Real roots u in (-pi/2, pi/2] of the binary cubic f(cos u, sin u) (f not identically 0).
std::vector<CircleRoot> roots_on_circle(const Form& f) {
  std::vector<CircleRoot> out;
  if (f[3].is_zero()) out.push_back({M_PI / 2, std::nullopt}); // s = 0
  const algebra::UPolyQ p = algebra::UPolyQ::from_coeffs({f[0], f[1], f[2], f[3]});
  if (p.degree() <= 0) return out;
  algebra::UPolyZ z = p.primitive_integer(), dz = z.derivative(), g, sq;
  fmpz_poly_gcd(g.raw_mut(), z.raw(), dz.raw());
  fmpz_poly_div(sq.raw_mut(), z.raw(), g.raw());
  sq = sq.primitive_part();
  const algebra::RootSeparation sep = algebra::isolate_real_roots(sq);
  for (size_t i = 0; i + 1 < sep.separators.size(); ++i) {
    Rational lo = sep.separators[i], hi = sep.separators[i + 1];
    const double m =
        std::max({1.0, std::fabs(lo.to_double_approx()), std::fabs(hi.to_double_approx())});
    // To 2^-110 of its size, not 2^-60: a face crossing's point is computed from it exactly
    // (end_point below), and far out (|X| >> 1, X_3 small) the point moves by ~|X|^2 times
    // the parameter's error.
    algebra::refine_root(sq, lo, hi, Rational::exact_from_double(std::ldexp(m, -110)));
    const Rational mid = (lo + hi) / Rational(2);
    out.push_back({std::atan(mid.to_double_approx()), mid});
  }
  return out;
}

struct Param {
  std::array<std::array<double, 4>, 4> c; // c[i][k]
  explicit Param(const certify::CubicAndLine& cl) {
    for (size_t i = 0; i < 4; ++i)
      for (size_t k = 0; k < 4; ++k)
        c[i][k] = cl.cubic[i][k].to_double_approx();
  }
  std::array<double, 4> homogeneous(double u) const {
    const double s = std::cos(u), t = std::sin(u);
    const double m[4] = {s * s * s, s * s * t, s * t * t, t * t * t};
    std::array<double, 4> x{};
    for (size_t i = 0; i < 4; ++i)
      for (size_t k = 0; k < 4; ++k)
        x[i] += c[i][k] * m[k];
    return x;
  }
  Point3 at(double u) const {
    const auto x = homogeneous(u);
    return {x[0] / x[3], x[1] / x[3], x[2] / x[3]};
  }
};

// X(1, tau) / X_3(1, tau) exactly, then rounded (nullopt at a point at infinity). In doubles
// (Param::at), a point far out carries an error ~2^-53 |X|^2 / |X_3| of its coordinates: a
// cubic's end on a face 10^4 out, where the cubic runs beside its tangent line, lay 5e-8 off
// the surfaces and could not be told from the line's end at 10^5.
std::optional<Point3> exact_point(const certify::CubicAndLine& cl, const Rational& tau) {
  const Rational m[4] = {Rational(1), tau, tau * tau, tau * tau * tau};
  std::array<Rational, 4> x;
  for (size_t i = 0; i < 4; ++i)
    for (size_t k = 0; k < 4; ++k)
      x[i] += cl.cubic[i][k] * m[k];
  if (x[3].is_zero()) return std::nullopt;
  return Point3{(x[0] / x[3]).to_double_approx(), (x[1] / x[3]).to_double_approx(),
                (x[2] / x[3]).to_double_approx()};
}

double dist(const Point3& p, const Point3& q) {
  return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                   (p[2] - q[2]) * (p[2] - q[2]));
}

// The breakpoints sorted on (-pi/2, pi/2].
std::vector<Break> sorted(std::vector<Break> b) {
  std::sort(b.begin(), b.end(), [](const Break& x, const Break& y) { return x.u < y.u; });
  return b;
}

std::vector<Break> infinity_breaks(const certify::CubicAndLine& cl) {
  std::vector<Break> out;
  for (const CircleRoot& r : roots_on_circle(cl.cubic[3]))
    out.push_back({r.u, -1, 0, std::nullopt});
  return sorted(out);
}

} // namespace

std::vector<Branch> cubic_in_box(const certify::CubicAndLine& cl, const Box& box, double chord,
                                 int max_points) {
  const Param par(cl);
  std::vector<Break> br = infinity_breaks(cl);
  for (size_t k = 0; k < 3; ++k)
    for (double v : {box.min[k], box.max[k]}) {
      const Rational c = Rational::exact_from_double(v);
      Form f;
      for (size_t j = 0; j < 4; ++j)
        f[j] = cl.cubic[k][j] - c * cl.cubic[3][j];
      if (f[0].is_zero() && f[1].is_zero() && f[2].is_zero() && f[3].is_zero()) continue;
      for (const CircleRoot& r : roots_on_circle(f))
        br.push_back({r.u, static_cast<int>(k), v, r.tan_u});
    }
  br = sorted(br);
  std::vector<Branch> out;
  if (br.empty()) return out; // X_3 has a real root: not reached
  auto end_point = [&](const Break& b) {
    std::optional<Point3> e = b.tan_u ? exact_point(cl, *b.tan_u) : std::nullopt;
    Point3 p = e ? *e : par.at(b.u);
    if (b.axis >= 0) p[static_cast<size_t>(b.axis)] = b.value;
    return p;
  };
  const size_t n = br.size();
  for (size_t i = 0; i < n; ++i) {
    const Break& a = br[i];
    Break b = br[(i + 1) % n];
    if (i + 1 == n) b.u += M_PI; // around the circle (X(-s, -t) = -X(s, t): the same point)
    if (!(b.u > a.u) || a.axis < 0 || b.axis < 0) continue; // an end at infinity: outside
    if (!box.contains(par.at(0.5 * (a.u + b.u)))) continue;
    Branch piece;
    piece.kind = "cubic";
    piece.closed = false;
    piece.points.push_back(end_point(a));
    const Point3 last = end_point(b);
    // Bisection of the parameter until the midpoint lies within `chord` of the chord's middle
    // (at least 2^5 segments).
    struct Seg {
      double u0, u1;
      Point3 p0, p1;
      int depth;
    };
    std::vector<Seg> stack{{a.u, b.u, piece.points.front(), last, 0}};
    while (!stack.empty()) {
      Seg s = stack.back();
      stack.pop_back();
      const double um = 0.5 * (s.u0 + s.u1);
      const Point3 pm = par.at(um);
      const Point3 mid{0.5 * (s.p0[0] + s.p1[0]), 0.5 * (s.p0[1] + s.p1[1]),
                       0.5 * (s.p0[2] + s.p1[2])};
      const bool split = s.depth < 5 || (dist(pm, mid) > chord && s.depth < 48 &&
                                         static_cast<int>(piece.points.size()) < max_points);
      if (!split) {
        piece.points.push_back(s.p1);
        continue;
      }
      stack.push_back({um, s.u1, pm, s.p1, s.depth + 1}); // the second half after the first
      stack.push_back({s.u0, um, s.p0, pm, s.depth + 1});
    }
    out.push_back(std::move(piece));
  }
  return out;
}

std::vector<Point3> cubic_arc_points(const certify::CubicAndLine& cl) {
  const Param par(cl);
  const std::vector<Break> br = infinity_breaks(cl);
  std::vector<Point3> out;
  const size_t n = br.size();
  for (size_t i = 0; i < n; ++i) {
    const double u0 = br[i].u, u1 = i + 1 == n ? br[0].u + M_PI : br[i + 1].u;
    Point3 best{};
    double bn = HUGE_VAL;
    for (int j = 1; j < 64; ++j) {
      const Point3 p = par.at(u0 + (u1 - u0) * j / 64.0);
      const double d = dist(p, Point3{0, 0, 0});
      if (std::isfinite(d) && d < bn) bn = d, best = p;
    }
    if (std::isfinite(bn)) out.push_back(best);
  }
  return out;
}

} // namespace surfcert::trace
