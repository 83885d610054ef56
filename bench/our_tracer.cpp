// our_tracer.cpp: the surfcert side of trace_bench after the topology: trace::trace_curve
// (branches from the already computed topology; conics from singular members, quartic
// branches marched from exact extreme points).
#include "our_tracer.hpp"

#include "surfcert/trace/intersect_curve.hpp"

namespace surfcert::bench {

int run_our_tracer(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                   const certify::QsicResult& topology, double tol, bool* exact_start_points) {
  trace::TraceOptions opt;
  opt.tolerance = tol;
  auto r = trace::trace_curve(a, b, topology, opt);
  if (exact_start_points) *exact_start_points = r.exact_start_points;
  if (r.status != certify::Status::Certified) return -2; // branches do not match the topology
  return static_cast<int>(r.branches.size());
}

} // namespace surfcert::bench
