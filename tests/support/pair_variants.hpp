// The same intersection curve posed several ways, for tests whose answer must not depend on
// the pose: the pair as given, moved by a rational rigid motion, swapped, moved and swapped,
// scaled (x -> 7/2 x), and with its matrices multiplied by -3 and 5/2 (the same surfaces).
// Each is an exact congruence (or a nonzero multiple), so counts and morphologies are equal.
#pragma once

#include "support/distance_checks.hpp"

#include "surfcert/core/quadric.hpp"

#include <string>
#include <vector>

namespace surfcert::testing {

struct PairVariant {
  std::string name;
  core::QuadricMatrix a, b;
};

inline std::vector<PairVariant> pair_variants(const core::Mat4& a0, const core::Mat4& b0) {
  const core::Mat4 m =
      motion(2, -1, 1, 3, {core::Rational(-3, 4), core::Rational(1, 2), core::Rational(2)});
  const core::QuadricMatrix a(a0), b(b0);
  return {
      {"as given", a, b},
      {"moved", a.congruent(m), b.congruent(m)},
      {"swapped", b, a},
      {"moved swapped", b.congruent(m), a.congruent(m)},
      {"scaled", a.congruent(scaling(core::Rational(7, 2))),
       b.congruent(scaling(core::Rational(7, 2)))},
      {"multiplied", core::QuadricMatrix(core::scaled(a0, core::Rational(-3))),
       core::QuadricMatrix(core::scaled(b0, core::Rational(5, 2)))},
  };
}

} // namespace surfcert::testing
