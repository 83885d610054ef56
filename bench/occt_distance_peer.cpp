// occt_distance_peer.cpp: see occt_distance_peer.hpp. Geom level only (Geom_*, GeomConvert,
// GeomAPI_ExtremaSurfaceSurface): Debian 12's OCCT 7.6.3 dev package lacks
// NCollection_AliasedArray.hxx, which the BRep headers include.
#include "occt_distance_peer.hpp"

#include <GeomAPI_ExtremaSurfaceSurface.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Standard_Failure.hxx>
#include <gp_Ax3.hxx>
#include <gp_Pnt.hxx>

#include <chrono>
#include <exception>

namespace surfcert::bench {

namespace {

// The unit sphere as a rational B-spline surface, converted once.
const Handle(Geom_BSplineSurface) & unit_sphere() {
  static const Handle(Geom_BSplineSurface) s = GeomConvert::SurfaceToBSplineSurface(
      new Geom_SphericalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), 1.0));
  return s;
}

Handle(Geom_Surface) ellipsoid_surface(const EllipsoidParams& e) {
  Handle(Geom_BSplineSurface) s = Handle(Geom_BSplineSurface)::DownCast(unit_sphere()->Copy());
  for (int i = 1; i <= s->NbUPoles(); ++i)
    for (int j = 1; j <= s->NbVPoles(); ++j) {
      const gp_Pnt& p = s->Pole(i, j);
      const double l[3] = {e.radii[0] * p.X(), e.radii[1] * p.Y(), e.radii[2] * p.Z()};
      double w[3];
      for (size_t k = 0; k < 3; ++k)
        w[k] = e.centre[k] + e.rotation[k][0] * l[0] + e.rotation[k][1] * l[1] +
               e.rotation[k][2] * l[2];
      s->SetPole(i, j, gp_Pnt(w[0], w[1], w[2])); // keeps the weight
    }
  return s;
}

Handle(Geom_Surface) torus_surface(const TorusParams& t) {
  const gp_Ax3 ax(gp_Pnt(t.centre[0], t.centre[1], t.centre[2]),
                  gp_Dir(t.rotation[0][2], t.rotation[1][2], t.rotation[2][2]),
                  gp_Dir(t.rotation[0][0], t.rotation[1][0], t.rotation[2][0]));
  return new Geom_ToroidalSurface(ax, t.major, t.minor);
}

std::array<double, 3> to_array(const gp_Pnt& p) {
  return {p.X(), p.Y(), p.Z()};
}

OcctDistanceResult extrema(const Handle(Geom_Surface) & s1, const Handle(Geom_Surface) & s2) {
  OcctDistanceResult r;
  auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&t0] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  try {
    GeomAPI_ExtremaSurfaceSurface ext(s1, s2);
    r.extrema = ext.NbExtrema();
    r.parallel = ext.Extrema().IsParallel();
    if (r.extrema > 0) {
      r.distance = ext.LowerDistance();
      gp_Pnt p1, p2;
      ext.NearestPoints(p1, p2);
      r.seconds = elapsed();
      r.p1 = to_array(p1);
      r.p2 = to_array(p2);
      r.ok = true;
    } else {
      r.seconds = elapsed();
      r.error = r.parallel ? "no extremum (parallel)" : "no extremum";
    }
  } catch (const Standard_Failure& f) {
    r.seconds = elapsed();
    r.error =
        std::string("Standard_Failure: ") + (f.GetMessageString() ? f.GetMessageString() : "");
  } catch (const std::exception& x) {
    r.seconds = elapsed();
    r.error = x.what();
  } catch (...) {
    r.seconds = elapsed();
    r.error = "unknown exception";
  }
  return r;
}

} // namespace

OcctDistanceResult occt_distance(const EllipsoidParams& e1, const EllipsoidParams& e2) {
  try {
    return extrema(ellipsoid_surface(e1), ellipsoid_surface(e2));
  } catch (const Standard_Failure& f) { // surface construction
    OcctDistanceResult r;
    r.error =
        std::string("Standard_Failure: ") + (f.GetMessageString() ? f.GetMessageString() : "");
    return r;
  }
}

OcctDistanceResult occt_distance(const EllipsoidParams& e, const TorusParams& t) {
  try {
    return extrema(ellipsoid_surface(e), torus_surface(t));
  } catch (const Standard_Failure& f) { // surface construction (e.g. major <= minor)
    OcctDistanceResult r;
    r.error =
        std::string("Standard_Failure: ") + (f.GetMessageString() ? f.GetMessageString() : "");
    return r;
  }
}

} // namespace surfcert::bench
