// surfcert::algebra Segre characteristic of a regular pencil l*A - B, two exact routes.
//
// The Segre characteristic lists, per eigenvalue (root of f), the sizes of its Jordan blocks,
// parenthesised when one eigenvalue has several blocks (research §1.2). Canonical text form:
// groups sorted by total multiplicity (descending), a single block before a parenthesised
// group of the same multiplicity, e.g. "[2(11)]", "[(21)1]", "[1111]".
// Route 1 (segre_from_facts): multiplicity + rank at each root (+ the two minimal-polynomial
// tests). Route 2 (segre_by_invariant_factors): gcds of k x k minors of l*A - B over Q[l],
// invariant factors i_k = d_k / d_(k-1), exponents of each irreducible factor of f.
#pragma once

#include "surfcert/algebra/pencil.hpp"

#include <string>
#include <vector>

namespace surfcert::algebra {

/// Canonical text from groups of block sizes (one vector per eigenvalue).
std::string segre_text(std::vector<std::vector<int>> groups);

/// Route 1, from an exact (or float) analysis of a regular pencil.
std::string segre_from_facts(const PencilFacts& facts);

/// Route 2, independent: invariant factors of l*A - B. Precondition: regular pencil.
std::string segre_by_invariant_factors(const core::Mat4& a, const core::Mat4& b);

} // namespace surfcert::algebra
