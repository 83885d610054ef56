// surfcert::certify::classify_qsic: the certified topology of the intersection of two quadrics.
//
// What a QsicResult represents: the morphology (one of 35, morphology.hpp) of the real
// intersection curve of two quadrics, the pencil facts that decide it, and how certain it is.
// Invariants: status Certified only when every sign used was decided exactly (mode exact) or
// by an interval filter that proved it (mode filtered; otherwise the exact path ran and
// exact_fallback is true). Mode float never yields Certified (status Uncertified).
// Degenerate pencils (det(lA - B) == 0) and coincident quadrics are certified outcomes of
// their own (pencil != Regular, tu_case == 0), never errors.
#pragma once

#include "surfcert/algebra/pencil.hpp"
#include "surfcert/certify/detail.hpp"
#include "surfcert/certify/morphology.hpp"
#include "surfcert/certify/pencil_filter.hpp"
#include "surfcert/core/quadric.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace surfcert::certify {

enum class Mode { Exact, Filtered, Float };
enum class Status { Certified, Undecided, Uncertified, Error };

const char* to_string(Mode m);
const char* to_string(Status s);
std::optional<Mode> parse_mode(const std::string& s);

/// A real singular or tangency point of the QSIC, exact when `exact` is set.
struct SpecialPoint {
  std::string kind;                  ///< "node", "acnode", "cusp", "crossing", "contact", ...
  bool exact = false;                ///< coordinates below are exact
  bool at_infinity = false;          ///< projective point with w = 0 (direction given)
  std::array<std::string, 3> coords; ///< exact text (rational or a + b*sqrt(d))
  std::array<double, 3> approx{};    ///< decimal approximations
  /// The exact coordinates as numbers of one field Q(sqrt d) (before normalisation), where
  /// they were computed so (points at conjugate roots); unset otherwise: read `coords`.
  std::optional<std::array<algebra::QuadraticNumber, 3>> numbers;
};

struct QsicResult {
  Status status = Status::Error;
  Mode mode = Mode::Filtered;
  algebra::PencilKind pencil = algebra::PencilKind::Regular;
  int tu_case = 0;
  const Morphology* morphology = nullptr;
  std::string segre;
  algebra::PencilFacts facts;                      ///< exact (or, in float mode, approximate) facts
  bool exact_fallback = false;                     ///< filtered mode needed exact arithmetic
  std::optional<FloatInvariants> float_invariants; ///< float mode only
  std::string note;                                ///< why undecided / error
  std::string ellipsoid_relation; ///< empty unless both quadrics are real ellipsoids
  std::string containment;        ///< "a_inside_b" / "b_inside_a" when nested/touching inside
  std::vector<SpecialPoint> special_points;
  bool special_points_complete = true; ///< false when some were not computed exactly
  bool special_points_done = false;    ///< special_points has been filled
  bool matrices_filled = false;        ///< facts.a, facts.b copied (filtered facts lack them)
};

/// Decision only (what the benchmark times): pencil facts, Tu case, Segre characteristic.
QsicResult classify_qsic(const core::QuadricMatrix& a, const core::QuadricMatrix& b, Mode mode);

/// The classification of the pair moved by a translation T (a2 = T^T A T, b2 = T^T B T, with r
/// the certified or undecided classification of (A, B)), without deciding anything again: a
/// congruence of determinant 1 leaves det(l A - B) and every fact of the pencil (roots, ranks,
/// inertias, indices, invariants, Segre symbol, Tu case, ellipsoid relation) unchanged. Only
/// the basis matrices are coordinates: those of r (exact facts carry them) are replaced by the
/// moved pair's, under the same re-basing; the special points are left to be recomputed there
/// (complete_special_points). Float facts are classified again. The tracer moves far pairs
/// so; classified again there, a pair needing exact arithmetic paid it twice (a coaxial cone
/// and cylinder posed in doubles: 60% of its time).
QsicResult translated_classification(const QsicResult& r, const core::QuadricMatrix& a2,
                                     const core::QuadricMatrix& b2);

/// What a report at `detail` shows beyond the decision (detail.hpp), and nothing more:
/// - every level: the ellipsoid relation and containment (certified from certified facts, an
///   estimate from float facts; ellipsoid_relation.hpp);
/// - Certificate: the exact f and invariants (filtered facts carry neither);
/// - Full: the special points.
/// Idempotent; a later call at a higher level adds what the lower one left out.
void complete_report_data(QsicResult& r, const core::QuadricMatrix& a, const core::QuadricMatrix& b,
                          Detail detail = Detail::Full);

/// The special points alone (certified regular pencils; what the tracer needs), without the
/// exact invariants. Idempotent.
void complete_special_points(QsicResult& r, const core::QuadricMatrix& a,
                             const core::QuadricMatrix& b);

} // namespace surfcert::certify
