#include "surfcert/core/torus.hpp"
#include "surfcert/core/surface.hpp"

#include <stdexcept>
#include <string>

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

std::array<std::array<Rational, 3>, 2> plane_frame(const std::array<Rational, 3>& a) {
  size_t k = 0;
  for (size_t i = 1; i < 3; ++i)
    if (abs(a[i]) < abs(a[k])) k = i;
  // a x e_k has components (a x e_k)_{k+1} = a_{k+2}, (a x e_k)_{k+2} = -a_{k+1}.
  std::array<Rational, 3> u{Rational(0), Rational(0), Rational(0)};
  u[(k + 1) % 3] = a[(k + 2) % 3];
  u[(k + 2) % 3] = -a[(k + 1) % 3];
  const std::array<Rational, 3> v{a[1] * u[2] - a[2] * u[1], a[2] * u[0] - a[0] * u[2],
                                  a[0] * u[1] - a[1] * u[0]};
  return {u, v};
}

Rational eval_poly(const std::vector<Rational>& c, const Rational& t) {
  Rational v;
  for (size_t i = c.size(); i-- > 0;)
    v = v * t + c[i];
  return v;
}

CanalSurface make_canal(std::array<std::vector<Rational>, 3> spine, std::vector<Rational> radius,
                        const Rational& t0, const Rational& t1) {
  if (!(t0 < t1)) throw std::invalid_argument("canal interval needs t0 < t1");
  bool moving = false;
  for (const auto& c : spine)
    for (size_t i = 1; i < c.size(); ++i)
      moving = moving || !c[i].is_zero();
  if (!moving) throw std::invalid_argument("canal spine is a single point (use a sphere)");
  if (radius.empty() || eval_poly(radius, t0).sign() <= 0 || eval_poly(radius, t1).sign() <= 0)
    throw std::invalid_argument("canal radius must be positive at both ends");
  return CanalSurface{std::move(spine), std::move(radius), t0, t1};
}

std::string surface_kind(const Surface& s) {
  if (std::holds_alternative<Torus>(s)) return "torus";
  if (std::holds_alternative<CanalSurface>(s)) return "canal";
  if (std::holds_alternative<ImplicitSurface>(s)) return "implicit";
  if (std::holds_alternative<ParametricSurface>(s)) return "parametric";
  return "quadric";
}

std::string surface_found(const Surface& s) {
  if (const auto* f = std::get_if<ImplicitSurface>(&s))
    return "total degree " + std::to_string(f->f.total_degree());
  if (std::holds_alternative<Torus>(s)) return "a torus";
  if (std::holds_alternative<CanalSurface>(s)) return "a canal surface";
  if (std::holds_alternative<ParametricSurface>(s)) return "a parametric surface";
  return "a quadric";
}

} // namespace surfcert::core
