// occt_peer: the intersection curve of two ellipsoids computed by Open CASCADE (benchmark
// peer only; nothing in surfcert depends on it). No OCCT header is included here, so callers
// compile without OCCT; only occt_peer.cpp needs it (CMake option SURFCERT_BENCH_OCCT).
//
// Each ellipsoid is the unit Geom_SphericalSurface converted by
// GeomConvert::SurfaceToBSplineSurface (rational, weights unchanged) whose poles are mapped by
// p -> centre + rotation * diag(radii) * p (affine maps commute with rational B-splines),
// then GeomAPI_IntSS(s1, s2, tol). Branches = NbLines(), ok = IsDone() and no exception.
// seconds: the wall time of GeomAPI_IntSS (construction + NbLines), not of building the
// B-spline surfaces.
#pragma once

#include "ellipsoid_params.hpp"

#include <array>
#include <string>
#include <vector>

namespace surfcert::bench {

struct OcctResult {
  int branches = 0;
  bool ok = false;
  double seconds = 0;
  // Diagnostics, computed outside the timing. GeomAPI_IntSS often returns one closed branch
  // as several open pieces (cut where the walking line meets the B-spline's seam or poles).
  int closed_branches = 0; ///< lines whose two ends coincide (within 10 * tol)
  int glued_branches = 0;  ///< connected components after joining lines whose ends coincide
  std::string error;       ///< exception text when OCCT threw
  /// Each line sampled at `samples` + 1 equally spaced parameters (when samples > 0; outside
  /// the timing).
  std::vector<std::vector<std::array<double, 3>>> polylines;
};

OcctResult occt_intersect(const EllipsoidParams& e1, const EllipsoidParams& e2, double tol,
                          int samples = 0);

/// "Open CASCADE 7.6.3" (the version compiled against).
std::string occt_version();

} // namespace surfcert::bench
