// surfcert::certify::lines_box_exits with algebraic directions (see box_exits.hpp): lines
// p + s d(t*) through a rational point p, t* the root of an irreducible integer polynomial f
// isolated in (lo, hi), d a vector of rational polynomials. Two cones sharing their apex meet
// in four lines through it; when the rational ones are a double line and the other two are
// conjugate over Q(sqrt D), the pair's face crossings are each double on the double line, and
// box_exits could only answer "a multiple crossing" in every box (automatic ones included).
//
// On the face x_k = c the line crosses at s = (c - p_k) / d_k(t*), so each comparison of a
// coordinate q_i with a face bound b reads as the sign at t* of the polynomial
// (p_i - b) d_k(t) + (c - p_k) d_i(t), times the sign of d_k(t*). A polynomial vanishes at t*
// exactly when f divides it (f is irreducible): its remainder by f is zero, decided exactly;
// otherwise its sign comes from Arb on the narrowed bracket (algebra::sign_at_root), and a sign
// not decided there leaves the crossings not certified.
#include "surfcert/certify/box_exits.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/real_roots.hpp"

#include <flint/fmpq_poly.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace surfcert::certify {

namespace {

using algebra::Ball;
using algebra::UPolyQ;
using core::Rational;

UPolyQ as_rational(const algebra::UPolyZ& f) {
  UPolyQ q;
  fmpq_poly_set_fmpz_poly(q.raw_mut(), f.raw());
  return q;
}

// The sign of e at the direction's root: 0 exactly when f divides e; nullopt when Arb did not
// separate a nonzero value from 0.
std::optional<int> sign_at(const UPolyQ& e, const AlgebraicDirection& d, const UPolyQ& fq) {
  if (e.is_zero() || e.rem(fq).is_zero()) return 0;
  const int s = algebra::sign_at_root(e, d.polynomial, d.lo, d.hi);
  if (s == 0) return std::nullopt;
  return s;
}

// e(t) on the ball t.
Ball evaluate(const UPolyQ& e, const Ball& t, long prec) {
  algebra::BallPoly q;
  arb_poly_set_fmpq_poly(q.v, e.raw(), prec);
  Ball v;
  arb_poly_evaluate(v.v, q.v, t.v, prec);
  return v;
}

} // namespace

BoxExits lines_box_exits(const std::array<Rational, 3>& p,
                         const std::vector<std::array<Rational, 3>>& rational_directions,
                         const std::vector<AlgebraicDirection>& algebraic_directions,
                         const std::array<Rational, 3>& lo, const std::array<Rational, 3>& hi) {
  // The rational lines, the flat box and the point on the boundary as before.
  BoxExits out = lines_box_exits(p, rational_directions, lo, hi);
  if (!out.certified) return out;
  auto fail = [&out](const char* why) {
    out.points.clear();
    out.certified = false;
    out.reason = why;
    return out;
  };
  for (const AlgebraicDirection& d : algebraic_directions) {
    if (d.polynomial.degree() < 2) return fail("a line's direction is not given as algebraic");
    const UPolyQ fq = as_rational(d.polynomial);
    // The root's bracket narrowed once, for the crossings' enclosures below.
    Rational tlo = d.lo, thi = d.hi;
    algebra::refine_root_newton(d.polynomial, tlo, thi,
                                (thi - tlo) * Rational::exact_from_double(0x1p-100));
    const long prec = 256;
    Ball t;
    arb_set_fmpq(t.v, ((tlo + thi) * Rational(1, 2)).raw(), prec);
    {
      Ball r;
      arb_set_fmpq(r.v, ((thi - tlo) * Rational(1, 2)).raw(), prec);
      arb_add_error(t.v, r.v);
    }
    for (size_t k = 0; k < 3; ++k) {
      // The sign of d_k at the root, once for the axis's two faces.
      const auto sk = sign_at(d.dir[k], d, fq);
      if (!sk) return fail("a line's direction not decided against a face");
      for (int side = 0; side < 2; ++side) {
        const Rational& c = side ? hi[k] : lo[k];
        if (*sk == 0) {
          if (p[k] == c) return fail("a line of the curve lies in the plane of a face");
          continue; // parallel to the face
        }
        // Where q_i lies against lo_i and hi_i (i != k), each by the sign of a polynomial.
        bool in = true, edge = false, on_face = true;
        for (size_t i = 0; i < 3; ++i) {
          if (i == k) continue;
          for (int bs = 0; bs < 2; ++bs) {
            const Rational& b = bs ? hi[i] : lo[i];
            const UPolyQ e = UPolyQ(p[i] - b) * d.dir[k] + UPolyQ(c - p[k]) * d.dir[i];
            const auto se = sign_at(e, d, fq);
            if (!se) return fail("a line's crossing not decided against a face's edge");
            const int s = *se * *sk; // sign of q_i - b
            if (s == 0) edge = true;
            if (bs == 0) {
              in = in && s > 0;
              on_face = on_face && s >= 0;
            } else {
              in = in && s < 0;
              on_face = on_face && s <= 0;
            }
          }
        }
        if (edge && on_face) return fail("a crossing on an edge of the box");
        if (!in) continue;
        BoxCrossing bc;
        bc.axis = static_cast<int>(k);
        bc.at_max = side == 1;
        const Ball dk = evaluate(d.dir[k], t, prec);
        double radius = 0;
        for (size_t i = 0; i < 3; ++i) {
          if (i == k) {
            bc.approx[i] = c.to_double_approx();
            continue;
          }
          // q_i = p_i + (c - p_k) d_i / d_k on the bracket.
          Ball q = evaluate(d.dir[i], t, prec), s;
          arb_div(q.v, q.v, dk.v, prec);
          arb_set_fmpq(s.v, (c - p[k]).raw(), prec);
          arb_mul(q.v, q.v, s.v, prec);
          arb_set_fmpq(s.v, p[i].raw(), prec);
          arb_add(q.v, q.v, s.v, prec);
          bc.approx[i] = arf_get_d(arb_midref(q.v), ARF_RND_NEAR);
          radius = std::max(radius, mag_get_d(arb_radref(q.v)) +
                                        std::fabs(bc.approx[i]) * 0x1p-53); // midpoint rounded
        }
        bc.radius = radius;
        out.points.push_back(bc);
      }
    }
  }
  return out;
}

} // namespace surfcert::certify
