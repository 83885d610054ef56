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

/// The "result" object (status and id are added by the caller's envelope).
core::io::Json qsic_result_json(const QsicResult& r, const core::QuadricMatrix& a,
                                const core::QuadricMatrix& b);

/// {"status": ..., "mode": ..., "result": ...} plus "note" / "exact_fallback" when relevant.
core::io::Json qsic_envelope_json(const QsicResult& r, const core::QuadricMatrix& a,
                                  const core::QuadricMatrix& b);

/// The signature sequence <I0, s1, I1, ...>, multiple roots wrapped in m parentheses.
std::string signature_sequence(const algebra::PencilFacts& f);

/// A few lines for a person.
std::string qsic_result_text(const QsicResult& r, const core::QuadricMatrix& a,
                             const core::QuadricMatrix& b);

/// Error object {"kind": ..., "message": ..., "source", "line", "column", "json_path",
/// "expected", "found"} for an InputError.
core::io::Json input_error_json(const core::InputError& e);

} // namespace surfcert::certify
