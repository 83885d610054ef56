// surfcert::certify::proven_loops: loops proven to lie wholly inside given boxes (see
// proven_loops.hpp).
#include "surfcert/certify/proven_loops.hpp"

#include "surfcert/certify/box_exits.hpp"

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

bool settle_by_proven_loops(AffineTopology& t, const ProvenLoops& p) {
  if (p.count <= 0 || !t.computed || t.readings.size() < 2) return false;
  std::vector<std::pair<int, int>> keep;
  for (const auto& r : t.readings)
    if (r.first >= p.count) keep.push_back(r);
  if (keep.size() != 1) return false;
  t.loops = keep[0].first;
  t.unbounded_branches = keep[0].second;
  t.undecided.erase(std::remove_if(t.undecided.begin(), t.undecided.end(),
                                   [](const auto& u) {
                                     return u.first == "loops" || u.first == "unbounded_branches";
                                   }),
                    t.undecided.end());
  t.readings = keep;
  t.route = "proven_loops";
  t.loop_boxes.clear();
  for (const auto& bx : p.boxes)
    t.loop_boxes.push_back({bx.lo, bx.hi});
  return true;
}

} // namespace surfcert::certify
