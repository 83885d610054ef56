#include "surfcert/certify/distance/cylinder_pair.hpp"

#include "surfcert/certify/distance/convex_distance.hpp"

#include <cmath>

namespace surfcert::certify {

using core::Rational;

namespace {

using V3 = std::array<Rational, 3>;

V3 cross(const V3& x, const V3& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}

Rational dot(const V3& x, const V3& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

Rational quad(const std::array<V3, 3>& W, const V3& n) {
  Rational s;
  for (size_t i = 0; i < 3; ++i)
    s += n[i] * dot(W[i], n);
  return s;
}

// The closest points of the lines p + s u and q + t v (u x v != 0), in double.
std::array<std::array<double, 3>, 2> line_pair(const std::array<double, 3>& p,
                                               const std::array<double, 3>& u,
                                               const std::array<double, 3>& q,
                                               const std::array<double, 3>& v) {
  auto d3 = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  };
  const std::array<double, 3> w{p[0] - q[0], p[1] - q[1], p[2] - q[2]};
  const double a = d3(u, u), b = d3(u, v), c = d3(v, v), d = d3(u, w), e = d3(v, w);
  const double den = a * c - b * b, s = (b * e - c * d) / den, t = (a * e - b * d) / den;
  std::array<std::array<double, 3>, 2> out{};
  for (size_t i = 0; i < 3; ++i) {
    out[0][i] = p[i] + s * u[i];
    out[1][i] = q[i] + t * v[i];
  }
  return out;
}

std::array<double, 3> to_d(const V3& x) {
  return {x[0].to_double_approx(), x[1].to_double_approx(), x[2].to_double_approx()};
}

} // namespace

std::optional<DistanceResult> cylinder_pair_distance(const ConvexQuadric& a, const ConvexQuadric& b,
                                                     long digits) {
  if (!a.is_cylinder() || !b.is_cylinder()) return std::nullopt;
  const V3 n = cross(*a.axis, *b.axis);
  if (n[0].is_zero() && n[1].is_zero() && n[2].is_zero()) {
    auto r = separated_convex_distance(a, b, digits);
    if (!r) return std::nullopt;
    r->minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
    r->critical_candidates = 1;
    r->method = Method::ConvexDuality;
    r->note = "disjoint parallel cylinders: certified by a separating direction orthogonal to "
              "the common axis (support-function duality, Arb); a line of closest pairs (one "
              "shown)";
    return r;
  }
  V3 dc;
  for (size_t i = 0; i < 3; ++i)
    dc[i] = b.c[i] - a.c[i];
  const Rational delta = dot(n, dc), wa = quad(a.W, n), wb = quad(b.W, n), nn = dot(n, n);
  // |delta| > sqrt(wa) + sqrt(wb)  <=>  t = delta^2 - wa - wb > 0 and t^2 > 4 wa wb.
  const Rational t = delta * delta - wa - wb;
  if (t.sign() <= 0 || !(t * t > Rational(4) * wa * wb)) return std::nullopt;
  Ball d;
  for (long prec = bits_for(digits + 10);; prec *= 2) {
    Ball D, A, B, N;
    arb_set_fmpq(D.v, core::abs(delta).raw(), prec);
    arb_set_fmpq(A.v, wa.raw(), prec);
    arb_sqrt(A.v, A.v, prec);
    arb_set_fmpq(B.v, wb.raw(), prec);
    arb_sqrt(B.v, B.v, prec);
    arb_sub(D.v, D.v, A.v, prec);
    arb_sub(D.v, D.v, B.v, prec);
    arb_set_fmpq(N.v, nn.raw(), prec);
    arb_sqrt(N.v, N.v, prec);
    arb_div(d.v, D.v, N.v, prec);
    if (arb_is_positive(d.v) &&
        arb_rel_accuracy_bits(d.v) > static_cast<slong>(3.33 * static_cast<double>(digits)) + 8)
      break;
    if (prec > (1L << 22)) return std::nullopt;
  }
  DistanceResult out;
  out.status = Status::Certified;
  set_distance_enclosure(out, d.v, digits);
  out.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
  out.critical_candidates = 1;
  out.method = Method::CylinderClosedForm;
  out.note = "disjoint crossed cylinders: the only direction admissible for both support "
             "functions is the common normal of the axes; d = (|n.(c_B - c_A)| - sqrt(n^T W_A n) "
             "- sqrt(n^T W_B n)) / |n| (exact sign decision, Arb); unique closest pair on the "
             "common perpendicular of the two support lines";
  // Support lines: c_A + W_A m / sqrt(m^T W_A m) along a (m = sign(delta) n towards B), and
  // c_B - W_B m / sqrt(...) along b.
  const double sg = delta.sign() > 0 ? 1.0 : -1.0, sa = std::sqrt(wa.to_double_approx()),
               sb = std::sqrt(wb.to_double_approx());
  std::array<double, 3> p{}, q{};
  for (size_t i = 0; i < 3; ++i) {
    p[i] = a.c[i].to_double_approx() + sg * dot(a.W[i], n).to_double_approx() / sa;
    q[i] = b.c[i].to_double_approx() - sg * dot(b.W[i], n).to_double_approx() / sb;
  }
  out.pairs.push_back(line_pair(p, to_d(*a.axis), q, to_d(*b.axis)));
  return out;
}

} // namespace surfcert::certify
