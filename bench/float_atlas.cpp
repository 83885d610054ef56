// The float-failure atlas: how often surfcert's float mode (seed 002's tolerance 1e-8) and a
// sweep of its tolerance answer a wrong Tu case, as a function of the distance 2^-k to a
// degeneracy, per degeneracy family of `surfcert generate` (app/generate.hpp).
//
// Every point of every family path (g = +-2^-k and 0, K random poses each) is labelled by the
// certified classifier; the float analysis (certify/pencil_filter.hpp) with each tolerance is
// wrong when its case (or pencil kind) differs from the label, or when it fails. Encodings:
// double (the float analysis reads exactly the labelled surface: every error is the method's)
// and exact (general rational poses: the input is first rounded to doubles, as a float user's
// would be).
// Usage: float_atlas [poses=20] [seed=1] [kmax=60] > bench/results/float_atlas.csv
// (one CSV row per family, encoding, side, k, tolerance: wrong / total).
#include "surfcert/app/generate.hpp"
#include "surfcert/certify/pencil_filter.hpp"
#include "surfcert/certify/qsic_rules.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <tuple>
#include <vector>

using namespace surfcert;

int main(int argc, char** argv) {
  const long poses = argc > 1 ? std::atol(argv[1]) : 20;
  const unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 1;
  const int kmax = argc > 3 ? std::atoi(argv[3]) : 60;
  const std::vector<double> tols = {1e-6, 1e-8, 1e-10, 1e-12, 1e-14};
  std::vector<int> gaps;
  for (int k = 2; k <= kmax; k += 2)
    gaps.push_back(k);
  // (family, encoding, sign, k, tol) -> (wrong, total)
  std::map<std::tuple<std::string, std::string, int, int, double>, std::pair<long, long>> cells;
  for (const char* family : {"tangency", "node", "acnode", "cusp", "double_conic"})
    for (app::Encoding enc : {app::Encoding::Double, app::Encoding::Exact}) {
      app::GenerateRequest r;
      r.family = family;
      r.gaps = gaps;
      r.count = poses;
      r.seed = seed;
      r.encoding = enc;
      r.threads = 2;
      for (const core::io::Json& line : app::generate(r)) {
        const core::io::Json& label = *line.find("label");
        if (label.find("status")->text() != "certified") continue;
        const std::string want = label.find("tu_case")->text();
        const core::io::Json& gap = *label.find("construction")->find("gap");
        const int sign = std::atoi(gap.find("sign")->text().c_str());
        const int k = sign == 0 ? 0 : std::atoi(gap.find("k")->text().c_str());
        const auto a = core::io::read_quadric(*line.find("a"), "<atlas>", "$.a");
        const auto b = core::io::read_quadric(*line.find("b"), "<atlas>", "$.b");
        for (double tol : tols) {
          std::string got = "failed";
          try {
            certify::FloatInvariants inv{};
            const algebra::PencilFacts f = certify::analyze_pencil_float(a, b, inv, tol);
            got = f.kind == algebra::PencilKind::Regular
                      ? std::to_string(certify::decide_tu_case(f))
                      : "not_regular";
          } catch (const std::exception&) {
          }
          auto& cell = cells[{family, app::to_string(enc), sign, k, tol}];
          cell.first += got == want ? 0 : 1;
          cell.second += 1;
        }
      }
    }
  std::printf("family,encoding,side,k,tolerance,wrong,total\n");
  for (const auto& [key, v] : cells) {
    const auto& [family, enc, sign, k, tol] = key;
    std::printf("%s,%s,%s,%d,%g,%ld,%ld\n", family.c_str(), enc.c_str(),
                sign < 0   ? "minus"
                : sign > 0 ? "plus"
                           : "zero",
                k, tol, v.first, v.second);
  }
  return 0;
}
