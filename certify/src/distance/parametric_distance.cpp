#include "surfcert/certify/distance/parametric_distance.hpp"

#include <flint/fmpz_mat.h>

#include <cmath>
#include <map>
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

// Float check: is the point x (approximately) an image P(u, v)? Failing withholds
// certification; passing is a float judgement (a point within ~1e-8 of a partial image passes).
// Gauss-Newton from the best of a grid of starts; relative residual <= 1e-8.
bool in_image(const core::ParametricSurface& p, const std::array<double, 3>& x) {
  auto res = [&](double u, double v, std::array<double, 3>& r) {
    double w = eval_d(p.W, u, v);
    if (w == 0) return false;
    r = {eval_d(p.X, u, v) / w - x[0], eval_d(p.Y, u, v) / w - x[1], eval_d(p.Z, u, v) / w - x[2]};
    return true;
  };
  auto norm = [](const std::array<double, 3>& r) { return std::hypot(r[0], r[1], r[2]); };
  double bu = 0, bv = 0, best = 1e300;
  std::array<double, 3> r{};
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) {
      double u = std::sinh(i / 8.0), v = std::sinh(j / 8.0);
      if (res(u, v, r) && norm(r) < best) best = norm(r), bu = u, bv = v;
    }
  for (int it = 0; it < 100 && best > 0; ++it) {
    const double h = 1e-7 * (1 + std::fabs(bu) + std::fabs(bv));
    std::array<double, 3> r0{}, ru{}, rv{};
    if (!res(bu, bv, r0) || !res(bu + h, bv, ru) || !res(bu, bv + h, rv)) break;
    double J[3][2];
    for (size_t k = 0; k < 3; ++k) {
      J[k][0] = (ru[k] - r0[k]) / h;
      J[k][1] = (rv[k] - r0[k]) / h;
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
    if (std::fabs(det) < 1e-300) break;
    const double du = (c * g0 - b * g1) / det, dv = (a * g1 - b * g0) / det;
    std::array<double, 3> rn{};
    if (!res(bu - du, bv - dv, rn) || norm(rn) >= best) break;
    bu -= du;
    bv -= dv;
    best = norm(rn);
  }
  return best <= 1e-8 * (1 + std::hypot(x[0], x[1], x[2]));
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
                                   long digits, bool parametric_first) {
  DistanceResult out;
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
  out = parametric_first ? surface_distance(implicit, other, digits, false)
                         : surface_distance(other, implicit, digits, false);
  // The points missed at infinity: the limit of P along every direction, when it is one point.
  const int d =
      std::max({p.X.total_degree(), p.Y.total_degree(), p.Z.total_degree(), p.W.total_degree()});
  const Poly3 Wd = top(p.W, d);
  std::string missed;
  std::array<double, 3> m{};
  bool point = false;
  if (!Wd.is_zero()) {
    point = true;
    std::array<Rational, 3> c;
    const Poly3* comps[3] = {&p.X, &p.Y, &p.Z};
    const auto& [e0, w0] = *Wd.terms().begin();
    for (size_t i = 0; i < 3; ++i) {
      const Poly3 t = top(*comps[i], d);
      c[i] = t.coeff(e0[0], e0[1], e0[2]) / w0;
      point = point && t == Wd.scaled(c[i]);
    }
    if (point) {
      missed = "(" + c[0].to_string() + ", " + c[1].to_string() + ", " + c[2].to_string() + ")";
      for (size_t i = 0; i < 3; ++i)
        m[i] = c[i].to_double_approx();
    }
  }
  std::string note =
      "distance to the closure of the parametrised surface (implicit form " + f->to_string() +
      " = 0; minimizers checked against the image by a float search: a minimizer found outside it "
      "withholds certification, one found inside it is a float judgement)";
  if (point) {
    note += "; the parametrisation misses " + missed;
    bool hit = false;
    for (const auto& pr : out.pairs) {
      const auto& s1 = parametric_first ? pr[0] : pr[1];
      hit = hit || std::hypot(s1[0] - m[0], s1[1] - m[1], s1[2] - m[2]) <=
                       1e-9 * (1 + std::hypot(m[0], m[1], m[2]));
    }
    note += hit ? ": a minimizer is that missed point (the minimum is attained only in the "
                  "closure)"
                : " (not a minimizer)";
  }
  // Every minimizer's point must be a missed point or (approximately) an image point; else the
  // minimum may lie on a part of the quadric the parametrisation does not cover.
  if (out.status == Status::Certified && out.pairs.empty()) {
    out.status = Status::Undecided;
    note += "; no minimizer point to check against the image of the parametrisation";
  }
  if (out.status == Status::Certified) {
    for (const auto& pr : out.pairs) {
      const auto& s1 = parametric_first ? pr[0] : pr[1];
      const bool at_missed = point && std::hypot(s1[0] - m[0], s1[1] - m[1], s1[2] - m[2]) <=
                                          1e-9 * (1 + std::hypot(m[0], m[1], m[2]));
      if (!at_missed && !in_image(p, s1)) {
        out.status = Status::Undecided;
        note += "; a minimizer was not found in the image of the parametrisation (it may cover "
                "only part of the quadric)";
        break;
      }
    }
  }
  if (point) {
  } else if (Wd.is_zero()) {
    note += "; limits at infinity are not finite points";
  } else {
    note += "; the limits at infinity form a curve (not listed)";
  }
  out.note = out.note.empty() ? note : out.note + "; " + note;
  return out;
}

} // namespace surfcert::certify
