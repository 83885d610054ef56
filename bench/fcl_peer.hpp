// fcl_peer: the distance between two ellipsoids computed by FCL 0.7 (the Flexible Collision
// Library; benchmark peer only, nothing in surfcert depends on it). No FCL header is included
// here, so callers compile without FCL; only fcl_peer.cpp needs it (CMake option
// SURFCERT_BENCH_FCL).
//
// Each ellipsoid is an fcl::Ellipsoidd(radii) placed by the rigid transform centre + rotation;
// fcl::distance(geometry1, tf1, geometry2, tf2, request, result) with
// DistanceRequest::enable_nearest_points = true. FCL treats shapes as SOLIDS (convex bodies):
// when the bodies overlap (surfaces crossing, or one ellipsoid inside the other) the unsigned
// query returns exactly -1 (libccd: "GJK found an intersection"; indep: GJK status not Valid)
// and the signed query an EPA penetration depth (negative), never the distance between the
// surfaces. Only for disjoint bodies is the result the surface distance.
//
// Relevant DistanceRequest fields (fcl/narrowphase/distance_request.h, FCL 0.7.0):
//   distance_tolerance (default 1e-6): GJK stops when an iteration improves the distance by
//     less than this; it is NOT an error bound (GJK converges slowly on curved bodies);
//   gjk_solver_type (default GST_LIBCCD; or GST_INDEP, FCL's own GJK/EPA);
//   enable_signed_distance (default false);
//   rel_err / abs_err: used only by BVH (mesh) traversals, ignored for shape-shape pairs.
// The iteration caps are not request fields: libccd max_distance_iterations = 1000,
// indep gjk_max_iterations = 128 (solver defaults, kept).
// seconds: the wall time of fcl::distance only (shape and transform construction excluded).
#pragma once

#include "ellipsoid_params.hpp"

#include <array>
#include <string>

namespace surfcert::bench {

enum class FclSolver { Libccd, Indep }; ///< fcl::GST_LIBCCD, fcl::GST_INDEP

struct FclOptions {
  double tolerance = 1e-6; ///< DistanceRequest::distance_tolerance (FCL's default 1e-6)
  FclSolver solver = FclSolver::Libccd;
  bool signed_distance = false; ///< DistanceRequest::enable_signed_distance
};

struct FclResult {
  double distance = 0; ///< DistanceResult::min_distance (-1 or <= 0 when the solids overlap)
  std::array<double, 3> p1{}, p2{}; ///< DistanceResult::nearest_points (world frame)
  double seconds = 0;
  bool ok = false;   ///< no exception
  std::string error; ///< exception text when FCL threw
};

FclResult fcl_distance(const EllipsoidParams& e1, const EllipsoidParams& e2,
                       const FclOptions& options = {});

/// fcl::collide(geometry1, tf1, geometry2, tf2, request, result) with a default CollisionRequest
/// (one contact, GJK solver libccd): do the SOLIDS overlap (touching counts as colliding within
/// libccd's tolerance)? ok = false (error set) when FCL threw.
struct FclCollideResult {
  bool collide = false;
  bool ok = false;
  std::string error;
};
FclCollideResult fcl_collide(const EllipsoidParams& e1, const EllipsoidParams& e2);

/// "FCL 0.7.0" (the version compiled against).
std::string fcl_version();

/// "libccd" or "indep".
const char* fcl_solver_name(FclSolver s);

} // namespace surfcert::bench
