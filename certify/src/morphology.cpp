#include "surfcert/certify/morphology.hpp"

#include <stdexcept>

namespace surfcert::certify {

namespace {
// clang-format off
// case, id, segre, description,
//   loops, points, lines, conics, cubics, double, connected, ellipsoid, reconstructed
const Morphology kTable[35] = {
  {1, "two_ovals", "[1111]", "smooth quartic with two disjoint real ovals", 2,0,0,0,0,0, 2, true, false},
  {2, "empty_smooth_quartic", "[1111]", "smooth quartic without real points (a definite member exists)", 0,0,0,0,0,0, 0, true, false},
  {3, "one_oval", "[1111]", "smooth quartic with one real oval", 1,0,0,0,0,0, 1, true, false},
  {4, "two_unbounded_branches", "[1111]", "smooth quartic with two real components, each meeting every plane (affinely unbounded)", 2,0,0,0,0,0, 2, false, false},
  {5, "figure_eight", "[211]", "nodal quartic: two loops joined at a real crunode (figure eight)", 1,0,0,0,0,0, 1, true, false},
  {6, "oval_and_acnode", "[211]", "nodal quartic: one real oval and an isolated singular point (acnode)", 1,1,0,0,0,0, 2, true, false},
  {7, "acnode_only", "[211]", "nodal quartic whose only real point is the acnode (one point)", 0,1,0,0,0,0, 1, true, false},
  {8, "crunode_unbounded_branches", "[211]", "nodal quartic: two branches meeting every plane, joined at a real crunode", 1,0,0,0,0,0, 1, false, false},
  {9, "cuspidal_loop", "[31]", "cuspidal quartic: one loop with a real cusp", 1,0,0,0,0,0, 1, true, false},
  {10, "cubic_and_secant_line", "[22]", "twisted cubic and a line meeting it in two real points", 0,0,1,0,1,0, 1, false, false},
  {11, "cubic_and_disjoint_line", "[22]", "twisted cubic and a line meeting it in two complex points (two disjoint real components)", 0,0,1,0,1,0, 2, false, false},
  {12, "cubic_and_tangent_line", "[4]", "twisted cubic and a line tangent to it", 0,0,1,0,1,0, 1, false, false},
  {13, "two_conics_crossing", "[(11)11]", "two real conics crossing in two real points (projectively bounded: some plane misses both; the affine reading may still be unbounded)", 0,0,0,2,0,0, 1, true, true},
  {14, "two_disjoint_conics", "[(11)11]", "two disjoint real conics (they meet in complex points)", 0,0,0,2,0,0, 2, true, true},
  {15, "two_points_imaginary_conics", "[(11)11]", "two imaginary conics meeting in two real points: two isolated points", 0,2,0,0,0,0, 2, true, true},
  {16, "empty_imaginary_conics", "[(11)11]", "two imaginary conics meeting in complex points: empty", 0,0,0,0,0,0, 0, true, true},
  {17, "one_conic", "[(11)11]", "one real conic (the other conic is imaginary)", 0,0,0,1,0,0, 1, true, false},
  {18, "two_conics_crossing_unbounded", "[(11)11]", "two real conics crossing in two real points (affinely unbounded)", 0,0,0,2,0,0, 1, false, false},
  {19, "two_tangent_conics", "[(21)1]", "two real conics tangent at one real point", 0,0,0,2,0,0, 1, true, true},
  {20, "point_tangent_imaginary_conics", "[(21)1]", "two imaginary conics tangent at a real point: one point", 0,1,0,0,0,0, 1, true, true},
  {21, "double_conic", "[(111)1]", "a real conic counted twice: the surfaces are tangent along it", 0,0,0,1,0,1, 1, true, true},
  {22, "empty_imaginary_double_conic", "[(111)1]", "an imaginary conic counted twice: empty", 0,0,0,0,0,0, 0, true, true},
  {23, "conic_and_two_lines", "[2(11)]", "a real conic and two real lines crossing off the conic, each meeting it", 0,0,2,1,0,0, 1, false, false},
  {24, "conic_and_point", "[2(11)]", "a real conic and an isolated point (where two imaginary lines cross)", 0,1,0,1,0,0, 2, true, true},
  {25, "point_imaginary_conic_and_lines", "[2(11)]", "an imaginary conic and two imaginary lines: one real point", 0,1,0,0,0,0, 1, true, true},
  {26, "conic_and_two_lines_crossing_on_it", "[(31)]", "a real conic and two real lines crossing each other on the conic", 0,0,2,1,0,0, 1, false, false},
  {27, "conic_with_tangency_point", "[(31)]", "a real conic and two imaginary lines crossing on it: one conic through a point of tangency", 0,0,0,1,0,0, 1, true, false},
  {28, "four_lines", "[(11)(11)]", "four real lines forming a skew quadrilateral", 0,0,4,0,0,0, 1, false, true},
  {29, "empty_imaginary_lines", "[(11)(11)]", "four imaginary lines without a real vertex: empty", 0,0,0,0,0,0, 0, false, true},
  {30, "two_points_imaginary_lines", "[(11)(11)]", "four imaginary lines with two real vertices: two points", 0,2,0,0,0,0, 2, true, false},
  {31, "two_skew_lines", "[(11)(11)]", "two real skew lines (and two imaginary lines)", 0,0,2,0,0,0, 2, false, false},
  {32, "two_double_lines", "[(211)]", "two real lines, each counted twice, meeting in a point", 0,0,2,0,0,2, 1, false, false},
  {33, "point_imaginary_double_lines", "[(211)]", "two imaginary double lines meeting in a real point: one point", 0,1,0,0,0,0, 1, true, false},
  {34, "double_line", "[(22)]", "a real line counted twice (the two other lines are imaginary)", 0,0,1,0,0,1, 1, false, false},
  {35, "double_line_and_two_lines", "[(22)]", "a real double line and two real skew lines meeting it", 0,0,3,0,0,1, 1, false, false},
};
// clang-format on
} // namespace

const Morphology& morphology_of_case(int tu_case) {
  if (tu_case < 1 || tu_case > 35) throw std::out_of_range("Tu case must be 1..35");
  return kTable[tu_case - 1];
}

const Morphology* morphology_by_id(const std::string& id) {
  for (const auto& m : kTable)
    if (id == m.id) return &m;
  return nullptr;
}

} // namespace surfcert::certify
