#include "surfcert/certify/distance/degenerate_locus.hpp"
#include "surfcert/core/rational_vec3.hpp"

#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/sphere_gap.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/kernel.hpp"

#include <cmath>
#include <string>

namespace surfcert::certify {

using core::along;
using core::cross;
using core::dot;
using core::Rational;
using core::sub;

namespace {

using Vec3 = std::array<Rational, 3>;
using Point = std::array<double, 3>;

bool is_zero(const Vec3& v) {
  return v[0].is_zero() && v[1].is_zero() && v[2].is_zero();
}
Point approx(const Vec3& v) {
  return {v[0].to_double_approx(), v[1].to_double_approx(), v[2].to_double_approx()};
}

// The certified distance sqrt(d2) of an exact squared distance.
void set_sqrt(DistanceResult& out, const Rational& d2, long digits) {
  if (d2.is_zero()) {
    out.distance = Enclosure::zero();
    return;
  }
  const long prec = bits_for(digits + 10);
  Ball b;
  arb_set_fmpq(b.v, d2.raw(), prec);
  arb_sqrt(b.v, b.v, prec);
  set_distance_enclosure(out, b.v, digits);
}

void add_pair(DistanceResult& out, const Point& on_line, const Point& on_other, bool line_first) {
  out.pairs.push_back(line_first ? std::array<Point, 2>{on_line, on_other}
                                 : std::array<Point, 2>{on_other, on_line});
}

DistanceResult certified(long candidates) {
  DistanceResult out;
  out.status = Status::Certified;
  out.method = Method::LineLocus;
  out.critical_candidates = static_cast<int>(candidates);
  return out;
}

// Two lines p1 + s d1 and p2 + t d2, exactly.
DistanceResult line_line(const RealLocus& l1, const RealLocus& l2, bool line_first, long digits) {
  const Vec3 w = sub(l2.point, l1.point), n = cross(l1.direction, l2.direction);
  DistanceResult out = certified(1);
  if (!is_zero(n)) {
    // Skew or crossing: the common perpendicular, unique; s, t by Cramer (det = -|n|^2).
    const Rational nn = dot(n, n), wn = dot(w, n);
    const Rational d11 = dot(l1.direction, l1.direction), d22 = dot(l2.direction, l2.direction),
                   d12 = dot(l1.direction, l2.direction), w1 = dot(w, l1.direction),
                   w2 = dot(w, l2.direction);
    const Rational det = -nn;
    const Rational s = (-(w1 * d22) + d12 * w2) / det, t = (d11 * w2 - w1 * d12) / det;
    set_sqrt(out, wn * wn / nn, digits);
    out.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
    add_pair(out, approx(along(l1.point, s, l1.direction)),
             approx(along(l2.point, t, l2.direction)), line_first);
    out.note = wn.is_zero() ? "two lines crossing at one point (exact)"
                            : "two skew lines: the common perpendicular, in closed form (exact "
                              "squared distance)";
    return out;
  }
  // Parallel: every point of one line has its foot on the other at the same distance.
  const Rational dd = dot(l1.direction, l1.direction), wd = dot(w, l1.direction);
  const Rational d2 = dot(w, w) - wd * wd / dd;
  set_sqrt(out, d2, digits);
  out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
  add_pair(out, approx(along(l1.point, wd / dd, l1.direction)), approx(l2.point), line_first);
  out.note =
      d2.is_zero() ? "the two lines coincide" : "two parallel lines (exact squared distance)";
  return out;
}

// A line and a point, exactly.
DistanceResult line_point(const RealLocus& l, const Vec3& p, bool line_first, long digits) {
  const Vec3 w = sub(p, l.point);
  const Rational dd = dot(l.direction, l.direction), wd = dot(w, l.direction);
  DistanceResult out = certified(1);
  set_sqrt(out, dot(w, w) - wd * wd / dd, digits);
  out.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
  add_pair(out, approx(along(l.point, wd / dd, l.direction)), approx(p), line_first);
  out.note = "a line and a point: the foot of the point on the line (exact squared distance)";
  return out;
}

// X^T M X at X = (p, 1), exactly.
Rational eval(const core::Mat4& m, const Vec3& p) {
  const Rational x[4] = {p[0], p[1], p[2], Rational(1)};
  Rational s;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      if (!m[i][j].is_zero() && !x[i].is_zero() && !x[j].is_zero()) s += x[i] * m[i][j] * x[j];
  return s;
}

// The distance from p to a quadric the point is proven not to lie on (r = 0 of the sphere gap),
// oriented as the line-quadric query.
DistanceResult point_gap(const Vec3& p, const core::QuadricMatrix& z, bool line_first,
                         long digits) {
  DistanceResult r = sphere_quadric_gap(p, Rational(0), z, digits, line_first);
  r.method = Method::LineLocus;
  return r;
}

} // namespace

RealLocus real_locus(const core::QuadricMatrix& q) {
  RealLocus out;
  if (q.shape() != nullptr || q.is_plane()) return out;
  const core::Mat4& m = q.matrix();
  const algebra::Inertia in = algebra::inertia_ldlt(m);
  if (!in.semidefinite() || in.rank() == 0 || in.rank() == 4) return out;
  if (in.rank() == 1) {
    // M = k v v^T: a row with a nonzero diagonal entry is a multiple of v.
    for (size_t i = 0; i < 4; ++i)
      if (!m[i][i].is_zero()) {
        if (m[i][0].is_zero() && m[i][1].is_zero() && m[i][2].is_zero()) return out; // w^2 = 0
        out.kind = RealLocus::Kind::Plane;
        out.plane = m[i];
        return out;
      }
    return out;
  }
  const auto ker = algebra::kernel_basis(m);
  if (ker.size() != static_cast<size_t>(4 - in.rank())) return out;
  // An affine kernel vector (w != 0) is the point; with rank 2 a second one, at infinity, the
  // direction.
  size_t affine = ker.size();
  for (size_t i = 0; i < ker.size(); ++i)
    if (!ker[i][3].is_zero()) affine = i;
  if (affine == ker.size()) return out; // the kernel lies at infinity: no real point
  const auto& k = ker[affine];
  out.point = {k[0] / k[3], k[1] / k[3], k[2] / k[3]};
  if (in.rank() == 3) {
    out.kind = RealLocus::Kind::Point;
    return out;
  }
  const auto& o = ker[1 - affine];
  for (size_t i = 0; i < 3; ++i)
    out.direction[i] = o[i] * k[3] - k[i] * o[3];
  if (is_zero(out.direction)) return RealLocus(); // cannot happen: the kernel has rank 2
  // An integer direction (the kernel vectors are integer vectors): kept as is.
  out.kind = RealLocus::Kind::Line;
  return out;
}

std::optional<DistanceResult> line_quadric_distance(const RealLocus& line,
                                                    const core::QuadricMatrix& other,
                                                    bool line_first, long digits) {
  if (line.kind != RealLocus::Kind::Line || other.is_plane()) return std::nullopt;
  const RealLocus o = real_locus(other);
  if (o.kind == RealLocus::Kind::Plane) return std::nullopt;
  if (o.kind == RealLocus::Kind::Line) return line_line(line, o, line_first, digits);
  if (o.kind == RealLocus::Kind::Point) return line_point(line, o.point, line_first, digits);

  const core::Mat4& M = other.matrix();
  const Vec3& p = line.point;
  const Vec3& d = line.direction;
  // g(p + t d) = a t^2 + b(p) t + g(p), b(x) = beta . x + beta0.
  Vec3 beta;
  Rational a, beta0;
  for (size_t i = 0; i < 3; ++i) {
    Rational ad;
    for (size_t j = 0; j < 3; ++j)
      ad += M[i][j] * d[j];
    a += d[i] * ad;
    beta[i] = Rational(2) * ad;
    beta0 += Rational(2) * d[i] * M[i][3];
  }
  const Rational g = eval(M, p), b = dot(beta, p) + beta0;
  const Point pd = approx(p), dd = approx(d);
  auto point_at = [&](double t) {
    return Point{pd[0] + t * dd[0], pd[1] + t * dd[1], pd[2] + t * dd[2]};
  };
  auto meets_once = [&](const Rational& t, const char* why) {
    DistanceResult r = certified(1);
    r.distance = Enclosure::zero();
    r.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
    const Point x = approx(along(p, t, d));
    add_pair(r, x, x, line_first);
    r.note = why;
    return r;
  };
  auto line_inside = [&] {
    DistanceResult r = certified(1);
    r.distance = Enclosure::zero();
    r.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
    add_pair(r, pd, pd, line_first);
    r.note = "the line lies on the quadric (its equation vanishes identically along it, exactly)";
    return r;
  };

  if (a.is_zero()) {
    if (!is_zero(beta)) {
      if (!b.is_zero())
        return meets_once(-g / b, "the line meets the quadric at one point (an asymptotic "
                                  "direction: the equation is linear along the line; exact)");
      if (g.is_zero()) return line_inside();
      DistanceResult r = certified(0);
      r.distance = Enclosure::zero();
      r.minimizers = Minimizers::not_attained(Minimizers::Proof::Exact);
      r.note = "the line misses the quadric but nearby parallel lines meet it ever farther out "
               "(an asymptotic direction, decided exactly): the distance is the infimum 0, not "
               "attained";
      return r;
    }
    if (!beta0.is_zero())
      return meets_once(-g / beta0, "every line of this direction meets the quadric once (the "
                                    "equation is linear along it; exact)");
    if (g.is_zero()) return line_inside();
    // The quadric is a cylinder along the line: d(L, S) = d(p, S), attained along lines.
    DistanceResult r = point_gap(p, other, line_first, digits);
    if (r.status == Status::Certified) {
      r.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
      r.ties = Ties::None;
      const std::string tie = kUnprovenTiesNote;
      if (const size_t at = r.note.find(tie); at != std::string::npos) r.note.erase(at, tie.size());
      r.note = "the quadric is a cylinder parallel to the line: the distance from a point of the "
               "line, attained along whole lines" +
               std::string(r.note.empty() ? "" : "; " + r.note);
    }
    return r;
  }

  // a != 0: the shadow {disc >= 0}, disc = X^T (B B^T - 4 a M) X.
  const Rational delta = b * b - Rational(4) * a * g;
  if (delta.sign() >= 0) {
    DistanceResult r = certified(delta.is_zero() ? 1 : 2);
    r.distance = Enclosure::zero();
    const double ad = a.to_double_approx(), bd = b.to_double_approx(),
                 sq = std::sqrt(delta.to_double_approx());
    if (delta.is_zero()) {
      r.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
      const Point x = approx(along(p, -b / (Rational(2) * a), d));
      add_pair(r, x, x, line_first);
      r.note = "the line touches the quadric at one point (the discriminant along it is 0, "
               "exactly)";
    } else {
      r.minimizers = Minimizers::count(2, Minimizers::Proof::Exact);
      for (double s : {-1.0, 1.0}) {
        const Point x = point_at((-bd + s * sq) / (2 * ad));
        add_pair(r, x, x, line_first);
      }
      r.note = "the line crosses the quadric at two points (the discriminant along it is "
               "positive, exactly)";
    }
    return r;
  }
  core::Mat4 Z;
  const Rational B[4] = {beta[0], beta[1], beta[2], beta0};
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      Z[i][j] = B[i] * B[j] - Rational(4) * a * M[i][j];
  bool flat = true;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      flat = flat && Z[i][j].is_zero();
  // The tangency point on S above a shadow boundary point x: the double root t = -b(x) / 2a.
  const double ad = a.to_double_approx(), b0d = beta0.to_double_approx();
  const Point betad = approx(beta);
  auto lift = [&](const Point& x) {
    return -(betad[0] * x[0] + betad[1] * x[1] + betad[2] * x[2] + b0d) / (2 * ad);
  };
  if (flat) {
    // disc = gamma . x + gamma0 (the shadow is a half-plane): the nearest boundary point is the
    // foot of p on the plane disc = 0, exactly.
    const Vec3 gamma = {Rational(2) * Z[0][3], Rational(2) * Z[1][3], Rational(2) * Z[2][3]};
    if (is_zero(gamma)) {
      DistanceResult r;
      r.status = Status::Undecided;
      r.method = Method::LineLocus;
      r.note = "the quadric's shadow along the line is empty (no real point)";
      return r;
    }
    const Rational gg = dot(gamma, gamma);
    DistanceResult r = certified(1);
    set_sqrt(r, delta * delta / gg, digits);
    r.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
    const Vec3 f = along(p, -delta / gg, gamma);
    const Rational t = -(dot(beta, f) + beta0) / (Rational(2) * a);
    add_pair(r, approx(along(p, t, d)), approx(along(f, t, d)), line_first);
    r.note = "a line and a quadric whose shadow along it is a half-plane: the distance to its "
             "boundary line, in closed form (exact squared distance)";
    return r;
  }
  DistanceResult r = point_gap(p, core::QuadricMatrix(Z), line_first, digits);
  for (auto& pr : r.pairs) {
    Point& on_line = line_first ? pr[0] : pr[1];
    Point& on_other = line_first ? pr[1] : pr[0];
    const double t = lift(on_other);
    for (size_t i = 0; i < 3; ++i) {
      on_line[i] += t * dd[i];
      on_other[i] += t * dd[i];
    }
  }
  r.note = "a line and a quadric: the distance from the line's point to the quadric's shadow "
           "cylinder along it (exact point-quadric critical distances)" +
           std::string(r.note.empty() ? "" : "; " + r.note);
  return r;
}

} // namespace surfcert::certify
