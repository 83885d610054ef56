// surfcert::app::generate (see generate.hpp): building the cases, encoding them, labelling
// them with the certified answers.
#include "surfcert/app/generate.hpp"

#include "surfcert/algebra/canonical_pencil.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/qsic.hpp"
#include "surfcert/certify/report.hpp"
#include "surfcert/core/error.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include "surfcert/core/quadric.hpp"
#include "surfcert/core/shape.hpp"

#include <flint/fmpz.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>

namespace surfcert::app {

using algebra::Rng;
using core::InputError;
using core::Integer;
using core::Location;
using core::Mat3;
using core::Mat4;
using core::Rational;
using core::ShapeType;
using core::io::Json;

std::optional<Encoding> parse_encoding(const std::string& s) {
  if (s == "exact") return Encoding::Exact;
  if (s == "double") return Encoding::Double;
  if (s == "shape") return Encoding::Shape;
  return std::nullopt;
}

const char* to_string(Encoding e) {
  switch (e) {
  case Encoding::Exact:
    return "exact";
  case Encoding::Double:
    return "double";
  case Encoding::Shape:
    return "shape";
  }
  return "exact";
}

const std::vector<std::string>& family_names() {
  static const std::vector<std::string> names = {"tangency",     "node",     "acnode", "cusp",
                                                 "double_conic", "touching", "nested"};
  return names;
}

namespace {

// `option`: the option's JSON path as a batch line's field (GenerateRefusal).
[[noreturn]] void refuse(const std::string& option, const std::string& expected,
                         const std::string& found) {
  throw GenerateRefusal(option, expected, found);
}

// ---- numbers -------------------------------------------------------------------------------

Rational pow2(int e) {
  Integer p(1);
  fmpz_mul_2exp(p.raw_mut(), p.raw(), static_cast<unsigned long>(e < 0 ? -e : e));
  return e < 0 ? Rational(Integer(1), p) : Rational(p);
}

// Exactly a binary64: a dyadic whose odd part has at most 53 bits, within the exponent range
// (subnormals included).
bool is_binary64(const Rational& r) {
  if (r.is_zero()) return true;
  const Integer num = r.num(), den = r.den();
  const long den_bits = den.bits();
  if (fmpz_val2(den.raw()) != static_cast<unsigned long>(den_bits - 1)) return false;
  const long zeros = static_cast<long>(fmpz_val2(num.raw()));
  const long odd_bits = num.bits() - zeros;
  const long low = zeros - (den_bits - 1); // exponent of the lowest set bit
  const long high = num.bits() - (den_bits - 1);
  return odd_bits <= 53 && low >= -1074 && high <= 1024;
}

// The exact decimal text of a dyadic n / 2^e: n 5^e / 10^e (finitely many digits).
std::string exact_decimal(const Rational& r) {
  const Integer num = r.num(), den = r.den();
  const long e = den.bits() - 1;
  if (e == 0) return num.to_string();
  Integer m;
  fmpz_abs(m.raw_mut(), num.raw());
  Integer five;
  fmpz_set_ui(five.raw_mut(), 5);
  fmpz_pow_ui(five.raw_mut(), five.raw(), static_cast<unsigned long>(e));
  m = m * five;
  std::string digits = m.to_string();
  if (digits.size() <= static_cast<size_t>(e))
    digits.insert(0, static_cast<size_t>(e) + 1 - digits.size(), '0');
  digits.insert(digits.size() - static_cast<size_t>(e), ".");
  return (num.sign() < 0 ? "-" : "") + digits;
}

const char* kExactReading[] = {
    "exact rationals: JSON integers and \"p/q\" strings",
    "every number is a binary64 and its decimal text is its exact value: read as doubles or as "
    "exact decimals, the same surface",
    "a shape whose numbers are all binary64 with exact decimal text; the rotation is the exact "
    "rational rotation of the integer quaternion q/|q| (here a signed permutation, so a float "
    "reader gets it exactly too)"};

Json number_json(const Rational& r, Encoding enc, const std::string& where) {
  if (enc == Encoding::Exact)
    return r.is_integer() ? Json::number_text(r.to_string()) : Json::string(r.to_string());
  if (!is_binary64(r))
    refuse("$.encoding", "a case the double encoding holds exactly (or --encoding exact)",
           where + " needs " + r.to_string() + ", not a binary64");
  return Json::number_text(exact_decimal(r));
}

// ---- surfaces and poses --------------------------------------------------------------------

struct LocalShape {
  ShapeType type = ShapeType::Ellipsoid;
  std::array<Rational, 3> radii{Rational(1), Rational(1), Rational(1)};
  std::array<Rational, 3> center{};
};

// A rigid motion x -> R x + t with R the exact rotation of an integer quaternion.
struct Pose {
  std::array<long, 4> q{1, 0, 0, 0};
  Mat3 r;
  std::array<Rational, 3> t{};
};

Mat3 rotation_of(const std::array<long, 4>& q) {
  return core::quaternion_rotation(
      {Rational(q[0]), Rational(q[1]), Rational(q[2]), Rational(q[3])});
}

// The 24 rotations of the cube (signed permutations of det 1) as integer quaternions with
// entries in {-1, 0, 1}, first nonzero entry positive.
const std::vector<std::array<long, 4>>& cube_rotations() {
  static const std::vector<std::array<long, 4>> qs = [] {
    std::vector<std::array<long, 4>> out;
    for (long w = -1; w <= 1; ++w)
      for (long x = -1; x <= 1; ++x)
        for (long y = -1; y <= 1; ++y)
          for (long z = -1; z <= 1; ++z) {
            const long n = w * w + x * x + y * y + z * z;
            const long first = w != 0 ? w : x != 0 ? x : y != 0 ? y : z;
            if ((n == 1 || n == 2 || n == 4) && first > 0) out.push_back({w, x, y, z});
          }
    return out;
  }();
  return qs;
}

// double-exact poses: a cube rotation and (when `translate`) a dyadic translation in quarters;
// exact poses: a general rational rotation (integer quaternion in [-3, 3]) and a small
// rational translation.
Pose random_pose(Rng& rng, bool exact, bool translate) {
  Pose p;
  if (exact) {
    do {
      for (long& c : p.q)
        c = rng.uniform(-3, 3);
    } while (p.q[0] == 0 && p.q[1] == 0 && p.q[2] == 0 && p.q[3] == 0);
  } else {
    const auto& cube = cube_rotations();
    p.q = cube[static_cast<size_t>(rng.uniform(0, static_cast<long>(cube.size()) - 1))];
  }
  p.r = rotation_of(p.q);
  if (translate)
    for (Rational& c : p.t)
      c = exact ? rng.small_rational(9, 4) : rng.small_dyadic(16, 2);
  return p;
}

// The quadric M (local coordinates) moved by the pose: T^T M T, T = [[R^T, -R^T t], [0, 1]]
// (T takes a world point to the local one).
Mat4 posed(const Mat4& m, const Pose& p) {
  Mat4 t{};
  for (int i = 0; i < 3; ++i) {
    Rational s;
    for (int j = 0; j < 3; ++j) {
      t[i][j] = p.r[j][i];
      s = s - p.r[j][i] * p.t[j];
    }
    t[i][3] = s;
  }
  t[3][3] = Rational(1);
  return core::transpose(t) * m * t;
}

LocalShape posed(const LocalShape& s, const Pose& p) {
  LocalShape out = s;
  for (int i = 0; i < 3; ++i) {
    Rational c = p.t[i];
    for (int j = 0; j < 3; ++j)
      c = c + p.r[i][j] * s.center[j];
    out.center[i] = c;
  }
  return out;
}

Mat4 shape_matrix(const LocalShape& s, const Pose& p) {
  Mat3 rt;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      rt[i][j] = p.r[j][i];
  return core::posed_quadric_matrix(s.type, s.radii, posed(s, p).center, rt);
}

Mat4 equation(const std::string& text) {
  return core::io::quadric_from_equation(text, Location{"<generate>", 1, 1, ""}).matrix();
}

Json matrix_json(const Mat4& m, Encoding enc, const std::string& where) {
  Json rows = Json::array();
  for (int i = 0; i < 4; ++i) {
    Json row = Json::array();
    for (int j = 0; j < 4; ++j)
      row.push_back(number_json(m[i][j], enc == Encoding::Exact ? enc : Encoding::Double, where));
    rows.push_back(row);
  }
  Json o = Json::object();
  o.set("matrix", rows);
  return o;
}

Json shape_json(const LocalShape& s, const Pose& p, const std::string& where) {
  const LocalShape w = posed(s, p);
  Json o = Json::object();
  o.set("type", Json::string(s.type == ShapeType::Sphere ? "sphere" : "ellipsoid"));
  Json c = Json::array();
  for (const Rational& x : w.center)
    c.push_back(number_json(x, Encoding::Double, where));
  o.set("center", c);
  if (s.type == ShapeType::Sphere) {
    o.set("radius", number_json(s.radii[0], Encoding::Double, where));
  } else {
    Json r = Json::array();
    for (const Rational& x : s.radii)
      r.push_back(number_json(x, Encoding::Double, where));
    o.set("radii", r);
  }
  if (p.q != std::array<long, 4>{1, 0, 0, 0}) {
    Json q = Json::array();
    for (long x : p.q)
      q.push_back(Json::number(x));
    Json rot = Json::object();
    rot.set("quaternion", q);
    o.set("rotation", rot);
  }
  return o;
}

// A surface of a line: a matrix, or a shape when the encoding and the construction allow.
struct Surf {
  Mat4 m;                          ///< local
  std::optional<LocalShape> shape; ///< when the construction is a shape
};

Surf shape_surf(ShapeType type, std::array<Rational, 3> radii, std::array<Rational, 3> center) {
  LocalShape s{type, radii, center};
  return Surf{shape_matrix(s, Pose{{1, 0, 0, 0}, rotation_of({1, 0, 0, 0}), {}}), s};
}

// ---- the jobs ------------------------------------------------------------------------------

struct Job {
  std::string id, op;
  Json a, b;
  Json construction;
};

// The encoding actually used for a pair (shape only when both are shapes).
Encoding pair_encoding(Encoding requested, const Surf& a, const Surf& b) {
  if (requested == Encoding::Shape && !(a.shape && b.shape)) return Encoding::Double;
  return requested;
}

Job make_job(const std::string& id, const std::string& op, const Surf& a, const Surf& b,
             const Pose& pose, Encoding requested, Json construction) {
  Job j;
  j.id = id;
  j.op = op;
  const Encoding enc = pair_encoding(requested, a, b);
  if (enc == Encoding::Shape) {
    j.a = shape_json(*a.shape, pose, id + " $.a");
    j.b = shape_json(*b.shape, pose, id + " $.b");
  } else {
    j.a = matrix_json(posed(a.m, pose), enc, id + " $.a");
    j.b = matrix_json(posed(b.m, pose), enc, id + " $.b");
  }
  construction.set("encoding", Json::string(to_string(enc)));
  construction.set("exact_reading", Json::string(kExactReading[static_cast<int>(enc)]));
  j.construction = std::move(construction);
  return j;
}

Json pencil_job_json(const algebra::PencilPair& ab, const std::string& id, Encoding enc, Job& j) {
  j.a = matrix_json(ab.a, enc == Encoding::Exact ? enc : Encoding::Double, id + " $.a");
  j.b = matrix_json(ab.b, enc == Encoding::Exact ? enc : Encoding::Double, id + " $.b");
  return Json::string(to_string(enc == Encoding::Exact ? enc : Encoding::Double));
}

// One independent stream per (set, case, instance): an instance replays without the others.
std::uint64_t stream_seed(std::uint64_t seed, const std::string& tag, long index) {
  std::uint64_t h = 1469598103934665603ULL; // FNV-1a of the tag
  for (char c : tag)
    h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (h ^ static_cast<std::uint64_t>(index + 1));
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL; // splitmix64 finaliser
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::string two_digits(long n) {
  return (n < 10 ? "0" : "") + std::to_string(n);
}

std::string index_text(long i) {
  std::string s = std::to_string(i);
  return std::string(s.size() < 4 ? 4 - s.size() : 0, '0') + s;
}

Json base_construction(const std::string& set, const GenerateRequest& r, long index) {
  Json c = Json::object();
  c.set("set", Json::string(set));
  c.set("seed", Json::number_text(std::to_string(r.seed)));
  c.set("index", Json::number(index));
  return c;
}

void pencil_case_jobs(int tu_case, const GenerateRequest& r, std::vector<Job>& out) {
  const algebra::CaseRecipe& row = algebra::case_recipes().at(static_cast<size_t>(tu_case - 1));
  const algebra::Recipe recipe = algebra::parse_recipe(row.recipe);
  for (long i = 0; i < r.count; ++i) {
    Rng rng(stream_seed(r.seed, "case" + std::to_string(tu_case), i));
    const algebra::PencilPair ab =
        algebra::scrambled_pencil(recipe, rng, r.encoding != Encoding::Exact);
    Job j;
    j.id = "case" + two_digits(tu_case) + "-" + index_text(i);
    j.op = "classify";
    Json c = base_construction("case", r, i);
    c.set("recipe", Json::string(row.recipe));
    c.set("tu_case", Json::number(tu_case));
    const Json enc = pencil_job_json(ab, j.id, r.encoding, j);
    c.set("encoding", enc);
    c.set("exact_reading", Json::string(kExactReading[r.encoding == Encoding::Exact ? 0 : 1]));
    j.construction = std::move(c);
    out.push_back(std::move(j));
  }
}

// A small random symmetric integer matrix block (top-left n x n of a 4 x 4), not zero.
Mat4 random_block(Rng& rng, int n) {
  for (;;) {
    Mat4 m{};
    bool nonzero = false;
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) {
        m[i][j] = m[j][i] = Rational(rng.uniform(-3, 3));
        nonzero = nonzero || !m[i][j].is_zero();
      }
    if (nonzero) return m;
  }
}

bool proportional(const Mat4& a, const Mat4& b) {
  // b = c a for some c (a nonzero).
  std::optional<Rational> c;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      if (a[i][j].is_zero() != b[i][j].is_zero()) return false;
      if (a[i][j].is_zero()) continue;
      const Rational q = b[i][j] / a[i][j];
      if (c && !(q == *c)) return false;
      c = q;
    }
  return true;
}

// degenerate_pencil: two quadrics singular at a common point (the last basis vector before
// the congruence), so det(l A - B) vanishes identically; coincident: B a multiple of A.
void special_pencil_jobs(const std::string& kind, const GenerateRequest& r, std::vector<Job>& out) {
  for (long i = 0; i < r.count; ++i) {
    Rng rng(stream_seed(r.seed, kind, i));
    algebra::PencilPair ab;
    if (kind == "degenerate_pencil") {
      do {
        ab.a = random_block(rng, 3);
        ab.b = random_block(rng, 3);
      } while (proportional(ab.a, ab.b));
    } else {
      Rational c;
      do {
        ab.a = random_block(rng, 4);
        c = rng.small_dyadic(4, 1);
      } while (c.is_zero());
      ab.b = core::scaled(ab.a, c);
    }
    ab = algebra::congruence(ab, algebra::random_invertible(rng, -2, 2));
    Job j;
    j.id = kind + "-" + index_text(i);
    j.op = "classify";
    Json c = base_construction(kind, r, i);
    c.set("pencil", Json::string(kind == "degenerate_pencil" ? "degenerate" : "coincident"));
    const Json enc = pencil_job_json(ab, j.id, r.encoding, j);
    c.set("encoding", enc);
    c.set("exact_reading", Json::string(kExactReading[r.encoding == Encoding::Exact ? 0 : 1]));
    j.construction = std::move(c);
    out.push_back(std::move(j));
  }
}

// ---- ellipsoid pairs (seed 002's 21 ellipsoid topologies) ------------------------------------

struct EllipsoidConfig {
  int tu_case;
  Surf a, b;
  std::string how; ///< the construction, in words
};

std::array<Rational, 3> vec(const Rational& x, const Rational& y, const Rational& z) {
  return {x, y, z};
}

const std::vector<EllipsoidConfig>& ellipsoid_configs() {
  static const std::vector<EllipsoidConfig> configs = [] {
    const Rational h(1, 2), q(1, 4), one(1), zero(0);
    const auto ell = [](std::array<Rational, 3> r, std::array<Rational, 3> c) {
      return shape_surf(ShapeType::Ellipsoid, r, c);
    };
    const Surf sphere = shape_surf(ShapeType::Sphere, vec(one, one, one), vec(zero, zero, zero));
    const Surf flat = ell(vec(one, h, q), vec(zero, zero, zero));
    // E: x^2 + 2y^2 + 4z^2 = 1 (not a sphere, so no accidental symmetry); the others are
    // E + mu Q with Q a plane pair or a cone at the vertex P = (1, 0, 0): the curve is E
    // cut by Q.
    const std::string e = "x^2 + 2y^2 + 4z^2 - 1";
    const auto pencil = [&e](const std::string& cut) {
      return Surf{equation(e + " + " + cut), std::nullopt};
    };
    const Surf E{equation(e), std::nullopt};
    std::vector<EllipsoidConfig> c = {
        {1, sphere, ell(vec(Rational(2), h, q), vec(zero, zero, zero)),
         "a long ellipsoid through a sphere, concentric"},
        {2, flat, ell(vec(h, one, Rational(2)), vec(Rational(4), zero, zero)), "far apart"},
        {3, flat, ell(vec(h, one, Rational(2)), vec(one, zero, zero)), "overlapping"},
        {5, E, pencil("(1/4)((x-1)^2 + y^2 - 2z^2)"),
         "E cut by a cone at P whose tangent-plane section is two real lines"},
        {6, E, pencil("(1/4)(-3(x-1)^2 + y^2 + 3z^2)"),
         "E cut by a cone at P meeting the tangent plane only at P, crossing E elsewhere"},
        {7, E, pencil("(1/4)((x-1)^2 + y^2 + 3z^2)"), "E cut by an imaginary cone at P"},
        {9, E, pencil("(1/4)(y^2 + (x-1)z)"), "E cut by a cone at P with a generator tangent to E"},
        {13, sphere, ell(vec(one, h, Rational(2)), vec(zero, zero, zero)),
         "concentric, one common axis: two planes through it"},
        {14, sphere, ell(vec(h, Rational(2), Rational(2)), vec(zero, zero, zero)),
         "concentric, two parallel planes"},
        {15, E, pencil("(1/2)(y^2 + z^2)"),
         "E cut by two imaginary planes through a real line piercing E"},
        {16, sphere, ell(vec(Rational(2), Rational(2), Rational(4)), vec(zero, zero, zero)),
         "concentric, nested"},
        {17, E, pencil("(x - 1/2)(x - 4)"), "E cut by two parallel planes, one missing E"},
        {19, E, pencil("(1/2)((x-1)^2 - y^2)"), "E cut by two planes crossing on a tangent line"},
        {20, E, pencil("(1/2)((x-1)^2 + y^2)"),
         "E cut by two imaginary planes through a tangent line"},
        {21, E, pencil("(x - 1/2)^2"), "E cut by a double plane"},
        {22, E, pencil("(1/4)(x - 2)^2"), "E cut by a double plane missing E"},
        {24, E, pencil("(x-1)(x - 1/2)"), "E cut by the tangent plane at P and a secant plane"},
        {25, E, pencil("(1/2)(x-1)(x-3)"), "E cut by the tangent plane at P and a plane missing E"},
        {27, E, pencil("(1/2)(x-1)(x-1+z)"),
         "E cut by the tangent plane at P and a secant plane through P"},
        {30, sphere, ell(vec(one, h, h), vec(zero, zero, zero)),
         "concentric, touching at two points"},
        {33, E, pencil("(x-1)^2"), "E cut by the double tangent plane at P"},
    };
    return c;
  }();
  return configs;
}

void ellipsoid_jobs(const GenerateRequest& r, std::vector<Job>& out) {
  for (const EllipsoidConfig& cfg : ellipsoid_configs())
    for (long i = 0; i < r.count; ++i) {
      Rng rng(stream_seed(r.seed, "ellipsoid" + std::to_string(cfg.tu_case), i));
      const Pose pose = random_pose(rng, r.encoding == Encoding::Exact, true);
      Json c = base_construction("ellipsoid", r, i);
      c.set("tu_case", Json::number(cfg.tu_case));
      c.set("how", Json::string(cfg.how));
      out.push_back(make_job("ellipsoid-case" + two_digits(cfg.tu_case) + "-" + index_text(i),
                             "classify", cfg.a, cfg.b, pose, r.encoding, std::move(c)));
    }
}

// ---- natural quadrics (seed 002 Table 7 and beyond) ------------------------------------------

struct NaturalConfig {
  std::string name; ///< the id stem, e.g. "t7-cylinder-empty"
  std::string pair; ///< "ellipsoid-cylinder", "cylinder-cylinder", ...
  std::string a, b; ///< the two equations (local coordinates)
  int tu_case;      ///< the Tu case the construction aims at; 0: a degenerate pencil
  std::string how;  ///< the construction, in words
};

// Seed 002 Table 7 (an ellipsoid against a cylinder and against a cone: no intersection, one
// branch, two branches; the paper gives pictures, not coefficients) and natural-quadric pairs
// (circular cylinders and cones, paraboloids, hyperboloids, spheres) for the Tu cases they
// reach; E is x^2 + 2y^2 + 4z^2 = 1 (semi-axes 1, 1/sqrt 2, 1/2), P = (1, 0, 0) its vertex.
const std::vector<NaturalConfig>& natural_configs() {
  static const std::vector<NaturalConfig> c = {
      {"t7-cylinder-empty", "ellipsoid-cylinder", "x^2 + 2y^2 + 4z^2 - 1", "(x-3)^2 + y^2 - 1", 2,
       "Table 7: a cylinder (axis parallel to z) beside E, no intersection"},
      {"t7-cylinder-one-branch", "ellipsoid-cylinder", "x^2 + 2y^2 + 4z^2 - 1",
       "(x-1)^2 + y^2 - 1/4", 3,
       "Table 7: a cylinder (axis parallel to z) through P clipping E: one loop"},
      {"t7-cylinder-two-branches", "ellipsoid-cylinder", "x^2 + 2y^2 + 4z^2 - 1",
       "y^2 + z^2 - 1/16", 1,
       "Table 7: a thin cylinder along E's long axis, piercing E: two loops"},
      {"t7-cone-empty", "ellipsoid-cone", "x^2 + 2y^2 + 4z^2 - 1", "(x-3)^2 + y^2 - z^2", 2,
       "Table 7: a cone (axis parallel to z, vertex (3, 0, 0)) beside E, no intersection"},
      {"t7-cone-one-branch", "ellipsoid-cone", "x^2 + 2y^2 + 4z^2 - 1", "(x-1)^2 + y^2 - (z-1)^2",
       3,
       "Table 7: a right cone with vertex (1, 0, 1) above P, its lower nappe cutting E: one loop"},
      {"t7-cone-two-branches", "ellipsoid-cone", "x^2 + 2y^2 + 4z^2 - 1",
       "y^2 + z^2 - (1/64)(x-3)^2", 1,
       "Table 7: a narrow cone along E's long axis (vertex (3, 0, 0)) piercing E: two loops"},
      {"cone-vertex-on-e-crunode", "ellipsoid-cone", "x^2 + 2y^2 + 4z^2 - 1",
       "(x-1)^2 + y^2 - 2z^2", 5,
       "a cone with its vertex at P whose tangent-plane section is two real lines: figure eight"},
      {"cone-vertex-on-e-acnode", "ellipsoid-cone", "x^2 + 2y^2 + 4z^2 - 1",
       "-3(x-1)^2 + y^2 + 3z^2", 6,
       "a cone with its vertex at P meeting the tangent plane only at P: a loop and P isolated"},
      {"cone-vertex-on-e-cusp", "ellipsoid-cone", "x^2 + 2y^2 + 4z^2 - 1", "y^2 + (x-1)z", 9,
       "a cone with its vertex at P and a generator tangent to E: a loop with a cusp at P"},
      {"cylinder-touching-outside", "ellipsoid-cylinder", "x^2 + 2y^2 + 4z^2 - 1",
       "(x-3/2)^2 + y^2 - 1/4", 7, "a cylinder touching E from outside at P: one point"},
      {"cylinder-touching-inside", "ellipsoid-cylinder", "x^2 + 2y^2 + 4z^2 - 1",
       "(x-3/4)^2 + y^2 - 1/16", 5,
       "a thin cylinder touching E from inside at P, leaving through the top and bottom: figure "
       "eight"},
      {"cylinder-around-two-points", "ellipsoid-cylinder", "x^2 + 2y^2 + 4z^2 - 1", "x^2 + y^2 - 1",
       15, "the cylinder around E touching it at (+-1, 0, 0): two points"},
      {"cylinders-crossing-equal", "cylinder-cylinder", "x^2 + y^2 - 1", "x^2 + z^2 - 1", 13,
       "two unit cylinders, axes crossing at right angles (Steinmetz): two ellipses crossing at "
       "two points"},
      {"cylinders-crossing-unequal", "cylinder-cylinder", "x^2 + y^2 - 1", "x^2 + z^2 - 1/4", 1,
       "a thin cylinder through a thick one, axes crossing at right angles: two loops"},
      {"cylinders-offset", "cylinder-cylinder", "x^2 + y^2 - 1", "(x-1)^2 + z^2 - 1/4", 3,
       "a thin cylinder clipping the side of a thick one, axes skew at right angles: one loop"},
      {"cylinders-parallel", "cylinder-cylinder", "x^2 + y^2 - 1", "(x-1)^2 + y^2 - 1", 0,
       "two parallel cylinders: a common vertex at infinity, degenerate pencil"},
      {"cone-cylinder-coaxial", "cone-cylinder", "x^2 + y^2 - z^2", "x^2 + y^2 - 1", 14,
       "a cone and a cylinder on one axis: two circles"},
      {"hyperboloid1-cylinder-coaxial", "hyperboloid-cylinder", "x^2 + y^2 - z^2 - 1",
       "x^2 + y^2 - 2", 14,
       "a one-sheet hyperboloid and a wider cylinder on one axis: two circles"},
      {"hyperboloid1-sphere-waist", "hyperboloid-sphere", "x^2 + y^2 - z^2 - 1",
       "x^2 + y^2 + z^2 - 1", 21,
       "a one-sheet hyperboloid and the sphere on its waist: tangent along a circle"},
      {"hyperboloid2-sphere", "hyperboloid-sphere", "z^2 - x^2 - y^2 - 1", "x^2 + y^2 + z^2 - 4",
       14, "a two-sheet hyperboloid and a concentric sphere: a circle on each sheet"},
      {"paraboloid-sphere", "paraboloid-sphere", "z - x^2 - y^2", "x^2 + y^2 + z^2 - 2z", 24,
       "a paraboloid and the sphere resting in it at its vertex: a circle and the vertex"},
  };
  return c;
}

void natural_jobs(const GenerateRequest& r, std::vector<Job>& out) {
  for (const NaturalConfig& cfg : natural_configs())
    for (long i = 0; i < r.count; ++i) {
      Rng rng(stream_seed(r.seed, "natural-" + cfg.name, i));
      const Pose pose = random_pose(rng, r.encoding == Encoding::Exact, true);
      Json c = base_construction("natural", r, i);
      c.set("config", Json::string(cfg.name));
      c.set("pair", Json::string(cfg.pair));
      if (cfg.tu_case > 0)
        c.set("tu_case", Json::number(cfg.tu_case));
      else
        c.set("pencil", Json::string("degenerate"));
      c.set("how", Json::string(cfg.how));
      c.set("equations",
            Json::string("a: " + cfg.a + " = 0; b: " + cfg.b + " = 0 (before the pose)"));
      out.push_back(make_job("natural-" + cfg.name + "-" + index_text(i), "classify",
                             Surf{equation(cfg.a), std::nullopt},
                             Surf{equation(cfg.b), std::nullopt}, pose, r.encoding, std::move(c)));
    }
}

// ---- families ------------------------------------------------------------------------------

struct PencilFamily {
  std::string name, a, b0, d, how;
  int case_at_zero; ///< the Tu case the construction aims at for g = 0 (the label decides)
};

// Paths B(g) = B0 + g D through a degeneracy at g = 0. The touching point is the origin and
// D is the constant 1 or the monomial x (entries zero in B0), so in the double encoding the
// gap is an entry of its own, exactly +-2^-k or 2^-(k+1), for any k.
const std::vector<PencilFamily>& pencil_families() {
  static const std::vector<PencilFamily> f = {
      {"tangency", "x^2 - 2x + 2y^2 + 4z^2", "4x^2 + 4x + y^2 + 3z^2", "1",
       "two ellipsoids touching outside at the origin; g > 0 parts them", 7},
      {"node", "x^2 - 2x + 2y^2 + 4z^2", "x^2 - 2x + 2y^2 + 4z^2 + (1/4)(x^2 + y^2 - 2z^2)", "1",
       "a crunode at the origin (figure eight) at g = 0", 5},
      {"acnode", "x^2 - 2x + 2y^2 + 4z^2", "x^2 - 2x + 2y^2 + 4z^2 + (1/4)(-3x^2 + y^2 + 3z^2)",
       "1", "an isolated singular point at the origin at g = 0", 6},
      {"cusp", "x^2 - 2x + 2y^2 + 4z^2", "x^2 - 2x + 2y^2 + 4z^2 + (1/4)(y^2 + xz)", "1",
       "a cusp at the origin at g = 0", 9},
      {"double_conic", "x^2 + 2y^2 + 4z^2 - 1", "2x^2 + 2y^2 + 4z^2 - 1", "x",
       "tangent along a conic at g = 0 (the planes x = 0 and x = -g)", 21},
  };
  return f;
}

// The gaps of a family, in increasing order: -2^-k (k increasing), 0, +2^-k (k decreasing).
std::vector<std::pair<int, int>> family_points(std::vector<int> gaps) {
  std::sort(gaps.begin(), gaps.end());
  gaps.erase(std::unique(gaps.begin(), gaps.end()), gaps.end());
  std::vector<std::pair<int, int>> pts; // (sign, k)
  for (int k : gaps)
    pts.push_back({-1, k});
  pts.push_back({0, 0});
  for (auto it = gaps.rbegin(); it != gaps.rend(); ++it)
    pts.push_back({1, *it});
  return pts;
}

Json gap_json(int sign, int k, const Rational& g) {
  Json o = Json::object();
  o.set("sign", Json::number(sign));
  if (sign != 0) o.set("k", Json::number(k));
  o.set("value", Json::string(g.to_string()));
  return o;
}

std::string gap_id(int sign, int k) {
  return sign == 0 ? "0" : (sign < 0 ? "minus" : "plus") + std::to_string(k);
}

void pencil_family_jobs(const PencilFamily& f, const GenerateRequest& r, std::vector<Job>& out) {
  const Mat4 a = equation(f.a), b0 = equation(f.b0);
  Mat4 d{}; // the constant 1 is no quadric equation of its own
  if (f.d == "1")
    d[3][3] = Rational(1);
  else
    d = equation(f.d);
  for (long i = 0; i < r.count; ++i) {
    // One pose per path: every point of it is moved alike.
    Rng rng(stream_seed(r.seed, "family-" + f.name, i));
    const Pose pose =
        random_pose(rng, r.encoding == Encoding::Exact, r.encoding == Encoding::Exact);
    for (const auto& [sign, k] : family_points(r.gaps)) {
      const Rational g = sign == 0 ? Rational(0) : Rational(sign) * pow2(-k);
      Json c = base_construction("family", r, i);
      c.set("family", Json::string(f.name));
      c.set("how", Json::string(f.how));
      c.set("path", Json::string("A = " + f.a + "; B = " + f.b0 + " + g (" + f.d + ")"));
      c.set("gap", gap_json(sign, k, g));
      c.set("tu_case_at_gap_0", Json::number(f.case_at_zero));
      out.push_back(make_job("family-" + f.name + "-" + gap_id(sign, k) + "-" + index_text(i),
                             "classify", Surf{a, std::nullopt},
                             Surf{b0 + core::scaled(d, g), std::nullopt}, pose, r.encoding,
                             std::move(c)));
    }
  }
}

// Distance pairs with a closed-form answer, as shapes (a matrix in the exact encoding).
void distance_family_jobs(const std::string& name, const GenerateRequest& r,
                          std::vector<Job>& out) {
  const Rational h(1, 2), q(1, 4), one(1), zero(0);
  for (long i = 0; i < r.count; ++i) {
    Rng rng(stream_seed(r.seed, "family-" + name, i));
    const Pose pose =
        random_pose(rng, r.encoding == Encoding::Exact, r.encoding == Encoding::Exact);
    for (const auto& [sign, k] : family_points(r.gaps)) {
      const Rational g = sign == 0 ? Rational(0) : Rational(sign) * pow2(-k);
      Surf a, b;
      Rational expected;
      std::string how;
      if (name == "touching") {
        a = shape_surf(ShapeType::Ellipsoid, vec(one, h, q), vec(zero, zero, zero));
        b = shape_surf(ShapeType::Ellipsoid, vec(h, one, h), vec(Rational(3, 2) + g, zero, zero));
        expected = g.sign() > 0 ? g : Rational(0);
        how = "vertex (1,0,0) of A facing vertex (1+g,0,0) of B along their common normal: "
              "distance g (0 when they overlap)";
      } else {
        a = shape_surf(ShapeType::Sphere, vec(one, one, one), vec(zero, zero, zero));
        b = shape_surf(ShapeType::Sphere, vec(one + g, one + g, one + g), vec(zero, zero, zero));
        expected = g.sign() < 0 ? -g : g;
        how = "concentric spheres of radii 1 and 1 + g: distance |g|, every point a minimizer";
      }
      Json c = base_construction("family", r, i);
      c.set("family", Json::string(name));
      c.set("how", Json::string(how));
      c.set("gap", gap_json(sign, k, g));
      c.set("expected_distance", Json::string(expected.to_string()));
      out.push_back(make_job(
          "family-" + name + "-" + gap_id(sign, k) + "-" + index_text(i), "distance", a, b, pose,
          r.encoding == Encoding::Exact ? r.encoding : Encoding::Shape, std::move(c)));
    }
  }
}

// A nested pair with 4 or a circle family of symmetric minimizers, from a point Q on the outer
// ellipsoid O = {sum x_i^2 / o_i^2 = 1} (o = (2, 3, 4) or (3, 3, 4)): P = Q - s grad(Q)/2
// and the inner ellipsoid {sum w_i x_i^2 = 1} through P with its normal along grad(Q) there
// (w_i = lambda g_i / P_i, g = grad(Q)/2, lambda = 1 / (P . g); w_i = 1 / c1^2 where P_i = 0).
// When P is the closest point of the inner surface to O (checked by the label, not assumed),
// the distance is s |g| and the symmetries of O and the inner ellipsoid (the coordinate
// reflections) give the other minimizers: 4 points for Q = (6/5, 12/5, 0) on o = (2, 3, 4),
// two circles for Q = (1, 2, 8/3) on the spheroid o = (3, 3, 4). Integer matrices (the
// rational w's times a common denominator), so the double encoding holds them.
struct SymmetricPair {
  Mat4 inner, outer;
  Rational distance_squared;
};
SymmetricPair symmetric_pair(const std::array<Rational, 3>& o, const std::array<Rational, 3>& q,
                             const Rational& s, const Rational& c1) {
  std::array<Rational, 3> g, p, w;
  Rational pg, g2;
  for (size_t i = 0; i < 3; ++i) {
    g[i] = q[i] / (o[i] * o[i]);
    p[i] = q[i] - s * g[i];
    pg = pg + p[i] * g[i];
    g2 = g2 + g[i] * g[i];
  }
  const Rational lambda = Rational(1) / pg;
  for (size_t i = 0; i < 3; ++i)
    w[i] = p[i].sign() == 0 ? Rational(1) / (c1 * c1) : lambda * g[i] / p[i];
  // Scale each diagonal to integers: diag(w, -1) and diag(1/o^2, -1) times their denominators'
  // product (the surface is unchanged).
  auto integral = [](std::array<Rational, 4> d) {
    Rational den(1);
    for (const Rational& x : d)
      den = den * Rational(x.den(), core::Integer(1));
    Mat4 m{};
    for (size_t i = 0; i < 4; ++i)
      m[i][i] = d[i] * den;
    return m;
  };
  SymmetricPair out;
  out.inner = integral({w[0], w[1], w[2], Rational(-1)});
  out.outer = integral({Rational(1) / (o[0] * o[0]), Rational(1) / (o[1] * o[1]),
                        Rational(1) / (o[2] * o[2]), Rational(-1)});
  out.distance_squared = s * s * g2;
  return out;
}

// --case distance: K random instances each of two separated spheres, nested spheres,
// ellipsoids touching at a gap 2^-k (k in 10..40), and nested pairs whose minimizers are k
// symmetric points or continua: a sphere centred in a triaxial ellipsoid (2 points), in a
// spheroid around its axis (a circle), and symmetric_pair's 4 points and two circles.
void distance_jobs(const GenerateRequest& r, std::vector<Job>& out) {
  const Encoding enc = r.encoding == Encoding::Exact ? r.encoding : Encoding::Shape;
  const bool exact = r.encoding == Encoding::Exact;
  for (const char* kind : {"two_spheres", "nested_spheres", "touching_ellipsoids", "minimizers_2",
                           "minimizers_circle", "minimizers_4", "minimizers_two_circles"})
    for (long i = 0; i < r.count; ++i) {
      Rng rng(stream_seed(r.seed, kind, i));
      Json c = base_construction("distance", r, i);
      c.set("kind", Json::string(kind));
      Surf a, b;
      const std::string k = kind;
      if (k == "two_spheres") {
        std::array<Rational, 3> c1, c2;
        Rational r1, r2, d2;
        do {
          for (int j = 0; j < 3; ++j) {
            c1[j] = rng.small_dyadic(16, 2);
            c2[j] = rng.small_dyadic(16, 2);
          }
          r1 = Rational(rng.uniform(1, 8), 4);
          r2 = Rational(rng.uniform(1, 8), 4);
          d2 = Rational(0);
          for (int j = 0; j < 3; ++j)
            d2 = d2 + (c1[j] - c2[j]) * (c1[j] - c2[j]);
        } while (!(d2 > (r1 + r2) * (r1 + r2)));
        a = shape_surf(ShapeType::Sphere, vec(r1, r1, r1), c1);
        b = shape_surf(ShapeType::Sphere, vec(r2, r2, r2), c2);
        c.set("how", Json::string("separated spheres: distance sqrt(centre_distance_squared) - "
                                  "radius_sum"));
        c.set("centre_distance_squared", Json::string(d2.to_string()));
        c.set("radius_sum", Json::string((r1 + r2).to_string()));
      } else if (k == "nested_spheres") {
        std::array<Rational, 3> c0;
        for (Rational& x : c0)
          x = rng.small_dyadic(16, 2);
        const Rational r1(rng.uniform(1, 8), 4);
        const Rational r2 = r1 + Rational(rng.uniform(1, 8), 4);
        a = shape_surf(ShapeType::Sphere, vec(r1, r1, r1), c0);
        b = shape_surf(ShapeType::Sphere, vec(r2, r2, r2), c0);
        c.set("how", Json::string("concentric spheres: distance r2 - r1, every point a minimizer"));
        c.set("expected_distance", Json::string((r2 - r1).to_string()));
      } else if (k == "minimizers_2" || k == "minimizers_circle") {
        // A sphere of radius rs at the centre of an ellipsoid with semi-axes e0 < e1 < e2 (or
        // e0 = e1 < e2): the closest points are the ends of the shortest axis, (+-e0, 0, 0)
        // (2 points), or the circle of radius e0 in the plane z = 0; distance e0 - rs.
        const Rational rs(rng.uniform(1, 4), 4);
        const Rational e0 = rs + Rational(rng.uniform(1, 8), 8);
        const Rational e1 = k == "minimizers_2" ? e0 + Rational(rng.uniform(1, 8), 8) : e0;
        const Rational e2 = e1 + Rational(rng.uniform(1, 8), 8);
        std::array<Rational, 3> c0;
        for (Rational& x : c0)
          x = rng.small_dyadic(16, 2);
        a = shape_surf(ShapeType::Sphere, vec(rs, rs, rs), c0);
        b = shape_surf(ShapeType::Ellipsoid, vec(e0, e1, e2), c0);
        c.set("how", Json::string(k == "minimizers_2"
                                      ? "a sphere centred in a triaxial ellipsoid: distance "
                                        "shortest semi-axis - radius, at the 2 ends of that axis"
                                      : "a sphere centred in a spheroid (two equal short "
                                        "semi-axes): distance short semi-axis - radius, along a "
                                        "circle"));
        c.set("expected_distance", Json::string((e0 - rs).to_string()));
        c.set("expected_minimizers", Json::string(k == "minimizers_2" ? "2" : "infinite"));
      } else if (k == "minimizers_4" || k == "minimizers_two_circles") {
        const bool four = k == "minimizers_4";
        const Rational s(rng.uniform(1, 2), 2); // 1/2 or 1
        const SymmetricPair sp =
            four ? symmetric_pair(vec(Rational(2), Rational(3), Rational(4)),
                                  vec(Rational(6, 5), Rational(12, 5), Rational(0)), s, Rational(1))
                 : symmetric_pair(vec(Rational(3), Rational(3), Rational(4)),
                                  vec(Rational(1), Rational(2), Rational(8, 3)), s, Rational(1));
        a = Surf{sp.inner, std::nullopt};
        b = Surf{sp.outer, std::nullopt};
        c.set("how", Json::string(
                         four ? "an ellipsoid inside the ellipsoid (2, 3, 4), touching its offset "
                                "at distance d at the 4 points (+-9/10, +-32/15, 0) (s = 1) or "
                                "(+-21/20, +-34/15, 0) (s = 1/2): d^2 = expected_distance_squared"
                              : "an ellipsoid of revolution inside the spheroid (3, 3, 4), "
                                "closest along two circles (z = +-(8/3 - s/6)): d^2 = "
                                "expected_distance_squared"));
        c.set("s", Json::string(s.to_string()));
        c.set("expected_distance_squared", Json::string(sp.distance_squared.to_string()));
        c.set("expected_minimizers", Json::string(four ? "4" : "infinite"));
      } else {
        const int kk = static_cast<int>(rng.uniform(10, 40));
        const Rational g = pow2(-kk);
        const Rational h(1, 2), q(1, 4), one(1), zero(0);
        a = shape_surf(ShapeType::Ellipsoid, vec(one, h, q), vec(zero, zero, zero));
        b = shape_surf(ShapeType::Ellipsoid, vec(h, one, h), vec(Rational(3, 2) + g, zero, zero));
        c.set("how", Json::string("vertex to vertex along the common normal at gap 2^-k"));
        c.set("k", Json::number(kk));
        c.set("expected_distance", Json::string(g.to_string()));
      }
      const Pose pose = random_pose(rng, exact, true);
      out.push_back(make_job(std::string(kind) + "-" + index_text(i), "distance", a, b, pose, enc,
                             std::move(c)));
    }
}

// ---- labels --------------------------------------------------------------------------------

Json label_of(const Job& j) {
  core::io::Readings readings;
  const core::Surface sa = core::io::read_surface(j.a, "<generate>", "$.a", &readings);
  const core::Surface sb = core::io::read_surface(j.b, "<generate>", "$.b", &readings);
  Json label = Json::object();
  if (j.op == "classify") {
    const auto& a = std::get<core::QuadricMatrix>(sa);
    const auto& b = std::get<core::QuadricMatrix>(sb);
    certify::QsicResult r = certify::classify_qsic(a, b, certify::Mode::Filtered);
    certify::complete_report_data(r, a, b, certify::Detail::Topology);
    const Json env = certify::qsic_envelope_json(r, a, b, certify::Detail::Topology);
    label.set("status", *env.find("status"));
    if (const Json* res = env.find("result"))
      for (const char* key : {"pencil", "tu_case", "morphology", "segre", "ellipsoid_relation"})
        if (const Json* v = res->find(key)) label.set(key, *v);
  } else {
    const certify::DistanceResult d =
        certify::surface_distance(sa, sb, 15, false, certify::Mode::Filtered);
    const Json env = certify::distance_envelope_json(d, 15, certify::Detail::Value);
    label.set("status", *env.find("status"));
    if (const Json* res = env.find("result"))
      for (const char* key : {"distance", "minimizers", "method"})
        if (const Json* v = res->find(key)) label.set(key, *v);
  }
  label.set("certified_by", Json::string(std::string("surfcert ") + j.op + " (mode filtered)"));
  label.set("construction", j.construction);
  return label;
}

} // namespace

std::vector<Json> generate(const GenerateRequest& r) {
  if (r.count < 1 || r.count > 1000000)
    refuse("$.count", "--count 1..1000000", std::to_string(r.count));
  for (std::size_t i = 0; i < r.gaps.size(); ++i)
    if (r.gaps[i] < 1 || r.gaps[i] > 1000)
      refuse(core::io::json_path_index("$.gaps", i), "gaps k from 1 to 1000",
             std::to_string(r.gaps[i]));
  std::vector<Job> jobs;
  if (!r.family.empty()) {
    const auto& names = family_names();
    if (r.family != "all" && std::find(names.begin(), names.end(), r.family) == names.end())
      refuse("$.family",
             "--family all, tangency, node, acnode, cusp, double_conic, touching or nested",
             "\"" + r.family + "\"");
    if (r.gaps.empty()) refuse("$.gaps", "--gaps: at least one k", "none");
    for (const PencilFamily& f : pencil_families())
      if (r.family == "all" || r.family == f.name) pencil_family_jobs(f, r, jobs);
    for (const char* name : {"touching", "nested"})
      if (r.family == "all" || r.family == name) distance_family_jobs(name, r, jobs);
  } else if (r.what == "all") {
    for (int c = 1; c <= 35; ++c)
      pencil_case_jobs(c, r, jobs);
    special_pencil_jobs("degenerate_pencil", r, jobs);
    special_pencil_jobs("coincident", r, jobs);
  } else if (r.what == "degenerate_pencil" || r.what == "coincident") {
    special_pencil_jobs(r.what, r, jobs);
  } else if (r.what == "ellipsoid") {
    ellipsoid_jobs(r, jobs);
  } else if (r.what == "natural") {
    natural_jobs(r, jobs);
  } else if (r.what == "distance") {
    distance_jobs(r, jobs);
  } else {
    int c = 0;
    if (r.what.size() <= 2 && r.what.find_first_not_of("0123456789") == std::string::npos &&
        !r.what.empty())
      c = std::stoi(r.what);
    if (c < 1 || c > 35)
      refuse("$.case",
             "--case 1..35, all, degenerate_pencil, coincident, ellipsoid, natural or distance",
             "\"" + r.what + "\"");
    pencil_case_jobs(c, r, jobs);
  }
  std::vector<Json> lines(jobs.size());
  auto one = [&](size_t i) {
    const Job& j = jobs[i];
    Json line = Json::object();
    line.set("id", Json::string(j.id));
    line.set("op", Json::string(j.op));
    line.set("a", j.a);
    line.set("b", j.b);
    Json label;
    try {
      label = label_of(j);
    } catch (const std::exception& e) {
      label = Json::object();
      label.set("status", Json::string("error"));
      label.set("message", Json::string(e.what()));
      label.set("construction", j.construction);
    }
    line.set("label", label);
    lines[i] = std::move(line);
  };
  tbb::task_arena arena(std::max(1, r.threads));
  arena.execute([&] { tbb::parallel_for(size_t(0), jobs.size(), [&](size_t i) { one(i); }); });
  return lines;
}

} // namespace surfcert::app
