// occt_distance_peer: the minimum distance between two ellipsoid SURFACES (or an ellipsoid and
// a torus) computed by Open CASCADE (benchmark peer only; nothing in surfcert depends on it).
// No OCCT header is included here; only occt_distance_peer.cpp needs OCCT (CMake option
// SURFCERT_BENCH_OCCT).
//
// Each ellipsoid is built as in occt_peer.cpp: the unit Geom_SphericalSurface converted by
// GeomConvert::SurfaceToBSplineSurface, poles mapped by p -> centre + rotation * diag(radii) * p.
// A torus is a Geom_ToroidalSurface. GeomAPI_ExtremaSurfaceSurface(s1, s2) over the full
// parameter ranges; distance = LowerDistance() (the minimum over its NbExtrema() extrema),
// p1/p2 = NearestPoints(). Surfaces, not solids: a nested pair gives the positive gap, a
// crossing pair should give ~0. GeomAPI_ExtremaSurfaceSurface takes no tolerance (OCCT's
// Precision::Confusion/PConfusion internally).
// seconds: the wall time of GeomAPI_ExtremaSurfaceSurface (construction + LowerDistance +
// NearestPoints), not of building the surfaces.
#pragma once

#include "ellipsoid_params.hpp"

#include <array>
#include <string>

namespace surfcert::bench {

/// The torus { c + rotation * q : q at distance minor from the circle of radius major in the
/// local xy-plane }: axis = rotation's third column, reference direction = its first column.
struct TorusParams {
  std::array<double, 3> centre{};
  std::array<std::array<double, 3>, 3> rotation{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  double major = 0, minor = 0;
};

struct OcctDistanceResult {
  double distance = 0;              ///< LowerDistance()
  std::array<double, 3> p1{}, p2{}; ///< NearestPoints()
  int extrema = 0;                  ///< NbExtrema()
  bool parallel = false;            ///< Extrema().IsParallel()
  double seconds = 0;
  bool ok = false;   ///< at least one extremum and no exception
  std::string error; ///< exception text, or "no extremum"
};

OcctDistanceResult occt_distance(const EllipsoidParams& e1, const EllipsoidParams& e2);

OcctDistanceResult occt_distance(const EllipsoidParams& e, const TorusParams& t);

} // namespace surfcert::bench
