#include "surfcert/core/io/surface_reader.hpp"

#include "surfcert/core/io/expression.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>

namespace surfcert::core::io {

namespace {

Location at(const Json& v, const std::string& source, const std::string& path) {
  return json_location(v, source, path);
}

std::string describe(const Json& v) {
  switch (v.type()) {
  case Json::Type::String:
    return "string \"" + v.text() + "\"";
  case Json::Type::Number:
    return "number " + v.text();
  default:
    return type_name(v.type());
  }
}

const Json& require(const Json& v, const std::string& key, const std::string& source,
                    const std::string& path) {
  const Json* f = v.find(key);
  if (!f) throw InputError(at(v, source, path), "a field \"" + key + "\"", "none");
  return *f;
}

std::vector<Rational> read_vector(const Json& v, size_t n, const std::string& source,
                                  const std::string& path) {
  if (!v.is_array() || v.size() != n)
    throw InputError(at(v, source, path), "an array of " + std::to_string(n) + " numbers",
                     describe(v) + (v.is_array() ? " of length " + std::to_string(v.size()) : ""));
  std::vector<Rational> out;
  for (size_t i = 0; i < n; ++i)
    out.push_back(read_number(v.items()[i], source, json_path_index(path, i)));
  return out;
}

std::vector<std::vector<Rational>> read_matrix(const Json& v, size_t n, const std::string& source,
                                               const std::string& path) {
  if (!v.is_array() || v.size() != n)
    throw InputError(at(v, source, path),
                     "a " + std::to_string(n) + "x" + std::to_string(n) + " matrix (array of " +
                         std::to_string(n) + " rows)",
                     describe(v));
  std::vector<std::vector<Rational>> rows;
  for (size_t i = 0; i < n; ++i)
    rows.push_back(read_vector(v.items()[i], n, source, json_path_index(path, i)));
  return rows;
}

Rational read_positive(const Json& v, const std::string& source, const std::string& path) {
  Rational r = read_number(v, source, path);
  if (r.sign() <= 0) throw InputError(at(v, source, path), "a positive length", r.to_string());
  return r;
}

// The exact inverse of an invertible 3x3 matrix (adjugate / determinant).
Mat3 inverse3(const Mat3& r) {
  Mat3 inv;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      // cofactor of r[j][i]
      const size_t a0 = (j + 1) % 3, a1 = (j + 2) % 3, b0 = (i + 1) % 3, b1 = (i + 2) % 3;
      inv[i][j] = r[a0][b0] * r[a1][b1] - r[a0][b1] * r[a1][b0];
    }
  Rational det;
  for (size_t k = 0; k < 3; ++k)
    det += r[0][k] * inv[k][0];
  for (auto& row : inv)
    for (auto& e : row)
      e = e / det;
  return inv;
}

// The largest |entry| of an exact deviation, as short decimal text (for a Reading).
std::string max_abs_text(const std::vector<Rational>& entries) {
  Rational m;
  for (const auto& e : entries)
    if (core::abs(e) > m) m = core::abs(e);
  return m.to_decimal_approx(3);
}

// Rotation (local -> world) from {"quaternion": [w,x,y,z]} or {"matrix": 3x3}. A matrix is
// read exactly as given: any invertible R (a double matrix is never exactly orthogonal) poses
// the shape as c + R S, with a Reading saying how far R^T R is from I (and det R when it is
// not 1).
Mat3 read_rotation(const Json& v, const std::string& source, const std::string& path,
                   Readings* readings) {
  Mat3 r;
  if (!v.is_object())
    throw InputError(at(v, source, path),
                     "an object {\"quaternion\": [w,x,y,z]} or {\"matrix\": 3x3}", describe(v));
  check_fields(v, {"quaternion", "matrix"}, source, path);
  if (const Json* q = v.find("quaternion")) {
    auto c = read_vector(*q, 4, source, json_path_child(path, "quaternion"));
    if (std::all_of(c.begin(), c.end(), [](const Rational& e) { return e.is_zero(); }))
      throw InputError(at(*q, source, json_path_child(path, "quaternion")), "a nonzero quaternion",
                       "[0,0,0,0]");
    r = quaternion_rotation({c[0], c[1], c[2], c[3]});
    return r;
  }
  if (const Json* m = v.find("matrix")) {
    std::string mp = json_path_child(path, "matrix");
    auto rows = read_matrix(*m, 3, source, mp);
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        r[i][j] = rows[i][j];
    Rational d = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                 r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                 r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    if (d.is_zero())
      throw InputError(at(*m, source, mp), "an invertible rotation matrix", "det = 0");
    std::vector<Rational> defect; // the entries of R^T R - I, exact
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        Rational s;
        for (size_t k = 0; k < 3; ++k)
          s += r[k][i] * r[k][j];
        defect.push_back(s - Rational(i == j ? 1 : 0));
      }
    const bool orthogonal =
        std::all_of(defect.begin(), defect.end(), [](const Rational& e) { return e.is_zero(); });
    if (readings && (!orthogonal || d != Rational(1)))
      readings->push_back(
          {mp,
           "the matrix R read exactly as given: the shape is c + R S for the unit shape S (R is "
           "not a rotation, so the surface is the image of S under this linear map)",
           {{"max_abs(R^T R - I)", max_abs_text(defect)}, {"det(R)", d.to_decimal_approx(17)}}});
    return r;
  }
  throw InputError(at(v, source, path), "a field \"quaternion\" or \"matrix\"", "neither");
}

// Whether a JSON number literal has a nonzero digit in its mantissa (before any exponent).
bool literal_is_nonzero(const std::string& s) {
  for (char c : s) {
    if (c == 'e' || c == 'E') break;
    if (c >= '1' && c <= '9') return true;
  }
  return false;
}

// The double value of a JSON number literal when it is exactly a binary64 (a non-integer
// literal is one by definition; an integer literal when it has at most 15 digits).
bool literal_double(const Json& v, double& out) {
  if (!v.is_number()) return false;
  const std::string& s = v.text();
  if (s.find_first_of(".eE") == std::string::npos && s.size() > 15 + (s[0] == '-')) return false;
  out = std::strtod(s.c_str(), nullptr);
  // An underflow to 0 is not the literal's double: the exact reader refuses it.
  return std::isfinite(out) && (out != 0 || !literal_is_nonzero(s));
}

bool literal_doubles(const Json* v, size_t n, double* out) {
  if (!v || !v->is_array() || v->size() != n) return false;
  for (size_t i = 0; i < n; ++i)
    if (!literal_double(v->items()[i], out[i])) return false;
  return true;
}

// The shape as a ShapeSpec when every number in it is a finite double, the radii positive and
// the rotation absent or a nonzero quaternion; otherwise nullopt (the exact reader then
// handles it, errors included).
std::optional<ShapeSpec> double_shape(const Json& v, ShapeType type, size_t nradii) {
  double radius = 0;
  std::array<double, 3> radii{1, 1, 1}, center{};
  std::array<double, 4> quaternion{};
  const Json* rj = v.find("radius");
  if (rj ? !literal_double(*rj, radius) : !literal_doubles(v.find("radii"), nradii, radii.data()))
    return std::nullopt;
  const Json* cj = v.find("center");
  if (cj && !literal_doubles(cj, 3, center.data())) return std::nullopt;
  const Json* rot = v.find("rotation");
  if (rot && (!rot->is_object() || rot->members().size() != 1 ||
              !literal_doubles(rot->find("quaternion"), 4, quaternion.data())))
    return std::nullopt;
  return double_shape_spec(type, rj ? &radius : nullptr, rj ? nullptr : &radii,
                           cj ? &center : nullptr, rot ? &quaternion : nullptr);
}

QuadricMatrix read_shape(const Json& v, const std::string& source, const std::string& path,
                         Readings* readings) {
  const Json& tj = require(v, "type", source, path);
  std::string tpath = json_path_child(path, "type");
  if (!tj.is_string()) throw InputError(at(tj, source, tpath), "a shape name string", describe(tj));
  const std::string& name = tj.text();
  const std::optional<ShapeType> found = shape_type_of_name(name);
  if (!found)
    throw InputError(at(tj, source, tpath),
                     "one of sphere, ellipsoid, cylinder, cone, elliptic_paraboloid, "
                     "hyperbolic_paraboloid, hyperboloid_one_sheet, hyperboloid_two_sheets",
                     "\"" + name + "\"");
  const ShapeType type = *found;
  const bool takes_radius = type == ShapeType::Sphere;
  const size_t nradii = shape_radii_count(type);
  std::set<std::string> allowed{"type", "center", "rotation"};
  allowed.insert(takes_radius ? "radius" : "radii");
  if (type == ShapeType::Cylinder) allowed.insert("radius");
  check_fields(v, allowed, source, path);
  // Doubles throughout (what users send): the exact matrix is formed lazily (shape.hpp).
  if (auto spec = double_shape(v, type, nradii)) return QuadricMatrix(*spec);
  std::array<Rational, 3> radii;
  if (takes_radius || (type == ShapeType::Cylinder && v.find("radius"))) {
    std::string rp = json_path_child(path, "radius");
    Rational r = read_positive(require(v, "radius", source, path), source, rp);
    radii = {r, r, r};
  } else {
    std::string rp = json_path_child(path, "radii");
    const Json& rj = require(v, "radii", source, path);
    auto rv = read_vector(rj, nradii, source, rp);
    for (size_t i = 0; i < nradii; ++i) {
      if (rv[i].sign() <= 0)
        throw InputError(at(rj.items()[i], source, json_path_index(rp, i)), "a positive length",
                         rv[i].to_string());
      radii[i] = rv[i];
    }
  }
  std::array<Rational, 3> c;
  if (const Json* cj = v.find("center")) {
    auto cv = read_vector(*cj, 3, source, json_path_child(path, "center"));
    std::copy(cv.begin(), cv.end(), c.begin());
  }
  Mat3 rot{};
  for (size_t i = 0; i < 3; ++i)
    rot[i][i] = Rational(1);
  if (const Json* rj = v.find("rotation"))
    rot = read_rotation(*rj, source, json_path_child(path, "rotation"), readings);
  // R^-1 = R^T for a rotation; the exact inverse otherwise.
  return QuadricMatrix(posed_quadric_matrix(type, radii, c, inverse3(rot)));
}

} // namespace

std::optional<QuadricMatrix> quadric_of_matrix(Mat4 a, const std::string& path,
                                               Readings* readings) {
  // A non-symmetric M means the quadric p^T M p, which is p^T ((M + M^T) / 2) p exactly:
  // read as its symmetric part, with a Reading giving the asymmetry.
  std::vector<Rational> asym;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i + 1; j < 4; ++j)
      if (a[i][j] != a[j][i]) {
        asym.push_back(a[i][j] - a[j][i]);
        a[i][j] = a[j][i] = (a[i][j] + a[j][i]) * Rational(1, 2);
      }
  if (is_zero(a)) return std::nullopt;
  if (readings && !asym.empty())
    readings->push_back({path,
                         "a non-symmetric matrix M read as its symmetric part (M + M^T) / 2: "
                         "the same quadric p^T M p, exactly",
                         {{"max_abs(M - M^T)", max_abs_text(asym)}}});
  return QuadricMatrix(a);
}

std::optional<QuadricMatrix> quadric_of_double_matrix(const std::array<std::array<double, 4>, 4>& m,
                                                      const std::string& path, Readings* readings) {
  // The same quadric and Reading as quadric_of_matrix on the exact values, without forming
  // the rationals (the matrix is lazy, quadric.hpp). The asymmetry max |m_ij - m_ji| is a
  // double when every difference is exact in double (TwoSum error zero: always so for the
  // ulp-level asymmetry of a computed matrix); otherwise it is taken in rationals.
  bool symmetric = true, zero = true, exact = true;
  double max_diff = 0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j) {
      if (!std::isfinite(m[i][j])) return std::nullopt;
      zero = zero && m[i][j] == -m[j][i];
      if (j <= i || m[i][j] == m[j][i]) continue;
      symmetric = false;
      const double x = m[i][j], y = -m[j][i], s = x + y;
      const double yv = s - x, err = (x - (s - yv)) + (y - yv); // TwoSum: x + y = s + err
      exact = exact && std::isfinite(s) && err == 0;
      max_diff = std::max(max_diff, std::fabs(s));
    }
  if (zero) return std::nullopt;
  if (readings && !symmetric) {
    std::string text;
    if (exact) {
      text = Rational::exact_from_double(max_diff).to_decimal_approx(3);
    } else {
      std::vector<Rational> asym;
      for (size_t i = 0; i < 4; ++i)
        for (size_t j = i + 1; j < 4; ++j)
          if (m[i][j] != m[j][i])
            asym.push_back(Rational::exact_from_double(m[i][j]) -
                           Rational::exact_from_double(m[j][i]));
      text = max_abs_text(asym);
    }
    readings->push_back({path,
                         "a non-symmetric matrix M read as its symmetric part (M + M^T) / 2: "
                         "the same quadric p^T M p, exactly",
                         {{"max_abs(M - M^T)", std::move(text)}}});
  }
  return QuadricMatrix::from_double_matrix(m);
}

std::optional<ShapeSpec> double_shape_spec(ShapeType type, const double* radius,
                                           const std::array<double, 3>* radii,
                                           const std::array<double, 3>* center,
                                           const std::array<double, 4>* quaternion) {
  ShapeSpec s;
  s.type = type;
  if (radius) {
    s.radii = {*radius, *radius, *radius};
  } else if (radii) {
    s.radii = *radii;
  } else {
    return std::nullopt;
  }
  for (size_t i = 0; i < shape_radii_count(type); ++i)
    if (!(s.radii[i] > 0) || !std::isfinite(s.radii[i])) return std::nullopt;
  if (center) {
    for (double c : *center)
      if (!std::isfinite(c)) return std::nullopt;
    s.center = *center;
  }
  if (quaternion) {
    for (double c : *quaternion)
      if (!std::isfinite(c)) return std::nullopt;
    if (*quaternion == std::array<double, 4>{0, 0, 0, 0}) return std::nullopt;
    s.quaternion = *quaternion;
    s.rotated = true;
  }
  return s;
}

std::optional<ShapeType> shape_type_of_name(std::string_view name) {
  static const std::pair<const char*, ShapeType> kTypes[] = {
      {"sphere", ShapeType::Sphere},
      {"ellipsoid", ShapeType::Ellipsoid},
      {"cylinder", ShapeType::Cylinder},
      {"cone", ShapeType::Cone},
      {"elliptic_paraboloid", ShapeType::EllipticParaboloid},
      {"hyperbolic_paraboloid", ShapeType::HyperbolicParaboloid},
      {"hyperboloid_one_sheet", ShapeType::HyperboloidOneSheet},
      {"hyperboloid_two_sheets", ShapeType::HyperboloidTwoSheets}};
  for (const auto& [n, t] : kTypes)
    if (name == n) return t;
  return std::nullopt;
}

size_t shape_radii_count(ShapeType type) {
  return type == ShapeType::Sphere ? 3 : (local_form(type).q_sign[2] != 0 ? 3 : 2);
}

Json readings_json(const Readings& rs) {
  Json out = Json::array();
  for (const auto& r : rs) {
    Json o = Json::object();
    o.set("path", Json::string(r.path));
    o.set("reading", Json::string(r.reading));
    Json d = Json::object();
    for (const auto& [name, value] : r.deviations)
      d.set(name, Json::string(value));
    o.set("deviations", d);
    out.push_back(o);
  }
  return out;
}

Location json_location(const Json& v, const std::string& source, const std::string& path) {
  return Location{source, v.line(), v.column(), path};
}

void check_fields(const Json& v, const std::set<std::string>& allowed, const std::string& source,
                  const std::string& path) {
  for (const auto& [k, val] : v.members())
    if (!allowed.count(k)) {
      std::string list;
      for (const auto& a : allowed)
        list += (list.empty() ? "" : ", ") + a;
      throw InputError(json_location(val, source, json_path_child(path, k)),
                       "one of the fields " + list, "unknown field \"" + k + "\"");
    }
}

namespace {

std::string number_bits_expected() {
  return "a number of at most " + std::to_string(kMaxExpressionCoefficientBits) +
         " bits (numerator and denominator), as coefficients of equations are";
}

// A decimal exponent of more than five digits (leading zeros aside): 10^100000 alone is past
// the limit (as in the equation reader).
bool decimal_exponent_too_large(const std::string& t) {
  if (t.find('/') != std::string::npos) return false;
  const std::size_t e = t.find_first_of("eE");
  if (e == std::string::npos) return false;
  const std::size_t d = t.find_first_not_of("+-0", e + 1);
  return d != std::string::npos && t.size() - d > 5;
}

Rational within_bits(Rational r, const Json& v, const std::string& source, const std::string& path,
                     const std::string& found) {
  const long bits = std::max(static_cast<long>(fmpz_bits(fmpq_numref(r.raw()))),
                             static_cast<long>(fmpz_bits(fmpq_denref(r.raw()))));
  if (bits > kMaxExpressionCoefficientBits)
    throw InputError(at(v, source, path), number_bits_expected(),
                     (found.size() > 80 ? found.substr(0, 77) + "..." : found) + " (" +
                         std::to_string(bits) + " bits)");
  return r;
}

} // namespace

Rational read_number(const Json& v, const std::string& source, const std::string& path) {
  if (v.is_number()) {
    const std::string& s = v.text();
    if (s.find_first_of(".eE") == std::string::npos) {
      auto r = Rational::from_string(s);
      if (r) return within_bits(*r, v, source, path, s);
    }
    // A JSON non-integer literal stands for a binary double: read it as that double, exactly.
    double d = std::strtod(s.c_str(), nullptr);
    if (!std::isfinite(d)) throw InputError(at(v, source, path), "a finite number", s);
    // Nor is a nonzero literal that underflows to 0 (1e-400, 2e-324) read as 0: refused as its
    // overflowing mirror is (a string holds its exact value). Subnormal doubles are doubles.
    if (d == 0 && literal_is_nonzero(s))
      throw InputError(at(v, source, path),
                       "a number literal within the double range (nonzero literals below "
                       "4.9e-324 round to 0; a string such as \"1e-400\" is read exactly)",
                       s);
    return Rational::exact_from_double(d);
  }
  if (v.is_string()) {
    // The equation reader's limit on coefficients (expression.hpp), checked before the power
    // of ten is formed: "1e999999" hung a distance query, while x^2 = 1e999999 was refused.
    if (decimal_exponent_too_large(v.text()))
      throw InputError(at(v, source, path), number_bits_expected(), "\"" + v.text() + "\"");
    auto r = Rational::from_string(v.text());
    if (!r)
      throw InputError(at(v, source, path), "an exact number such as \"3\", \"-7/4\" or \"0.125\"",
                       "\"" + v.text() + "\"");
    return within_bits(*r, v, source, path, "\"" + v.text() + "\"");
  }
  throw InputError(at(v, source, path), "a number or a numeric string", describe(v));
}

QuadricMatrix quadric_from_equation(const std::string& text, const Location& where) {
  Poly3 p = parse_polynomial(text, where);
  int d = p.total_degree();
  if (d < 1 || d > 2)
    throw InputError(where, "a quadric equation (total degree 1 or 2)",
                     d < 0 ? "the zero polynomial" : "total degree " + std::to_string(d));
  return QuadricMatrix::from_poly(p);
}

QuadricMatrix read_quadric(const Json& v, const std::string& source, const std::string& path,
                           Readings* readings) {
  if (v.is_string()) {
    Location w = at(v, source, path);
    if (w.column > 0) ++w.column; // past the opening quote
    return quadric_from_equation(v.text(), w);
  }
  if (!v.is_object())
    throw InputError(
        at(v, source, path),
        "a surface: an equation string, {\"matrix\": ...}, {\"equation\": ...} or a shape object",
        describe(v));
  if (const Json* e = v.find("equation")) {
    check_fields(v, {"equation"}, source, path);
    std::string ep = json_path_child(path, "equation");
    if (!e->is_string()) throw InputError(at(*e, source, ep), "an equation string", describe(*e));
    return read_quadric(*e, source, ep, readings);
  }
  if (const Json* m = v.find("matrix")) {
    check_fields(v, {"matrix"}, source, path);
    std::string mp = json_path_child(path, "matrix");
    auto rows = read_matrix(*m, 4, source, mp);
    Mat4 a;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        a[i][j] = rows[i][j];
    auto q = quadric_of_matrix(std::move(a), mp, readings);
    if (!q) throw InputError(at(*m, source, mp), "a nonzero matrix", "all entries zero");
    return *q;
  }
  if (v.find("type")) return read_shape(v, source, path, readings);
  throw InputError(at(v, source, path), "a field \"matrix\", \"equation\" or \"type\"",
                   "an object without them");
}

namespace {

// A polynomial as a coefficient list [c0, c1, ...] (constant first) or a single number.
std::vector<Rational> read_coeffs(const Json& v, const std::string& source,
                                  const std::string& path) {
  std::vector<Rational> c;
  if (!v.is_array()) {
    c.push_back(read_number(v, source, path));
    return c;
  }
  if (v.size() == 0)
    throw InputError(at(v, source, path), "coefficients [c0, c1, ...] (constant first)", "[]");
  for (size_t i = 0; i < v.size(); ++i)
    c.push_back(read_number(v.items()[i], source, json_path_index(path, i)));
  return c;
}

Surface read_canal(const Json& v, const std::string& source, const std::string& path,
                   bool capsule) {
  std::array<std::vector<Rational>, 3> spine;
  std::vector<Rational> radius;
  Rational t0(0), t1(1);
  const std::string rp = json_path_child(path, "radius");
  if (capsule) {
    check_fields(v, {"type", "from", "to", "radius"}, source, path);
    auto a =
        read_vector(require(v, "from", source, path), 3, source, json_path_child(path, "from"));
    auto b = read_vector(require(v, "to", source, path), 3, source, json_path_child(path, "to"));
    if (a == b)
      throw InputError(at(require(v, "to", source, path), source, json_path_child(path, "to")),
                       "an end point different from \"from\" (else use a sphere)",
                       "the same point");
    for (size_t i = 0; i < 3; ++i)
      spine[i] = {a[i], b[i] - a[i]};
    radius = {read_positive(require(v, "radius", source, path), source, rp)};
  } else {
    check_fields(v, {"type", "spine", "radius", "interval"}, source, path);
    const std::string sp = json_path_child(path, "spine");
    const Json& sj = require(v, "spine", source, path);
    if (!sj.is_array() || sj.size() != 3)
      throw InputError(at(sj, source, sp),
                       "three coefficient lists [[x0, x1, ...], [y...], [z...]]",
                       type_name(sj.type()));
    for (size_t i = 0; i < 3; ++i)
      spine[i] = read_coeffs(sj.items()[i], source, json_path_index(sp, i));
    radius = read_coeffs(require(v, "radius", source, path), source, rp);
    const std::string ip = json_path_child(path, "interval");
    auto iv = read_vector(require(v, "interval", source, path), 2, source, ip);
    t0 = iv[0];
    t1 = iv[1];
    if (!(t0 < t1))
      throw InputError(at(require(v, "interval", source, path), source, ip),
                       "[t0, t1] with t0 < t1", "[" + t0.to_string() + ", " + t1.to_string() + "]");
  }
  try {
    return make_canal(std::move(spine), std::move(radius), t0, t1);
  } catch (const std::invalid_argument& e) {
    throw InputError(at(v, source, path), "a canal surface (" + std::string(e.what()) + ")",
                     "an invalid one");
  }
}

} // namespace

Surface read_surface(const Json& v, const std::string& source, const std::string& path,
                     Readings* readings) {
  // An equation of degree 3 to 12 (string or {"equation": ...}) is an implicit surface.
  const Json* eqj = v.is_string() ? &v : (v.is_object() ? v.find("equation") : nullptr);
  if (eqj && eqj->is_string()) {
    const std::string epath = v.is_string() ? path : json_path_child(path, "equation");
    Location where = at(*eqj, source, epath);
    if (where.column > 0) ++where.column; // past the opening quote, as read_quadric does
    Poly3 p = parse_polynomial(eqj->text(), where);
    const int d = p.total_degree();
    if (d >= 3) {
      if (v.is_object()) check_fields(v, {"equation"}, source, path);
      if (d > kMaxImplicitDegree)
        throw InputError(where,
                         "an implicit surface of total degree at most " +
                             std::to_string(kMaxImplicitDegree),
                         "total degree " + std::to_string(d));
      return ImplicitSurface{std::move(p)};
    }
  }
  if (!v.is_object()) return read_quadric(v, source, path, readings);
  const Json* tj = v.find("type");
  if (tj && tj->is_string() && tj->text() == "parametric") {
    check_fields(v, {"type", "x", "y", "z", "w"}, source, path);
    // Expressions in u and v, read by the equation parser with u -> x, v -> y.
    auto comp = [&](const char* key, bool optional) -> Poly3 {
      const Json* j = v.find(key);
      const std::string kp = json_path_child(path, key);
      if (!j) {
        if (optional) return Poly3(Rational(1));
        throw InputError(at(v, source, path), std::string("a field \"") + key + "\"", "none");
      }
      if (!j->is_string())
        throw InputError(at(*j, source, kp), "an expression in u and v", type_name(j->type()));
      std::string t = j->text();
      for (char c : t)
        if (c == 'x' || c == 'y' || c == 'z')
          throw InputError(at(*j, source, kp), "an expression in u and v only", "\"" + t + "\"");
      for (char& c : t) {
        if (c == 'u') c = 'x';
        if (c == 'v') c = 'y';
      }
      Location where = at(*j, source, kp);
      if (where.column > 0) ++where.column; // past the opening quote
      return parse_polynomial(t, where);
    };
    ParametricSurface ps{comp("x", false), comp("y", false), comp("z", false), comp("w", true)};
    if (ps.W.is_zero()) throw InputError(at(v, source, path), "a nonzero denominator \"w\"", "0");
    return ps;
  }
  if (tj && tj->is_string() && (tj->text() == "canal" || tj->text() == "capsule"))
    return read_canal(v, source, path, tj->text() == "capsule");
  if (!tj || !tj->is_string() || tj->text() != "torus")
    return read_quadric(v, source, path, readings);
  check_fields(v, {"type", "center", "axis", "major_radius", "minor_radius"}, source, path);
  std::string cp = json_path_child(path, "center"), ap = json_path_child(path, "axis");
  auto c = read_vector(require(v, "center", source, path), 3, source, cp);
  auto a = read_vector(require(v, "axis", source, path), 3, source, ap);
  const Json& Rj = require(v, "major_radius", source, path);
  const Json& rj = require(v, "minor_radius", source, path);
  Rational R = read_positive(Rj, source, json_path_child(path, "major_radius"));
  Rational r = read_positive(rj, source, json_path_child(path, "minor_radius"));
  if (a[0].is_zero() && a[1].is_zero() && a[2].is_zero())
    throw InputError(at(require(v, "axis", source, path), source, ap), "a nonzero axis vector",
                     "[0, 0, 0]");
  if (!(R > r))
    throw InputError(at(Rj, source, json_path_child(path, "major_radius")),
                     "major_radius > minor_radius (a ring torus; spindle and horn tori are not "
                     "supported)",
                     R.to_string() + " <= " + r.to_string());
  return make_torus({c[0], c[1], c[2]}, {a[0], a[1], a[2]}, R, r);
}

} // namespace surfcert::core::io
