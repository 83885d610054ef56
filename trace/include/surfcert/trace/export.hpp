// surfcert::trace exports of traced curves: OBJ and PLY polylines (plus isolated points) and
// an SVG picture (three orthographic views with the surfaces' outlines, the curves, the
// special points marked, and the topology in the caption).
#pragma once

#include "surfcert/trace/curve.hpp"

#include <optional>
#include <string>
#include <vector>

namespace surfcert::trace {

struct Picture {
  std::vector<Branch> branches;
  std::vector<Point3> special_points;
  std::string caption;    ///< e.g. "case 5 figure_eight: ... (certified)"
  std::optional<Box> box; ///< the box the curve was traced in: the panels show it
};

/// Wavefront OBJ text: "v" lines, one "l" element per branch (closed ones repeat the first
/// vertex), isolated points as "p" elements.
std::string to_obj(const std::vector<Branch>& branches, const std::vector<Point3>& points);

/// ASCII PLY text: vertices, one edge per consecutive pair of polyline points.
std::string to_ply(const std::vector<Branch>& branches, const std::vector<Point3>& points);

/// SVG text: views along z (x-y), y (x-z) and x (y-z) side by side; the outlines of both
/// quadrics in each view (<path class="outline">: an ellipsoid's silhouette ellipse whole; for
/// any other quadric, a cylinder, cone, hyperboloid, paraboloid or plane, its silhouette
/// conic, or its cross-section when it is a cylinder along the view, traced inside the
/// panel: the box's projection when pic.box is set), one <path class="curve"> per branch, one
/// <circle class="special"> per special point, a zoomed inset (<g class="inset">) for each
/// branch smaller than 6 pixels in every view, the caption as <text>. Tick labels are whole
/// steps of a 1-2-5 grid; on an axis whose values are beyond 10^4 steps from 0 they are
/// measured from an offset named with the axis ("x - 1000": label + offset is the value).
std::string to_svg(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const Picture& pic);

} // namespace surfcert::trace
