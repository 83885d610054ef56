#include "surfcert/core/torus.hpp"
#include "surfcert/core/surface.hpp"

#include <stdexcept>

namespace surfcert::core {

Torus make_torus(const std::array<Rational, 3>& centre, const std::array<Rational, 3>& axis,
                 const Rational& R, const Rational& r) {
  if (axis[0].is_zero() && axis[1].is_zero() && axis[2].is_zero())
    throw std::invalid_argument("torus axis is the zero vector");
  if (r.sign() <= 0) throw std::invalid_argument("torus tube radius must be positive");
  if (!(R > r))
    throw std::invalid_argument("torus needs R > r (ring torus; spindle/horn tori not supported)");
  return Torus{centre, axis, R, r};
}

std::string surface_kind(const Surface& s) {
  return std::holds_alternative<Torus>(s) ? "torus" : "quadric";
}

} // namespace surfcert::core
