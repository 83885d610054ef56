// march: predictor-corrector tracing of the QSIC from start points, through known singular
// points, closing loops. Approximate (floating point); nothing here is certified.
//
// Step control at a point p with unit tangent t (travel direction):
//   h_free = min(hmax, 0.93 sqrt(8 tol / kappa), 0.2 / kappa),
//   h      = min(h_free, max(sqrt(0.5 d_sep / kappa), h_free / 20))
// with tol = tolerance * L (L = diagonal of the bounding box of the start and singular points:
// the scene size, so the result does not depend on the scale), hmax = 200 tol, kappa the
// larger of the curve's curvature at p (exact, from the surfaces' second derivatives) and of
// the turning rate over the last step, and d_sep the distance at which the local second-order
// model of the pair puts another piece of curve: in the (approximate) common tangent plane the
// curve is {l . v + v^T Q v / 2 = 0}, l the difference of the unit normals, Q the difference
// of the shape operators; another branch of that conic lies about |l| / |Q| away. The second
// bound keeps the predictor's sideways error below d_sep / 4.
// The factor 0.93: sqrt(8 tol / kappa) puts a circular arc's chord error kappa h^2 / 8 exactly at
// tol, where the corrector's chord test below rejects about half the steps (measured: 59,080
// rejected of 177,522 tried on 1000 random ellipsoid pairs, each costing a Newton projection);
// aiming 7% short, 3% are rejected, and fewer points are accepted in all (108,683, was 118,424:
// a rejected step is retried at 0.7 h).
// A corrected point is accepted when the chord to it stays within tol of the curve (estimated
// from the end tangents: len/4 times the sine of the tangent-chord angle; the closing chord
// too), it lies within h/2 of the predictor and 1.5h of p, the
// step made progress, the tangent (grad f x grad g with the walk's orientation sign) turned by
// less than ~45 degrees, h is not too long for the curvature and d_sep at the new point, and
// the rounded coefficients resolve the curve there (QuadricPair::noise_radius <= d_sep / 4);
// otherwise h is halved, down to 2^-40 of |p| (a neck of 2^-100 at the origin is walked). The
// orientation test is what keeps the walk on its own piece where two pieces of curve run closer
// than the step: next to each other the field grad f x grad g runs in opposite directions on them
// (they are neighbouring zero sets of one function on the surface), so a jump shows up as a
// reversed tangent.
//
// Singular points (crunode, cusp, acnode) are classified locally from the pair: there the
// gradients are parallel, g - mu f is singular at S, and the tangent cone of the curve is
// {v in the tangent plane : v^T (B - mu A) v = 0} (A, B the quadratic parts): two lines
// (crunode), one double line (cusp; a tacnode looks the same at this order and is treated as
// one, so conic cases belong to conic_branches) or none (acnode). Next to a crunode or cusp
// the steps stay below half the distance to it (other pieces of curve may pass that close). A
// walk that gets within h_free / 16 of one ahead of it, on a branch through it (the chord to it
// runs along the curve: its midpoint projects within r/50 of itself), steps onto it exactly and
// continues along the branch that best continues its direction (crunode: the arm's tangent
// there read as 2 chord - t, and while that is not clearly nearer one line than the other the
// walk first comes closer) or back along the other half (cusp); the outgoing point solves
// f = g = 0, |X - S| = r by Newton (at a crunode r >= h_free / 64, and the chord from the
// crunode to it must run along the curve too). Start points at which
// the curve is singular (extreme_points returns them) are not starts; they join the list of
// singular points. A walk further than escape_scenes (100) L from its start is on a non-compact
// branch and stops. A walk that ended off the box's faces at both ends and lies wholly on another
// traced piece (a stretch walked twice from a start next to a cusp) is dropped.
#include "surfcert/trace/curve.hpp"

#include "surfcert/core/budget.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace surfcert::trace {

namespace {

using V = Point3;

V add(const V& a, const V& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
V sub(const V& a, const V& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
V mul(double s, const V& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
double dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const V& a) {
  return std::sqrt(dot(a, a));
}
V cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V unit(const V& a) {
  double n = norm(a);
  return n > 0 ? mul(1 / n, a) : V{0, 0, 0};
}
double dist(const V& a, const V& b) {
  return norm(sub(a, b));
}

// v^T M v and u^T M v for the quadratic part (upper-left 3x3 block) of a 4x4 matrix.
double quad(const std::array<std::array<double, 4>, 4>& m, const V& u, const V& v) {
  double s = 0;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      s += u[i] * m[i][j] * v[j];
  return s;
}

// The angle between unit vectors u and v less than ~46 degrees apart (u . v > 0.7): 2 asin(s)
// with s = |u - v| / 2 <= 0.39, by the series to s^7 (relative error below 2e-5: a curvature
// estimate for the step size needs no more; std::acos was 3.6% of a traced ellipsoid pair).
double small_angle(const V& u, const V& v) {
  const double s = 0.5 * norm(sub(u, v)), s2 = s * s;
  return 2 * s * (1 + s2 * (1.0 / 6 + s2 * (3.0 / 40 + s2 * (15.0 / 336))));
}

// A unit vector orthogonal to the unit vector n.
V orthogonal(const V& n) {
  size_t k = 0;
  for (size_t i = 1; i < 3; ++i)
    if (std::abs(n[i]) < std::abs(n[k])) k = i;
  V e{0, 0, 0};
  e[k] = 1;
  return unit(cross(n, e));
}

// Eigen-decomposition of the symmetric 2x2 matrix [[a, b], [b, d]]: values l1 <= l2 and the
// unit eigenvector of l1 (the other one is its rotation by 90 degrees).
void eig2(double a, double b, double d, double& l1, double& l2, double& c, double& s) {
  const double m = (a + d) / 2, r = std::hypot((a - d) / 2, b);
  l1 = m - r;
  l2 = m + r;
  // Eigenvector of l1: (b, l1 - a) or (l1 - d, b), whichever is better conditioned.
  double x1 = b, y1 = l1 - a, x2 = l1 - d, y2 = b;
  double n1 = std::hypot(x1, y1), n2 = std::hypot(x2, y2);
  if (n1 >= n2 && n1 > 0) {
    c = x1 / n1;
    s = y1 / n1;
  } else if (n2 > 0) {
    c = x2 / n2;
    s = y2 / n2;
  } else {
    c = 1;
    s = 0;
  }
}

enum class SKind { Crunode, Cusp, Acnode, Other };

struct Singular {
  V p;
  SKind kind = SKind::Other;
  V n{};               // unit normal of the common tangent plane
  std::vector<V> dirs; // unit tangent directions of the curve at p (crunode 2, cusp 1)
};

// sin of the angle between the gradients (0 when one vanishes).
double sin_angle(const QuadricPair& q, const V& p) {
  const V gf = q.grad_f(p), gg = q.grad_g(p);
  const double d = norm(gf) * norm(gg);
  return d > 0 ? norm(cross(gf, gg)) / d : 0;
}

Singular classify(const QuadricPair& q, const V& p) {
  Singular s;
  s.p = p;
  const V gf = q.grad_f(p), gg = q.grad_g(p);
  const double nf = norm(gf), ng = norm(gg);
  const double big = std::max(nf, ng);
  if (!(big > 0)) return s;
  // A gradient below 1e-6 of the other: p is (the rounding of) a singular point of that
  // surface, a cone's apex; its computed direction is noise, so the angle between the
  // gradients says nothing there (an apex 1e-8 of the scene off the rounded special point was
  // read as a smooth point, and the walks crawled into it instead of passing through).
  const bool on_apex = !(nf > 1e-6 * big && ng > 1e-6 * big);
  if (!on_apex && norm(cross(gf, gg)) > 1e-6 * nf * ng) return s; // not singular on the curve
  // M = B - mu A (quadratic parts), with grad g = mu grad f; or the quadratic part of the
  // surface that is singular at p.
  std::array<std::array<double, 4>, 4> m{};
  if (!on_apex) {
    const double mu = dot(gg, gf) / dot(gf, gf);
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        m[i][j] = q.b[i][j] - mu * q.a[i][j];
  } else {
    m = nf > ng ? q.b : q.a;
  }
  s.n = unit(nf >= ng ? gf : gg);
  const V e1 = orthogonal(s.n), e2 = cross(s.n, e1);
  const double a = quad(m, e1, e1), b = quad(m, e1, e2), d = quad(m, e2, e2);
  double l1, l2, c, sn;
  eig2(a, b, d, l1, l2, c, sn);
  const V u1 = add(mul(c, e1), mul(sn, e2)), u2 = add(mul(-sn, e1), mul(c, e2));
  double scale = std::max(std::abs(l1), std::abs(l2));
  double mscale = 0;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      mscale = std::max(mscale, std::abs(m[i][j]));
  if (!(scale > 1e-12 * mscale)) return s; // degenerate: a higher-order contact
  const double lo = std::min(std::abs(l1), std::abs(l2));
  if (lo <= 1e-7 * scale) {
    s.kind = SKind::Cusp;
    s.dirs.push_back(std::abs(l1) < std::abs(l2) ? u1 : u2);
  } else if (l1 * l2 > 0) {
    s.kind = SKind::Acnode;
  } else {
    s.kind = SKind::Crunode;
    const double cc = std::sqrt(l2 / (l2 - l1)), ss = std::sqrt(-l1 / (l2 - l1));
    s.dirs.push_back(unit(add(mul(cc, u1), mul(ss, u2))));
    s.dirs.push_back(unit(add(mul(cc, u1), mul(-ss, u2))));
  }
  return s;
}

// Newton on f = g = 0, |X - S|^2 = r^2 from x (3x3 system, partial pivoting).
bool newton_sphere(const QuadricPair& q, const V& sp, double r, V& x) {
  for (int it = 0; it < 50; ++it) {
    const double fv = q.f(x), gv = q.g(x);
    const V dx = sub(x, sp);
    const double sv = dot(dx, dx) - r * r;
    const double n2 = dot(x, x);
    if (!std::isfinite(fv) || !std::isfinite(gv) || !std::isfinite(sv)) return false;
    if (std::max(std::abs(fv), std::abs(gv)) <= 1e-15 * (1 + n2) && std::abs(sv) <= 1e-12 * r * r)
      return true;
    const V gf = q.grad_f(x), gg = q.grad_g(x);
    double m[3][4] = {{gf[0], gf[1], gf[2], fv},
                      {gg[0], gg[1], gg[2], gv},
                      {2 * dx[0], 2 * dx[1], 2 * dx[2], sv}};
    // Row scaling so pivoting compares like with like.
    for (auto& row : m) {
      double s = std::max({std::abs(row[0]), std::abs(row[1]), std::abs(row[2])});
      if (!(s > 0)) return false;
      for (double& v : row)
        v /= s;
    }
    for (int col = 0; col < 3; ++col) {
      int piv = col;
      for (int i = col + 1; i < 3; ++i)
        if (std::abs(m[i][col]) > std::abs(m[piv][col])) piv = i;
      if (!(std::abs(m[piv][col]) > 1e-300)) return false;
      if (piv != col)
        for (int j = 0; j < 4; ++j)
          std::swap(m[col][j], m[piv][j]);
      for (int i = col + 1; i < 3; ++i) {
        const double fct = m[i][col] / m[col][col];
        for (int j = col; j < 4; ++j)
          m[i][j] -= fct * m[col][j];
      }
    }
    double d[3];
    for (int i = 2; i >= 0; --i) {
      double s = m[i][3];
      for (int j = i + 1; j < 3; ++j)
        s -= m[i][j] * d[j];
      d[i] = s / m[i][i];
    }
    const V step{d[0], d[1], d[2]};
    x = sub(x, step);
    if (norm(step) <= 1e-16 * (1 + norm(x))) {
      const double res = std::max(std::abs(q.f(x)), std::abs(q.g(x)));
      return res <= 1e-13 * (1 + dot(x, x));
    }
  }
  return false;
}

struct Walk {
  std::vector<V> pts;
  std::vector<double>
      sg; // per point: travel direction = sg * (grad f x grad g), 0 at a singular point
  bool closed = false;
  bool dead = false;       // stopped where it could not continue (an end or a failure)
  bool capped = false;     // hit max_points_per_branch
  bool exited = false;     // left the box: the last point lies on one of its faces
  bool unresolved = false; // dead where the rounded pair cannot tell the curve's pieces apart
  std::vector<int> passes; // per singular point: number of times walked through
};

class Tracer {
public:
  Tracer(const QuadricPair& q, const TraceOptions& opt, double scene)
      : q_(q), opt_(opt), scene_(scene), tol_(opt.tolerance * opt.chord_scale * scene),
        hmax_(200 * opt.tolerance * scene) {}

  // Whether p lies on a face of the box with the travel direction t pointing out of it.
  bool leaving_at(const V& p, const V& t) const {
    if (!opt_.box) return false;
    const Box& b = *opt_.box;
    const double eps = 1e-9 * scene_;
    for (size_t k = 0; k < 3; ++k) {
      if (std::abs(p[k] - b.min[k]) <= eps && t[k] < 0) return true;
      if (std::abs(p[k] - b.max[k]) <= eps && t[k] > 0) return true;
    }
    return false;
  }

  // The segment p -> x leaves the box: the curve's point on the face crossed first (Newton on
  // f = g = 0, x_k = c from the linear interpolation). False when Newton fails.
  bool exit_point(const V& p, const V& x, V& out) const {
    V y{};
    if (!face_crossing(q_, *opt_.box, p, x, y)) return false;
    if (dist(y, p) > 2 * dist(x, p) + 1e-12 * scene_) return false;
    out = y;
    return true;
  }

  std::vector<Singular> sing;

  // Raw unit tangent grad f x grad g (zero at a singular point).
  V raw_tangent(const V& p) const { return unit(cross(q_.grad_f(p), q_.grad_g(p))); }

  // Curvature of the curve at p (t the unit tangent): solve grad f . k = -t^T H_f t,
  // grad g . k = -t^T H_g t, t . k = 0.
  double curvature(const V& p, const V& t) const {
    return curvature(t, q_.grad_f(p), q_.grad_g(p));
  }
  double curvature(const V& t, const V& gf, const V& gg) const {
    return curvature(t, gf, gg, quad(q_.a, t, t), quad(q_.b, t, t));
  }
  // The same with t^T A t and t^T B t given (target() shares them with separation()).
  double curvature(const V& t, const V& gf, const V& gg, double att, double btt) const {
    const double det = dot(t, cross(gf, gg));
    if (!(std::abs(det) > 0)) return std::numeric_limits<double>::infinity();
    const double r1 = -2 * att, r2 = -2 * btt;
    const V k = mul(1 / det, add(mul(r1, cross(gg, t)), mul(r2, cross(t, gf))));
    return norm(k);
  }

  // Distance to another piece of curve predicted by the local second-order model.
  double separation(const V& t, const V& gf, const V& gg, double att, double btt) const {
    const double nf = norm(gf), ng = norm(gg);
    if (!(nf > 0) || !(ng > 0)) return 0;
    const V uf = mul(1 / nf, gf), ug = mul(1 / ng, gg);
    const double sg = dot(uf, ug) < 0 ? -1 : 1;
    const V n = unit(add(uf, mul(sg, ug)));
    const V e2 = cross(n, t);
    const double lin = std::abs(dot(sub(uf, mul(sg, ug)), e2));
    // Q = 2 A / |grad f| - sg 2 B / |grad g| restricted to span(t, e2).
    auto qf = [&](const V& u, const V& v) {
      return 2 * quad(q_.a, u, v) / nf - sg * 2 * quad(q_.b, u, v) / ng;
    };
    const double a = 2 * att / nf - sg * 2 * btt / ng, b = qf(t, e2), d = qf(e2, e2);
    // sqrt, not std::hypot (~2% of a traced pair): an overflow (|grad| below ~1e-150) only
    // makes d_sep 0, i.e. the step h_free / 20.
    const double u = (a - d) / 2;
    const double qn = std::abs((a + d) / 2) + std::sqrt(u * u + b * b);
    if (!(qn > 0)) return std::numeric_limits<double>::infinity();
    return lin / qn;
  }

  // Target step at p; h_free excludes the separation bound (used for snapping).
  double target(const V& p, const V& t, double kappa_est, double* h_free,
                double* d_sep = nullptr) const {
    const V gf = q_.grad_f(p), gg = q_.grad_g(p); // shared by the two bounds below
    const double att = quad(q_.a, t, t), btt = quad(q_.b, t, t);
    const double kappa = std::max(curvature(t, gf, gg, att, btt), kappa_est);
    double h = hmax_;
    if (kappa > 0) h = std::min({h, 0.93 * std::sqrt(8 * tol_ / kappa), 0.2 / kappa});
    if (h_free) *h_free = h;
    // The predictor's sideways error kappa h^2 / 2 stays below a quarter of d_sep, so Newton
    // is not drawn to another piece of curve lying d_sep away. A second line of defence (the
    // orientation test of the corrector comes first: on two neighbouring pieces of curve
    // grad f x grad g runs in opposite directions), so it never shrinks the step below
    // h_free / 20: the point count stays bounded when two pieces run close for long.
    const double sep = separation(t, gf, gg, att, btt);
    if (d_sep) *d_sep = sep;
    if (kappa > 0 && std::isfinite(sep))
      h = std::min(h, std::max(std::sqrt(0.5 * sep / kappa), 0.05 * h));
    return h;
  }

  double hmin(const V& p) const { return std::max(1e-290, 0x1p-40 * norm(p)); }

  enum class Pass { Through, Failed, NotYet };

  // Through singular point sp arriving from p with unit tangent t: the first point after it.
  // NotYet: at a crunode, which of its two lines the arm arrives along is not clear from p yet.
  Pass pass_singular(const Singular& s, const V& p, const V& t, double h_free, V& out) const {
    const double r = dist(s.p, p);
    if (s.kind == SKind::Crunode) {
      // The arm's tangent at the crunode, from the chord and the tangent at p: on a circular
      // arc the chord halves the angle between the end tangents, so 2 chord - t is the far end's
      // tangent to second order. The chord alone deviates from it by ~kappa r / 2: where the
      // two lines cross at a small angle that picked the other line (a figure eight in a box
      // 3e4 wide: one face point ending three pieces, generate --case 5 --seed 32).
      const V din = unit(sub(s.p, p));
      const V tin = unit(sub(mul(2, din), t));
      V best{};
      double bd = -2, other = -2;
      for (const V& d : s.dirs) {
        const double v = std::abs(dot(d, tin));
        if (v > bd) {
          other = bd;
          bd = v;
          best = mul(dot(d, tin) >= 0 ? 1 : -1, d);
        } else {
          other = std::max(other, v);
        }
      }
      // The estimate's error grows like the change of curvature times r^2: while the angle to
      // the chosen line is not well below the angle to the other one, the walk first comes
      // closer (down to h_free / 64: then the best guess, as before).
      const double a_best = std::acos(std::min(1.0, bd)), a_other = std::acos(std::min(1.0, other));
      if (!(a_best < 0.25 * a_other) && r > h_free / 64) return Pass::NotYet;
      double rr = std::max(r, h_free / 64);
      for (int attempt = 0; attempt < 6; ++attempt, rr *= 0.5) {
        V x = add(s.p, mul(rr, best));
        if (!newton_sphere(q_, s.p, rr, x)) continue;
        if (dist(x, add(s.p, mul(rr, best))) > 0.3 * rr) continue;
        // On the arm, not on another piece of curve passing the crunode within rr (then the
        // chord from the crunode runs along the curve, as on arrival): a walk leaving a
        // crunode at 2 units landed on a component passing it 0.58 away, and two pieces ended
        // on one face point (generate --case 8 --seed 32, pair 8, box 2.6e4 wide).
        const V mid = add(s.p, mul(0.5, sub(x, s.p)));
        V y = mid;
        if (!project_onto_curve(q_, y) || dist(y, mid) > 0.02 * rr) continue;
        out = x;
        return Pass::Through;
      }
      return Pass::Failed;
    }
    if (s.kind == SKind::Cusp) {
      V d = s.dirs[0];
      const V u = sub(p, s.p);
      if (dot(d, u) < 0) d = mul(-1, d);
      const V e = cross(s.n, d);
      const double a = dot(u, d), b = dot(u, e), c = dot(u, s.n);
      for (double k : {1.0, 2.0, 0.5, 4.0}) {
        V x = add(s.p, add(mul(a, d), add(mul(-k * b, e), mul(c, s.n))));
        if (!newton_sphere(q_, s.p, r, x)) continue;
        if (dot(sub(x, s.p), d) <= 0) continue;
        if (dist(x, p) <= std::max(std::abs(b), 1e-9 * r)) continue; // came back to p
        out = x;
        return Pass::Through;
      }
      return Pass::Failed;
    }
    return Pass::Failed;
  }

  Walk walk(const V& p0, double s0) const {
    Walk w;
    w.passes.assign(sing.size(), 0);
    // Room for a few points first, for a typical loop at the usual tolerances (~100 points)
    // once the walk gets that far (see below): grown by doubling from empty, a walk's points
    // were copied ~8 times, each large reallocation consolidating malloc's free lists (6% and
    // 5% of a pipe pair's intersect); reserved for 256 points at once, the walks that end after
    // a point or two (starts on the box's faces heading out, most walks of a pair in a box) paid
    // one consolidation each (~38,000 instructions: 9.6% of a cone-cone pair).
    w.pts.reserve(short_walk);
    w.sg.reserve(short_walk);
    w.pts.push_back(p0);
    w.sg.push_back(s0);
    V p = p0;
    double s = s0;
    V t = mul(s, raw_tangent(p0));
    const V t0 = t;
    double kest = 0;
    double hlast = -1;
    bool have_next = false;
    double next_h = 0, next_hfree = 0;
    bool away = false;
    int stalled = 0; // consecutive accepted steps far below their target
    const size_t cap = static_cast<size_t>(std::max(opt_.max_points_per_branch, 2));
    if (leaving_at(p0, t)) { // started on a face, heading out: nothing inside this way
      w.exited = true;
      return w;
    }
    while (true) {
      if (w.pts.size() >= cap) {
        w.capped = true;
        return w;
      }
      // Running off to infinity (a non-compact branch: every compact one has both of its
      // extreme points among the starts, so it stays within a few scene sizes of them).
      if (dist(p, p0) > opt_.escape_scenes * scene_) {
        w.dead = true;
        return w;
      }
      double hfree = 0;
      double h;
      if (have_next) { // computed when the previous step was accepted (same p, t, kest)
        h = next_h;
        hfree = next_hfree;
        have_next = false;
      } else {
        h = target(p, t, kest, &hfree);
      }
      if (hlast > 0) h = std::min(h, 2 * hlast);
      // Next to a crunode or cusp other pieces of curve come as close as the point is to it:
      // the step stays below half that distance (not below h_free / 64: a walk on a branch
      // through it that does not step onto it passes it as before). Long straight steps (a box 3e4
      // wide around a unit-size curve: steps of ~20) passing a crunode 1 away on another component
      // landed on one of its arms running the same way, and two walks ended on one face point.
      for (const Singular& sg : sing)
        if (sg.kind == SKind::Crunode || sg.kind == SKind::Cusp)
          h = std::min(h, std::max(0.5 * dist(p, sg.p), hfree / 64));
      // Closing the loop.
      const double d0 = dist(p, p0);
      if (!away && d0 > 1.5 * h && w.pts.size() > 2) away = true;
      if (away && d0 <= 1.2 * h && dot(sub(p0, p), t) > 0 && dot(t0, t) > 0.5) {
        // The closing chord obeys the same bound as every other one (see the corrector).
        const V cdir = mul(1 / d0, sub(p0, p));
        const double sag = 0.25 * d0 * std::max(norm(cross(t, cdir)), norm(cross(t0, cdir)));
        if (sag <= tol_) {
          w.closed = true;
          return w;
        }
        h = std::min(h, 0.5 * d0); // one more point before closing
      }
      // Singular point ahead within reach: step onto it and through it.
      bool passed = false;
      for (size_t i = 0; i < sing.size(); ++i) {
        const Singular& sg = sing[i];
        if (sg.kind != SKind::Crunode && sg.kind != SKind::Cusp) continue;
        const V d = sub(sg.p, p);
        const double r = norm(d);
        if (!(r > 0) || r > hfree / 16 || dot(d, t) <= 0.9 * r) continue;
        // Only from a branch through it: there the chord to the point runs along the curve
        // (its midpoint within a tenth of r of it). Another piece of curve passing by within
        // h_free (a figure eight's other components in a box 2000 wide) was snapped onto the
        // crossing and left along its branch: every component glued to it, the counts and ends
        // still matching (generate --case 5, seed 32, pair 17 in a box of 1000). What this test
        // lets through (a piece passing within ~r / 5) settle_box refuses: too many arms.
        {
          const V mid = add(p, mul(0.5, d));
          V x = mid;
          if (!project_onto_curve(q_, x) || dist(x, mid) > 0.02 * r) continue;
        }
        V x;
        const Pass how = pass_singular(sg, p, t, hfree, x);
        if (how == Pass::NotYet) { // closer first, by ordinary steps
          h = std::min(h, 0.5 * r);
          continue;
        }
        if (how == Pass::Failed) {
          w.dead = true;
          return w;
        }
        const V rt = raw_tangent(x);
        s = dot(rt, sub(x, sg.p)) >= 0 ? 1 : -1;
        w.pts.push_back(sg.p);
        w.sg.push_back(0);
        w.pts.push_back(x);
        w.sg.push_back(s);
        ++w.passes[i];
        t = mul(s, rt);
        p = x;
        kest = 0;
        hlast = dist(x, sg.p);
        away = away || dist(x, p0) > 1.5 * hlast;
        passed = true;
        break;
      }
      if (passed) continue;
      // A long walk answers to the query's time budget (core/budget.hpp), every 64 points.
      if ((w.pts.size() & 63) == 0) core::check_budget();
      // Predictor-corrector step.
      bool ok = false;
      bool noisy = false; // a step of this point was refused by the noise test
      while (!ok) {
        if (!(h >= hmin(p))) { // NaN too (a scene beyond the doubles): never a step
          w.dead = true;
          w.unresolved = noisy;
          return w;
        }
        const V pp = add(p, mul(h, t));
        V x = pp;
        if (project_onto_curve(q_, x)) {
          const V dq = sub(x, p);
          const double len = norm(dq);
          const V tx = mul(s, raw_tangent(x));
          if (len <= 1.5 * h && len >= 0.25 * h && dist(x, pp) <= 0.5 * h &&
              dot(dq, t) > 0.5 * len && dot(tx, t) > 0.7) {
            const double ang = small_angle(t, tx);
            const double k2 = ang / len;
            double hx_free = 0, sep_x = 0;
            const double hx = target(x, tx, k2, &hx_free, &sep_x);
            // The chord p-x must stay within the tolerance of the curve. The curvature
            // estimates at its ends can miss a sharper bend in between; the end tangents
            // cannot: a smooth arc leaves its chord by about len/4 times the sine of the
            // angle between a tangent and the chord (len*theta/8 for a circular arc).
            const V cdir = mul(1 / len, dq);
            const double sag = 0.25 * len * std::max(norm(cross(t, cdir)), norm(cross(tx, cdir)));
            const bool chord_ok = sag <= tol_;
            // Where the rounded pair's curve may lie farther from the exact one than a quarter
            // of the distance to the next piece of curve (next to a cone's apex at |c| ~ 1:
            // the rounded cone's zero set there is a hyperboloid's neck of ~1e-8, whatever the
            // exact pair does), the walk follows the rounded pair's topology, not the exact
            // one's: a loop made of two pieces passed every other test. The step shrinks there
            // until the walk ends (undecided).
            const bool resolved = !(q_.noise_radius(x) > 0.25 * sep_x);
            if (!resolved) {
              noisy = true;
              h *= 0.5;
              continue;
            }
            if (h <= 2 * hx && chord_ok) {
              // A walk whose steps stay far below their target (each longer one failing, e.g.
              // Newton not converging between two nearly tangent surfaces around a loop of
              // 1e-8) crawls: 290,000 points and 9 s for one such pair once the step floor fell
              // to 2^-40 |p|. It ends instead (undecided). Not too soon: a walk closing in on a
              // cone's apex passed by 2^-100 halves its steps ~100 times in a row, each far
              // below the target of the nearly straight curve there.
              stalled = len < 1e-4 * hx ? stalled + 1 : 0;
              if (stalled > 2048) {
                w.dead = true;
                return w;
              }
              ok = true;
              have_next = true;
              next_h = hx;
              next_hfree = hx_free;
              kest = k2;
              p = x;
              t = tx;
              hlast = len;
              if (opt_.box && !opt_.box->contains(x)) {
                V y;
                if (exit_point(w.pts.back(), x, y)) {
                  w.pts.push_back(y);
                  w.sg.push_back(s);
                  w.exited = true;
                } else {
                  w.dead = true;
                }
                return w;
              }
              if (w.pts.size() == short_walk) {
                w.pts.reserve(256);
                w.sg.reserve(256);
              }
              w.pts.push_back(x);
              w.sg.push_back(s);
              break;
            }
            h = chord_ok ? std::min(0.5 * h, hx) : 0.7 * h;
            continue;
          }
        }
        h *= 0.5;
      }
    }
  }

private:
  // Points reserved for a walk at its start (below malloc's large-request threshold).
  static constexpr size_t short_walk = 16;
  const QuadricPair& q_;
  const TraceOptions& opt_;
  double scene_, tol_, hmax_;
};

// Distance from x to the segment [a, b].
double seg_dist(const V& x, const V& a, const V& b) {
  const V ab = sub(b, a);
  const double l2 = dot(ab, ab);
  double t = l2 > 0 ? dot(sub(x, a), ab) / l2 : 0;
  t = std::min(1.0, std::max(0.0, t));
  return dist(x, add(a, mul(t, ab)));
}

// A traced branch with, per point, the sign relating its travel direction to grad f x grad g.
struct Traced {
  Branch br;
  std::vector<double> sg;
  V lo{}, hi{};       // the points' bounding box (set by bound())
  double max_len = 0; // the longest segment
  void bound() {
    const auto& pts = br.points;
    for (size_t i = 0; i < pts.size(); ++i) {
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = i ? std::min(lo[k], pts[i][k]) : pts[i][k];
        hi[k] = i ? std::max(hi[k], pts[i][k]) : pts[i][k];
      }
      if (i > 0) max_len = std::max(max_len, dist(pts[i - 1], pts[i]));
    }
    if (br.closed && pts.size() > 1) max_len = std::max(max_len, dist(pts.back(), pts.front()));
  }
};

// Whether the curve point x lies on the traced branch: within the chord error of one of its
// segments (kappa len^2 / 4 with kappa the curvature at x, plus the rounding floor, which
// grows like 1/sin(angle between the surfaces)), and with its tangent running the same way as
// the segment. The orientation test is what tells apart two pieces of curve closer than the
// steps: next to each other the field grad f x grad g runs in opposite directions on them.
// `hint`, when given, is the segment to try first (the answer does not depend on it) and
// receives the one that matched: consecutive points of another walk along this branch match
// consecutive segments (a dead arc checked point by point against the branch it doubles: 117,000
// segment tests, half of a Steinmetz pair posed in doubles, scanning from the first each time).
bool on_branch(const Tracer& tr, const QuadricPair& q, const V& x, const Traced& t, double eps,
               size_t* hint = nullptr) {
  const auto& pts = t.br.points;
  const size_t n = pts.size();
  const double sa = sin_angle(q, x);
  const double noise = 1e-15 * (1 + norm(x)) / std::max(sa, 1e-300);
  // Every test below accepts x only within 0.05 max_len + noise + eps of a point or segment:
  // farther than that from the points' bounding box, x is on no segment (a start far from this
  // branch was checked against all of its points and segments: 13% of a walked pair's time).
  const double reach = 0.05 * t.max_len + noise + eps;
  for (size_t k = 0; k < 3; ++k)
    if (x[k] < t.lo[k] - reach || x[k] > t.hi[k] + reach) return false;
  if (n == 0) return false;
  if (n == 1) return dist(x, pts[0]) <= eps;
  // x is on the branch when a point lies within eps of it or a segment passes the test below:
  // both looked at together, from the hint on (where the previous point of a walk checked
  // against this branch was found), so that a stretch lying on the branch is checked in time
  // proportional to its own length. (All points first, then the segments from the hint: a
  // dead walk of 200,000 points checked against a piece of 200,000 took 66 s, generate --case
  // 9 --seed 46 pair 6 in a box 20,000 wide.)
  const V rx = tr.raw_tangent(x);
  const double kappa = std::min(tr.curvature(x, rx), 1e300);
  const size_t segs = t.br.closed ? n : n - 1;
  const size_t first = hint && *hint < n ? *hint : 0;
  for (size_t m = 0; m < n; ++m) {
    const size_t i = first + m < n ? first + m : first + m - n;
    if (dist(x, pts[i]) <= eps) {
      if (hint) *hint = i;
      return true;
    }
    if (i >= segs) continue;
    const V& a = pts[i];
    const V& b = pts[(i + 1) % n];
    const double len = dist(a, b);
    const double thr = std::min(0.05 * len, kappa * len * len / 4) + noise + eps;
    if (seg_dist(x, a, b) > thr) continue;
    double sg = t.sg[i] != 0 ? t.sg[i] : t.sg[(i + 1) % n];
    if (sg * dot(rx, sub(b, a)) > 0.5 * len) {
      if (hint) *hint = i;
      return true;
    }
  }
  return false;
}

} // namespace

std::vector<Branch> march(const QuadricPair& q, const std::vector<Point3>& starts,
                          const std::vector<Point3>& singular_points, const TraceOptions& opt,
                          int* unresolved_walks) {
  std::vector<Branch> out;
  if (unresolved_walks) *unresolved_walks = 0;
  auto count = [unresolved_walks](const Walk& w) {
    if (unresolved_walks && w.unresolved) ++*unresolved_walks;
  };
  // Scene size: the bounding box of everything we were given.
  V lo{}, hi{};
  bool any = false;
  for (const auto* list : {&starts, &singular_points})
    for (const V& p : *list) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      for (size_t i = 0; i < 3; ++i) {
        lo[i] = any ? std::min(lo[i], p[i]) : p[i];
        hi[i] = any ? std::max(hi[i], p[i]) : p[i];
      }
      any = true;
    }
  double scene = any ? dist(lo, hi) : 0;
  if (!(scene > 0)) scene = any ? 1 + norm(lo) : 1;
  if (opt.box) scene = opt.box->diagonal();

  Tracer tr(q, opt, scene);
  for (const V& p : singular_points)
    tr.sing.push_back(classify(q, p));
  const double near_eps = 1e-7 * scene;
  auto near_singular = [&](const V& p) {
    for (const auto& s : tr.sing)
      if (dist(s.p, p) <= near_eps) return true;
    return false;
  };
  // Start points at which the curve is singular are not starts; they join the list.
  std::vector<V> smooth;
  for (const V& p0 : starts) {
    V p = p0;
    if (near_singular(p)) continue;
    if (sin_angle(q, p) <= 1e-9) {
      Singular s = classify(q, p);
      if (s.kind != SKind::Other) {
        // Not a start either way; with the exact list complete, not a singular point to pass
        // through: the walks from the other starts meet it and end there (noise test).
        if (!opt.singular_points_complete) tr.sing.push_back(s);
        continue;
      }
    }
    if (!project_onto_curve(q, p)) continue;
    if (near_singular(p)) continue;
    if (opt.box && !opt.box->contains(p, 1e-9 * scene)) continue;
    smooth.push_back(p);
  }

  std::vector<Traced> traced;
  for (const V& p0 : smooth) {
    bool known = false;
    for (const auto& t : traced)
      if (on_branch(tr, q, p0, t, 1e-12 * scene)) known = true;
    if (known) continue;
    if (norm(tr.raw_tangent(p0)) == 0) continue;
    Walk fw = tr.walk(p0, 1.0);
    count(fw);
    Traced tb;
    Branch& br = tb.br;
    std::vector<int> passes = fw.passes;
    if (fw.closed || fw.capped) {
      br.points = std::move(fw.pts);
      tb.sg = std::move(fw.sg);
      br.closed = fw.closed;
    } else {
      Walk bw = tr.walk(p0, -1.0);
      count(bw);
      if (fw.pts.size() + bw.pts.size() <= 2) continue; // no curve through p0 to follow
      for (size_t i = 0; i < passes.size(); ++i)
        passes[i] += bw.passes[i];
      br.points.reserve(bw.pts.size() + fw.pts.size());
      tb.sg.reserve(bw.pts.size() + fw.pts.size());
      br.points.assign(bw.pts.rbegin(), bw.pts.rend());
      for (auto it = bw.sg.rbegin(); it != bw.sg.rend(); ++it)
        tb.sg.push_back(-*it); // walked backwards: the travel direction flips
      br.points.insert(br.points.end(), fw.pts.begin() + 1, fw.pts.end());
      tb.sg.insert(tb.sg.end(), fw.sg.begin() + 1, fw.sg.end());
      br.closed = false;
    }
    int crunode_twice = 0, cusps = 0;
    for (size_t i = 0; i < passes.size(); ++i) {
      if (tr.sing[i].kind == SKind::Crunode && passes[i] >= 2) ++crunode_twice;
      if (tr.sing[i].kind == SKind::Cusp && passes[i] >= 1) ++cusps;
    }
    br.kind = crunode_twice > 0 ? "figure_eight" : cusps > 0 ? "loop_with_cusp" : "loop";
    if (!br.closed && opt.box) br.kind = "arc"; // a piece of an unbounded branch in the box
    tb.bound();
    traced.push_back(std::move(tb));
  }
  // A walk that ended off the box's faces (it died: next to a cusp, where the rounded pair's
  // gradients are noise) is dropped when every point of it lies on another traced piece: a
  // stretch of that piece walked twice (a start 6e-6 from the cusp of a cuspidal loop gave an
  // 8-point arc beside the loop through it: undecided, "open branches do not end on the box's
  // faces"; generate --case 9 --seed 32 pair 18). At one end or both: a start 1e-4 from a cusp
  // whose surfaces are tangent to high order died there at once, and its other half ran to a
  // face along a piece already walked through the cusp (generate --case 9 --seed 45 pair 7).
  // Anything else is kept, and the picture is judged as traced.
  auto on_face = [&](const V& p) {
    if (!opt.box) return false;
    for (size_t k = 0; k < 3; ++k)
      if (std::abs(p[k] - opt.box->min[k]) <= 1e-9 * scene ||
          std::abs(p[k] - opt.box->max[k]) <= 1e-9 * scene)
        return true;
    return false;
  };
  // So is a walk that died at both ends within 1e-6 of the scene of an isolated point (an
  // acnode): next to one, f and g vanish to second order, and points ~7e-7 from the acnode of
  // generate --case 6 --seed 48 pair 3 (posed in doubles) passed the residual test: a walk
  // started there circled a loop of rounding noise (its starts are kept 1e-7 away).
  std::vector<bool> dropped(traced.size(), false);
  for (size_t i = 0; i < traced.size(); ++i) {
    const auto& pts = traced[i].br.points;
    if (traced[i].br.closed || pts.empty() || on_face(pts.front()) || on_face(pts.back())) continue;
    for (const Singular& s : tr.sing) {
      if (s.kind != SKind::Acnode) continue;
      dropped[i] = dropped[i] || std::all_of(pts.begin(), pts.end(), [&](const V& p) {
                     return dist(p, s.p) <= 1e-6 * scene;
                   });
    }
  }
  for (size_t i = 0; i < traced.size(); ++i) {
    const auto& pts = traced[i].br.points;
    if (dropped[i] || traced[i].br.closed || pts.empty() ||
        (on_face(pts.front()) && on_face(pts.back())))
      continue;
    for (size_t j = 0; j < traced.size() && !dropped[i]; ++j) {
      if (j == i || dropped[j]) continue;
      size_t hint = 0;
      dropped[i] = std::all_of(pts.begin(), pts.end(), [&](const V& p) {
        return on_branch(tr, q, p, traced[j], 1e-12 * scene, &hint);
      });
    }
  }
  // And a piece between two face crossings that another kept piece joins too (its ends within
  // 1e-9 of the scene of that piece's ends, either way round), every point of it on that piece:
  // the same stretch walked twice. A transversal crossing ends one piece of the curve, so two
  // pieces cannot share both (two branches running out side by side 0.5 apart towards a crunode
  // at infinity, in a given box 25,000 wide: the walk from one crossing missed that the other
  // start lay on a piece already traced; generate --case 5 --seed 46 pair 5 boxed).
  auto same_ends = [&](const std::vector<V>& u, const std::vector<V>& v) {
    const double e = 1e-9 * scene;
    return (dist(u.front(), v.front()) <= e && dist(u.back(), v.back()) <= e) ||
           (dist(u.front(), v.back()) <= e && dist(u.back(), v.front()) <= e);
  };
  for (size_t i = 0; i < traced.size(); ++i) {
    const auto& pts = traced[i].br.points;
    if (dropped[i] || traced[i].br.closed || pts.size() < 2 || !on_face(pts.front()) ||
        !on_face(pts.back()))
      continue;
    for (size_t j = 0; j < i && !dropped[i]; ++j) {
      const auto& other = traced[j].br.points;
      if (dropped[j] || traced[j].br.closed || other.size() < 2 || !same_ends(pts, other)) continue;
      // (The ends matched already: a face crossing found from two sides differs by ~1e-11 of
      // the scene, beyond the last segment's reach.)
      size_t hint = 0;
      dropped[i] = std::all_of(pts.begin() + 1, pts.end() - 1, [&](const V& p) {
        return on_branch(tr, q, p, traced[j], 1e-12 * scene, &hint);
      });
    }
  }
  for (size_t i = 0; i < traced.size(); ++i)
    if (!dropped[i]) out.push_back(std::move(traced[i].br));
  return out;
}

bool face_crossing(const QuadricPair& q, const Box& box, const Point3& in, const Point3& out,
                   Point3& y) {
  double best = 2;
  size_t face_k = 0;
  double face_c = 0;
  for (size_t k = 0; k < 3; ++k)
    for (double c : {box.min[k], box.max[k]}) {
      const double den = out[k] - in[k];
      if (den == 0) continue;
      const double lam = (c - in[k]) / den;
      const bool outward = (c == box.min[k]) ? den < 0 : den > 0;
      if (outward && lam >= 0 && lam <= 1 && lam < best) {
        best = lam;
        face_k = k;
        face_c = c;
      }
    }
  if (best > 1) return false;
  for (size_t k = 0; k < 3; ++k)
    y[k] = in[k] + best * (out[k] - in[k]);
  y[face_k] = face_c;
  if (!newton_on_face(q, face_k, face_c, y)) return false;
  y[face_k] = face_c;
  return true;
}

} // namespace surfcert::trace
