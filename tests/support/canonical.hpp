// surfcert::testing: real canonical pencils of quadrics for the tests, deterministic random
// scrambling of them (research qsic-classification §1.7, §4.5, §0.2), and the tests' own
// route from pencil facts to a Tu case.
//
// What it represents: the recipes (lists of real canonical blocks J_k / C_k), build_pencil and
// the seeded scrambling are the library's (algebra/canonical_pencil.hpp), named here for the
// tests. Every failure can be replayed: the seed is test_seed() = SURFCERT_TEST_SEED
// (environment) or 20261122.
#pragma once

#include "surfcert/algebra/canonical_pencil.hpp"
#include "surfcert/algebra/pencil.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/rational.hpp"

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace surfcert::testing {

using core::Mat4;
using core::Rational;

// The recipes and the scrambling live in the library (algebra/canonical_pencil.hpp, also what
// `surfcert generate` builds from); the tests name them here. What stays test-only is the
// independent route to the case: the signature sequence's normal form looked up in the §2.1
// table (never the classifier's rules).
using algebra::Block;
using algebra::build_pencil;
using algebra::case_recipes;
using algebra::CaseRecipe;
using algebra::change_basis;
using algebra::complex_block;
using algebra::congruence;
using algebra::direct_sum;
using algebra::parse_recipe;
using algebra::PencilPair;
using algebra::random_basis_change;
using algebra::random_invertible;
using algebra::real_block;
using algebra::Recipe;
using algebra::recipe_to_string;
using algebra::redraw_eigenvalues;
using algebra::Rng;
using algebra::scrambled_pencil;
using algebra::SmallMat;

/// Normal form (research §1.4) of the signature sequence read off exact pencil facts: the
/// lexicographically smallest among all rotations, each optionally reversed and/or
/// complemented (interval entries by value, root entries by (m, p, n)), as ASCII text.
/// Precondition: regular pencil analysed with det(facts.a) != 0.
std::string signature_normal_form(const algebra::PencilFacts& facts);

/// Case from the §2.1 table given the Segre text and the normalised sequence: the pair
/// (Segre, sequence) is unique per case. 0 when no row matches.
int case_from_table(const std::string& segre, const std::string& sequence);

/// SURFCERT_TEST_SEED if set (decimal), else 20261122.
std::uint64_t test_seed();

/// Random symmetric integer matrix with entries in [lo, hi] (not identically zero).
Mat4 random_symmetric(Rng& rng, long lo, long hi);

/// Multi-line text of a matrix, e.g. "[[1, 0, 0, 0], [0, -1/2, ...], ...]".
std::string mat_to_string(const Mat4& m);
/// "A = ...\nB = ...\n" (for failure messages).
std::string pencil_to_string(const Mat4& a, const Mat4& b);
inline std::string pencil_to_string(const PencilPair& ab) {
  return pencil_to_string(ab.a, ab.b);
}

} // namespace surfcert::testing
