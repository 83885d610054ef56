#include "surfcert/certify/distance/critical_signs.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/solution_cover.hpp"

namespace surfcert::certify {

using core::Poly3;
using core::Rational;

CriticalSigns critical_signs(const SourceQuadric& src, const Poly3& h, const CriticalStop& enough) {
  // grad f x grad h = 0 is three equations of which two generic combinations (fixed small
  // integers, so runs are reproducible) suffice together with f = 0: the cover then holds the
  // critical points (and possibly a few spurious isolated points, which only add boxes whose
  // sign is tested like the others).
  const std::array<core::Poly3, 3> gh{h.derivative(0), h.derivative(1), h.derivative(2)};
  const std::array<core::Poly3, 3> v = core::cross(src.N, gh);
  const std::array<std::array<long, 3>, 2> ls{{{3, -5, 7}, {2, 7, -11}}};
  Poly3 e1, e2;
  for (size_t i = 0; i < 3; ++i) {
    e1 = e1 + Poly3(ls[0][i]) * v[i];
    e2 = e2 + Poly3(ls[1][i]) * v[i];
  }
  CriticalSigns st;
  algebra::SolutionCover cc = algebra::cover_real_solutions({src.f, e1, e2}, Rational(1, 16));
  if (!cc.ok) return st;
  st.finite = true;
  for (long bits = 16; bits <= 512; bits *= 2) {
    Rational width(1);
    fmpq_div_2exp(width.raw_mut(), width.raw(), static_cast<ulong>(bits));
    algebra::refine_cover(cc, width);
    const long prec = algebra::precision_for_width(width) + 64;
    st.all_signed = true;
    st.any_pos = st.any_neg = false;
    st.boxes = cc.boxes.size();
    for (const auto& b : cc.boxes) {
      Ball box[3], val;
      algebra::box_balls(cc, b, box[0].v, box[1].v, box[2].v, prec);
      algebra::evaluate(val.v, h, ball_point(box), prec);
      const bool pos = arb_is_positive(val.v), neg = arb_is_negative(val.v);
      st.any_pos = st.any_pos || pos;
      st.any_neg = st.any_neg || neg;
      st.all_signed = st.all_signed && (pos || neg);
      // A certified point of S near the box on a side not yet witnessed.
      if ((pos && !st.pos_point) || (neg && !st.neg_point)) {
        std::array<double, 3> at{};
        const int s = certified_sign_near(src, h, cc, b, prec, &at);
        if (s > 0 && !st.pos_point) st.pos_point = at;
        if (s < 0 && !st.neg_point) st.neg_point = at;
      }
    }
    const bool done =
        enough ? enough(st) : (st.pos_point && st.neg_point) || (st.all_signed && st.boxes > 0);
    if (done) break;
  }
  return st;
}

} // namespace surfcert::certify
