// surfcert::certify::decide_tu_case: the decision list of research qsic-classification §2.3.
//
// Input: the facts of a regular pencil (multiplicities, ranks, inertias at the real roots,
// indices between them, the minimal-polynomial tests, Finsler's definite-member flag).
// Output: the Tu case 1..35 (a label of the morphology; see morphology.hpp). The rules only
// read the facts, so exact and float analyses share them: the certainty of the answer is the
// certainty of the facts.
#pragma once

#include "surfcert/algebra/pencil.hpp"

namespace surfcert::certify {

/// Tu case of a regular pencil. Throws std::logic_error on facts no regular pencil can have
/// (e.g. inconsistent float facts); callers map that to "undecided"/"error".
int decide_tu_case(const algebra::PencilFacts& facts);

} // namespace surfcert::certify
