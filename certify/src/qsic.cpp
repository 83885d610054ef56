#include "surfcert/certify/qsic.hpp"

#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/segre.hpp"
#include "surfcert/certify/ellipsoid_relation.hpp"
#include "surfcert/certify/qsic_rules.hpp"
#include "surfcert/certify/special_points.hpp"

#include <algorithm>
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

namespace {

// The filter does not copy the matrices (no big-number copies on its fast path): the facts'
// a and b, in their basis (re-based like the exact path's: a' = t A - B, b' = -A), on first need.
// The pencil basis of the facts from the pair's matrices, under the facts' re-basing.
void set_basis(algebra::PencilFacts& f, const core::QuadricMatrix& a,
               const core::QuadricMatrix& b) {
  if (f.rebased) {
    const Rational t(f.rebase_t);
    core::Mat4 ra, rb;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        ra[i][j] = t * a.matrix()[i][j] - b.matrix()[i][j];
        rb[i][j] = -a.matrix()[i][j];
      }
    f.a = ra;
    f.b = rb;
  } else {
    f.a = a.matrix();
    f.b = b.matrix();
  }
}

void fill_filtered_matrices(QsicResult& r, const core::QuadricMatrix& a,
                            const core::QuadricMatrix& b) {
  if (r.mode != Mode::Filtered || r.exact_fallback || r.matrices_filled) return;
  set_basis(r.facts, a, b);
  r.matrices_filled = true;
}

} // namespace

QsicResult classify_qsic(const core::QuadricMatrix& a, const core::QuadricMatrix& b, Mode mode) {
  QsicResult r;
  r.mode = mode;
  if (mode == Mode::Float) {
    FloatInvariants inv{};
    try {
      r.facts = analyze_pencil_float(a, b, inv);
    } catch (const std::domain_error& e) { // overflow to inf/nan in plain doubles
      r.status = Status::Undecided;
      r.note = std::string("float analysis failed: ") + e.what();
      return r;
    }
    r.float_invariants = inv;
    r.status = Status::Uncertified;
  } else {
    // The filter writes into r.facts (no moves of the facts' exact members on the fast path).
    if (!(mode == Mode::Filtered && analyze_pencil_filtered(a, b, r.facts))) {
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

QsicResult translated_classification(const QsicResult& r, const core::QuadricMatrix& a2,
                                     const core::QuadricMatrix& b2) {
  if (r.mode == Mode::Float || r.pencil != PencilKind::Regular)
    return classify_qsic(a2, b2, Mode::Filtered); // (as the tracer did before)
  QsicResult out = r;
  out.special_points.clear();
  out.special_points_complete = true;
  out.special_points_done = false;
  // Filtered facts without their matrices get the moved pair's on demand
  // (fill_filtered_matrices); matrices already present are replaced by the moved ones.
  if (r.mode != Mode::Filtered || r.exact_fallback || r.matrices_filled)
    set_basis(out.facts, a2, b2);
  return out;
}

void complete_special_points(QsicResult& r, const core::QuadricMatrix& a,
                             const core::QuadricMatrix& b) {
  if (r.special_points_done || r.pencil != PencilKind::Regular || r.mode == Mode::Float ||
      r.status != Status::Certified)
    return;
  // Special points sit on the singular members at multiple real roots: with only simple real
  // roots there are none, and a curve without conics needs no exact matrices at all (for
  // shapes posed in doubles they are never formed then).
  const bool multiple = std::any_of(r.facts.real_roots.begin(), r.facts.real_roots.end(),
                                    [](const auto& rt) { return rt.multiplicity >= 2; });
  if (!multiple && (!r.morphology || r.morphology->conics == 0)) {
    r.special_points.clear();
    r.special_points_complete = true;
    r.special_points_done = true;
    return;
  }
  fill_filtered_matrices(r, a, b);
  r.special_points = special_points(r.facts, r.tu_case, r.special_points_complete);
  r.special_points_done = true;
}

void complete_report_data(QsicResult& r, const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                          Detail detail) {
  if (r.pencil != PencilKind::Regular) return;
  // The relation of two ellipsoids is part of every level (cheap: ellipsoid_relation.hpp);
  // from float facts it is an estimate, like the rest of a float answer.
  if (r.status == Status::Certified || (r.mode == Mode::Float && r.status == Status::Uncertified))
    if (r.ellipsoid_relation.empty()) ellipsoid_relation(r, a, b);
  if (detail < Detail::Certificate || r.mode == Mode::Float) return;
  fill_filtered_matrices(r, a, b);
  if (!r.facts.invariants_filled) complete_exact_invariants(r.facts);
  if (detail == Detail::Full) complete_special_points(r, a, b);
}

} // namespace surfcert::certify
