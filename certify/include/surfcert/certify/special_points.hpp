// surfcert::certify::special_points: the real singular / tangency points of the QSIC, exactly.
//
// A real point X is singular on the QSIC iff (theta*A - B) X = 0 and X^T A X = 0 for a root
// theta of f (research §2.2). At a rational multiple root the kernel of theta*A - B is
// computed over Q: rank 3 gives one point (cone vertex: node, acnode, cusp, crossing of two
// lines), rank 2 a line meeting Q_A in at most two points (crossings of conics, contact
// points, vertices of line quadrilaterals), rank 1 a plane whose pole is the crossing point
// of two double lines. Coordinates are rational or in Q(sqrt d). At conjugate multiple roots
// in Q(sqrt d) only a rank-3 member's kernel point is computed (over Q(sqrt d): the crossings
// of a twisted cubic with its secant line, case 10); other points there (a kernel line's
// points would need a square root over Q(sqrt d)) are not, and `complete` is then false.
#pragma once

#include "surfcert/certify/qsic.hpp"

#include <vector>

namespace surfcert::certify {

std::vector<SpecialPoint> special_points(const algebra::PencilFacts& facts, int tu_case,
                                         bool& complete);

} // namespace surfcert::certify
