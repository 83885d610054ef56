#include "surfcert/certify/distance/plane_pair_distance.hpp"

#include "surfcert/certify/affine.hpp"

#include "surfcert/algebra/arb.hpp"

namespace surfcert::certify {

std::optional<DistanceResult> plane_pair_distance(const core::QuadricMatrix& pair,
                                                  const core::QuadricMatrix& other, bool pair_is_a,
                                                  long digits, Mode mode) {
  if (pair.is_plane() || other.is_plane()) return std::nullopt;
  const auto planes = rational_plane_pair(pair.matrix());
  if (!planes) return std::nullopt;
  for (const auto& n : *planes)
    if (n[0].is_zero() && n[1].is_zero() && n[2].is_zero()) return std::nullopt; // at infinity
  if (rational_plane_pair(other.matrix())) return std::nullopt; // two plane pairs: not here
  // Each plane against the other quadric, oriented as the query (plane where the pair is).
  DistanceResult r[2];
  for (size_t k = 0; k < 2; ++k) {
    const core::QuadricMatrix plane(plane_as_quadric((*planes)[k]));
    r[k] = pair_is_a ? surface_distance(plane, other, digits, false, mode)
                     : surface_distance(other, plane, digits, false, mode);
  }
  DistanceResult out;
  out.method = Method::PlanePairMin;
  out.critical_candidates = r[0].critical_candidates + r[1].critical_candidates;
  const bool both = r[0].distance && r[1].distance;
  auto below = [&r](size_t i, size_t j) { // d_i < d_j proven
    return r[i].distance && r[j].distance &&
           arf_cmp(r[i].distance->upper_arf(), r[j].distance->lower_arf()) < 0;
  };
  for (size_t i = 0; i < 2; ++i)
    if (r[i].status == Status::Certified && below(i, 1 - i)) {
      // The other plane is farther, certified or not: its lower bound is above this minimum.
      out = r[i];
      out.method = Method::PlanePairMin;
      out.note = "a plane pair: the nearer plane (proven nearer by its enclosure)" +
                 std::string(r[i].note.empty() ? "" : "; " + r[i].note);
      return out;
    }
  if (r[0].status == Status::Certified && r[1].status == Status::Certified && both) {
    out.status = Status::Certified;
    out.distance = Enclosure::min_of(*r[0].distance, *r[1].distance);
    out.pairs = r[0].pairs;
    out.pairs.insert(out.pairs.end(), r[1].pairs.begin(), r[1].pairs.end());
    if (r[0].distance->is_zero() && r[1].distance->is_zero()) {
      // Parallel planes share no point: their contact points add up. Crossing planes may
      // share one on their common line (not decided here).
      const auto& n0 = (*planes)[0];
      const auto& n1 = (*planes)[1];
      const bool parallel = (n0[1] * n1[2] - n0[2] * n1[1]).is_zero() &&
                            (n0[2] * n1[0] - n0[0] * n1[2]).is_zero() &&
                            (n0[0] * n1[1] - n0[1] * n1[0]).is_zero();
      if (r[0].minimizers.is_continuum() || r[1].minimizers.is_continuum())
        out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
      else if (parallel && r[0].minimizers.is_count() && r[1].minimizers.is_count())
        out.minimizers =
            Minimizers::count(r[0].minimizers.value() + r[1].minimizers.value(),
                              r[0].minimizers.proof() == Minimizers::Proof::Exact &&
                                      r[1].minimizers.proof() == Minimizers::Proof::Exact
                                  ? Minimizers::Proof::Exact
                                  : Minimizers::Proof::Interval);
      else
        out.minimizers = Minimizers::undecided(static_cast<long>(out.pairs.size()));
      out.note = "a plane pair: both planes meet the other surface";
      return out;
    }
    out.minimizers = Minimizers::undecided(static_cast<long>(out.pairs.size()));
    out.ties = Ties::Unproven;
    out.note = "a plane pair: both planes at the same distance to the requested precision (the "
               "minimum of the two enclosures; their equality, and so the count, not proven)";
    return out;
  }
  // Some plane undecided: what holds for the minimum (each bound needs both planes' bounds).
  out.status = Status::Undecided;
  if (both) out.distance = Enclosure::min_of(*r[0].distance, *r[1].distance);
  out.note = "a plane pair: the distance to one plane was not decided (" +
             (r[0].status == Status::Certified ? r[1].note : r[0].note) + ")";
  return out;
}

} // namespace surfcert::certify
