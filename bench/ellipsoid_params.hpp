// EllipsoidParams: an ellipsoid as plain doubles, for peer libraries (no surfcert types).
// The ellipsoid is { c + R * diag(radii) * u : |u| = 1 }, i.e. the unit sphere scaled by the
// semi-axes, rotated by R (orthogonal, rows = R[i]) and translated by c.
#pragma once

#include <array>

namespace surfcert::bench {

struct EllipsoidParams {
  std::array<double, 3> centre{};
  std::array<double, 3> radii{};
  std::array<std::array<double, 3>, 3> rotation{}; ///< world = centre + rotation * local
};

} // namespace surfcert::bench
