// double_path_bench: surfcert on double-valued input through the user's real path (issue 12):
// the whole `surfcert batch` process (parse + decide + print) on a JSONL file, timed from
// spawn to exit, against the peers run in-process on the same doubles (FCL 0.7 GJK for
// distances, Open CASCADE GeomAPI_IntSS for curves; each optional, see CMakeLists.txt).
//
// Pairs (seed 002 §5.1.3, drawn as doubles): centres uniform in [-1/2, 1/2]^3, semi-axes
// uniform in [1/10, 1], rotations uniformly random as double unit quaternions (normalised
// gaussian 4-vectors). Each pair is written twice: as shapes (centre, radii, quaternion) and
// as 4x4 matrices computed in double the way a numpy user would ((R @ D) @ R.T with
// D = diag(1/r^2), b = -A c, e = c.A.c - 1; not exactly symmetric, read as its symmetric
// part). The peers get the same doubles (centre, radii, the rotation matrix of the
// quaternion computed in double).
//
// Figures (markdown on stdout, progress on stderr):
//  1. classify, "detail": "topology", modes float / filtered / exact, --threads 1;
//  2. classify, --threads 2 vs --threads 1 on the same batch;
//  3. intersect (topology + every curve, tolerance 2e-4) vs OCCT on the same pairs;
//  4. distance, 15 digits, "detail": "value", separated pairs vs FCL (libccd, indep), FCL's
//     error against our enclosure (exact rational comparison); nested pairs;
//  5. extremes: spheres of radius 1e-200, 1e-320 and (1e-150 at 1e150) against the unit sphere.
// Usage: double_path_bench [--pairs N=100000] [--thread-lines N=100000] [--intersect N=1000]
//        [--occt N=100] [--distance N=2000] [--nested N=500] [--seed S=2026]
//        [--surfcert PATH (default: the build's app/surfcert)] [--tmp DIR=/tmp]
//        [--sections LIST=12345 (the figures to run, e.g. 45; the pairs stay the same)]
//        [--thread-runs N=5 (figure 2: runs of each thread count, in turn)]
//        [--keep 1 (keep the classify, threads, intersect and distance JSONL files in DIR, for
//        profiling and A/B runs)]
// (about two minutes on 2 cores; the JSONL files are written to DIR and removed).
#include "ellipsoid_params.hpp"

#include "surfcert/core/rational.hpp"

#ifdef SURFCERT_HAVE_FCL
#include "fcl_peer.hpp"
#endif
#ifdef SURFCERT_HAVE_OCCT
#include "occt_peer.hpp"
#endif

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

using surfcert::bench::EllipsoidParams;

namespace {

// ---------------------------------------------------------------- pairs as doubles

struct Ellipsoid {
  std::array<double, 3> c{}, r{};
  std::array<double, 4> q{1, 0, 0, 0}; ///< unit quaternion (w, x, y, z), normalised in double
  EllipsoidParams params() const;
};

std::array<std::array<double, 3>, 3> rotation_of(const std::array<double, 4>& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

EllipsoidParams Ellipsoid::params() const {
  EllipsoidParams p;
  p.centre = c;
  p.radii = r;
  p.rotation = rotation_of(q);
  return p;
}

std::array<double, 4> random_quaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    std::array<double, 4> q{g(rng), g(rng), g(rng), g(rng)};
    double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n < 1e-6) continue;
    for (double& v : q)
      v /= n;
    return q;
  }
}

Ellipsoid random_ellipsoid(std::mt19937_64& rng, double rmin = 0.1, double rmax = 1.0,
                           double cmax = 0.5) {
  std::uniform_real_distribution<double> cen(-cmax, cmax), rad(rmin, rmax);
  Ellipsoid e;
  for (double& v : e.c)
    v = cen(rng);
  for (double& v : e.r)
    v = rad(rng);
  e.q = random_quaternion(rng);
  return e;
}

struct Pair {
  Ellipsoid a, b;
};

// ---------------------------------------------------------------- JSON lines

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string vec(const double* v, size_t n) {
  std::string s = "[";
  for (size_t i = 0; i < n; ++i)
    s += (i ? "," : "") + num(v[i]);
  return s + "]";
}

std::string shape_json(const Ellipsoid& e) {
  return R"({"type":"ellipsoid","center":)" + vec(e.c.data(), 3) + R"(,"radii":)" +
         vec(e.r.data(), 3) + R"(,"rotation":{"quaternion":)" + vec(e.q.data(), 4) + "}}";
}

// The 4x4 matrix a numpy user would write: A = (R @ D) @ R.T, b = -A @ c, e = c @ A @ c - 1.
std::string matrix_json(const Ellipsoid& e) {
  auto R = e.params().rotation;
  double d[3], RD[3][3], A[3][3], b[3];
  for (size_t k = 0; k < 3; ++k)
    d[k] = 1.0 / (e.r[k] * e.r[k]);
  for (size_t i = 0; i < 3; ++i)
    for (size_t k = 0; k < 3; ++k)
      RD[i][k] = R[i][k] * d[k];
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      A[i][j] = RD[i][0] * R[j][0] + RD[i][1] * R[j][1] + RD[i][2] * R[j][2];
  for (size_t i = 0; i < 3; ++i)
    b[i] = -(A[i][0] * e.c[0] + A[i][1] * e.c[1] + A[i][2] * e.c[2]);
  double Ac[3];
  for (size_t i = 0; i < 3; ++i)
    Ac[i] = A[i][0] * e.c[0] + A[i][1] * e.c[1] + A[i][2] * e.c[2];
  double k = e.c[0] * Ac[0] + e.c[1] * Ac[1] + e.c[2] * Ac[2] - 1.0;
  double M[4][4] = {{A[0][0], A[0][1], A[0][2], b[0]},
                    {A[1][0], A[1][1], A[1][2], b[1]},
                    {A[2][0], A[2][1], A[2][2], b[2]},
                    {b[0], b[1], b[2], k}};
  std::string s = R"({"matrix":[)";
  for (size_t i = 0; i < 4; ++i)
    s += (i ? "," : "") + vec(M[i], 4);
  return s + "]}";
}

std::string line(size_t id, const char* op, const std::string& a, const std::string& b,
                 const std::string& extra) {
  return R"({"id":)" + std::to_string(id) + R"(,"op":")" + op + R"(","a":)" + a + R"(,"b":)" + b +
         extra + "}\n";
}

// ---------------------------------------------------------------- running surfcert batch

struct Answer {
  std::string status, morphology, relation, containment, lower, upper, method;
  bool fallback = false;
  double time_ms = NAN;
  int curves = -1;   ///< certified loops + conics + lines + cubics
  int branches = -1; ///< traced branches
};

struct Run {
  double wall_s = 0;
  double cpu_s = 0; ///< user + system time of the surfcert process
  size_t bytes = 0;
  std::vector<Answer> answers; ///< by id
  int exit_code = -1;
};

// The value of "key" in a flat JSON line: a string's contents or a scalar's text; "" when
// absent. Looks for the first occurrence at or after `from`.
std::string field(const std::string& s, const std::string& key, size_t from = 0) {
  std::string pat = "\"" + key + "\":";
  size_t p = s.find(pat, from);
  if (p == std::string::npos) return "";
  p += pat.size();
  if (s[p] == '"') {
    size_t e = s.find('"', p + 1);
    return s.substr(p + 1, e - p - 1);
  }
  size_t e = s.find_first_of(",}]", p);
  return s.substr(p, e - p);
}

int count_of(const std::string& s, const std::string& pat) {
  int n = 0;
  for (size_t p = s.find(pat); p != std::string::npos; p = s.find(pat, p + 1))
    ++n;
  return n;
}

Answer parse_answer(const std::string& l) {
  Answer a;
  a.status = field(l, "status");
  a.morphology = field(l, "morphology");
  a.relation = field(l, "ellipsoid_relation");
  a.containment = field(l, "containment");
  a.fallback = field(l, "exact_fallback") == "true";
  std::string t = field(l, "time_ms");
  if (!t.empty()) a.time_ms = std::strtod(t.c_str(), nullptr);
  size_t d = l.find("\"distance\":{");
  if (d != std::string::npos) {
    a.lower = field(l, "lower", d);
    a.upper = field(l, "upper", d);
  }
  a.method = field(l, "method");
  size_t comp = l.find("\"components\":{");
  if (comp != std::string::npos) {
    auto get = [&](const char* k) { return std::atoi(field(l, k, comp).c_str()); };
    a.curves = get("loops") + get("conics") + get("lines") + get("cubics");
  }
  size_t br = l.find("\"branches\":[");
  if (br != std::string::npos) {
    size_t end = l.find("\"isolated_points\":[", br);
    a.branches = count_of(l.substr(br, end - br), "\"kind\":");
  }
  return a;
}

std::string g_surfcert = SURFCERT_CLI_PATH;
std::string g_tmp = "/tmp";
bool g_keep = false; // keep the classify, threads, intersect and distance JSONL files

// A `surfcert batch` process started on input_path (its output to input_path + ".out").
struct Spawned {
  pid_t pid = 0;
  std::string out_path, err_path;
};

Spawned spawn_batch(const std::string& input_path, const std::vector<std::string>& args) {
  Spawned sp{0, input_path + ".out", input_path + ".err"};
  std::vector<std::string> argv_s{g_surfcert, "batch"};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : argv_s)
    argv.push_back(s.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, input_path.c_str(), O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, sp.out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, sp.err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (posix_spawn(&sp.pid, g_surfcert.c_str(), &fa, nullptr, argv.data(), environ) != 0) {
    std::fprintf(stderr, "cannot run %s\n", g_surfcert.c_str());
    std::exit(2);
  }
  posix_spawn_file_actions_destroy(&fa);
  return sp;
}

// Waits for sp and adds its CPU time and exit code to r.
void wait_batch(const Spawned& sp, Run& r) {
  int st = 0;
  struct rusage ru {};
  wait4(sp.pid, &st, 0, &ru);
  r.cpu_s += static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
             static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) * 1e-6;
  const int code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.exit_code = std::max(r.exit_code, code);
}

// Reads the answers of an ended process into r (ids below r's size) and removes its files.
void read_batch(const Spawned& sp, Run& r) {
  std::ifstream in(sp.out_path);
  std::string l;
  while (std::getline(in, l)) {
    r.bytes += l.size() + 1;
    size_t id = static_cast<size_t>(std::atol(field(l, "id").c_str()));
    if (id < r.answers.size()) r.answers[id] = parse_answer(l);
  }
  std::remove(sp.out_path.c_str());
  std::remove(sp.err_path.c_str());
}

// The wall time is spawn to exit: the answers are read afterwards.
Run run_batch(const std::string& input_path, const std::vector<std::string>& args, size_t lines) {
  Run r;
  r.answers.resize(lines);
  auto t0 = std::chrono::steady_clock::now();
  const Spawned sp = spawn_batch(input_path, args);
  wait_batch(sp, r);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  read_batch(sp, r);
  return r;
}

// Two `batch --threads 1` processes at once, one per input: the wall time from the first
// spawn to the last exit (what the machine gives two independent single-threaded processes).
Run run_batch_pair(const std::string& path_a, const std::string& path_b, size_t lines) {
  Run r;
  r.answers.resize(lines);
  auto t0 = std::chrono::steady_clock::now();
  const Spawned a = spawn_batch(path_a, {"--threads", "1"});
  const Spawned b = spawn_batch(path_b, {"--threads", "1"});
  wait_batch(a, r);
  wait_batch(b, r);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  read_batch(a, r);
  read_batch(b, r);
  return r;
}

std::string write_file(const std::string& name, const std::string& text) {
  std::string path = g_tmp + "/double_path_bench_" + std::to_string(getpid()) + "_" + name;
  std::ofstream(path) << text;
  return path;
}

// ---------------------------------------------------------------- statistics

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double mean(const std::vector<double>& v) {
  double s = 0;
  size_t n = 0;
  for (double x : v)
    if (!std::isnan(x)) s += x, ++n;
  return n ? s / static_cast<double>(n) : NAN;
}

std::vector<double> times_ms(const Run& r) {
  std::vector<double> t;
  for (const auto& a : r.answers)
    t.push_back(a.time_ms);
  return t;
}

long count_status(const Run& r, const char* s) {
  return std::count_if(r.answers.begin(), r.answers.end(),
                       [&](const Answer& a) { return a.status == s; });
}

std::string loadavg() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

void progress(const char* what) {
  std::fprintf(stderr, "double_path_bench: %s\n", what);
}

std::string machine() {
  std::ifstream in("/proc/cpuinfo");
  std::string l, model = "unknown CPU";
  while (std::getline(in, l))
    if (l.rfind("model name", 0) == 0) {
      model = l.substr(l.find(':') + 2);
      break;
    }
  char date[32];
  std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) +
         " cores (shared with other work; load average " + loadavg() + " at the start); " + date;
}

// ---------------------------------------------------------------- the figures

void classify_figures(const std::vector<Pair>& pairs) {
  const size_t n = pairs.size();
  std::printf("## 1. classify, `\"detail\": \"topology\"`, `batch --threads 1`\n\n");
  std::printf("%zu random pairs. Whole process: spawn to exit of `surfcert batch --mode M "
              "--threads 1` on the JSONL file (parse + decide + print), divided by the pairs; "
              "`time_ms`: the answers' own per-line wall time. Differing: morphology, "
              "ellipsoid_relation or containment not equal to the exact mode's answer.\n\n",
              n);
  std::printf("| input | mode | whole process µs/pair | median `time_ms` µs | bytes/line | "
              "differing from exact | exact fallbacks | certified |\n|---|---|---|---|---|---|"
              "---|---|\n");
  std::map<std::string, std::map<std::string, double>> per_pair;
  std::vector<Run> exact_runs;
  for (int form = 0; form < 2; ++form) {
    std::string text;
    for (size_t i = 0; i < n; ++i) {
      const auto& p = pairs[i];
      text +=
          form == 0
              ? line(i, "classify", shape_json(p.a), shape_json(p.b), R"(,"detail":"topology")")
              : line(i, "classify", matrix_json(p.a), matrix_json(p.b), R"(,"detail":"topology")");
    }
    const char* form_name = form == 0 ? "shapes (quaternion)" : "4x4 matrices";
    std::string path = write_file(form == 0 ? "classify_q.jsonl" : "classify_m.jsonl", text);
    std::map<std::string, Run> runs;
    for (const char* mode : {"exact", "filtered", "float"}) {
      progress((std::string("classify ") + form_name + " " + mode).c_str());
      runs[mode] = run_batch(path, {"--mode", mode, "--threads", "1"}, n);
    }
    const Run& ex = runs["exact"];
    for (const char* mode : {"float", "filtered", "exact"}) {
      const Run& r = runs[mode];
      long differ = 0, fallbacks = 0;
      for (size_t i = 0; i < n; ++i) {
        const auto &a = r.answers[i], &e = ex.answers[i];
        if (a.morphology != e.morphology || a.relation != e.relation ||
            a.containment != e.containment)
          ++differ;
        fallbacks += a.fallback;
      }
      double us = r.wall_s / static_cast<double>(n) * 1e6;
      per_pair[form_name][mode] = us;
      std::printf("| %s | %s | %.2f | %.2f | %.0f | %s | %s | %ld |\n", form_name, mode, us,
                  median(times_ms(r)) * 1e3, static_cast<double>(r.bytes) / static_cast<double>(n),
                  std::string(mode) == "exact" ? "(reference)" : std::to_string(differ).c_str(),
                  std::string(mode) == "filtered" ? std::to_string(fallbacks).c_str() : "-",
                  count_status(r, "certified"));
    }
    exact_runs.push_back(runs["exact"]);
    if (!g_keep) std::remove(path.c_str());
  }
  std::printf("\n");
  for (const auto& [form, m] : per_pair)
    std::printf("%s: filtered / float = %.2f (whole process); exact / filtered = %.1f.\n",
                form.c_str(), m.at("filtered") / m.at("float"), m.at("exact") / m.at("filtered"));
  long form_differ = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto &a = exact_runs[0].answers[i], &b = exact_runs[1].answers[i];
    form_differ += a.morphology != b.morphology || a.relation != b.relation;
  }
  std::printf("Pairs whose exact answer differs between the quaternion and the matrix input "
              "(two slightly different exact surfaces): %ld of %zu.\n\n",
              form_differ, n);
}

// Figure 2: --threads 1, --threads 2, and two independent --threads 1 processes on the two
// halves of the file, run in turn (1 2 P 1 2 P ...), g_thread_runs times each: the median and
// the fastest run of each. On a shared machine the runs meet the same load drift; the fastest
// are the nearest to an idle machine. The two-process figure is the machine's own ceiling for
// two single-threaded workers (shared caches, memory bandwidth, a host's frequency policy):
// two threads / two processes is what the batch's threading itself costs.
size_t g_thread_runs = 5;

void thread_figures(const std::vector<Pair>& pairs) {
  const size_t n = pairs.size();
  std::string text, halves[2];
  for (size_t i = 0; i < n; ++i) {
    const std::string l = line(i, "classify", shape_json(pairs[i].a), shape_json(pairs[i].b),
                               R"(,"detail":"topology")");
    text += l;
    halves[i < n / 2 ? 0 : 1] += l;
  }
  std::string path = write_file("threads.jsonl", text);
  std::string half_paths[2] = {write_file("threads_a.jsonl", halves[0]),
                               write_file("threads_b.jsonl", halves[1])};
  const std::string load = loadavg();
  std::vector<Run> runs[3];
  for (size_t k = 0; k < g_thread_runs; ++k)
    for (int t : {1, 2, 3}) {
      progress(t == 1 ? "threads 1" : t == 2 ? "threads 2" : "two processes");
      runs[t - 1].push_back(t == 3 ? run_batch_pair(half_paths[0], half_paths[1], n)
                                   : run_batch(path, {"--threads", std::to_string(t)}, n));
    }
  if (!g_keep)
    for (const std::string& p : {path, half_paths[0], half_paths[1]})
      std::remove(p.c_str());
  std::printf("## 2. two threads vs one (classify, filtered, topology)\n\n");
  std::printf("%zu lines (shapes with quaternions): `batch --threads 1`, `--threads 2`, and two "
              "independent `--threads 1` processes on the two halves of the file at once (the "
              "machine's ceiling for two single-threaded workers), run in turn, %zu runs each. "
              "The machine has %u cores, shared with other work (load average %s before the "
              "runs, %s after). CPU s: user + system time of the process(es); CPU / wall near 2 "
              "means two cores ran.\n\n",
              n, g_thread_runs, std::thread::hardware_concurrency(), load.c_str(),
              loadavg().c_str());
  std::printf("| workers | run | whole process s | µs/pair | CPU s | CPU / wall | certified |\n"
              "|---|---|---|---|---|---|---|\n");
  const char* names[3] = {"1 thread", "2 threads", "2 processes"};
  double best[3], median[3];
  for (int t : {0, 1, 2}) {
    std::vector<Run*> by_wall;
    for (auto& r : runs[t])
      by_wall.push_back(&r);
    std::sort(by_wall.begin(), by_wall.end(),
              [](const Run* x, const Run* y) { return x->wall_s < y->wall_s; });
    const Run* picks[2] = {by_wall.front(), by_wall[by_wall.size() / 2]};
    best[t] = picks[0]->wall_s;
    median[t] = picks[1]->wall_s;
    for (int k : {0, 1}) {
      const Run& r = *picks[k];
      std::printf("| %s | %s | %.3f | %.2f | %.3f | %.2f | %ld |\n", names[t],
                  k == 0 ? "fastest" : "median", r.wall_s, r.wall_s / static_cast<double>(n) * 1e6,
                  r.cpu_s, r.cpu_s / r.wall_s, count_status(r, "certified"));
    }
  }
  // Runs k of each series ran back to back: their ratios pair runs under the same load.
  std::vector<double> paired;
  for (size_t k = 0; k < g_thread_runs; ++k)
    paired.push_back(runs[0][k].wall_s / runs[1][k].wall_s);
  std::sort(paired.begin(), paired.end());
  std::printf("\nSpeed-up two threads / one: %.2f× (fastest runs), %.2f× (medians), %.2f× "
              "(median of the ratios of runs side by side). Two processes / one thread: %.2f× "
              "(fastest), %.2f× (medians): two threads reach %.0f%% of it (medians).\n\n",
              best[0] / best[1], median[0] / median[1], paired[paired.size() / 2],
              best[0] / best[2], median[0] / median[2], 100.0 * median[2] / median[1]);
}

void intersect_figures(const std::vector<Pair>& pairs, size_t occt_pairs) {
  const size_t n = pairs.size();
  const double tol = 2e-4;
  std::string text;
  for (size_t i = 0; i < n; ++i)
    text += line(i, "intersect", shape_json(pairs[i].a), shape_json(pairs[i].b),
                 R"(,"detail":"topology","tolerance":)" + num(tol));
  std::string path = write_file("intersect.jsonl", text);
  progress("intersect");
  Run r = run_batch(path, {"--threads", "1"}, n);
  if (!g_keep) std::remove(path.c_str());
  std::printf("## 3. intersect: topology + every curve (tolerance 2e-4), vs Open CASCADE\n\n");
  double ours_us = r.wall_s / static_cast<double>(n) * 1e6;
  long match = 0;
  for (const auto& a : r.answers)
    match += a.status == "certified" && a.curves == a.branches;
  std::printf("surfcert `batch --threads 1`, %zu pairs (shapes with quaternions, `\"detail\": "
              "\"topology\"`): whole process %.2f µs/pair, median `time_ms` %.2f µs, mean "
              "%.2f µs; %.0f bytes/line; certified with branches matching the certified "
              "topology: %ld of %zu.\n\n",
              n, ours_us, median(times_ms(r)) * 1e3, mean(times_ms(r)) * 1e3,
              static_cast<double>(r.bytes) / static_cast<double>(n), match, n);
#ifdef SURFCERT_HAVE_OCCT
  occt_pairs = std::min(occt_pairs, n);
  std::vector<double> occt_us, ours_sub_us, ratio;
  long equal = 0, glued_equal = 0, failed = 0, compared = 0;
  for (size_t i = 0; i < occt_pairs; ++i) {
    if (i % 50 == 0) progress(("OCCT " + std::to_string(i)).c_str());
    auto o = surfcert::bench::occt_intersect(pairs[i].a.params(), pairs[i].b.params(), tol);
    const Answer& a = r.answers[i];
    if (!o.ok) {
      ++failed;
      continue;
    }
    occt_us.push_back(o.seconds * 1e6);
    ours_sub_us.push_back(a.time_ms * 1e3);
    ratio.push_back(o.seconds * 1e6 / (a.time_ms * 1e3));
    if (a.status != "certified") continue;
    ++compared;
    equal += o.branches == a.curves;
    glued_equal += o.glued_branches == a.curves;
  }
  std::printf("OCCT %s `GeomAPI_IntSS` (the ellipsoids as rational B-spline surfaces from the "
              "same doubles) on the first %zu of these pairs, in-process (construction + "
              "NbLines timed):\n\n",
              surfcert::bench::occt_version().c_str(), occt_pairs);
  std::printf("| side | pairs | median µs/pair | mean µs/pair |\n|---|---|---|---|\n");
  std::printf("| surfcert, whole process / pairs (all pairs) | %zu | - | %.2f |\n", n, ours_us);
  std::printf("| surfcert `time_ms`, the OCCT pairs | %zu | %.2f | %.2f |\n", ours_sub_us.size(),
              median(ours_sub_us), mean(ours_sub_us));
  std::printf("| OCCT GeomAPI_IntSS (successful runs) | %zu | %.2f | %.2f |\n", occt_us.size(),
              median(occt_us), mean(occt_us));
  std::printf("\nOCCT / surfcert: %.0f× (OCCT mean / surfcert whole-process mean), %.0f× "
              "(medians, per line), per-pair ratio median %.0f×. OCCT failed on %ld pairs.\n",
              mean(occt_us) / ours_us, median(occt_us) / median(ours_sub_us), median(ratio),
              failed);
  std::printf("OCCT's curve count against our certified component count (loops + conics + "
              "lines + cubics) on %ld pairs: NbLines equal on %ld (%ld differ; OCCT often cuts "
              "one closed curve at the B-spline seam), lines with coincident ends joined equal "
              "on %ld (%ld differ).\n\n",
              compared, equal, compared - equal, glued_equal, compared - glued_equal);
#else
  (void)occt_pairs;
  std::printf("Open CASCADE peer not built (SURFCERT_BENCH_OCCT=OFF): surfcert figures "
              "only.\n\n");
#endif
}

#ifdef SURFCERT_HAVE_FCL
// How far an FCL distance lies outside the certified enclosure [lower, upper] (decimal
// strings, outward rounded), compared exactly: max(0, lower - d, d - upper).
double error_outside(double d, const std::string& lower, const std::string& upper) {
  using surfcert::core::Rational;
  auto lo = Rational::from_string(lower), hi = Rational::from_string(upper);
  if (!lo || !hi) return NAN;
  Rational x = Rational::exact_from_double(d);
  if (x < *lo) return (*lo - x).to_double_approx();
  if (*hi < x) return (x - *hi).to_double_approx();
  return 0;
}
#endif

void distance_figures(const std::vector<Pair>& separated, const std::vector<Pair>& nested) {
  std::printf("## 4. distance, 15 digits, certified (`\"detail\": \"value\"`), vs FCL GJK\n\n");
  for (int family = 0; family < 2; ++family) {
    const auto& pairs = family == 0 ? separated : nested;
    const size_t n = pairs.size();
    std::string text;
    for (size_t i = 0; i < n; ++i)
      text += line(i, "distance", shape_json(pairs[i].a), shape_json(pairs[i].b),
                   R"(,"detail":"value","digits":15)");
    std::string path =
        write_file(family == 0 ? "distance_separated.jsonl" : "distance_nested.jsonl", text);
    progress(family == 0 ? "distance separated" : "distance nested");
    Run r = run_batch(path, {"--threads", "1"}, n);
    size_t slowest = 0;
    for (size_t i = 0; i < n; ++i)
      if (r.answers[i].time_ms > r.answers[slowest].time_ms) slowest = i;
    if (!g_keep)
      std::remove(path.c_str());
    else
      std::fprintf(stderr, "kept %s\n", path.c_str());
    std::map<std::string, long> methods;
    for (const auto& a : r.answers)
      ++methods[a.method.empty() ? "(none)" : a.method];
    std::string m;
    for (const auto& [k, v] : methods)
      m += (m.empty() ? "" : ", ") + k + " " + std::to_string(v);
    double us = r.wall_s / static_cast<double>(n) * 1e6;
    const std::vector<double> t_ms = times_ms(r);
    double max_ms = 0;
    long over_100ms = 0;
    for (double t : t_ms)
      if (!std::isnan(t)) max_ms = std::max(max_ms, t), over_100ms += t > 100;
    std::printf("%s: %zu pairs, surfcert `batch --threads 1`: whole process **%.2f µs/pair**, "
                "median `time_ms` %.2f µs, mean %.2f µs, max %.2f ms (%ld lines over 100 ms); %.0f "
                "bytes/line; certified %ld, undecided %ld; methods: %s.\n\n",
                family == 0 ? "**Separated pairs** (second centre pushed out along a random "
                              "direction by the sum of the largest semi-axes + [0.01, 1])"
                            : "**Nested pairs** (a random recipe ellipsoid inside one of "
                              "semi-axes in [3, 4], centre in [-0.3, 0.3]^3)",
                n, us, median(times_ms(r)) * 1e3, mean(times_ms(r)) * 1e3, max_ms, over_100ms,
                static_cast<double>(r.bytes) / static_cast<double>(n), count_status(r, "certified"),
                count_status(r, "undecided"), m.c_str());
    if (n)
      std::printf("Slowest line (%.1f ms, %s):\n\n```\n%s```\n\n", r.answers[slowest].time_ms,
                  r.answers[slowest].method.c_str(),
                  line(slowest, "distance", shape_json(pairs[slowest].a),
                       shape_json(pairs[slowest].b), R"(,"detail":"value","digits":15)")
                      .c_str());
    if (family == 1) break;
#ifdef SURFCERT_HAVE_FCL
    using surfcert::bench::FclOptions;
    using surfcert::bench::FclSolver;
    std::printf("FCL %s `fcl::distance` on fcl::Ellipsoidd shapes with the same doubles, "
                "in-process (the call only). Error: distance outside our certified enclosure, "
                "compared exactly.\n\n",
                surfcert::bench::fcl_version().c_str());
    std::printf("| FCL solver | tolerance | median µs/pair | mean µs/pair | surfcert / FCL "
                "(whole process / mean) | surfcert / FCL (medians, per line) | max error | pairs "
                "with error > 1e-6 (1 + d) | overlap answered |\n"
                "|---|---|---|---|---|---|---|---|---|\n");
    for (FclSolver s : {FclSolver::Libccd, FclSolver::Indep})
      for (double tol : {1e-6, 1e-12}) {
        FclOptions o;
        o.solver = s;
        o.tolerance = tol;
        std::vector<double> t;
        double max_err = 0;
        long bad = 0, overlap = 0;
        for (size_t i = 0; i < n; ++i) {
          auto f = surfcert::bench::fcl_distance(pairs[i].a.params(), pairs[i].b.params(), o);
          t.push_back(f.seconds * 1e6);
          const Answer& a = r.answers[i];
          if (!f.ok || f.distance < 0) {
            ++overlap;
            continue;
          }
          if (a.status != "certified") continue;
          double e = error_outside(f.distance, a.lower, a.upper);
          max_err = std::max(max_err, e);
          bad += e > 1e-6 * (1 + f.distance);
        }
        std::printf("| %s | %g | %.2f | %.2f | %.1f× | %.1f× | %.2e | %ld | %ld |\n",
                    surfcert::bench::fcl_solver_name(s), tol, median(t), mean(t), us / mean(t),
                    median(t_ms) * 1e3 / median(t), max_err, bad, overlap);
      }
    std::printf("\n");
#else
    std::printf("FCL peer not built (SURFCERT_BENCH_FCL=OFF): surfcert figures only.\n\n");
#endif
  }
}

void extreme_figures() {
  std::printf("## 5. extremes\n\n");
  std::printf("Each case is its own `surfcert batch` process of two lines: a warm-up line (two "
              "ordinary spheres, same op) and the case; `time_ms` is the case line's own, "
              "\"first line\" the warm-up line's (a process's first answer pays one-time "
              "initialisation).\n\n");
  std::printf("| case | op | whole process ms | `time_ms` | first line `time_ms` | status | "
              "answer |\n|---|---|---|---|---|---|---|\n");
  struct Case {
    const char* name;
    std::string a;
  };
  const std::string unit = R"({"type":"sphere","center":[0,0,0],"radius":1})";
  std::vector<Case> cases = {
      {"radius 1e-200 at 0", R"({"type":"sphere","center":[0,0,0],"radius":1e-200})"},
      {"radius 1e-320 (subnormal) at 0", R"({"type":"sphere","center":[0,0,0],"radius":1e-320})"},
      {"radius 1e-150 at (1e150, 0, 0)",
       R"({"type":"sphere","center":[1e150,0,0],"radius":1e-150})"}};
  for (const auto& c : cases)
    for (const char* op : {"classify", "distance"}) {
      std::string extra = std::string(op) == "classify" ? R"(,"detail":"topology")"
                                                        : R"(,"detail":"value","digits":15)";
      const std::string warm = R"({"type":"sphere","center":[0,0,0.25],"radius":0.5})";
      std::string path = write_file("extreme.jsonl",
                                    line(0, op, warm, unit, extra) + line(1, op, c.a, unit, extra));
      Run r = run_batch(path, {"--threads", "1"}, 2);
      std::remove(path.c_str());
      const Answer& a = r.answers[1];
      std::string ans = std::string(op) == "classify"
                            ? a.morphology + ", " + a.relation +
                                  (a.containment.empty() ? "" : ", " + a.containment)
                            : "[" + a.lower + ", " + a.upper + "]";
      std::printf("| sphere %s vs unit sphere | %s | %.2f | %.3f | %.3f | %s | %s |\n", c.name, op,
                  r.wall_s * 1e3, a.time_ms, r.answers[0].time_ms, a.status.c_str(), ans.c_str());
    }
  std::string path = write_file("empty.jsonl", "");
  Run r = run_batch(path, {"--threads", "1"}, 0);
  std::remove(path.c_str());
  std::printf("\nProcess start and exit alone (an empty batch): %.2f ms.\n\n", r.wall_s * 1e3);
}

} // namespace

int main(int argc, char** argv) {
  size_t pairs = 100000, thread_lines = 100000, inter = 1000, occt = 100, dist = 2000, nested = 500;
  unsigned long seed = 2026;
  std::string sections = "12345";
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string k = argv[i];
    const char* v = argv[i + 1];
    auto z = static_cast<size_t>(std::atol(v));
    if (k == "--pairs")
      pairs = z;
    else if (k == "--thread-lines")
      thread_lines = z;
    else if (k == "--intersect")
      inter = z;
    else if (k == "--occt")
      occt = z;
    else if (k == "--distance")
      dist = z;
    else if (k == "--nested")
      nested = z;
    else if (k == "--seed")
      seed = std::strtoul(v, nullptr, 10);
    else if (k == "--surfcert")
      g_surfcert = v;
    else if (k == "--tmp")
      g_tmp = v;
    else if (k == "--sections")
      sections = v;
    else if (k == "--thread-runs")
      g_thread_runs = std::max<size_t>(1, static_cast<size_t>(z));
    else if (k == "--keep")
      g_keep = z != 0;
    else {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      return 2;
    }
  }
  std::mt19937_64 rng(seed);
  // One list of random pairs: figures 1-3 use its prefixes (the same pairs).
  std::vector<Pair> random(std::max({pairs, thread_lines, inter}));
  for (auto& p : random)
    p = {random_ellipsoid(rng), random_ellipsoid(rng)};
  std::vector<Pair> separated(dist), nest(nested);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> gap(0.01, 1.0);
  for (auto& p : separated) {
    p = {random_ellipsoid(rng), random_ellipsoid(rng)};
    double d[3] = {g(rng), g(rng), g(rng)};
    double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double push = *std::max_element(p.a.r.begin(), p.a.r.end()) +
                  *std::max_element(p.b.r.begin(), p.b.r.end()) + gap(rng);
    for (size_t k = 0; k < 3; ++k)
      p.b.c[k] = p.a.c[k] + d[k] / len * push;
  }
  for (auto& p : nest)
    p = {random_ellipsoid(rng), random_ellipsoid(rng, 3.0, 4.0, 0.3)};

  std::printf("# double_path_bench: surfcert on double input, whole `surfcert batch` process\n\n");
  std::printf("Machine: %s. surfcert: %s. Seed %lu.\n\n", machine().c_str(), g_surfcert.c_str(),
              seed);
  std::printf("Pairs (seed 002 §5.1.3 as doubles): centres uniform in [-1/2, 1/2]^3, semi-axes "
              "in [1/10, 1], uniformly random rotations as double unit quaternions; the same "
              "pairs as numpy-style double 4x4 matrices.\n\n");
  auto run = [&](char c) { return sections.find(c) != std::string::npos; };
  if (run('1')) classify_figures({random.begin(), random.begin() + static_cast<long>(pairs)});
  if (run('2')) thread_figures({random.begin(), random.begin() + static_cast<long>(thread_lines)});
  if (run('3'))
    intersect_figures({random.begin(), random.begin() + static_cast<long>(inter)}, occt);
  if (run('4')) distance_figures(separated, nest);
  if (run('5')) extreme_figures();
  return 0;
}
