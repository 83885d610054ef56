// The ball type (algebra::Ball, RAII over Arb's arb_t) and outward-rounded decimal bounds: the
// two pieces every certified enclosure in the distance code needs.
#pragma once

#include "surfcert/algebra/arb.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <string>

namespace surfcert::certify {

// The Arb ball value type lives with the Arb includes (surfcert/algebra/arb.hpp).
using algebra::Ball;

/// Decimal text of x with `digits` significant digits, rounded down (lower bound) or up
/// (upper bound), so the text never lies inside the enclosure it bounds.
std::string decimal_bound(const arf_t x, bool upper, long digits);

/// The enclosure [lower(lo), upper(hi)] of a minimum from a certified lower bound `lo` and a
/// certified upper bound `hi`: true when lo > 0 and hi is finite for certain and
/// upper - lower <= 10^-digits lower; d then holds that interval (the answer at `digits`).
bool relative_enclosure(arb_t d, const arb_t lo, const arb_t hi, long digits, long prec);

/// [lo, hi] in doubles rounded outward, containing the ball x (infinite when x is).
std::array<double, 2> outward_interval(const arb_t x);

/// The unit frame (u, v) of the plane orthogonal to a: core::plane_frame(a) normalised in Arb
/// (the unit vectors are irrational in general; the balls contain them).
void unit_plane_frame(Ball (&u)[3], Ball (&v)[3], const std::array<core::Rational, 3>& a,
                      long prec);

/// Working precision (bits) for an answer of `digits` decimal digits, with a 64-bit margin.
inline long bits_for(long digits) {
  return static_cast<long>(static_cast<double>(digits) * 3.33) + 64;
}

} // namespace surfcert::certify
