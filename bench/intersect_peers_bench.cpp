// intersect_peers_bench: curves of two quadrics of every natural kind, surfcert vs Open CASCADE,
// in one run, side by side (issue 15's benchmark).
//
// Each case is two surfaces in their own frames (exact rational parameters and rational
// rigid motions), posed by a random rational rigid motion per repetition, and an axis-aligned
// box (the same doubles for both sides). Our side: trace::intersect_curve (filtered
// classification, certified affine topology, curves traced inside the box), timed whole (thread CPU
// time, both sides: the machine is shared). OCCT: GeomAPI_IntSS on the analytic surfaces
// (occt_quadric_peer.hpp; surfaces trimmed to cover the box), timed alone; its lines are clipped to
// the box and pieces that continue each other joined (outside the timing). Reference: the certified
// affine topology (loops, unbounded branches); named cases also carry a hand-derived answer, which
// the certified one must equal. Counts compared in the box: loops + unbounded branches pieces
// (isolated points apart), and how many of them close up. Usage: intersect_peers_bench
// [repetitions=20] [random_pairs=300] [seed=2026] [tol=2e-4]
//        [occt_tol=1e-7] [only: run the named cases whose name contains this]
// SURFCERT_DUMP=FILE: each pair's answer (curve_envelope_json at --detail topology, then a second
// call's at --detail full, outside the timings) written to FILE as JSON lines, one per pair:
// the reference that a speed-up must reproduce (certified fields equal, points within tolerance).
// SURFCERT_BENCH_ORDER=interleaved: OCCT's call right after ours for each pair (default: our
// side on every pair, then OCCT on every pair; see main). SURFCERT_BENCH_NO_PEER=1: our side
// only (a profile of our code; the OCCT columns and the comparisons then stay empty).
// SURFCERT_BENCH_DOUBLES=1: our side gets each posed quadric as a matrix of doubles (every entry
// of the exact matrix rounded once, read exactly: core::QuadricMatrix::from_double_matrix), the
// data a user sends, with denominators of ~2^60..2^110 where the rational poses have small
// ones; OCCT gets its usual doubles. Rounding moves tangent cases off tangency, so the named
// cases' hand-derived answers are not checked then (the reference is our certified topology
// of the rounded pair, as for the random pairs).
#include "occt_quadric_peer.hpp"
#include "support/distance_checks.hpp"
#include "surfcert/trace/intersect_curve.hpp"

#include <flint/flint.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

using namespace surfcert;
using bench::PeerSurface;
using core::Mat4;
using core::Rational;
using K = PeerSurface::Kind;

namespace {

// This thread's CPU time in microseconds: the figures are CPU time per pair, both sides (the
// 2 cores are shared, so wall time would count other people's work).
double cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e6 * static_cast<double>(ts.tv_sec) + 1e-3 * static_cast<double>(ts.tv_nsec);
}

struct Pose {
  long w = 1, x = 0, y = 0, z = 0;
  std::array<Rational, 3> t{};
};

// A surface in its own frame: exact parameters (see PeerSurface; for an ellipsoid a, b, c are
// the inverse squared semi-axes) and its pose.
struct Surf {
  K kind;
  Rational a{1}, b{1}, c{1};
  Pose pose;
};

struct Case {
  std::string group, name;
  Surf s1, s2;
  double half_width;    ///< the box: the pair's translation +- half_width
  int loops, unbounded; ///< hand-derived; -1: not derived (the certified answer is the reference)
};

Mat4 local_matrix(const Surf& s) {
  Mat4 m;
  const Rational h(1, 2);
  switch (s.kind) {
  case K::Plane:
    m[2][3] = m[3][2] = h;
    break;
  case K::Sphere:
    m[0][0] = m[1][1] = m[2][2] = Rational(1);
    m[3][3] = -s.a * s.a;
    break;
  case K::Cylinder:
    m[0][0] = m[1][1] = Rational(1);
    m[3][3] = -s.a * s.a;
    break;
  case K::Cone:
    m[0][0] = m[1][1] = Rational(1);
    m[2][2] = -s.a * s.a;
    break;
  case K::Ellipsoid:
    m[0][0] = s.a;
    m[1][1] = s.b;
    m[2][2] = s.c;
    m[3][3] = Rational(-1);
    break;
  case K::Paraboloid:
    m[0][0] = m[1][1] = s.a;
    m[2][3] = m[3][2] = -h;
    break;
  case K::Hyperboloid1:
    m[0][0] = m[1][1] = Rational(1) / (s.a * s.a);
    m[2][2] = -Rational(1) / (s.c * s.c);
    m[3][3] = Rational(-1);
    break;
  }
  return m;
}

using D3 = std::array<std::array<double, 3>, 3>;

D3 rotation(const Pose& p) {
  const long w = p.w, x = p.x, y = p.y, z = p.z;
  const double n = static_cast<double>(w * w + x * x + y * y + z * z);
  const long r[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                        {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                        {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  D3 m{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      m[i][j] = static_cast<double>(r[i][j]) / n;
  return m;
}

std::array<double, 3> rotate(const D3& r, const std::array<double, 3>& v) {
  std::array<double, 3> o{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      o[i] += r[i][j] * v[j];
  return o;
}

std::array<double, 3> to_d(const std::array<Rational, 3>& t) {
  return {t[0].to_double_approx(), t[1].to_double_approx(), t[2].to_double_approx()};
}

// The surface posed by its own pose, then by the pair's: exactly (P = P_s P_pair, Q' = P^T Q P)
// and as doubles for OCCT.
core::QuadricMatrix exact_surface(const Surf& s, const Pose& pair) {
  const Mat4 p = testing::motion(s.pose.w, s.pose.x, s.pose.y, s.pose.z, s.pose.t) *
                 testing::motion(pair.w, pair.x, pair.y, pair.z, pair.t);
  return core::QuadricMatrix(core::transpose(p) * local_matrix(s) * p);
}

PeerSurface peer_surface(const Surf& s, const Pose& pair) {
  PeerSurface o;
  o.kind = s.kind;
  const D3 rp = rotation(pair), rs = rotation(s.pose);
  auto o1 = rotate(rp, to_d(s.pose.t));
  const auto tp = to_d(pair.t);
  for (size_t k = 0; k < 3; ++k)
    o.origin[k] = o1[k] + tp[k];
  for (size_t m = 0; m < 3; ++m) {
    std::array<double, 3> e{};
    e[m] = 1;
    o.axes[m] = rotate(rp, rotate(rs, e));
  }
  const double a = s.a.to_double_approx(), b = s.b.to_double_approx(), c = s.c.to_double_approx();
  if (s.kind == K::Ellipsoid) {
    o.a = 1 / std::sqrt(a), o.b = 1 / std::sqrt(b), o.c = 1 / std::sqrt(c);
  } else {
    o.a = a, o.b = b, o.c = c;
  }
  return o;
}

Surf surf(K k, Rational a = Rational(1), std::array<Rational, 3> t = {}, char axis = 'z') {
  Surf s{k, a, Rational(1), Rational(1), Pose{}};
  s.pose.t = t;
  if (axis == 'x') s.pose = Pose{1, 0, 1, 0, t};  // local z -> world x
  if (axis == 'y') s.pose = Pose{1, -1, 0, 0, t}; // local z -> world y
  return s;
}

Rational R(long p, long q = 1) {
  return Rational(p, q);
}

std::vector<Case> named_cases() {
  const std::array<Rational, 3> o{};
  auto at = [](long x, long y, long z, long d = 1) {
    return std::array<Rational, 3>{R(x, d), R(y, d), R(z, d)};
  };
  Surf e{K::Ellipsoid, R(1), R(2), R(4), Pose{}}; // x^2 + 2y^2 + 4z^2 = 1
  Surf tilted = surf(K::Plane, R(1), at(0, 0, 1));
  tilted.pose.w = 4, tilted.pose.y = 1; // a plane through (0, 0, 1) tilted about y
  Surf hyp{K::Hyperboloid1, R(1), R(1), R(1), Pose{}};
  return {
      {"pipes", "Steinmetz (equal radii, axes crossing)", surf(K::Cylinder),
       surf(K::Cylinder, R(1), o, 'y'), 3, 2, 0},
      {"pipes", "T-junction, radii 1 and 1/2", surf(K::Cylinder),
       surf(K::Cylinder, R(1, 2), o, 'y'), 3, 2, 0},
      {"pipes", "offset pipes, one loop (offset 1)", surf(K::Cylinder),
       surf(K::Cylinder, R(1, 2), at(1, 0, 0), 'y'), 3, 1, 0},
      {"pipes", "offset pipes, two loops (offset 1/4)", surf(K::Cylinder),
       surf(K::Cylinder, R(1, 2), at(1, 0, 0, 4), 'y'), 3, 2, 0},
      {"pipes", "offset pipes, tangent inside (offset 1/2)", surf(K::Cylinder),
       surf(K::Cylinder, R(1, 2), at(1, 0, 0, 2), 'y'), 3, 1, 0},
      {"cone-cylinder", "coaxial (two circles)", surf(K::Cone), surf(K::Cylinder), 3, 2, 0},
      {"cone-cylinder", "tangent (cylinder through the apex)", surf(K::Cone),
       surf(K::Cylinder, R(1), at(1, 0, 0)), 3, 1, 0},
      {"cone-cylinder", "generic (axis offset 1/2)", surf(K::Cone),
       surf(K::Cylinder, R(1), at(1, 0, 0, 2)), 3, 2, 0},
      {"hyperboloid-sphere", "coaxial, sphere radius 2", hyp, surf(K::Sphere, R(2)), 3, 2, 0},
      {"hyperboloid-sphere", "sphere radius 3/2 off the axis", hyp,
       surf(K::Sphere, R(3, 2), at(1, 0, 1, 2)), 3, -1, -1},
      {"paraboloid-plane", "plane z = 1 (circle)", surf(K::Paraboloid),
       surf(K::Plane, R(1), at(0, 0, 1)), 3, 1, 0},
      {"paraboloid-plane", "tilted plane (ellipse)", surf(K::Paraboloid), tilted, 3, 1, 0},
      {"Table 7", "ellipsoid-cylinder, empty", e, surf(K::Cylinder, R(1), at(3, 0, 0)), 3, 0, 0},
      {"Table 7", "ellipsoid-cylinder, one branch", e, surf(K::Cylinder, R(1, 2), at(1, 0, 0)), 3,
       1, 0},
      {"Table 7", "ellipsoid-cylinder, two branches", e, surf(K::Cylinder, R(1, 4), o, 'x'), 3, 2,
       0},
      {"Table 7", "ellipsoid-cone, empty", e, surf(K::Cone, R(1), at(3, 0, 0)), 3, 0, 0},
      {"Table 7", "ellipsoid-cone, one branch", e, surf(K::Cone, R(1), at(1, 0, 1)), 3, 1, 0},
      {"Table 7", "ellipsoid-cone, two branches", e, surf(K::Cone, R(1, 8), at(3, 0, 0), 'x'), 3, 2,
       0},
  };
}

Pose random_pose(std::mt19937_64& rng, long translation_hundredths) {
  std::uniform_int_distribution<long> q(-9, 9), t(-translation_hundredths, translation_hundredths);
  Pose p;
  do {
    p.w = q(rng), p.x = q(rng), p.y = q(rng), p.z = q(rng);
  } while (p.w == 0 && p.x == 0 && p.y == 0 && p.z == 0);
  for (auto& v : p.t)
    v = R(t(rng), 100);
  return p;
}

Surf random_natural(std::mt19937_64& rng, bool plane_allowed) {
  std::uniform_int_distribution<int> kind(0, plane_allowed ? 3 : 2);
  std::uniform_int_distribution<long> radius(30, 100), slope(25, 200);
  const K ks[4] = {K::Sphere, K::Cylinder, K::Cone, K::Plane};
  const K k = ks[kind(rng)];
  Surf s{k, k == K::Cone ? R(slope(rng), 100) : R(radius(rng), 100), R(1), R(1), Pose{}};
  s.pose = random_pose(rng, 100);
  return s;
}

struct Row {
  std::string group, name;
  int want_loops = -1, want_unbounded = -1;
  long pairs = 0;
  std::vector<double> ours_us, occt_us, classify_us;
  long exact_fallbacks = 0;
  long exact_starts = 0; ///< pairs whose loops needed the exact extreme points
  long ours_undecided = 0, ours_wrong = 0, reference_missing = 0, hand_disagrees = 0;
  long occt_failed = 0, occt_count = 0, occt_closure = 0, occt_lines_differ = 0;
  std::map<std::string, long> certified; ///< "loops/unbounded" -> pairs
  std::map<std::string, long> occt_seen; ///< OCCT "pieces(closed)" -> pairs
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v)
    s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

// One pair of a run: the surfaces, the pair's pose and box half width, and our answer once
// computed (kept for the OCCT pass and the comparison).
struct Job {
  Row* row;
  Surf s1, s2;
  Pose pair;
  double half_width;
  std::optional<trace::CurveResult> ours;
  double ours_us = 0;
};

// Our side of a job: the timed call (and, outside the figure, the profiling repeats, the dump
// and the classification alone).
bool doubles_mode() {
  static const bool on = std::getenv("SURFCERT_BENCH_DOUBLES") != nullptr;
  return on;
}

// The quadric as a user sends it in doubles (SURFCERT_BENCH_DOUBLES), or exact.
core::QuadricMatrix user_surface(const Surf& s, const Pose& pair) {
  const core::QuadricMatrix e = exact_surface(s, pair);
  if (!doubles_mode()) return e;
  core::DoubleMat4 d{};
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      d[i][j] = e.matrix()[i][j].to_double_approx();
  return core::QuadricMatrix::from_double_matrix(d);
}

void run_ours(Job& job, double tol, bool warm_up = false) {
  Row& row = *job.row;
  const auto a = user_surface(job.s1, job.pair), b = user_surface(job.s2, job.pair);
  trace::TraceOptions opt;
  opt.tolerance = tol;
  ++row.pairs;

  // Our side chooses the box (every bounded component, special point and a margin inside;
  // grown until every unbounded branch shows); OCCT gets the same box. Pairs with an ellipsoid
  // (bounded curves, no box) use the pair's translation +- half_width.
  const double t0 = cpu_us();
  job.ours = trace::intersect_curve(a, b, certify::Mode::Filtered, opt, certify::Detail::Topology);
  job.ours_us = cpu_us() - t0;
  const trace::CurveResult& r = *job.ours;
  row.ours_us.push_back(job.ours_us);
  row.exact_starts += r.exact_start_points ? 1 : 0;
  // SURFCERT_PROFILE_REPEAT=n: our side n more times, outside the figures, so that a sampling
  // profiler of the whole run sees mostly our code (OCCT takes ~30x our time per pair). The
  // repeats run on fresh copies of the quadrics: the same quadric object keeps what it cached
  // (its kind, whether it is singular), which a first call pays.
  static const long repeat = [] {
    const char* e = std::getenv("SURFCERT_PROFILE_REPEAT");
    return e ? std::max(0L, std::atol(e)) : 0L;
  }();
  // (A matrix of doubles is copied as one: a copy from its exact rationals would be read
  // through the rationals, not the doubles, and profile another path.)
  auto fresh = [](const core::QuadricMatrix& q) {
    if (const core::DoubleMat4* d = q.double_matrix())
      return core::QuadricMatrix::from_double_matrix(*d);
    return core::QuadricMatrix(q.matrix());
  };
  for (long i = 0; i < (warm_up ? 0 : repeat); ++i) // (a profile of the warm-up: not wanted)
    (void)trace::intersect_curve(fresh(a), fresh(b), certify::Mode::Filtered, opt,
                                 certify::Detail::Topology);
  static FILE* dump = [] {
    const char* e = std::getenv("SURFCERT_DUMP");
    return e ? std::fopen(e, "w") : nullptr;
  }();
  if (dump) {
    static long index = 0;
    const auto full =
        trace::intersect_curve(a, b, certify::Mode::Filtered, opt, certify::Detail::Full);
    std::string line = "{\"index\":" + std::to_string(index++) + ",\"case\":";
    core::io::append_json_string(line, row.name);
    line += ",\"ours_us\":" + std::to_string(job.ours_us);
    line += ",\"topology\":" +
            core::io::dump(trace::curve_envelope_json(r, a, b, certify::Detail::Topology)) +
            ",\"full\":" + core::io::dump(trace::curve_envelope_json(full, a, b)) + "}\n";
    std::fputs(line.c_str(), dump);
    std::fflush(dump);
  }
  { // The classification alone (not part of the figure above): where our time goes.
    const double c0 = cpu_us();
    const auto t = certify::classify_qsic(a, b, certify::Mode::Filtered);
    row.classify_us.push_back(cpu_us() - c0);
    row.exact_fallbacks += t.exact_fallback ? 1 : 0;
  }
}

// OCCT's side of a job (our answer computed), and both sides' counts against the reference.
void run_occt(const Job& job, double occt_tol, std::vector<double>& ratios) {
  Row& row = *job.row;
  const trace::CurveResult& r = *job.ours;
  trace::Box box;
  if (r.box) {
    box = *r.box;
  } else {
    const auto c = to_d(job.pair.t);
    for (size_t k = 0; k < 3; ++k)
      box.min[k] = c[k] - job.half_width, box.max[k] = c[k] + job.half_width;
  }

  const auto o = bench::occt_intersect_in_box(
      peer_surface(job.s1, job.pair), peer_surface(job.s2, job.pair), box.min, box.max, occt_tol);
  if (o.ok) {
    row.occt_us.push_back(o.cpu_seconds * 1e6);
    ratios.push_back(o.seconds * 1e6 / job.ours_us);
  }

  int loops = -1, unbounded = -1;
  if (r.affine.certified()) {
    loops = *r.affine.loops;
    unbounded = *r.affine.unbounded_branches;
  }
  if (loops < 0) {
    ++row.reference_missing;
    return;
  }
  row.certified[std::to_string(loops) + "/" + std::to_string(unbounded)]++;
  if (row.want_loops >= 0 && !doubles_mode() &&
      (loops != row.want_loops || unbounded != row.want_unbounded))
    ++row.hand_disagrees;
  int closed = 0, open = 0;
  for (const auto& br : r.branches)
    (br.closed ? closed : open) += 1;
  if (r.status != certify::Status::Certified) {
    static int shown = 0;
    if (shown++ < 5)
      std::fprintf(stderr, "  surfcert undecided on %s: %s\n", row.name.c_str(), r.note.c_str());
    ++row.ours_undecided;
  } else if (closed != loops || open != unbounded)
    ++row.ours_wrong;
  if (!o.ok) {
    static int shown = 0;
    if (shown++ < 5)
      std::fprintf(stderr, "  OCCT failed on %s: %s\n", row.name.c_str(),
                   o.error.empty() ? "IsDone() false" : o.error.c_str());
    ++row.occt_failed;
    row.occt_seen["failed"]++;
    return;
  }
  row.occt_seen[std::to_string(o.pieces) + "(" + std::to_string(o.closed_pieces) + ")"]++;
  if (o.pieces != loops + unbounded)
    ++row.occt_count;
  else if (o.closed_pieces != loops)
    ++row.occt_closure;
  if (o.lines != loops + unbounded) ++row.occt_lines_differ;
}

std::string keys(const std::map<std::string, long>& m) {
  std::string s;
  for (const auto& [k, v] : m)
    s += (s.empty() ? "" : ", ") + k + (m.size() > 1 ? " x" + std::to_string(v) : "");
  return s;
}

} // namespace

int main(int argc, char** argv) {
  const long reps = argc > 1 ? std::max(1L, std::atol(argv[1])) : 20;
  const long random_pairs = argc > 2 ? std::max(0L, std::atol(argv[2])) : 300;
  const unsigned long seed = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 2026;
  const double tol = argc > 4 ? std::atof(argv[4]) : 2e-4;
  const double occt_tol = argc > 5 ? std::atof(argv[5]) : 1e-7;
  std::mt19937_64 rng(seed);
  std::vector<Row> rows;
  std::vector<double> ratios;
  // SURFCERT_BENCH_ORDER=interleaved: each pair's OCCT call right after ours (the order of
  // sessions up to 26). By default ("blocked") our side answers every pair, then OCCT answers
  // every pair: each library runs as in a user's loop over a list of pairs, after its own
  // previous pair, not after the other library's (whose ~10 ms evict our code and data from
  // the caches: measured at session 27, a first call after OCCT's took ~1.7x the time of the
  // same call repeated on fresh copies of the quadrics). The pairs are the same either way.
  const char* order_env = std::getenv("SURFCERT_BENCH_ORDER");
  const bool interleaved = order_env && std::string(order_env) == "interleaved";
  { // Warm-up outside the figures (first-call costs: library initialisation, caches).
    Row warm;
    std::vector<double> r;
    const auto cases = named_cases();
    Job w{&warm, cases[0].s1, cases[0].s2, Pose{}, 3, std::nullopt, 0};
    run_ours(w, tol, true);
    run_occt(w, occt_tol, r);
  }
  const std::string only =
      argc > 6 ? argv[6] : ""; // run only the cases (named or random kinds) containing this
  std::deque<Row> named_rows;
  std::vector<Job> jobs;
  for (const Case& c : named_cases()) {
    if (!only.empty() && c.name.find(only) == std::string::npos) continue;
    Row& row = named_rows.emplace_back();
    row.group = c.group, row.name = c.name;
    row.want_loops = c.loops, row.want_unbounded = c.unbounded;
    for (long i = 0; i < reps; ++i)
      jobs.push_back({&row, c.s1, c.s2, random_pose(rng, 100), c.half_width, std::nullopt, 0});
  }
  // Random natural-quadric pairs: sphere, circular cylinder, circular cone, plane (not two
  // planes), each with its own random rational pose, in the box [-3, 3]^3.
  std::map<std::string, Row> random_rows;
  for (long i = 0; i < random_pairs; ++i) {
    const Surf s1 = random_natural(rng, true);
    const Surf s2 = random_natural(rng, s1.kind != K::Plane);
    static const char* names[] = {"plane",     "sphere",     "cylinder",   "cone",
                                  "ellipsoid", "paraboloid", "hyperboloid"};
    std::string n1 = names[static_cast<int>(s1.kind)], n2 = names[static_cast<int>(s2.kind)];
    if (n2 < n1) std::swap(n1, n2);
    // The filter applies to the random kinds too (the same pairs are drawn either way).
    if (!only.empty() && (n1 + "-" + n2).find(only) == std::string::npos) continue;
    Row& row = random_rows[n1 + "-" + n2];
    row.group = "random natural", row.name = n1 + "-" + n2;
    jobs.push_back({&row, s1, s2, Pose{}, 3, std::nullopt, 0});
  }
  // SURFCERT_BENCH_JOB=k: the k-th pair only (counted without a case filter from 0; in a
  // SURFCERT_DUMP file it is the line with "index" k + 1, line 0 being the warm-up): one slow
  // pair under a profiler, with SURFCERT_PROFILE_REPEAT.
  if (const char* e = std::getenv("SURFCERT_BENCH_JOB")) {
    const long k = std::atol(e);
    if (k < 0 || static_cast<size_t>(k) >= jobs.size()) {
      std::fprintf(stderr, "SURFCERT_BENCH_JOB=%ld: only %zu pairs\n", k, jobs.size());
      return 2;
    }
    jobs = {jobs[static_cast<size_t>(k)]};
  }
  // SURFCERT_BENCH_NO_PEER=1: our side only (for a profiler: no OCCT samples, no ratios).
  const bool no_peer = std::getenv("SURFCERT_BENCH_NO_PEER") != nullptr;
  const auto progress = [&](size_t i, const char* side) {
    if ((i + 1) % 100 == 0 || i + 1 == jobs.size())
      std::fprintf(stderr, "\r%s: %zu of %zu pairs", side, i + 1, jobs.size());
    if (i + 1 == jobs.size()) std::fprintf(stderr, "\n");
  };
  for (size_t i = 0; i < jobs.size(); ++i) {
    run_ours(jobs[i], tol);
    if (interleaved && !no_peer) run_occt(jobs[i], occt_tol, ratios);
    progress(i, interleaved ? "surfcert and OCCT" : "surfcert");
  }
  if (!interleaved && !no_peer)
    for (size_t i = 0; i < jobs.size(); ++i) {
      run_occt(jobs[i], occt_tol, ratios);
      progress(i, "OCCT");
    }
  for (auto& r : named_rows)
    rows.push_back(std::move(r));
  for (auto& [k, r] : random_rows)
    rows.push_back(std::move(r));

  std::printf("| group | case | pairs | certified loops/unbounded | surfcert median us | of which "
              "classification | OCCT median us | OCCT/surfcert | surfcert undecided | surfcert "
              "wrong | OCCT pieces(closed) "
              "in box | OCCT wrong count | OCCT wrong closure | OCCT failed |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  Row total;
  for (const Row& r : rows) {
    const double mo = median(r.ours_us), mc = median(r.occt_us);
    std::printf("| %s | %s | %ld | %s%s | %.0f | %.0f (%ld exact) | %.0f | %.1f | %ld | %ld | %s | "
                "%ld | %ld | %ld |\n",
                r.group.c_str(), r.name.c_str(), r.pairs, keys(r.certified).c_str(),
                r.reference_missing
                    ? (" (" + std::to_string(r.reference_missing) + " not certified)").c_str()
                    : "",
                mo, median(r.classify_us), r.exact_fallbacks, mc, mo > 0 ? mc / mo : 0.0,
                r.ours_undecided, r.ours_wrong + r.hand_disagrees, keys(r.occt_seen).c_str(),
                r.occt_count, r.occt_closure, r.occt_failed);
    total.pairs += r.pairs;
    total.ours_us.insert(total.ours_us.end(), r.ours_us.begin(), r.ours_us.end());
    total.occt_us.insert(total.occt_us.end(), r.occt_us.begin(), r.occt_us.end());
    total.ours_undecided += r.ours_undecided;
    total.ours_wrong += r.ours_wrong + r.hand_disagrees;
    total.reference_missing += r.reference_missing;
    total.occt_count += r.occt_count;
    total.occt_closure += r.occt_closure;
    total.occt_failed += r.occt_failed;
  }
  std::printf("\nAll %ld pairs: surfcert mean %.0f us, median %.0f us; OCCT mean %.0f us, median "
              "%.0f us; OCCT/surfcert: ratio of means %.1f, median per-pair ratio %.1f.\n",
              total.pairs, mean(total.ours_us), median(total.ours_us), mean(total.occt_us),
              median(total.occt_us), mean(total.occt_us) / mean(total.ours_us), median(ratios));
  std::printf("surfcert: %ld undecided, %ld wrong (traced counts differing from a certified "
              "answer, or a certified answer differing from the hand-derived one); %ld pairs "
              "without a certified affine topology (excluded from the counts).\n",
              total.ours_undecided, total.ours_wrong, total.reference_missing);
  std::printf("OCCT: %ld wrong piece counts, %ld wrong closure (right count), %ld failed.\n",
              total.occt_count, total.occt_closure, total.occt_failed);
  // Where our time goes: each case's share of our total (the ratio of means is total against
  // total), its mean, and how many pairs needed the exact extreme points (a loop the float
  // start points missed: the costliest fallback of the tracer).
  {
    double sum = 0;
    for (const Row& r : rows)
      sum += mean(r.ours_us) * static_cast<double>(r.ours_us.size());
    std::printf("\nOur time by case (share of our total, mean us, pairs with exact start points):");
    for (const Row& r : rows)
      std::printf("%s %s %.1f%% %.0f %ld", &r == &rows.front() ? "" : ";", r.name.c_str(),
                  sum > 0 ? 100 * mean(r.ours_us) * static_cast<double>(r.ours_us.size()) / sum
                          : 0.0,
                  mean(r.ours_us), r.exact_starts);
    std::printf("\n");
  }
  std::printf("(intersect_peers_bench %ld %ld %lu %g %g; order %s; our input %s)\n", reps,
              random_pairs, seed, tol, occt_tol, interleaved ? "interleaved" : "blocked",
              doubles_mode() ? "matrices of doubles (SURFCERT_BENCH_DOUBLES)" : "exact rationals");
  { // The run's circumstances: machine, date (UTC), load; times above are thread CPU time.
    std::string cpu = "unknown CPU";
    if (FILE* f = std::fopen("/proc/cpuinfo", "r")) {
      char line[512];
      while (std::fgets(line, sizeof line, f))
        if (std::string l(line); l.rfind("model name", 0) == 0) {
          cpu = l.substr(l.find(':') + 2);
          cpu.erase(cpu.find_last_not_of(" \n") + 1);
          break;
        }
      std::fclose(f);
    }
    double load[3] = {0, 0, 0};
    getloadavg(load, 3);
    char date[64];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    std::printf("Machine: %s, %ld cores online; %s; load average %.2f %.2f %.2f at the end; "
                "times are thread CPU time per pair.\n",
                cpu.c_str(), sysconf(_SC_NPROCESSORS_ONLN), date, load[0], load[1], load[2]);
  }
  flint_cleanup();
  return 0;
}
