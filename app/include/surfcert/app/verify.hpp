// surfcert::app::verify_claims: certified verdicts on another program's claims about a pair of
// surfaces (issue 13: relation, solids_collide, morphology, tu_case, components, distance,
// closest_points, curve).
//
// What it represents: for each claim, in claim order, a verdict
//   "confirmed"  the claim is proven true (within its stated tolerance),
//   "refuted"    the claim is proven false, with a "counterexample" the caller can check
//                (the certified value, relation or enclosure that contradicts it),
//   "undecided"  neither could be proven; "established" says what was proven instead.
// A verdict is never a guess: every decision reads a certified answer of the engine
// (classify_qsic with status Certified, complete_report_data's ellipsoid relation, or a
// certified Enclosure of surface_distance) or a checkable certificate on claimed points
// (claim_geometry.hpp: sign-change segments, point-surface distance bounds, Krawczyk boxes of
// curve points), and distances are compared as exact rationals on the printed
// (outward-rounded) bounds, so the counterexample the caller sees proves it. A curve claim is
// confirmed only through a coverage subdivision (claim_geometry.hpp), when a or b is an
// ellipsoid; the float tracer's branches only propose points to certify.
//
// Contract: verify_claims validates every claim before computing anything; a bad claim
// (unknown kind, wrong value type, negative tolerance, a quadric-only claim on a torus, no
// claims) throws core::InputError with its JSON path ($.claims[i]..., or
// $.queries[q].claims[i]... in a scene). It returns
// {"status": "certified" | "undecided", "result": {"verdicts": [...]}}: "certified" when
// every verdict is decided. Work is shared between claims (one classification, one distance
// per kind and precision) and a distance claim refines only until it is decided (digits from
// its tolerance, at most kMaxVerifyDigits). The caller's core::BudgetScope is honoured: past
// it the remaining verdicts are undecided with note "budget".
#pragma once

#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/surface.hpp"

#include <string>

namespace surfcert::app {

/// The most working digits a distance claim refines to before answering undecided.
constexpr long kMaxVerifyDigits = 100;

/// Verdicts on the claims of `line` (its "claims" array, JSON path path + ".claims": a batch
/// line is "$", a scene query "$.queries[i]") about surfaces a and b. Throws
/// core::InputError on a bad or missing claim.
core::io::Json verify_claims(const core::Surface& a, const core::Surface& b,
                             const core::io::Json& line, const std::string& source,
                             certify::Mode mode, const std::string& path = "$");

/// Validates the claims of `query` as verify_claims does, computing nothing (a scene is
/// checked whole before any query runs). Throws core::InputError.
void check_claims(const core::Surface& a, const core::Surface& b, const core::io::Json& query,
                  const std::string& source, const std::string& path);

} // namespace surfcert::app
