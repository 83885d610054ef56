// surfcert::certify::Method: which route of the distance registry produced an answer (the JSON
// "method" field; route.hpp).
//
// One enumerator per route id of the registry's tables, plus the finer names a route may give
// its answer (a closed form or a special case inside the route). The JSON spellings are a
// contract other programs code against: to_string gives them, extend the list, never rename.
#pragma once

#include <optional>
#include <ostream>
#include <string_view>

namespace surfcert::certify {

enum class Method {
  None, ///< not recorded (error answers)
  // quadric pairs
  CylinderClosedForm,
  ConvexDualityFloat,
  ConvexDuality,
  NestedConvexDuality,
  ConeGeneratorBound,
  EllipsoidPlaneClosedForm,
  PlaneClosedForm,
  QsicTopology,
  CommonApex,
  ParallelSections,
  SpherePointQuadric,
  OffsetSystem,
  // tori, canal surfaces, implicit and parametric surfaces
  TorusDistance,
  TorusCircleBound,
  TorusCirclePair,
  TorusCoaxialClosedForm,
  CanalDistance,
  CapsuleClosedForm,
  SphereFamilyBnb,
  ImplicitBnb,
  SignChangeContact,
  ParametricReduction,
  // quadric pairs (added later; spellings keep enum order)
  PlanePairMin,
  DoublePlaneReduction, ///< a double plane (v . X)^2 = 0 answered as its plane (reduced_by)
  LineLocus,            ///< a quadric whose real points form a line, as that line
};

/// The JSON spelling ("offset_system", ...; "" for None).
const char* to_string(Method m);

/// The method of a JSON spelling (for tests and readers of answers); nullopt if unknown.
std::optional<Method> method_from_string(std::string_view s);

inline std::ostream& operator<<(std::ostream& o, Method m) {
  return o << to_string(m);
}

} // namespace surfcert::certify
