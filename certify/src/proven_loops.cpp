// surfcert::certify::proven_loops: loops proven to lie wholly inside given boxes (see
// proven_loops.hpp).
#include "surfcert/certify/proven_loops.hpp"

#include "surfcert/certify/box_exits.hpp"
#include "surfcert/certify/inner_loops.hpp"

#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/algebra/real_roots.hpp"

#include <flint/fmpz_poly.h>

#include <cmath>

#include <algorithm>
#include <utility>

namespace surfcert::certify {

using core::Rational;

namespace {

bool disjoint(const RationalBox& p, const RationalBox& q) {
  for (size_t k = 0; k < 3; ++k)
    if (p.hi[k] < q.lo[k] || q.hi[k] < p.lo[k]) return true;
  return false;
}

} // namespace

LoopInBox prove_loop_in_box(const core::Mat4& a, const core::Mat4& b, const RationalBox& box) {
  LoopInBox out;
  for (size_t k = 0; k < 3; ++k)
    if (!(box.lo[k] < box.hi[k])) {
      out.reason = "the box is flat or empty along axis " + std::to_string(k);
      return out;
    }
  const BoxExits outer = box_exits(a, b, box.lo, box.hi);
  if (!outer.certified) {
    out.reason = "the crossings with the box's faces are not certified: " + outer.reason;
    return out;
  }
  if (!outer.points.empty()) {
    out.reason = "the curve crosses the box's faces (" + std::to_string(outer.points.size()) +
                 " exact crossing(s))";
    return out;
  }
  // The curve misses the boundary of B. A point of it inside: a crossing with a split plane.
  // The axes by decreasing width (a tight box around a loop: the mid-plane of its widest axis
  // cuts it twice, far from tangency); on each the mid-plane, then planes off it by 1/8 and
  // 3/8 of the width (a mid-plane tangent to the loop, or through a crossing on an edge).
  std::array<size_t, 3> axes{0, 1, 2};
  std::stable_sort(axes.begin(), axes.end(), [&](size_t i, size_t j) {
    return box.hi[i] - box.lo[i] > box.hi[j] - box.lo[j];
  });
  std::string last = "no split plane of the box crosses the curve";
  for (size_t k : axes) {
    const Rational w = box.hi[k] - box.lo[k];
    for (const Rational& f :
         {Rational(1, 2), Rational(3, 8), Rational(5, 8), Rational(1, 8), Rational(7, 8)}) {
      const Rational c = box.lo[k] + f * w;
      std::array<Rational, 3> hi = box.hi;
      hi[k] = c;
      const BoxExits half = box_exits(a, b, box.lo, hi);
      if (!half.certified) {
        last = "a split's crossings are not certified: " + half.reason;
        continue;
      }
      if (half.points.empty()) continue; // this plane misses the curve inside B
      out.proven = true;
      out.axis = static_cast<int>(k);
      out.cut = c;
      out.crossings = static_cast<int>(half.points.size());
      return out;
    }
  }
  out.reason = last;
  return out;
}

ProvenLoops proven_loops(const core::Mat4& a, const core::Mat4& b,
                         const std::vector<std::vector<RationalBox>>& proposals) {
  ProvenLoops out;
  for (const auto& boxes : proposals) {
    std::string why = "no box given";
    for (const RationalBox& box : boxes) {
      const bool apart = std::all_of(out.boxes.begin(), out.boxes.end(),
                                     [&](const RationalBox& p) { return disjoint(p, box); });
      if (!apart) {
        why = "the box meets one already holding a proven loop";
        continue;
      }
      const LoopInBox one = prove_loop_in_box(a, b, box);
      if (one.proven) {
        out.boxes.push_back(box);
        ++out.count;
        why.clear();
        break;
      }
      why = one.reason;
    }
    if (!why.empty()) out.rejected.push_back(why);
  }
  return out;
}

// (See the header.) The conics are read in the plane's coordinates (x_i, x_j, 1).
algebra::UPolyZ critical_value_polynomial(const core::Mat4& a, const core::Mat4& b, int k) {
  using algebra::UPolyQ;
  const size_t ku = static_cast<size_t>(k), i = (ku + 1) % 3, j = (ku + 2) % 3;
  // The conic in the plane's coordinates (x_i, x_j, 1).
  auto conic = [&](const core::Mat4& m) {
    const std::array<size_t, 2> in{i, j};
    std::array<std::array<UPolyQ, 3>, 3> c;
    for (size_t r = 0; r < 2; ++r) {
      for (size_t s = 0; s < 2; ++s)
        c[r][s] = UPolyQ(m[in[r]][in[s]]);
      c[r][2] = c[2][r] = UPolyQ::linear(m[in[r]][ku], m[in[r]][3]);
    }
    c[2][2] = UPolyQ::from_coeffs({m[3][3], Rational(2) * m[ku][3], m[ku][ku]});
    return c;
  };
  // Integer multiples of both (the discriminant only scales by a positive constant): integer
  // polynomial arithmetic, no gcd per product.
  const auto fc = conic(core::integer_multiple(a)), gc = conic(core::integer_multiple(b));
  using M3 = std::array<std::array<UPolyQ, 3>, 3>;
  auto adj = [](const M3& m) {
    M3 r;
    for (size_t p = 0; p < 3; ++p)
      for (size_t q = 0; q < 3; ++q) {
        const size_t p1 = (p + 1) % 3, p2 = (p + 2) % 3, q1 = (q + 1) % 3, q2 = (q + 2) % 3;
        r[q][p] = m[p1][q1] * m[p2][q2] - m[p1][q2] * m[p2][q1]; // cofactor (p, q), transposed
      }
    return r;
  };
  auto pair_trace = [](const M3& x, const M3& y) { // tr(x y)
    UPolyQ t(0);
    for (size_t p = 0; p < 3; ++p)
      for (size_t q = 0; q < 3; ++q)
        t = t + x[p][q] * y[q][p];
    return t;
  };
  const M3 af = adj(fc), ag = adj(gc);
  // det(l F + m G) = al l^3 + be l^2 m + ga l m^2 + de m^3.
  auto det = [](const M3& m, const M3& adj_m) { // by the first row
    return m[0][0] * adj_m[0][0] + m[0][1] * adj_m[1][0] + m[0][2] * adj_m[2][0];
  };
  const UPolyQ al = det(fc, af), be = pair_trace(af, gc), ga = pair_trace(fc, ag), de = det(gc, ag);
  const UPolyQ d = be * be * ga * ga - UPolyQ(4) * al * ga * ga * ga -
                   UPolyQ(4) * be * be * be * de - UPolyQ(27) * al * al * de * de +
                   UPolyQ(18) * al * be * ga * de;
  if (d.is_zero()) return algebra::UPolyZ();
  return d.primitive_integer();
}

namespace {

using core::Poly3;

// The real roots of P_k (see the header) as an open interval (lo, hi) holding all of them;
// nullopt: no bound (P_k identically zero); an empty optional interval: no real root.
struct Slab {
  bool roots = false;
  Rational lo, hi;
};

// Res_u(f, g) for each variable u, computed when first wanted (every axis's elimination uses
// two of them: computed once, not once per axis).
struct CurveResultants {
  const Poly3& f;
  const Poly3& g;
  std::array<std::optional<Poly3>, 3> of{};
  const Poly3& operator()(int u) {
    auto& r = of[static_cast<size_t>(u)];
    if (!r) r = algebra::resultant(f, g, u);
    return *r;
  }
};

// The slab of D_k's real roots (critical_value_polynomial); nullopt when D_k is zero or its
// range does not prove out (the caller eliminates instead).
std::optional<Slab> discriminant_slab(const core::Mat4& a, const core::Mat4& b, int k) {
  const algebra::UPolyZ d = critical_value_polynomial(a, b, k);
  if (d.is_zero()) return std::nullopt;
  if (d.degree() == 0) return Slab{}; // a nonzero constant: no critical value at all
  const auto range = algebra::real_root_range(d);
  if (!range) return std::nullopt;
  Slab s;
  if (!range->any) return s;
  s.roots = true;
  s.lo = range->lo;
  s.hi = range->hi;
  return s;
}

std::optional<Slab> critical_slab(const Poly3& f, const Poly3& g,
                                  const std::array<Poly3, 3>& grad_f,
                                  const std::array<Poly3, 3>& grad_g, CurveResultants& fg, int k) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const Poly3 h = grad_f[static_cast<size_t>(i)] * grad_g[static_cast<size_t>(j)] -
                  grad_f[static_cast<size_t>(j)] * grad_g[static_cast<size_t>(i)];
  // A resultant of two polynomials both free of its variable is 1 by convention, not in
  // their ideal: such an elimination proves nothing.
  auto occurs = [](const Poly3& p, const Poly3& q, int var) {
    return p.degree(var) >= 1 || q.degree(var) >= 1;
  };
  for (const auto& [u, v] : {std::pair<int, int>{i, j}, std::pair<int, int>{j, i}}) {
    if (!occurs(f, g, u) || !occurs(f, h, u)) continue;
    const Poly3& r1 = fg(u);
    const Poly3 r2 = algebra::resultant(f, h, u);
    if (r1.is_zero() || r2.is_zero() || !occurs(r1, r2, v)) continue;
    const Poly3 p = algebra::resultant(r1, r2, v);
    if (p.is_zero()) continue;
    Slab out;
    if (p.is_constant()) return out; // a nonzero constant: no solution at all
    // Only the range of the real roots is wanted, proved by Descartes' rule beyond the float
    // roots (real_root_range); isolating them (Arb's complex roots of a degree-16 eliminant
    // with coefficients of hundreds of bits) took 10 ms on one cone pair, 6% of the intersect
    // bench. The range is tried on P_k itself first (real_root_range takes any polynomial):
    // its square-free part (a multivariate factorisation of the content and a gcd) was a
    // quarter of a cone pair's bound posed in doubles. Isolation, square-free, only when the
    // range does not prove out.
    auto range_of = [&out](const algebra::UPolyZ& q) -> std::optional<Slab> {
      const auto range = algebra::real_root_range(q);
      if (!range) return std::nullopt;
      if (!range->any) return out;
      Slab s;
      s.roots = true;
      s.lo = range->lo;
      s.hi = range->hi;
      return s;
    };
    if (const auto s = range_of(algebra::to_univariate(p, k))) return s;
    const algebra::UPolyZ pz = algebra::to_univariate(algebra::squarefree_part(p), k);
    if (const auto s = range_of(pz)) return s;
    const algebra::RootSeparation sep = algebra::isolate_real_roots(pz);
    if (sep.num_roots() == 0) return out;
    out.roots = true;
    out.lo = sep.separators.front();
    out.hi = sep.separators.back();
    // The separators bracket the roots; a root never equals an outer separator, but make
    // the slab open whatever the isolator's convention.
    out.lo -= Rational(1);
    out.hi += Rational(1);
    return out;
  }
  return std::nullopt;
}

// A double d <= q (rounding down, exactly checked), or >= q.
double outward(const Rational& q, bool down) {
  double d = q.to_double_approx();
  for (int n = 0; n < 4 && std::isfinite(d); ++n) {
    const Rational e = Rational::exact_from_double(d);
    if (down ? e <= q : e >= q) return d;
    d = std::nextafter(d, down ? -HUGE_VAL : HUGE_VAL);
  }
  return down ? -HUGE_VAL : HUGE_VAL;
}

} // namespace

LoopUpperBound loops_upper_bound(const core::Mat4& a, const core::Mat4& b, int wanted,
                                 long budget) {
  LoopUpperBound out;
  const Poly3 f = algebra::quadric_poly(a), g = algebra::quadric_poly(b);
  std::array<Poly3, 3> grad_f, grad_g;
  for (size_t k = 0; k < 3; ++k) {
    grad_f[k] = f.derivative(static_cast<int>(k));
    grad_g[k] = g.derivative(static_cast<int>(k));
  }
  std::array<double, 3> lo{}, hi{};
  CurveResultants fg{f, g};
  for (int k = 0; k < 3; ++k) {
    auto slab = discriminant_slab(a, b, k);
    if (!slab) slab = critical_slab(f, g, grad_f, grad_g, fg, k);
    if (!slab) {
      out.reason = "the critical points of axis " + std::to_string(k) +
                   " are not a finite set (the eliminant vanishes identically)";
      return out;
    }
    if (!slab->roots) {
      // x_k has no critical point on the curve: no compact component at all.
      out.bound = 0;
      for (size_t m = 0; m < 3; ++m)
        out.box.lo[m] = Rational(0), out.box.hi[m] = Rational(0);
      return out;
    }
    // A little wider than the slab, on a dyadic grid (short exact faces for box_exits).
    const Rational w = slab->hi - slab->lo;
    const double unit = std::ldexp(1.0, std::ilogb(w.to_double_approx()) - 6);
    const size_t ku = static_cast<size_t>(k);
    lo[ku] = std::floor(outward(slab->lo - w / Rational(16), true) / unit) * unit;
    hi[ku] = std::ceil(outward(slab->hi + w / Rational(16), false) / unit) * unit;
    if (!std::isfinite(lo[ku]) || !std::isfinite(hi[ku]) ||
        !(Rational::exact_from_double(lo[ku]) < slab->lo) ||
        !(Rational::exact_from_double(hi[ku]) > slab->hi)) {
      out.reason = "the box of the critical points is beyond the double range";
      return out;
    }
  }
  // The box's crossings, certified (moved outwards a little, unevenly, when a face meets the
  // curve non-generically: a larger box still holds every compact component).
  std::string why;
  for (int nudge = 0; nudge < 4; ++nudge) {
    std::array<Rational, 3> rlo, rhi;
    for (size_t k = 0; k < 3; ++k) {
      rlo[k] = Rational::exact_from_double(lo[k]);
      rhi[k] = Rational::exact_from_double(hi[k]);
    }
    const BoxExits ex = box_exits(a, b, rlo, rhi);
    if (ex.certified) {
      const InnerComponentBound ib = inner_component_bound(a, b, lo, hi, &ex, wanted, budget);
      if (!ib.bound) {
        out.reason =
            "no bound on the compact components in the box of the critical points: " + ib.reason;
        return out;
      }
      out.bound = ib.bound;
      out.box = RationalBox{rlo, rhi};
      return out;
    }
    why = ex.reason;
    for (size_t k = 0; k < 3; ++k) {
      const double h = hi[k] - lo[k];
      const double unit = std::ldexp(1.0, std::ilogb(h) - 6);
      lo[k] = std::floor((lo[k] - h * 0.0371 * (k + 1)) / unit) * unit;
      hi[k] = std::ceil((hi[k] + h * 0.0253 * (3 - k)) / unit) * unit;
    }
  }
  out.reason = "the crossings with the box of the critical points are not certified: " + why;
  return out;
}

bool settle_by_proven_loops(AffineTopology& t, const ProvenLoops& p, const LoopUpperBound* upper) {
  const bool has_upper = upper && upper->bound;
  if ((p.count <= 0 && !has_upper) || !t.computed || t.readings.size() < 2) return false;
  std::vector<std::pair<int, int>> keep;
  for (const auto& r : t.readings)
    if (r.first >= p.count && (!has_upper || r.first <= *upper->bound)) keep.push_back(r);
  if (keep.size() != 1) return false;
  keep_reading(t, keep[0], "proven_loops");
  for (const auto& bx : p.boxes)
    t.loop_boxes.push_back({bx.lo, bx.hi});
  // (No box when the curve has no critical point at all: no compact component anywhere.)
  if (has_upper && upper->box.lo[0] < upper->box.hi[0])
    t.all_loops_box = std::array<std::array<Rational, 3>, 2>{upper->box.lo, upper->box.hi};
  return true;
}

} // namespace surfcert::certify
