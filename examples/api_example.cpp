// The embedding API in one page (surfcert/surfcert.hpp): surfaces from an equation, a posed
// shape in doubles and a 4x4 matrix of rationals; classify, intersect, distance and verify;
// the typed answers, and one answer's JSON (the batch line's). Run: build/examples/api_example
#include <surfcert/surfcert.hpp>

#include <iostream>

int main() try {
  using namespace surfcert;
  const Surface sphere = Surface::parse("x^2 + y^2 + z^2 = 1");
  const Surface ellipsoid =
      Surface::from_shape("ellipsoid", {0.3, 0.2, -0.1}, {0.6, 0.6, 0.9},
                          std::array<double, 4>{0.9238795325112867, 0.3826834323650898, 0, 0});
  // (x - 3)^2 + y^2 + z^2 = 1/4 as an exact matrix.
  const Rational o(0), one(1);
  const Surface small = Surface::from_matrix(
      std::array<std::array<Rational, 4>, 4>{{{one, o, o, Rational(-3)},
                                              {o, one, o, o},
                                              {o, o, one, o},
                                              {Rational(-3), o, o, Rational(35, 4)}}});

  Options topo;
  topo.detail = Detail::Topology;
  const Classification c = classify(sphere, ellipsoid, topo);
  std::cout << "classify: " << certify::to_string(c.status()) << ", morphology "
            << c.qsic.morphology->id << ", Segre " << c.qsic.segre << "\n";

  const Intersection x = intersect(sphere, ellipsoid);
  std::cout << "intersect: " << certify::to_string(x.status()) << ", " << x.curve.branches.size()
            << " branch(es)";
  for (const auto& b : x.curve.branches)
    std::cout << " " << b.kind << "(" << b.points.size() << " points)";
  std::cout << "\n";

  Options d30;
  d30.digits = 30;
  const Distance d = distance(sphere, small, d30);
  std::cout << "distance: " << certify::to_string(d.status()) << " in [" << d.result.lower() << ", "
            << d.result.upper() << "], minimizers " << d.result.minimizers << " ("
            << d.result.minimizers.proof_str() << "), method "
            << certify::to_string(d.result.method) << "\n";

  const Verification v = verify(
      sphere, small,
      core::io::parse_json(R"([{"kind":"distance","value":1.5,"abs_tol":1e-9}])", "<claims>"));
  std::cout << "verify: " << certify::to_string(v.status()) << ", claim 1 "
            << v.verdicts.find("result")->find("verdicts")->items()[0].find("verdict")->text()
            << "\n";
  std::cout << "classify as JSON: " << core::io::dump(c.to_json()) << "\n";
  return 0;
} catch (const surfcert::InputError& e) {
  std::cerr << "input error: " << e.what() << "\n";
  return 2;
}
