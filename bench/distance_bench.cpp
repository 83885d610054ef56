// distance_bench: median time per certified distance, sphere vs random ellipsoid (the first
// capability of the distance issue), at several precisions, and the time per extra digit.
// Usage: distance_bench [pairs=2000] [seed=2026]
#include "random_ellipsoids.hpp"

#include "surfcert/certify/distance/distance.hpp"

#include <flint/flint.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

using namespace surfcert;

int main(int argc, char** argv) {
  long pairs = argc > 1 ? std::atol(argv[1]) : 2000;
  unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2026;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<long> c(-3000, 3000), r(10, 100);
  std::vector<std::pair<core::QuadricMatrix, core::QuadricMatrix>> in;
  for (long i = 0; i < pairs; ++i) {
    auto e = bench::random_ellipsoid(rng).quadric;
    core::Rational cx(c(rng), 1000), cy(c(rng), 1000), cz(c(rng), 1000), rad(r(rng), 100);
    core::Mat4 m;
    m[0][0] = m[1][1] = m[2][2] = core::Rational(1);
    m[0][3] = m[3][0] = -cx;
    m[1][3] = m[3][1] = -cy;
    m[2][3] = m[3][2] = -cz;
    m[3][3] = cx * cx + cy * cy + cz * cz - rad * rad;
    in.emplace_back(core::QuadricMatrix(m), e);
  }
  std::printf("## Sphere vs ellipsoid certified distance (distance_bench %ld %lu)\n\n", pairs,
              seed);
  std::printf("| digits | median us | mean us | certified | undecided | distance 0 "
              "|\n|---|---|---|---|---|---|\n");
  double med15 = 0, med100 = 0;
  for (long digits : {15L, 100L, 300L}) {
    std::vector<double> t;
    long cert = 0, und = 0, zero = 0;
    for (const auto& [a, b] : in) {
      auto t0 = std::chrono::steady_clock::now();
      auto d = certify::surface_distance(a, b, digits, false);
      auto t1 = std::chrono::steady_clock::now();
      t.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
      cert += d.status == certify::Status::Certified;
      und += d.status == certify::Status::Undecided;
      zero += d.upper() == "0";
    }
    double mean = 0;
    for (double x : t)
      mean += x;
    mean /= static_cast<double>(t.size());
    std::nth_element(t.begin(), t.begin() + static_cast<long>(t.size() / 2), t.end());
    double med = t[t.size() / 2];
    if (digits == 15) med15 = med;
    if (digits == 100) med100 = med;
    std::printf("| %ld | %.1f | %.1f | %ld | %ld | %ld |\n", digits, med, mean, cert, und, zero);
    std::fprintf(stderr, "digits %ld done\n", digits);
  }
  std::printf("\ntime per extra digit (15 -> 100, medians): %.2f us\n", (med100 - med15) / 85);
  flint_cleanup();
  return 0;
}
