// route_timing: median time of one certified distance per route added in sessions 4 and 5
// (plane and cylinder closed forms, paraboloid duality, coaxial tori, the seed pair with its tie
// proof, the sphere-family branch and bound; implicit branch and bound against an ellipsoid and
// a clipped cylinder, parallel cylinder sections, a common apex, proper conics at infinity), at
// 15 and 100 digits, 7 runs each. Prints a Markdown table (a progress line per case on
// stderr). Run: build/bench/route_timing
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>
using namespace surfcert;
core::Surface S(const char* s) {
  if (s[0] == '{') return core::io::read_surface(core::io::parse_json(s, "a"), "a", "$");
  return core::io::read_surface(core::io::Json::string(s), "t", "$"); // quadric or implicit
}
int main() {
  const char* cases[][3] = {
      {"plane-paraboloid", "2x - z = 5", "x^2 + y^2 - z = 0"},
      {"plane-hyperboloid2 tie", "z = 0", "x^2 + y^2 - z^2 = -1"},
      {"crossed cylinders", "x^2/4 + y^2 = 1", "(y - 6)^2/9 + (x + z)^2/2 = 1"},
      {"paraboloid pair", "x^2 + y^2 - z = 0", "(x-5)^2 + y^2 + z = 0"},
      {"coaxial tori",
       "{\"type\": \"torus\", \"center\": [0, 0, 0], \"axis\": [0, 0, 1], \"major_radius\": 3, "
       "\"minor_radius\": \"1/2\"}",
       "{\"type\": \"torus\", \"center\": [0, 0, 5], \"axis\": [0, 0, 1], \"major_radius\": 2, "
       "\"minor_radius\": \"1/2\"}"},
      {"seed pair (tie proof)", "x^2 + y^2/4 + (z+3)^2/9 = 1", "x^2/4 + y^2/9 + z^2/49 = 1"},
      {"canal-torus",
       "{\"type\": \"torus\", \"center\": [0, 0, 0], \"axis\": [0, 0, 1], \"major_radius\": 3, "
       "\"minor_radius\": 1}",
       "{\"type\": \"canal\", \"spine\": [[0, 1], [0, 0, \"1/2\"], [4, \"1/3\"]], \"radius\": "
       "[\"1/4\", 0, \"1/8\"], \"interval\": [-1, 2]}"},
      {"quartic-ellipsoid", "x^4 + y^4 + z^4 + x y = 2", "(x-3)^2 + (y-1)^2/4 + (z-1/2)^2 = 1"},
      {"quartic-tilted cylinder", "x^4 + y^4 + z^4 + x y = 2",
       "(x-3)^2 + y^2 + z^2 - ((x-3) + y + 2z)^2/6 = 1"},
      {"hyperbolic-circular cylinders", "x^2 - y^2 = 1", "(x-3)^2 + y^2 = 1"},
      {"cones with one apex", "x^2 + y^2 - z^2 = 0", "4x^2 + y^2 - z^2 = 0"},
      {"hyperboloid2-cone", "x^2 + y^2 - z^2/100 = -1", "y^2 + (z - 3)^2 - (x - 4)^2/100 = 0"},
  };
  std::printf("| pair | digits | median | method | lower |\n|---|---|---|---|---|\n");
  for (auto& c : cases) {
    std::fprintf(stderr, "%s ...\n", c[0]);
    auto a = S(c[1]), b = S(c[2]);
    for (long dg : {15L, 100L}) {
      std::vector<double> ts;
      certify::DistanceResult r;
      for (int k = 0; k < 7; ++k) {
        auto t0 = std::chrono::steady_clock::now();
        r = certify::surface_distance(a, b, dg, false);
        ts.push_back(
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0)
                .count());
      }
      std::sort(ts.begin(), ts.end());
      std::printf("| %s | %ld | %.0f us | %s | %s |\n", c[0], dg, ts[3],
                  certify::to_string(r.method), r.lower().substr(0, 20).c_str());
    }
  }
}
