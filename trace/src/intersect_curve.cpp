// surfcert::trace::intersect_curve: certified topology plus traced branches, checked against
// it (see intersect_curve.hpp).
#include "surfcert/trace/intersect_curve.hpp"

#include "surfcert/certify/report.hpp"
#include "surfcert/certify/special_points.hpp"
#include "surfcert/trace/conics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace surfcert::trace {

using certify::classify_qsic;
using certify::complete_report_data;
using certify::Mode;
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

double residual(const QuadricPair& q, const Point3& p) {
  double n = 1 + p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
  return std::max(std::fabs(q.f(p)), std::fabs(q.g(p))) / n;
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

} // namespace

CurveResult intersect_curve(const core::QuadricMatrix& a, const core::QuadricMatrix& b, Mode mode,
                            const TraceOptions& opt, certify::Detail detail) {
  QsicResult t = classify_qsic(a, b, mode == Mode::Float ? Mode::Filtered : mode);
  complete_report_data(t, a, b, detail);
  return trace_curve(a, b, std::move(t), opt);
}

CurveResult trace_curve(const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                        QsicResult topology, const TraceOptions& opt) {
  CurveResult out;
  out.tolerance = opt.tolerance;
  out.topology = std::move(topology);
  QsicResult& t = out.topology;
  // The branches need the special points (isolated points, singular points), at every detail.
  if (t.morphology) certify::complete_special_points(t, a, b);
  out.affine = certify::affine_topology(t, a, b);
  if (t.status != Status::Certified || t.pencil != algebra::PencilKind::Regular || !t.morphology) {
    out.status = t.status == Status::Certified ? Status::Undecided : t.status;
    out.note = t.pencil == algebra::PencilKind::Coincident
                   ? "the quadrics coincide: the intersection is a surface, not a curve"
                   : "no regular pencil: curves of degenerate pencils are not traced";
    return out;
  }
  if (a.kind() != core::QuadricKind::Ellipsoid && b.kind() != core::QuadricKind::Ellipsoid) {
    out.status = Status::Undecided;
    out.note = "intersect needs one ellipsoid (or sphere): the curve may be unbounded otherwise";
    return out;
  }
  QuadricPair q(a, b);
  std::vector<Point3> singular;
  for (const auto& p : t.special_points) {
    if (p.at_infinity) continue;
    if (isolated_kind(p.kind))
      out.isolated_points.push_back(p.approx);
    else
      singular.push_back(p.approx);
  }
  const int c = t.tu_case;
  if (quartic_case(c)) {
    // Float start points first (cheap); if the branches traced from them do not reproduce the
    // certified topology (a small loop missed), the exact extreme points are used instead.
    out.branches = march(q, extreme_points_float(q), singular, opt);
    if (!branches_match(out.branches, c)) {
      out.branches = march(q, extreme_points(a, b), singular, opt);
      out.exact_start_points = true;
    }
  } else if (t.morphology->conics > 0) {
    out.branches = conic_branches(a, b, t.facts, opt);
    drop_point_sections(out, t.morphology->conics, opt.tolerance);
  }
  for (const auto& br : out.branches)
    for (const auto& p : br.points)
      out.max_residual = std::max(out.max_residual, residual(q, p));
  for (const auto& p : out.isolated_points)
    out.max_residual = std::max(out.max_residual, residual(q, p));

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
  return out;
}

Json curve_envelope_json(const CurveResult& r, const core::QuadricMatrix& a,
                         const core::QuadricMatrix& b, certify::Detail detail) {
  Json env = qsic_envelope_json(r.topology, a, b, detail);
  env.set("status", Json::string(to_string(r.status)));
  if (!r.note.empty()) env.set("note", Json::string(r.note));
  Json res = *env.find("result");
  auto num = [](double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return Json::number_text(buf);
  };
  auto point = [&](const Point3& p) {
    Json a3 = Json::array();
    for (double x : p)
      a3.push_back(num(x));
    return a3;
  };
  Json branches = Json::array();
  for (const auto& br : r.branches) {
    Json o = Json::object();
    o.set("kind", Json::string(br.kind));
    o.set("closed", Json::boolean(br.closed));
    Json pts = Json::array();
    for (const auto& p : br.points)
      pts.push_back(point(p));
    o.set("points", pts);
    branches.push_back(o);
  }
  res.set("branches", branches);
  Json iso = Json::array();
  for (const auto& p : r.isolated_points)
    iso.push_back(point(p));
  res.set("isolated_points", iso);
  res.set("branches_match_topology", Json::boolean(r.matches_topology));
  res.set("branch_points_approximate", Json::boolean(true));
  res.set("max_residual", num(r.max_residual));
  res.set("tolerance", num(r.tolerance));
  res.set("affine", certify::affine_json(r.affine));
  env.set("result", res);
  return env;
}

} // namespace surfcert::trace
