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

#include <array>
#include <optional>
#include <set>
#include <string>
#include <string_view>
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

/// The quadric of a 4x4 matrix as {"matrix": a} reads it: a non-symmetric a as its symmetric
/// part (with a Reading at `path`); nullopt when that part is zero (an input error).
std::optional<QuadricMatrix> quadric_of_matrix(Mat4 a, const std::string& path, Readings* readings);
/// The same for a matrix of doubles (each read as its exact value).
std::optional<QuadricMatrix> quadric_of_double_matrix(const std::array<std::array<double, 4>, 4>& m,
                                                      const std::string& path, Readings* readings);

/// The shape type a "type" string names ("sphere", "ellipsoid", ..., "hyperboloid_two_sheets");
/// nullopt for any other string.
std::optional<ShapeType> shape_type_of_name(std::string_view name);

/// How many radii a shape type reads: 3 for a sphere's radius and most types, 2 when the
/// unit shape has no z^2 term (cylinder, paraboloids).
size_t shape_radii_count(ShapeType type);

/// A shape posed in doubles as the shape reader reads it when every number is a finite double:
/// a radius (all three radii) or the radii (shape_radii_count of them, positive), the centre
/// (default the origin) and the unit quaternion (default no rotation; nonzero). nullopt when a
/// value is out of range (the exact reader then handles the shape, errors included).
std::optional<ShapeSpec> double_shape_spec(ShapeType type, const double* radius,
                                           const std::array<double, 3>* radii,
                                           const std::array<double, 3>* center,
                                           const std::array<double, 4>* quaternion);

/// A quadric from an equation string (degree 1 or 2 required).
QuadricMatrix quadric_from_equation(const std::string& text, const Location& where);

} // namespace surfcert::core::io
