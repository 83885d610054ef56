// quadric_distance_bench: certified surface distance between two quadrics, neither a sphere
// (the offset method), on five random families, at 15 and 100 digits; with an independent
// float check of the enclosures (a float search gives a genuine pair of surface points, so
// its distance f bounds the true minimum from above: lower > f is a bug).
// Families (each `pairs` cases, exact rational coefficients, fixed seed):
//   1. separated ellipsoids (the second translated by a rational vector of length 2.5-3.5);
//   2. nested ellipsoids (a random ellipsoid inside one with radii in [3, 4]);
//   3. ellipsoid vs circular/elliptic cylinder (radii in [0.3, 1], axis 2-3 from the origin);
//   4. ellipsoid vs circular/elliptic cone (vertex 2-3 from the origin);
//   5. ellipsoid vs elliptic paraboloid (vertex 2-3 from the origin).
// Float search: multi-start alternating projection (Eberly's bisection for ellipsoids and
// ellipses, a secular equation for the paraboloid, the rulings for the cone) and a sampling
// of the ellipsoid projected onto the other surface.
// Usage: quadric_distance_bench [pairs=200] [seed=2026] [mode_pairs=20]
// (mode_pairs: how many pairs per family also run in float and exact mode)
#include "random_ellipsoids.hpp"

#include "surfcert/certify/distance/distance.hpp"

#include <flint/flint.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace surfcert;

namespace {

using V3 = std::array<double, 3>;
using M3 = std::array<V3, 3>;

V3 add(const V3& a, const V3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
V3 sub(const V3& a, const V3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const V3& a) {
  return std::sqrt(dot(a, a));
}
V3 mul(const M3& r, const V3& v) { // r v
  return {dot(r[0], v), dot(r[1], v), dot(r[2], v)};
}
V3 mul_t(const M3& r, const V3& v) { // r^T v
  V3 o{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      o[i] += r[j][i] * v[j];
  return o;
}

// ---------------------------------------------------------------------------------------
// Float point-to-surface projections (local frames). Each returns a point ON the surface.

// Eberly, "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid".
double robust_length(double a, double b, double c = 0) {
  double m = std::max({std::fabs(a), std::fabs(b), std::fabs(c)});
  if (m == 0) return 0;
  a /= m, b /= m, c /= m;
  return m * std::sqrt(a * a + b * b + c * c);
}

double root2(double r0, double z0, double z1, double g) {
  double n0 = r0 * z0, s0 = z1 - 1, s1 = g < 0 ? 0 : robust_length(n0, z1) - 1, s = 0;
  for (int i = 0; i < 1100; ++i) {
    s = (s0 + s1) / 2;
    if (s == s0 || s == s1) break;
    double a = n0 / (s + r0), b = z1 / (s + 1);
    double gg = a * a + b * b - 1;
    if (gg > 0)
      s0 = s;
    else if (gg < 0)
      s1 = s;
    else
      break;
  }
  return s;
}

// e0 >= e1 > 0, y0, y1 >= 0.
void ellipse_closest(double e0, double e1, double y0, double y1, double& x0, double& x1) {
  if (y1 > 0) {
    if (y0 > 0) {
      double z0 = y0 / e0, z1 = y1 / e1, g = z0 * z0 + z1 * z1 - 1;
      if (g != 0) {
        double r0 = (e0 / e1) * (e0 / e1), s = root2(r0, z0, z1, g);
        x0 = r0 * y0 / (s + r0);
        x1 = y1 / (s + 1);
      } else {
        x0 = y0, x1 = y1;
      }
    } else {
      x0 = 0, x1 = e1;
    }
  } else {
    double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
    if (numer0 < denom0) {
      double xde0 = numer0 / denom0;
      x0 = e0 * xde0;
      x1 = e1 * std::sqrt(std::max(0.0, 1 - xde0 * xde0));
    } else {
      x0 = e0, x1 = 0;
    }
  }
}

double root3(double r0, double r1, double z0, double z1, double z2, double g) {
  double n0 = r0 * z0, n1 = r1 * z1, s0 = z2 - 1;
  double s1 = g < 0 ? 0 : robust_length(n0, n1, z2) - 1, s = 0;
  for (int i = 0; i < 1100; ++i) {
    s = (s0 + s1) / 2;
    if (s == s0 || s == s1) break;
    double a = n0 / (s + r0), b = n1 / (s + r1), c = z2 / (s + 1);
    double gg = a * a + b * b + c * c - 1;
    if (gg > 0)
      s0 = s;
    else if (gg < 0)
      s1 = s;
    else
      break;
  }
  return s;
}

// e0 >= e1 >= e2 > 0, y_i >= 0.
void ellipsoid_closest_sorted(const V3& e, const V3& y, V3& x) {
  if (y[2] > 0) {
    if (y[1] > 0) {
      if (y[0] > 0) {
        double z0 = y[0] / e[0], z1 = y[1] / e[1], z2 = y[2] / e[2];
        double g = z0 * z0 + z1 * z1 + z2 * z2 - 1;
        if (g != 0) {
          double r0 = (e[0] / e[2]) * (e[0] / e[2]), r1 = (e[1] / e[2]) * (e[1] / e[2]);
          double s = root3(r0, r1, z0, z1, z2, g);
          x = {r0 * y[0] / (s + r0), r1 * y[1] / (s + r1), y[2] / (s + 1)};
        } else {
          x = y;
        }
      } else {
        x[0] = 0;
        ellipse_closest(e[1], e[2], y[1], y[2], x[1], x[2]);
      }
    } else {
      x[1] = 0;
      if (y[0] > 0)
        ellipse_closest(e[0], e[2], y[0], y[2], x[0], x[2]);
      else
        x = {0, 0, e[2]};
    }
  } else {
    double d0 = e[0] * e[0] - e[2] * e[2], d1 = e[1] * e[1] - e[2] * e[2];
    double n0 = e[0] * y[0], n1 = e[1] * y[1];
    if (n0 < d0 && n1 < d1) {
      double a = n0 / d0, b = n1 / d1, discr = 1 - a * a - b * b;
      if (discr > 0) {
        x = {e[0] * a, e[1] * b, e[2] * std::sqrt(discr)};
        return;
      }
    }
    x[2] = 0;
    ellipse_closest(e[0], e[1], y[0], y[1], x[0], x[1]);
  }
}

V3 ellipsoid_closest(const V3& radii, const V3& y) {
  std::array<int, 3> idx{0, 1, 2};
  std::sort(idx.begin(), idx.end(), [&](int i, int j) {
    return radii[static_cast<size_t>(i)] > radii[static_cast<size_t>(j)];
  });
  V3 e, ya, x;
  for (size_t k = 0; k < 3; ++k) {
    e[k] = radii[static_cast<size_t>(idx[k])];
    ya[k] = std::fabs(y[static_cast<size_t>(idx[k])]);
  }
  ellipsoid_closest_sorted(e, ya, x);
  V3 out;
  for (size_t k = 0; k < 3; ++k) {
    size_t i = static_cast<size_t>(idx[k]);
    out[i] = std::copysign(x[k], y[i]);
  }
  return out;
}

V3 ellipse_closest_any(double a, double b, double y0, double y1) { // x^2/a^2 + y^2/b^2 = 1
  double x0, x1;
  if (a >= b) {
    ellipse_closest(a, b, std::fabs(y0), std::fabs(y1), x0, x1);
  } else {
    ellipse_closest(b, a, std::fabs(y1), std::fabs(y0), x1, x0);
  }
  return {std::copysign(x0, y0), std::copysign(x1, y1), 0};
}

// Cone x^2/a^2 + y^2/b^2 = z^2: its points are s (a cos t, b sin t, 1); for a fixed t the best
// s is the projection onto the ruling, then t is minimised (dense scan + golden section).
V3 cone_closest(double a, double b, const V3& y) {
  auto ruling = [&](double t, V3& q) {
    V3 d{a * std::cos(t), b * std::sin(t), 1};
    double s = dot(y, d) / dot(d, d);
    q = {s * d[0], s * d[1], s * d[2]};
    V3 r = sub(y, q);
    return dot(r, r);
  };
  const int n = 180;
  const double two_pi = 2 * M_PI;
  int best = 0;
  double bv = 1e300;
  V3 q;
  for (int i = 0; i < n; ++i) {
    double v = ruling(two_pi * i / n, q);
    if (v < bv) bv = v, best = i;
  }
  double lo = two_pi * (best - 1) / n, hi = two_pi * (best + 1) / n;
  const double gr = (std::sqrt(5.0) - 1) / 2;
  double c = hi - gr * (hi - lo), d = lo + gr * (hi - lo);
  double fc = ruling(c, q), fd = ruling(d, q);
  for (int it = 0; it < 60; ++it) {
    if (fc < fd) {
      hi = d, d = c, fd = fc;
      c = hi - gr * (hi - lo);
      fc = ruling(c, q);
    } else {
      lo = c, c = d, fc = fd;
      d = lo + gr * (hi - lo);
      fd = ruling(d, q);
    }
  }
  ruling((lo + hi) / 2, q);
  return q;
}

// Paraboloid z = x^2/a^2 + y^2/b^2: q = (y0/(1-2l/a^2), y1/(1-2l/b^2), .) with the unique root
// l < min(a^2, b^2)/2 of the increasing secular function; z recomputed so q is on it.
V3 paraboloid_closest(double a, double b, const V3& y) {
  double A = a * a, B = b * b;
  auto h = [&](double l) {
    double u = y[0] / (1 - 2 * l / A), v = y[1] / (1 - 2 * l / B);
    return u * u / A + v * v / B - y[2] + l;
  };
  double hi = std::min(A, B) / 2, lo = std::min(y[2], 0.0) - 1;
  while (h(lo) > 0)
    lo = 2 * lo - 1;
  for (int i = 0; i < 1100; ++i) {
    double m = (lo + hi) / 2;
    if (m == lo || m == hi) break;
    double v = h(m);
    if (v > 0)
      hi = m;
    else if (v < 0)
      lo = m;
    else {
      lo = hi = m;
      break;
    }
  }
  double l = lo;
  double u = y[0] / (1 - 2 * l / A), v = y[1] / (1 - 2 * l / B);
  return {u, v, u * u / A + v * v / B};
}

enum class Kind { Ellipsoid, Cylinder, Cone, Paraboloid };
const char* kind_name(Kind k) {
  switch (k) {
  case Kind::Ellipsoid:
    return "ellipsoid";
  case Kind::Cylinder:
    return "cylinder";
  case Kind::Cone:
    return "cone";
  case Kind::Paraboloid:
    return "paraboloid";
  }
  return "?";
}

// A surface as doubles: world = centre + rotation * local.
struct FSurface {
  Kind kind = Kind::Ellipsoid;
  V3 radii{}; // ellipsoid: 3 semi-axes; others: a, b (third unused)
  M3 rot{};
  V3 centre{};
  std::string exact_params; // the exact construction, for reports

  V3 project(const V3& p) const {
    V3 y = mul_t(rot, sub(p, centre)), x;
    switch (kind) {
    case Kind::Ellipsoid:
      x = ellipsoid_closest(radii, y);
      break;
    case Kind::Cylinder:
      x = ellipse_closest_any(radii[0], radii[1], y[0], y[1]);
      x[2] = y[2];
      break;
    case Kind::Cone:
      x = cone_closest(radii[0], radii[1], y);
      break;
    case Kind::Paraboloid:
      x = paraboloid_closest(radii[0], radii[1], y);
      break;
    }
    return add(centre, mul(rot, x));
  }
  V3 ellipsoid_point(const V3& u) const { // u a unit vector
    return add(centre, mul(rot, V3{radii[0] * u[0], radii[1] * u[1], radii[2] * u[2]}));
  }
};

std::vector<V3> fibonacci(int n) {
  std::vector<V3> out;
  const double ga = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(std::max(0.0, 1 - z * z));
    out.push_back({r * std::cos(ga * i), r * std::sin(ga * i), z});
  }
  return out;
}

struct FloatResult {
  double f = 1e300;       ///< best pair distance found (upper bound up to float error)
  double sampled = 1e300; ///< coarse sampling alone
  V3 p{}, q{};
};

// a must be an ellipsoid. Alternating projection p -> q = P_b(p) -> p = P_a(q).
FloatResult float_distance(const FSurface& a, const FSurface& b) {
  FloatResult r;
  struct Run {
    V3 p, q;
    double d;
  };
  auto step = [&](Run& s, int iters) {
    double window = s.d;
    for (int it = 0; it < iters; ++it) {
      V3 q = b.project(s.p);
      V3 p = a.project(q);
      double d = norm(sub(p, q));
      double moved = norm(sub(p, s.p));
      s.p = p, s.q = q;
      s.d = std::min(s.d, d);
      if (d < r.f) r.f = d, r.p = p, r.q = q;
      if (moved < 1e-15) break;
      if (it % 100 == 99) { // stalled (float noise of the projections): stop
        if (window - s.d < 1e-15) break;
        window = s.d;
      }
    }
  };
  // Coarse sampling: points of a, each to its closest point of b.
  std::vector<Run> runs;
  for (const V3& u : fibonacci(400)) {
    V3 p = a.ellipsoid_point(u), q = b.project(p);
    double d = norm(sub(p, q));
    runs.push_back({p, q, d});
    r.sampled = std::min(r.sampled, d);
    if (d < r.f) r.f = d, r.p = p, r.q = q;
  }
  std::sort(runs.begin(), runs.end(), [](const Run& x, const Run& y) { return x.d < y.d; });
  runs.resize(6);
  for (const V3& u : fibonacci(50)) {
    V3 p = a.ellipsoid_point(u);
    runs.push_back({p, p, 1e300});
  }
  for (Run& s : runs)
    step(s, 150);
  std::sort(runs.begin(), runs.end(), [](const Run& x, const Run& y) { return x.d < y.d; });
  for (size_t i = 0; i < 3 && i < runs.size(); ++i)
    step(runs[i], 20000);
  return r;
}

// ---------------------------------------------------------------------------------------
// Exact construction.

struct Pose {
  long w, x, y, z; // integer quaternion
  long n;          // w^2 + x^2 + y^2 + z^2
  long R[3][3];
};

Pose random_pose(std::mt19937_64& rng) {
  std::uniform_int_distribution<long> q(-9, 9);
  Pose p;
  do {
    p.w = q(rng), p.x = q(rng), p.y = q(rng), p.z = q(rng);
  } while (p.w == 0 && p.x == 0 && p.y == 0 && p.z == 0);
  long w = p.w, x = p.x, y = p.y, z = p.z;
  p.n = w * w + x * x + y * y + z * z;
  long R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                  {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                  {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      p.R[i][j] = R[i][j];
  return p;
}

// The quadric {centre + R/n * l : local(l) = 0}.
core::QuadricMatrix place(const core::Mat4& local, const Pose& pose,
                          const std::array<core::Rational, 3>& cen) {
  using core::Rational;
  core::Mat4 t;
  for (size_t i = 0; i < 3; ++i) {
    Rational s;
    for (size_t j = 0; j < 3; ++j) {
      t[i][j] = Rational(pose.R[j][i]) / Rational(pose.n);
      s += t[i][j] * cen[j];
    }
    t[i][3] = -s;
  }
  t[3][3] = Rational(1);
  return core::QuadricMatrix(core::transpose(t) * local * t);
}

M3 rot_double(const Pose& p) {
  M3 r;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      r[i][j] = static_cast<double>(p.R[i][j]) / static_cast<double>(p.n);
  return r;
}

std::string pose_text(const Pose& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "quaternion [%ld, %ld, %ld, %ld]", p.w, p.x, p.y, p.z);
  return buf;
}

std::string vec_text(const std::array<core::Rational, 3>& c) {
  return "[" + c[0].to_string() + ", " + c[1].to_string() + ", " + c[2].to_string() + "]";
}

// Translation of q by the exact vector t: q'(x) = q(x - t).
core::QuadricMatrix translated(const core::QuadricMatrix& q,
                               const std::array<core::Rational, 3>& t) {
  core::Mat4 p = core::identity4();
  for (size_t i = 0; i < 3; ++i)
    p[i][3] = -t[i];
  return q.congruent(p);
}

// A rational vector (step 1/1000) of length about len in a uniformly random direction.
std::array<core::Rational, 3> random_offset(std::mt19937_64& rng, double len) {
  std::normal_distribution<double> g(0, 1);
  V3 v;
  do {
    v = {g(rng), g(rng), g(rng)};
  } while (norm(v) < 1e-3);
  double s = len / norm(v);
  std::array<core::Rational, 3> t;
  for (size_t i = 0; i < 3; ++i)
    t[i] = core::Rational(std::lround(v[i] * s * 1000), 1000);
  return t;
}

struct Case {
  core::QuadricMatrix a, b;
  FSurface fa, fb;
};

FSurface ellipsoid_surface(const bench::EllipsoidParams& p, const std::string& text) {
  FSurface s;
  s.kind = Kind::Ellipsoid;
  s.radii = {p.radii[0], p.radii[1], p.radii[2]};
  for (size_t i = 0; i < 3; ++i) {
    s.centre[i] = p.centre[i];
    for (size_t j = 0; j < 3; ++j)
      s.rot[i][j] = p.rotation[i][j];
  }
  s.exact_params = text;
  return s;
}

std::string ellipsoid_text(const bench::EllipsoidParams& p) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "random_ellipsoid radii [%.2f, %.2f, %.2f] centre [%.3f, %.3f, %.3f]", p.radii[0],
                p.radii[1], p.radii[2], p.centre[0], p.centre[1], p.centre[2]);
  return buf;
}

Case make_case(int set, std::mt19937_64& rng) {
  using core::Mat4;
  using core::Rational;
  auto e = bench::random_ellipsoid(rng);
  Case c{e.quadric, e.quadric, ellipsoid_surface(e.params, ellipsoid_text(e.params)), {}};
  if (set == 1) {
    auto e2 = bench::random_ellipsoid(rng);
    std::uniform_real_distribution<double> len(2.5, 3.5);
    auto t = random_offset(rng, len(rng));
    c.b = translated(e2.quadric, t);
    c.fb =
        ellipsoid_surface(e2.params, ellipsoid_text(e2.params) + " translated by " + vec_text(t));
    for (size_t i = 0; i < 3; ++i)
      c.fb.centre[i] = e2.params.centre[i] + t[i].to_double_approx();
    return c;
  }
  Pose pose = random_pose(rng);
  std::array<Rational, 3> cen;
  FSurface& s = c.fb;
  s.rot = rot_double(pose);
  Mat4 local;
  if (set == 2) {
    std::uniform_int_distribution<long> r(300, 400), cc(-300, 300);
    long ri[3] = {r(rng), r(rng), r(rng)};
    for (size_t i = 0; i < 3; ++i) {
      Rational rad(ri[i], 100);
      local[i][i] = Rational(1) / (rad * rad);
      s.radii[i] = static_cast<double>(ri[i]) / 100;
    }
    local[3][3] = Rational(-1);
    for (size_t i = 0; i < 3; ++i) {
      long ci = cc(rng);
      cen[i] = Rational(ci, 1000);
      s.centre[i] = static_cast<double>(ci) / 1000;
    }
    s.kind = Kind::Ellipsoid;
    c.b = place(local, pose, cen);
    s.exact_params = "ellipsoid radii [" + std::to_string(ri[0]) + "/100, " +
                     std::to_string(ri[1]) + "/100, " + std::to_string(ri[2]) + "/100] " +
                     pose_text(pose) + " centre " + vec_text(cen);
    // The inner one is a: b must be the big one, order (small, big).
    return c;
  }
  // Sets 3-5: radii a, b in [0.3, 1] (circular half the time), placed at D in [2, 3] along
  // the rotated local x axis (perpendicular to the axis).
  std::uniform_int_distribution<long> r(30, 100), dd(2000, 3000), coin(0, 1);
  long ra = r(rng), rb = coin(rng) ? ra : r(rng);
  long di = dd(rng);
  Rational A(ra, 100), B(rb, 100), D(di, 1000);
  s.radii = {static_cast<double>(ra) / 100, static_cast<double>(rb) / 100, 0};
  for (size_t i = 0; i < 3; ++i) {
    cen[i] = D * Rational(pose.R[i][0]) / Rational(pose.n);
    s.centre[i] = cen[i].to_double_approx();
  }
  local[0][0] = Rational(1) / (A * A);
  local[1][1] = Rational(1) / (B * B);
  std::string shape;
  if (set == 3) {
    s.kind = Kind::Cylinder;
    local[3][3] = Rational(-1);
    shape = "cylinder x^2/a^2 + y^2/b^2 = 1";
  } else if (set == 4) {
    s.kind = Kind::Cone;
    local[2][2] = Rational(-1);
    shape = "cone x^2/a^2 + y^2/b^2 = z^2";
  } else {
    s.kind = Kind::Paraboloid;
    local[2][3] = local[3][2] = Rational(-1, 2);
    shape = "paraboloid x^2/a^2 + y^2/b^2 = z";
  }
  c.b = place(local, pose, cen);
  s.exact_params = shape + " a = " + A.to_string() + " b = " + B.to_string() + " " +
                   pose_text(pose) + " centre " + vec_text(cen) + " (D = " + D.to_string() + ")";
  return c;
}

// ---------------------------------------------------------------------------------------

struct Run {
  certify::DistanceResult r;
  bool threw = false;
  std::string what;
  double us = 0;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

std::string equation(const core::QuadricMatrix& q) {
  return q.to_poly().to_string() + " = 0";
}

bool is_zero_result(const certify::DistanceResult& r) {
  return r.status == certify::Status::Certified && r.upper() == "0";
}

} // namespace

int main(int argc, char** argv) {
  long pairs = argc > 1 ? std::atol(argv[1]) : 200;
  unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2026;
  // pairs per family also run in float and exact mode (the exact offset method is slow)
  const long mode_pairs = argc > 3 ? std::atol(argv[3]) : 20;
  const char* titles[6] = {"",
                           "Separated ellipsoid pairs",
                           "Nested ellipsoid pairs (small inside big)",
                           "Ellipsoid vs cylinder",
                           "Ellipsoid vs cone",
                           "Ellipsoid vs elliptic paraboloid"};
  std::printf("# Quadric pair certified distance (quadric_distance_bench %ld %lu)\n\n", pairs,
              seed);
  long total_violations = 0;
  for (int set = 1; set <= 5; ++set) {
    std::mt19937_64 rng(seed * 10 + static_cast<unsigned long>(set));
    std::vector<Case> cases;
    for (long i = 0; i < pairs; ++i)
      cases.push_back(make_case(set, rng));
    const long digits_list[2] = {15, 100};
    std::vector<std::vector<Run>> runs(2, std::vector<Run>(static_cast<size_t>(pairs)));
    std::vector<FloatResult> fl(static_cast<size_t>(pairs));
    double float_us = 0;
    long next_pct = 10;
    for (long i = 0; i < pairs; ++i) {
      const Case& c = cases[static_cast<size_t>(i)];
      for (size_t k = 0; k < 2; ++k) {
        Run& run = runs[k][static_cast<size_t>(i)];
        auto t0 = std::chrono::steady_clock::now();
        try {
          run.r = certify::surface_distance(c.a, c.b, digits_list[k], false);
        } catch (const std::exception& ex) {
          run.threw = true;
          run.what = ex.what();
        }
        auto t1 = std::chrono::steady_clock::now();
        run.us = std::chrono::duration<double, std::micro>(t1 - t0).count();
      }
      auto t0 = std::chrono::steady_clock::now();
      fl[static_cast<size_t>(i)] = float_distance(c.fa, c.fb);
      auto t1 = std::chrono::steady_clock::now();
      float_us += std::chrono::duration<double, std::micro>(t1 - t0).count();
      while ((i + 1) * 100 >= next_pct * pairs && next_pct <= 100) {
        std::fprintf(stderr, "set %d: %ld%% (%ld/%ld)\n", set, next_pct, i + 1, pairs);
        next_pct += 10;
      }
    }

    std::printf("## %d. %s\n\n", set, titles[set]);
    std::printf("| digits | median us | mean us | certified | undecided | zero | error |\n"
                "|---|---|---|---|---|---|---|\n");
    double med[2] = {0, 0};
    for (size_t k = 0; k < 2; ++k) {
      std::vector<double> t;
      long cert = 0, und = 0, zero = 0, err = 0;
      double mean = 0;
      for (const Run& run : runs[k]) {
        t.push_back(run.us);
        mean += run.us;
        if (run.threw || run.r.status == certify::Status::Error ||
            run.r.status == certify::Status::Uncertified)
          ++err;
        else if (run.r.status == certify::Status::Certified)
          ++cert;
        else
          ++und;
        zero += !run.threw && is_zero_result(run.r);
      }
      mean /= static_cast<double>(std::max<size_t>(1, t.size()));
      med[k] = median(t);
      std::printf("| %ld | %.0f | %.0f | %ld | %ld | %ld | %ld |\n", digits_list[k], med[k], mean,
                  cert, und, zero, err);
    }
    std::printf("\ntime per extra digit (15 -> 100, medians): %.1f us\n", (med[1] - med[0]) / 85);

    // The same pairs in the two other modes at 15 digits: float (uncertified double answer
    // where a float route exists) and exact (the offset method, no fast path), against the
    // filtered (default) result above.
    {
      std::vector<double> tf, tx;
      long f_answered = 0, x_cert = 0, x_disagree = 0;
      double f_err = 0;
      for (long i = 0; i < pairs && i < mode_pairs; ++i) {
        const Case& c = cases[static_cast<size_t>(i)];
        const Run& ref = runs[0][static_cast<size_t>(i)];
        auto t0 = std::chrono::steady_clock::now();
        auto rf = certify::surface_distance(c.a, c.b, 15, false, certify::Mode::Float);
        auto t1 = std::chrono::steady_clock::now();
        tf.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
        if (rf.status == certify::Status::Uncertified) {
          ++f_answered;
          if (!ref.threw && ref.r.status == certify::Status::Certified)
            f_err = std::max(f_err, std::fabs(rf.approx() - ref.r.approx()) / (1 + ref.r.approx()));
        }
        t0 = std::chrono::steady_clock::now();
        auto rx = certify::surface_distance(c.a, c.b, 15, false, certify::Mode::Exact);
        t1 = std::chrono::steady_clock::now();
        tx.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
        if (rx.status == certify::Status::Certified) {
          ++x_cert;
          auto lx = core::Rational::from_string(rx.lower()),
               ux = core::Rational::from_string(rx.upper());
          auto lr = core::Rational::from_string(ref.r.lower()),
               ur = core::Rational::from_string(ref.r.upper());
          if (lx && ux && lr && ur && (*lx > *ur || *lr > *ux)) ++x_disagree;
        }
      }
      std::printf("\nmodes at 15 digits (%zu pairs): float %.1f us median, %ld answered "
                  "(uncertified), max relative error %.2e vs the certified value; filtered "
                  "%.1f us; exact (offset method only) %.0f us, %ld certified, %ld enclosures "
                  "disjoint from the filtered ones\n",
                  tf.size(), median(tf), f_answered, f_err, med[0], median(tx), x_cert, x_disagree);
    }

    // Degrees (15-digit runs, offset method only).
    std::vector<double> elim, sqf;
    for (const Run& run : runs[0]) {
      if (run.threw) continue;
      if (run.r.eliminated_degree > 0) elim.push_back(run.r.eliminated_degree);
      if (!run.r.squarefree_degrees.empty())
        sqf.push_back(static_cast<double>(run.r.squarefree_degrees[0]));
    }
    std::printf("median eliminated_degree: %.0f (over %zu cases); median squarefree_degrees[0]: "
                "%.0f (over %zu cases)\n",
                median(elim), elim.size(), median(sqf), sqf.size());

    // Float check and consistency of the two precisions.
    long checked = 0, violations = 0, stuck = 0, zero_far = 0, inconsistent = 0;
    double worst_gap = -1e300; // max of lower - f over checked cases
    for (long i = 0; i < pairs; ++i) {
      const Case& c = cases[static_cast<size_t>(i)];
      const FloatResult& f = fl[static_cast<size_t>(i)];
      const Run& r15 = runs[0][static_cast<size_t>(i)];
      const Run& r100 = runs[1][static_cast<size_t>(i)];
      // The two enclosures must overlap (exact comparison).
      if (!r15.threw && !r100.threw && !r15.r.lower().empty() && !r100.r.lower().empty() &&
          !r15.r.upper().empty() && !r100.r.upper().empty()) {
        auto l15 = core::Rational::from_string(r15.r.lower()),
             u15 = core::Rational::from_string(r15.r.upper()),
             l100 = core::Rational::from_string(r100.r.lower()),
             u100 = core::Rational::from_string(r100.r.upper());
        if (l15 && u15 && l100 && u100 && (*l15 > *u100 || *l100 > *u15)) {
          ++inconsistent;
          std::printf("\n**INCONSISTENT 15/100-digit enclosures, case %ld**: [%s, %s] vs [%s, "
                      "%s]\n",
                      i, r15.r.lower().c_str(), r15.r.upper().c_str(), r100.r.lower().c_str(),
                      r100.r.upper().c_str());
        }
      }
      for (size_t k = 0; k < 2; ++k) {
        const Run& run = runs[k][static_cast<size_t>(i)];
        if (run.threw || run.r.status != certify::Status::Certified) continue;
        double lower = std::strtod(run.r.lower().c_str(), nullptr);
        double upper = std::strtod(run.r.upper().c_str(), nullptr);
        if (k == 0) {
          ++checked;
          worst_gap = std::max(worst_gap, lower - f.f);
          if (f.f - upper > 1e-6) ++stuck;
          if (upper == 0 && f.f > 1e-3) ++zero_far;
        }
        if (lower > f.f + 1e-9) {
          ++violations;
          std::printf("\n**VIOLATION (certified lower bound above a float pair distance)** set "
                      "%d case %ld, %ld digits\n",
                      set, i, digits_list[k]);
          std::printf("- enclosure [%s, %s], float f = %.17g (sampling %.17g)\n",
                      run.r.lower().c_str(), run.r.upper().c_str(), f.f, f.sampled);
          std::printf("- float pair p = (%.17g, %.17g, %.17g), q = (%.17g, %.17g, %.17g)\n", f.p[0],
                      f.p[1], f.p[2], f.q[0], f.q[1], f.q[2]);
          std::printf("- A: %s\n- B: %s\n", c.fa.exact_params.c_str(), c.fb.exact_params.c_str());
          std::printf("- EQ_A: `%s`\n- EQ_B: `%s`\n", equation(c.a).c_str(), equation(c.b).c_str());
        }
      }
    }
    total_violations += violations;
    std::printf("\nfloat check (%s vs %s, %.0f us/case): %ld certified cases checked (15 digits; "
                "both precisions for violations); lower > f + 1e-9: **%ld**; float stuck (f - "
                "upper > 1e-6): %ld; max(lower - f): %.3g; certified 0 but f > 1e-3: %ld; "
                "15/100-digit enclosures disjoint: %ld\n",
                kind_name(cases.empty() ? Kind::Ellipsoid : cases[0].fa.kind),
                kind_name(cases.empty() ? Kind::Ellipsoid : cases[0].fb.kind),
                float_us / static_cast<double>(std::max(1L, pairs)), checked, violations, stuck,
                worst_gap, zero_far, inconsistent);

    // Undecided / error notes.
    std::map<std::string, long> notes;
    std::vector<long> examples;
    for (long i = 0; i < pairs; ++i) {
      for (size_t k = 0; k < 2; ++k) {
        const Run& run = runs[k][static_cast<size_t>(i)];
        if (!run.threw && run.r.status == certify::Status::Certified) continue;
        std::string n = run.threw
                            ? "exception: " + run.what
                            : std::string(certify::to_string(run.r.status)) + ": " + run.r.note;
        if (n.size() > 120) n = n.substr(0, 117) + "...";
        ++notes[std::to_string(digits_list[k]) + " digits, " + n];
        if (examples.empty() || examples.back() != i) examples.push_back(i);
      }
    }
    if (!notes.empty()) {
      std::printf("\nnot certified:\n\n");
      for (const auto& [n, cnt] : notes)
        std::printf("- %ld x %s\n", cnt, n.c_str());
      std::printf("\nexamples (case: EQ_A | EQ_B):\n\n");
      for (size_t j = 0; j < examples.size() && j < 3; ++j) {
        long i = examples[j];
        const Case& c = cases[static_cast<size_t>(i)];
        const Run& run = runs[0][static_cast<size_t>(i)];
        std::printf("- case %ld (15 digits: %s, [%s, %s], float f = %.6g): `%s` | `%s`\n", i,
                    run.threw ? "exception" : certify::to_string(run.r.status),
                    run.r.lower().c_str(), run.r.upper().c_str(), fl[static_cast<size_t>(i)].f,
                    equation(c.a).c_str(), equation(c.b).c_str());
      }
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  std::printf("total violations: %ld\n", total_violations);
  flint_cleanup();
  return total_violations ? 1 : 0;
}
