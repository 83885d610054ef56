// The float-failure atlas: how often float methods answer wrong as a function of the distance
// 2^-k to a degeneracy, per degeneracy family of `surfcert generate` (app/generate.hpp):
// surfcert's float mode (seed 002's tolerance 1e-8 and a sweep of it) and, where they can read
// the family, the peers: Open CASCADE GeomAPI_IntSS (curve branch counts, on the classify
// families: all are ellipsoid pairs) and FCL (collide / distance, on the distance families).
//
// Every point of every family path (g = +-2^-k and 0, K random poses each) carries the
// certified label. A method is *wrong* when it answers something else, and *gives up* when it
// says it cannot answer (the float mode's "inconsistent" undecided, a peer's exception):
//   classify families: the float analysis (certify/pencil_filter.hpp) per tolerance gets the
//     Tu case (or pencil kind) of the label; GeomAPI_IntSS's branches, joined where their ends
//     meet (glued_branches), equal the label's curve components (connected components minus
//     isolated points: an isolated point is no curve to return).
//   distance families: the verdict (surfaces meet: certified upper bound 0) and, when apart,
//     the distance within 1% of the certified one; surfcert's float distance mode (batch line,
//     mode float) and FCL's distance (libccd GJK, default tolerance 1e-6; FCL reads the shapes
//     as solids: for the nested family the solids overlap although the surfaces do not meet,
//     so FCL answers another question there).
// Encodings: double (every number a binary64 with its exact value: the float mode reads exactly
// the labelled surface) and exact (general rational poses rounded to doubles). The peers read
// the double encoding only; they get each ellipsoid as centre, radii and rotation computed in
// double from the matrices (classify families: radii like sqrt(3)/2 are not binary64, so the
// peer's surface is within ~1e-16 relative of the labelled one) or from the shape (distance
// families: exact).
// Usage: float_atlas [poses=20] [seed=1] [kmax=60] [peer_poses=5]
//   > bench/results/float_atlas.csv
// (one CSV row per family, encoding, side, k, method: wrong, gave_up, total).
#include "surfcert/algebra/eigen4.hpp"
#include "surfcert/app/generate.hpp"
#include "surfcert/app/scene.hpp"
#include "surfcert/certify/enclosure.hpp"
#include "surfcert/certify/morphology.hpp"
#include "surfcert/certify/pencil_filter.hpp"
#include "surfcert/certify/qsic_rules.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "ellipsoid_params.hpp"
#ifdef SURFCERT_HAVE_OCCT
#include "occt_peer.hpp"
#endif
#ifdef SURFCERT_HAVE_FCL
#include "fcl_peer.hpp"
#endif

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

using namespace surfcert;
using core::io::Json;

namespace {

struct Cell {
  long wrong = 0, gave_up = 0, total = 0;
};
// (family, encoding, side sign, k, method) -> counts
using Cells = std::map<std::tuple<std::string, std::string, int, int, std::string>, Cell>;

double num(const Json& v) {
  return std::strtod(v.text().c_str(), nullptr);
}

// An ellipsoid {X : X^T M X = 0} (M from doubles) as centre, radii, rotation, in double;
// nullopt when M is not an ellipsoid.
std::optional<bench::EllipsoidParams> ellipsoid_of(const algebra::Mat4T<double>& m) {
  // Centre: Q c = -q (Cramer on the 3x3 block).
  auto det3 = [](const double q[3][3]) {
    return q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) -
           q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
           q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
  };
  double q[3][3];
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      q[i][j] = m[i][j];
  const double d = det3(q);
  if (d == 0) return std::nullopt;
  bench::EllipsoidParams e;
  for (size_t col = 0; col < 3; ++col) {
    double t[3][3];
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        t[i][j] = j == col ? -m[i][3] : q[i][j];
    e.centre[col] = det3(t) / d;
  }
  double c = m[3][3];
  for (size_t i = 0; i < 3; ++i)
    c += m[i][3] * e.centre[i]; // the constant at the centre
  if (c == 0) return std::nullopt;
  algebra::Mat4d s{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      s[i][j] = m[i][j] / -c;
  s[3][3] = -1; // decoupled, recognised below by its eigenvector
  std::array<double, 4> w{};
  algebra::Mat4d v{};
  algebra::jacobi4(s, w, v);
  size_t col = 0;
  for (size_t k = 0; k < 4; ++k) {
    if (std::fabs(v[3][k]) > 0.5) continue;
    if (!(w[k] > 0)) return std::nullopt;
    e.radii[col] = 1 / std::sqrt(w[k]);
    for (size_t i = 0; i < 3; ++i)
      e.rotation[i][col] = v[i][k];
    ++col;
  }
  if (col != 3) return std::nullopt;
  return e;
}

// A generated ellipsoid / sphere shape (center, radii or radius, quaternion rotation).
std::optional<bench::EllipsoidParams> ellipsoid_of(const Json& shape) {
  const std::string type = shape.find("type")->text();
  bench::EllipsoidParams e;
  const Json& c = *shape.find("center");
  for (size_t i = 0; i < 3; ++i)
    e.centre[i] = num(c.items()[i]);
  if (type == "sphere") {
    e.radii = {num(*shape.find("radius")), num(*shape.find("radius")), num(*shape.find("radius"))};
  } else if (type == "ellipsoid") {
    for (size_t i = 0; i < 3; ++i)
      e.radii[i] = num(shape.find("radii")->items()[i]);
  } else {
    return std::nullopt;
  }
  double w = 1, x = 0, y = 0, z = 0;
  if (const Json* rot = shape.find("rotation")) {
    const Json& qj = *rot->find("quaternion");
    w = num(qj.items()[0]), x = num(qj.items()[1]), y = num(qj.items()[2]), z = num(qj.items()[3]);
  }
  const double n = w * w + x * x + y * y + z * z;
  e.rotation = {
      {{(w * w + x * x - y * y - z * z) / n, 2 * (x * y - w * z) / n, 2 * (x * z + w * y) / n},
       {2 * (x * y + w * z) / n, (w * w - x * x + y * y - z * z) / n, 2 * (y * z - w * x) / n},
       {2 * (x * z - w * y) / n, 2 * (y * z + w * x) / n, (w * w - x * x - y * y + z * z) / n}}};
  return e;
}

// Is `got` (a float distance, <= 0 meaning "they meet") right against the certified label?
bool distance_right(double got, bool meet, double want) {
  if (meet) return got <= 0;
  return got > 0 && std::fabs(got - want) <= 0.01 * want;
}

void classify_families(const std::vector<int>& gaps, long poses, long peer_poses,
                       unsigned long seed, Cells& cells) {
  const std::vector<double> tols = {1e-6, 1e-8, 1e-10, 1e-12, 1e-14};
  for (const char* family : {"tangency", "node", "acnode", "cusp", "double_conic"})
    for (app::Encoding enc : {app::Encoding::Double, app::Encoding::Exact}) {
      app::GenerateRequest r;
      r.family = family;
      r.gaps = gaps;
      r.count = poses;
      r.seed = seed;
      r.encoding = enc;
      r.threads = 2;
      for (const Json& line : app::generate(r)) {
        const Json& label = *line.find("label");
        if (label.find("status")->text() != "certified") continue;
        const std::string want = label.find("tu_case")->text();
        const Json& construction = *label.find("construction");
        const Json& gap = *construction.find("gap");
        const int sign = std::atoi(gap.find("sign")->text().c_str());
        const int k = sign == 0 ? 0 : std::atoi(gap.find("k")->text().c_str());
        const long pose = std::atol(construction.find("index")->text().c_str());
        const auto a = core::io::read_quadric(*line.find("a"), "<atlas>", "$.a");
        const auto b = core::io::read_quadric(*line.find("b"), "<atlas>", "$.b");
        for (double tol : tols) {
          char method[64];
          std::snprintf(method, sizeof method, "surfcert_float tol=%g", tol);
          auto& cell = cells[{family, app::to_string(enc), sign, k, method}];
          ++cell.total;
          try {
            certify::FloatInvariants inv{};
            const algebra::PencilFacts f = certify::analyze_pencil_float(a, b, inv, tol);
            const std::string got = f.kind == algebra::PencilKind::Regular
                                        ? std::to_string(certify::decide_tu_case(f))
                                        : "not_regular";
            cell.wrong += got == want ? 0 : 1;
          } catch (const std::exception&) {
            ++cell.gave_up; // float facts that contradict each other: undecided
          }
        }
#ifdef SURFCERT_HAVE_OCCT
        if (enc != app::Encoding::Double || pose >= peer_poses) continue;
        const auto ea = ellipsoid_of(certify::approx(a)), eb = ellipsoid_of(certify::approx(b));
        if (!ea || !eb) continue; // not an ellipsoid pair: OCCT's peer reads ellipsoids
        const auto& m = certify::morphology_of_case(std::atoi(want.c_str()));
        const int curves = m.connected_components - m.isolated_points;
        auto& cell = cells[{family, app::to_string(enc), sign, k, "occt_intss"}];
        ++cell.total;
        const bench::OcctResult o = bench::occt_intersect(*ea, *eb, 1e-7);
        if (!o.ok)
          ++cell.gave_up;
        else if (o.glued_branches != curves)
          ++cell.wrong;
#else
        (void)pose;
        (void)peer_poses;
#endif
      }
    }
}

void distance_families(const std::vector<int>& gaps, long poses, unsigned long seed, Cells& cells) {
  for (const char* family : {"touching", "nested"}) {
    app::GenerateRequest r;
    r.family = family;
    r.gaps = gaps;
    r.count = poses;
    r.seed = seed;
    r.encoding = app::Encoding::Double;
    r.threads = 2;
    for (const Json& line : app::generate(r)) {
      const Json& label = *line.find("label");
      if (label.find("status")->text() != "certified") continue;
      const Json& dist = *label.find("distance");
      const bool meet = num(*dist.find("upper")) == 0;
      const double want = 0.5 * (num(*dist.find("lower")) + num(*dist.find("upper")));
      const Json& gap = *label.find("construction")->find("gap");
      const int sign = std::atoi(gap.find("sign")->text().c_str());
      const int k = sign == 0 ? 0 : std::atoi(gap.find("k")->text().c_str());
      {
        auto& cell = cells[{family, "double", sign, k, "surfcert_float"}];
        ++cell.total;
        const Json ans = app::process_batch_line(core::io::dump(line), 1, certify::Mode::Float,
                                                 nullptr, 0, certify::Detail::Topology);
        const std::string status = ans.find("status")->text();
        const Json* res = ans.find("result");
        if (status == "undecided" || status == "error" || !res) {
          ++cell.gave_up;
        } else {
          double got;
          if (const Json* est = res->find("estimate"))
            got = num(*est->find("value"));
          else
            got = num(*res->find("distance")->find("upper"));
          cell.wrong += distance_right(got, meet, want) ? 0 : 1;
        }
      }
#ifdef SURFCERT_HAVE_FCL
      const auto ea = ellipsoid_of(*line.find("a")), eb = ellipsoid_of(*line.find("b"));
      if (!ea || !eb) continue;
      auto& cell = cells[{family, "double", sign, k, "fcl_libccd"}];
      ++cell.total;
      const bench::FclResult f = bench::fcl_distance(*ea, *eb);
      if (!f.ok)
        ++cell.gave_up;
      else
        cell.wrong += distance_right(f.distance, meet, want) ? 0 : 1;
#endif
    }
  }
}

} // namespace

int main(int argc, char** argv) {
  const long poses = argc > 1 ? std::atol(argv[1]) : 20;
  const unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 1;
  const int kmax = argc > 3 ? std::atoi(argv[3]) : 60;
  const long peer_poses = argc > 4 ? std::atol(argv[4]) : 5;
  std::vector<int> gaps;
  for (int k = 2; k <= kmax; k += 2)
    gaps.push_back(k);
  Cells cells;
  classify_families(gaps, poses, peer_poses, seed, cells);
  // The touching family's double encoding holds 3/2 + 2^-k only up to k = 51.
  std::vector<int> dgaps;
  for (int k : gaps)
    if (k <= 50) dgaps.push_back(k);
  distance_families(dgaps, poses, seed, cells);
  std::printf("family,encoding,side,k,method,wrong,gave_up,total\n");
  for (const auto& [key, v] : cells) {
    const auto& [family, enc, sign, k, method] = key;
    std::printf("%s,%s,%s,%d,%s,%ld,%ld,%ld\n", family.c_str(), enc.c_str(),
                sign < 0   ? "minus"
                : sign > 0 ? "plus"
                           : "zero",
                k, method.c_str(), v.wrong, v.gave_up, v.total);
  }
  return 0;
}
