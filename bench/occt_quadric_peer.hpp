// occt_quadric_peer: the intersection curve of two quadric surfaces of any natural kind computed
// by Open CASCADE inside an axis-aligned box (benchmark peer only; nothing in surfcert depends
// on it; no OCCT header here, only occt_quadric_peer.cpp needs OCCT).
//
// Each surface is given in its own frame (origin, orthonormal x/y/z directions in world
// coordinates) and built as OCCT's analytic surface where OCCT has one (Geom_Plane,
// Geom_SphericalSurface, Geom_CylindricalSurface, Geom_ConicalSurface); an ellipsoid is the
// unit sphere's rational B-spline with its poles scaled (as in occt_peer.hpp); a paraboloid or
// a one-sheet hyperboloid is a Geom_SurfaceOfRevolution of a Geom_Parabola / Geom_Hyperbola
// (Geom has no analytic paraboloid or hyperboloid). Unbounded surfaces are trimmed
// (Geom_RectangularTrimmedSurface) to parameter ranges that cover the box, then
// GeomAPI_IntSS(s1, s2, tol) runs (timed alone). The lines it returns are sampled and clipped
// to the box (outside the timing): `pieces` counts the connected pieces inside the box after
// joining pieces whose ends coincide, `closed_pieces` those that close up.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace surfcert::bench {

struct PeerSurface {
  enum class Kind { Plane, Sphere, Cylinder, Cone, Ellipsoid, Paraboloid, Hyperboloid1 };
  Kind kind = Kind::Plane;
  std::array<double, 3> origin{};              ///< centre / apex / vertex / point of plane
  std::array<std::array<double, 3>, 3> axes{}; ///< world directions of local x, y, z
  double a = 1, b = 1, c = 1;                  ///< see below
  // Local equations (x, y, z in the frame): plane z = 0; sphere |x| = a; cylinder
  // x^2 + y^2 = a^2; cone x^2 + y^2 = (a z)^2 (a = tan of the half-angle); ellipsoid
  // (x/a)^2 + (y/b)^2 + (z/c)^2 = 1; paraboloid z = a (x^2 + y^2);
  // hyperboloid (x^2 + y^2) / a^2 - z^2 / c^2 = 1.
};

struct OcctBoxResult {
  bool ok = false;
  double seconds = 0;     ///< GeomAPI_IntSS only (surfaces built before the clock starts)
  double cpu_seconds = 0; ///< the same span in this thread's CPU time (insensitive to load)
  int lines = 0;          ///< NbLines()
  int pieces = 0;         ///< connected pieces inside the box, coincident ends joined
  int closed_pieces = 0;
  std::string error;
};

OcctBoxResult occt_intersect_in_box(const PeerSurface& s1, const PeerSurface& s2,
                                    const std::array<double, 3>& box_min,
                                    const std::array<double, 3>& box_max, double tol);

} // namespace surfcert::bench
