// run_our_tracer: the surfcert side of trace_bench after the topology: trace every branch of
// the intersection curve of a and b to tolerance `tol` and return how many curve branches
// (loops, conics, lines, ...; isolated points not counted) it produced, or -1 when the tracer
// is not available in this build. `topology` is the classify_qsic result already computed
// (filtered mode) for the same pair, so the tracer need not classify again.
#pragma once

#include "surfcert/certify/qsic.hpp"
#include "surfcert/core/quadric.hpp"

namespace surfcert::bench {

int run_our_tracer(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                   const certify::QsicResult& topology, double tol,
                   bool* exact_start_points = nullptr);

} // namespace surfcert::bench
