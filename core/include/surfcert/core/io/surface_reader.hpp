// surfcert::core::io reading quadrics from the forms the CLI, scenes and batches accept.
//
// A SURFACE is one of: an equation string in x, y, z ("x^2 + y^2/4 + z^2 = 1"); an object
// {"equation": "..."}; {"matrix": 4x4 symmetric, entries numbers or "p/q"/decimal strings};
// or a shape with a pose: {"type": "sphere"|"ellipsoid"|"cylinder"|"cone"|
// "elliptic_paraboloid"|"hyperbolic_paraboloid"|"hyperboloid_one_sheet"|
// "hyperboloid_two_sheets", "center": [x,y,z], "radius"/"radii": ..., "rotation":
// {"quaternion": [w,x,y,z]} | {"matrix": 3x3 rational orthogonal, det 1}}.
// Numbers: JSON integers exactly; other JSON number literals are binary doubles and are read
// as their exact dyadic value; strings are exact decimals or p/q ("0.1" = 1/10).
// Every problem is an InputError naming the JSON path, line and column; unknown fields too.
// Distance queries also accept a ring torus (read_surface).
#pragma once

#include "surfcert/core/error.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/surface.hpp"

#include <set>
#include <string>

namespace surfcert::core::io {

/// Location of a parsed JSON value (source, its line and column, and its JSON path).
Location json_location(const Json& v, const std::string& source, const std::string& path);

/// Throws InputError naming the first member of object v whose key is not in `allowed`.
void check_fields(const Json& v, const std::set<std::string>& allowed, const std::string& source,
                  const std::string& path);

/// An exact number from a JSON number or numeric string.
Rational read_number(const Json& v, const std::string& source, const std::string& path);

/// A quadric from a SURFACE JSON value (see above).
QuadricMatrix read_quadric(const Json& v, const std::string& source, const std::string& path);

/// A surface for distance queries: {"type": "torus", "center": [x,y,z], "axis": [x,y,z],
/// "major_radius": R, "minor_radius": r} (R > r > 0, axis nonzero); a canal surface
/// {"type": "canal", "spine": [[x0, x1, ...], [y0, ...], [z0, ...]], "radius": [r0, r1, ...]
/// or r, "interval": [t0, t1]} (polynomial coefficients, constant first); a capsule
/// {"type": "capsule", "from": [x,y,z], "to": [x,y,z], "radius": r}; an equation of total
/// degree 3 to 6 (an implicit surface); or any SURFACE above.
Surface read_surface(const Json& v, const std::string& source, const std::string& path);

/// A quadric from an equation string (degree 1 or 2 required).
QuadricMatrix quadric_from_equation(const std::string& text, const Location& where);

} // namespace surfcert::core::io
