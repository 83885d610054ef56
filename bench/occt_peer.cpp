// occt_peer.cpp: see occt_peer.hpp. Geom level only (Geom_*, GeomConvert, GeomAPI_IntSS,
// TColgp arrays): Debian 12's OCCT 7.6.3 dev package lacks NCollection_AliasedArray.hxx,
// which the BRep headers include.
#include "occt_peer.hpp"

#include <GeomAPI_IntSS.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Curve.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>
#include <gp_Ax3.hxx>
#include <gp_Pnt.hxx>

#include <chrono>
#include <exception>
#include <vector>

namespace surfcert::bench {

namespace {

// The unit sphere as a rational B-spline surface, converted once.
const Handle(Geom_BSplineSurface) & unit_sphere() {
  static const Handle(Geom_BSplineSurface) s = GeomConvert::SurfaceToBSplineSurface(
      new Geom_SphericalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), 1.0));
  return s;
}

Handle(Geom_BSplineSurface) ellipsoid_surface(const EllipsoidParams& e) {
  Handle(Geom_BSplineSurface) s = Handle(Geom_BSplineSurface)::DownCast(unit_sphere()->Copy());
  for (int i = 1; i <= s->NbUPoles(); ++i)
    for (int j = 1; j <= s->NbVPoles(); ++j) {
      const gp_Pnt& p = s->Pole(i, j);
      double l[3] = {e.radii[0] * p.X(), e.radii[1] * p.Y(), e.radii[2] * p.Z()};
      double w[3];
      for (int k = 0; k < 3; ++k)
        w[k] = e.centre[static_cast<size_t>(k)] + e.rotation[static_cast<size_t>(k)][0] * l[0] +
               e.rotation[static_cast<size_t>(k)][1] * l[1] +
               e.rotation[static_cast<size_t>(k)][2] * l[2];
      s->SetPole(i, j, gp_Pnt(w[0], w[1], w[2])); // keeps the weight
    }
  return s;
}

} // namespace

OcctResult occt_intersect(const EllipsoidParams& e1, const EllipsoidParams& e2, double tol,
                          int samples) {
  OcctResult r;
  auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&t0] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  try {
    Handle(Geom_BSplineSurface) s1 = ellipsoid_surface(e1);
    Handle(Geom_BSplineSurface) s2 = ellipsoid_surface(e2);
    t0 = std::chrono::steady_clock::now();
    GeomAPI_IntSS inter(s1, s2, tol);
    r.ok = inter.IsDone();
    r.branches = r.ok ? inter.NbLines() : 0;
    r.seconds = elapsed();
    // Diagnostics: closed lines, and components after gluing coincident ends (union-find).
    const double glue = 10 * tol;
    std::vector<gp_Pnt> ends; // 2 per line
    std::vector<int> parent(static_cast<size_t>(r.branches));
    for (int i = 0; i < r.branches; ++i) {
      parent[static_cast<size_t>(i)] = i;
      const Handle(Geom_Curve)& c = inter.Line(i + 1);
      gp_Pnt a = c->Value(c->FirstParameter()), b = c->Value(c->LastParameter());
      if (a.Distance(b) <= glue) ++r.closed_branches;
      ends.push_back(a);
      ends.push_back(b);
    }
    auto find = [&parent](int x) {
      while (parent[static_cast<size_t>(x)] != x)
        x = parent[static_cast<size_t>(x)] =
            parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
      return x;
    };
    for (size_t p = 0; p < ends.size(); ++p)
      for (size_t q = p + 1; q < ends.size(); ++q)
        if (p / 2 != q / 2 && ends[p].Distance(ends[q]) <= glue)
          parent[static_cast<size_t>(find(static_cast<int>(p / 2)))] =
              find(static_cast<int>(q / 2));
    for (int i = 0; i < r.branches; ++i)
      r.glued_branches += find(i) == i;
    for (int i = 0; samples > 0 && i < r.branches; ++i) {
      const Handle(Geom_Curve)& c = inter.Line(i + 1);
      const double u0 = c->FirstParameter(), u1 = c->LastParameter();
      r.polylines.emplace_back();
      for (int k = 0; k <= samples; ++k) {
        const gp_Pnt p = c->Value(u0 + (u1 - u0) * k / samples);
        r.polylines.back().push_back({p.X(), p.Y(), p.Z()});
      }
    }
  } catch (const Standard_Failure& f) {
    r.ok = false;
    r.seconds = elapsed();
    r.error =
        std::string("Standard_Failure: ") + (f.GetMessageString() ? f.GetMessageString() : "");
  } catch (const std::exception& x) {
    r.ok = false;
    r.seconds = elapsed();
    r.error = x.what();
  } catch (...) {
    r.ok = false;
    r.seconds = elapsed();
    r.error = "unknown exception";
  }
  return r;
}

std::string occt_version() {
  return std::string("Open CASCADE ") + OCC_VERSION_COMPLETE;
}

} // namespace surfcert::bench
