// surfcert::algebra canonical pencils: real canonical forms of the 35 Tu cases of a regular
// pencil of quadrics, and deterministic random scrambling of them (research
// qsic-classification §1.7, §4.5, §0.2). Used by `surfcert generate` (app/generate.hpp) and
// by the tests.
//
// What it represents: a "recipe" is a list of real canonical blocks J_k(theta, eps) (real
// eigenvalue theta, block size k, sign eps) and C_k(a+bi) (complex pair a +- bi, size k) whose
// sizes add up to 4 (complex blocks count 2k). build_pencil turns it into the 4x4 pair (A, B)
// whose pencil l*A - B is the direct sum of the blocks. The 35 recipes of §4.5 are hard-coded
// with their Tu case (a construction: what a case's label is, is decided by the classifier,
// never by this table). Randomisation (eigenvalue redraw, integer congruence, change of pencil
// basis) uses a seeded Rng whose draws are the same on every platform, so a seed replays.
// Contract: every operation here preserves the Segre characteristic and the signature
// sequence of the recipe (congruences and basis changes are invertible, the redraw keeps the
// order and equalities of the eigenvalues), hence its Tu case.
#pragma once

#include "surfcert/core/quadric.hpp"
#include "surfcert/core/rational.hpp"

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace surfcert::algebra {

using core::Mat4;
using core::Rational;

/// A square rational matrix of any small size (canonical blocks are k x k or 2k x 2k).
using SmallMat = std::vector<std::vector<Rational>>;

struct Block {
  bool complex = false; ///< false: J_k(theta, sign); true: C_k(theta + im*i)
  int size = 1;         ///< k (a complex block occupies 2k rows)
  Rational theta;       ///< real eigenvalue, or real part of the complex one
  Rational im;          ///< imaginary part (complex blocks only, nonzero)
  int sign = 1;         ///< +1 / -1 (real blocks only)
  int dimension() const { return complex ? 2 * size : size; }
};
using Recipe = std::vector<Block>;

struct PencilPair {
  Mat4 a, b;
};

/// One row of the §4.5 table.
struct CaseRecipe {
  int tu_case;
  const char* recipe; ///< text accepted by parse_recipe
  const char* segre;  ///< Segre characteristic of the case (research §2.1), canonical text
  /// Normalised signature sequence(s) of §2.1 in ASCII ("<1,(1,2),2,((1,1)),3>"; index =
  /// number of positive eigenvalues; a root in m pairs of parentheses); case 16 has two,
  /// separated by a space.
  const char* sequences;
};

/// The 35 recipes of research §4.5, in case order (index = case - 1).
const std::vector<CaseRecipe>& case_recipes();

/// Parses e.g. "J1(-3,+) J1(-1,+) J1(1,-) J1(3,+)", "J2(-3,+) C1(1+2i)", "C2(i)",
/// "J1(-1/2,-) C1(-3/2-i)", "J1(-3,+)x3 J1(-1,+)" (x3 = repeat). Throws
/// std::invalid_argument on malformed text or when the sizes do not add up to 4.
Recipe parse_recipe(const std::string& text);
std::string recipe_to_string(const Recipe& r);

/// J_k(theta, eps): A-block eps*F_k, B-block eps*(theta*F_k + G_k).
std::pair<SmallMat, SmallMat> real_block(int k, const Rational& theta, int eps);
/// C_k(a+bi): A-block R(F_k), B-block R((a+bi)F_k + G_k), R(M) = [[Re M, -Im M], [-Im M, -Re M]].
std::pair<SmallMat, SmallMat> complex_block(int k, const Rational& a, const Rational& b);
/// Block-diagonal direct sum; the sizes must add up to 4 (throws std::invalid_argument).
PencilPair direct_sum(const std::vector<std::pair<SmallMat, SmallMat>>& blocks);
PencilPair build_pencil(const Recipe& r);

/// Deterministic random source: std::mt19937_64 (its output sequence is fixed by the
/// standard) with our own range reduction, so a seed gives the same draws everywhere.
class Rng {
public:
  explicit Rng(std::uint64_t seed) : gen_(seed) {}
  /// Uniform integer in [lo, hi].
  long uniform(long lo, long hi);
  /// Small random rational num/den, num in [-num_max, num_max], den in [1, den_max].
  Rational small_rational(long num_max = 9, long den_max = 4);
  /// Small random dyadic num/2^e, num in [-num_max, num_max], e in [0, max_exp] (exactly a
  /// binary64).
  Rational small_dyadic(long num_max = 9, int max_exp = 2);
  std::mt19937_64& engine() { return gen_; }

private:
  std::mt19937_64 gen_;
};

/// New eigenvalues keeping everything that determines the case: the distinct real eigenvalues
/// keep their relative order and equalities (random small rationals, dyadic ones when
/// `dyadic`), every distinct complex value gets a random a in [-4, 4], b in {1, 2, 3}
/// (distinct complex values stay distinct, a repeated complex value stays repeated). Block
/// sizes and signs are kept.
Recipe redraw_eigenvalues(const Recipe& r, Rng& rng, bool dyadic = false);

/// Random integer matrix with entries uniform in [lo, hi] and det != 0.
Mat4 random_invertible(Rng& rng, long lo, long hi);
/// A -> P^T A P, B -> P^T B P.
PencilPair congruence(const PencilPair& ab, const Mat4& p);
/// (A, B) -> (pA + qB, rA + tB); nullopt when pt - qr == 0 or a matrix becomes zero.
std::optional<PencilPair> change_basis(const PencilPair& ab, long p, long q, long r, long t);
/// Random p, q, r, t in [-2, 2] with pt - qr != 0 and both matrices nonzero.
PencilPair random_basis_change(const PencilPair& ab, Rng& rng);
/// Recipe with redrawn eigenvalues, then a random congruence (entries in [-2, 2]), then a
/// random change of pencil basis (research §0.2, random set). With `dyadic` every entry of
/// the result is a dyadic rational with a few bits (integer congruence and basis, dyadic
/// eigenvalues): exactly a binary64.
PencilPair scrambled_pencil(const Recipe& r, Rng& rng, bool dyadic = false);

} // namespace surfcert::algebra
