// surfcert::certify fast analyses of a pencil: an interval filter (certified when it answers)
// and a plain floating-point analysis (uncertified, for the `float` mode).
//
// analyze_pencil_filtered: the exact algorithm of analyze_pencil_exact, evaluated in interval
// arithmetic (CGAL::Interval_nt, rounding mode switched inside) on enclosures of the exact
// matrices (enclosure.hpp: for shapes posed in doubles, computed from the doubles, so the
// exact rationals are never formed when the filter answers). It answers only when every
// sign it needs is certain: the discriminant D4 != 0 (all roots simple), the root count from
// D2, D3, D4, separators whose f-signs alternate (k exact roots, k+1 alternating signs: one
// root per gap), and nonzero charpoly coefficients or a certain determinant for the indices.
// Otherwise it returns nullopt and the caller falls back to exact arithmetic. Where the
// enclosure of det A (f's leading coefficient) or det B (its constant) contains 0 but the
// determinant is not 0 exactly (a cone or cylinder posed in doubles: the rounding leaves it
// ~1e-17 of the entries), the exact determinant, enclosed, takes its place (no re-basing, as on
// the exact path); separators then come from f' in closed form or, failing that (or where the
// indices there are not certain), from the float roots, each inner one near the root of
// smaller magnitude (candidates either way); beyond every root the index is A's exact inertia
// (above the roots) or -A's (below), where the intervals cannot tell. A pencil whose A
// is singular (det A = 0 exactly: QuadricMatrix::singular) is re-based as the exact path does
// (a' = t A - B, b' = -A, the same first t with det(tA - B) != 0; every t skipped a proven
// zero), so its facts are the exact path's; rebased and rebase_t are set, facts.a / facts.b
// stay empty (qsic.cpp fills them, in that basis, when a later stage needs them). A pencil with
// a plane among its members (exactly: a plane n . x + d = 0, n != 0, as either quadric) has that
// member's root theta double by construction (rank 2; theta = 0, or -1/t when B is the plane and
// the pencil was re-based): f = (l - theta)^2 g is read with g's discriminant, g(theta) and its
// signs at the separators certain, the double root reported exact with rank 2 and inertia (1, 1)
// (a plane's). When the other quadric is singular at a point at infinity (a cylinder: det = 0
// and its quadratic part singular, exactly; by construction for a posed shape), that point lies
// on the plane's quadric (n . x + d) w = 0 as well, so the other quadric's own parameter phi (0
// or -1/t) is a second double root: f = c (l - theta)^2 (l - phi)^2 exactly (R6), read with c's
// sign and the indices at separators around theta and phi certain; phi's member of rank 3 (its
// charpoly's linear coefficient certainly nonzero) with the inertia its other coefficients' signs
// give. Any other multiple root goes to the exact path. Its facts carry exact dyadic
// separators but no exact f/D values (fill them with complete_exact_invariants).
//
// analyze_pencil_float: doubles throughout (facts.a / facts.b left empty). The root pattern from
// the float roots of f (Aberth): a cluster of m roots is one m-fold root when f is within
// relative `tol` (seed 002's 1e-8 by default) of a polynomial with that m-fold root (its Taylor
// coefficients at the refined cluster centre); indices from the members' eigenvalue signs at
// separators, ranks and inertias at multiple roots from eigenvalues with `tol`. B = tA within
// `tol` is coincident. D2, D3, D4, E (reported in `inv`) are computed from the roots. Nothing it
// returns is certified; away from degeneracy (relative distance >> tol) it should be right.
#pragma once

#include "surfcert/algebra/pencil.hpp"
#include "surfcert/core/quadric.hpp"

#include <optional>

namespace surfcert::certify {

std::optional<algebra::PencilFacts> analyze_pencil_filtered(const core::QuadricMatrix& a,
                                                            const core::QuadricMatrix& b);
/// The same, written into `out` (a default-constructed PencilFacts): true when the filter
/// decides (out holds the facts), false when it cannot (out is then unspecified). Spares the
/// fast path the moves of the facts' exact members.
bool analyze_pencil_filtered(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                             algebra::PencilFacts& out);

struct FloatInvariants {
  double f[5];
  double d2, d3, d4, e;
};

/// Float analysis; facts.f / d2.. are left empty, the float values go to `inv`.
algebra::PencilFacts analyze_pencil_float(const core::QuadricMatrix& a,
                                          const core::QuadricMatrix& b, FloatInvariants& inv,
                                          double tol = 1e-8);

/// Fills f, d2, d3, d4, e and root_pattern of facts exactly from facts.a, facts.b.
void complete_exact_invariants(algebra::PencilFacts& facts);

} // namespace surfcert::certify
