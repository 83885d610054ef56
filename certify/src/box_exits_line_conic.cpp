// line_conic_crossings: see box_exits_line_conic.hpp.
#include "box_exits_line_conic.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/inertia.hpp"

#include <algorithm>

namespace surfcert::certify::detail {

namespace {

using algebra::QuadraticNumber;
using core::Integer;
using core::Rational;
using V3 = std::array<Rational, 3>;

// A 128-bit enclosure of a + b sqrt(d).
algebra::Ball enclose(const QuadraticNumber& q) {
  constexpr long prec = 128;
  algebra::Ball x, r;
  arb_set_fmpq(x.v, q.a.raw(), prec);
  if (!q.b.is_zero() && !q.d.is_zero()) {
    arb_set_fmpz(r.v, q.d.raw());
    arb_sqrt(r.v, r.v, prec);
    algebra::Ball b;
    arb_set_fmpq(b.v, q.b.raw(), prec);
    arb_addmul(x.v, r.v, b.v, prec);
  }
  return x;
}

// The sign of x - c: from the enclosure bx of x when it decides (a ball of x - c that
// excludes 0 has the exact sign), else exactly (x on the face's edge, or within 2^-128 of it).
int sign_minus(const QuadraticNumber& x, const algebra::Ball& bx, const Rational& c) {
  constexpr long prec = 128;
  algebra::Ball d;
  arb_set_fmpq(d.v, c.raw(), prec);
  arb_sub(d.v, bx.v, d.v, prec);
  if (arb_is_positive(d.v)) return 1;
  if (arb_is_negative(d.v)) return -1;
  return QuadraticNumber{x.a - c, x.b, x.d}.sign();
}

} // namespace

LineConic line_conic_crossings(const FaceForm& line, const FaceForm& conic, const Rational& u_lo,
                               const Rational& u_hi, const Rational& v_lo, const Rational& v_hi,
                               std::vector<FacePoint>& out) {
  // The line 2 l_u u + 2 l_v v + l_1 = 0 as p + t d, p = (pu, pv, 1), d = (du, dv, 0).
  const Rational &lu = line[0][2], &lv = line[1][2], &l1 = line[2][2];
  V3 p, d;
  if (!lv.is_zero()) { // v = -(2 l_u t + l_1) / (2 l_v), u = t
    p = {Rational(0), -l1 / (Rational(2) * lv), Rational(1)};
    d = {Rational(1), -lu / lv, Rational(0)};
  } else { // u = -l_1 / (2 l_u), v = t
    p = {-l1 / (Rational(2) * lu), Rational(0), Rational(1)};
    d = {Rational(0), Rational(1), Rational(0)};
  }
  // The conic along the line: A t^2 + 2 B t + C.
  // (The conic restricted to span(d, p) at once: its common denominator found once.)
  const auto dp = algebra::restrict_form(conic, std::array<V3, 2>{d, p});
  const Rational &a2 = dp[0][0], &b1 = dp[0][1], &c0 = dp[1][1];
  // The roots as t = ra + rb sqrt(D); `simple` false for a double root.
  std::vector<QuadraticNumber> roots;
  bool simple = true;
  if (a2.is_zero()) {
    if (b1.is_zero()) {
      if (c0.is_zero()) return LineConic::Component;
      return LineConic::Complete; // no common affine point
    }
    roots.push_back({-c0 / (Rational(2) * b1), Rational(0), Integer(0)});
  } else {
    const Rational disc = b1 * b1 - a2 * c0; // (2B)^2 - 4AC over 4
    if (disc.sign() < 0) return LineConic::Complete;
    if (disc.is_zero()) {
      simple = false;
      roots.push_back({-b1 / a2, Rational(0), Integer(0)});
    } else {
      // sqrt(n / m) = sqrt(n m) / m: t = (-B +- sqrt(n m) / m) / A.
      const Integer nm = disc.num() * disc.den();
      const Rational s = Rational(1) / (Rational(disc.den()) * a2);
      roots.push_back({-b1 / a2, s, nm});
      roots.push_back({-b1 / a2, Rational(0) - s, nm});
    }
  }
  for (const QuadraticNumber& t : roots) {
    // u = pu + du t, v = pv + dv t: exact numbers of the same field.
    const QuadraticNumber u{p[0] + d[0] * t.a, d[0] * t.b, t.d};
    const QuadraticNumber v{p[1] + d[1] * t.a, d[1] * t.b, t.d};
    // The enclosures first (the reported point's): they decide most of the four signs (exact
    // signs in Q(sqrt D) were ~35% of this call).
    const algebra::Ball bu = enclose(u), bv = enclose(v);
    const int su0 = sign_minus(u, bu, u_lo), su1 = sign_minus(u, bu, u_hi);
    const int sv0 = sign_minus(v, bv, v_lo), sv1 = sign_minus(v, bv, v_hi);
    const bool outside = su0 < 0 || su1 > 0 || sv0 < 0 || sv1 > 0;
    if (outside) continue; // not on this face (a tangency there touches no face point)
    if (!simple) return LineConic::Tangent;
    if (su0 == 0 || su1 == 0 || sv0 == 0 || sv1 == 0) return LineConic::Edge;
    FacePoint fp;
    fp.u = arf_get_d(arb_midref(bu.v), ARF_RND_NEAR);
    fp.v = arf_get_d(arb_midref(bv.v), ARF_RND_NEAR);
    fp.radius = std::max(mag_get_d(arb_radref(bu.v)), mag_get_d(arb_radref(bv.v)));
    out.push_back(fp);
  }
  return LineConic::Complete;
}

} // namespace surfcert::certify::detail
