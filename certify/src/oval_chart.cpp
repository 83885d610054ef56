// surfcert::certify::oval_chart: the ovals' points at infinity, read in a chart where the
// curve is compact (see oval_chart.hpp).
#include "surfcert/certify/oval_chart.hpp"

#include "surfcert/algebra/eigen4.hpp"
#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/pencil.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/certify/box_exits.hpp"
#include "surfcert/core/quadric.hpp"

#include <algorithm>
#include <cmath>

namespace surfcert::certify {

using core::Rational;

namespace {

// x^T m x, exactly.
Rational form_at(const core::Mat4& m, const std::array<Rational, 4>& x) {
  Rational s(0);
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      if (x[i].sign() != 0 && x[j].sign() != 0) s += x[i] * m[i][j] * x[j];
  return s;
}

// The shortest dyadic strictly inside (lo, hi) (lo < hi, finite): few bits keep the member's
// entries, and every chart matrix after it, short.
double short_dyadic_between(double lo, double hi) {
  const double mid = 0.5 * (lo + hi);
  for (int k = -8; k < 60; ++k) {
    const double x = std::ldexp(std::nearbyint(std::ldexp(mid, k)), -k);
    if (lo < x && x < hi) return x;
  }
  return mid;
}

// A rational point p with p^T m p of sign `s` (m of inertia (3,1) or (1,3), s the lone sign):
// the eigenvector of the lone eigenvalue in floats, rounded to 20 bits, then unit vectors and
// their sums; each checked exactly (the floats only propose).
std::optional<std::array<Rational, 4>> point_of_sign(const core::Mat4& m, int s) {
  std::vector<std::array<Rational, 4>> tries;
  algebra::Mat4d md{};
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      md[i][j] = m[i][j].to_double_approx();
  std::array<double, 4> w{};
  algebra::Mat4d v{};
  algebra::jacobi4(md, w, v);
  size_t best = 0;
  for (size_t k = 1; k < 4; ++k)
    if (s * w[k] > s * w[best]) best = k;
  double big = 0;
  for (size_t i = 0; i < 4; ++i)
    big = std::max(big, std::fabs(v[i][best]));
  if (std::isfinite(big) && big > 0) {
    std::array<Rational, 4> p;
    for (size_t i = 0; i < 4; ++i)
      p[i] = Rational(static_cast<long>(std::nearbyint(std::ldexp(v[i][best] / big, 20))));
    tries.push_back(p);
  }
  for (size_t i = 0; i < 4; ++i) {
    std::array<Rational, 4> e{Rational(0), Rational(0), Rational(0), Rational(0)};
    e[i] = Rational(1);
    tries.push_back(e);
    for (size_t j = i + 1; j < 4; ++j)
      for (int sj : {1, -1}) {
        auto f = e;
        f[j] = Rational(sj);
        tries.push_back(f);
      }
  }
  for (const auto& p : tries)
    if (form_at(m, p).sign() == s) return p;
  return std::nullopt;
}

} // namespace

std::optional<OvalChart> oval_chart(const core::Mat4& a, const core::Mat4& b, std::string& why) {
  // The members tried: A, B, then l A - B at short dyadics between the float roots of
  // det(l A - B) and beyond them (each member's inertia is then decided exactly).
  std::vector<core::Mat4> members{a, b};
  const algebra::UPolyQ f = algebra::pencil_char_poly(a, b);
  if (f.degree() >= 1) {
    std::vector<double> c;
    for (long i = 0; i <= f.degree(); ++i)
      c.push_back(f.coeff(i).to_double_approx());
    std::vector<double> r;
    for (const auto& z : algebra::approx_complex_roots(c))
      if (std::isfinite(z.real())) r.push_back(z.real());
    std::sort(r.begin(), r.end());
    std::vector<double> at;
    if (!r.empty()) {
      at.push_back(short_dyadic_between(r.front() - 2 - std::fabs(r.front()), r.front()));
      at.push_back(short_dyadic_between(r.back(), r.back() + 2 + std::fabs(r.back())));
    }
    for (size_t i = 0; i + 1 < r.size(); ++i)
      if (r[i] < r[i + 1]) {
        const double gap = r[i + 1] - r[i];
        at.push_back(short_dyadic_between(r[i] + 0.25 * gap, r[i + 1] - 0.25 * gap));
      }
    for (double l : at)
      if (std::isfinite(l))
        members.push_back(core::scaled(a, Rational::exact_from_double(l)) +
                          core::scaled(b, Rational(-1)));
  }
  for (const core::Mat4& m : members) {
    const algebra::Inertia in = algebra::inertia_ldlt(m);
    if (!(in.rank() == 4 && std::min(in.p, in.n) == 1)) continue;
    const int lone = in.p == 1 ? 1 : -1;
    const auto p = point_of_sign(m, lone);
    if (!p) continue;
    // h = M p: on its plane, x^T M x has the sign opposite to `lone` and never vanishes (the
    // M-orthogonal complement of p is definite), so the plane misses the curve.
    std::array<Rational, 4> h;
    for (size_t i = 0; i < 4; ++i) {
      h[i] = Rational(0);
      for (size_t j = 0; j < 4; ++j)
        h[i] += m[i][j] * (*p)[j];
    }
    // The coordinate left out: the largest |h_i| of x, y, z (h_i != 0; h = (0, 0, 0, h_3)
    // would be the plane at infinity, which then misses the curve: nothing to settle).
    size_t k = 3;
    double hk = 0;
    for (size_t i = 0; i < 3; ++i)
      if (h[i].sign() != 0 && std::fabs(h[i].to_double_approx()) >= hk)
        k = i, hk = std::fabs(h[i].to_double_approx());
    if (k == 3) continue;
    const Rational hk_exact = h[k];
    for (auto& e : h)
      e = e / hk_exact;
    std::array<size_t, 2> rest{};
    for (size_t i = 0, n = 0; i < 3; ++i)
      if (i != k) rest[n++] = i;
    // x = P y: x_w = y_0, x_rest0 = y_1, x_rest1 = y_2, x_k = y_3 - h . (the others).
    core::Mat4 pm;
    for (auto& row : pm)
      for (auto& e : row)
        e = Rational(0);
    pm[3][0] = Rational(1);
    pm[rest[0]][1] = Rational(1);
    pm[rest[1]][2] = Rational(1);
    pm[k][0] = -h[3];
    pm[k][1] = -h[rest[0]];
    pm[k][2] = -h[rest[1]];
    pm[k][3] = Rational(1);
    OvalChart out;
    out.a = core::congruence(pm, a);
    out.b = core::congruence(pm, b);
    out.from_chart = pm;
    out.plane = h;
    out.member = m;
    return out;
  }
  why = "no member of the pencil tried has inertia (3,1) or (1,3)";
  return std::nullopt;
}

std::optional<OvalChart> oval_chart_along(const OvalChart& c, const std::array<Rational, 3>& d,
                                          std::array<std::array<Rational, 3>, 3>& r) {
  if (d[1].sign() == 0 && d[2].sign() == 0) return std::nullopt;
  const bool keep2 = abs(d[1]) >= abs(d[2]);
  const size_t o = keep2 ? 2 : 1, m = keep2 ? 1 : 2; // kept, and solved for (d_m != 0)
  for (auto& row : r)
    for (auto& e : row)
      e = Rational(0);
  r[0][0] = Rational(1);
  r[1] = d;
  r[2][o] = Rational(1);
  // The homogeneous inverse: y_0 = y'_0, y_o = y'_2, y_m = (y'_1 - d_0 y'_0 - d_o y'_2) / d_m,
  // y_3 = y'_3.
  core::Mat4 t;
  for (auto& row : t)
    for (auto& e : row)
      e = Rational(0);
  t[0][0] = Rational(1);
  t[o][2] = Rational(1);
  t[m][1] = Rational(1) / d[m];
  t[m][0] = -d[0] / d[m];
  t[m][2] = -d[o] / d[m];
  t[3][3] = Rational(1);
  OvalChart out = c;
  out.a = core::congruence(t, c.a);
  out.b = core::congruence(t, c.b);
  out.from_chart = c.from_chart * t;
  return out;
}

OvalsAtInfinity ovals_at_infinity(const OvalChart& chart, const ProvenLoops& proven, int components,
                                  int points_at_infinity) {
  OvalsAtInfinity out;
  if (proven.count != components || static_cast<int>(proven.boxes.size()) != components) {
    out.reason = std::to_string(proven.count) + " of the " + std::to_string(components) +
                 " components proven in boxes of the chart";
    return out;
  }
  int loops = 0, total = 0;
  for (const RationalBox& box : proven.boxes) {
    int n = 0;
    if (box.lo[0].sign() < 0 && box.hi[0].sign() > 0) {
      // The part of the box with Y_0 <= 0: its faces other than Y_0 = 0 lie on the box's
      // boundary, which the curve misses (proven_loops), so its crossings are the curve's
      // points on Y_0 = 0 inside the box.
      std::array<Rational, 3> hi = box.hi;
      hi[0] = Rational(0);
      const BoxExits ex = box_exits(chart.a, chart.b, box.lo, hi);
      if (!ex.certified) {
        out.reason =
            "the crossings with the old plane at infinity in a box are not certified: " + ex.reason;
        out.crossings.clear();
        return out;
      }
      n = static_cast<int>(ex.points.size());
    }
    out.crossings.push_back(n);
    total += n;
    if (n == 0) ++loops;
  }
  if (total != points_at_infinity) {
    out.reason = "the crossings found in the boxes (" + std::to_string(total) +
                 ") are not the curve's real points at infinity (" +
                 std::to_string(points_at_infinity) + ")";
    out.crossings.clear();
    return out;
  }
  out.loops = loops;
  return out;
}

bool settle_by_oval_chart(AffineTopology& t, const OvalsAtInfinity& o) {
  if (!o.loops || !t.computed || t.readings.size() < 2) return false;
  std::vector<std::pair<int, int>> keep;
  for (const auto& r : t.readings)
    if (r.first == *o.loops) keep.push_back(r);
  if (keep.size() != 1) return false;
  t.loops = keep[0].first;
  t.unbounded_branches = keep[0].second;
  t.undecided.erase(std::remove_if(t.undecided.begin(), t.undecided.end(),
                                   [](const auto& u) {
                                     return u.first == "loops" || u.first == "unbounded_branches";
                                   }),
                    t.undecided.end());
  t.readings = keep;
  t.route = "oval_chart";
  t.loop_boxes.clear();
  t.all_loops_box.reset();
  return true;
}

} // namespace surfcert::certify
