#include "surfcert/certify/distance/plane_quadric.hpp"

#include "surfcert/certify/distance/ball.hpp"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

using V3 = std::array<Rational, 3>;

// a + b s + c s^2 over Q (the level polynomials have degree <= 2).
struct Quad {
  Rational c[3];
  Quad operator+(const Quad& o) const { return {{c[0] + o.c[0], c[1] + o.c[1], c[2] + o.c[2]}}; }
  Quad operator-(const Quad& o) const { return {{c[0] - o.c[0], c[1] - o.c[1], c[2] - o.c[2]}}; }
  Quad operator*(const Rational& k) const { return {{c[0] * k, c[1] * k, c[2] * k}}; }
  bool zero() const { return c[0].is_zero() && c[1].is_zero() && c[2].is_zero(); }
  double at(double s) const {
    return c[0].to_double_approx() + s * (c[1].to_double_approx() + s * c[2].to_double_approx());
  }
};

// Product of two affine polynomials (degree <= 1 each).
Quad mul(const Quad& a, const Quad& b) {
  return {{a.c[0] * b.c[0], a.c[0] * b.c[1] + a.c[1] * b.c[0], a.c[1] * b.c[1]}};
}

Rational dot(const V3& x, const V3& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

V3 cross(const V3& x, const V3& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}

V3 mulM(const std::array<V3, 3>& M, const V3& x) {
  return {dot(M[0], x), dot(M[1], x), dot(M[2], x)};
}

// Where the nearest root of h (h(0) != 0) lies: rho = 2 |h0| / (|h1| + sqrt(D)) with sign
// -sign(h1) sign(h0) (both signs when h1 = 0: a tie, exactly). False when h has no real root.
struct NearestRoot {
  bool exists = false;
  bool tie = false;
  int sign = 0;
  Rational D; ///< discriminant h1^2 - 4 h2 h0 (h1^2 when h2 = 0)
};

NearestRoot nearest_root(const Quad& h) {
  NearestRoot r;
  const Rational &h0 = h.c[0], &h1 = h.c[1], &h2 = h.c[2];
  if (h2.is_zero()) {
    if (h1.is_zero()) return r;
    r.D = h1 * h1;
  } else {
    r.D = h1 * h1 - Rational(4) * h2 * h0;
    if (r.D.sign() < 0) return r;
  }
  r.exists = true;
  r.tie = h1.is_zero();
  r.sign = -h1.sign() * h0.sign();
  return r;
}

// rho / |n| in Arb, to relative width 10^-digits.
void enclose(arb_t d, const Quad& h, const NearestRoot& nr, const Rational& nn, long digits) {
  for (long prec = bits_for(digits + 10);; prec *= 2) {
    Ball D, a1, a0, t, n;
    arb_set_fmpq(D.v, nr.D.raw(), prec);
    arb_sqrt(D.v, D.v, prec);
    arb_set_fmpq(a1.v, core::abs(h.c[1]).raw(), prec);
    arb_add(t.v, D.v, a1.v, prec);
    arb_set_fmpq(a0.v, core::abs(h.c[0]).raw(), prec);
    arb_mul_2exp_si(a0.v, a0.v, 1);
    arb_div(d, a0.v, t.v, prec);
    arb_set_fmpq(n.v, nn.raw(), prec);
    arb_sqrt(n.v, n.v, prec);
    arb_div(d, d, n.v, prec);
    if (arb_rel_accuracy_bits(d) > static_cast<slong>(3.33 * static_cast<double>(digits)) + 8 ||
        prec > 1 << 20)
      return;
  }
}

} // namespace

DistanceResult plane_quadric_distance(const core::QuadricMatrix& plane,
                                      const core::QuadricMatrix& q, long digits, bool plane_first) {
  DistanceResult out;
  out.method = Method::PlaneClosedForm;
  // The plane n.x = delta (its matrix holds n as half the linear part).
  const V3 n{plane(0, 3), plane(1, 3), plane(2, 3)};
  const Rational nn = dot(n, n), delta = -plane(3, 3) * Rational(1, 2);
  std::array<V3, 3> M;
  V3 b;
  for (size_t i = 0; i < 3; ++i) {
    b[i] = q(static_cast<int>(i), 3);
    for (size_t j = 0; j < 3; ++j)
      M[i][j] = q(static_cast<int>(i), static_cast<int>(j));
  }
  const Rational c = q(3, 3);
  // A rational orthogonal basis e1, e2 of n-perp, and the level points x0(s) = p0 + s p1.
  size_t k = 0;
  for (size_t i = 1; i < 3; ++i)
    if (core::abs(n[i]) < core::abs(n[k])) k = i;
  V3 ek{Rational(0), Rational(0), Rational(0)};
  ek[k] = Rational(1);
  const V3 e1 = cross(n, ek), e2 = cross(n, e1);
  V3 p0, p1;
  for (size_t i = 0; i < 3; ++i) {
    p1[i] = n[i] / nn;
    p0[i] = delta * p1[i];
  }
  // q_s(u, v) = [u v] A [u v]^T + 2 g(s).(u, v) + f(s).
  const std::array<V3, 2> E{e1, e2};
  Rational A[2][2];
  Quad g[2], f;
  const V3 Mp0 = mulM(M, p0), Mp1 = mulM(M, p1);
  for (size_t i = 0; i < 2; ++i) {
    const V3 Me = mulM(M, E[i]);
    for (size_t j = 0; j < 2; ++j)
      A[i][j] = dot(E[j], Me);
    g[i] = {{dot(E[i], Mp0) + dot(E[i], b), dot(E[i], Mp1), Rational(0)}};
  }
  f = {{dot(p0, Mp0) + Rational(2) * dot(b, p0) + c,
        Rational(2) * dot(p1, Mp0) + Rational(2) * dot(b, p1), dot(p1, Mp1)}};
  const Rational det = A[0][0] * A[1][1] - A[0][1] * A[0][1];

  // The pair at level s from in-plane coordinates (u, v) (doubles: approximate points).
  auto add_pair = [&](double s, double u, double v) {
    std::array<double, 3> x{}, y{};
    for (size_t i = 0; i < 3; ++i) {
      x[i] = p0[i].to_double_approx() + s * p1[i].to_double_approx() +
             u * e1[i].to_double_approx() + v * e2[i].to_double_approx();
      y[i] = x[i] - s * p1[i].to_double_approx(); // its foot on the plane
    }
    out.pairs.push_back(plane_first ? std::array<std::array<double, 3>, 2>{y, x}
                                    : std::array<std::array<double, 3>, 2>{x, y});
  };
  auto meet = [&](const std::string& how, Minimizers count, double u, double v) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = count;
    out.note = "the plane meets the quadric (" + how + "; decided exactly on the section)";
    add_pair(0, u, v);
    return out;
  };
  auto not_attained = [&](const std::string& why) {
    out.status = Status::Certified;
    out.distance = Enclosure::zero();
    out.minimizers = Minimizers::not_attained(Minimizers::Proof::Exact);
    out.note = "the surfaces do not meet but approach each other at infinity (" + why +
               "): the distance is the infimum 0, not attained";
    return out;
  };
  // The distance to the nearest level of S = {h <= 0} (or {h = 0}), h(0) != 0.
  auto at_nearest = [&](const Quad& h, const char* shape, const std::string& how,
                        const std::function<std::array<double, 2>(double)>& point) {
    const NearestRoot nr = nearest_root(h);
    if (!nr.exists) {
      out.status = Status::Undecided;
      out.note = "the quadric has no real point";
      return out;
    }
    Ball d;
    enclose(d.v, h, nr, nn, digits);
    out.status = Status::Certified;
    set_distance_enclosure(out, d.v, digits);
    out.eliminated_degree = !h.c[2].is_zero() ? 2 : 1;
    out.critical_candidates = nr.tie ? 2 : 1;
    const double rho = out.approx() * std::sqrt(nn.to_double_approx());
    for (int sg : nr.tie ? std::vector<int>{-1, 1} : std::vector<int>{nr.sign}) {
      const auto uv = point(sg * rho);
      add_pair(sg * rho, uv[0], uv[1]);
    }
    if (std::string(shape) == "point") {
      out.minimizers = Minimizers::count(nr.tie ? 2 : 1, Minimizers::Proof::Exact);
    } else {
      out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
    }
    out.note = "plane and quadric: the nearest parallel level the quadric reaches (" + how +
               "), a root of a polynomial of degree <= 2 over Q; closed form in Arb";
    if (nr.tie && out.minimizers == Minimizers::count(2, Minimizers::Proof::Exact)) {
      out.ties = Ties::Proven;
      out.note += "; two levels at exactly the same distance on both sides of the plane "
                  "(the roots are +-rho exactly)";
    }
    return out;
  };

  if (det.sign() < 0) { // indefinite: every level is met; a witness on a line through (0, 0)
    const Rational f0 = f.c[0];
    if (f0.is_zero())
      return meet("a hyperbola or two lines", Minimizers::continuum(Minimizers::Proof::Exact), 0,
                  0);
    // A direction (du, dv) where the form has the sign opposite to f0 (exists: A indefinite):
    // (1, 0), (0, 1), the vertex direction (1, -A01/A11') of A(1, t), or, when A11 = 0, a
    // point of the linear A(1, t). Along it lambda^2 a + 2 lambda g.d + f0 has a real root.
    std::vector<std::array<Rational, 2>> dirs = {{Rational(1), Rational(0)},
                                                 {Rational(0), Rational(1)}};
    if (!A[1][1].is_zero())
      dirs.push_back({Rational(1), -A[0][1] / A[1][1]});
    else
      dirs.push_back({Rational(1), (-A[0][0] - Rational(f0.sign())) / (Rational(2) * A[0][1])});
    for (const auto& d : dirs) {
      const Rational at =
          A[0][0] * d[0] * d[0] + Rational(2) * A[0][1] * d[0] * d[1] + A[1][1] * d[1] * d[1];
      if (at.sign() * f0.sign() < 0) {
        const double a = at.to_double_approx(),
                     gb = (g[0].c[0] * d[0] + g[1].c[0] * d[1]).to_double_approx(),
                     c0 = f0.to_double_approx();
        const double lam = (-gb + std::sqrt(gb * gb - a * c0)) / a;
        return meet("a hyperbola or two lines", Minimizers::continuum(Minimizers::Proof::Exact),
                    lam * d[0].to_double_approx(), lam * d[1].to_double_approx());
      }
    }
    return meet("a hyperbola or two lines", Minimizers::continuum(Minimizers::Proof::Exact), 0,
                0); // unreachable: A indefinite
  }

  if (det.sign() > 0) { // definite: S = {m <= 0}, m = f - g^T A^-1 g (sign normalised)
    const Rational sg(A[0][0].sign());
    // g^T adj(A) g / det, with adj = [[A11, -A01], [-A01, A00]].
    const Quad gAg = mul(g[0], g[0]) * A[1][1] - mul(g[0], g[1]) * (Rational(2) * A[0][1]) +
                     mul(g[1], g[1]) * A[0][0];
    const Quad m = (f - gAg * (Rational(1) / det)) * sg;
    auto centre = [&](double s) -> std::array<double, 2> { // -A^-1 g(s)
      const double g0 = g[0].at(s), g1 = g[1].at(s), dd = det.to_double_approx();
      return {-(A[1][1].to_double_approx() * g0 - A[0][1].to_double_approx() * g1) / dd,
              -(A[0][0].to_double_approx() * g1 - A[0][1].to_double_approx() * g0) / dd};
    };
    if (m.c[0].sign() <= 0) {
      const auto cu = centre(0);
      const double t = std::sqrt(std::max(0.0, -m.c[0].to_double_approx() * sg.to_double_approx() /
                                                   A[0][0].to_double_approx()));
      return m.c[0].is_zero() ? meet("they touch at one point",
                                     Minimizers::count(1, Minimizers::Proof::Exact), cu[0], cu[1])
                              : meet("an ellipse", Minimizers::continuum(Minimizers::Proof::Exact),
                                     cu[0] + t, cu[1]);
    }
    return at_nearest(m, "point", "a tangency point", centre);
  }

  const bool A_zero = A[0][0].is_zero() && A[0][1].is_zero() && A[1][1].is_zero();
  if (!A_zero) { // rank 1: kernel k, row w; q = a p^2 + 2 (g.w) p + 2 (g.k) t + f
    Rational kv[2], wv[2];
    if (!A[0][0].is_zero() || !A[0][1].is_zero()) {
      kv[0] = -A[0][1];
      kv[1] = A[0][0];
      wv[0] = A[0][0];
      wv[1] = A[0][1];
    } else {
      kv[0] = Rational(1);
      kv[1] = Rational(0);
      wv[0] = A[0][1];
      wv[1] = A[1][1];
    }
    const Rational a =
        wv[0] * (A[0][0] * wv[0] + A[0][1] * wv[1]) + wv[1] * (A[0][1] * wv[0] + A[1][1] * wv[1]);
    const Quad gk = g[0] * kv[0] + g[1] * kv[1], gw = g[0] * wv[0] + g[1] * wv[1];
    auto uv = [&](double p, double t) -> std::array<double, 2> {
      return {p * wv[0].to_double_approx() + t * kv[0].to_double_approx(),
              p * wv[1].to_double_approx() + t * kv[1].to_double_approx()};
    };
    if (!gk.zero()) {
      if (!gk.c[0].is_zero()) {
        const auto w = uv(0, -f.c[0].to_double_approx() / (2 * gk.c[0].to_double_approx()));
        return meet("a parabola", Minimizers::continuum(Minimizers::Proof::Exact), w[0], w[1]);
      }
      const Rational disc0 = gw.c[0] * gw.c[0] - a * f.c[0];
      if (disc0.sign() >= 0) {
        const auto w = uv((-gw.c[0].to_double_approx() + std::sqrt(disc0.to_double_approx())) /
                              a.to_double_approx(),
                          0);
        return meet(disc0.is_zero() ? "a line" : "two lines",
                    Minimizers::continuum(Minimizers::Proof::Exact), w[0], w[1]);
      }
      return not_attained("a parabolic section whose axis is parallel to the plane");
    }
    const Rational sg(a.sign());
    const Quad m = (f - mul(gw, gw) * (Rational(1) / a)) * sg;
    auto line_point = [&](double s) { return uv(-gw.at(s) / a.to_double_approx(), 0); };
    if (m.c[0].sign() <= 0) { // a p^2 + 2 (g.w) p + f = 0 at level 0
      const double gw0 = gw.c[0].to_double_approx(), ad = a.to_double_approx();
      const double disc = std::max(0.0, gw0 * gw0 - ad * f.c[0].to_double_approx());
      const auto w = uv((-gw0 + std::sqrt(disc)) / ad, 0);
      return meet(m.c[0].is_zero() ? "they touch along a line" : "two lines",
                  Minimizers::continuum(Minimizers::Proof::Exact), w[0], w[1]);
    }
    return at_nearest(m, "line", "a line of contact", line_point);
  }

  // A = 0: the quadric is linear along the plane's directions.
  if (!g[0].zero() || !g[1].zero()) {
    const double g0 = g[0].c[0].to_double_approx(), g1 = g[1].c[0].to_double_approx();
    if (!g[0].c[0].is_zero() || !g[1].c[0].is_zero()) {
      const double k0 = -f.c[0].to_double_approx() / (2 * (g0 * g0 + g1 * g1));
      return meet("a line", Minimizers::continuum(Minimizers::Proof::Exact), k0 * g0, k0 * g1);
    }
    if (f.c[0].is_zero())
      return meet("the plane lies in the quadric", Minimizers::continuum(Minimizers::Proof::Exact),
                  0, 0);
    return not_attained("the quadric is asymptotic to the plane");
  }
  if (f.c[0].is_zero())
    return meet("the plane lies in the quadric", Minimizers::continuum(Minimizers::Proof::Exact), 0,
                0);
  return at_nearest(f, "plane", "a parallel plane", [](double) {
    return std::array<double, 2>{0, 0};
  });
}

} // namespace surfcert::certify
