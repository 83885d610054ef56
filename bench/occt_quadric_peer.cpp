// occt_quadric_peer.cpp: see occt_quadric_peer.hpp. Geom level only (no BRep: Debian 12's
// OCCT 7.6.3 dev package lacks a header the BRep headers include, see occt_peer.cpp).
#include "occt_quadric_peer.hpp"

#include <GeomAPI_IntSS.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_Curve.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Hyperbola.hxx>
#include <Geom_Parabola.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Ax3.hxx>
#include <gp_Pnt.hxx>

#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <numeric>
#include <vector>

namespace surfcert::bench {

namespace {

// This thread's CPU time in seconds (the machine is shared: wall time counts other work).
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

using V = std::array<double, 3>;

gp_Dir dir(const V& v) {
  return gp_Dir(v[0], v[1], v[2]);
}

gp_Pnt pnt(const V& v) {
  return gp_Pnt(v[0], v[1], v[2]);
}

V neg(const V& v) {
  return {-v[0], -v[1], -v[2]};
}

// The surface, trimmed so that it covers the ball of radius `reach` around its own origin.
Handle(Geom_Surface) make_surface(const PeerSurface& s, double reach) {
  using K = PeerSurface::Kind;
  const gp_Ax3 frame(pnt(s.origin), dir(s.axes[2]), dir(s.axes[0]));
  switch (s.kind) {
  case K::Plane:
    return new Geom_RectangularTrimmedSurface(new Geom_Plane(frame), -reach, reach, -reach, reach);
  case K::Sphere:
    return new Geom_SphericalSurface(frame, s.a);
  case K::Cylinder:
    return new Geom_RectangularTrimmedSurface(new Geom_CylindricalSurface(frame, s.a), -reach,
                                              reach, false);
  case K::Cone: // v: the distance along a generatrix from the apex (both nappes)
    return new Geom_RectangularTrimmedSurface(new Geom_ConicalSurface(frame, std::atan(s.a), 0.0),
                                              -reach, reach, false);
  case K::Ellipsoid: {
    static const Handle(Geom_BSplineSurface) unit = GeomConvert::SurfaceToBSplineSurface(
        new Geom_SphericalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), 1.0));
    Handle(Geom_BSplineSurface) e = Handle(Geom_BSplineSurface)::DownCast(unit->Copy());
    const double r[3] = {s.a, s.b, s.c};
    for (int i = 1; i <= e->NbUPoles(); ++i)
      for (int j = 1; j <= e->NbVPoles(); ++j) {
        const gp_Pnt& p = e->Pole(i, j);
        const double l[3] = {r[0] * p.X(), r[1] * p.Y(), r[2] * p.Z()};
        V w = s.origin;
        for (size_t k = 0; k < 3; ++k)
          for (size_t m = 0; m < 3; ++m)
            w[k] += s.axes[m][k] * l[m];
        e->SetPole(i, j, pnt(w)); // keeps the weight
      }
    return e;
  }
  case K::Paraboloid: {
    // Meridian z = a x^2 in the local xz plane: a parabola with axis z (XDirection) and
    // YDirection x (= y cross z), focal length 1 / (4a); revolved about z.
    Handle(Geom_Parabola) p =
        new Geom_Parabola(gp_Ax2(pnt(s.origin), dir(s.axes[1]), dir(s.axes[2])), 1.0 / (4 * s.a));
    // The meridian itself trimmed (OCCT evaluates the basis curve far out otherwise).
    return new Geom_SurfaceOfRevolution(new Geom_TrimmedCurve(p, 0, reach),
                                        gp_Ax1(pnt(s.origin), dir(s.axes[2])));
  }
  case K::Hyperboloid1: {
    // Meridian x^2/a^2 - z^2/c^2 = 1: XDirection x, YDirection z (= -y cross x).
    Handle(Geom_Hyperbola) h =
        new Geom_Hyperbola(gp_Ax2(pnt(s.origin), dir(neg(s.axes[1])), dir(s.axes[0])), s.a, s.c);
    const double v = std::asinh(reach / s.c);
    // The meridian trimmed: on the untrimmed hyperbola OCCT's walking evaluates cosh far out
    // and throws ("Result of Cosh exceeds the maximum value Standard_Real").
    return new Geom_SurfaceOfRevolution(new Geom_TrimmedCurve(h, -v, v),
                                        gp_Ax1(pnt(s.origin), dir(s.axes[2])));
  }
  }
  return nullptr;
}

double dist(const V& p, const V& q) {
  return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                   (p[2] - q[2]) * (p[2] - q[2]));
}

struct End {
  V p, out; ///< the end point and the unit direction leaving the piece there
  int piece;
};

} // namespace

OcctBoxResult occt_intersect_in_box(const PeerSurface& s1, const PeerSurface& s2, const V& box_min,
                                    const V& box_max, double tol) {
  OcctBoxResult r;
  V centre;
  double diag2 = 0;
  for (size_t k = 0; k < 3; ++k) {
    centre[k] = 0.5 * (box_min[k] + box_max[k]);
    diag2 += (box_max[k] - box_min[k]) * (box_max[k] - box_min[k]);
  }
  const double diag = std::sqrt(diag2);
  auto inside = [&](const V& p) {
    const double slack = 1e-12 * diag;
    for (size_t k = 0; k < 3; ++k)
      if (p[k] < box_min[k] - slack || p[k] > box_max[k] + slack) return false;
    return true;
  };
  auto t0 = std::chrono::steady_clock::now();
  double c0 = thread_cpu_seconds();
  try {
    Handle(Geom_Surface) g1 = make_surface(s1, dist(s1.origin, centre) + diag);
    Handle(Geom_Surface) g2 = make_surface(s2, dist(s2.origin, centre) + diag);
    t0 = std::chrono::steady_clock::now();
    c0 = thread_cpu_seconds();
    GeomAPI_IntSS inter(g1, g2, tol);
    r.ok = inter.IsDone();
    r.lines = r.ok ? inter.NbLines() : 0;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.cpu_seconds = thread_cpu_seconds() - c0;

    // Pieces inside the box: each line sampled densely (an infinite parameter range through
    // u = tan(s)), maximal runs of samples inside the box kept.
    std::vector<std::vector<V>> runs;
    for (int i = 1; i <= r.lines; ++i) {
      const Handle(Geom_Curve)& c = inter.Line(i);
      double u0 = c->FirstParameter(), u1 = c->LastParameter();
      const bool infinite = Precision::IsInfinite(u0) || Precision::IsInfinite(u1);
      const int n = infinite ? 40000 : 8000;
      std::vector<V> run;
      for (int k = 0; k <= n; ++k) {
        double u;
        if (infinite) {
          const double s = -M_PI / 2 + M_PI * (k + 0.5) / (n + 1);
          u = diag * std::tan(s);
        } else {
          u = u0 + (u1 - u0) * k / n;
        }
        const gp_Pnt g = c->Value(u);
        const V p{g.X(), g.Y(), g.Z()};
        if (inside(p)) {
          run.push_back(p);
        } else if (!run.empty()) {
          runs.push_back(std::move(run));
          run.clear();
        }
      }
      if (!run.empty()) runs.push_back(std::move(run));
    }
    // Join pieces whose ends coincide and continue each other (opposite leaving directions):
    // OCCT cuts a closed branch at seams; two branches crossing at a point stay apart.
    std::vector<End> ends;
    for (size_t i = 0; i < runs.size(); ++i) {
      const auto& run = runs[i];
      if (run.size() < 2) continue;
      auto out = [](const V& a, const V& b) {
        V d{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
        const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (double& x : d)
          x = n > 0 ? x / n : 0;
        return d;
      };
      ends.push_back({run.front(), out(run[0], run[1]), static_cast<int>(i)});
      ends.push_back(
          {run.back(), out(run[run.size() - 1], run[run.size() - 2]), static_cast<int>(i)});
    }
    std::vector<int> parent(runs.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&parent](int x) {
      while (parent[static_cast<size_t>(x)] != x)
        x = parent[static_cast<size_t>(x)] =
            parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
      return x;
    };
    const double glue = std::max(1e-6 * diag, 100 * tol);
    std::vector<bool> matched(ends.size(), false);
    for (size_t e = 0; e < ends.size(); ++e) {
      if (matched[e]) continue;
      size_t best = ends.size();
      double best_d = glue;
      for (size_t f = 0; f < ends.size(); ++f) {
        if (f == e || matched[f]) continue;
        const double d = dist(ends[e].p, ends[f].p);
        const double dot = ends[e].out[0] * ends[f].out[0] + ends[e].out[1] * ends[f].out[1] +
                           ends[e].out[2] * ends[f].out[2];
        if (d <= best_d && dot < -0.7) best = f, best_d = d;
      }
      if (best == ends.size()) continue;
      matched[e] = matched[best] = true;
      parent[static_cast<size_t>(find(ends[e].piece))] = find(ends[best].piece);
    }
    std::vector<int> free_ends(runs.size(), 0);
    for (size_t e = 0; e < ends.size(); ++e)
      if (!matched[e]) ++free_ends[static_cast<size_t>(find(ends[e].piece))];
    for (size_t i = 0; i < runs.size(); ++i)
      if (runs[i].size() >= 2 && find(static_cast<int>(i)) == static_cast<int>(i)) {
        ++r.pieces;
        r.closed_pieces += free_ends[i] == 0;
      }
  } catch (const Standard_Failure& f) {
    r.ok = false;
    r.error =
        std::string("Standard_Failure: ") + (f.GetMessageString() ? f.GetMessageString() : "");
  } catch (const std::exception& x) {
    r.ok = false;
    r.error = x.what();
  } catch (...) {
    r.ok = false;
    r.error = "unknown exception";
  }
  if (!r.ok && r.seconds == 0) {
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.cpu_seconds = thread_cpu_seconds() - c0;
  }
  return r;
}

} // namespace surfcert::bench
