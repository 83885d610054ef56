// surfcert::certify critical signs: the sign of a polynomial h at the critical points of h
// restricted to a surface S = {f = 0}, the contact test every "is S on one side of {h = 0}"
// question reduces to.
//
// Why it decides contact: on a compact component of S (or one on which h grows at infinity)
// h takes its extreme values at critical points of h|S, i.e. where f = 0 and
// grad f x grad h = 0 (singular points of S satisfy it too). So one strict sign of h at every
// critical point means S never meets {h = 0}; certified points of S with h > 0 and with h < 0
// mean S crosses it (S connected) or reaches into it.
//
// Invariants: `finite` is false when the critical set is not proven finite (then nothing else
// holds); `all_signed`, `any_pos`, `any_neg` describe the last refinement of the exact
// solution cover (every critical point lies in a box; a box's sign is an Arb sign over the
// whole box); `pos_point` / `neg_point` are set only for points of S certified to lie on that
// side (Arb balls around an exact point of S), their coordinates rounded to double.
#pragma once

#include "surfcert/algebra/poly_ops.hpp"
#include "surfcert/certify/distance/offset_minimum.hpp"

#include <array>
#include <functional>
#include <optional>

namespace surfcert::certify {

struct CriticalSigns {
  bool finite = false;     ///< the critical points of h on S form a finite, covered set
  bool all_signed = false; ///< every cover box has a certified strict sign of h
  bool any_pos = false;    ///< some box with h > 0 (last refinement)
  bool any_neg = false;    ///< some box with h < 0 (last refinement)
  size_t boxes = 0;        ///< boxes of the last refinement
  std::optional<std::array<double, 3>> pos_point, neg_point; ///< certified points of S
};

/// When to stop refining (called after each refinement; the default stops once both sides
/// have certified points or every box is signed).
using CriticalStop = std::function<bool(const CriticalSigns&)>;

/// Refines the critical points of h on S (2^-16 ... 2^-512 boxes) until `enough` holds or the
/// refinement budget is spent; returns the last state.
CriticalSigns critical_signs(const SourceQuadric& src, const core::Poly3& h,
                             const CriticalStop& enough = nullptr);

} // namespace surfcert::certify
