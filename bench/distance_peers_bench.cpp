// distance_peers_bench: ellipsoid-ellipsoid minimum distance by the benchmark peers only (FCL
// 0.7 GJK, Open CASCADE GeomAPI_ExtremaSurfaceSurface); it does not link surfcert (our
// certified distance is compared separately, from the CSV). Prints two known pairs, then
// per-peer times over N random pairs, and writes one CSV row per pair.
//
// Usage: distance_peers_bench <out.csv> [pairs=200] [seed=2026] [offset=0]
//
// Pair i = the ellipsoids drawn 2i and 2i+1 from std::mt19937_64(seed) by the recipe of
// random_ellipsoids.hpp (as trace_bench/qsic_bench draw a then b), with the second centre then
// shifted by (offset, 0, 0). random_params() below repeats random_ellipsoid()'s rng calls and
// doubles exactly but without the exact quadric, so that this program needs neither surfcert
// nor FLINT. With offset 0 most pairs overlap (centres in [-1/2, 1/2]^3, semi-axes in
// [1/10, 1]); offset > 3 makes every pair disjoint.
#include "ellipsoid_params.hpp"

#if SURFCERT_HAVE_FCL
#include "fcl_peer.hpp"
#endif
#if SURFCERT_HAVE_OCCT
#include "occt_distance_peer.hpp"
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

using surfcert::bench::EllipsoidParams;

namespace {

// random_ellipsoid(rng).params of random_ellipsoids.hpp: same distributions, same call order
// (radii x3, quaternion w x y z redrawn while all zero, centre x3), same divisions.
EllipsoidParams random_params(std::mt19937_64& rng) {
  std::uniform_int_distribution<long> c(-500, 500), r(10, 100), q(-9, 9);
  EllipsoidParams p;
  for (size_t i = 0; i < 3; ++i)
    p.radii[i] = static_cast<double>(r(rng)) / 100.0;
  long w, x, y, z;
  do {
    w = q(rng), x = q(rng), y = q(rng), z = q(rng);
  } while (w == 0 && x == 0 && y == 0 && z == 0);
  long n = w * w + x * x + y * y + z * z;
  long R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                  {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                  {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  for (size_t i = 0; i < 3; ++i)
    p.centre[i] = static_cast<double>(c(rng)) / 1000.0;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      p.rotation[i][j] = static_cast<double>(R[i][j]) / static_cast<double>(n);
  return p;
}

EllipsoidParams axis_aligned(std::array<double, 3> centre, std::array<double, 3> radii) {
  EllipsoidParams p;
  p.centre = centre;
  p.radii = radii;
  p.rotation = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  return p;
}

#if SURFCERT_HAVE_OCCT
// The ellipsoid with semi-axes radii along (z, y, -x): rotation [[0,0,-1],[0,1,0],[1,0,0]].
EllipsoidParams rotated_x_up(std::array<double, 3> centre, std::array<double, 3> radii) {
  EllipsoidParams p = axis_aligned(centre, radii);
  p.rotation = {{{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};
  return p;
}
#endif

struct PeerOutput {
  double distance = 0;
  std::array<double, 3> p1{}, p2{};
  double seconds = 0;
  bool ok = false;
  std::string note; ///< error text or extra diagnostics
};

struct Peer {
  std::string name; ///< CSV column prefix
  std::function<PeerOutput(const EllipsoidParams&, const EllipsoidParams&)> run;
};

std::vector<Peer> make_peers() {
  std::vector<Peer> peers;
#if SURFCERT_HAVE_FCL
  using surfcert::bench::FclOptions;
  using surfcert::bench::FclSolver;
  for (FclSolver s : {FclSolver::Libccd, FclSolver::Indep})
    for (double tol : {1e-6, 1e-12}) {
      FclOptions o;
      o.solver = s;
      o.tolerance = tol;
      char name[64];
      std::snprintf(name, sizeof name, "fcl_%s_%s", surfcert::bench::fcl_solver_name(s),
                    tol == 1e-6 ? "tol1e-6" : "tol1e-12");
      peers.push_back({name, [o](const EllipsoidParams& a, const EllipsoidParams& b) {
                         auto r = surfcert::bench::fcl_distance(a, b, o);
                         return PeerOutput{r.distance, r.p1, r.p2, r.seconds, r.ok, r.error};
                       }});
    }
#endif
#if SURFCERT_HAVE_OCCT
  peers.push_back({"occt_extss", [](const EllipsoidParams& a, const EllipsoidParams& b) {
                     auto r = surfcert::bench::occt_distance(a, b);
                     std::string note = r.ok ? "extrema " + std::to_string(r.extrema) : r.error;
                     return PeerOutput{r.distance, r.p1, r.p2, r.seconds, r.ok, note};
                   }});
#endif
  return peers;
}

void print_output(const std::string& name, const PeerOutput& o, double expected) {
  if (!o.ok) {
    std::printf("  %-22s FAILED (%s), %.1f us\n", name.c_str(), o.note.c_str(), o.seconds * 1e6);
    return;
  }
  std::printf("  %-22s %.15g (err %+.2e)  p1 (%.6f, %.6f, %.6f)  p2 (%.6f, %.6f, %.6f)  %.1f us"
              "%s%s\n",
              name.c_str(), o.distance, o.distance - expected, o.p1[0], o.p1[1], o.p1[2], o.p2[0],
              o.p2[1], o.p2[2], o.seconds * 1e6, o.note.empty() ? "" : "  ", o.note.c_str());
}

void known_pair(const char* title, const EllipsoidParams& a, const EllipsoidParams& b,
                double expected, const std::vector<Peer>& peers) {
  std::printf("%s (expected %.12g):\n", title, expected);
  for (const Peer& p : peers)
    print_output(p.name, p.run(a, b), expected);
#if SURFCERT_HAVE_FCL
  // Signed distance with libccd only: GST_INDEP + enable_signed_distance on overlapping
  // ellipsoids aborts the process (assert "index != static_cast<std::size_t>(-1)" in
  // fcl/narrowphase/distance-inl.h, kept in Debian's libfcl.so: its fallback collide() finds
  // no contact), so it cannot be caught.
  surfcert::bench::FclOptions o;
  o.signed_distance = true;
  auto r = surfcert::bench::fcl_distance(a, b, o);
  print_output("fcl_libccd_signed", PeerOutput{r.distance, r.p1, r.p2, r.seconds, r.ok, r.error},
               expected);
#endif
}

struct Stats {
  double median_us = 0, mean_us = 0;
};

Stats stats(std::vector<double> us) {
  Stats s;
  if (us.empty()) return s;
  for (double x : us)
    s.mean_us += x;
  s.mean_us /= static_cast<double>(us.size());
  std::sort(us.begin(), us.end());
  size_t n = us.size();
  s.median_us = n % 2 ? us[n / 2] : (us[n / 2 - 1] + us[n / 2]) / 2;
  return s;
}

void write_params(std::FILE* f, const EllipsoidParams& e) {
  for (double v : e.centre)
    std::fprintf(f, ",%.17g", v);
  for (double v : e.radii)
    std::fprintf(f, ",%.17g", v);
  for (const auto& row : e.rotation)
    for (double v : row)
      std::fprintf(f, ",%.17g", v);
}

void write_params_header(std::FILE* f, const char* e) {
  for (const char* k : {"cx", "cy", "cz", "a", "b", "c"})
    std::fprintf(f, ",%s_%s", e, k);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      std::fprintf(f, ",%s_R%d%d", e, i, j);
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s <out.csv> [pairs=200] [seed=2026] [offset=0]\n", argv[0]);
    return 2;
  }
  const char* csv_path = argv[1];
  long pairs = argc > 2 ? std::atol(argv[2]) : 200;
  unsigned long seed = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 2026;
  double offset = argc > 4 ? std::atof(argv[4]) : 0.0;
  std::vector<Peer> peers = make_peers();
  if (peers.empty()) {
    std::fprintf(stderr, "no peer compiled in (SURFCERT_BENCH_FCL and SURFCERT_BENCH_OCCT off)\n");
    return 2;
  }

  std::printf("## Ellipsoid distance peers (distance_peers_bench %ld %lu %g)\n\npeers:", pairs,
              seed, offset);
#if SURFCERT_HAVE_FCL
  std::printf(" %s;", surfcert::bench::fcl_version().c_str());
#endif
#if SURFCERT_HAVE_OCCT
  std::printf(" Open CASCADE GeomAPI_ExtremaSurfaceSurface;");
#endif
  std::printf("\n\n### Known pairs\n\n");
  for (const Peer& p : peers) // warm-up: the first FCL call builds its dispatch tables
    p.run(axis_aligned({0, 0, 0}, {1, 1, 1}), axis_aligned({3, 0, 0}, {1, 1, 1}));
  // S1: x^2 + y^2/4 + (z+3)^2/9 = 1 inside S2: x^2/4 + y^2/9 + z^2/49 = 1.
  known_pair("nested S1 (1,2,3 at (0,0,-3)) in S2 (2,3,7 at 0)",
             axis_aligned({0, 0, -3}, {1, 2, 3}), axis_aligned({0, 0, 0}, {2, 3, 7}),
             0.530229360238, peers);
  known_pair("unit spheres at (0,0,0) and (3,0,0)", axis_aligned({0, 0, 0}, {1, 1, 1}),
             axis_aligned({3, 0, 0}, {1, 1, 1}), 1.0, peers);
#if SURFCERT_HAVE_OCCT
  {
    surfcert::bench::TorusParams t; // R = 3, r = 1, axis z, centre 0
    t.major = 3;
    t.minor = 1;
    struct Case {
      const char* title;
      EllipsoidParams e;
      double expected;
    };
    const Case cases[] = {
        {"torus(3,1) vs sphere r=0.5 at 0 (in the hole)", axis_aligned({0, 0, 0}, {0.5, 0.5, 0.5}),
         1.5},
        {"torus(3,1) vs sphere r=0.25 at (3,0,0) (inside the tube)",
         axis_aligned({3, 0, 0}, {0.25, 0.25, 0.25}), 0.75},
        {"torus(3,1) vs ellipsoid (1,1,0.5) at (3,0,2.5) (above; nearest point at the "
         "B-spline's pole)",
         axis_aligned({3, 0, 2.5}, {1, 1, 0.5}), 1.0},
        {"torus(3,1) vs the same ellipsoid as (0.5,1,1) rotated local x -> z (pole moved "
         "off the nearest point)",
         rotated_x_up({3, 0, 2.5}, {0.5, 1, 1}), 1.0},
    };
    for (const Case& c : cases) {
      std::printf("%s (expected %.12g):\n", c.title, c.expected);
      auto r = surfcert::bench::occt_distance(c.e, t);
      print_output("occt_extss_torus",
                   PeerOutput{r.distance, r.p1, r.p2, r.seconds, r.ok,
                              r.ok ? "extrema " + std::to_string(r.extrema) : r.error},
                   c.expected);
    }
  }
#endif

  std::FILE* csv = std::fopen(csv_path, "w");
  if (!csv) {
    std::perror(csv_path);
    return 1;
  }
  std::fprintf(csv, "pair");
  write_params_header(csv, "e1");
  write_params_header(csv, "e2");
  for (const Peer& p : peers)
    std::fprintf(csv, ",%s_distance,%s_us,%s_ok", p.name.c_str(), p.name.c_str(), p.name.c_str());
  std::fprintf(csv, "\n");

  // All pairs first, then each peer over all pairs (peer-major: a peer's timings are not
  // polluted by the cache traffic of the other peers between two of its calls).
  std::mt19937_64 rng(seed);
  std::vector<std::pair<EllipsoidParams, EllipsoidParams>> in;
  for (long i = 0; i < pairs; ++i) {
    EllipsoidParams a = random_params(rng);
    EllipsoidParams b = random_params(rng);
    b.centre[0] += offset;
    in.emplace_back(a, b);
  }
  std::fprintf(stderr, "distance_peers_bench: %ld pairs (seed %lu, offset %g), %zu peers\n", pairs,
               seed, offset, peers.size());
  std::vector<std::vector<PeerOutput>> out(peers.size());
  for (size_t k = 0; k < peers.size(); ++k) {
    for (size_t i = 0; i < in.size(); ++i) {
      out[k].push_back(peers[k].run(in[i].first, in[i].second));
      if ((i + 1) % std::max<size_t>(1, in.size() / 20) == 0 || i + 1 == in.size())
        std::fprintf(stderr, "\r  peer %zu/%zu %-22s %zu / %zu pairs", k + 1, peers.size(),
                     peers[k].name.c_str(), i + 1, in.size());
    }
  }
  std::fprintf(stderr, "\n");

  std::vector<std::vector<double>> us(peers.size());
  std::vector<std::vector<double>> dist(peers.size());
  std::vector<long> failed(peers.size(), 0), negative(peers.size(), 0), tiny(peers.size(), 0);
  for (size_t i = 0; i < in.size(); ++i) {
    std::fprintf(csv, "%zu", i);
    write_params(csv, in[i].first);
    write_params(csv, in[i].second);
    for (size_t k = 0; k < peers.size(); ++k) {
      const PeerOutput& o = out[k][i];
      us[k].push_back(o.seconds * 1e6);
      dist[k].push_back(o.ok ? o.distance : NAN);
      failed[k] += !o.ok;
      negative[k] += o.ok && o.distance < 0;
      tiny[k] += o.ok && o.distance >= 0 && o.distance < 1e-7;
      std::fprintf(csv, ",%.17g,%.3f,%d", o.ok ? o.distance : NAN, o.seconds * 1e6, o.ok ? 1 : 0);
    }
    std::fprintf(csv, "\n");
  }
  std::fclose(csv);

  std::printf("\n### %ld random pairs\n\n| peer | median us | mean us | failed | distance < 0 | "
              "0 <= distance < 1e-7 |\n|---|---|---|---|---|---|\n",
              pairs);
  for (size_t k = 0; k < peers.size(); ++k) {
    Stats s = stats(us[k]);
    std::printf("| %s | %.1f | %.1f | %ld | %ld | %ld |\n", peers[k].name.c_str(), s.median_us,
                s.mean_us, failed[k], negative[k], tiny[k]);
  }
  // Agreement with the last peer (OCCT when built) on the pairs where both are >= 0.
  if (peers.size() > 1) {
    size_t ref = peers.size() - 1;
    std::printf("\nmax |peer - %s| over pairs where both are >= 0:\n", peers[ref].name.c_str());
    for (size_t k = 0; k + 1 < peers.size(); ++k) {
      double worst = 0;
      long both = 0;
      for (size_t i = 0; i < dist[k].size(); ++i)
        if (dist[k][i] >= 0 && dist[ref][i] >= 0) {
          ++both;
          worst = std::max(worst, std::fabs(dist[k][i] - dist[ref][i]));
        }
      std::printf("  %s: %.3e (%ld pairs)\n", peers[k].name.c_str(), worst, both);
    }
  }
  std::printf("\nCSV: %s\n", csv_path);
  return 0;
}
