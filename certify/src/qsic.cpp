#include "surfcert/certify/qsic.hpp"

#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/segre.hpp"
#include "surfcert/certify/qsic_rules.hpp"
#include "surfcert/certify/special_points.hpp"

#include <stdexcept>

namespace surfcert::certify {

using algebra::PencilFacts;
using algebra::PencilKind;
using core::Rational;

const char* to_string(Mode m) {
  switch (m) {
  case Mode::Exact:
    return "exact";
  case Mode::Filtered:
    return "filtered";
  case Mode::Float:
    return "float";
  }
  return "?";
}

const char* to_string(Status s) {
  switch (s) {
  case Status::Certified:
    return "certified";
  case Status::Undecided:
    return "undecided";
  case Status::Uncertified:
    return "uncertified";
  case Status::Error:
    return "error";
  }
  return "?";
}

std::optional<Mode> parse_mode(const std::string& s) {
  if (s == "exact") return Mode::Exact;
  if (s == "filtered") return Mode::Filtered;
  if (s == "float") return Mode::Float;
  return std::nullopt;
}

QsicResult classify_qsic(const core::QuadricMatrix& a, const core::QuadricMatrix& b, Mode mode) {
  QsicResult r;
  r.mode = mode;
  if (mode == Mode::Float) {
    FloatInvariants inv{};
    try {
      r.facts = analyze_pencil_float(a.matrix(), b.matrix(), inv);
    } catch (const std::domain_error& e) { // overflow to inf/nan in plain doubles
      r.status = Status::Undecided;
      r.note = std::string("float analysis failed: ") + e.what();
      return r;
    }
    r.float_invariants = inv;
    r.status = Status::Uncertified;
  } else {
    std::optional<PencilFacts> fast;
    if (mode == Mode::Filtered) fast = analyze_pencil_filtered(a.matrix(), b.matrix());
    if (fast) {
      r.facts = std::move(*fast);
    } else {
      r.exact_fallback = mode == Mode::Filtered;
      r.facts = algebra::analyze_pencil_exact(a.matrix(), b.matrix());
    }
    r.status = Status::Certified;
  }
  r.pencil = r.facts.kind;
  if (r.pencil != PencilKind::Regular) return r;
  try {
    r.tu_case = decide_tu_case(r.facts);
    r.morphology = &morphology_of_case(r.tu_case);
    r.segre = algebra::segre_from_facts(r.facts);
  } catch (const std::logic_error& e) {
    if (mode != Mode::Float) throw; // exact facts can never be inconsistent: our bug
    r.status = Status::Undecided;   // float facts contradict each other
    r.note = std::string("float analysis inconsistent: ") + e.what();
  }
  return r;
}

namespace {

// Sign of the real root in (lo, hi) of the square-free g (g(lo) g(hi) < 0).
int root_sign(const algebra::UPolyZ& g, const Rational& lo, const Rational& hi) {
  if (lo.sign() >= 0) return 1;
  if (hi.sign() <= 0) return -1;
  int s0 = g.sign_at(Rational(0));
  if (s0 == 0) return 0;
  return s0 == g.sign_at(lo) ? 1 : -1;
}

// (-det M)^3 / det(Q)^4 is proportional to the squared volume of the ellipsoid X^T M X <= 0
// (Q = upper 3x3 block, normalised positive definite).
Rational squared_volume_measure(const core::Mat4& m) {
  Rational d = core::det(m), q = core::leading_minor(m, 3);
  Rational nd = -d;
  return nd * nd * nd / (q * q * q * q);
}

void ellipsoid_relation(QsicResult& r, const core::QuadricMatrix& a, const core::QuadricMatrix& b) {
  if (a.kind() != core::QuadricKind::Ellipsoid || b.kind() != core::QuadricKind::Ellipsoid) return;
  if (r.pencil == PencilKind::Coincident) {
    r.ellipsoid_relation = "coincident";
    return;
  }
  // Normalise each matrix so that its quadratic block is positive definite (interior < 0);
  // the roots of the normalised det(lA - B) are eps * (roots of f), eps = sa * sb.
  int sa = a(0, 0).sign(), sb = b(0, 0).sign();
  int eps = sa * sb;
  // Two ellipsoids: det A != 0, so the facts are in the given basis (never re-based).
  algebra::UPolyZ fz = algebra::pencil_char_poly(a.matrix(), b.matrix()).primitive_integer();
  algebra::UPolyZ g, fd, h;
  fmpz_poly_derivative(fd.raw_mut(), fz.raw());
  fmpz_poly_gcd(h.raw_mut(), fz.raw(), fd.raw());
  fmpz_poly_div(g.raw_mut(), fz.raw(), h.raw());
  int negative_distinct = 0;
  bool negative_double = false;
  for (const auto& root : r.facts.real_roots) {
    int s = eps * root_sign(g, root.lo, root.hi);
    if (s < 0) {
      ++negative_distinct;
      if (root.multiplicity >= 2) negative_double = true;
    }
  }
  int c = r.tu_case;
  bool nested_possible = false;
  if (negative_distinct >= 2) {
    r.ellipsoid_relation = "separated";
  } else if (negative_double) {
    r.ellipsoid_relation = "externally_touching";
  } else if (c == 2 || c == 16 || c == 22) {
    r.ellipsoid_relation = "nested";
    nested_possible = true;
  } else if (c == 7 || c == 15 || c == 20 || c == 21 || c == 25 || c == 30 || c == 33) {
    r.ellipsoid_relation = "internally_touching";
    nested_possible = true;
  } else {
    r.ellipsoid_relation = "overlapping";
  }
  if (nested_possible) {
    core::Mat4 ma = sa < 0 ? core::scaled(a.matrix(), Rational(-1)) : a.matrix();
    core::Mat4 mb = sb < 0 ? core::scaled(b.matrix(), Rational(-1)) : b.matrix();
    r.containment =
        squared_volume_measure(ma) < squared_volume_measure(mb) ? "a_inside_b" : "b_inside_a";
  }
}

} // namespace

void complete_report_data(QsicResult& r, const core::QuadricMatrix& a,
                          const core::QuadricMatrix& b) {
  if (r.pencil != PencilKind::Regular) return;
  if (r.mode == Mode::Filtered && !r.exact_fallback) {
    r.facts.a = a.matrix(); // the filter does not copy the matrices
    r.facts.b = b.matrix();
  }
  if (r.mode != Mode::Float && !r.facts.invariants_filled) complete_exact_invariants(r.facts);
  if (r.mode != Mode::Float && r.status == Status::Certified) {
    ellipsoid_relation(r, a, b);
    r.special_points = special_points(r.facts, r.tu_case, r.special_points_complete);
    r.special_points_done = true;
  }
}

} // namespace surfcert::certify
