// surfcert::certify::Isometry, common_symmetries, prove_ties: exact proofs that tied
// minimizers of a distance query are at exactly the same distance.
//
// An Isometry is g(x) = P x + t with rational P, P^T P = I and P^2 = I (an involution: the
// reflection in a plane, the half-turn about a line, or the point reflection through a point).
// If g maps each of the two surfaces onto itself, it maps closest pairs to closest pairs at the
// same distance. common_symmetries tries the involutions built from rational candidate
// directions (rational eigenvectors of the quadratic parts, torus axes, spine directions, the
// line between centres, the coordinate axes, and cross products of these) through rational
// candidate fixed points (centres), and keeps those whose invariance is checked exactly:
// quadric matrices with T^T A T = +-A, a torus's centre fixed and axis kept up to sign, a canal
// spine and radius kept (or reversed on the parameter interval), an implicit polynomial kept up
// to sign. Parametric surfaces have no candidates (never claimed).
//
// prove_ties: the route that found the minimizers supplies regions (outward double enclosures,
// in point space where g acts as x -> P x + t, in unit-direction space where it acts as
// n -> P n, or as line directions up to sign, where the image is taken with both signs) with
// two guarantees: (a) every global minimizer lies in one of the regions, and
// (b) each region holds at most one global minimizer. If g(region i) meets only region j, the
// minimizer in i (when there is one) maps to a global minimizer in j; when these arrows connect
// every region to every other, all regions hold a minimizer and all minimal distances are
// exactly equal. Anything unproven (overlapping images, no symmetry) leaves the tie unproven.
#pragma once

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/surface.hpp"

#include <array>
#include <string>
#include <vector>

namespace surfcert::certify {

struct Isometry {
  std::array<std::array<core::Rational, 3>, 3> P; ///< orthogonal, P * P = I
  std::array<core::Rational, 3> t;
  std::string name; ///< e.g. "reflection in the plane (0, 1, 0).x = 0"
  /// g(x) = P x + t at a rational point.
  std::array<core::Rational, 3> apply(const std::array<core::Rational, 3>& x) const;
};

/// True when g maps s onto itself (decided exactly; false for parametric surfaces).
bool preserves(const Isometry& g, const core::Surface& s);

/// Every candidate involution (see above) that maps a onto a and b onto b, identity excluded.
std::vector<Isometry> common_symmetries(const core::Surface& a, const core::Surface& b);

/// When r.tie_regions lists the regions of r's minimizers (count >= 2), tries to prove their
/// distances equal by common symmetries of a and b; on success sets r.ties = "proven" and
/// replaces the "not proven" wording of the note by the isometries used.
void prove_ties(DistanceResult& r, const core::Surface& a, const core::Surface& b);

} // namespace surfcert::certify
