// surfcert::trace::intersect_curve: certified topology plus traced branches, checked against
// it (see intersect_curve.hpp).
#include "surfcert/trace/intersect_curve.hpp"

#include "surfcert/algebra/eigen4.hpp"
#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/kernel.hpp"
#include "surfcert/certify/curve_lines.hpp"
#include "surfcert/certify/ellipses_in_box.hpp"
#include "surfcert/certify/enclosure.hpp"
#include "surfcert/certify/inner_loops.hpp"
#include "surfcert/certify/oval_chart.hpp"
#include "surfcert/certify/proven_loops.hpp"
#include "surfcert/certify/report.hpp"
#include "surfcert/certify/special_points.hpp"
#include "surfcert/trace/conics.hpp"

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

namespace surfcert::trace {

using certify::classify_qsic;
using certify::complete_report_data;
using certify::Mode;
using certify::Morphology;
using certify::qsic_envelope_json;
using certify::QsicResult;
using certify::Status;
using certify::to_string;
using core::io::Json;

std::vector<std::string> expected_branch_kinds(int c) {
  switch (c) {
  case 1:
    return {"loop", "loop"};
  case 3:
    return {"loop"};
  case 5:
    return {"figure_eight"};
  case 6:
    return {"loop"};
  case 9:
    return {"loop_with_cusp"};
  case 13:
  case 14:
  case 19:
    return {"conic", "conic"};
  case 17:
  case 24:
  case 27:
    return {"conic"};
  case 21:
    return {"double_conic"};
  default:
    return {};
  }
}

namespace {

bool quartic_case(int c) {
  return c == 1 || c == 3 || c == 5 || c == 6 || c == 9;
}

bool isolated_kind(const std::string& k) {
  return k == "acnode" || k == "isolated_point";
}

// max(|f| / |grad f|, |g| / |grad g|) at the double point p, f, g and their gradients exact
// (rationals): for the few points where double-double cannot resolve it. Next to a cone's apex
// f ~ r^2 sinks below double-double's evaluation error (2^-98 of the terms' size) while
// |grad f| ~ r: a point 1e-16 off the exact curve, 1e-18 from an apex at |c| ~ 1, read 7.7e-12.
double exact_residual(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const Point3& p) {
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return HUGE_VAL;
  const std::array<core::Rational, 4> x{core::Rational::exact_from_double(p[0]),
                                        core::Rational::exact_from_double(p[1]),
                                        core::Rational::exact_from_double(p[2]), core::Rational(1)};
  double worst = 0;
  for (const core::QuadricMatrix* q : {&a, &b}) {
    const auto& m = q->matrix();
    const double f = std::fabs(algebra::bilinear(m, x, x).to_double_approx());
    if (f == 0) continue; // on the surface exactly
    double g2 = 0;
    for (size_t i = 0; i < 3; ++i) {
      std::array<core::Rational, 4> e{};
      e[i] = core::Rational(1);
      const double gi = 2 * algebra::bilinear(m, e, x).to_double_approx();
      g2 += gi * gi;
    }
    worst = std::max(worst, g2 > 0 ? f / std::sqrt(g2) : f);
  }
  return worst;
}

// Every returned point brought within 1e-13 of the curve's size of both EXACT surfaces, and
// max_residual measured geometrically (the largest max(|f| / |grad f|, |g| / |grad g|)). The
// tracer walks on the coefficients rounded to doubles; where their error bound shows that
// may leave a point too far off (near a cone's apex, where a rounded cone is a hyperboloid
// with a waist ~1e-8), the point is corrected by Newton on the double-double coefficients
// (RefinedPair); endpoints on a box face stay on it.
// The diagonal of the bounding box of the branches' points (and the isolated points when
// asked); *big, when given, receives the largest |coordinate|.
double points_size(const CurveResult& out, bool isolated_too, double* big = nullptr) {
  Point3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double m = 0;
  auto grow = [&](const Point3& p) {
    for (size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
      m = std::max(m, std::fabs(p[k]));
    }
  };
  for (const auto& br : out.branches)
    for (const auto& p : br.points)
      grow(p);
  if (isolated_too)
    for (const auto& p : out.isolated_points)
      grow(p);
  double size = 0;
  for (size_t k = 0; k < 3; ++k)
    if (hi[k] >= lo[k]) size += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  if (big) *big = m;
  return std::sqrt(size);
}

void finish_points(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const QuadricPair& q,
                   CurveResult& out) {
  double size = points_size(out, true);
  if (!(size > 0)) size = out.box ? out.box->diagonal() : 1.0;
  const double target = 1e-13 * size;
  std::optional<RefinedPair> exact; // built on first need (reads the exact rationals)
  auto face_axis = [&out](const Point3& p) {
    if (!out.box) return -1;
    for (size_t k = 0; k < 3; ++k)
      if (p[k] == out.box->min[k] || p[k] == out.box->max[k]) return static_cast<int>(k);
    return -1;
  };
  out.max_residual = 0;
  out.branch_residual = 0;
  for (auto& br : out.branches)
    for (size_t i = 0; i < br.points.size(); ++i) {
      Point3& p = br.points[i];
      double d = q.distance_bound(p, target);
      if (!(d <= target)) {
        if (!exact) exact.emplace(a, b);
        const bool end = !br.closed && (i == 0 || i + 1 == br.points.size());
        d = exact->refine(p, target, end ? face_axis(p) : -1);
        if (!(d <= target)) d = std::min(d, exact_residual(a, b, p));
      }
      out.max_residual = std::max(out.max_residual, d);
      out.branch_residual = std::max(out.branch_residual, d);
    }
  for (const auto& p : out.isolated_points) { // exact points rounded: measured, not moved
    double d = q.distance_bound(p);
    if (!(d <= target)) {
      if (!exact) exact.emplace(a, b);
      d = exact->distance(p);
      if (!(d <= target)) d = std::min(d, exact_residual(a, b, p));
    }
    out.max_residual = std::max(out.max_residual, d);
  }
}

// The affine special points: isolated ones appended to `isolated`, the others (crunodes,
// cusps, tangency points on the curve) returned: the tracer passes through them.
std::vector<Point3> split_special_points(const QsicResult& t, std::vector<Point3>& isolated) {
  std::vector<Point3> singular;
  for (const auto& p : t.special_points) {
    if (p.at_infinity) continue;
    if (isolated_kind(p.kind))
      isolated.push_back(p.approx);
    else
      singular.push_back(p.approx);
  }
  return singular;
}

bool branches_match(const std::vector<Branch>& branches, int c) {
  std::vector<std::string> got, want = expected_branch_kinds(c);
  for (const auto& br : branches)
    got.push_back(br.kind);
  std::sort(got.begin(), got.end());
  std::sort(want.begin(), want.end());
  return got == want;
}

double diameter(const Branch& br) {
  double d = 0;
  for (size_t i = 0; i < br.points.size(); i += std::max<size_t>(1, br.points.size() / 16))
    for (const auto& q : br.points) {
      double s = 0;
      for (size_t k = 0; k < 3; ++k)
        s += (br.points[i][k] - q[k]) * (br.points[i][k] - q[k]);
      d = std::max(d, std::sqrt(s));
    }
  return d;
}

// A plane of a singular member that is tangent to the quadric meets it in one point (cases 24,
// 25: the crossing point of two imaginary lines); in floating point that section can come out
// as a tiny ellipse around the point. When the float route returns more conics than the
// certified topology has, the extra ones may be dropped only if each is smaller than the
// tolerance and surrounds an exact isolated special point; otherwise everything is kept and
// the mismatch makes the result undecided.
// Whether the certified morphology has lines and no proper conic (four lines, two lines and a
// double line, ...): its plane sections are then drawn as lines.
bool lines_only(const QsicResult& t) {
  return t.morphology && t.morphology->conics == 0 && t.morphology->lines > 0;
}

// What the certified readings say the plane sections are: lines only (the morphology), or
// proper conics only (the affine reading certified without lines: lines of the morphology at
// infinity, as a conic and two lines at infinity, are no section drawn).
SectionKinds section_kinds(const QsicResult& t, const certify::AffineTopology& af) {
  if (lines_only(t)) return SectionKinds::LinesOnly;
  if (af.certified() && af.lines && *af.lines == 0 && af.conics && *af.conics > 0)
    return SectionKinds::ProperOnly;
  return SectionKinds::Any;
}

void drop_point_sections(CurveResult& out, int expected_conics, double tol) {
  auto& br = out.branches;
  if (static_cast<int>(br.size()) <= expected_conics) return;
  std::vector<size_t> order(br.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](size_t x, size_t y) { return diameter(br[x]) > diameter(br[y]); });
  std::vector<Branch> keep;
  for (size_t r = 0; r < order.size(); ++r) {
    const auto& b = br[order[r]];
    bool droppable = false;
    if (static_cast<int>(r) >= expected_conics && diameter(b) < tol)
      for (const auto& p : out.isolated_points) {
        double s = 0;
        for (size_t k = 0; k < 3; ++k)
          s += (b.points[0][k] - p[k]) * (b.points[0][k] - p[k]);
        droppable = droppable || std::sqrt(s) < tol;
      }
    if (!droppable) keep.push_back(b);
  }
  br = std::move(keep);
}

using V = Point3;

// The box widened to short dyadic faces (multiples of 2^-12 of its diagonal's binary order):
// the exact face conics then have small coefficients.
Box dyadic_outward(Box b) {
  int e = 0;
  std::frexp(b.diagonal(), &e);
  const double unit = std::ldexp(1.0, e - 12);
  for (size_t k = 0; k < 3; ++k) {
    b.min[k] = std::floor(b.min[k] / unit) * unit;
    b.max[k] = std::ceil(b.max[k] / unit) * unit;
  }
  return b;
}

// The automatic box: the bounding box of the given points, widened on every side by half its
// diagonal (at least 2^-30 of the points' distance from the origin, and 1 for a single point,
// up to 2^-40 of that distance). The floors were 1e-3 and 1e-6: a plane's circle 2e-4 across,
// 1414 from the origin (a pipe of radius 1e-4 cut by a plane), got a box 2,048 wide, where it
// is a dot; 2^-30 of the distance still leaves ~2^22 doubles across the box.
Box box_around(const std::vector<V>& pts) {
  Box b;
  bool any = false;
  for (const V& p : pts) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
    for (size_t k = 0; k < 3; ++k) {
      b.min[k] = any ? std::min(b.min[k], p[k]) : p[k];
      b.max[k] = any ? std::max(b.max[k], p[k]) : p[k];
    }
    any = true;
  }
  if (!any) b.min = b.max = V{0, 0, 0};
  double far = 0;
  for (size_t k = 0; k < 3; ++k)
    far = std::max({far, std::fabs(b.min[k]), std::fabs(b.max[k])});
  double m = std::max(0.5 * b.diagonal(), 0x1p-30 * far);
  if (!(b.diagonal() > 0x1p-40 * (1 + far))) m = 1; // one point (up to rounding): no size
  for (size_t k = 0; k < 3; ++k) {
    b.min[k] -= m;
    b.max[k] += m;
  }
  return dyadic_outward(b);
}

// The points without the outliers: those farther from the points' coordinate-wise median than
// 1000 times the median of the distances from it (all of them when that median is 0).
std::vector<V> without_outliers(const std::vector<V>& pts) {
  std::vector<V> fin;
  for (const V& p : pts)
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) fin.push_back(p);
  if (fin.size() < 3) return pts;
  V med{};
  for (size_t k = 0; k < 3; ++k) {
    std::vector<double> c;
    for (const V& p : fin)
      c.push_back(p[k]);
    std::nth_element(c.begin(), c.begin() + static_cast<long>(c.size() / 2), c.end());
    med[k] = c[c.size() / 2];
  }
  std::vector<double> d;
  for (const V& p : fin)
    d.push_back(std::hypot(p[0] - med[0], p[1] - med[1], p[2] - med[2]));
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                   sorted.end());
  const double typical = sorted[sorted.size() / 2];
  if (!(typical > 0)) return pts;
  std::vector<V> out;
  for (size_t i = 0; i < fin.size(); ++i)
    if (d[i] <= 1000 * typical) out.push_back(fin[i]);
  return out;
}

bool on_face(const Box& b, const V& p, double eps) {
  if (!b.contains(p, eps)) return false;
  for (size_t k = 0; k < 3; ++k)
    if (std::fabs(p[k] - b.min[k]) <= eps || std::fabs(p[k] - b.max[k]) <= eps) return true;
  return false;
}

// Pieces of an open polyline inside the box, each end where it leaves cut onto the face by
// Newton (the polyline's points lie on the curve).
std::vector<Branch> clip_to_box(const QuadricPair& q, const Branch& br, const Box& box) {
  std::vector<Branch> out;
  Branch cur;
  cur.kind = br.kind;
  cur.closed = false;
  cur.plane = br.plane;
  // A planar piece (a conic) that f = g = 0 cannot cut (a double conic: the surfaces tangent
  // along it) is cut on its plane: the segment's crossing of the face, by Newton on
  // {face, plane, one surface}.
  auto cut = [&](const V& in, const V& outp, V& y) {
    if (face_crossing(q, box, in, outp, y) && box.contains(y, 1e-9 * box.diagonal())) return true;
    if (!br.plane) return false;
    for (size_t k = 0; k < 3; ++k)
      for (double c : {box.min[k], box.max[k]}) {
        const double den = outp[k] - in[k];
        const bool outward = c == box.min[k] ? den < 0 : den > 0;
        if (!outward) continue;
        const double lam = (c - in[k]) / den;
        if (!(lam >= 0 && lam <= 1)) continue;
        V z{};
        for (size_t m = 0; m < 3; ++m)
          z[m] = in[m] + lam * (outp[m] - in[m]);
        if (newton_on_face_in_plane(q, k, c, *br.plane, z) &&
            box.contains(z, 1e-9 * box.diagonal())) {
          z[k] = c;
          y = z;
          return true;
        }
      }
    return false;
  };
  for (size_t i = 0; i < br.points.size(); ++i) {
    const V& p = br.points[i];
    const bool inside = box.contains(p);
    if (inside) {
      if (cur.points.empty() && i > 0) {
        V y{};
        if (cut(p, br.points[i - 1], y)) cur.points.push_back(y);
      }
      cur.points.push_back(p);
    } else if (!cur.points.empty()) {
      V y{};
      if (cut(br.points[i - 1], p, y)) cur.points.push_back(y);
      out.push_back(cur);
      cur.points.clear();
    }
  }
  if (!cur.points.empty()) out.push_back(cur);
  return out;
}

// A closed polyline inside the box: itself when wholly inside, else its pieces inside (opened
// at a point outside, so that no piece is split at the seam). A given box may cut a closed
// conic (x = 1/2 through the Steinmetz ellipses): the arcs then end on the faces, where the
// exact crossings are matched, instead of the whole conic counting as a loop in the box.
std::vector<Branch> clip_closed_to_box(const QuadricPair& q, const Branch& br, const Box& box) {
  const auto& pts = br.points;
  size_t start = pts.size();
  for (size_t i = 0; i < pts.size() && start == pts.size(); ++i)
    if (!box.contains(pts[i])) start = i;
  if (start == pts.size()) return {br};
  Branch open = br;
  open.closed = false;
  open.points.clear();
  for (size_t i = 0; i <= pts.size(); ++i)
    open.points.push_back(pts[(start + i) % pts.size()]);
  return clip_to_box(q, open, box);
}

certify::BoxExits exact_exits(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                              const Box& box) {
  std::array<core::Rational, 3> lo, hi;
  for (size_t k = 0; k < 3; ++k) {
    lo[k] = core::Rational::exact_from_double(box.min[k]);
    hi[k] = core::Rational::exact_from_double(box.max[k]);
  }
  return certify::box_exits(a.matrix(), b.matrix(), lo, hi);
}

// The crossings of the affine curve with the box's faces, from the pair that writes it most
// simply: on route common_apex the rational lines themselves (lines_box_exits); on the plane
// routes the affine curve is `plane` ∩ `section_of` (for "pencil_plane"
// the plane B - cA replaces B), so a tangency along a line reads as the plane's rank-1
// section (box_exits' exception) where the two quadrics show only a multiple crossing (two
// parallel cylinders touching along a ruling). Route "plane_pair": the crossings of the two
// sections together, certified when each is and no crossing of one may be one of the other
// (disjoint enclosures: the curve is smooth there).
// The plane of a curve that is one double conic or two double lines crossing (the surfaces
// tangent along it): the rank-1 member at a rational root, exactly (the row of its largest
// diagonal entry), as a quadric; nullopt otherwise. Its crossings with a face are double
// roots of f = g = 0 there ("a multiple crossing"), simple ones of that plane and either
// surface (as a set the curve is A ∩ B = A ∩ (B - lambda A) = A ∩ plane).
std::optional<core::QuadricMatrix> double_conic_plane(const QsicResult& t) {
  if (t.status != Status::Certified || !t.morphology) return std::nullopt;
  const certify::Morphology& m = *t.morphology;
  const bool conic = m.conics == 1 && m.double_components == 1 && !m.lines;
  const bool line_pair = m.lines == 2 && m.double_components == 2 && !m.conics;
  if (!(conic || line_pair) || m.loops || m.cubics) return std::nullopt;
  for (const auto& r : t.facts.real_roots) {
    if (r.rank != 1 || !r.rational_value) continue;
    const core::Mat4 e = core::scaled(t.facts.a, *r.rational_value) + core::scaled(t.facts.b, -1);
    size_t k = 4;
    for (size_t i = 0; i < 4; ++i)
      if (!e[i][i].is_zero() && (k == 4 || core::abs(e[i][i]) > core::abs(e[k][k]))) k = i;
    if (k == 4) return std::nullopt;
    if (e[k][0].is_zero() && e[k][1].is_zero() && e[k][2].is_zero()) return std::nullopt;
    return core::QuadricMatrix(certify::plane_as_quadric({e[k][0], e[k][1], e[k][2], e[k][3]}));
  }
  return std::nullopt;
}

// The curve's real lines, exactly (certify/curve_lines.hpp), for a certified lines-only
// morphology: from the pencil's rank-2 rational members and the rational points at infinity.
// nullopt when they are not all found that way.
std::optional<std::vector<certify::ExactLine>> exact_lines(const QsicResult& t,
                                                           const certify::AffineTopology& af) {
  if (t.status != Status::Certified || !t.morphology || !af.certified()) return std::nullopt;
  if (af.route == "exact_lines") return af.exact_lines; // one line at infinity: the affine ones
  const certify::Morphology& m = *t.morphology;
  // Lines only: every real component a line (a cubic, conic or loop beside them has crossings
  // of its own, which the lines' do not include).
  if (m.lines <= 0 || m.conics || m.cubics || m.loops) return std::nullopt;
  std::vector<std::array<core::Rational, 3>> dirs;
  for (const auto& pt : af.points_at_infinity) {
    if (!pt.rational) continue;
    std::array<core::Rational, 3> d;
    bool ok = true;
    for (size_t k = 0; k < 3 && ok; ++k) {
      const auto v = core::Rational::from_string(pt.direction[k]);
      ok = v.has_value();
      if (v) d[k] = *v;
    }
    if (ok) dirs.push_back(d);
  }
  return certify::exact_curve_lines(t.facts, t.morphology->lines, dirs);
}

certify::BoxExits curve_exits(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                              const certify::AffineTopology& af, const Box& box,
                              const QsicResult& t) {
  if (af.certified() && af.apex) {
    // Route common_apex: the lines from the apex, exact (a line along which the surfaces are
    // tangent is then no multiple crossing): rational directions, and algebraic ones (a double
    // rational line beside two conjugate ones) compared with the faces at their roots.
    std::vector<std::array<core::Rational, 3>> dirs;
    std::vector<certify::AlgebraicDirection> algebraic;
    bool exact = true;
    for (const auto& pt : af.points_at_infinity) {
      if (!pt.rational) {
        exact = exact && pt.polynomial.degree() >= 2;
        algebraic.push_back({pt.polynomial, pt.lo, pt.hi, pt.dir_in_t});
        continue;
      }
      std::array<core::Rational, 3> d;
      for (size_t k = 0; k < 3 && exact; ++k) {
        const auto v = core::Rational::from_string(pt.direction[k]);
        exact = v.has_value();
        if (v) d[k] = *v;
      }
      dirs.push_back(d);
    }
    if (exact) {
      std::array<core::Rational, 3> lo, hi;
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = core::Rational::exact_from_double(box.min[k]);
        hi[k] = core::Rational::exact_from_double(box.max[k]);
      }
      return algebraic.empty() ? certify::lines_box_exits(*af.apex, dirs, lo, hi)
                               : certify::lines_box_exits(*af.apex, dirs, algebraic, lo, hi);
    }
  }
  if (af.certified() && af.ruling) {
    // Route parallel_cylinders: the lines b + t d, exact when every base point is rational (a
    // line along which the cylinders touch is then no multiple crossing); parallel lines
    // with distinct base points cross the faces at distinct points. Otherwise A and B, or a
    // plane pair of their pencil cut with A (af.plane, when a line is multiple), below.
    std::array<core::Rational, 3> lo, hi;
    for (size_t k = 0; k < 3; ++k) {
      lo[k] = core::Rational::exact_from_double(box.min[k]);
      hi[k] = core::Rational::exact_from_double(box.max[k]);
    }
    bool rational = true;
    for (const auto& l : af.ruling_lines)
      rational = rational && l.base.has_value();
    if (rational) {
      certify::BoxExits all;
      all.certified = true;
      for (const auto& l : af.ruling_lines) {
        certify::BoxExits one = certify::lines_box_exits(*l.base, {*af.ruling}, lo, hi);
        if (!one.certified) return one;
        all.points.insert(all.points.end(), one.points.begin(), one.points.end());
      }
      return all;
    }
  }
  if (af.certified() && !af.plane)
    if (const auto plane = double_conic_plane(t)) {
      // The other quadric: not a plane, and not the double plane itself (A of rank 1, the
      // plane's square: its section by the plane is the whole plane, "a component in the plane"
      // of every face it crosses; generate --case 21 --seed 32, pairs 7 and 11).
      const bool a_flat = a.is_plane() || algebra::kernel_basis(a.matrix()).size() >= 3;
      return exact_exits(*plane, a_flat ? b : a, box);
    }
  if (!af.plane)
    if (const auto lines = exact_lines(t, af)) {
      // A curve of lines only (a real double line among them: its crossings are double roots
      // of the face resultants, which the generic reading refuses), each line exactly.
      std::array<core::Rational, 3> lo, hi;
      for (size_t k = 0; k < 3; ++k) {
        lo[k] = core::Rational::exact_from_double(box.min[k]);
        hi[k] = core::Rational::exact_from_double(box.max[k]);
      }
      return certify::exact_lines_box_exits(*lines, lo, hi);
    }
  if (!af.certified() || !af.plane || !af.section_of) return exact_exits(a, b, box);
  const core::QuadricMatrix plane(*af.plane), other(*af.section_of);
  certify::BoxExits ex = exact_exits(plane, other, box);
  if (!af.plane2 || !ex.certified) return ex;
  certify::BoxExits ex2 = exact_exits(core::QuadricMatrix(*af.plane2), other, box);
  if (!ex2.certified) return ex2;
  for (const auto& p : ex.points)
    for (const auto& q2 : ex2.points) {
      if (p.axis != q2.axis || p.at_max != q2.at_max) continue;
      // Each point lies within its radius of its enclosure's midpoint, which approx rounds:
      // the margin covers both radii and the roundings (of the midpoints and of this
      // arithmetic) many times over, so a larger gap proves two distinct points.
      double gap = 0, size = 0;
      for (size_t k = 0; k < 3; ++k) {
        gap = std::max(gap, std::fabs(p.approx[k] - q2.approx[k]));
        size = std::max({size, std::fabs(p.approx[k]), std::fabs(q2.approx[k])});
      }
      if (!(gap > 2 * (p.radius + q2.radius) + 0x1p-48 * size + 0x1p-1000)) {
        certify::BoxExits out;
        out.reason = "the sections of the two planes may cross each other on a face";
        return out;
      }
    }
  ex.points.insert(ex.points.end(), ex2.points.begin(), ex2.points.end());
  return ex;
}

// One unit in the last place of a double of magnitude |x| (0 for x = 0).
double ulp_of(double x) {
  return x != 0 ? std::ldexp(1.0, std::ilogb(x) - 52) : 0.0;
}

// The picture checks' tolerance in a box: `rel` of its diagonal, and never below 16 units in
// the last place of its largest coordinate (a box 2.4 wide 2^31 from the origin holds its
// points on a grid of 2.4e-7: its ends cannot be nearer their exact crossings than that).
double picture_tolerance(const Box& box, double rel) {
  double big = 0;
  for (size_t k = 0; k < 3; ++k)
    big = std::max({big, std::fabs(box.min[k]), std::fabs(box.max[k])});
  return rel * box.diagonal() + 16 * ulp_of(big);
}

// Matches each end of each open piece with exactly one exact crossing (within tol) and each
// crossing with exactly one end; sets the pieces' `exits`. Empty string on success, else why.
// Crossings closer together than tol (two lines 2e-10 apart, in a box 3 wide) are told apart
// when each one's nearest end is within tol and the next nearest 8 times farther (plus the
// crossing's radius): the traced ends of such lines are their exact points rounded.
std::string match_exits(std::vector<Branch>& branches, const certify::BoxExits& ex, double tol) {
  std::vector<const Point3*> ends;
  for (auto& br : branches) {
    br.exits.clear();
    if (br.closed || br.points.empty()) continue;
    ends.push_back(&br.points.front());
    ends.push_back(&br.points.back());
  }
  if (ends.size() != ex.points.size())
    return "traced " + std::to_string(ends.size() / 2) + " open piece(s) in the box; the curve " +
           "crosses its faces at " + std::to_string(ex.points.size()) + " exact point(s)";
  auto dist = [](const Point3& p, const Point3& q) {
    return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                     (p[2] - q[2]) * (p[2] - q[2]));
  };
  std::vector<int> of_end(ends.size(), -1);
  for (size_t c = 0; c < ex.points.size(); ++c) {
    int hit = -1;
    double d1 = INFINITY, d2 = INFINITY; // the nearest end's distance, the next nearest's
    for (size_t e = 0; e < ends.size(); ++e) {
      const double d = dist(*ends[e], ex.points[c].approx);
      if (d < d1) {
        d2 = d1, d1 = d;
        hit = static_cast<int>(e);
      } else if (d < d2) {
        d2 = d;
      }
    }
    const bool unique = d2 > tol || d2 > 8 * d1 + 2 * ex.points[c].radius;
    if (hit < 0 || !(d1 <= tol) || !unique || of_end[static_cast<size_t>(hit)] >= 0)
      return "a traced end does not match exactly one exact crossing with the box's faces";
    of_end[static_cast<size_t>(hit)] = static_cast<int>(c);
  }
  size_t e = 0;
  for (auto& br : branches) {
    if (br.closed || br.points.empty()) continue;
    br.exits = {of_end[e], of_end[e + 1]};
    e += 2;
  }
  return "";
}

// A picture in which more pieces of polyline leave a crossing (crunode: 4) or a cusp (2) than
// the curve has there: a walk on another piece of curve was drawn through it (the counts and
// the ends can still match, each component glued to the crossing). Empty when none, else why.
std::string too_many_arms(const QsicResult& t, const std::vector<Branch>& branches) {
  for (const auto& sp : t.special_points) {
    if (sp.at_infinity) continue;
    const int most = sp.kind == "crunode" ? 4 : sp.kind == "cusp" ? 2 : -1;
    if (most < 0) continue;
    int arms = 0;
    for (const auto& br : branches)
      for (size_t i = 0; i < br.points.size(); ++i)
        if (br.points[i] == sp.approx)
          arms += br.closed || (i > 0 && i + 1 < br.points.size()) ? 2 : 1;
    if (arms > most)
      return "the traced pieces leave a " + sp.kind + " along " + std::to_string(arms) +
             " arms (a picture gluing other pieces of curve to it)";
  }
  return "";
}

// An automatic box is doubled, at most this many times, while it shows fewer open pieces than
// the certified number of unbounded branches: a branch may pass outside the first box, far
// outside (a cuspidal quartic's cusp at infinity with a simple point at infinity 0.004 rad
// beside it: the arc between the two turns ~4,700 out, where the box placed around the rest of
// the curve was 12 wide; six doublings missed it, generate --case 9 --seed 45 pair 8 swapped).
// The steps scale with the box: a doubling costs about one trace.
constexpr int kMaxBoxDoublings = 12;

using ExactPoint = std::array<algebra::QuadraticNumber, 3>;

// Whether an exact point lies in the closed box: each coordinate a + b sqrt(d) against each
// face, the face's double read exactly.
bool exact_in_box(const ExactPoint& c, const Box& box) {
  for (size_t k = 0; k < 3; ++k) {
    const auto side = [&c, k](double face) {
      return algebra::QuadraticNumber{c[k].a - core::Rational::exact_from_double(face), c[k].b,
                                      c[k].d}
          .sign();
    };
    if (side(box.min[k]) < 0 || side(box.max[k]) > 0) return false;
  }
  return true;
}

// The curve's affine isolated points, exact, with their rounded coordinates; nullopt when the
// special points do not account for the affine reading's isolated points or one of them is not
// exact.
std::optional<std::vector<std::pair<ExactPoint, Point3>>>
exact_isolated_points(const QsicResult& t, const certify::AffineTopology& af) {
  if (!af.isolated_points) return std::nullopt;
  std::vector<std::pair<ExactPoint, Point3>> out;
  if (af.apex && af.lines && *af.lines == 0 && *af.isolated_points == 1) {
    // Two cones with one common apex and no real common generator: the apex alone, exact.
    ExactPoint c;
    Point3 approx{};
    for (size_t k = 0; k < 3; ++k) {
      c[k] = {(*af.apex)[k], core::Rational(0), core::Integer(0)};
      approx[k] = (*af.apex)[k].to_double_approx();
    }
    out.emplace_back(c, approx);
    return out;
  }
  if (!t.special_points_complete) return std::nullopt;
  for (const auto& p : t.special_points) {
    if (p.at_infinity || !isolated_kind(p.kind)) continue;
    ExactPoint c;
    for (size_t k = 0; k < 3; ++k) {
      if (p.numbers) {
        c[k] = (*p.numbers)[k];
      } else {
        const auto r = p.exact ? core::Rational::from_string(p.coords[k]) : std::nullopt;
        if (!r) return std::nullopt;
        c[k] = {*r, core::Rational(0), core::Integer(0)};
      }
    }
    out.emplace_back(c, p.approx);
  }
  if (static_cast<int>(out.size()) != *af.isolated_points) return std::nullopt;
  return out;
}

// The curve's affine isolated points that lie in the closed box (their rounded coordinates),
// decided exactly from the exact special points (exact_in_box); nullopt when they are not all
// known exactly (exact_isolated_points). (Drawn by the rounded point in the box and held
// against the whole affine curve's count, a given box missing an acnode left the answer
// undecided: 140 of 1480 generated pairs in boxes.)
std::optional<std::vector<Point3>>
isolated_in_box(const QsicResult& t, const certify::AffineTopology& af, const Box& box) {
  const auto all = exact_isolated_points(t, af);
  if (!all) return std::nullopt;
  std::vector<Point3> inside;
  for (const auto& [c, approx] : *all)
    if (exact_in_box(c, box)) inside.push_back(approx);
  return inside;
}

// A curve whose affine part is one loop and isolated points, crossing no face of a given box
// (certified): the loop lies wholly inside the box or wholly outside. Which one is decided by
// one real point of the curve that is no isolated point (so on the loop): a certified crossing
// of the faces of a small box around a float extreme point of the curve, that small box
// disjoint from the given one (or inside it) and holding no isolated point, both exactly.
// True: the loop lies outside; false: inside; nullopt: no such point proven. (Where an acnode
// lies in the given box, inner_component_bound's cover meets a singular point in every
// direction: generate --case 6 --seed 42 pair 19, boxed, with its oval outside the box.)
std::optional<bool> lone_loop_outside(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                      const Box& box, const QsicResult& t,
                                      const certify::AffineTopology& af) {
  const auto isolated = exact_isolated_points(t, af);
  if (!isolated) return std::nullopt;
  const double big =
      std::max({1.0, std::fabs(box.min[0]), std::fabs(box.min[1]), std::fabs(box.min[2]),
                std::fabs(box.max[0]), std::fabs(box.max[1]), std::fabs(box.max[2])});
  int tried = 0;
  for (const Point3& p : extreme_points_float(QuadricPair(a, b))) {
    const double far = std::max({big, std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
    for (int e : {-10, -16}) {
      const double w = std::ldexp(1.0, std::ilogb(far) + e);
      Box small;
      for (size_t k = 0; k < 3; ++k) {
        small.min[k] = p[k] - w;
        small.max[k] = p[k] + w;
      }
      bool outside = false, inside = true;
      for (size_t k = 0; k < 3; ++k) {
        outside = outside || small.max[k] < box.min[k] || small.min[k] > box.max[k];
        inside = inside && small.min[k] >= box.min[k] && small.max[k] <= box.max[k];
      }
      if (!outside && !inside) continue;
      if (std::any_of(isolated->begin(), isolated->end(),
                      [&small](const auto& c) { return exact_in_box(c.first, small); }))
        continue;
      if (++tried > 12) return std::nullopt;
      const certify::BoxExits ex = curve_exits(a, b, af, small, t);
      if (ex.certified && !ex.points.empty()) return outside;
    }
  }
  return std::nullopt;
}

CurveResult trace_curve_at(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                           QsicResult topology, const TraceOptions& opt, int depth,
                           const certify::AffineTopology* known = nullptr,
                           const Point3* centre = nullptr, bool unit_size_there = false);

std::vector<std::vector<certify::RationalBox>> loop_proposals(const CurveResult& out);
std::vector<certify::RationalBox> loop_boxes(const std::vector<Point3>& points);

// The loops lying wholly inside a given box when the affine curve is loops (and isolated points)
// only: the pair traced whole (an automatic box), each loop proven in a box of its own
// (certify::proven_loops, as many boxes as loops: every point of a loop lies in its box, none
// on a box's faces), each exact crossing of the given box's faces placed in one loop box by its
// enclosure (that loop is cut), and each loop crossing no face inside the given box when its
// box is, outside when its box misses it. nullopt when a step proves nothing (a crossing in no
// loop box, a loop box straddling a face of the given box). The floats choose the loop boxes.
std::optional<int> loops_inside_by_loop_boxes(const core::QuadricMatrix& a,
                                              const core::QuadricMatrix& b, const Box& box,
                                              const certify::BoxExits& ex, const QsicResult& t,
                                              const certify::AffineTopology& af) {
  const int loops = *af.loops;
  if (*af.unbounded_branches != 0 || loops < 1 || !ex.certified) return std::nullopt;
  const CurveResult whole = trace_curve_at(a, b, t, TraceOptions{}, 0, &af);
  const auto proposals = loop_proposals(whole);
  if (static_cast<int>(proposals.size()) != loops) return std::nullopt;
  certify::ProvenLoops p = certify::proven_loops(a.matrix(), b.matrix(), proposals);
  if (p.count != loops && loops == 2) {
    // Two loops whose boxes (with their margins) meet, but whose points lie apart along an
    // axis (a cone and a cylinder: two ovals 0.013 apart in z, each ~5 long): each box cut
    // a third of the way into the gap on that axis.
    std::vector<const std::vector<Point3>*> pts;
    for (const auto& br : whole.branches)
      if (br.closed && br.points.size() >= 3) pts.push_back(&br.points);
    if (pts.size() != 2) return std::nullopt;
    size_t axis = 3;
    double gap = 0, cut_lo = 0, cut_hi = 0;
    size_t below = 0;
    for (size_t k = 0; k < 3; ++k) {
      std::array<double, 2> lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
      for (size_t l = 0; l < 2; ++l)
        for (const Point3& x : *pts[l]) {
          lo[l] = std::min(lo[l], x[k]);
          hi[l] = std::max(hi[l], x[k]);
        }
      const size_t lower = hi[0] < lo[1] ? 0 : 1;
      const double g = lo[1 - lower] - hi[lower];
      if (g > gap) {
        axis = k, gap = g, below = lower;
        cut_lo = hi[lower] + g / 3;
        cut_hi = lo[1 - lower] - g / 3;
      }
    }
    if (axis == 3 || !(cut_lo < cut_hi)) return std::nullopt;
    const core::Rational clo = core::Rational::exact_from_double(cut_lo),
                         chi = core::Rational::exact_from_double(cut_hi);
    std::vector<std::vector<certify::RationalBox>> clipped;
    for (size_t l = 0; l < 2; ++l) {
      std::vector<certify::RationalBox> boxes;
      for (certify::RationalBox bx : loop_boxes(*pts[l])) {
        if (l == below && clo < bx.hi[axis]) bx.hi[axis] = clo;
        if (l != below && bx.lo[axis] < chi) bx.lo[axis] = chi;
        if (bx.lo[axis] < bx.hi[axis]) boxes.push_back(std::move(bx));
      }
      clipped.push_back(std::move(boxes));
    }
    p = certify::proven_loops(a.matrix(), b.matrix(), clipped);
  }
  if (p.count != loops) return std::nullopt;
  using core::Rational;
  std::vector<int> crossings(p.boxes.size(), 0);
  for (const auto& c : ex.points) {
    if (!std::isfinite(c.radius)) return std::nullopt;
    int in = -1;
    for (size_t i = 0; i < p.boxes.size() && in < 0; ++i) {
      bool inside = true;
      for (size_t k = 0; k < 3 && inside; ++k) {
        // The crossing within twice the enclosure's half-width of the reported point (which
        // the enclosure holds: Newton's point or its rounded midpoint), widened by 4 ulps of it
        // and a relative 2^-50 (the half-width itself was rounded).
        const double r = 2 * c.radius * (1 + 0x1p-50) +
                         4 * std::ldexp(DBL_EPSILON, std::ilogb(c.approx[k])) + DBL_MIN;
        const Rational lo =
            Rational::exact_from_double(c.approx[k]) - Rational::exact_from_double(r);
        const Rational hi =
            Rational::exact_from_double(c.approx[k]) + Rational::exact_from_double(r);
        inside = p.boxes[i].lo[k] < lo && hi < p.boxes[i].hi[k];
      }
      if (inside) in = static_cast<int>(i);
    }
    if (in < 0) return std::nullopt;
    ++crossings[static_cast<size_t>(in)];
  }
  int inside = 0;
  for (size_t i = 0; i < p.boxes.size(); ++i) {
    if (crossings[i] > 0) continue; // cut by the faces
    const auto& lb = p.boxes[i];
    bool within = true, apart = false;
    for (size_t k = 0; k < 3; ++k) {
      const Rational lo = Rational::exact_from_double(box.min[k]),
                     hi = Rational::exact_from_double(box.max[k]);
      within = within && lo <= lb.lo[k] && lb.hi[k] <= hi;
      apart = apart || lb.hi[k] < lo || hi < lb.lo[k];
    }
    if (within) {
      ++inside;
    } else if (!apart) {
      return std::nullopt;
    }
  }
  return inside;
}

// Whether `closed` traced loops are all the loops lying wholly inside a given box (which may
// cut others): all `loops` of the affine topology, or as many as certify/inner_loops.hpp proves
// at most (from the critical points of a direction in the box and the crossings `ex`, by
// interval arithmetic, whatever the tracer saw). Else false, with the reason in `why`.
bool loops_in_given_box(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const Box& box,
                        const certify::BoxExits& ex, int closed, const certify::AffineTopology& af,
                        const QsicResult& t, std::string& why) {
  const int loops = *af.loops, unbounded = *af.unbounded_branches;
  if (closed == loops) return true;
  if (closed > loops) return false;
  // Loops that are conics of rational planes (certify/ellipses_in_box.hpp): each one inside
  // the box or not, exactly (the interval proof below fails on a curve singular where two
  // conics cross: two crossing ellipses in a box cutting one of them).
  if (t.status == Status::Certified) {
    std::array<core::Rational, 3> lo, hi;
    for (size_t k = 0; k < 3; ++k) {
      lo[k] = core::Rational::exact_from_double(box.min[k]);
      hi[k] = core::Rational::exact_from_double(box.max[k]);
    }
    if (const auto inside = certify::ellipses_in_box(t.facts, loops, lo, hi)) {
      if (*inside == closed) return true;
      why = "traced " + std::to_string(closed) + " closed branch(es) in the box; " +
            std::to_string(*inside) + " of the curve's " + std::to_string(loops) +
            " loop(s) (conics) lie wholly inside it";
      return false;
    }
  }
  // The whole affine curve one component (a loop) and a certified crossing of the box's faces:
  // that point lies on it, so it is cut, and no loop lies wholly inside (a double conic, where
  // the interval proof below meets a curve singular everywhere).
  if (loops + unbounded == 1 && ex.certified && !ex.points.empty()) return closed == 0;
  // ... and crossing none: inside or outside as a whole (lone_loop_outside).
  if (loops == 1 && unbounded == 0 && ex.certified && ex.points.empty())
    if (const auto out = lone_loop_outside(a, b, box, t, af)) {
      if (closed == (*out ? 0 : 1)) return true;
      why = "traced " + std::to_string(closed) + " closed branch(es) in the box; the curve's " +
            "one loop lies wholly " + (*out ? "outside" : "inside") + " it";
      return false;
    }
  const certify::InnerComponentBound p =
      certify::inner_component_bound(a.matrix(), b.matrix(), box.min, box.max, &ex, closed);
  if (p.bound && *p.bound == closed) return true;
  // Loops only: each crossing placed on its loop by proven loop boxes (a box cutting both ovals
  // of a cone and a cylinder, where no direction's critical points bounded the loops inside:
  // natural_pairs_doubles.py --seed 38 pair 239 boxed).
  if (const auto inside = loops_inside_by_loop_boxes(a, b, box, ex, t, af)) {
    if (*inside == closed) return true;
    why = "traced " + std::to_string(closed) + " closed branch(es) in the box; " +
          std::to_string(*inside) + " of the curve's " + std::to_string(loops) +
          " loop(s) lie wholly inside it (proven loop boxes)";
    return false;
  }
  why = "traced " + std::to_string(closed) + " closed branch(es) in the box; the certified " +
        "affine topology has " + std::to_string(loops) + " loop(s), which the box may cut or " +
        "hold: " +
        (p.bound ? "at most " + std::to_string(*p.bound) + " proven to lie wholly inside"
                 : "not proven how many lie wholly inside (" + p.reason + ")");
  return false;
}

// The exact crossings with the box's faces (an automatic box meeting the curve
// non-generically — on an edge, tangentially — is widened a little, unevenly, up to 3 times,
// and `retrace` called for it), then the verdict: certified only when the affine topology is
// certified, the traced closed branches and isolated points in the box have its counts, an
// automatic box shows at least one open piece per unbounded branch, and the traced open
// pieces' ends match the exact crossings one to one. Returns true when the verdict is
// undecided because of the traced picture alone (its pieces, their ends), which a finer trace
// may fix; false when certified or when an exact part is missing.
bool settle_box(const core::QuadricMatrix& a, const core::QuadricMatrix& b, const QuadricPair& q,
                CurveResult& out, Box& box, bool automatic,
                const std::function<void(const Box&)>& retrace, bool special_points_complete) {
  const certify::AffineTopology& af = out.affine;
  out.box_exits = curve_exits(a, b, af, box, out.topology);
  // Each nudge moves the faces by its own uneven amounts: with one ratio scaled up, the corner
  // of a box placed symmetrically around a line x + y = c (the line meeting that edge) moved
  // along the line when the box's widths happened to match the ratio (generate --case 10
  // --seed 53 pair 13: every nudge kept the crossing on the edge).
  constexpr double kLow[3] = {0.0371, 0.0517, 0.0293}, kHigh[3] = {0.0253, 0.0197, 0.0611};
  for (int nudge = 1; nudge <= 3 && automatic && !out.box_exits->certified; ++nudge) {
    Box wider = box;
    const auto n = static_cast<size_t>(nudge - 1);
    for (size_t k = 0; k < 3; ++k) {
      const double h = box.max[k] - box.min[k];
      wider.min[k] -= h * kLow[n] * nudge * static_cast<double>(k + 1);
      wider.max[k] += h * kHigh[n] * nudge * static_cast<double>(3 - k);
    }
    wider = dyadic_outward(wider);
    certify::BoxExits ex = curve_exits(a, b, af, wider, out.topology);
    if (!ex.certified) continue;
    box = wider;
    retrace(box);
    out.box_exits = std::move(ex);
  }
  out.box = box;
  // The isolated points in the box: decided exactly where the special points allow it, else
  // by their rounded coordinates (and then held against the whole curve's count).
  const auto exact_inside = isolated_in_box(out.topology, af, box);
  if (exact_inside) {
    out.isolated_points = *exact_inside;
  } else {
    std::vector<Point3> inside;
    for (const auto& p : out.isolated_points)
      if (box.contains(p)) inside.push_back(p);
    out.isolated_points = inside;
  }
  finish_points(a, b, q, out);

  int closed = 0, open = 0, open_off_face = 0;
  const double eps = picture_tolerance(box, 1e-7);
  for (const auto& br : out.branches) {
    if (br.closed) {
      ++closed;
      continue;
    }
    ++open;
    if (br.points.size() < 2 || !on_face(box, br.points.front(), eps) ||
        !on_face(box, br.points.back(), eps))
      ++open_off_face;
  }
  std::string why;
  bool tracer_fault = false; // the traced pieces, not an exact part, are what fails
  if (!af.certified()) {
    why = "the affine topology is not certified";
  } else if (!special_points_complete) {
    why = "special points not all computed exactly";
  } else if (!(out.max_residual <= picture_tolerance(box, 1e-9))) {
    // The points are corrected onto the exact surfaces to ~1e-13 of their extent; one that
    // stays off them (a hyperbola sampled through its centre at a far offset, its pieces
    // joining crossings on different halves: helper-11's audit) is no picture of the curve,
    // whatever its ends match.
    tracer_fault = true;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g", out.max_residual / box.diagonal());
    why = std::string("traced points lie up to ") + buf +
          " box diagonals off the surfaces (a picture of another curve)";
  } else if (const std::string arms = too_many_arms(out.topology, out.branches); !arms.empty()) {
    tracer_fault = true;
    why = arms;
  } else if (!(automatic ? closed == *af.loops && open >= *af.unbounded_branches
                         : loops_in_given_box(a, b, box, *out.box_exits, closed, af, out.topology,
                                              why))) {
    tracer_fault = true;
    if (why.empty())
      why = "traced " + std::to_string(closed) + " closed and " + std::to_string(open) +
            " open branch(es) in the box; the certified affine topology has " +
            std::to_string(*af.loops) + " loop(s) and " + std::to_string(*af.unbounded_branches) +
            " unbounded branch(es)";
  } else if (open_off_face > 0) {
    tracer_fault = true;
    why = std::to_string(open_off_face) + " open branch(es) do not end on the box's faces";
  } else if (!out.box_exits->certified) {
    why = "the crossings with the box's faces are not certified: " + out.box_exits->reason;
  } else if (const int want =
                 exact_inside ? static_cast<int>(exact_inside->size()) : *af.isolated_points;
             static_cast<int>(out.isolated_points.size()) != want) {
    why = std::to_string(out.isolated_points.size()) + " isolated point(s) drawn in the box; " +
          std::to_string(want) + " lie in it";
  } else {
    why = match_exits(out.branches, *out.box_exits, picture_tolerance(box, 1e-7));
    tracer_fault = !why.empty();
  }
  out.matches_topology = why.empty();
  out.status = why.empty() ? Status::Certified : Status::Undecided;
  out.note = why;
  return tracer_fault;
}

// Degenerate pencils whose affine curve is made of lines: a plane section (a plane along a
// cylinder's rulings or through a cone's apex, equal parallel cylinders, two planes), two
// cones with a common apex, or two cylinders along one direction: the lines in closed form
// from exact data, clipped to the box, checked like any box.
bool trace_section_lines(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                         CurveResult& out, const TraceOptions& opt) {
  const certify::AffineTopology& af = out.affine;
  if (!af.certified()) return false;
  std::optional<SectionComponents> sec;
  if (af.ruling) {
    // Parallel cylinders: the lines from their base points along the common ruling (a plane
    // pair of their pencil, when one is kept, serves the box's crossings only).
    sec.emplace();
    Point3 d;
    for (size_t k = 0; k < 3; ++k)
      d[k] = (*af.ruling)[k].to_double_approx();
    for (const auto& l : af.ruling_lines)
      sec->lines.push_back({l.approx, d});
  } else if (af.plane && af.section_of) {
    sec = section_lines(*af.plane, *af.section_of);
    if (sec && af.plane2) { // route plane_pair: the second plane's section too
      const auto sec2 = section_lines(*af.plane2, *af.section_of);
      if (!sec2) return false;
      sec->lines.insert(sec->lines.end(), sec2->lines.begin(), sec2->lines.end());
      sec->points.insert(sec->points.end(), sec2->points.begin(), sec2->points.end());
    }
  } else if (af.apex) {
    // Lines from the common apex along the exact points at infinity (directions rounded).
    sec.emplace();
    Point3 p;
    for (size_t k = 0; k < 3; ++k)
      p[k] = (*af.apex)[k].to_double_approx();
    for (const auto& d : af.points_at_infinity)
      sec->lines.push_back({p, d.approx});
    if (sec->lines.empty()) sec->points.push_back(p);
  }
  if (!sec) return false;
  std::vector<Point3> sizing = sec->points;
  for (const auto& [p, d] : sec->lines)
    sizing.push_back(p);
  // Special points of the degenerate pencil are not computed: the box holds the lines'
  // base points (their crossing point, or their points nearest the plane's base point).
  Box box = opt.box ? *opt.box : box_around(sizing);
  auto trace_at = [&](const Box& in) {
    out.branches.clear();
    out.isolated_points = sec->points;
    for (const auto& [p, d] : sec->lines)
      if (auto br = line_in_box(p, d, in)) out.branches.push_back(std::move(*br));
  };
  trace_at(box);
  out.box_automatic = !opt.box;
  settle_box(a, b, QuadricPair(a, b), out, box, !opt.box, trace_at, true);
  return true;
}

// A twisted cubic and a line (cases 10-12): both from their exact parametrisations
// (certify/cubic_line.hpp), never marched: the line in closed form, the cubic's arcs sampled
// from its rational parametrisation, clipped to the box and checked like any box (the
// automatic box holds the special points, the line's point nearest the origin and a point of
// every arc of the cubic, doubled while it shows fewer open pieces than unbounded branches).
void trace_cubic_line(const core::QuadricMatrix& a, const core::QuadricMatrix& b, CurveResult& out,
                      const TraceOptions& opt) {
  const QsicResult& t = out.topology;
  const certify::AffineTopology& af = out.affine;
  const certify::CubicAndLine cl =
      af.cubic_line ? *af.cubic_line : certify::cubic_and_line(a.matrix(), b.matrix());
  if (!cl.found) {
    out.status = Status::Undecided;
    out.note = "the twisted cubic and the line were not found exactly: " + cl.reason;
    return;
  }
  std::vector<V> sizing;
  const std::vector<Point3> singular = split_special_points(t, out.isolated_points);
  sizing = out.isolated_points;
  sizing.insert(sizing.end(), singular.begin(), singular.end());
  Point3 lp{}, ld{};
  if (!cl.line_at_infinity) {
    double dd = 0, pd = 0;
    for (size_t k = 0; k < 3; ++k) {
      lp[k] = cl.line_point[k].to_double_approx();
      ld[k] = cl.line_direction[k].to_double_approx();
      dd += ld[k] * ld[k];
      pd += lp[k] * ld[k];
    }
    V near = lp;
    for (size_t k = 0; k < 3; ++k)
      near[k] -= pd / dd * ld[k];
    sizing.push_back(near);
  }
  for (const auto& p : cubic_arc_points(cl))
    sizing.push_back(p);
  auto trace_at = [&](const Box& in) {
    out.branches.clear();
    if (!cl.line_at_infinity)
      if (auto br = line_in_box(lp, ld, in)) out.branches.push_back(std::move(*br));
    for (auto& br : cubic_in_box(cl, in, opt.tolerance * opt.chord_scale * in.diagonal(),
                                 opt.max_points_per_branch))
      out.branches.push_back(std::move(br));
  };
  out.box_automatic = !opt.box;
  Box box = opt.box ? *opt.box : box_around(sizing);
  for (int attempt = 0; attempt <= kMaxBoxDoublings; ++attempt) {
    trace_at(box);
    if (opt.box || !af.unbounded_branches ||
        static_cast<int>(out.branches.size()) >= *af.unbounded_branches)
      break;
    for (size_t k = 0; k < 3; ++k) {
      const double c = 0.5 * (box.min[k] + box.max[k]), h = box.max[k] - box.min[k];
      box.min[k] = c - h;
      box.max[k] = c + h;
    }
  }
  settle_box(a, b, QuadricPair(a, b), out, box, !opt.box, trace_at, t.special_points_complete);
}

// Non-ellipsoid pairs: the curve inside a box, checked against the affine topology. With
// `section` (a degenerate pencil whose curve is one plane's proper conic, as a plane across a
// parabolic cylinder's rulings: no morphology) the conic is that plane's section of the
// other quadric; otherwise the conics come from the pencil's singular members.
void trace_in_box(const core::QuadricMatrix& a, const core::QuadricMatrix& b, CurveResult& out,
                  const TraceOptions& opt,
                  const std::optional<std::pair<core::Mat4, core::Mat4>>& section = std::nullopt) {
  const QsicResult& t = out.topology;
  const certify::AffineTopology& af = out.affine;
  if (!section && t.morphology->cubics > 0) {
    trace_cubic_line(a, b, out, opt);
    return;
  }
  const auto exact_lines_found = section ? std::nullopt : exact_lines(t, af);
  auto conic_branches_at = [&](const TraceOptions& o) {
    if (section) return section_branches(section->first, core::QuadricMatrix(section->second), o);
    std::vector<Branch> brs;
    auto draw_line = [&o, &brs](const Point3& p, const Point3& d) {
      if (o.box) {
        if (auto br = line_in_box(p, d, *o.box)) brs.push_back(std::move(*br));
      } else { // for the sizing: the point nearest the origin in the middle
        Branch br;
        br.kind = "line";
        br.closed = false;
        for (double u : {-1.0, 0.0, 1.0})
          br.points.push_back({p[0] + u * d[0], p[1] + u * d[1], p[2] + u * d[2]});
        brs.push_back(std::move(br));
      }
    };
    // Lines only, each found exactly (a real double line too, which neither the singular
    // members' planes nor the diametral planes below give): drawn from the exact lines, the
    // ones curve_exits reads.
    if (exact_lines_found) {
      for (const auto& l : *exact_lines_found) {
        Point3 p{}, d{};
        for (size_t k = 0; k < 3; ++k) {
          p[k] = l.point[k].to_double_approx();
          d[k] = l.direction[k].to_double_approx();
        }
        const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(n > 0) || !std::isfinite(n)) continue;
        draw_line(p, {d[0] / n, d[1] / n, d[2] / n});
      }
      return brs;
    }
    brs = conic_branches(a, b, t.facts, o, section_kinds(t, af));
    // A plane of a singular member tangent to a quadric meets it in one real point (the
    // crossing of two imaginary lines); in doubles that section comes out as a closed "conic"
    // of no size there. It is no branch: dropped when it sits on an exact special or isolated
    // point (the certified topology judges the rest; a conic_with_tangency_point pencil in a
    // box drew its tangency point as a loop: generate --case 27 --seed 38 pair 9, undecided).
    brs.erase(std::remove_if(brs.begin(), brs.end(),
                             [&](const Branch& br) {
                               if (!br.closed || br.points.empty()) return false;
                               const Point3& c = br.points.front();
                               const double scale =
                                   1 + std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
                               if (!(diameter(br) <= 1e-9 * scale)) return false;
                               auto near = [&](const Point3& x) {
                                 double d = 0;
                                 for (size_t k = 0; k < 3; ++k)
                                   d = std::max(d, std::fabs(x[k] - c[k]));
                                 return d <= 1e-9 * scale;
                               };
                               for (const auto& sp : t.special_points)
                                 if (!sp.at_infinity && near(sp.approx)) return true;
                               return std::any_of(out.isolated_points.begin(),
                                                  out.isolated_points.end(), near);
                             }),
              brs.end());
    // Lines only, none drawn from the singular members (two real skew lines from a complex
    // conjugate pair of members, a real double line): each real point at infinity is the
    // direction of one real line (affine.cpp), the line through it found on both surfaces.
    if (brs.empty() && lines_only(t) && af.certified())
      for (const auto& pi : af.points_at_infinity)
        if (const auto ln = line_in_direction(a, b, pi.approx)) draw_line(ln->first, ln->second);
    return brs;
  };
  QuadricPair q(a, b);
  std::vector<Point3> singular = split_special_points(t, out.isolated_points);
  const bool curve_by_conics =
      section || t.morphology->conics > 0 || t.morphology->lines > 0 || t.morphology->cubics > 0;
  std::vector<Branch> conics;
  std::vector<V> sizing = out.isolated_points;
  sizing.insert(sizing.end(), singular.begin(), singular.end());
  // The points march() never starts a walk at: the singular points it passes through and the
  // isolated points (an acnode attracts Gauss-Newton from the seeds near it; a walk started
  // there, on the rounded coefficients, circles a loop of rounding noise and ends off the
  // box's faces: pairs 4 of --seed 6, 94 and 101 of --seed 8).
  std::vector<V> stops = singular;
  stops.insert(stops.end(), out.isolated_points.begin(), out.isolated_points.end());
  std::vector<V> starts;
  // No loop and no unbounded branch (certified): the affine curve is its isolated points, if
  // any. Nothing is walked: on the rounded pair a walk seeded near an acnode circles a loop of
  // rounding noise and ends off the faces (undecided: generate --case 30 --seed 50 pair 1, case 7
  // --encoding double pair 18), and a picture of points needs no walk.
  const bool points_only = af.certified() && *af.loops == 0 && *af.unbounded_branches == 0;
  if (curve_by_conics && !points_only) {
    conics = conic_branches_at(opt);
    for (const auto& br : conics) {
      if (br.closed)
        sizing.insert(sizing.end(), br.points.begin(), br.points.end());
      else if (!br.points.empty())
        sizing.push_back(br.points[br.points.size() / 2]); // the vertex of the sampled range
    }
  }
  // Closed loops traced whole, so that the automatic box contains them. A walk on an unbounded
  // branch runs until it is 100 scene sizes out (5,000 points, then dropped: 90% of a random
  // cone pair's time), so the walks first stop 4 scene sizes out, and go the whole way only
  // when that misses a certified loop. Not when the number of loops is not known yet (points at
  // infinity shared among ovals in several ways, settled later by settle_by_traced_loops):
  // every compact loop stays within a scene size of its extreme points, so the far walks only
  // drew unbounded branches, to be dropped (5,000 points each: 4-10 ms of a cone pair posed in
  // doubles).
  auto size_by_loops = [&]() {
    TraceOptions near = opt;
    near.escape_scenes = 4;
    std::vector<Branch> found = march(q, starts, stops, near);
    const auto closed =
        std::count_if(found.begin(), found.end(), [](const Branch& br) { return br.closed; });
    if (af.loops && closed < *af.loops) found = march(q, starts, stops, opt);
    for (const auto& br : found)
      if (br.closed) sizing.insert(sizing.end(), br.points.begin(), br.points.end());
  };
  // With the number of loops certified, the box is first placed without them (around the
  // start points: each loop's extreme points along one direction, with the box's margin of
  // half its size on every side) and the loops traced once, in it; only when it does not show
  // them all closed are they traced first, the box placed around them and the curve traced
  // again, as always before (the loops were traced twice: ~13% of the bench's pairs' time).
  const bool lazy_loops = !opt.box && !curve_by_conics && af.loops && *af.loops > 0;
  if (!curve_by_conics && !points_only) {
    starts = extreme_points_float(q);
    sizing.insert(sizing.end(), starts.begin(), starts.end());
    if (!opt.box && !(af.loops && *af.loops == 0) && !lazy_loops) size_by_loops();
  }
  // Curve points near the origin (Gauss-Newton from a few seeds): a piece of an unbounded
  // branch without a critical point still gets into the automatic box. (Conics and lines
  // have their vertices and crossing points in it already.)
  for (double r : {0.0, 1.0, 10.0})
    if (!curve_by_conics && !points_only)
      for (size_t k = 0; k < 3; ++k)
        for (double sg : {1.0, -1.0}) {
          V p{0, 0, 0};
          p[k] = sg * r;
          if (project_onto_curve(q, p)) sizing.push_back(p);
          if (r == 0) break;
        }
  out.box_automatic = !opt.box;
  Box box = opt.box ? *opt.box : box_around(sizing);
  // The open pieces the picture shows crossing the box: half the distinct points where open
  // pieces end on its faces. A walk that died inside ends off the faces, and a walk that jumped
  // from one branch to another (steps of ~170 in a box 3,000 wide) ends on crossings that
  // other pieces end on too: counted as pieces, they stopped the doubling below one step
  // short of an arc running 4,700 out (generate --case 9 --seed 45 pair 8).
  auto count_open = [&] {
    const double eps = picture_tolerance(box, 1e-7);
    std::vector<Point3> ends;
    for (const auto& br : out.branches) {
      if (br.closed || br.points.size() < 2) continue;
      for (const Point3* e : {&br.points.front(), &br.points.back()}) {
        if (!on_face(box, *e, eps)) continue;
        const bool seen = std::any_of(ends.begin(), ends.end(), [&](const Point3& x) {
          return std::fabs(x[0] - (*e)[0]) + std::fabs(x[1] - (*e)[1]) +
                     std::fabs(x[2] - (*e)[2]) <=
                 eps;
        });
        if (!seen) ends.push_back(*e);
      }
    }
    return static_cast<int>(ends.size() / 2);
  };
  // An automatic box is doubled (kMaxBoxDoublings) while count_open() is short of the
  // certified number of unbounded branches.
  const bool all_closed =
      curve_by_conics && !conics.empty() &&
      std::all_of(conics.begin(), conics.end(), [](const Branch& br) { return br.closed; });
  TraceOptions topt = opt; // its tolerance is refined below when the picture does not match
  bool exact_starts_allowed = !lazy_loops;
  auto trace_at = [&](const Box& in) {
    TraceOptions bopt = topt;
    bopt.box = in;
    out.branches.clear();
    if (points_only) return;
    if (curve_by_conics) {
      // Open conics sampled far enough to leave this box. (Closed ones do not depend on the
      // box: the conics sampled for the sizing are reused when all are closed.)
      if (!all_closed) conics = conic_branches_at(bopt);
      for (const auto& br : conics)
        for (auto& piece : br.closed ? clip_closed_to_box(q, br, in) : clip_to_box(q, br, in))
          out.branches.push_back(std::move(piece));
    } else {
      int unresolved = 0; // walks of the last run that stopped on the noise test
      auto run = [&](std::vector<V> st) {
        const auto faces = box_face_points(q, in);
        st.insert(st.end(), faces.begin(), faces.end());
        // Retraced in the same box: the exact crossings with its faces start walks too. The
        // float face points come from a quartic's roots in doubles, where two crossings of
        // arms sharing a point at infinity lie close together on a far face (a near-double
        // root, dropped as complex): a given box 3e4 across missed arms that only start there.
        if (out.box_exits && out.box_exits->certified && out.box && out.box->min == in.min &&
            out.box->max == in.max)
          for (const auto& x : out.box_exits->points) {
            V p = x.approx;
            const auto k = static_cast<size_t>(x.axis);
            p[k] = x.at_max ? in.max[k] : in.min[k];
            st.push_back(p);
          }
        return march(q, st, stops, bopt, &unresolved);
      };
      out.branches = run(starts);
      auto count_closed = [&out] {
        return static_cast<int>(std::count_if(out.branches.begin(), out.branches.end(),
                                              [](const Branch& br) { return br.closed; }));
      };
      int closed = count_closed();
      // Walks that stopped where the rounded pair cannot tell two pieces of curve apart (the
      // neck of two pipes posed in doubles) are not missing a start: the pair evaluated on its
      // exact coefficients in double-double passes there (as settle_box's retry below would,
      // after the exact extreme points had been computed and walked in vain: 3 of the bench's
      // 20 Steinmetz pairs posed in doubles, ~3 ms each).
      if (af.loops && closed != *af.loops && unresolved > 0 && !q.refined_form)
        if (auto r = q.refined(a, b)) {
          q = std::move(*r);
          out.branches = run(starts);
          closed = count_closed();
        }
      // The float extreme points may miss a small loop: the exact ones then (not while the
      // box is placed without the loops: a loop it cuts first moves the box).
      if (exact_starts_allowed && af.loops && closed != *af.loops) {
        out.branches = run(extreme_points(a, b));
        out.exact_start_points = true;
      }
    }
  };
  // When no doubling shows every branch crossing, the box is placed once more around the
  // sizing points without the outliers (farther from their coordinate-wise median than 1000
  // times their median distance from it) and left to settle_box's finer retraces: float extreme
  // points of two branches running out side by side 2 apart towards a crunode at infinity lay
  // 1.8e7 out, where walks started from them cannot tell the branches apart, and the doublings
  // only made the steps longer (generate --case 5 --seed 46 pair 18 in doubles: a box 5e7
  // across doubled 12 times, undecided; certified in given boxes 20 to 2e5 across). Floats:
  // only the picture's frame; the exact crossings and the topology judge it.
  bool placed_without_outliers = false;
  auto place = [&]() {
    for (int attempt = 0; attempt <= kMaxBoxDoublings; ++attempt) {
      trace_at(box);
      if (opt.box || !af.unbounded_branches || count_open() >= *af.unbounded_branches) return;
      if (attempt == kMaxBoxDoublings) break;
      for (size_t k = 0; k < 3; ++k) {
        const double c = 0.5 * (box.min[k] + box.max[k]), h = box.max[k] - box.min[k];
        box.min[k] = c - h;
        box.max[k] = c + h;
      }
    }
    const std::vector<V> inner = without_outliers(sizing);
    if (inner.size() < sizing.size()) {
      box = box_around(inner);
      trace_at(box);
      placed_without_outliers = true;
    }
  };
  place();
  if (lazy_loops) {
    exact_starts_allowed = true;
    const auto closed = std::count_if(out.branches.begin(), out.branches.end(),
                                      [](const Branch& br) { return br.closed; });
    if (closed != *af.loops) { // the loops first, then the box around them, as before
      size_by_loops();
      box = box_around(sizing);
      place();
    }
  }
  // The exact crossings with the faces; an automatic box whose faces meet the curve
  // non-generically (on an edge, tangentially) is widened a little, unevenly, and retraced.
  bool retry = settle_box(a, b, q, out, box, !opt.box, trace_at, t.special_points_complete);
  // A picture that does not match is traced again on the exact coefficients first, evaluated in
  // double-double (QuadricPair::refined): where two pieces of curve pass within ~1e-8 of each
  // other (the neck of two pipes rounded to doubles, offset pipes 2^-30 from tangency) the
  // rounding of the coefficients, or of the long double evaluation of a pair posed in doubles,
  // moves the curve by about that much, and the walk stops there rather than guess which way
  // it runs (noise_radius against the gap). Several times the cost of a walk's evaluations:
  // only here, once the plain picture failed.
  if (retry && !q.refined_form)
    if (auto r = q.refined(a, b)) {
      q = std::move(*r);
      trace_at(box);
      retry = settle_box(a, b, q, out, box, !opt.box, trace_at, t.special_points_complete);
    }
  // A traced picture that does not match is traced again with the tolerance divided by 8
  // (twice at most): the step is bounded by 200 times the tolerance, relative to the scene
  // (the box), and where the box is large against the gaps between pieces of curve (an
  // automatic box holding a loop 200 across, around two pieces 0.9 apart: pair 139 of
  // natural_box_pairs.py --seed 6) a long step from one smooth, nearly straight stretch lands
  // on another piece running the same way, which neither end of the step can see. The exact
  // crossings and the topology stay the judges; only the float picture is redone. Conics too:
  // sampled more finely, a piece's cut onto a face (Newton from the last sample inside) that
  // failed from a sample far off the face may succeed (two parabolas posed at 2^-7 scale).
  // Then once more with the chords alone 64 times finer (the steps' bound kept): in a given box
  // of 3e4 around a figure eight of unit size, the tolerance divided by 64 is still ~0.1 unit,
  // and walks on other components passing the crunode within the step ahead still glued
  // themselves to it (too many arms), or walks joined pieces a unit apart; 8 of 12 such
  // undecided pictures of 1480 random given boxes are certified at the third refinement.
  // A fourth, the chords 4096 times finer: two branches twisting around each other within
  // 0.05-0.4 next to an acnode, in a given box 24,000 wide, were still joined across by a walk
  // at 1/64 (three pieces on four crossings; generate --case 6 --seed 36 pair 4, boxed). Only
  // failed pictures pay it; the steps stay long where the curve is straight.
  // "tolerance" reports the chord bound the picture was drawn with.
  // Not after a walk hit max_points_per_branch: finer chords only shorten its steps, and it
  // stops at the cap again (a cusp at infinity whose half-branches run together in a given box
  // 20,000 wide: five walks of up to 200,000 points per picture, 11 s for four refinements
  // that all ended as the first; generate --case 9 --seed 46 pair 6, boxed).
  auto capped = [&]() {
    return std::any_of(out.branches.begin(), out.branches.end(), [&](const Branch& br) {
      return static_cast<long>(br.points.size()) >= topt.max_points_per_branch;
    });
  };
  auto refine_until_settled = [&]() {
    for (int refine = 0; refine < 4 && retry && !capped(); ++refine) {
      if (refine < 2)
        topt.tolerance /= 8;
      else
        topt.chord_scale = refine == 2 ? 1.0 / 64 : 1.0 / 4096;
      trace_at(box);
      retry = settle_box(a, b, q, out, box, !opt.box, trace_at, t.special_points_complete);
      out.tolerance = topt.tolerance * topt.chord_scale;
    }
  };
  refine_until_settled();
  // Still no match in an automatic box that far outliers of the sizing points widened (float
  // extreme points 1e7 out next to an acnode at infinity, where walks started from them drew
  // pieces of rounding noise: generate --case 6 --seed 54 pair 10 in doubles): the box is
  // placed once more around the points without them (unless place() did already) and the
  // picture traced and refined again from the tolerance asked.
  if (retry && !opt.box && !placed_without_outliers) {
    const std::vector<V> inner = without_outliers(sizing);
    if (inner.size() < sizing.size()) {
      box = box_around(inner);
      topt.tolerance = opt.tolerance;
      topt.chord_scale = opt.chord_scale;
      trace_at(box);
      retry = settle_box(a, b, q, out, box, true, trace_at, t.special_points_complete);
      out.tolerance = topt.tolerance * topt.chord_scale;
      refine_until_settled();
    }
  }
  if (retry && out.status != Status::Certified && capped())
    out.note += " (a walk stopped at the " + std::to_string(topt.max_points_per_branch) +
                "-point cap: not refined further)";
}

} // namespace

CurveResult intersect_curve(const core::QuadricMatrix& a, const core::QuadricMatrix& b, Mode mode,
                            const TraceOptions& opt, certify::Detail detail) {
  QsicResult t = classify_qsic(a, b, mode == Mode::Float ? Mode::Filtered : mode);
  complete_report_data(t, a, b, detail);
  return trace_curve(a, b, std::move(t), opt);
}

namespace {

// Moves each coordinate of the centre c of a translation, for a pair of shapes posed in doubles,
// into the range where every shape's centre minus c is again exactly a double (|x - c| <=
// 2^ilogb(x) for a centre coordinate x, c a multiple of x's ulp): the translated shapes then
// stay lazy (QuadricMatrix::translated), and the exact matrices of double quaternions (hundreds
// of digits) are never formed: on random unit-size ellipsoid pairs, where a small ellipsoid half
// a unit out counts as far, that was 23% of an intersect. Where both shapes lie far out in a
// coordinate (the case the translation is for) the range holds the least-squares centre and
// nothing moves; a coordinate clamped towards a centre near the origin moves less, and the pair
// is traced that much nearer its original place (translated() checks the exactness anyway).
void keep_shapes_lazy(const core::QuadricMatrix& a, const core::QuadricMatrix& b, Point3& c) {
  const core::ShapeSpec* sa = a.shape();
  const core::ShapeSpec* sb = b.shape();
  if (!sa || !sb) return;
  for (size_t k = 0; k < 3; ++k) {
    double lo = -std::numeric_limits<double>::infinity(), hi = -lo, grid = 0;
    for (const core::ShapeSpec* s : {sa, sb}) {
      const double x = s->center[k];
      if (x == 0 || !std::isfinite(x)) continue;
      const double reach = std::ldexp(1.0, std::ilogb(x));
      lo = std::max(lo, x - reach);
      hi = std::min(hi, x + reach);
      grid = std::max(grid, ulp_of(x));
    }
    if (!(grid > 0)) continue;
    if (!(lo <= hi)) { // no common range: no translation in this coordinate
      c[k] = 0;
      continue;
    }
    // Inside [lo, hi], on the coarser grid (an end of the range on the finer grid of the other
    // centre may leave c off it: then translated() forms the exact congruence, as before).
    double y = std::clamp(c[k], lo, hi);
    y = std::nearbyint(y / grid) * grid;
    c[k] = std::clamp(y, lo, hi);
  }
}

// A point near which the curve lives, when the pair lies far from the origin relative to its
// size; nullopt otherwise: the point nearest (least squares, minimum norm) to the centres of
// both quadrics (A c = -b: a sphere's centre, a cylinder's axis, a cone's apex), far when its
// distance from the origin exceeds 4 times the smaller positive size of the quadrics there
// (sqrt(|f(c)| / max |eigenvalue|): a sphere's radius). The tracer's double computations
// (plane pairs from eigenvectors of singular members, conic centres, start points, step
// bounds) lose the curve's digits to a large translation (a quartic loop 14 sizes off the
// origin was lost); they run on the exactly translated pair instead.
std::optional<Point3> far_centre(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                 bool size_checks = true) {
  // Normal equations sum_q (A_q^T A_q) c = -sum_q A_q^T b_q, each quadric scaled to max
  // |A_q| = 1.
  algebra::Mat4d n{};
  Point3 rhs{0, 0, 0};
  std::array<algebra::Mat4d, 2> ms{certify::approx(a), certify::approx(b)};
  std::array<double, 2> norms{0, 0}; // the divisor of each (0: a plane, not divided)
  for (size_t q = 0; q < 2; ++q) {
    auto& m = ms[q];
    double s = 0;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        s = std::max(s, std::fabs(m[i][j]));
    if (!(s > 0) || !std::isfinite(s)) continue; // a plane: no centre
    norms[q] = s;
    for (auto& row : m)
      for (double& x : row)
        x /= s;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        for (size_t k = 0; k < 3; ++k)
          n[i][j] += m[k][i] * m[k][j];
        rhs[i] -= m[j][i] * m[j][3];
      }
  }
  std::array<double, 4> w{};
  algebra::Mat4d v{};
  algebra::jacobi4(n, w, v);
  double lmax = 0;
  for (double x : w)
    lmax = std::max(lmax, std::fabs(x));
  if (!(lmax > 0) || !std::isfinite(lmax)) return std::nullopt;
  Point3 c{0, 0, 0};
  for (size_t k = 0; k < 4; ++k) {
    if (!(std::fabs(w[k]) > 1e-12 * lmax)) continue;
    double vb = 0;
    for (size_t i = 0; i < 3; ++i)
      vb += v[i][k] * rhs[i];
    for (size_t i = 0; i < 3; ++i)
      c[i] += vb / w[k] * v[i][k];
  }
  if (!std::isfinite(c[0] + c[1] + c[2])) return std::nullopt;
  if (!size_checks) return c; // the least-squares centre alone (a cone's apex, say)
  const double far = std::max({std::fabs(c[0]), std::fabs(c[1]), std::fabs(c[2])});
  double size = 0;
  const std::array<const core::QuadricMatrix*, 2> qs{&a, &b};
  for (size_t q = 0; q < 2; ++q) {
    const auto& m = ms[q];
    double lq = 0, f = m[3][3];
    for (size_t i = 0; i < 3; ++i) {
      f += 2 * m[i][3] * c[i];
      for (size_t j = 0; j < 3; ++j) {
        f += c[i] * m[i][j] * c[j];
        lq = std::max(lq, std::fabs(m[i][j]));
      }
    }
    // f(c) carries a rounding error ~1e-16 |c|^2: sizes below 1e-6 |c| can be a cone's 0.
    double sq = lq > 0 ? std::sqrt(std::fabs(f) / lq) : 0;
    if (lq > 0 && !(sq > 1e-6 * far) && norms[q] > 0) {
      // Then f(c) exactly, on the exact quadric (a unit pipe 2^20 out has size 1 = 1e-6 |c|:
      // read as a cone, it was not translated, and its curves were lost in the doubles). A
      // cone's apex rounded into c leaves |c - apex| ~ 1e-16 |c|: sizes below 1e-12 |c| stay 0.
      const std::array<core::Rational, 4> x{
          core::Rational::exact_from_double(c[0]), core::Rational::exact_from_double(c[1]),
          core::Rational::exact_from_double(c[2]), core::Rational(1)};
      const double fe = algebra::bilinear(qs[q]->matrix(), x, x).to_double_approx() / norms[q];
      sq = std::sqrt(std::fabs(fe) / lq);
      if (!(sq > 1e-12 * far)) sq = 0;
    } else if (!(sq > 1e-6 * far)) {
      sq = 0;
    }
    if (sq > 0 && (size == 0 || sq < size)) size = sq; // the smaller (a saddle's is inflated)
  }
  if (!(size > 0) || !(far > 4 * size)) return std::nullopt; // size 0: cones and planes only
  // Rounded to a multiple of a power of two near size * 2^-24: shorter dyadic rationals for
  // the translated pair's exact classification. (Coarser, size / 16, made the tracer lose
  // loops of cone pairs: it does better with a centre or apex at the origin.)
  const double unit = std::ldexp(1.0, std::ilogb(size) - 24);
  for (double& x : c)
    x = std::nearbyint(x / unit) * unit;
  keep_shapes_lazy(a, b, c);
  if (!(std::max({std::fabs(c[0]), std::fabs(c[1]), std::fabs(c[2])}) > 4 * size))
    return std::nullopt; // kept near the origin: traced where it is
  return c;
}

// The exponent k of the power of two 2^k the pair is traced at unit size in (see
// trace_curve), when its features lie beyond 2^+-8 (256); nullopt otherwise. Most of the
// tracer's steps, tolerances and Newton tests are relative, but not all (the smallest step has
// an absolute floor ~1e-14; seeds sit at distances 1 and 10), and its double products (x^2 at
// 1e-200, the coefficients 1/r^2 at 1e-160) leave the double range long before the input does:
// offset pipes scaled by 2^+-40 were undecided (30 of 85 scaled pairs of an audit, now
// certified with the unit pair's counts).
std::optional<int> extreme_order(const core::QuadricMatrix& a, const core::QuadricMatrix& b) {
  const auto la = core::length_order(a), lb = core::length_order(b);
  if (!la && !lb) return std::nullopt;
  const long k = std::max(la.value_or(LONG_MIN), lb.value_or(LONG_MIN));
  if (k >= -8 && k <= 8) return std::nullopt;
  return static_cast<int>(std::clamp(k, -100000L, 100000L));
}

// A result traced on a moved copy of the pair (translated or rescaled) whose box is reported
// for the original pair: the box's exact crossings recomputed on the original pair and matched
// again with the traced ends (the claim is about the box reported).
// When the moved copy's verdict stopped at its own box crossings (its box's faces rounded
// onto a tangency, say: helper-27's face 2^-100 above a point where the curve touches y = 0,
// moved by a translation), the checks that follow settle_box's are made again on the original
// pair's crossings; otherwise an answer could carry certified `exits` beside a note saying
// they are not.
void rematch_exits(const core::QuadricMatrix& a, const core::QuadricMatrix& b, CurveResult& local) {
  const std::string exits_note = "the crossings with the box's faces are not certified: ";
  const bool stopped_at_exits = local.status != Status::Certified && local.box_exits &&
                                !local.box_exits->certified &&
                                local.note == exits_note + local.box_exits->reason;
  local.box_exits = curve_exits(a, b, local.affine, *local.box, local.topology);
  if (local.status != Status::Certified && !stopped_at_exits) return;
  std::string why;
  if (!local.box_exits->certified)
    why = exits_note + local.box_exits->reason;
  else if (local.affine.isolated_points) {
    // Decided exactly in the box reported, when the special points allow it (as in settle_box).
    const auto in = isolated_in_box(local.topology, local.affine, *local.box);
    if (in) local.isolated_points = *in;
    const int want = in ? static_cast<int>(in->size()) : *local.affine.isolated_points;
    if (static_cast<int>(local.isolated_points.size()) != want)
      why = std::to_string(local.isolated_points.size()) + " isolated point(s) drawn in the box; " +
            std::to_string(want) + " lie in it";
  }
  if (why.empty() && local.box_exits->certified)
    why = match_exits(local.branches, *local.box_exits, picture_tolerance(*local.box, 1e-7));
  local.matches_topology = why.empty();
  local.status = why.empty() ? Status::Certified : Status::Undecided;
  local.note = why;
}

// Two checks of a certified picture against what it must be, whatever route drew it: (1) no
// branch drawn as a straight line when the certified affine reading has no line (a plane
// passing a cone's apex by 1e-10 at |apex| ~ 1: its hyperbola's centre value fell below a float
// threshold and the section was drawn as its two asymptotes, each crossing from one branch of
// the hyperbola to the other, matched to the exact box exits and certified); (2) every point
// traced point within 1e-9 of the curve's own size (plus 16 ulps of the coordinates) of both
// surfaces (isolated points are exact points rounded, not checked here): the
// check against the box's diagonal passed a circle 0.25 off a paraboloid in a box 3.7e9 wide,
// and a loop of radius 2^-100 drawn 4e-6 wide. A failed check makes the answer undecided.
void check_picture(CurveResult& out) {
  if (out.status != Status::Certified) return;
  std::string why;
  if (out.affine.lines && *out.affine.lines == 0)
    for (const auto& br : out.branches)
      if (br.kind == "line") {
        why = "a branch was drawn as a straight line where the certified affine topology has no "
              "line (a conic within the doubles' reach of a line pair)";
        break;
      }
  if (why.empty()) {
    double big = 0;
    const double size = points_size(out, false, &big);
    const double bound = 1e-9 * size + 16 * ulp_of(big) + 0x1p-1070;
    if (!(out.branch_residual <= bound)) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "traced points lie up to %.3g off the surfaces, more than 1e-9 of the "
                    "curve's size (%.3g) and the doubles' spacing there",
                    out.branch_residual, size);
      why = buf;
    }
  }
  if (why.empty()) return;
  out.status = Status::Undecided;
  out.matches_topology = false;
  out.note = why;
}

void trace_here(const core::QuadricMatrix& a, const core::QuadricMatrix& b, CurveResult& out,
                const TraceOptions& opt);

// The centre of the quadric s (least squares, minimum norm: a cone's apex, a sphere's centre,
// the point of a cylinder's axis nearest the origin) to double precision (an apex 12345.678
// out rounded to a grid of 2^-40 of its distance stayed 1e-8 off the origin, too far for a
// neck of 1e-20); nullopt for a plane or a centre at the origin. Not moved to keep a pair of
// double-posed shapes lazy (as far_centre does): that put a cone's apex up to ~1 off the origin,
// and only the retry of an undecided pair pays for the exact matrices.
std::optional<Point3> own_centre(const core::QuadricMatrix& s) {
  std::optional<Point3> c;
  // A central quadric's centre -A^-1 b exactly (Cramer's rule over Q), then rounded: the
  // least-squares one in double is off by ~1e-16 of its distance, which leaves a neck of 2^-100
  // next to an apex at |c| ~ 1 unresolved.
  const auto& m = s.matrix();
  auto det3 = [&m](size_t col, bool replace) {
    // det of the 3x3 block with column col replaced by -b when replace
    auto e = [&](size_t i, size_t j) { return replace && j == col ? -m[i][3] : m[i][j]; };
    return e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1)) -
           e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0)) +
           e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0));
  };
  const core::Rational d = det3(0, false);
  if (!d.is_zero()) {
    c = Point3{};
    for (size_t k = 0; k < 3; ++k)
      (*c)[k] = (det3(k, true) / d).to_double_approx();
  } else {
    c = far_centre(s, s, false);
  }
  if (!c) return std::nullopt;
  const double far = std::max({std::fabs((*c)[0]), std::fabs((*c)[1]), std::fabs((*c)[2])});
  if (!(far > 0) || !std::isfinite(far)) return std::nullopt;
  return c;
}

// The affine reading of a pair carried to a copy moved by an exact translation or a scaling
// by a power of two: its counts and its points at infinity (directions) do not move; routes
// that hold coordinates (a plane, a section, an apex, a cubic and a line, exact lines) are read
// again.
const certify::AffineTopology* movable(const certify::AffineTopology& af) {
  const bool coordinates = af.plane || af.plane2 || af.section_of || af.apex || af.ruling ||
                           af.cubic_line || !af.exact_lines.empty();
  return coordinates ? nullptr : &af;
}

// x + y when that double sum is exact (TwoSum's error term is zero), else nullopt.
std::optional<double> exact_sum(double x, double y) {
  const double s = x + y, bb = s - x, err = (x - (s - bb)) + (y - bb);
  if (err != 0 || !std::isfinite(s)) return std::nullopt;
  return s;
}

// The pair traced at unit size: on the exact pair in the coordinates u = x / 2^k (its
// classification re-done there: the same certified answer), every point and the box scaled
// back by 2^k (exact, unless the result is subnormal: a rounding of at most 2^-1075 per
// coordinate, added to max_residual), the box's exact crossings recomputed on the original
// pair; topology and affine reading stay those of the original pair.
CurveResult trace_rescaled(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                           CurveResult out, const TraceOptions& opt, int k, int depth) {
  const auto a2 = a.rescaled(k), b2 = b.rescaled(k);
  TraceOptions o2 = opt;
  if (o2.box)
    for (size_t i = 0; i < 3; ++i) {
      o2.box->min[i] = std::ldexp(o2.box->min[i], -k);
      o2.box->max[i] = std::ldexp(o2.box->max[i], -k);
    }
  CurveResult local = trace_curve_at(a2, b2, classify_qsic(a2, b2, Mode::Filtered), o2, depth + 1,
                                     movable(out.affine));
  // Below the normal range: a curve (or a lone isolated point) whose size, scaled back, is
  // under DBL_MIN has subnormal coordinates (fewer than 53 significant bits, 14 at 2^-1060) or
  // none at all (a circle 1e-400 wide at 1e-400 from the origin came back as points [0, 0, 0]
  // with max_residual 0, certified). No picture: undecided, as beyond the range above.
  double big_unit = 0;
  const double size_unit = points_size(local, true, &big_unit);
  const double measure = std::ldexp(size_unit > 0 ? size_unit : big_unit, k);
  const bool has_points = !local.branches.empty() || !local.isolated_points.empty();
  if (has_points && measure < DBL_MIN) {
    if (local.status == Status::Certified) local.status = Status::Undecided;
    local.matches_topology = false;
    local.branches.clear();
    local.isolated_points.clear();
    local.box_exits.reset();
    local.box = opt.box;    // a box of its own would be subnormal too
    local.max_residual = 0; // no point returned
    local.branch_residual = 0;
    local.topology = std::move(out.topology);
    local.affine = std::move(out.affine);
    local.note = "the curve, traced at unit size, lies below the double range once scaled back "
                 "(its size under 2^-1022: its points would be subnormal or 0)";
    return local;
  }
  bool finite = true, subnormal = false, box_exact = true;
  auto back = [&](Point3& x) {
    for (size_t i = 0; i < 3; ++i) {
      const double unit = x[i];
      x[i] = std::ldexp(x[i], k);
      finite = finite && std::isfinite(x[i]);
      // Rounded on the subnormal grid, or flushed to 0 (an error of at most 2^-1075 either way).
      subnormal = subnormal || (unit != 0 && std::fabs(x[i]) < DBL_MIN);
    }
  };
  auto box_back = [&](Point3& x) {
    for (size_t i = 0; i < 3; ++i) {
      const double y = std::ldexp(x[i], k);
      box_exact = box_exact && std::isfinite(y) && std::ldexp(y, -k) == x[i];
      x[i] = y;
    }
    finite = finite && box_exact;
  };
  for (auto& br : local.branches)
    for (auto& x : br.points)
      back(x);
  for (auto& x : local.isolated_points)
    back(x);
  local.max_residual = std::ldexp(local.max_residual, k) + (subnormal ? 0x1p-1073 : 0.0);
  local.branch_residual = std::ldexp(local.branch_residual, k) + (subnormal ? 0x1p-1073 : 0.0);
  if (local.box) {
    box_back(local.box->min);
    box_back(local.box->max);
    if (opt.box) local.box = opt.box;
  }
  local.topology = std::move(out.topology);
  local.affine = std::move(out.affine);
  if (!finite) {
    local.status = Status::Undecided;
    local.matches_topology = false;
    local.branches.clear();
    local.box_exits.reset();
    local.box = opt.box; // the given box (finite), or none
    local.isolated_points.clear();
    local.max_residual = 0; // no point returned
    local.note = "the curve or its box, traced at unit size, lies beyond the double range once "
                 "scaled back";
    return local;
  }
  if (local.box_exits && local.box) {
    // The box scaled back exactly: its crossings are those of the scaled box, scaled back (a
    // rounded midpoint's error joins its radius). Else they are recomputed for the box
    // reported.
    if (box_exact) {
      for (auto& c : local.box_exits->points) {
        bool sub = false;
        for (size_t i = 0; i < 3; ++i) {
          c.approx[i] = std::ldexp(c.approx[i], k);
          sub = sub || (c.approx[i] != 0 && std::fabs(c.approx[i]) < DBL_MIN);
        }
        c.radius = std::ldexp(c.radius, k) + (sub ? 0x1p-1073 : 0.0);
      }
      return local;
    }
    rematch_exits(a, b, local);
  }
  return local;
}

} // namespace

namespace {

// Boxes proposed around one loop the tracer drew closed, for certify::proven_loops: its points'
// bounding box widened by 1/16, 1/4, then 1/64 of its largest extent, outwards to the grid of
// dyadic_outward (empty when the points are not finite or all equal). Floats only choose them.
std::vector<certify::RationalBox> loop_boxes(const std::vector<Point3>& points) {
  Box bb;
  bool finite = true;
  for (size_t k = 0; k < 3; ++k)
    bb.min[k] = HUGE_VAL, bb.max[k] = -HUGE_VAL;
  for (const auto& p : points)
    for (size_t k = 0; k < 3; ++k) {
      finite = finite && std::isfinite(p[k]);
      bb.min[k] = std::min(bb.min[k], p[k]);
      bb.max[k] = std::max(bb.max[k], p[k]);
    }
  double extent = 0;
  for (size_t k = 0; k < 3; ++k)
    extent = std::max(extent, bb.max[k] - bb.min[k]);
  std::vector<certify::RationalBox> boxes;
  if (!finite || !(extent > 0) || !std::isfinite(extent)) return boxes;
  for (double margin : {1.0 / 16, 1.0 / 4, 1.0 / 64}) {
    Box m = bb;
    for (size_t k = 0; k < 3; ++k) {
      m.min[k] -= margin * extent;
      m.max[k] += margin * extent;
    }
    m = dyadic_outward(m);
    certify::RationalBox r;
    bool ok = true;
    for (size_t k = 0; k < 3; ++k) {
      ok = ok && std::isfinite(m.min[k]) && std::isfinite(m.max[k]) && m.min[k] < m.max[k];
      if (!ok) break;
      r.lo[k] = core::Rational::exact_from_double(m.min[k]);
      r.hi[k] = core::Rational::exact_from_double(m.max[k]);
    }
    if (ok) boxes.push_back(std::move(r));
  }
  return boxes;
}

// The loops the tracer drew closed, as proposals for certify::proven_loops (loop_boxes each).
std::vector<std::vector<certify::RationalBox>> loop_proposals(const CurveResult& out) {
  std::vector<std::vector<certify::RationalBox>> proposals;
  for (const auto& br : out.branches) {
    if (!br.closed || br.points.size() < 3) continue;
    auto boxes = loop_boxes(br.points);
    if (!boxes.empty()) proposals.push_back(std::move(boxes));
  }
  return proposals;
}

// A direction d (largest |d_k| = 1) along which the points of p and of q lie in disjoint
// intervals, the one with the widest gap relative to the sets' extent among the centroids'
// difference, the axes, the face and body diagonals and 2000 directions spread over a sphere;
// nullopt when none separates them.
// Floats: it only proposes the boxes' frame.
std::optional<std::array<double, 3>> separating_direction(const std::vector<Point3>& p,
                                                          const std::vector<Point3>& q) {
  if (p.empty() || q.empty()) return std::nullopt;
  auto centroid = [](const std::vector<Point3>& v) {
    Point3 c{};
    for (const auto& x : v)
      for (size_t k = 0; k < 3; ++k)
        c[k] += x[k] / static_cast<double>(v.size());
    return c;
  };
  const Point3 cp = centroid(p), cq = centroid(q);
  std::vector<std::array<double, 3>> tries{{cq[0] - cp[0], cq[1] - cp[1], cq[2] - cp[2]}};
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (i > 0 || (i == 0 && (j > 0 || (j == 0 && k > 0))))
          tries.push_back({double(i), double(j), double(k)});
  // Then 2000 directions spread evenly over a hemisphere (a Fibonacci lattice): ovals on the
  // two sides of a cone's apex are often separated by no axis nor diagonal.
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double z = (i + 0.5) / n, rho = std::sqrt(1 - z * z);
    const double phi = 2.399963229728653 * i; // the golden angle
    tries.push_back({rho * std::cos(phi), rho * std::sin(phi), z});
  }
  std::optional<std::array<double, 3>> best;
  double best_gap = 0;
  for (auto d : tries) {
    const double big = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])});
    if (!(big > 0) || !std::isfinite(big)) continue;
    for (auto& e : d)
      e /= big;
    auto range = [&d](const std::vector<Point3>& v) {
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      for (const auto& x : v) {
        const double t = d[0] * x[0] + d[1] * x[1] + d[2] * x[2];
        lo = std::min(lo, t), hi = std::max(hi, t);
      }
      return std::array<double, 2>{lo, hi};
    };
    const auto rp = range(p), rq = range(q);
    const double gap = std::max(rq[0] - rp[1], rp[0] - rq[1]);
    const double extent = std::max(rp[1] - rp[0], rq[1] - rq[0]);
    if (gap > 0 && extent > 0 && gap / extent > best_gap) best_gap = gap / extent, best = d;
  }
  return best;
}

// The reading whose loops loops_in_oval_chart proves (see the header).
std::optional<certify::AffineTopology> settle_in_oval_chart(const core::QuadricMatrix& a,
                                                            const core::QuadricMatrix& b,
                                                            const CurveResult& out,
                                                            const TraceOptions& opt) {
  const certify::Morphology* m = out.topology.morphology;
  if (!m || !out.affine.points_at_infinity_complete) return std::nullopt;
  // The pair's least-squares centre (far_centre) and the order of its features' lengths there
  // frame it for the chart: a pair scaled by 2^-20 or moved 2^30 away is brought near unit
  // size first (certify::oval_chart; floats choose the frame, which is exact).
  certify::ChartFrame frame;
  const certify::ChartFrame* framed = nullptr;
  if (const auto c = far_centre(a, b, false)) {
    const auto la = core::length_order(a.translated(*c)), lb = core::length_order(b.translated(*c));
    if (la || lb) {
      frame.centre = *c;
      frame.size = std::ldexp(
          1.0, static_cast<int>(std::clamp(std::max(la.value_or(LONG_MIN), lb.value_or(LONG_MIN)),
                                           -900L, 900L)));
      framed = &frame;
    }
  }
  const auto loops = loops_in_oval_chart(
      a, b, *m, static_cast<int>(out.affine.points_at_infinity.size()), opt, framed);
  if (!loops) return std::nullopt;
  certify::OvalsAtInfinity ov;
  ov.loops = loops;
  certify::AffineTopology af = out.affine;
  if (certify::settle_by_oval_chart(af, ov)) return af;
  return std::nullopt;
}

// The affine reading left undecided only by how the points at infinity are shared among the
// ovals (AffineTopology::readings), settled by the loops the tracer drew closed: each closed
// branch proposes tight dyadic boxes around it (its points' bounding box widened by 1/16,
// 1/4, then 1/64 of its largest extent, outwards to the grid of dyadic_outward), and
// certify::proven_loops proves exactly, on the original pair, that a loop lies wholly inside
// (no crossing with the box's faces, at least one with a plane splitting it). The floats only
// choose the boxes; a loop the tracer missed proves nothing, so only the readings with fewer
// loops than proven are dropped. When more than one remains, certify::loops_upper_bound may
// drop those with more loops than it proves at most. Still several: the ovals are asked which
// of them meet infinity in a chart where all are bounded (settle_in_oval_chart). nullopt when
// none of these leaves one reading.
std::optional<certify::AffineTopology> settle_by_traced_loops(const core::QuadricMatrix& a,
                                                              const core::QuadricMatrix& b,
                                                              const CurveResult& out,
                                                              const TraceOptions& opt) {
  if (out.affine.readings.size() < 2 || out.affine.certified()) return std::nullopt;
  const auto proposals = loop_proposals(out);
  const certify::ProvenLoops p = proposals.empty()
                                     ? certify::ProvenLoops{}
                                     : certify::proven_loops(a.matrix(), b.matrix(), proposals);
  certify::AffineTopology af = out.affine;
  if (certify::settle_by_proven_loops(af, p)) return af;
  // Readings with more loops than proven remain: an upper bound, exact, from the critical
  // points of the coordinates (no float proposal): at most p.count compact components leaves
  // one reading when the tracer saw every loop.
  const certify::LoopUpperBound u = certify::loops_upper_bound(a.matrix(), b.matrix(), p.count);
  if (u.bound && certify::settle_by_proven_loops(af, p, &u)) return af;
  return settle_in_oval_chart(a, b, out, opt);
}

} // namespace

std::optional<int> loops_in_oval_chart(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                                       const certify::Morphology& m, int points_at_infinity,
                                       const TraceOptions& opt, const certify::ChartFrame* frame) {
  if (m.loops != 2 || m.connected_components != 2) return std::nullopt;
  std::string why;
  const auto chart = certify::oval_chart(a.matrix(), b.matrix(), why, frame);
  if (!chart) return std::nullopt;
  const core::QuadricMatrix ca(chart->a), cb(chart->b);
  QsicResult t = classify_qsic(ca, cb, Mode::Filtered);
  if (t.status != Status::Certified || t.morphology != &m) return std::nullopt;
  TraceOptions o;
  o.tolerance = opt.tolerance;
  o.max_points_per_branch = opt.max_points_per_branch;
  const CurveResult there = trace_curve_at(ca, cb, std::move(t), o, 0);
  std::vector<const std::vector<Point3>*> loops;
  for (const auto& br : there.branches)
    if (br.closed && br.points.size() >= 3) loops.push_back(&br.points);
  if (loops.size() != 2) return std::nullopt;
  // Boxes around the two loops, disjoint: along a direction d that separates the traced loops
  // (floats propose it), made the chart's second coordinate (certify::oval_chart_along), each
  // box cut at the middle of the gap; d = the first coordinate's axis needs no new chart.
  const auto sep = separating_direction(*loops[0], *loops[1]);
  if (!sep) return std::nullopt;
  std::array<core::Rational, 3> d;
  for (size_t k = 0; k < 3; ++k)
    d[k] = core::Rational::exact_from_double(
        std::ldexp(std::nearbyint(std::ldexp((*sep)[k], 12)), -12));
  std::array<std::array<core::Rational, 3>, 3> r;
  std::optional<certify::OvalChart> along = certify::oval_chart_along(*chart, d, r);
  const size_t axis = along ? 1 : 0;
  std::array<std::array<double, 3>, 3> rd{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      rd[i][j] = along ? r[i][j].to_double_approx() : (i == j ? 1.0 : 0.0);
  if (!along) along = *chart;
  std::array<std::vector<Point3>, 2> pts;
  std::array<double, 2> lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (size_t l = 0; l < 2; ++l)
    for (const Point3& y : *loops[l]) {
      Point3 z{};
      for (size_t i = 0; i < 3; ++i)
        z[i] = rd[i][0] * y[0] + rd[i][1] * y[1] + rd[i][2] * y[2];
      pts[l].push_back(z);
      lo[l] = std::min(lo[l], z[axis]);
      hi[l] = std::max(hi[l], z[axis]);
    }
  const size_t below = hi[0] < lo[1] ? 0 : 1;
  if (!(hi[below] < lo[1 - below])) return std::nullopt;
  // Cut a third of the gap from each side: closed boxes that touch are not disjoint.
  const double gap = lo[1 - below] - hi[below];
  const core::Rational cut_lo = core::Rational::exact_from_double(hi[below] + gap / 3),
                       cut_hi = core::Rational::exact_from_double(lo[1 - below] - gap / 3);
  if (!(cut_lo < cut_hi)) return std::nullopt;
  std::vector<std::vector<certify::RationalBox>> proposals;
  for (size_t l = 0; l < 2; ++l) {
    std::vector<certify::RationalBox> boxes;
    for (certify::RationalBox bx : loop_boxes(pts[l])) {
      if (l == below && cut_lo < bx.hi[axis]) bx.hi[axis] = cut_lo;
      if (l != below && bx.lo[axis] < cut_hi) bx.lo[axis] = cut_hi;
      if (bx.lo[axis] < bx.hi[axis]) boxes.push_back(std::move(bx));
    }
    proposals.push_back(std::move(boxes));
  }
  const certify::ProvenLoops p = certify::proven_loops(along->a, along->b, proposals);
  const certify::OvalsAtInfinity ov =
      certify::ovals_at_infinity(*along, p, m.loops, points_at_infinity);
  return ov.loops;
}

CurveResult trace_curve(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                        QsicResult topology, const TraceOptions& opt) {
  if (opt.box && !std::isfinite(opt.box->diagonal())) {
    // A given box whose diagonal is beyond the doubles (corners at +-1e308): the tracer's
    // scene size, steps and floors are relative to it, and a walk's step became NaN and never
    // ended (a hang, deaf to a batch budget). Nothing traced.
    CurveResult out;
    out.tolerance = opt.tolerance;
    out.topology = std::move(topology);
    if (out.topology.morphology) certify::complete_special_points(out.topology, a, b);
    out.affine = certify::affine_topology(out.topology, a, b);
    out.status = out.topology.status == Status::Certified ? Status::Undecided : out.topology.status;
    out.box = opt.box;
    out.note = "the box's diagonal is beyond the double range: nothing traced (a box up to about "
               "1e308 across is traced)";
    return out;
  }
  CurveResult out = trace_curve_at(a, b, std::move(topology), opt, 0);
  if (auto settled = settle_by_traced_loops(a, b, out, opt)) {
    // The affine reading is now certified: the picture is judged against it from the start
    // (the same routes, translated or rescaled copies included, with this reading carried).
    QsicResult t = out.topology;
    out = trace_curve_at(a, b, std::move(t), opt, 0, &*settled);
  }
  check_picture(out);
  // Doubles beyond the range (a unit pair's hyperbolas followed out to a given box 1e300 wide,
  // where f ~ x^2 overflows) make no picture: nothing half-written, an honest undecided.
  bool finite = std::isfinite(out.max_residual);
  for (const auto& br : out.branches)
    for (const auto& p : br.points)
      finite = finite && std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  for (const auto& p : out.isolated_points)
    finite = finite && std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  auto finite3 = [](const Point3& p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  };
  // A box (or a crossing) beyond the double range (a curve 1e350 wide, a plane x = 1e320: the
  // automatic box came out [-inf, inf], an internal error in the JSON): no box at all.
  bool box_finite = !out.box || (finite3(out.box->min) && finite3(out.box->max));
  if (out.box_exits)
    for (const auto& c : out.box_exits->points)
      box_finite = box_finite && finite3(c.approx) && std::isfinite(c.radius);
  if (!box_finite) {
    out.box.reset();
    out.box_exits.reset();
    finite = false;
  }
  if (!finite) {
    out.branches.clear();
    out.isolated_points.clear();
    out.max_residual = 0;
    out.matches_topology = false;
    if (out.status == Status::Certified) out.status = Status::Undecided;
    out.note = "the traced curve left the double range (a box far larger than the curve's "
               "features, or the reverse): no points returned";
  }
  return out;
}

namespace {

CurveResult trace_curve_at(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                           QsicResult topology, const TraceOptions& opt, int depth,
                           const certify::AffineTopology* known, const Point3* centre,
                           bool unit_size_there) {
  CurveResult out;
  out.tolerance = opt.tolerance;
  out.topology = std::move(topology);
  QsicResult& t = out.topology;
  // The branches need the special points (isolated points, singular points), at every detail.
  if (t.morphology) certify::complete_special_points(t, a, b);
  out.affine = known ? *known : certify::affine_topology(t, a, b);
  // A pair whose features are of moderate size but lie up to 2^40 from the origin is traced
  // where it is (translated below when it has a centre), not scaled down by its distance:
  // scaled by 2^-10, a unit cone-plane parabola 1000 units out became a curve of 2^-10 next to
  // the tracer's absolute seeds and floors, its automatic box grew to 596,000 wide and nothing
  // was traced (helper-11's audit; before the rescaling such pairs were certified). Its size:
  // the order of the pair moved to its least-squares centre (a cone's apex).
  // Either reading is sound (the exact parts judge both), and neither suits every far pair (a
  // cylinder pair 2^20 out is certified at unit size and not where it is, a parabola the other
  // way round): when the first is undecided the other is tried, and a certified one returned.
  if (depth < 4)
    if (const auto k = extreme_order(a, b)) {
      bool moderate = false;
      std::optional<Point3> centre_here;
      if (*k > 8 && *k <= 40)
        if (const auto c = far_centre(a, b, false)) {
          moderate = !extreme_order(a.translated(*c), b.translated(*c));
          // The translation used where the sizes at that centre are none (a paraboloid's
          // vertex, a cone's apex: far_centre's size test finds nothing to compare the
          // distance with), on a dyadic grid 2^-30 of the distance: a unit paraboloid's circle
          // 2^20 out was lost in the doubles of its offset.
          const double far = std::max({std::fabs((*c)[0]), std::fabs((*c)[1]), std::fabs((*c)[2])});
          if (moderate && far > 0) {
            Point3 g = *c;
            const double unit = std::ldexp(1.0, std::ilogb(far) - 30);
            for (double& x : g)
              x = std::nearbyint(x / unit) * unit;
            keep_shapes_lazy(a, b, g);
            if (g[0] != 0 || g[1] != 0 || g[2] != 0) centre_here = g;
          }
        }
      if (!moderate) return trace_rescaled(a, b, std::move(out), opt, *k, depth);
      CurveResult here = trace_curve_at(a, b, out.topology, opt, 4, &out.affine,
                                        centre_here ? &*centre_here : nullptr);
      if (here.status == Status::Certified) return here;
      CurveResult scaled = trace_rescaled(a, b, std::move(out), opt, *k, depth);
      return scaled.status == Status::Certified ? scaled : here;
    }
  if (t.pencil != algebra::PencilKind::Regular && t.pencil != algebra::PencilKind::Coincident) {
    if (trace_section_lines(a, b, out, opt)) return out;
    const certify::AffineTopology& af = out.affine;
    if (af.certified() && af.plane && af.section_of && !af.plane2 && *af.conics == 1) {
      // One plane's proper conic (a plane across a parabolic cylinder's rulings).
      trace_in_box(a, b, out, opt, std::make_pair(*af.plane, *af.section_of));
      return out;
    }
  }
  if (t.status != Status::Certified || t.pencil != algebra::PencilKind::Regular || !t.morphology) {
    out.status = t.status == Status::Certified ? Status::Undecided : t.status;
    out.note = t.pencil == algebra::PencilKind::Coincident
                   ? "the quadrics coincide: the intersection is a surface, not a curve"
                   : "no regular pencil: curves of degenerate pencils are not traced";
    return out;
  }
  // Translations nest at most max_translation_depth deep: an ellipsoid and a cone whose apex
  // lies on it, moved by (27/5, -6, 7/5), had a least-squares centre that stayed "far" after
  // every exact move, and the calls recursed until the stack overflowed (helper-26's probe;
  // a batch lost every later line). Past the limit the pair is traced where it is.
  constexpr int max_translation_depth = 16;
  // A plane's section (one quadric a plane, the curve its conic) is sampled in its plane, where
  // it lies: moved to a rounded cone's apex it gained nothing and paid the special points and
  // the box's crossings twice, there and back (~30% of a cone-plane pair posed in doubles).
  const bool plane_section = out.affine.certified() && out.affine.route == "plane_section";
  std::optional<Point3> far =
      depth < max_translation_depth && !plane_section ? far_centre(a, b) : std::optional<Point3>{};
  if (!far && centre && depth < max_translation_depth) far = *centre;
  if (const auto& c = far) {
    // Traced on the pair translated exactly by -c (its classification re-done there: the same
    // certified answer, the special points and singular members in the new coordinates), the
    // points moved back (adding c in double: an error ~1e-16 |c|) and corrected on the
    // original exact pair; topology and affine reading stay those of the original pair.
    const auto a2 = a.translated(*c), b2 = b.translated(*c);
    TraceOptions o2 = opt;
    if (o2.box)
      for (size_t k = 0; k < 3; ++k)
        o2.box->min[k] -= (*c)[k], o2.box->max[k] -= (*c)[k];
    // Asked by the retry below (unit_size_there): a pair whose features are extreme in a
    // quadric's own frame is traced there at unit size: a cone and a plane 1e-15 off a
    // generator, the apex at (1/3, 0, -1), is the pair at the origin once moved (certified at
    // unit size), but the retry (depth >= 4) did not rescale and the parabola 1e-15 wide was
    // lost in the doubles. (Second, after the plain retry: rescaled first, 512 answers of an
    // audit of near-degenerate pairs that the plain retry certifies were lost.)
    const int k_there = unit_size_there ? extreme_order(a2, b2).value_or(0) : 0;
    CurveResult local;
    if (k_there != 0) {
      CurveResult moved;
      moved.topology = certify::translated_classification(out.topology, a2, b2);
      moved.affine = out.affine; // read there through movable(); replaced below
      local = trace_rescaled(a2, b2, std::move(moved), o2, k_there, depth + 1);
    } else {
      local = trace_curve_at(a2, b2, certify::translated_classification(out.topology, a2, b2), o2,
                             depth + 1, movable(out.affine));
    }
    auto back = [&c](Point3& x) {
      for (size_t k = 0; k < 3; ++k)
        x[k] += (*c)[k];
    };
    for (auto& br : local.branches)
      for (auto& x : br.points)
        back(x);
    for (auto& x : local.isolated_points)
      back(x);
    // The box moved back exactly (every sum exact, the given box when there was one) is the
    // translated box moved back: the crossings found there are the original pair's, moved.
    bool box_exact = local.box.has_value();
    if (local.box) {
      for (size_t k = 0; k < 3; ++k) {
        const auto lo = exact_sum(local.box->min[k], (*c)[k]);
        const auto hi = exact_sum(local.box->max[k], (*c)[k]);
        box_exact = box_exact && lo && hi &&
                    (!opt.box || (*lo == opt.box->min[k] && *hi == opt.box->max[k]));
        local.box->min[k] = opt.box ? opt.box->min[k] : local.box->min[k] + (*c)[k];
        local.box->max[k] = opt.box ? opt.box->max[k] : local.box->max[k] + (*c)[k];
      }
    }
    local.topology = std::move(out.topology);
    local.affine = std::move(out.affine);
    finish_points(a, b, QuadricPair(a, b), local);
    if (local.box_exits && local.box) {
      if (box_exact) {
        // Each midpoint moved in double: a rounding of at most half an ulp per coordinate,
        // added (twice over) to the radius.
        for (auto& e : local.box_exits->points) {
          double moved = 0;
          for (size_t k = 0; k < 3; ++k) {
            e.approx[k] += (*c)[k];
            moved = std::max(moved, std::fabs(e.approx[k]));
          }
          e.radius += 0x1p-52 * moved + 0x1p-1074;
        }
      } else {
        // The reported box is the translated one moved back with a rounding: its exact
        // crossings are recomputed on the original pair and matched again (the claim is about
        // this box).
        rematch_exits(a, b, local);
      }
    }
    return local;
  }
  // The exact special points are all the curve has (when computed): a start at which the
  // rounded pair looks singular elsewhere is a near-crossing the rounding closed, not a
  // singular point to walk through.
  TraceOptions here = opt;
  here.singular_points_complete = t.special_points_complete;
  trace_here(a, b, out, here);
  check_picture(out);
  // Undecided where it is: once more in the frame of either quadric's own centre (a cone's
  // apex, a sphere's centre, the point of a cylinder's axis nearest the origin), translated
  // exactly. Next to an apex at |c| ~ 1 the rounded cone's zero set is noise within ~1e-8 of
  // it (f ~ r^2 against a rounding of ~1e-16 |c|^2), so a curve passing an apex that close
  // (a cylinder 1e-10 off it: two loops whose necks are 2e-10 apart) cannot be walked there;
  // at the origin the same cone is exact to ~1e-16 r^2. Depth 8 marks the retry (no further
  // retries inside it). Not while the affine reading itself is open (readings that
  // settle_by_traced_loops decides after this trace): a retry carries that reading and can
  // only be undecided too (four retries were ~45 ms of a rounded cone pair's 50).
  // For a pair traced exactly as posed (QuadricPair::noise_unit at the evaluation's floor) a
  // frame is tried only when the traced curve comes near its centre (within 1/64 of the
  // curve's size; nothing traced counts as near): moved to a double centre the matrices are no
  // longer doubles, and the walk there has the coefficients' 2^-53 to contend with where here
  // it had ~4e-19, which only pays next to a centre that is nearly on the curve (a cylinder
  // through a cone's apex). The undecided rounded Steinmetz pairs spent ~40 ms each in retries
  // at their axes, which the curve never comes near.
  auto near_curve = [&out](const Point3& c) {
    double size = points_size(out, true), best = HUGE_VAL;
    for (const auto& br : out.branches)
      for (const auto& p : br.points)
        best = std::min(best, std::hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]));
    return !(best > size / 64);
  };
  if (out.status == Status::Certified || !out.affine.certified() || centre || depth >= 8)
    return out;
  const bool as_posed = QuadricPair(a, b).noise_unit < 0x1p-53;
  for (const core::QuadricMatrix* s : {&a, &b})
    if (const auto c = own_centre(*s); c && (!as_posed || near_curve(*c))) {
      CurveResult again = trace_curve_at(a, b, out.topology, opt, 8, &out.affine, &*c);
      if (again.status == Status::Certified) return again;
      again = trace_curve_at(a, b, out.topology, opt, 8, &out.affine, &*c, true);
      if (again.status == Status::Certified) return again;
    }
  return out;
}

// The curve of a regular pencil traced where the pair lies: in a box (no ellipsoid) or whole.
void trace_here(const core::QuadricMatrix& a, const core::QuadricMatrix& b, CurveResult& out,
                const TraceOptions& opt) {
  const QsicResult& t = out.topology;
  if (opt.box ||
      (a.kind() != core::QuadricKind::Ellipsoid && b.kind() != core::QuadricKind::Ellipsoid)) {
    trace_in_box(a, b, out, opt);
    return;
  }
  QuadricPair q(a, b);
  std::vector<Point3> singular = split_special_points(t, out.isolated_points);
  const int c = t.tu_case;
  if (quartic_case(c)) {
    // Float start points first (cheap); if the branches traced from them do not reproduce the
    // certified topology (a small loop missed), the exact extreme points are used instead.
    int unresolved = 0;
    const std::vector<Point3> float_starts = extreme_points_float(q);
    out.branches = march(q, float_starts, singular, opt, &unresolved);
    // Every branch of a quartic case is a closed loop here (one surface is an ellipsoid): an
    // open one is a walk that died.
    auto whole = [c](const std::vector<Branch>& brs) {
      return branches_match(brs, c) &&
             std::all_of(brs.begin(), brs.end(), [](const Branch& br) { return br.closed; });
    };
    // Walks stopped by the noise test (a cylinder rounded into a long ellipsoid, crossing
    // another pipe at a neck): the float starts on the pair evaluated in double-double first
    // (see trace_in_box), before the exact extreme points.
    if (!whole(out.branches) && unresolved > 0)
      if (const auto r = q.refined(a, b)) {
        std::vector<Branch> again = march(*r, float_starts, singular, opt);
        if (whole(again)) out.branches = std::move(again);
      }
    if (!whole(out.branches)) {
      const std::vector<Point3> starts = extreme_points(a, b);
      out.branches = march(q, starts, singular, opt);
      out.exact_start_points = true;
      // Then on the exact coefficients in double-double (see trace_in_box): a loop whose
      // pieces pass within ~1e-8 of each other, which the rounded pair cannot separate.
      if (!whole(out.branches))
        if (const auto r = q.refined(a, b)) {
          std::vector<Branch> again = march(*r, starts, singular, opt);
          if (whole(again)) out.branches = std::move(again);
        }
    }
  } else if (t.morphology->conics > 0) {
    out.branches = conic_branches(a, b, t.facts, opt,
                                  lines_only(t) ? SectionKinds::LinesOnly : SectionKinds::Any);
    drop_point_sections(out, t.morphology->conics, opt.tolerance);
  }
  finish_points(a, b, q, out);

  // The branches must reproduce the certified topology exactly.
  std::vector<std::string> got, want = expected_branch_kinds(c);
  for (const auto& br : out.branches)
    got.push_back(br.kind);
  std::sort(got.begin(), got.end());
  std::sort(want.begin(), want.end());
  bool points_ok = static_cast<int>(out.isolated_points.size()) == t.morphology->isolated_points;
  bool closed_ok = std::all_of(out.branches.begin(), out.branches.end(),
                               [](const Branch& br) { return br.closed; });
  out.matches_topology = got == want && points_ok && closed_ok && t.special_points_complete;
  if (out.matches_topology) {
    out.status = Status::Certified;
  } else {
    out.status = Status::Undecided;
    std::string g;
    for (const auto& k : got)
      g += (g.empty() ? "" : ", ") + k;
    std::string w;
    for (const auto& k : want)
      w += (w.empty() ? "" : ", ") + k;
    out.note = "traced branches [" + g + "] and " + std::to_string(out.isolated_points.size()) +
               " isolated point(s) do not match the certified topology [" + w + "] with " +
               std::to_string(t.morphology->isolated_points) + " isolated point(s)" +
               (closed_ok ? "" : "; an open branch was returned") +
               (t.special_points_complete ? "" : "; special points not all computed exactly");
  }
}

} // namespace

std::string curve_caption(const CurveResult& r) {
  const QsicResult& t = r.topology;
  if (!t.morphology) return "no curve: " + r.note;
  char tol[32];
  std::snprintf(tol, sizeof tol, "%g", r.tolerance);
  std::string s = "case " + std::to_string(t.tu_case) + " " + t.morphology->id + ": " +
                  t.morphology->description + " (topology " + to_string(t.status);
  const auto& af = r.affine;
  if (af.computed) {
    auto n = [](const std::optional<int>& v) { return v ? std::to_string(*v) : std::string("?"); };
    s += "; affine: " + n(af.loops) + " loop(s), " + n(af.unbounded_branches) +
         " unbounded branch(es), " + n(af.isolated_points) + " isolated point(s)" +
         (af.certified() ? "" : " (not all certified)");
  }
  s += ")";
  int closed = 0, open = 0;
  for (const auto& br : r.branches)
    (br.closed ? closed : open) += 1;
  if (r.branches.empty() && r.isolated_points.empty()) {
    const bool empty_ok = r.matches_topology;
    return s + (empty_ok ? ": empty, nothing to trace"
                         : ": nothing traced (undecided: " + r.note + ")");
  }
  s += ": traced " + std::to_string(closed) + " closed and " + std::to_string(open) +
       " open branch(es)" + (r.box ? " in the box" : "") + ", " +
       std::to_string(r.isolated_points.size()) + " isolated point(s), tolerance " + tol;
  return s + (r.matches_topology
                  ? ", matching the certified topology"
                  : ", NOT matching the certified topology: undecided (" + r.note + ")");
}

namespace {

// A point as dump() writes a Json array of three Json::number_double: "[x,y,z]".
void append_point(std::string& out, const Point3& p) {
  out += '[';
  for (size_t k = 0; k < 3; ++k) {
    if (k) out += ',';
    core::io::append_json_double(out, p[k]);
  }
  out += ']';
}

Json point_json(const Point3& p) {
  Json a3 = Json::array();
  a3.reserve(3);
  for (double x : p)
    a3.push_back(Json::number_double(x));
  return a3;
}

// The envelope with every member in its place, except that result.branches holds null: the
// branches are filled in by curve_envelope_json as a document and by append_curve_envelope as
// text (the polylines are almost all of an answer's bytes; a document of them costs four
// values and three heap strings per point).
Json envelope_without_branches(const CurveResult& r, const core::QuadricMatrix& a,
                               const core::QuadricMatrix& b, certify::Detail detail) {
  Json env = qsic_envelope_json(r.topology, a, b, detail);
  env.set("status", Json::string(to_string(r.status)));
  if (!r.note.empty()) env.set("note", Json::string(r.note));
  Json res = *env.find("result");
  auto num = [](double x) { return Json::number_double(x); };
  res.set("branches", Json::null());
  Json iso = Json::array();
  for (const auto& p : r.isolated_points)
    iso.push_back(point_json(p));
  res.set("isolated_points", std::move(iso));
  res.set("branches_match_topology", Json::boolean(r.matches_topology));
  res.set("branch_points_approximate", Json::boolean(true));
  res.set("max_residual", num(r.max_residual));
  res.set("tolerance", num(r.tolerance));
  res.set("affine", certify::affine_json(r.affine));
  if (r.box) {
    Json bx = Json::object();
    bx.set("min", point_json(r.box->min));
    bx.set("max", point_json(r.box->max));
    bx.set("automatic", Json::boolean(r.box_automatic));
    if (r.box_exits) {
      // The exact crossings of the curve with the faces: "certified" when complete and each
      // transversal, off the edges (certify/box_exits.hpp); points are their double values.
      Json ex = Json::object();
      ex.set("status", Json::string(r.box_exits->certified ? "certified" : "undecided"));
      if (r.box_exits->certified) {
        ex.set("count", Json::number_text(std::to_string(r.box_exits->points.size())));
        Json pts = Json::array();
        for (const auto& c : r.box_exits->points)
          pts.push_back(point_json(c.approx));
        ex.set("points", pts);
      } else {
        ex.set("count", Json::null());
        ex.set("reason", Json::string(r.box_exits->reason));
      }
      bx.set("exits", ex);
    }
    res.set("box", bx);
  }
  env.set("result", std::move(res));
  return env;
}

// {"kind", "closed", "exits" (when matched), "points"} up to "points"'s value.
Json branch_head_json(const Branch& br) {
  Json o = Json::object();
  o.set("kind", Json::string(br.kind));
  o.set("closed", Json::boolean(br.closed));
  if (!br.exits.empty()) {
    Json ex = Json::array();
    for (int i : br.exits)
      ex.push_back(Json::number_text(std::to_string(i)));
    o.set("exits", ex);
  }
  return o;
}

// The branches as dump() writes the array curve_envelope_json builds.
void append_branches(std::string& out, const std::vector<Branch>& branches) {
  size_t points = 0;
  for (const auto& br : branches)
    points += br.points.size();
  out.reserve(out.size() + 64 * points + 128 * branches.size() + 2);
  out += '[';
  for (size_t i = 0; i < branches.size(); ++i) {
    const Branch& br = branches[i];
    if (i) out += ',';
    std::string head = core::io::dump(branch_head_json(br));
    head.pop_back(); // its '}': "points" continues the object
    out += head;
    out += ",\"points\":[";
    for (size_t k = 0; k < br.points.size(); ++k) {
      if (k) out += ',';
      append_point(out, br.points[k]);
    }
    out += "]}";
  }
  out += ']';
}

} // namespace

Json curve_envelope_json(const CurveResult& r, const core::QuadricMatrix& a,
                         const core::QuadricMatrix& b, certify::Detail detail) {
  Json env = envelope_without_branches(r, a, b, detail);
  Json res = *env.find("result");
  Json branches = Json::array();
  for (const auto& br : r.branches) {
    Json o = branch_head_json(br);
    Json pts = Json::array();
    pts.reserve(br.points.size());
    for (const auto& p : br.points)
      pts.push_back(point_json(p));
    o.set("points", std::move(pts));
    branches.push_back(std::move(o));
  }
  res.set("branches", std::move(branches));
  env.set("result", std::move(res));
  return env;
}

void append_curve_envelope(std::string& out, const CurveResult& r, const core::QuadricMatrix& a,
                           const core::QuadricMatrix& b, certify::Detail detail) {
  const Json env = envelope_without_branches(r, a, b, detail);
  out += '{';
  bool first = true;
  for (const auto& [key, value] : env.members()) {
    if (!first) out += ',';
    first = false;
    core::io::append_json_string(out, key);
    out += ':';
    if (key != "result") {
      out += core::io::dump(value);
      continue;
    }
    out += '{';
    bool first_member = true;
    for (const auto& [k, v] : value.members()) {
      if (!first_member) out += ',';
      first_member = false;
      core::io::append_json_string(out, k);
      out += ':';
      if (k == "branches")
        append_branches(out, r.branches);
      else
        out += core::io::dump(v);
    }
    out += '}';
  }
  out += '}';
}

} // namespace surfcert::trace
