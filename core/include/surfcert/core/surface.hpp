// surfcert::core::Surface: any surface the distance queries accept: a quadric (planes
// included) or a ring torus. Quadric-only operations (classify, intersect) take the
// QuadricMatrix alternative and report an input error for the others.
#pragma once

#include "surfcert/core/quadric.hpp"
#include "surfcert/core/torus.hpp"

#include <string>
#include <variant>

namespace surfcert::core {

using Surface = std::variant<QuadricMatrix, Torus>;

/// "quadric" or "torus".
std::string surface_kind(const Surface& s);

} // namespace surfcert::core
