// surfcert::certify::ellipses_in_box: how many of a QSIC's bounded conic components lie wholly
// inside a box, exactly.
//
// What it is for: a given box that cuts some loops of the curve and holds others; the tracer's
// closed pieces must be the loops wholly inside. Where the curve's loops are conics (Tu cases
// with conic components: two conics crossing or disjoint, a conic and lines, a double conic)
// each lies in a rational plane of a singular member of the pencil, and whether it lies in the
// box is decided exactly, without the interval proof that a curve singular at the conics'
// crossings defeats (certify/inner_loops.hpp).
//
// How (exact arithmetic): the planes of the members theta A - B at rational roots of rank 2 (a
// plane pair, rational or conjugate over Q(sqrt D): pipes crossing at 45 degrees) or rank 1 (a
// double plane); A's section by each plane pi lies on the curve (B = theta A on pi). Over
// Q(sqrt D) every step below is exact in a + b sqrt D (signs as algebra::QuadraticNumber's). In the
// plane's chart u = (s, t) the section is u^T S u + 2 b.u + c = 0; with S definite (sign fixed so S
// > 0) and rho = b^T S^-1 b - c > 0 it is a real ellipse with centre u0 = -S^-1 b, and a coordinate
// x_k = g.u + h ranges over [m - sqrt(r), m + sqrt(r)], m = g.u0 + h, r = rho g^T S^-1 g: inside
// [lo_k, hi_k] iff hi_k - m >= 0, m - lo_k >= 0 and r <= both squared. Ellipses in one plane are
// one conic.
//
// Contract: returns the number of real ellipses wholly inside the closed box [lo, hi] when the
// ellipses found are exactly `loops` (the certified affine count of loops: then every loop is
// one of them); nullopt otherwise (a loop that is no conic of such a plane, or the basis of
// `facts` not set).
#pragma once

#include "surfcert/algebra/pencil.hpp"
#include "surfcert/core/rational.hpp"

#include <array>
#include <optional>

namespace surfcert::certify {

std::optional<int> ellipses_in_box(const algebra::PencilFacts& facts, int loops,
                                   const std::array<core::Rational, 3>& lo,
                                   const std::array<core::Rational, 3>& hi);

} // namespace surfcert::certify
