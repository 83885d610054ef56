// fcl_peer.cpp: see fcl_peer.hpp. The only translation unit that includes FCL (and Eigen).
#include "fcl_peer.hpp"

#include <fcl/config.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <chrono>
#include <exception>

namespace surfcert::bench {

namespace {

fcl::Transform3d placement(const EllipsoidParams& e) {
  fcl::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r(i, j) = e.rotation[static_cast<size_t>(i)][static_cast<size_t>(j)];
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = r;
  tf.translation() = fcl::Vector3d(e.centre[0], e.centre[1], e.centre[2]);
  return tf;
}

std::array<double, 3> to_array(const fcl::Vector3d& v) {
  return {v[0], v[1], v[2]};
}

} // namespace

FclResult fcl_distance(const EllipsoidParams& e1, const EllipsoidParams& e2,
                       const FclOptions& options) {
  FclResult r;
  const fcl::Ellipsoidd s1(e1.radii[0], e1.radii[1], e1.radii[2]);
  const fcl::Ellipsoidd s2(e2.radii[0], e2.radii[1], e2.radii[2]);
  const fcl::Transform3d tf1 = placement(e1), tf2 = placement(e2);
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  request.enable_signed_distance = options.signed_distance;
  request.distance_tolerance = options.tolerance;
  request.gjk_solver_type = options.solver == FclSolver::Libccd ? fcl::GST_LIBCCD : fcl::GST_INDEP;
  fcl::DistanceResultd result;
  auto t0 = std::chrono::steady_clock::now();
  try {
    fcl::distance(&s1, tf1, &s2, tf2, request, result);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.ok = true;
    r.distance = result.min_distance;
    r.p1 = to_array(result.nearest_points[0]);
    r.p2 = to_array(result.nearest_points[1]);
  } catch (const std::exception& x) {
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.error = x.what();
  } catch (...) {
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.error = "unknown exception";
  }
  return r;
}

FclCollideResult fcl_collide(const EllipsoidParams& e1, const EllipsoidParams& e2) {
  FclCollideResult r;
  const fcl::Ellipsoidd s1(e1.radii[0], e1.radii[1], e1.radii[2]);
  const fcl::Ellipsoidd s2(e2.radii[0], e2.radii[1], e2.radii[2]);
  const fcl::Transform3d tf1 = placement(e1), tf2 = placement(e2);
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  try {
    fcl::collide(&s1, tf1, &s2, tf2, request, result);
    r.collide = result.isCollision();
    r.ok = true;
  } catch (const std::exception& x) {
    r.error = x.what();
  } catch (...) {
    r.error = "unknown exception";
  }
  return r;
}

std::string fcl_version() {
  return std::string("FCL ") + FCL_VERSION;
}

const char* fcl_solver_name(FclSolver s) {
  return s == FclSolver::Libccd ? "libccd" : "indep";
}

} // namespace surfcert::bench
