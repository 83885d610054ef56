#include "surfcert/certify/qsic_rules.hpp"

#include <stdexcept>

namespace surfcert::certify {

using algebra::PencilFacts;
using algebra::RootFacts;

int decide_tu_case(const PencilFacts& f) {
  const auto& roots = f.real_roots;
  std::vector<const RootFacts*> multiple;
  for (const auto& r : roots)
    if (r.multiplicity > 1) multiple.push_back(&r);
  const bool def = f.definite_member;
  auto fail = [](const char* why) -> int { throw std::logic_error(why); };

  if (multiple.empty() && !f.complex_double_pair) {
    // All roots simple: [1111].
    switch (roots.size()) {
    case 4:
      return def ? 2 : 1;
    case 2:
      return 3;
    case 0:
      return 4;
    default:
      return fail("a quartic with simple roots has 0, 2 or 4 real roots");
    }
  }
  if (f.complex_double_pair) return f.minimal_poly_split ? 31 : 11;

  if (multiple.size() == 2) {
    // Two real double roots (rational, or conjugate in Q(sqrt d)).
    const RootFacts& x = *multiple[0];
    const RootFacts& y = *multiple[1];
    if (x.multiplicity != 2 || y.multiplicity != 2)
      return fail("two multiple roots must be double");
    if (x.rank == 3 && y.rank == 3) return 10;
    if (x.rank == 2 && y.rank == 2) {
      int semi = (x.sigma.semidefinite() ? 1 : 0) + (y.sigma.semidefinite() ? 1 : 0);
      return semi == 0 ? 28 : (semi == 1 ? 30 : 29);
    }
    const RootFacts& r2 = x.rank == 2 ? x : y;
    const RootFacts& r3 = x.rank == 2 ? y : x;
    if (r2.rank != 2 || r3.rank != 3) return fail("unexpected ranks at two double roots");
    if (!r2.jump()) return 23;
    return r3.sigma.semidefinite() ? 25 : 24;
  }
  if (multiple.size() != 1) return fail("more than two multiple roots");
  const RootFacts& t = *multiple[0];
  if (t.multiplicity == 2) {
    // One double root and two simple roots (real or complex).
    const bool simple_complex = f.complex_roots == 2;
    if (t.rank == 3) { // [211]
      if (t.sigma.semidefinite()) return 7;
      if (simple_complex) return 8;
      if (t.index_left == 1 || t.index_left == 3) return 6;
      if (t.index_left == 2) return 5;
      return fail("[211] with an impossible index");
    }
    if (t.rank == 2) { // [(11)11]
      if (t.sigma.semidefinite()) return def ? 16 : 15;
      if (simple_complex) return t.jump() ? 17 : 18;
      if (!t.jump()) return 13;
      return def ? 16 : 14;
    }
    return fail("double root with rank < 2");
  }
  if (t.multiplicity == 3) {
    if (t.rank == 3) return 9;
    if (t.rank == 2) return t.sigma.semidefinite() ? 20 : 19;
    if (t.rank == 1) return def ? 22 : 21;
    return fail("triple root with rank 0");
  }
  if (t.multiplicity == 4) {
    if (t.rank == 3) return 12;
    if (t.rank == 2) {
      if (f.quadruple_n2_zero) return t.sigma.semidefinite() ? 34 : 35;
      return t.jump() ? 27 : 26;
    }
    if (t.rank == 1) return t.jump() ? 33 : 32;
    return fail("quadruple root of rank 0: coincident quadrics, not a regular pencil case");
  }
  return fail("impossible multiplicity");
}

} // namespace surfcert::certify
