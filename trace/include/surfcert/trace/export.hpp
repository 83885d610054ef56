// surfcert::trace exports of traced curves: OBJ and PLY polylines (plus isolated points) and
// an SVG picture (three orthographic views with the surfaces' outlines, the curves, the
// special points marked, and the topology in the caption).
#pragma once

#include "surfcert/trace/curve.hpp"

#include <string>
#include <vector>

namespace surfcert::trace {

struct Picture {
  std::vector<Branch> branches;
  std::vector<Point3> special_points;
  std::string caption; ///< e.g. "case 5 figure_eight: ... (certified)"
};

/// Wavefront OBJ text: "v" lines, one "l" element per branch (closed ones repeat the first
/// vertex), isolated points as "p" elements.
std::string to_obj(const std::vector<Branch>& branches, const std::vector<Point3>& points);

/// ASCII PLY text: vertices, one edge per consecutive pair of polyline points.
std::string to_ply(const std::vector<Branch>& branches, const std::vector<Point3>& points);

/// SVG text: views along z (x-y), y (x-z) and x (y-z) side by side; outlines of both quadrics
/// when they are ellipsoids (their silhouettes in each view), one <path class="curve"> per
/// branch, one <circle class="special"> per special point, the caption as <text>.
std::string to_svg(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const Picture& pic);

} // namespace surfcert::trace
