// surfcert::core::io reading surfaces from the forms the CLI, scenes and batches accept.
//
// A SURFACE (quadric) is one of: an equation string in x, y, z ("x^2 + y^2/4 + z^2 = 1"); an
// object {"equation": "..."}; {"matrix": 4x4, entries numbers or "p/q"/decimal strings}; or a
// shape with a pose: {"type": "sphere"|"ellipsoid"|"cylinder"|"cone"|
// "elliptic_paraboloid"|"hyperbolic_paraboloid"|"hyperboloid_one_sheet"|
// "hyperboloid_two_sheets", "center": [x,y,z] (default the origin), "radius"/"radii": ...,
// "rotation": {"quaternion": [w,x,y,z]} | {"matrix": 3x3}}.
// Numbers: JSON integers exactly; other JSON number literals are binary doubles and are read
// as their exact dyadic value; strings are exact decimals or p/q ("0.1" = 1/10).
// Float data is read exactly as given, never refused for rounding (each such reading is
// reported as a Reading when the caller asks for them):
//   - a rotation matrix R that is not exactly orthogonal (any double matrix) poses the shape
//     as c + R S exactly (u = R^-1 (x - c)); only a singular R is an error;
//   - a non-symmetric 4x4 matrix M means the quadric p^T M p, i.e. its symmetric part
//     (M + M^T) / 2, exactly.
// Every problem is an InputError naming the JSON path, line and column; unknown fields too.
#pragma once

#include "surfcert/core/error.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/surface.hpp"

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace surfcert::core::io {

/// How a float input was read exactly (see above): the JSON path, what the reading is, and the
/// measured deviations (name, short decimal value), e.g. {"max_abs(R^T R - I)", "2.2e-16"}.
struct Reading {
  std::string path;
  std::string reading;
  std::vector<std::pair<std::string, std::string>> deviations;
};
using Readings = std::vector<Reading>;

/// [{"path", "reading", "deviations": {name: value}}] (the answers' "readings" field).
Json readings_json(const Readings& r);

/// Location of a parsed JSON value (source, its line and column, and its JSON path).
Location json_location(const Json& v, const std::string& source, const std::string& path);

/// Throws InputError naming the first member of object v whose key is not in `allowed`.
void check_fields(const Json& v, const std::set<std::string>& allowed, const std::string& source,
                  const std::string& path);

/// An exact number from a JSON number or numeric string.
Rational read_number(const Json& v, const std::string& source, const std::string& path);

/// A quadric from a SURFACE JSON value (see above); readings, when given, receives how float
/// data was read.
QuadricMatrix read_quadric(const Json& v, const std::string& source, const std::string& path,
                           Readings* readings = nullptr);

/// A surface for distance queries: {"type": "torus", "center": [x,y,z], "axis": [x,y,z],
/// "major_radius": R, "minor_radius": r} (R > r > 0, axis nonzero); a canal surface
/// {"type": "canal", "spine": [[x0, x1, ...], [y0, ...], [z0, ...]], "radius": [r0, r1, ...]
/// or r, "interval": [t0, t1]} (polynomial coefficients, constant first); a capsule
/// {"type": "capsule", "from": [x,y,z], "to": [x,y,z], "radius": r}; an equation of total
/// degree 3 to 12 (an implicit surface); a parametric surface {"type": "parametric", "x", "y",
/// "z", "w"?: expressions in u, v} (the point (x, y, z) / w); or any SURFACE above.
Surface read_surface(const Json& v, const std::string& source, const std::string& path,
                     Readings* readings = nullptr);

/// A quadric from an equation string (degree 1 or 2 required).
QuadricMatrix quadric_from_equation(const std::string& text, const Location& where);

} // namespace surfcert::core::io
