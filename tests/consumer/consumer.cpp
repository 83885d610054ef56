// Uses the installed API: two spheres 3 apart with radii 1 and 1/2 -> a distance of exactly
// 3/2, proven; prints the JSON and exits 0 only when the typed answer says so.
#include <surfcert/surfcert.hpp>

#include <iostream>

int main() {
  const surfcert::Surface a = surfcert::Surface::parse("x^2 + y^2 + z^2 = 1");
  const surfcert::Surface b = surfcert::Surface::from_shape("sphere", {3, 0, 0}, {0.5, 0.5, 0.5});
  const surfcert::Distance d = surfcert::distance(a, b);
  std::cout << surfcert::core::io::dump(d.to_json()) << "\n";
  const bool ok = d.status() == surfcert::Status::Certified && d.result.lower() == "1.5" &&
                  d.result.upper() == "1.5";
  return ok ? 0 : 1;
}
