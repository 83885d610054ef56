// surfcert::certify::Morphology: the 35 real morphologies of the intersection curve (QSIC) of
// a regular pencil of quadrics (Tu, Wang, Mourrain, Wang 2009; research qsic-classification §2).
//
// Each entry has a stable string identifier (the contract key; never renumbered), the Tu case
// number as a label (inside {13-16}, {19-22}, {24,25}, {28,29} the numbers are a reconstruction,
// flagged by label_reconstructed), the Segre characteristic, a sentence, and the counts of
// real components by kind in real projective space (equal to the affine ones whenever one
// quadric is an ellipsoid). Counting conventions: a figure-eight, a cuspidal loop or two
// branches joined at a node count as one loop; a double conic counts as one conic and one
// double component; isolated points are counted separately from curves.
#pragma once

#include <string>

namespace surfcert::certify {

struct Morphology {
  int tu_case;
  const char* id;
  const char* segre;
  const char* description;
  int loops; ///< quartic branches (smooth or singular closed curves)
  int isolated_points;
  int lines;
  int conics;
  int cubics;
  int double_components;
  int connected_components; ///< in real projective space
  bool ellipsoid_possible;  ///< one of the 21 cases possible for two ellipsoids
  bool label_reconstructed; ///< the Tu number inside its group is a reconstruction
};

/// Entry for Tu case 1..35; throws std::out_of_range otherwise.
const Morphology& morphology_of_case(int tu_case);
/// Entry by identifier; nullptr when unknown.
const Morphology* morphology_by_id(const std::string& id);

} // namespace surfcert::certify
