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
//     mode float); FCL's distance (libccd GJK, default tolerance 1e-6) and FCL's collide (its
//     verdict against "the surfaces meet"). FCL reads the shapes as solids: for the nested
//     family the solids overlap although the surfaces do not meet, so FCL answers another
//     question there (every answer of collide and distance is then wrong for the surfaces).
//     Each family point's two FCL calls run in a child process (fork + pipe): libccd aborts
//     on some touching pairs (assertion in doSimplex2), counted as *crashed*, apart from
//     wrong and gave up.
// Encodings: double (every number a binary64 with its exact value: the float mode reads exactly
// the labelled surface) and exact (general rational poses rounded to doubles). The peers read
// the double encoding only; they get each ellipsoid as centre, radii and rotation computed in
// double from the matrices (classify families: radii like sqrt(3)/2 are not binary64, so the
// peer's surface is within ~1e-16 relative of the labelled one) or from the shape (distance
// families: exact).
// Usage: float_atlas [poses=20] [seed=1] [kmax=60] [peer_poses=5]
//   > bench/results/float_atlas.csv
// (one CSV row per family, encoding, side, k, method: wrong, gave_up, crashed, total).
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

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

using namespace surfcert;
using core::io::Json;

namespace {

struct Cell {
  long wrong = 0, gave_up = 0, crashed = 0, total = 0;
};
// (family, encoding, side sign, k, method) -> counts
using Cells = std::map<std::tuple<std::string, std::string, int, int, std::string>, Cell>;

double num(const Json& v) {
  return std::strtod(v.text().c_str(), nullptr);
}

// An ellipsoid {X : X^T M X = 0} (M from doubles) as centre, radii, rotation, in double;
// nullopt when M is not an ellipsoid.
// [[maybe_unused]]: only the peer columns call these (builds without OCCT / FCL have none).
[[maybe_unused]] std::optional<bench::EllipsoidParams>
ellipsoid_of(const algebra::Mat4T<double>& m) {
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
[[maybe_unused]] std::optional<bench::EllipsoidParams> ellipsoid_of(const Json& shape) {
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

#ifdef SURFCERT_HAVE_FCL
// FCL's distance and collide on one pair, run in a child process: libccd answers some touching
// pairs with a failed assertion (doSimplex2) that aborts the process, and one abort must cost
// one family point, not the run. The child writes the two results through a pipe; a child that
// dies by a signal or exits without writing the whole record is "crashed".
struct FclOutcome {
  bool crashed = false;
  bool distance_ok = false, collide_ok = false, collide = false;
  double distance = 0;
};

FclOutcome fcl_in_child(const bench::EllipsoidParams& a, const bench::EllipsoidParams& b) {
  struct Record {
    int distance_ok, collide_ok, collide;
    double distance;
  };
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("float_atlas: pipe failed");
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("float_atlas: fork failed");
  if (pid == 0) {
    close(fd[0]);
    const bench::FclResult d = bench::fcl_distance(a, b);
    const bench::FclCollideResult c = bench::fcl_collide(a, b);
    const Record rec{d.ok ? 1 : 0, c.ok ? 1 : 0, c.collide ? 1 : 0, d.distance};
    const bool all = write(fd[1], &rec, sizeof rec) == static_cast<ssize_t>(sizeof rec);
    _exit(all ? 0 : 1);
  }
  close(fd[1]);
  Record rec{};
  size_t got = 0;
  while (got < sizeof rec) {
    const ssize_t n = read(fd[0], reinterpret_cast<char*>(&rec) + got, sizeof rec - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += static_cast<size_t>(n);
  }
  close(fd[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  FclOutcome o;
  if (got != sizeof rec || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    o.crashed = true;
    return o;
  }
  o.distance_ok = rec.distance_ok != 0;
  o.collide_ok = rec.collide_ok != 0;
  o.collide = rec.collide != 0;
  o.distance = rec.distance;
  return o;
}
#endif

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
      std::fprintf(stderr, "float_atlas: %s %s\n", family, app::to_string(enc)); // progress
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
    std::fprintf(stderr, "float_atlas: %s\n", family); // progress
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
      auto& dist_cell = cells[{family, "double", sign, k, "fcl_distance"}];
      auto& coll_cell = cells[{family, "double", sign, k, "fcl_collide"}];
      ++dist_cell.total;
      ++coll_cell.total;
      const FclOutcome f = fcl_in_child(*ea, *eb);
      if (f.crashed) {
        // libccd asserts (doSimplex2) on some touching pairs: the abort takes both calls of
        // this family point with it, so both count as crashed.
        ++dist_cell.crashed;
        ++coll_cell.crashed;
        continue;
      }
      if (!f.distance_ok)
        ++dist_cell.gave_up;
      else
        dist_cell.wrong += distance_right(f.distance, meet, want) ? 0 : 1;
      if (!f.collide_ok)
        ++coll_cell.gave_up;
      else
        coll_cell.wrong += f.collide == meet ? 0 : 1;
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
  {
    // The run's circumstances, on stderr (stdout is the CSV): command, date, machine, load.
    std::string cmd;
    for (int i = 0; i < argc; ++i)
      cmd += std::string(i ? " " : "") + argv[i];
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
    double load[3] = {0, 0, 0};
    if (getloadavg(load, 3) < 0) load[0] = load[1] = load[2] = -1;
    std::fprintf(stderr, "float_atlas: %s; %s; %ld cpus; load %.2f %.2f %.2f\n", cmd.c_str(), date,
                 sysconf(_SC_NPROCESSORS_ONLN), load[0], load[1], load[2]);
  }
  Cells cells;
  classify_families(gaps, poses, peer_poses, seed, cells);
  // The touching family's double encoding holds 3/2 + 2^-k only up to k = 51.
  std::vector<int> dgaps;
  for (int k : gaps)
    if (k <= 50) dgaps.push_back(k);
  distance_families(dgaps, poses, seed, cells);
  std::printf("family,encoding,side,k,method,wrong,gave_up,crashed,total\n");
  for (const auto& [key, v] : cells) {
    const auto& [family, enc, sign, k, method] = key;
    std::printf("%s,%s,%s,%d,%s,%ld,%ld,%ld,%ld\n", family.c_str(), enc.c_str(),
                sign < 0   ? "minus"
                : sign > 0 ? "plus"
                           : "zero",
                k, method.c_str(), v.wrong, v.gave_up, v.crashed, v.total);
  }
  return 0;
}
