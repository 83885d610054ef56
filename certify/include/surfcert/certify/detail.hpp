// surfcert::certify::Detail: how much an answer carries, and so how much is computed for it.
//
// What it represents: the "detail" of a classify / intersect / distance answer (JSON field
// "detail" of a batch line or scene query, `--detail` on the command line).
// - classify / intersect: Topology (the decision: pencil, Tu case, morphology, Segre, root
//   pattern, components, ellipsoid relation and containment; intersect adds its branches),
//   Certificate (adds what lets someone re-check independently: the matrices, the exact f and
//   its invariants, the real roots with isolating intervals, ranks and inertias, the signature
//   sequence and the certificate's separators and indices), Full (adds the special points:
//   the answer as it always was; the default).
// - distance: Value (the enclosure, minimizers and their proof, pairs, method) or Full (adds
//   the certificate data: candidate counts and the degrees of the eliminated system; the
//   default).
// Contract: Full is byte-for-byte the answer without a detail request; a lower level only
// leaves fields out (never renames or changes one), and computes nothing it does not show
// beyond what its decision needs. The levels are ordered: Topology < Certificate < Full.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace surfcert::certify {

enum class Detail { Value, Topology, Certificate, Full };

const char* to_string(Detail d);

/// "value", "topology", "certificate" or "full" (exactly those bytes: the view need not end
/// in a NUL); nullopt otherwise. Views, so that the batch reader compares its line's bytes in
/// place (no string built, no out-of-line compare per spelling).
std::optional<Detail> parse_detail(std::string_view s);

/// Which levels an op accepts in a line or query of its own ("classify" / "intersect":
/// topology, certificate, full; "distance": value, full; other ops: none); others are input
/// errors.
bool detail_accepted(std::string_view op, Detail d);

/// The spellings accepted for an op, for error messages ("\"topology\", ... or \"full\"").
const char* detail_spellings(std::string_view op);

/// A default for every op (batch --detail): the nearest level an op has. For distance, topology
/// and certificate are the lean answer (Value); for classify / intersect, value is Topology.
Detail detail_for_op(std::string_view op, Detail d);

} // namespace surfcert::certify
