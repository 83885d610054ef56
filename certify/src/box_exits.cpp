// box_exits: exact crossings of the curve with the faces of a box (see box_exits.hpp).
#include "surfcert/certify/box_exits.hpp"

#include "box_exits_double_line.hpp"
#include "box_exits_filter.hpp"
#include "box_exits_line_conic.hpp"

#include "surfcert/certify/conic_pair.hpp"
#include "surfcert/certify/enclosure.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/real_roots.hpp"

#include <CGAL/FPU.h>
#include <flint/fmpz_poly.h>
#include <flint/fmpz_poly_factor.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace surfcert::certify {

namespace {

using algebra::Ball;
using algebra::UPolyQ;
using algebra::UPolyZ;
using core::Rational;
using M3 = std::array<std::array<Rational, 3>, 3>;
using V3 = std::array<Rational, 3>;

bool is_zero(const M3& m) {
  for (const auto& row : m)
    for (const auto& x : row)
      if (!x.is_zero()) return false;
  return true;
}

// No quadratic part: a line of the face (or a constant).
bool linear(const M3& m) {
  return m[0][0].is_zero() && m[0][1].is_zero() && m[1][1].is_zero();
}

// One face in one chart: R(x) and the first subresultant s11(x) y + s10(x) (conic_pair.hpp).
struct FaceChart {
  std::array<V3, 3> t; ///< columns: (u, v, 1) = x t[0] + y t[1] + t[2]
  UPolyQ r;
  UPolyZ rz; ///< R's square-free part (R's real roots, all simple)
  UPolyQ s11, s10;
};

enum class ChartOutcome { Ok, SharedComponent, Failed };

// The first chart (conic_charts()) where every real root of R is simple.
ChartOutcome face_chart(const M3& ca, const M3& cb, FaceChart& out) {
  for (size_t n = 0; n < conic_charts().size(); ++n) {
    const auto cr = conic_resultant(ca, cb, n);
    if (!cr) continue;
    // With a2 != 0 constant, r == 0 exactly when the conics share a component.
    if (cr->r.is_zero()) return ChartOutcome::SharedComponent;
    UPolyZ rz = cr->r.primitive_integer();
    if (rz.degree() >= 1 && !fmpz_poly_is_squarefree(rz.raw())) {
      // Multiple non-real roots are harmless (complex points, e.g. of a double component
      // that misses the face); a multiple real root is not read: another chart.
      UPolyZ g;
      fmpz_poly_gcd(g.raw_mut(), rz.raw(), rz.derivative().raw());
      if (algebra::has_real_root(g)) continue;
      fmpz_poly_div(rz.raw_mut(), rz.raw(), g.raw());
    }
    out = FaceChart{cr->t, cr->r, rz, cr->s11, cr->s10};
    return ChartOutcome::Ok;
  }
  return ChartOutcome::Failed;
}

// The form restricted to the face x_k = c in the coordinates (u, v, 1) = (x_i, x_j, 1):
// restrict_form(m, T) for T's columns e_i, e_j, c e_k + e_w, written out (the same exact
// entries without the products by T's zeros).
M3 face_form(const core::Mat4& m, size_t i, size_t j, size_t k, const Rational& c) {
  M3 r;
  r[0][0] = m[i][i];
  r[0][1] = r[1][0] = m[i][j];
  r[1][1] = m[j][j];
  r[0][2] = r[2][0] = m[i][k] * c + m[i][3];
  r[1][2] = r[2][1] = m[j][k] * c + m[j][3];
  r[2][2] = (m[k][k] * c + m[k][3] + m[3][k]) * c + m[3][3];
  return r;
}

Ball ball_of(const Rational& q, long prec) {
  Ball b;
  arb_set_fmpq(b.v, q.raw(), prec);
  return b;
}

Ball eval(const UPolyQ& p, const Ball& x, long prec) {
  Ball s;
  for (long i = p.degree(); i >= 0; --i) {
    arb_mul(s.v, s.v, x.v, prec);
    Ball c = ball_of(p.coeff(i), prec);
    arb_add(s.v, s.v, c.v, prec);
  }
  return s;
}

enum class Where { Inside, Outside, Unknown };

// Where v lies against the open interval (lo, hi).
Where against(const Ball& v, const Rational& lo, const Rational& hi, long prec) {
  const Ball l = ball_of(lo, prec), h = ball_of(hi, prec);
  if (arb_lt(v.v, l.v) || arb_gt(v.v, h.v)) return Where::Outside;
  if (arb_gt(v.v, l.v) && arb_lt(v.v, h.v)) return Where::Inside;
  return Where::Unknown;
}

// The crossings found on the face x_k = c (face coordinates u = x_i, v = x_j), appended.
void add_face_points(BoxExits& out, int k, bool at_max, size_t i, size_t j, const Rational& c,
                     const std::vector<detail::FacePoint>& pts) {
  for (const auto& fp : pts) {
    BoxCrossing bc;
    bc.axis = k;
    bc.at_max = at_max;
    bc.approx[static_cast<size_t>(k)] = c.to_double_approx();
    bc.approx[i] = fp.u;
    bc.approx[j] = fp.v;
    bc.radius = fp.radius;
    out.points.push_back(bc);
  }
}

// A box with lo >= hi in some coordinate: not certified, with the reason (its crossings would
// be refined towards a width of 0 without end). Nullopt for a proper box.
std::optional<BoxExits> flat_box(const std::array<Rational, 3>& lo,
                                 const std::array<Rational, 3>& hi) {
  for (size_t k = 0; k < 3; ++k)
    if (!(lo[k] < hi[k])) {
      BoxExits out;
      out.reason = "the box is flat or empty along axis " + std::to_string(k) + " (min >= max)";
      return out;
    }
  return std::nullopt;
}

} // namespace

BoxExits box_exits(const core::Mat4& a_in, const core::Mat4& b_in,
                   const std::array<Rational, 3>& lo, const std::array<Rational, 3>& hi,
                   bool interval_filter) {
  // Integer multiples (the same curve): the face forms and the crossings' polynomials then
  // have the box's dyadic denominators only, and their products skip most gcds (on a pair
  // posed in doubles this was ~30% of an intersect, in gcds of ~150-digit denominators).
  if (auto flat = flat_box(lo, hi)) return std::move(*flat);
  const core::Mat4 a = core::integer_multiple(a_in), b = core::integer_multiple(b_in);
  if (auto dl = detail::double_line_exits(a, b, lo, hi)) return std::move(*dl);
  BoxExits out;
  Rational scale;
  for (size_t k = 0; k < 3; ++k)
    if (hi[k] - lo[k] > scale) scale = hi[k] - lo[k];
  // The pair and the box in intervals, once: a face whose two conics (neither a line of the
  // face) the interval filter proves apart from these needs no exact face form at all (most
  // faces; the exact forms were ~14% of this call). Its enclosures contain the exact forms'
  // (inclusion-isotone operations), so every cell it excludes the filter on the exact forms
  // excludes too: when it proves a face, so would the exact forms' filter; when it does not,
  // that filter runs as before. Either way the same answer.
  IMat4 ia, ib;
  std::array<Interval, 3> ilo, ihi;
  {
    CGAL::Protect_FPU_rounding<true> guard;
    for (size_t r = 0; r < 4; ++r)
      for (size_t s = 0; s < 4; ++s) {
        ia[r][s] = enclose(a[r][s]);
        ib[r][s] = enclose(b[r][s]);
      }
    for (size_t k = 0; k < 3; ++k) {
      ilo[k] = enclose(lo[k]);
      ihi[k] = enclose(hi[k]);
    }
  }
  // No quadratic part on the face x_k (face_form's upper-left block, read off the matrix).
  auto linear_on = [](const core::Mat4& m, size_t i, size_t j) {
    return m[i][i].is_zero() && m[i][j].is_zero() && m[j][j].is_zero();
  };
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      const size_t ku = static_cast<size_t>(k);
      const size_t i = (ku + 1) % 3, j = (ku + 2) % 3;
      const Rational& c = side ? hi[ku] : lo[ku];
      if (interval_filter && !linear_on(a, i, j) && !linear_on(b, i, j)) {
        // The face's crossings proved in interval arithmetic (box_exits_filter.hpp): none on
        // most faces, else each a Krawczyk-proved simple root inside the face (the exact
        // resultant, root isolation and Arb refinement below were ~40% of a cone-cone pair).
        std::optional<std::vector<detail::FacePoint>> pts;
        {
          CGAL::Protect_FPU_rounding<true> guard;
          const Interval& ic = side ? ihi[ku] : ilo[ku];
          pts =
              detail::face_crossings(detail::IConic(ia, i, j, ku, ic),
                                     detail::IConic(ib, i, j, ku, ic), lo[i], hi[i], lo[j], hi[j]);
        }
        if (pts) {
          if (!pts->empty()) ++out.filtered_faces;
          add_face_points(out, k, side == 1, i, j, c, *pts);
          continue;
        }
      } else if (interval_filter && linear_on(a, i, j) != linear_on(b, i, j)) {
        // A plane's section (a line of the face) against a conic: the quadratic along the
        // line in intervals (the exact line_conic_crossings below, in Q(sqrt D) and Arb, was
        // ~30% of a cone-plane pair).
        std::optional<std::vector<detail::FacePoint>> pts;
        {
          CGAL::Protect_FPU_rounding<true> guard;
          const Interval& ic = side ? ihi[ku] : ilo[ku];
          const detail::IConic fa(ia, i, j, ku, ic), fb(ib, i, j, ku, ic);
          const bool a_line = linear_on(a, i, j);
          pts = detail::line_face_crossings(a_line ? fa : fb, a_line ? fb : fa, lo[i], hi[i], lo[j],
                                            hi[j]);
        }
        if (pts) {
          if (!pts->empty()) ++out.filtered_faces;
          add_face_points(out, k, side == 1, i, j, c, *pts);
          continue;
        }
      }
      // (u, v, 1) -> (x, y, z, w): u along axis i, v along axis j, x_k = c.
      const M3 ca = face_form(a, i, j, ku, c), cb = face_form(b, i, j, ku, c);
      const std::string name =
          std::string(side ? "max" : "min") + " face of axis " + std::to_string(k);
      if (is_zero(ca) || is_zero(cb)) {
        out.reason = "the " + name + " lies on a quadric";
        return out;
      }
      if (linear(ca) && linear(cb)) {
        // Two planes: two lines of the face, one common point (rational) or none.
        auto constant = [](const M3& m) { return m[0][2].is_zero() && m[1][2].is_zero(); };
        if (constant(ca) || constant(cb)) continue; // a face parallel to a plane: no point
        const Rational det = ca[0][2] * cb[1][2] - ca[1][2] * cb[0][2];
        if (det.is_zero()) {
          const bool same = (ca[0][2] * cb[2][2] - ca[2][2] * cb[0][2]).is_zero() &&
                            (ca[1][2] * cb[2][2] - ca[2][2] * cb[1][2]).is_zero();
          if (same) {
            out.reason = "the curve has a component in the plane of the " + name;
            return out;
          }
          continue;
        }
        // 2 ca[0][2] u + 2 ca[1][2] v + ca[2][2] = 0, and the same for cb.
        const Rational u = (ca[1][2] * cb[2][2] - ca[2][2] * cb[1][2]) / (Rational(2) * det);
        const Rational v = (ca[2][2] * cb[0][2] - ca[0][2] * cb[2][2]) / (Rational(2) * det);
        if (u == lo[i] || u == hi[i] || v == lo[j] || v == hi[j]) {
          out.points.clear();
          out.reason = "a crossing on an edge of the box on the " + name;
          return out;
        }
        if (lo[i] < u && u < hi[i] && lo[j] < v && v < hi[j]) {
          BoxCrossing bc;
          bc.axis = k;
          bc.at_max = side == 1;
          bc.approx[ku] = c.to_double_approx();
          bc.approx[i] = u.to_double_approx();
          bc.approx[j] = v.to_double_approx();
          out.points.push_back(bc);
        }
        continue;
      }
      if (linear(ca) || linear(cb)) {
        // One form is a line of the face (a plane's section; or a quadric such as a parabolic
        // cylinder met along its rulings): the crossings in closed form.
        const M3& ln = linear(ca) ? ca : cb;
        const M3& cn = linear(ca) ? cb : ca;
        if (ln[0][2].is_zero() && ln[1][2].is_zero()) continue; // a nonzero constant: no point
        std::vector<detail::FacePoint> pts;
        switch (detail::line_conic_crossings(ln, cn, lo[i], hi[i], lo[j], hi[j], pts)) {
        case detail::LineConic::Complete:
          break;
        case detail::LineConic::Component:
          out.points.clear();
          out.reason = "the curve has a component in the plane of the " + name;
          return out;
        case detail::LineConic::Tangent:
          out.points.clear();
          out.reason = "a multiple crossing on the " + name + " (tangency)";
          return out;
        case detail::LineConic::Edge:
          out.points.clear();
          out.reason = "a crossing on an edge of the box on the " + name;
          return out;
        }
        add_face_points(out, k, side == 1, i, j, c, pts);
        continue;
      }
      // The float filter first: a face the curve provably misses needs no exact work (most
      // faces: every face of a box around bounded loops).
      {
        CGAL::Protect_FPU_rounding<true> guard; // IConic encloses with rounding upwards
        if (detail::no_common_point(detail::IConic(ca), detail::IConic(cb), lo[i], hi[i], lo[j],
                                    hi[j], 256))
          continue;
      }
      FaceChart fc;
      switch (face_chart(ca, cb, fc)) {
      case ChartOutcome::SharedComponent:
        out.reason = "the curve has a component in the plane of the " + name;
        return out;
      case ChartOutcome::Failed:
        out.reason = "a multiple crossing on the " + name +
                     " (tangency, singular point or components meeting there)";
        return out;
      case ChartOutcome::Ok:
        break;
      }
      if (fc.r.degree() < 1) continue; // no common affine point on this face
      const UPolyZ& rz = fc.rz;
      const algebra::RootSeparation sep = algebra::isolate_real_roots(rz);
      // The crossing's face coordinates (u, v) from an isolating interval of x narrowed to
      // 2^-bits of the box (nullopt while s11 is not proved nonzero there).
      auto enclose = [&](Rational& l, Rational& h,
                         long bits) -> std::optional<std::array<Ball, 2>> {
        algebra::refine_root_newton(rz, l, h,
                                    scale * Rational::exact_from_double(std::ldexp(1.0, -bits)));
        const long prec = bits + 64;
        Ball x = ball_of((l + h) * Rational(1, 2), prec);
        if (l != h) {
          Ball rad = ball_of((h - l) * Rational(1, 2), prec);
          arb_add_error(x.v, rad.v);
        }
        const Ball s11 = eval(fc.s11, x, prec);
        if (arb_contains_zero(s11.v)) return std::nullopt;
        Ball y = eval(fc.s10, x, prec);
        arb_div(y.v, y.v, s11.v, prec);
        arb_neg(y.v, y.v);
        std::array<Ball, 2> uv;
        for (size_t d = 0; d < 2; ++d) {
          Ball tx = ball_of(fc.t[0][d], prec), ty = ball_of(fc.t[1][d], prec);
          arb_mul(tx.v, tx.v, x.v, prec);
          arb_addmul(tx.v, ty.v, y.v, prec);
          uv[d] = tx;
        }
        return uv;
      };
      for (size_t r = 0; r + 1 < sep.separators.size(); ++r) {
        Rational l = sep.separators[r], h = sep.separators[r + 1];
        Where where = Where::Unknown;
        BoxCrossing bc;
        // The first try narrows to 2^-80 of the box, the width of the reported point (one
        // refinement, not a coarse one to decide and a second to report: Newton's last steps
        // cost little against a call); wider tries when an end is still too close to call.
        std::optional<std::array<Ball, 2>> uv;
        long used = 0; // the bits of the enclosure that decided
        for (long bits : {80L, 120L, 200L}) {
          used = bits;
          uv = enclose(l, h, bits);
          if (!uv) continue;
          const long prec = bits + 64;
          const Where wu = against((*uv)[0], lo[i], hi[i], prec);
          const Where wv = against((*uv)[1], lo[j], hi[j], prec);
          if (wu == Where::Outside || wv == Where::Outside) {
            where = Where::Outside;
            break;
          }
          if (wu == Where::Inside && wv == Where::Inside) {
            where = Where::Inside;
            break;
          }
        }
        if (where == Where::Inside) {
          // The reported point: an enclosure of the crossing within 2^-80 of the box. The
          // bits above narrow the chart's x; the face coordinates follow through
          // y = -s10(x) / s11(x), which near a tangency (s11 small: two crossings 1e-15 apart)
          // is wider by far (helper-27: points 1e-6 off at a face 2^-100 from tangent):
          // narrowed further until they are, or s11 is not proved nonzero any more.
          const double want = 0x1p-80 * scale.to_double_approx();
          auto radius = [](const std::array<Ball, 2>& e) {
            return std::max(mag_get_d(arb_radref(e[0].v)), mag_get_d(arb_radref(e[1].v)));
          };
          while (!(radius(*uv) <= want) && used < 2000) {
            used += used;
            auto finer = enclose(l, h, used);
            if (!finer) break;
            uv = std::move(finer);
          }
          bc.axis = k;
          bc.at_max = side == 1;
          bc.approx[ku] = c.to_double_approx();
          bc.approx[i] = arf_get_d(arb_midref((*uv)[0].v), ARF_RND_NEAR);
          bc.approx[j] = arf_get_d(arb_midref((*uv)[1].v), ARF_RND_NEAR);
          bc.radius = radius(*uv);
        }
        if (where == Where::Unknown) {
          out.points.clear();
          out.reason = "a crossing on an edge of the box (or within 2^-200 of one) on the " + name;
          return out;
        }
        if (where == Where::Inside) out.points.push_back(bc);
      }
    }
  out.certified = true;
  return out;
}

BoxExits lines_box_exits(const std::array<Rational, 3>& p, const std::vector<V3>& directions,
                         const std::array<Rational, 3>& lo, const std::array<Rational, 3>& hi) {
  if (auto flat = flat_box(lo, hi)) return std::move(*flat);
  BoxExits out;
  bool within = true, inside = true;
  for (size_t k = 0; k < 3; ++k) {
    within = within && lo[k] <= p[k] && p[k] <= hi[k];
    inside = inside && lo[k] < p[k] && p[k] < hi[k];
  }
  if (within && !inside) {
    out.reason = "the lines meet on the boundary of the box";
    return out;
  }
  for (const V3& d : directions)
    for (int k = 0; k < 3; ++k)
      for (int side = 0; side < 2; ++side) {
        const size_t ku = static_cast<size_t>(k);
        const Rational& c = side ? hi[ku] : lo[ku];
        if (d[ku].is_zero()) {
          if (p[ku] == c) {
            out.points.clear();
            out.reason = "a line of the curve lies in the plane of a face";
            return out;
          }
          continue;
        }
        const Rational t = (c - p[ku]) / d[ku];
        V3 q;
        for (size_t i = 0; i < 3; ++i)
          q[i] = i == ku ? c : p[i] + t * d[i];
        bool in = true, edge = false;
        for (size_t i = 0; i < 3; ++i) {
          if (i == ku) continue;
          if (q[i] == lo[i] || q[i] == hi[i]) edge = true;
          in = in && lo[i] < q[i] && q[i] < hi[i];
        }
        if (edge) {
          bool on_face = true;
          for (size_t i = 0; i < 3; ++i)
            on_face = on_face && lo[i] <= q[i] && q[i] <= hi[i];
          if (on_face) {
            out.points.clear();
            out.reason = "a crossing on an edge of the box";
            return out;
          }
        }
        if (!in) continue;
        BoxCrossing bc;
        bc.axis = k;
        bc.at_max = side == 1;
        for (size_t i = 0; i < 3; ++i)
          bc.approx[i] = q[i].to_double_approx();
        out.points.push_back(bc);
      }
  out.certified = true;
  return out;
}

} // namespace surfcert::certify
