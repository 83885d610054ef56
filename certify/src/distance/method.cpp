#include "surfcert/certify/distance/method.hpp"

#include <utility>

namespace surfcert::certify {

namespace {

// The JSON spellings, in enum order (checked by the static_assert below).
constexpr std::pair<Method, const char*> kSpellings[] = {
    {Method::None, ""},
    {Method::CylinderClosedForm, "cylinder_closed_form"},
    {Method::ConvexDualityFloat, "convex_duality_float"},
    {Method::ConvexDuality, "convex_duality"},
    {Method::NestedConvexDuality, "nested_convex_duality"},
    {Method::ConeGeneratorBound, "cone_generator_bound"},
    {Method::EllipsoidPlaneClosedForm, "ellipsoid_plane_closed_form"},
    {Method::PlaneClosedForm, "plane_closed_form"},
    {Method::QsicTopology, "qsic_topology"},
    {Method::CommonApex, "common_apex"},
    {Method::ParallelSections, "parallel_sections"},
    {Method::SpherePointQuadric, "sphere_point_quadric"},
    {Method::OffsetSystem, "offset_system"},
    {Method::TorusDistance, "torus_distance"},
    {Method::TorusCircleBound, "torus_circle_bound"},
    {Method::TorusCirclePair, "torus_circle_pair"},
    {Method::TorusCoaxialClosedForm, "torus_coaxial_closed_form"},
    {Method::CanalDistance, "canal_distance"},
    {Method::CapsuleClosedForm, "capsule_closed_form"},
    {Method::SphereFamilyBnb, "sphere_family_bnb"},
    {Method::ImplicitBnb, "implicit_bnb"},
    {Method::SignChangeContact, "sign_change_contact"},
    {Method::ParametricReduction, "parametric_reduction"},
    {Method::PlanePairMin, "plane_pair_min"},
    {Method::DoublePlaneReduction, "double_plane_reduction"},
    {Method::LineLocus, "line_locus"},
};

constexpr bool in_enum_order() {
  for (size_t i = 0; i < std::size(kSpellings); ++i)
    if (static_cast<size_t>(kSpellings[i].first) != i) return false;
  return true;
}
static_assert(in_enum_order(), "kSpellings must list every Method in enum order");
static_assert(std::size(kSpellings) == static_cast<size_t>(Method::LineLocus) + 1,
              "a Method without a JSON spelling");

} // namespace

const char* to_string(Method m) {
  return kSpellings[static_cast<size_t>(m)].second;
}

std::optional<Method> method_from_string(std::string_view s) {
  for (const auto& [m, text] : kSpellings)
    if (s == text) return m;
  return std::nullopt;
}

} // namespace surfcert::certify
