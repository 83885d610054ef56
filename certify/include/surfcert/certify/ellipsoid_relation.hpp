// surfcert::certify::ellipsoid_relation: how two real ellipsoids lie to each other, from the
// facts of their pencil.
//
// What it decides: "separated", "externally_touching", "overlapping", "internally_touching"
// or "nested" (with "a_inside_b" / "b_inside_a" for the last two), for two real ellipsoids
// with a regular pencil; nothing for other pairs. The relation follows from the Tu case and
// the signs of the real roots of f(l) = det(lA - B) (after normalising both matrices so that
// their quadratic blocks are positive definite); the containment from the squared volumes.
// Cost (what makes it cheap enough for a topology-only answer): each root sign comes from the
// facts' isolating interval when it lies on one side of 0, else from the signs of f(0) =
// det(-B) and of det A (a 4x4 determinant in CGAL interval arithmetic, exact only when the
// interval holds 0) and the root multiplicities; the containment compares the volumes in
// intervals first. Exact arithmetic (the characteristic polynomial, its square-free part)
// runs only when those do not decide (an even-multiplicity root without an exact value whose
// interval holds 0, or volumes the intervals cannot separate).
// Certified facts give a certified relation; float facts (mode float) give an estimate.
#pragma once

#include "surfcert/certify/qsic.hpp"

namespace surfcert::certify {

/// Sets r.ellipsoid_relation and r.containment from r.facts and r.tu_case (a, b: the quadrics
/// r classifies). Leaves them empty unless both are real ellipsoids.
void ellipsoid_relation(QsicResult& r, const core::QuadricMatrix& a, const core::QuadricMatrix& b);

} // namespace surfcert::certify
