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

// The diagonal frame Y = F Z (F = [[diag(2^k), c], [0, 1]], c dyadic) that brings the ellipsoid
// e (a chart member: 3x3 block definite up to sign) near the unit cube around the origin; its
// centre and extents in floats (they only choose F; F is exact). nullopt when the floats fail.
std::optional<core::Mat4> unit_frame(const core::Mat4& e) {
  double q[3][3], bv[3];
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j)
      q[i][j] = e[i][j].to_double_approx();
    bv[i] = e[i][3].to_double_approx();
  }
  const double c33 = e[3][3].to_double_approx();
  // Q^-1 by cofactors (3x3).
  const double det = q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) -
                     q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
                     q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
  if (!std::isfinite(det) || det == 0) return std::nullopt;
  double inv[3][3];
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      const size_t r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      inv[i][j] = (q[r0][c0] * q[r1][c1] - q[r0][c1] * q[r1][c0]) / det;
    }
  double centre[3];
  for (size_t i = 0; i < 3; ++i)
    centre[i] = -(inv[i][0] * bv[0] + inv[i][1] * bv[1] + inv[i][2] * bv[2]);
  // The ellipsoid (x - centre)^T Q (x - centre) = r, r = centre^T Q centre - c33; its
  // half-extent along axis i is sqrt(r (Q^-1)_ii).
  double r = -c33;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      r += centre[i] * q[i][j] * centre[j];
  core::Mat4 f;
  for (auto& row : f)
    for (auto& x : row)
      x = Rational(0);
  for (size_t i = 0; i < 3; ++i) {
    const double ext2 = r * inv[i][i];
    if (!(ext2 > 0) || !std::isfinite(ext2) || !std::isfinite(centre[i])) return std::nullopt;
    const int k = std::ilogb(std::sqrt(ext2));
    f[i][i] = Rational::exact_from_double(std::ldexp(1.0, k));
    // The centre rounded to a multiple of 2^(k - 20): short, and within 2^-20 of an extent.
    f[i][3] = Rational::exact_from_double(
        std::ldexp(std::nearbyint(std::ldexp(centre[i], 20 - k)), k - 20));
  }
  f[3][3] = Rational(1);
  return f;
}

} // namespace

namespace {

// Steps 1 and 2 in the coordinates given.
std::optional<OvalChart> chart_of(const core::Mat4& a, const core::Mat4& b, std::string& why) {
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
    // The member in the chart is an ellipsoid (it misses the chart's plane at infinity) that
    // holds the curve; each chart axis is moved to its centre and scaled by a power of two to
    // about its half-extent (Y_i = 2^k_i Z_i + c_i, c_i dyadic: exact), so the tracer sees a
    // curve of unit size in every direction (a pair scaled by 2^-20 gave a chart curve 1e-6
    // across in two axes and 1 in the third: nothing traced). The old plane at infinity
    // Y_0 = 0 becomes Z_0 = -c_0 / 2^k_0.
    core::Mat4 pm2 = pm;
    if (const auto frame = unit_frame(core::congruence(pm, m))) pm2 = pm * *frame;
    OvalChart out;
    out.a = core::congruence(pm2, a);
    out.b = core::congruence(pm2, b);
    out.from_chart = pm2;
    out.plane = h;
    out.member = m;
    // Y_0 = sum_j frame[0][j] Z_j with frame[0] = (2^k_0, 0, 0, c_0): Y_0 = 0 at Z_0 = -c_0/2^k_0.
    out.infinity_at = pm2[3][0].sign() != 0 ? -pm2[3][3] / pm2[3][0] : Rational(0);
    return out;
  }
  why = "no member of the pencil tried has inertia (3,1) or (1,3)";
  return std::nullopt;
}

} // namespace

std::optional<OvalChart> oval_chart(const core::Mat4& a, const core::Mat4& b, std::string& why,
                                    const ChartFrame* frame) {
  if (!frame || !(frame->size > 0) || !std::isfinite(frame->size)) return chart_of(a, b, why);
  // x = F x0, F = [[2^k I, c], [0, 1]]: the pair at about unit size around the origin.
  const int k = std::ilogb(frame->size);
  core::Mat4 f = core::identity4(), finv = core::identity4();
  const Rational s = Rational::exact_from_double(std::ldexp(1.0, k));
  const Rational sinv = Rational::exact_from_double(std::ldexp(1.0, -k));
  for (size_t i = 0; i < 3; ++i) {
    if (!std::isfinite(frame->centre[i])) return chart_of(a, b, why);
    const Rational c = Rational::exact_from_double(
        std::ldexp(std::nearbyint(std::ldexp(frame->centre[i], 30 - k)), k - 30));
    f[i][i] = s;
    f[i][3] = c;
    finv[i][i] = sinv;
    finv[i][3] = -c * sinv;
  }
  auto out = chart_of(core::congruence(f, a), core::congruence(f, b), why);
  if (!out) return out;
  out->from_chart = f * out->from_chart;
  std::array<Rational, 4> h;
  for (size_t j = 0; j < 4; ++j) {
    h[j] = Rational(0);
    for (size_t i = 0; i < 4; ++i)
      h[j] += finv[i][j] * out->plane[i];
  }
  out->plane = h;
  out->member = core::congruence(finv, out->member);
  return out;
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
    if (box.lo[0] < chart.infinity_at && chart.infinity_at < box.hi[0]) {
      // The part of the box with Y_0 <= 0: its faces other than Y_0 = 0 lie on the box's
      // boundary, which the curve misses (proven_loops), so its crossings are the curve's
      // points on Y_0 = 0 inside the box.
      std::array<Rational, 3> hi = box.hi;
      hi[0] = chart.infinity_at;
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
  keep_reading(t, keep[0], "oval_chart");
  return true;
}

} // namespace surfcert::certify
