#include "surfcert/certify/distance/parametric_distance.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/implicit_bnb.hpp"
#include "surfcert/certify/distance/solid_relation.hpp"

#include <flint/fmpq.h>
#include <flint/fmpz_mat.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace surfcert::certify {

using core::Poly3;
using core::Rational;

namespace {

// The monomials of degree <= d in x, y, z.
std::vector<Poly3::Exponent> monomials(int d) {
  std::vector<Poly3::Exponent> m;
  for (int t = 0; t <= d; ++t)
    for (int i = t; i >= 0; --i)
      for (int j = t - i; j >= 0; --j)
        m.push_back({i, j, t - i - j});
  return m;
}

// Integer nullspace of the substitution map on degree-d forms: F(X, Y, Z, W) homogenised.
std::vector<std::vector<Rational>> substitution_nullspace(const core::ParametricSurface& p, int d) {
  const auto mons = monomials(d);
  std::vector<Poly3> cols;
  for (const auto& e : mons)
    cols.push_back(p.X.pow(static_cast<unsigned>(e[0])) * p.Y.pow(static_cast<unsigned>(e[1])) *
                   p.Z.pow(static_cast<unsigned>(e[2])) *
                   p.W.pow(static_cast<unsigned>(d - e[0] - e[1] - e[2])));
  std::map<Poly3::Exponent, size_t> rows;
  for (const auto& c : cols)
    for (const auto& [e, v] : c.terms())
      rows.emplace(e, rows.size());
  fmpz_mat_t A, N;
  fmpz_mat_init(A, static_cast<slong>(rows.size()), static_cast<slong>(cols.size()));
  // Integer rows: scale each column by its common denominator (the nullspace is unchanged up
  // to scaling the unknowns, undone below).
  std::vector<core::Integer> cden(cols.size(), core::Integer(1));
  for (size_t j = 0; j < cols.size(); ++j) {
    for (const auto& [e, v] : cols[j].terms())
      fmpz_lcm(cden[j].raw_mut(), cden[j].raw(), v.den().raw());
    for (const auto& [e, v] : cols[j].terms()) {
      Rational s = v * Rational(cden[j]);
      fmpz_set(fmpz_mat_entry(A, static_cast<slong>(rows[e]), static_cast<slong>(j)),
               s.num().raw());
    }
  }
  fmpz_mat_init(N, static_cast<slong>(cols.size()), static_cast<slong>(cols.size()));
  const slong nullity = fmpz_mat_nullspace(N, A);
  std::vector<std::vector<Rational>> out;
  for (slong k = 0; k < nullity; ++k) {
    std::vector<Rational> v(cols.size());
    for (size_t j = 0; j < cols.size(); ++j) {
      core::Integer e;
      fmpz_set(e.raw_mut(), fmpz_mat_entry(N, static_cast<slong>(j), k));
      v[j] = Rational(e) * Rational(cden[j]); // undo the column scaling
    }
    out.push_back(std::move(v));
  }
  fmpz_mat_clear(A);
  fmpz_mat_clear(N);
  return out;
}

// The top-degree homogeneous part.
Poly3 top(const Poly3& p, int d) {
  Poly3 r;
  for (const auto& [e, v] : p.terms())
    if (e[0] + e[1] + e[2] == d) r.add_term(e, v);
  return r;
}

double eval_d(const Poly3& p, double u, double v) {
  double s = 0;
  for (const auto& [e, c] : p.terms())
    s += c.to_double_approx() * std::pow(u, e[0]) * std::pow(v, e[1]);
  return s;
}

// The float proposer: (u, v) whose image P(u, v) is near x (Gauss-Newton from the best of a
// grid of starts). It only PROPOSES parameters; whatever it returns is checked exactly (the
// image point is evaluated in rationals and used as a witness, never as a membership verdict).
std::array<double, 2> propose_parameters(const core::ParametricSurface& p,
                                         const std::array<double, 3>& x) {
  auto res = [&](double u, double v, std::array<double, 3>& r) {
    double w = eval_d(p.W, u, v);
    if (w == 0) return false;
    r = {eval_d(p.X, u, v) / w - x[0], eval_d(p.Y, u, v) / w - x[1], eval_d(p.Z, u, v) / w - x[2]};
    return true;
  };
  auto norm = [](const std::array<double, 3>& r) { return std::hypot(r[0], r[1], r[2]); };
  // Gauss-Newton from (u, v); returns the residual reached and updates (u, v). Forward
  // differences with steps relative to each coordinate (a fixed step would swamp u ~ 1e-5 of
  // u^2 = 1e-10).
  auto descend = [&](double& bu, double& bv) {
    std::array<double, 3> r0{};
    if (!res(bu, bv, r0)) return 1e300;
    double best = norm(r0);
    for (int it = 0; it < 200 && best > 0; ++it) {
      const double hu = 1e-7 * (std::fabs(bu) > 1e-250 ? std::fabs(bu) : 1.0),
                   hv = 1e-7 * (std::fabs(bv) > 1e-250 ? std::fabs(bv) : 1.0);
      std::array<double, 3> ru{}, rv{};
      if (!res(bu, bv, r0) || !res(bu + hu, bv, ru) || !res(bu, bv + hv, rv)) break;
      double J[3][2];
      for (size_t k = 0; k < 3; ++k) {
        J[k][0] = (ru[k] - r0[k]) / hu;
        J[k][1] = (rv[k] - r0[k]) / hv;
      }
      double a = 0, b = 0, c = 0, g0 = 0, g1 = 0;
      for (size_t k = 0; k < 3; ++k) {
        a += J[k][0] * J[k][0];
        b += J[k][0] * J[k][1];
        c += J[k][1] * J[k][1];
        g0 += J[k][0] * r0[k];
        g1 += J[k][1] * r0[k];
      }
      const double det = a * c - b * b;
      if (!(std::fabs(det) > 1e-300)) break;
      const double du = (c * g0 - b * g1) / det, dv = (a * g1 - b * g0) / det;
      std::array<double, 3> rn{};
      if (!res(bu - du, bv - dv, rn) || !(norm(rn) < best)) break;
      bu -= du;
      bv -= dv;
      best = norm(rn);
    }
    return best;
  };
  // Several starts: the best grid point may sit where the Jacobian is singular (u = 0 of u^2).
  std::vector<std::array<double, 3>> starts; // (residual, u, v)
  std::array<double, 3> r{};
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) {
      double u = std::sinh(i / 8.0), v = std::sinh(j / 8.0);
      if (res(u, v, r)) starts.push_back({norm(r), u, v});
    }
  const size_t keep = std::min<size_t>(6, starts.size());
  std::partial_sort(starts.begin(), starts.begin() + static_cast<long>(keep), starts.end());
  double bu = 0, bv = 0, best = 1e300;
  for (size_t s = 0; s < keep; ++s) {
    double u = starts[s][1], v = starts[s][2];
    const double e = descend(u, v);
    if (e < best) best = e, bu = u, bv = v;
  }
  return {bu, bv};
}

using Point = std::array<Rational, 3>;

// The exact image point P(u, v) (rational u, v); nullopt where W(u, v) = 0.
std::optional<Point> image_point(const core::ParametricSurface& p, const Rational& u,
                                 const Rational& v) {
  const Rational z(0), w = p.W.evaluate(u, v, z);
  if (w.is_zero()) return std::nullopt;
  return Point{p.X.evaluate(u, v, z) / w, p.Y.evaluate(u, v, z) / w, p.Z.evaluate(u, v, z) / w};
}

// A polynomial whose real zero set is exactly the other surface (so an exact sign change of it
// along a segment proves a point of that surface on the segment); nullopt for canal surfaces.
std::optional<Poly3> zero_set_polynomial(const core::Surface& s) {
  if (const auto* q = std::get_if<core::QuadricMatrix>(&s)) return q->to_poly();
  if (const auto* im = std::get_if<core::ImplicitSurface>(&s)) return im->f;
  if (const auto* t = std::get_if<core::Torus>(&s)) return torus_polynomial(*t);
  return std::nullopt;
}

int exact_sign(const Poly3& g, const Point& x) {
  const Rational s = g.evaluate(x[0], x[1], x[2]);
  return s.is_zero() ? 0 : (s > Rational(0) ? 1 : -1);
}

Point along(const Point& q, const Point& d, const Rational& t) {
  return {q[0] + t * d[0], q[1] + t * d[1], q[2] + t * d[2]};
}

// A certified upper bound of the distance from the exact point q to the zero set of g: on the
// ray q + t (ya - q) (ya a float proposal of the foot), an exact sign change of g on
// [t_lo, t_hi] proves a root y there, and |q - y| <= t_hi |ya - q|. The bracket is narrowed by
// exact bisection to relative width 2^-bits. False when no sign change is found near t = 1.
bool ray_upper_bound(const Poly3& g, const Point& q, const std::array<double, 3>& ya, long bits,
                     arb_t up, std::array<double, 3>& foot) {
  Point d;
  for (size_t k = 0; k < 3; ++k)
    d[k] = Rational::exact_from_double(ya[k]) - q[k];
  if (d[0].is_zero() && d[1].is_zero() && d[2].is_zero()) return false;
  Rational lo, hi;
  int slo = 0, shi = 0;
  bool found = false;
  for (ulong e : {40UL, 30UL, 20UL, 10UL, 4UL}) {
    Rational h(1);
    fmpq_div_2exp(h.raw_mut(), h.raw(), e);
    lo = Rational(1) - h;
    hi = Rational(1) + h;
    slo = exact_sign(g, along(q, d, lo));
    shi = exact_sign(g, along(q, d, hi));
    if (slo * shi < 0) {
      found = true;
      break;
    }
  }
  if (!found) return false;
  Rational width = hi - lo, tol(1);
  fmpq_div_2exp(tol.raw_mut(), tol.raw(), static_cast<ulong>(bits));
  while (width > tol) {
    const Rational mid = (lo + hi) * Rational(1, 2);
    const int s = exact_sign(g, along(q, d, mid));
    if (s == 0) {
      lo = hi = mid;
      break;
    }
    (s == slo ? lo : hi) = mid;
    width = hi - lo;
  }
  const Rational n2 = hi * hi * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const long prec = bits + 64;
  arb_set_fmpq(up, n2.raw(), prec);
  arb_sqrt(up, up, prec);
  const Point y = along(q, d, hi);
  for (size_t k = 0; k < 3; ++k)
    foot[k] = y[k].to_double_approx();
  return true;
}

// W evaluated over the parameter box [u0, u1] x [v0, v1] in Arb: nonzero for certain means the
// parametrisation is continuous on every path inside that box.
bool w_nonzero_on(const Poly3& W, const Rational& u0, const Rational& u1, const Rational& v0,
                  const Rational& v1) {
  const long prec = 256;
  Ball U, V, a, s;
  arb_set_fmpq(U.v, u0.raw(), prec);
  arb_set_fmpq(a.v, u1.raw(), prec);
  arb_union(U.v, U.v, a.v, prec);
  arb_set_fmpq(V.v, v0.raw(), prec);
  arb_set_fmpq(a.v, v1.raw(), prec);
  arb_union(V.v, V.v, a.v, prec);
  for (const auto& [e, c] : W.terms()) {
    Ball t, x;
    arb_set_fmpq(t.v, c.raw(), prec);
    arb_pow_ui(x.v, U.v, static_cast<ulong>(e[0]), prec);
    arb_mul(t.v, t.v, x.v, prec);
    arb_pow_ui(x.v, V.v, static_cast<ulong>(e[1]), prec);
    arb_mul(t.v, t.v, x.v, prec);
    arb_add(s.v, s.v, t.v, prec);
  }
  return arb_is_nonzero(s.v) != 0;
}

// Contact proof: two exact image points on a straight parameter segment (W nonzero on it) where
// g has strict opposite signs; the image path between them is continuous, so it meets the zero
// set of g. (u0, v0) is the float proposal near the contact.
bool image_meets(const core::ParametricSurface& p, const Poly3& g, double u0d, double v0d) {
  const Rational u0 = Rational::exact_from_double(u0d), v0 = Rational::exact_from_double(v0d);
  if (auto q = image_point(p, u0, v0))
    if (exact_sign(g, *q) == 0) return true; // an exact common point
  const int dirs[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  for (long e = 40; e >= 4; e -= 6)
    for (const auto& dd : dirs) {
      Rational h(1);
      fmpq_div_2exp(h.raw_mut(), h.raw(), static_cast<ulong>(e));
      const Rational du = h * Rational(dd[0]), dv = h * Rational(dd[1]);
      const auto a = image_point(p, u0 - du, v0 - dv), b = image_point(p, u0 + du, v0 + dv);
      if (!a || !b || exact_sign(g, *a) * exact_sign(g, *b) >= 0) continue;
      const Rational ua = u0 - du, ub = u0 + du, va = v0 - dv, vb = v0 + dv;
      if (w_nonzero_on(p.W, ua < ub ? ua : ub, ua < ub ? ub : ua, va < vb ? va : vb,
                       va < vb ? vb : va))
        return true;
    }
  return false;
}

} // namespace

std::optional<core::Poly3> implicit_polynomial(const core::ParametricSurface& p, int max_degree) {
  for (int d = 1; d <= max_degree; ++d) {
    auto ns = substitution_nullspace(p, d);
    if (ns.size() == 1) {
      // Remove the content so the implicit form reads small.
      core::Integer g(0);
      for (const auto& c : ns[0])
        fmpz_gcd(g.raw_mut(), g.raw(), c.num().raw());
      if (!g.is_zero())
        for (auto& c : ns[0])
          c = c / Rational(g);
      const auto mons = monomials(d);
      Poly3 f;
      for (size_t k = 0; k < mons.size(); ++k)
        if (!ns[0][k].is_zero()) f.add_term(mons[k], ns[0][k]);
      return f;
    }
    if (ns.size() > 1) return std::nullopt; // the image is not a surface (or degenerate)
  }
  return std::nullopt;
}

std::optional<core::QuadricMatrix> implicit_quadric(const core::ParametricSurface& p) {
  const auto f = implicit_polynomial(p, 2);
  if (!f) return std::nullopt;
  return core::QuadricMatrix::from_poly(*f);
}

DistanceResult parametric_distance(const core::ParametricSurface& p, const core::Surface& other,
                                   long digits, bool parametric_first, Mode mode, bool solid) {
  DistanceResult out;
  out.solid = solid;
  out.mode = mode;
  const auto f = implicit_polynomial(p, 6);
  if (!f) {
    out.status = Status::Undecided;
    out.note = "not supported yet: a parametric surface whose implicit equation has degree > 6 "
               "(or whose image is not a surface)";
    return out;
  }
  const core::Surface implicit = f->total_degree() <= 2
                                     ? core::Surface(core::QuadricMatrix::from_poly(*f))
                                     : core::Surface(core::ImplicitSurface{*f});
  if (std::holds_alternative<core::ParametricSurface>(other)) {
    out.status = Status::Undecided;
    out.note = "not supported yet: two parametric surfaces";
    return out;
  }
  // The implicit surface's distance, in the caller's mode and with its solid option: its lower
  // bound is a lower bound here too (the closure of the image lies on the implicit surface);
  // its upper bound is NOT (the image may cover only part of the implicit surface).
  const DistanceResult imp = parametric_first
                                 ? surface_distance(implicit, other, digits, solid, mode)
                                 : surface_distance(other, implicit, digits, solid, mode);
  out = imp;
  out.solid = solid;
  out.mode = mode;
  out.pairs.clear();
  out.ties = Ties::None;
  out.tie_regions.clear(); // they isolate the implicit route's minimizers, not ours
  out.tie_directions = out.tie_lines = false;
  out.minimizers = {};
  out.count_unproven = false;
  // This route's answer; the route that solved the implicit problem is reported beside it.
  out.method = Method::ParametricReduction;
  out.reduced_by = imp.method;
  std::string note = "distance to the closure of the parametrised surface (implicit form " +
                     f->to_string() + " = 0)";

  // The points missed at infinity: the limit of P along every direction, when it is one point.
  const int deg =
      std::max({p.X.total_degree(), p.Y.total_degree(), p.Z.total_degree(), p.W.total_degree()});
  const Poly3 Wd = top(p.W, deg);
  bool point = false;
  Point m;
  std::array<double, 3> md{};
  std::array<Rational, 2> dir{Rational(1), Rational(0)}; // a direction where Wd != 0
  if (!Wd.is_zero()) {
    point = true;
    const Poly3* comps[3] = {&p.X, &p.Y, &p.Z};
    const Poly3::Terms wt = Wd.terms();
    const auto& [e0, w0] = *wt.begin();
    for (size_t i = 0; i < 3; ++i) {
      const Poly3 t = top(*comps[i], deg);
      m[i] = t.coeff(e0[0], e0[1], e0[2]) / w0;
      md[i] = m[i].to_double_approx();
      point = point && t == Wd.scaled(m[i]);
    }
    for (const auto& dd : {std::array<long, 2>{1, 0}, {0, 1}, {1, 1}, {1, 2}})
      if (!Wd.evaluate(Rational(dd[0]), Rational(dd[1]), Rational(0)).is_zero()) {
        dir = {Rational(dd[0]), Rational(dd[1])};
        break;
      }
  }
  if (point)
    note += "; the parametrisation misses (" + m[0].to_string() + ", " + m[1].to_string() + ", " +
            m[2].to_string() + ")";
  else if (Wd.is_zero())
    note += "; limits at infinity are not finite points";
  else
    note += "; the limits at infinity form a curve (not listed)";

  auto finish = [&](const std::string& extra) {
    out.note = note + "; " + extra + (imp.note.empty() ? "" : "; the implicit route: " + imp.note);
    return out;
  };
  // What the implicit answer proves for the closure: its lower bound only (upper +inf, as the
  // implicit upper bound does not bound the closure's distance).
  auto keep_lower_only = [&] {
    out.distance.reset();
    if (imp.distance) {
      Arf inf;
      arf_pos_inf(inf.v);
      out.distance = Enclosure::from_bounds(imp.distance->lower_arf(), inf.v, digits);
    }
  };
  auto undecided = [&](const std::string& why) {
    out.status = Status::Undecided;
    out.minimizers = {};
    out.count_unproven = false;
    out.ties = Ties::None;
    out.pairs.clear();
    out.estimate.reset();
    if (imp.status == Status::Certified || imp.status == Status::Undecided)
      keep_lower_only();
    else
      out.distance.reset();
    return finish(why + (out.distance ? "; the lower bound is the implicit surface's (a "
                                        "certified lower bound for the closure)"
                                      : std::string()));
  };

  if (imp.status == Status::Uncertified) { // Float mode: the implicit surface's float answer
    if (out.distance) keep_lower_only();
    return finish("float answer for the implicit surface; the image was not checked");
  }
  if (imp.status != Status::Certified)
    return undecided("the implicit surface's distance was not certified");
  if (!imp.distance) return undecided("the implicit surface's answer carries no enclosure");
  const auto g = zero_set_polynomial(other);
  if (!g)
    return undecided("no polynomial equation of the other surface to witness an upper bound "
                     "with");
  std::vector<std::array<double, 3>> xs, ys; // the implicit minimizers, parametric side first
  for (const auto& pr : imp.pairs) {
    xs.push_back(parametric_first ? pr[0] : pr[1]);
    ys.push_back(parametric_first ? pr[1] : pr[0]);
  }
  if (xs.empty()) {
    // Solids nesting (no pair listed): take a few image points to test.
    for (const auto& uv : {std::array<double, 2>{0, 0}, {1, 0}, {0, 1}, {-1, 0}, {0, -1}})
      if (auto q = image_point(p, Rational::exact_from_double(uv[0]),
                               Rational::exact_from_double(uv[1]))) {
        xs.push_back(
            {(*q)[0].to_double_approx(), (*q)[1].to_double_approx(), (*q)[2].to_double_approx()});
        ys.push_back(xs.back());
      }
  }

  if (arf_is_zero(imp.distance->upper_arf())) {
    // The implicit surface meets the other one (or, solid, the solids nest): the parametrised
    // surface's distance is 0 only with a proof on the image itself.
    for (size_t i = 0; i < xs.size(); ++i) {
      const auto uv = propose_parameters(p, xs[i]);
      if (image_meets(p, *g, uv[0], uv[1])) {
        out.pairs = {{xs[i], xs[i]}};
        out.distance = Enclosure::zero();
        out.estimate.reset();
        // The contact set of the closure is not counted: the image crosses the other surface,
        // but a parametrisation may collapse the crossing curve to a point.
        out.minimizers = Minimizers::undecided(0);
        out.ties = Ties::None;
        return finish("the image meets the other surface: exact image points on a parameter "
                      "segment (W nonzero on it) on both sides of it");
      }
    }
    if (solid && is_closed_surface(other))
      for (size_t i = 0; i < xs.size(); ++i) {
        const auto uv = propose_parameters(p, xs[i]);
        const auto q =
            image_point(p, Rational::exact_from_double(uv[0]), Rational::exact_from_double(uv[1]));
        if (!q) continue;
        Ball qb[3];
        for (size_t k = 0; k < 3; ++k)
          arb_set_fmpq(qb[k].v, (*q)[k].raw(), 256);
        if (side_of(other, qb) < 0) {
          out.pairs.clear();
          out.distance = Enclosure::zero();
          out.estimate.reset();
          // q is strictly inside the other solid, so are the image points near it (W(u, v) != 0
          // there: P is continuous and, its image a surface, not constant): infinitely many.
          out.minimizers = Minimizers::continuum(Minimizers::Proof::Interval);
          out.ties = Ties::None;
          return finish("solid distance 0: an exact image point lies inside the other solid");
        }
      }
    return undecided("the implicit surface meets (or its solid nests with) the other surface, "
                     "but no image point proves it for the parametrised surface");
  }

  // Positive distance: [implicit lower, witnessed upper]. A witness is an exact image point q
  // (rational parameters proposed by floats) and an exact sign change of the other surface's
  // polynomial on a short segment of a ray from q: |q - y| bounds the distance from above.
  const long bits = bits_for(digits) + 32, prec = bits + 64;
  Ball L, U, d;
  arb_set_arf(L.v, imp.distance->lower_arf());
  arb_pos_inf(U.v);
  size_t witnessed = 0;
  bool via_missed = false;
  for (size_t i = 0; i < xs.size(); ++i) {
    std::vector<Point> cands;
    const auto uv = propose_parameters(p, xs[i]);
    if (auto q =
            image_point(p, Rational::exact_from_double(uv[0]), Rational::exact_from_double(uv[1])))
      cands.push_back(*q);
    // Near the missed point: image points P(2^k dir) tending to it (the proposal is a float
    // hint only; each candidate is checked exactly like the others).
    const bool near_missed =
        point && std::hypot(xs[i][0] - md[0], xs[i][1] - md[1], xs[i][2] - md[2]) <=
                     1e-6 * (1 + std::hypot(md[0], md[1], md[2]));
    if (near_missed)
      for (ulong k = 8; k <= static_cast<ulong>(2 * bits); k *= 2) {
        Rational s(1);
        fmpq_mul_2exp(s.raw_mut(), s.raw(), k);
        if (auto q = image_point(p, s * dir[0], s * dir[1])) cands.push_back(*q);
      }
    Ball best, up;
    arb_pos_inf(best.v);
    std::array<double, 3> bq{}, by{};
    for (size_t c = 0; c < cands.size(); ++c) {
      std::array<double, 3> foot{};
      if (!ray_upper_bound(*g, cands[c], ys[i], bits, up.v, foot)) continue;
      if (arf_cmp(arb_midref(up.v), arb_midref(best.v)) < 0) {
        arb_set(best.v, up.v);
        by = foot;
        for (size_t k = 0; k < 3; ++k)
          bq[k] = cands[c][k].to_double_approx();
      }
    }
    if (!arb_is_finite(best.v)) continue;
    if (arf_cmp(arb_midref(best.v), arb_midref(U.v)) < 0) arb_set(U.v, best.v);
    if (relative_enclosure(d.v, L.v, best.v, digits, prec)) {
      ++witnessed;
      via_missed = via_missed || near_missed;
      out.pairs.push_back(parametric_first ? std::array<std::array<double, 3>, 2>{bq, by}
                                           : std::array<std::array<double, 3>, 2>{by, bq});
    }
  }
  if (witnessed == 0 || !relative_enclosure(d.v, L.v, U.v, digits, prec))
    return undecided("no exact image point witnesses an upper bound within the requested width "
                     "(the implicit surface's minimum may lie outside the image)");
  // The lower bound is the implicit route's (exact arf); the upper bound the witness's,
  // rounded up.
  out.status = Status::Certified;
  out.estimate.reset();
  {
    Arf hi;
    arb_get_ubound_arf(hi.v, U.v, prec);
    out.distance = Enclosure::from_bounds(imp.distance->lower_arf(), hi.v, digits);
  }
  // The count rests on the implicit minimizers having a witness, whose membership in the
  // closure is not proven: a numeric count is marked unproven (finalize reports "undecided");
  // a continuum of implicit minimizers says nothing about how many lie in the closure.
  const bool continuum = imp.minimizers.is_continuum();
  out.minimizers =
      continuum ? Minimizers::undecided(0)
                : Minimizers::count(static_cast<long>(witnessed), Minimizers::Proof::Interval);
  out.count_unproven = !continuum;
  out.ties = Ties::None;
  std::string extra =
      "certified as [lower bound of the implicit surface, |q - y| for an exact image point q and "
      "a point y of the other surface proven by an exact sign change]; minimizers: the implicit "
      "route's minimizers with such a witness within the enclosure (their membership in the "
      "closure is not proven)";
  if (via_missed)
    extra += "; a minimizer appears (float proposal) to be the missed point: image points "
             "tending to it witness the upper bound (the minimum may be attained only in the "
             "closure)";
  if (continuum)
    extra += "; the implicit surface has a continuum of minimizers (how many lie in the closure "
             "is not proven)";
  finish(extra);
  if (!continuum) note_unproven_ties(out, witnessed);
  return out;
}

} // namespace surfcert::certify
