// distance_vs_peers: surfcert's certified distance side by side with FCL 0.7 (solids, GJK:
// libccd and indep, tolerance 1e-6 and 1e-12) and Open CASCADE (GeomAPI_ExtremaSurfaceSurface)
// in one run, on the same pairs:
//   separated  random ellipsoid pairs (seed 002 recipe), the second moved ~3 units away;
//   nested     a random small ellipsoid inside a random big one (surface distance > 0; FCL,
//              working on solids, can only answer "overlap");
//   torus      a random ellipsoid against a random ring torus (OCCT only; FCL has no torus);
//   seed000    seed 000's nested pair (true distance 0.530229360238, decoy 1).
// For each peer: median time, ratio of medians to ours (15 digits), largest error against our
// certified value, and how often it is wrong (error > 1e-6 (1 + d), or no answer / overlap for
// disjoint surfaces). Usage: distance_vs_peers [pairs=100] [seed=2026]. Progress on stderr.
#include "random_ellipsoids.hpp"

#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#ifdef SURFCERT_HAVE_FCL
#include "fcl_peer.hpp"
#endif
#ifdef SURFCERT_HAVE_OCCT
#include "occt_distance_peer.hpp"
#endif

#include <flint/flint.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace surfcert;
using bench::EllipsoidParams;

namespace {

struct Case {
  core::Surface a, b;
  EllipsoidParams ea{}, eb{};
  bool torus = false;
#ifdef SURFCERT_HAVE_OCCT
  bench::TorusParams tb{};
#endif
  double truth = 0; // our certified midpoint
  bool certified = false;
};

core::QuadricMatrix translated(const core::QuadricMatrix& q,
                               const std::array<core::Rational, 3>& v) {
  core::Mat4 p;
  for (size_t i = 0; i < 4; ++i)
    p[i][i] = core::Rational(1);
  for (size_t i = 0; i < 3; ++i)
    p[i][3] = -v[i];
  return q.congruent(p);
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

struct PeerStats {
  std::vector<double> us;
  double max_err = 0;
  long wrong = 0, overlap = 0, n = 0;
};

void progress(const char* what, long i, long n) {
  if (n >= 10 && i % (n / 10) == 0) std::fprintf(stderr, "%s %ld/%ld\n", what, i, n);
}

} // namespace

int main(int argc, char** argv) {
  const long pairs = argc > 1 ? std::atol(argv[1]) : 100;
  const unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2026;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<long> dir(-1000, 1000), q9(-9, 9), big(300, 400), cc(-300, 300),
      tor_R(150, 250), tor_r(20, 50);
  std::map<std::string, std::vector<Case>> sets;
  for (long i = 0; i < pairs; ++i) {
    // separated: move the second by ~3 units along a random rational direction.
    auto e1 = bench::random_ellipsoid(rng), e2 = bench::random_ellipsoid(rng);
    double dx = static_cast<double>(dir(rng)), dy = static_cast<double>(dir(rng)),
           dz = static_cast<double>(dir(rng));
    double n = std::sqrt(dx * dx + dy * dy + dz * dz) + 1e-9;
    std::array<core::Rational, 3> v;
    for (size_t k = 0; k < 3; ++k) {
      double comp = (k == 0 ? dx : k == 1 ? dy : dz) / n * 3.0;
      long m = std::lround(comp * 1000);
      v[k] = core::Rational(m, 1000);
      e2.params.centre[k] += static_cast<double>(m) / 1000.0;
    }
    Case c{e1.quadric, translated(e2.quadric, v), e1.params, e2.params};
    sets["separated"].push_back(c);
    // nested: a small random ellipsoid inside a big one (radii 3..4, random rotation).
    auto s = bench::random_ellipsoid(rng);
    core::Mat4 local;
    EllipsoidParams bp;
    for (size_t k = 0; k < 3; ++k) {
      long r = big(rng);
      local[k][k] = core::Rational(100 * 100, static_cast<unsigned long>(r * r));
      bp.radii[k] = static_cast<double>(r) / 100.0;
    }
    local[3][3] = core::Rational(-1);
    long w, x, y, z;
    do {
      w = q9(rng), x = q9(rng), y = q9(rng), z = q9(rng);
    } while (w == 0 && x == 0 && y == 0 && z == 0);
    long nn = w * w + x * x + y * y + z * z;
    long R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                    {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                    {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
    long ci[3] = {cc(rng), cc(rng), cc(rng)};
    core::Mat4 t;
    for (size_t a = 0; a < 3; ++a) {
      core::Rational sum;
      for (size_t b = 0; b < 3; ++b) {
        t[a][b] = core::Rational(R[b][a], static_cast<unsigned long>(nn));
        sum += t[a][b] * core::Rational(ci[b], 1000);
        bp.rotation[a][b] = static_cast<double>(R[a][b]) / static_cast<double>(nn);
      }
      t[a][3] = -sum;
      bp.centre[a] = static_cast<double>(ci[a]) / 1000.0;
    }
    t[3][3] = core::Rational(1);
    core::QuadricMatrix bq(core::transpose(t) * local * t);
    sets["nested"].push_back(Case{s.quadric, bq, s.params, bp});
    // torus: a random ring torus (R 1.5..2.5, r 0.2..0.5, rational axis) and a random
    // ellipsoid moved ~3.5 units away.
    auto e = bench::random_ellipsoid(rng);
    do {
      w = q9(rng), x = q9(rng), y = q9(rng), z = q9(rng);
    } while (w == 0 && x == 0 && y == 0 && z == 0);
    nn = w * w + x * x + y * y + z * z;
    long T[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                    {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                    {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
    long Rr = tor_R(rng), rr = tor_r(rng);
    std::array<core::Rational, 3> axis{core::Rational(T[0][2]), core::Rational(T[1][2]),
                                       core::Rational(T[2][2])};
    core::Torus tor = core::make_torus({core::Rational(0), core::Rational(0), core::Rational(0)},
                                       axis, core::Rational(Rr, 100), core::Rational(rr, 100));
    dx = static_cast<double>(dir(rng)), dy = static_cast<double>(dir(rng)),
    dz = static_cast<double>(dir(rng));
    n = std::sqrt(dx * dx + dy * dy + dz * dz) + 1e-9;
    for (size_t k = 0; k < 3; ++k) {
      double comp = (k == 0 ? dx : k == 1 ? dy : dz) / n * 3.5;
      long m = std::lround(comp * 1000);
      v[k] = core::Rational(m, 1000);
      e.params.centre[k] += static_cast<double>(m) / 1000.0;
    }
    Case tc{translated(e.quadric, v), tor, e.params, {}};
    tc.torus = true;
#ifdef SURFCERT_HAVE_OCCT
    for (size_t a = 0; a < 3; ++a)
      for (size_t b = 0; b < 3; ++b)
        tc.tb.rotation[a][b] = static_cast<double>(T[a][b]) / static_cast<double>(nn);
    tc.tb.major = static_cast<double>(Rr) / 100.0;
    tc.tb.minor = static_cast<double>(rr) / 100.0;
#endif
    sets["torus"].push_back(tc);
  }
  {
    auto qa = core::io::quadric_from_equation("x^2 + y^2/4 + (z+3)^2/9 = 1", {"s", 1, 1, ""});
    auto qb = core::io::quadric_from_equation("x^2/4 + y^2/9 + z^2/49 = 1", {"s", 1, 1, ""});
    EllipsoidParams pa, pb;
    pa.radii = {1, 2, 3};
    pa.centre = {0, 0, -3};
    pb.radii = {2, 3, 7};
    for (size_t k = 0; k < 3; ++k)
      pa.rotation[k][k] = pb.rotation[k][k] = 1;
    sets["seed000"].push_back(Case{qa, qb, pa, pb});
  }

  std::printf("## Certified distance vs peers (distance_vs_peers %ld %lu)\n\n", pairs, seed);
  for (auto& [name, cases] : sets) {
    std::vector<double> t15, t100;
    long cert = 0, undec = 0, zero = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
      progress(name.c_str(), static_cast<long>(i), static_cast<long>(cases.size()));
      auto t0 = std::chrono::steady_clock::now();
      auto r = certify::surface_distance(cases[i].a, cases[i].b, 15, false);
      auto t1 = std::chrono::steady_clock::now();
      t15.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
      cases[i].certified = r.status == certify::Status::Certified;
      cert += cases[i].certified;
      undec += r.status == certify::Status::Undecided;
      zero += r.upper() == "0";
      if (cases[i].certified) cases[i].truth = r.approx();
      t0 = std::chrono::steady_clock::now();
      auto r100 = certify::surface_distance(cases[i].a, cases[i].b, 100, false);
      t1 = std::chrono::steady_clock::now();
      t100.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
    const double m15 = median(t15), m100 = median(t100);
    std::printf("### %s (%zu pairs)\n\nsurfcert: %ld certified, %ld undecided, %ld distance 0; "
                "median %.1f us at 15 digits, %.1f us at 100 digits (%.1f us per extra "
                "digit)\n\n",
                name.c_str(), cases.size(), cert, undec, zero, m15, m100, (m100 - m15) / 85);
    std::printf(
        "| peer | median us | surfcert (15 digits) / peer time | max error vs certified | wrong | "
        "overlap / no answer |\n|---|---|---|---|---|---|\n");
    std::map<std::string, PeerStats> peers;
    auto judge = [&](PeerStats& st, const Case& c, double d, bool answered) {
      ++st.n;
      if (!c.certified) return;
      if (!answered) {
        ++st.overlap;
        ++st.wrong;
        return;
      }
      double err = std::fabs(d - c.truth);
      st.max_err = std::max(st.max_err, err);
      if (err > 1e-6 * (1 + c.truth)) ++st.wrong;
    };
    (void)judge; // unused when no peer is built
#ifdef SURFCERT_HAVE_FCL
    if (name != "torus") {
      for (auto solver : {bench::FclSolver::Libccd, bench::FclSolver::Indep})
        for (double tol : {1e-6, 1e-12}) {
          std::string label = std::string("FCL ") + bench::fcl_solver_name(solver) + " tol " +
                              (tol > 1e-9 ? "1e-6" : "1e-12");
          auto& st = peers[label];
          bench::FclOptions o;
          o.solver = solver;
          o.tolerance = tol;
          bench::fcl_distance(cases[0].ea, cases[0].eb, o); // warm-up
          for (const auto& c : cases) {
            auto r = bench::fcl_distance(c.ea, c.eb, o);
            st.us.push_back(r.seconds * 1e6);
            judge(st, c, r.distance, r.ok && r.distance > 0);
          }
        }
    }
#endif
#ifdef SURFCERT_HAVE_OCCT
    {
      auto& st = peers["OCCT ExtremaSurfaceSurface"];
      for (size_t i = 0; i < cases.size(); ++i) {
        progress("OCCT", static_cast<long>(i), static_cast<long>(cases.size()));
        const auto& c = cases[i];
        auto r = c.torus ? bench::occt_distance(c.ea, c.tb) : bench::occt_distance(c.ea, c.eb);
        st.us.push_back(r.seconds * 1e6);
        judge(st, c, r.distance, r.ok);
      }
    }
#endif
    for (const auto& [label, st] : peers) {
      double m = median(st.us);
      std::printf("| %s | %.1f | %.3g | %.2e | %ld | %ld |\n", label.c_str(), m, m15 / m,
                  st.max_err, st.wrong, st.overlap);
    }
    if (peers.empty()) std::printf("| (no peer built) | | | | | |\n");
    if (name == "seed000") std::printf("\nsurfcert: %.15g (certified)\n", cases[0].truth);
    std::printf("\n");
  }
  flint_cleanup();
  return 0;
}
