// surfcert::certify reports: the JSON result object of a classification (the oracle
// contract, documented in README.md "JSON contract") and a human-readable summary.
//
// Exact numbers travel as strings ("-729/4"); approximations as decimal strings in fields
// whose names end in "_approx". Fields are only ever added, never renamed or removed.
#pragma once

#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/error.hpp"
#include "surfcert/core/io/json.hpp"

#include <string>

namespace surfcert::certify {

/// The "result" object (status and id are added by the caller's envelope), with the fields of
/// `detail` (detail.hpp; r completed by complete_report_data at that level or higher):
/// Topology: pencil, tu_case, morphology, description, tu_label_reconstructed, segre,
/// root_pattern, components, ellipsoid_relation, containment; Certificate adds matrices,
/// pencil_basis, the characteristic polynomial and its coefficients, invariants, real_roots,
/// complex_roots, signature_sequence, definite_member, certificate; Full adds special_points
/// and special_points_complete.
core::io::Json qsic_result_json(const QsicResult& r, const core::QuadricMatrix& a,
                                const core::QuadricMatrix& b, Detail detail = Detail::Full);

/// {"status": ..., "mode": ..., "result": ...} plus "note" / "exact_fallback" when relevant,
/// and "detail" below Full.
core::io::Json qsic_envelope_json(const QsicResult& r, const core::QuadricMatrix& a,
                                  const core::QuadricMatrix& b, Detail detail = Detail::Full);

/// Appends dump(qsic_envelope_json(r, a, b, Detail::Topology)) byte for byte, written directly
/// (no document is built: the batch's lean answers; tests compare the two).
void append_qsic_topology_envelope(std::string& out, const QsicResult& r);

/// The signature sequence <I0, s1, I1, ...>, multiple roots wrapped in m parentheses.
std::string signature_sequence(const algebra::PencilFacts& f);

/// A few lines for a person.
std::string qsic_result_text(const QsicResult& r, const core::QuadricMatrix& a,
                             const core::QuadricMatrix& b);

/// Error object {"kind": ..., "message": ..., "source", "line", "column", "json_path",
/// "expected", "found"} for an InputError.
core::io::Json input_error_json(const core::InputError& e);

} // namespace surfcert::certify
