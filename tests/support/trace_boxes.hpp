// Helpers shared by the tracer's box tests: trace options with a given box (the curve is
// clipped to [lo, hi], its exits on the box's faces counted), instead of the automatic one.
#pragma once

#include "surfcert/trace/intersect_curve.hpp"

namespace surfcert::testing {

/// Default trace options but for the box [lo, hi] (componentwise lo <= hi).
inline trace::TraceOptions given_box(trace::Point3 lo, trace::Point3 hi) {
  trace::TraceOptions opt;
  trace::Box box;
  box.min = lo;
  box.max = hi;
  opt.box = box;
  return opt;
}

} // namespace surfcert::testing
