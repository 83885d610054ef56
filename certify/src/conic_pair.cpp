// conic_pair: the resultant of two plane conics in a sheared chart, and whether they have a
// real common point (see conic_pair.hpp).
#include "surfcert/certify/conic_pair.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/real_roots.hpp"

#include <cmath>

namespace surfcert::certify {

namespace {

using algebra::UPolyQ;
using core::Rational;
using V3 = std::array<Rational, 3>;

// A conic in chart coordinates as c2 y^2 + c1(x) y + c0(x).
struct InY {
  Rational c2;
  UPolyQ c1, c0;
};

InY in_y(const ConicForm& c) {
  InY r;
  r.c2 = c[1][1];
  r.c1 = UPolyQ::from_coeffs({Rational(2) * c[1][2], Rational(2) * c[0][1]});
  r.c0 = UPolyQ::from_coeffs({c[2][2], Rational(2) * c[0][2], c[0][0]});
  return r;
}

std::vector<std::array<V3, 3>> make_charts() {
  const std::pair<long, long> shears[] = {{0, 1}, {1, 3}, {-2, 5}, {3, 7}, {-5, 4}, {7, 11}};
  std::vector<std::array<V3, 3>> out;
  for (int swap = 0; swap < 2; ++swap)
    for (const auto& [n, d] : shears) {
      const Rational s(n, d);
      std::array<V3, 3> t;
      t[0] = swap ? V3{Rational(0), Rational(1), Rational(0)}
                  : V3{Rational(1), Rational(0), Rational(0)};
      t[1] = swap ? V3{Rational(1), s, Rational(0)} : V3{s, Rational(1), Rational(0)};
      t[2] = V3{Rational(0), Rational(0), Rational(1)};
      out.push_back(t);
    }
  return out;
}

} // namespace

const std::vector<std::array<std::array<Rational, 3>, 3>>& conic_charts() {
  static const std::vector<std::array<V3, 3>> all = make_charts();
  return all;
}

std::optional<ConicResultant> conic_resultant(const ConicForm& ca, const ConicForm& cb,
                                              size_t chart) {
  const auto& t = conic_charts()[chart];
  // The first chart is the identity: the forms as they are (T^T C T == C, no arithmetic).
  InY a = in_y(chart == 0 ? ca : algebra::restrict_form(ca, t));
  InY b = in_y(chart == 0 ? cb : algebra::restrict_form(cb, t));
  if (a.c2.is_zero()) std::swap(a, b);
  if (a.c2.is_zero()) return std::nullopt; // (0 : 1 : 0) on both conics: another chart
  const UPolyQ A2(a.c2), B2(b.c2);
  const UPolyQ x = A2 * b.c0 - a.c0 * B2;
  ConicResultant out;
  out.t = t;
  out.r = x * x - (A2 * b.c1 - a.c1 * B2) * (a.c1 * b.c0 - a.c0 * b.c1);
  out.s11 = B2 * a.c1 - A2 * b.c1;
  out.s10 = B2 * a.c0 - A2 * b.c0;
  out.a2 = a.c2;
  out.a1 = a.c1;
  out.a0 = a.c0;
  return out;
}

std::optional<bool> conics_meet(const ConicForm& ca, const ConicForm& cb) {
  for (size_t n = 0; n < conic_charts().size(); ++n) {
    const auto cr = conic_resultant(ca, cb, n);
    if (!cr) continue;
    if (cr->r.is_zero()) return std::nullopt; // a shared component: its real points not read
    if (cr->r.degree() < 1) return false;     // no common point over any x
    const UPolyQ disc = cr->a1 * cr->a1 - UPolyQ(Rational(4) * cr->a2) * cr->a0;
    bool open = false;
    for (const algebra::IrreducibleFactor& f :
         algebra::irreducible_factors(cr->r.primitive_integer())) {
      const algebra::RootSeparation s = algebra::isolate_real_roots(f.poly);
      if (s.separators.size() < 2) continue; // no real root
      UPolyQ fq;
      fmpq_poly_set_fmpz_poly(fq.raw_mut(), f.poly.raw());
      // s11 != 0 at the roots of f (f irreducible: all or none): one real point over each.
      if (!cr->s11.rem(fq).is_zero()) return true;
      // s11 = 0 there: the common points over x0 are A's; real iff disc(x0) >= 0.
      if (disc.rem(fq).is_zero()) return true; // a real double root in y
      for (size_t k = 0; k + 1 < s.separators.size(); ++k) {
        const int sg = algebra::sign_at_root(disc, f.poly, s.separators[k], s.separators[k + 1]);
        if (sg > 0) return true;
        if (sg == 0) open = true;
      }
    }
    if (open) return std::nullopt;
    return false;
  }
  return std::nullopt;
}

} // namespace surfcert::certify
