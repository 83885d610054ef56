#include "surfcert/certify/report.hpp"

#include "surfcert/algebra/real_roots.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

namespace surfcert::certify {

using core::Rational;
using core::io::Json;

namespace {

const char* const kDegenerateDescription =
    "det(lA - B) vanishes identically: every member of the pencil is singular (outside the "
    "35-case classification)";
const char* const kCoincidentDescription =
    "the two quadrics coincide (B is a multiple of A): the intersection is the whole surface";
const char* const kComponentsSpace =
    "real projective; equal to the affine count when one quadric is an ellipsoid";

Json str(const std::string& s) {
  return Json::string(s);
}

std::string dbl(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

Json matrix_json(const core::Mat4& m) {
  Json rows = Json::array();
  for (const auto& row : m) {
    Json r = Json::array();
    for (const auto& v : row)
      r.push_back(str(v.to_string()));
    rows.push_back(r);
  }
  return rows;
}

const char* pencil_name(algebra::PencilKind k) {
  switch (k) {
  case algebra::PencilKind::Regular:
    return "regular";
  case algebra::PencilKind::Degenerate:
    return "degenerate";
  case algebra::PencilKind::Coincident:
    return "coincident";
  }
  return "?";
}

// Exact text of a real root: rational, a + b sqrt(d), or "root of P in (lo, hi)".
std::string root_exact_text(const algebra::RootFacts& r) {
  if (r.rational_value) return r.rational_value->to_string();
  if (r.quadratic) return r.quadratic->to_string();
  if (r.factor.degree() > 0)
    return "root of " + r.factor.to_string("l") + " in (" + r.lo.to_string() + ", " +
           r.hi.to_string() + ")";
  return "";
}

std::string root_approx(const algebra::RootFacts& r, const algebra::PencilFacts& f) {
  if (r.float_value) return dbl(*r.float_value); // float mode: the float root, an estimate
  if (r.rational_value) return r.rational_value->to_decimal_approx(17);
  if (r.quadratic) return dbl(r.quadratic->to_double_approx());
  algebra::UPolyZ p = r.factor;
  if (p.degree() <= 0 && !f.f.is_zero()) {
    // Filtered facts carry no factor: a simple root of f itself.
    p = f.f.primitive_integer();
  }
  if (p.degree() <= 0) return dbl(0.5 * (r.lo.to_double_approx() + r.hi.to_double_approx()));
  Rational lo = r.lo, hi = r.hi;
  Rational width = core::pow2(-60) * (core::abs(lo) + core::abs(hi) + Rational(1));
  // Newton's proposal checked by exact signs (refine_root_newton), not 60 exact bisections:
  // those were ~6% of a `batch` of natural pairs posed in doubles at detail full (f's
  // coefficients there have hundreds of bits).
  algebra::refine_root_newton(p, lo, hi, width);
  return ((lo + hi) * Rational(1, 2)).to_decimal_approx(17);
}

Json components_json(const Morphology& m) {
  Json c = Json::object();
  c.set("loops", Json::number(m.loops));
  c.set("isolated_points", Json::number(m.isolated_points));
  c.set("lines", Json::number(m.lines));
  c.set("conics", Json::number(m.conics));
  c.set("cubics", Json::number(m.cubics));
  c.set("double_components", Json::number(m.double_components));
  c.set("connected_components", Json::number(m.connected_components));
  c.set("space", str(kComponentsSpace));
  return c;
}

} // namespace

std::string signature_sequence(const algebra::PencilFacts& f) {
  std::string s = "<";
  for (size_t i = 0; i < f.indices.size(); ++i) {
    s += std::to_string(f.indices[i]);
    if (i < f.real_roots.size()) {
      const auto& r = f.real_roots[i];
      s += ",";
      s += std::string(static_cast<size_t>(r.multiplicity), '(');
      s += std::to_string(r.sigma.p) + "," + std::to_string(r.sigma.n);
      s += std::string(static_cast<size_t>(r.multiplicity), ')');
      s += ",";
    }
  }
  return s + ">";
}

Json qsic_result_json(const QsicResult& r, const core::QuadricMatrix& a,
                      const core::QuadricMatrix& b, Detail detail) {
  // Levels (detail.hpp): fields are left out below their level, in the order of Full.
  const bool certificate = detail >= Detail::Certificate, full = detail == Detail::Full;
  Json res = Json::object();
  res.set("pencil", str(pencil_name(r.pencil)));
  if (certificate) {
    Json mats = Json::object();
    mats.set("a", matrix_json(a.matrix()));
    mats.set("b", matrix_json(b.matrix()));
    res.set("matrices", mats);
  }
  if (r.pencil != algebra::PencilKind::Regular) {
    res.set("tu_case", Json::null());
    res.set("morphology", str(r.pencil == algebra::PencilKind::Degenerate ? "degenerate_pencil"
                                                                          : "coincident_quadrics"));
    res.set("description",
            str(r.pencil == algebra::PencilKind::Degenerate ? kDegenerateDescription
                                                            : kCoincidentDescription));
    if (!r.ellipsoid_relation.empty()) res.set("ellipsoid_relation", str(r.ellipsoid_relation));
    return res;
  }
  const algebra::PencilFacts& f = r.facts;
  if (r.morphology) {
    res.set("tu_case", Json::number(r.tu_case));
    res.set("morphology", str(r.morphology->id));
    res.set("description", str(r.morphology->description));
    res.set("tu_label_reconstructed", Json::boolean(r.morphology->label_reconstructed));
  } else {
    res.set("tu_case", Json::null());
    res.set("morphology", Json::null());
  }
  res.set("segre", str(r.segre));
  res.set("root_pattern", str(f.root_pattern));
  if (!certificate) {
    if (r.morphology) res.set("components", components_json(*r.morphology));
    if (!r.ellipsoid_relation.empty()) res.set("ellipsoid_relation", str(r.ellipsoid_relation));
    if (!r.containment.empty()) res.set("containment", str(r.containment));
    return res;
  }
  Json basis = Json::object();
  basis.set("rebased", Json::boolean(f.rebased));
  if (f.rebased) {
    basis.set("t", Json::number(f.rebase_t));
    basis.set("note", str("det A = 0: the pencil is written in the basis (tA - B, -A); its "
                          "parameter l' relates to l by l = t + 1/l'"));
  }
  res.set("pencil_basis", basis);
  if (r.mode == Mode::Float && r.float_invariants) {
    const auto& fi = *r.float_invariants;
    Json c = Json::array();
    for (int i = 0; i < 5; ++i)
      c.push_back(str(dbl(fi.f[i])));
    res.set("characteristic_polynomial_coeffs_approx", c);
    Json inv = Json::object();
    inv.set("D2_approx", str(dbl(fi.d2)));
    inv.set("D3_approx", str(dbl(fi.d3)));
    inv.set("D4_approx", str(dbl(fi.d4)));
    inv.set("E_approx", str(dbl(fi.e)));
    inv.set("note", str("float mode: of f as printed, computed from its float roots; "
                        "the root pattern is read from root clusters, not from these signs"));
    res.set("invariants", inv);
  } else if (!f.f.is_zero()) {
    res.set("characteristic_polynomial", str(f.f.to_string("l")));
    Json c = Json::array();
    for (long i = 0; i <= 4; ++i)
      c.push_back(str(f.f.coeff(i).to_string()));
    res.set("characteristic_polynomial_coeffs", c);
    Json inv = Json::object();
    inv.set("D2", str(f.d2.to_string()));
    inv.set("D3", str(f.d3.to_string()));
    inv.set("D4", str(f.d4.to_string()));
    inv.set("E", str(f.e.to_string()));
    inv.set("D2_approx", str(f.d2.to_decimal_approx(6)));
    inv.set("D3_approx", str(f.d3.to_decimal_approx(6)));
    inv.set("D4_approx", str(f.d4.to_decimal_approx(6)));
    inv.set("E_approx", str(f.e.to_decimal_approx(6)));
    res.set("invariants", inv);
  }
  Json roots = Json::array();
  for (const auto& root : f.real_roots) {
    // The root's own irreducible factor (a square-free factor of f may still split over Q): a
    // rational root reads as a rational, a quadratic one as a + b*sqrt(d).
    const algebra::RootFacts rt = r.mode == Mode::Float ? root : algebra::simplest_root_form(root);
    Json o = Json::object();
    o.set("multiplicity", Json::number(rt.multiplicity));
    if (r.mode != Mode::Float) {
      std::string ex = root_exact_text(rt);
      o.set("exact", ex.empty() ? Json::null() : str(ex));
      Json iv = Json::array();
      iv.push_back(str(rt.lo.to_string()));
      iv.push_back(str(rt.hi.to_string()));
      o.set("isolating_interval", iv);
    }
    o.set("approx", str(root_approx(rt, f)));
    o.set("rank", Json::number(rt.rank));
    Json in = Json::array();
    in.push_back(Json::number(rt.sigma.p));
    in.push_back(Json::number(rt.sigma.n));
    o.set("inertia", in);
    roots.push_back(o);
  }
  res.set("real_roots", roots);
  res.set("complex_roots", Json::number(f.complex_roots));
  res.set("signature_sequence", str(signature_sequence(f)));
  Json samples = Json::array();
  for (const auto& s : f.samples)
    samples.push_back(str(s.to_string()));
  Json idx = Json::array();
  for (int i : f.indices)
    idx.push_back(Json::number(i));
  res.set("definite_member", Json::boolean(f.definite_member));
  if (r.morphology) res.set("components", components_json(*r.morphology));
  if (full && r.mode != Mode::Float && r.status == Status::Certified) {
    Json sp = Json::array();
    for (const auto& p : r.special_points) {
      Json o = Json::object();
      o.set("kind", str(p.kind));
      o.set("at_infinity", Json::boolean(p.at_infinity));
      Json ex = Json::array(), ap = Json::array();
      for (size_t i = 0; i < 3; ++i) {
        ex.push_back(str(p.coords[i]));
        // Past the doubles (a point at 1e-350 read "0", one at 1e400 "inf"): a rational
        // coordinate's decimal at any exponent.
        const double d = p.approx[i];
        const bool lost = !std::isfinite(d) || (d == 0 && p.coords[i] != "0");
        const auto exact = lost ? Rational::from_string(p.coords[i]) : std::nullopt;
        ap.push_back(str(exact ? exact->to_decimal_approx(17) : dbl(d)));
      }
      o.set("exact", ex);
      o.set("approx", ap);
      sp.push_back(o);
    }
    res.set("special_points", sp);
    res.set("special_points_complete", Json::boolean(r.special_points_complete));
  }
  if (!r.ellipsoid_relation.empty()) res.set("ellipsoid_relation", str(r.ellipsoid_relation));
  if (!r.containment.empty()) res.set("containment", str(r.containment));
  Json cert = Json::object();
  cert.set("separators", samples);
  cert.set("indices", idx);
  cert.set("isolation_fallback", Json::boolean(f.isolation_fallback));
  cert.set("method", str(r.mode == Mode::Float ? "float (uncertified, tolerance 1e-8)"
                         : r.mode == Mode::Filtered && !r.exact_fallback
                             ? "interval filter: certain signs of f at the separators and of the "
                               "charpoly coefficients at them"
                             : "exact rational arithmetic: f over Q, square-free factorisation, "
                               "exact signs at the separators, Descartes on charpolys"));
  res.set("certificate", cert);
  return res;
}

Json qsic_envelope_json(const QsicResult& r, const core::QuadricMatrix& a,
                        const core::QuadricMatrix& b, Detail detail) {
  Json o = Json::object();
  o.set("status", str(to_string(r.status)));
  o.set("mode", str(to_string(r.mode)));
  if (r.mode == Mode::Filtered) o.set("exact_fallback", Json::boolean(r.exact_fallback));
  if (!r.note.empty()) o.set("note", str(r.note));
  // A lean answer says so (Full, the default, adds nothing: the contract's bytes).
  if (detail != Detail::Full) o.set("detail", str(to_string(detail)));
  o.set("result", qsic_result_json(r, a, b, detail));
  return o;
}

namespace {

// The parts of a topology line fixed by the morphology, written once per morphology: a line
// costs a few µs, and escaping the same sentences again was a sixth of it.
struct MorphologyFragments {
  std::string head;       ///< "morphology":…,"description":…,"tu_label_reconstructed":…
  std::string components; ///< ,"components":{…}
};

const MorphologyFragments& morphology_fragments(const Morphology& m) {
  static const std::vector<MorphologyFragments> table = [] {
    std::vector<MorphologyFragments> t;
    for (int c = 1; c <= 35; ++c) {
      const Morphology& e = morphology_of_case(c);
      MorphologyFragments f;
      f.head = "\"morphology\":";
      core::io::append_json_string(f.head, e.id);
      f.head += ",\"description\":";
      core::io::append_json_string(f.head, e.description);
      f.head += ",\"tu_label_reconstructed\":";
      f.head += e.label_reconstructed ? "true" : "false";
      f.components = ",\"components\":";
      f.components += core::io::dump(components_json(e));
      t.push_back(std::move(f));
    }
    return t;
  }();
  return table.at(static_cast<size_t>(m.tu_case - 1));
}

} // namespace

void append_qsic_topology_envelope(std::string& out, const QsicResult& r) {
  // The fields and order of qsic_envelope_json at Detail::Topology. Keys and the names of enum
  // values (status, mode, pencil) are plain lower-case words that need no escaping: each run of
  // constant text is one append; strings computed per answer go through append_json_string.
  using namespace std::string_view_literals;
  auto text = [&out](std::string_view v) { core::io::append_json_string(out, v); };
  out += "{\"status\":\""sv;
  out += to_string(r.status);
  out += "\",\"mode\":\""sv;
  out += to_string(r.mode);
  if (r.mode == Mode::Filtered)
    out += r.exact_fallback ? "\",\"exact_fallback\":true"sv : "\",\"exact_fallback\":false"sv;
  else
    out += '"';
  if (!r.note.empty()) {
    out += ",\"note\":"sv;
    text(r.note);
  }
  out += ",\"detail\":\"topology\",\"result\":{\"pencil\":\""sv;
  out += pencil_name(r.pencil);
  if (r.pencil != algebra::PencilKind::Regular) {
    out += "\",\"tu_case\":null,\"morphology\":"sv;
    text(r.pencil == algebra::PencilKind::Degenerate ? "degenerate_pencil" : "coincident_quadrics");
    out += ",\"description\":"sv;
    text(r.pencil == algebra::PencilKind::Degenerate ? kDegenerateDescription
                                                     : kCoincidentDescription);
  } else {
    out += "\",\"tu_case\":"sv;
    if (r.morphology) {
      char buf[24];
      out.append(buf, std::to_chars(buf, buf + sizeof buf, r.tu_case).ptr);
      out += ',';
      out += morphology_fragments(*r.morphology).head;
    } else {
      out += "null,\"morphology\":null"sv;
    }
    out += ",\"segre\":"sv;
    text(r.segre);
    out += ",\"root_pattern\":"sv;
    text(r.facts.root_pattern);
    if (r.morphology) out += morphology_fragments(*r.morphology).components;
  }
  if (!r.ellipsoid_relation.empty()) {
    out += ",\"ellipsoid_relation\":"sv;
    text(r.ellipsoid_relation);
  }
  if (r.pencil == algebra::PencilKind::Regular && !r.containment.empty()) {
    out += ",\"containment\":"sv;
    text(r.containment);
  }
  out += "}}"sv;
}

std::string qsic_result_text(const QsicResult& r, const core::QuadricMatrix& a,
                             const core::QuadricMatrix& b) {
  std::ostringstream os;
  os << "A: " << a.to_poly().to_string() << " = 0\n";
  os << "B: " << b.to_poly().to_string() << " = 0\n";
  os << "status: " << to_string(r.status) << " (mode " << to_string(r.mode)
     << (r.exact_fallback ? ", exact fallback" : "") << ")\n";
  if (r.pencil != algebra::PencilKind::Regular) {
    os << (r.pencil == algebra::PencilKind::Degenerate ? "degenerate pencil: det(lA - B) == 0\n"
                                                       : "coincident quadrics\n");
    return os.str();
  }
  const auto& f = r.facts;
  if (!f.f.is_zero())
    os << "f(l) = det(lA - B) = " << f.f.to_string("l") << (f.rebased ? "  (re-based pencil)" : "")
       << "\n";
  if (r.morphology)
    os << "topology: case " << r.tu_case << " " << r.morphology->id << ": "
       << r.morphology->description << "\n";
  os << "Segre " << r.segre << ", root pattern " << f.root_pattern << ", signature sequence "
     << signature_sequence(f) << "\n";
  if (r.morphology) {
    const auto& m = *r.morphology;
    os << "components: " << m.loops << " loop(s), " << m.isolated_points << " isolated point(s), "
       << m.lines << " line(s), " << m.conics << " conic(s), " << m.cubics << " cubic(s), "
       << m.double_components << " double; " << m.connected_components
       << " connected component(s)\n";
  }
  for (const auto& p : r.special_points)
    os << "special point (" << p.kind << "): (" << p.coords[0] << ", " << p.coords[1] << ", "
       << p.coords[2] << ") ~ (" << p.approx[0] << ", " << p.approx[1] << ", " << p.approx[2] << ")"
       << (p.at_infinity ? " at infinity" : "") << "\n";
  if (!r.ellipsoid_relation.empty())
    os << "ellipsoids: " << r.ellipsoid_relation
       << (r.containment.empty() ? "" : " (" + r.containment + ")") << "\n";
  if (!r.note.empty()) os << "note: " << r.note << "\n";
  return os.str();
}

Json input_error_json(const core::InputError& e) {
  Json o = Json::object();
  o.set("kind", str("input"));
  o.set("message", str(e.what()));
  const auto& w = e.where();
  if (!w.source.empty()) o.set("source", str(w.source));
  if (w.line > 0) o.set("line", Json::number(w.line));
  if (w.column > 0) o.set("column", Json::number(w.column));
  if (!w.json_path.empty()) o.set("json_path", str(w.json_path));
  o.set("expected", str(e.expected()));
  o.set("found", str(e.found()));
  return o;
}

} // namespace surfcert::certify
