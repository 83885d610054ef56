// shape_distance_check: cross-checks certified surface distances (ellipsoid/sphere against a
// ring torus, a capsule, a canal surface; a cubic graph against a sphere) with an independent
// floating-point search (dense sampling + local pattern search; no library code in it).
// For every certified result: lower <= f + 1e-9, f being the float distance (an upper bound
// of the true distance; 0 when the float search sees the surfaces cross). Also counts
// f - upper > 1e-6 (float search stuck) and certified 0 with f > 1e-3 (suspicious).
// Usage: shape_distance_check [cases=40] [seed=2026] [digits=15]
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <flint/flint.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

using namespace surfcert;

namespace {

using V3 = std::array<double, 3>;
V3 add(V3 a, V3 b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
V3 sub(V3 a, V3 b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
V3 mul(V3 a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
double dot(V3 a, V3 b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(V3 a) {
  return std::sqrt(dot(a, a));
}

// ---- exact decimals: integers in thousandths -------------------------------------------
std::string dec(long n) { // n / 1000 as an exact decimal string
  std::string s = n < 0 ? "-" : "";
  long a = std::labs(n);
  s += std::to_string(a / 1000);
  long f = a % 1000;
  if (f) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "%03ld", f);
    std::string fs = buf;
    while (fs.back() == '0')
      fs.pop_back();
    s += "." + fs;
  }
  return s;
}
std::string jnum(long n) {
  return "\"" + dec(n) + "\"";
}
std::string jvec(const std::array<long, 3>& v) {
  return "[" + jnum(v[0]) + "," + jnum(v[1]) + "," + jnum(v[2]) + "]";
}
double val(long n) {
  return static_cast<double>(n) / 1000.0;
}
V3 val3(const std::array<long, 3>& v) {
  return {val(v[0]), val(v[1]), val(v[2])};
}

std::mt19937_64 rng;
// uniform multiple of `step` thousandths in [lo, hi] (thousandths)
long rnd(long lo, long hi, long step = 10) {
  std::uniform_int_distribution<long> d(lo / step, hi / step);
  return d(rng) * step;
}
double urand() {
  return std::uniform_real_distribution<double>(0, 1)(rng);
}
V3 rand_dir() {
  std::normal_distribution<double> n(0, 1);
  for (;;) {
    V3 v{n(rng), n(rng), n(rng)};
    double l = norm(v);
    if (l > 1e-3) return mul(v, 1 / l);
  }
}

// ---- float search --------------------------------------------------------------------------
// A 2-parameter surface patch A(u, v) and a signed distance-like function g to B.
// Returns min over samples/refinements of |g| (objective), and whether g changes sign.
struct FloatResult {
  double f = 1e300; ///< min |g| found (upper bound of the distance when |g| is exact)
  bool neg = false, pos = false;
  double gmin = 1e300; ///< smallest signed value seen (-penetration depth when negative)
  V3 best{};
  double signed_gap() const { return neg ? gmin : f; } ///< for the placement only
};

FloatResult float_min(const std::function<V3(double, double)>& A, double u0, double u1, double v0,
                      double v1, bool u_periodic, int nu, int nv,
                      const std::function<double(const V3&)>& g, int refine_count) {
  FloatResult out;
  struct S {
    double val, u, v;
  };
  std::vector<S> s;
  s.reserve(static_cast<size_t>(nu + 1) * (nv + 1));
  const double du = (u1 - u0) / nu, dv = (v1 - v0) / nv;
  for (int i = 0; i <= nu - (u_periodic ? 1 : 0); ++i)
    for (int j = 0; j <= nv; ++j) {
      double u = u0 + du * i, v = v0 + dv * j;
      double gv = g(A(u, v));
      out.gmin = std::min(out.gmin, gv);
      if (gv < 0) out.neg = true;
      if (gv > 0) out.pos = true;
      s.push_back({std::fabs(gv), u, v});
    }
  std::partial_sort(s.begin(), s.begin() + std::min<size_t>(s.size(), 64), s.end(),
                    [](const S& a, const S& b) { return a.val < b.val; });
  // refine the best few, skipping starts close (in parameters) to one already refined
  std::vector<S> starts;
  for (size_t k = 0; k < std::min<size_t>(s.size(), 64) && (int)starts.size() < refine_count; ++k) {
    bool near = false;
    for (const auto& t : starts)
      if (std::fabs(t.u - s[k].u) < 3 * du && std::fabs(t.v - s[k].v) < 3 * dv) near = true;
    if (!near) starts.push_back(s[k]);
  }
  auto clampv = [&](double v) { return std::min(v1, std::max(v0, v)); };
  auto clampu = [&](double u) { return u_periodic ? u : std::min(u1, std::max(u0, u)); };
  for (auto st : starts) {
    double u = st.u, v = st.v, best = st.val;
    double hu = du, hv = dv;
    for (int it = 0; it < 4000 && (hu > 1e-13 || hv > 1e-13); ++it) {
      bool improved = false;
      const double cand[8][2] = {{hu, 0},  {-hu, 0},  {0, hv},   {0, -hv},
                                 {hu, hv}, {-hu, hv}, {hu, -hv}, {-hu, -hv}};
      for (const auto& c : cand) {
        double nu2 = clampu(u + c[0]), nv2 = clampv(v + c[1]);
        double gv = g(A(nu2, nv2));
        if (gv < 0) out.neg = true;
        if (gv > 0) out.pos = true;
        if (std::fabs(gv) < best) {
          best = std::fabs(gv), u = nu2, v = nv2, improved = true;
          break;
        }
      }
      if (!improved) hu *= 0.5, hv *= 0.5;
    }
    if (best < out.f) out.f = best, out.best = A(u, v);
  }
  for (const auto& x : s)
    if (x.val < out.f) out.f = x.val, out.best = A(x.u, x.v);
  return out;
}

// ---- shapes in double ----------------------------------------------------------------------
struct Ell {
  V3 c, a;
};
V3 ell_point(const Ell& e, double u, double v) { // u in [0, 2pi), v in [0, pi]
  return {e.c[0] + e.a[0] * std::cos(u) * std::sin(v), e.c[1] + e.a[1] * std::sin(u) * std::sin(v),
          e.c[2] + e.a[2] * std::cos(v)};
}
FloatResult float_ell(const Ell& e, const std::function<double(const V3&)>& g, bool fine) {
  return float_min([&](double u, double v) { return ell_point(e, u, v); }, 0, 2 * M_PI, 0, M_PI,
                   true, fine ? 360 : 48, fine ? 180 : 24, g, fine ? 12 : 2);
}

struct TorusD {
  V3 c, n; // n unit
  double R, r;
  double g(const V3& p) const { // signed distance to the tube surface (exact)
    V3 d = sub(p, c);
    double h = dot(d, n);
    double rho = norm(sub(d, mul(n, h)));
    return std::hypot(rho - R, h) - r;
  }
};
double seg_dist(const V3& p, const V3& a, const V3& b) {
  V3 ab = sub(b, a);
  double t = std::clamp(dot(sub(p, a), ab) / dot(ab, ab), 0.0, 1.0);
  return norm(sub(p, add(a, mul(ab, t))));
}
struct CanalD { // C(t) = p0 + p1 t + p2 t^2, r(t) = r0 + r1 t, t in [0, 1]
  V3 p0, p1, p2;
  double r0, r1;
  double h(const V3& p, double t) const {
    V3 C = add(p0, add(mul(p1, t), mul(p2, t * t)));
    return norm(sub(p, C)) - (r0 + r1 * t);
  }
  double g(const V3& p) const { // min_t |p - C(t)| - r(t): exact distance for outside points
    const int N = 64;
    double best = 1e300;
    int bi = 0;
    for (int i = 0; i <= N; ++i) {
      double v = h(p, double(i) / N);
      if (v < best) best = v, bi = i;
    }
    double lo = std::max(0.0, double(bi - 1) / N), hi = std::min(1.0, double(bi + 1) / N);
    const double gr = (std::sqrt(5.0) - 1) / 2;
    double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
    double f1 = h(p, x1), f2 = h(p, x2);
    for (int it = 0; it < 60; ++it) {
      if (f1 < f2)
        hi = x2, x2 = x1, f2 = f1, x1 = hi - gr * (hi - lo), f1 = h(p, x1);
      else
        lo = x1, x1 = x2, f1 = f2, x2 = lo + gr * (hi - lo), f2 = h(p, x2);
    }
    return std::min({best, f1, f2});
  }
};
struct Graph { // z = a x^3 + b x y^2 + c x + d
  double a, b, c, d;
  V3 at(double x, double y) const { return {x, y, a * x * x * x + b * x * y * y + c * x + d}; }
};
FloatResult float_graph(const Graph& G, const V3& sc, double rho, bool fine) {
  V3 q0 = G.at(sc[0], sc[1]);
  // Every graph point within rho + D0 of the centre (D0 = distance to the point below it) has
  // (x, y) within L of (cx, cy): this covers the nearest points and any crossing.
  double L = norm(sub(sc, q0)) + rho + 1e-3;
  auto g = [&](const V3& p) { return norm(sub(p, sc)) - rho; };
  return float_min([&](double x, double y) { return G.at(x, y); }, sc[0] - L, sc[0] + L, sc[1] - L,
                   sc[1] + L, false, fine ? 400 : 60, fine ? 400 : 60, g, fine ? 12 : 2);
}

// ---- cases ---------------------------------------------------------------------------------
struct Case {
  int family;
  std::string ja, jb;                  ///< JSON texts for read_surface
  std::string cla, clb;                ///< CLI arguments
  double f = 0;                        ///< float distance (0 when crossing seen)
  bool crossing = false;               ///< float search saw a sign change
  bool inside = false;                 ///< float: A entirely inside B (canal): f unusable
  double target = 0;                   ///< intended signed gap
  std::function<double(const V3&)> gB; ///< float distance-like function to B (diagnostic)
};

// Scan s from +8 down (translation of B by s*dir); return s where the coarse signed gap
// first drops below target (bisected), or the s of the smallest gap seen.
double place(const std::function<double(double)>& sd, double target, bool* hit = nullptr) {
  if (hit) *hit = true;
  double prev_s = 8, prev = sd(prev_s), best_s = prev_s, best = prev;
  for (double s = 8 - 0.1; s > -8; s -= 0.1) {
    double v = sd(s);
    if (v < best) best = v, best_s = s;
    if (v < target) {
      double lo = s, hi = prev_s; // sd(lo) < target <= sd(hi)
      for (int it = 0; it < 25; ++it) {
        double m = 0.5 * (lo + hi);
        (sd(m) < target ? lo : hi) = m;
      }
      return hi;
    }
    prev_s = s, prev = v;
  }
  if (hit) *hit = false;
  return best_s;
}

double pick_target() {
  double u = urand();
  if (u < 0.1) return -0.05 + 0.05 * urand(); // crossing
  if (u < 0.22) return 0.02 * urand();        // nearly touching
  return 0.05 + 1.5 * urand();
}

std::array<long, 3> round3(const V3& v) {
  return {std::lround(v[0] * 1000), std::lround(v[1] * 1000), std::lround(v[2] * 1000)};
}

struct EllI {
  std::array<long, 3> c, a;
  bool sphere = false;
  Ell d() const { return {val3(c), val3(a)}; }
  std::string json() const {
    if (sphere)
      return "{\"type\":\"sphere\",\"center\":" + jvec(c) + ",\"radius\":" + jnum(a[0]) + "}";
    return "{\"type\":\"ellipsoid\",\"center\":" + jvec(c) + ",\"radii\":" + jvec(a) + "}";
  }
};
EllI rand_ell(bool sphere) {
  EllI e;
  for (int i = 0; i < 3; ++i)
    e.c[i] = rnd(-2000, 2000), e.a[i] = rnd(300, 1500);
  if (sphere) e.a[1] = e.a[2] = e.a[0], e.sphere = true;
  return e;
}

void finish_float(Case& k, const Ell& e, bool canal) {
  FloatResult fr = float_ell(e, k.gB, true);
  k.crossing = fr.neg && fr.pos;
  k.inside = canal && fr.neg && !fr.pos;
  k.f = k.crossing ? 0 : fr.f;
}

Case make_torus_case() {
  Case k;
  k.family = 1;
  EllI e = rand_ell(false);
  std::array<long, 3> ax;
  do
    for (auto& x : ax)
      x = rnd(-2000, 2000, 1000);
  while (ax[0] == 0 && ax[1] == 0 && ax[2] == 0);
  long R = rnd(1500, 3000), r = rnd(200, 800);
  V3 n = val3(ax);
  n = mul(n, 1 / norm(n));
  V3 dir = urand() < 0.3 ? n : rand_dir(); // along the axis: often through the hole
  k.target = pick_target();
  Ell ed = e.d();
  auto tor_at = [&](V3 c) { return TorusD{c, n, val(R), val(r)}; };
  double s = 0;
  for (int attempt = 0; attempt < 5; ++attempt) {
    bool hit = false;
    s = place(
        [&](double sh) {
          TorusD T = tor_at(add(ed.c, mul(dir, sh)));
          FloatResult fr = float_ell(
              ed, [&](const V3& p) { return T.g(p); }, false);
          return fr.signed_gap();
        },
        k.target, &hit);
    if (hit || k.target > 0.05) break; // near/crossing wanted: try another direction
    dir = rand_dir();
  }
  std::array<long, 3> tc = round3(add(ed.c, mul(dir, s)));
  TorusD T = tor_at(val3(tc));
  k.gB = [T](const V3& p) { return T.g(p); };
  finish_float(k, ed, false);
  k.ja = k.cla = e.json();
  k.jb = k.clb = "{\"type\":\"torus\",\"center\":" + jvec(tc) + ",\"axis\":" + jvec(ax) +
                 ",\"major_radius\":" + jnum(R) + ",\"minor_radius\":" + jnum(r) + "}";
  return k;
}

Case make_capsule_case() {
  Case k;
  k.family = 2;
  EllI e = rand_ell(urand() < 0.5);
  std::array<long, 3> P, D;
  for (int i = 0; i < 3; ++i)
    P[i] = rnd(-1500, 1500);
  do
    for (auto& x : D)
      x = rnd(-2000, 2000);
  while (norm(val3(D)) < 0.5);
  long r = rnd(100, 800);
  V3 dir = rand_dir();
  k.target = pick_target();
  Ell ed = e.d();
  V3 Pd = val3(P), Dd = val3(D);
  double s = place(
      [&](double sh) {
        V3 a = add(add(ed.c, mul(dir, sh)), Pd), b = add(a, Dd);
        FloatResult fr = float_ell(
            ed, [&](const V3& p) { return seg_dist(p, a, b) - val(r); }, false);
        return fr.signed_gap();
      },
      k.target);
  std::array<long, 3> A = round3(add(add(ed.c, mul(dir, s)), Pd)), B;
  for (int i = 0; i < 3; ++i)
    B[i] = A[i] + D[i];
  V3 a = val3(A), b = val3(B);
  double rr = val(r);
  k.gB = [a, b, rr](const V3& p) { return seg_dist(p, a, b) - rr; };
  finish_float(k, ed, false);
  k.ja = k.cla = e.json();
  k.jb = k.clb = "{\"type\":\"capsule\",\"from\":" + jvec(A) + ",\"to\":" + jvec(B) +
                 ",\"radius\":" + jnum(r) + "}";
  return k;
}

Case make_canal_case() {
  Case k;
  k.family = 3;
  EllI e = rand_ell(false);
  std::array<long, 3> P1, P2;
  do
    for (int i = 0; i < 3; ++i)
      P1[i] = rnd(-2000, 2000), P2[i] = rnd(-1500, 1500);
  while (norm(val3(P1)) < 0.3);
  long r0 = rnd(200, 800), r1 = rnd(200, 800) - r0; // r(1) = r0 + r1 in [0.2, 0.8]
  V3 dir = rand_dir();
  k.target = pick_target();
  Ell ed = e.d();
  V3 off = {val(rnd(-1000, 1000)), val(rnd(-1000, 1000)), val(rnd(-1000, 1000))};
  auto canal_at = [&](V3 p0) { return CanalD{p0, val3(P1), val3(P2), val(r0), val(r1)}; };
  double s = place(
      [&](double sh) {
        CanalD C = canal_at(add(add(ed.c, off), mul(dir, sh)));
        FloatResult fr = float_ell(
            ed, [&](const V3& p) { return C.g(p); }, false);
        return fr.signed_gap();
      },
      k.target);
  std::array<long, 3> P0 = round3(add(add(ed.c, off), mul(dir, s)));
  CanalD C = canal_at(val3(P0));
  k.gB = [C](const V3& p) { return C.g(p); };
  finish_float(k, ed, true);
  k.ja = k.cla = e.json();
  std::string sp = "[";
  for (int i = 0; i < 3; ++i)
    sp +=
        std::string(i ? "," : "") + "[" + jnum(P0[i]) + "," + jnum(P1[i]) + "," + jnum(P2[i]) + "]";
  sp += "]";
  k.jb = k.clb = "{\"type\":\"canal\",\"spine\":" + sp + ",\"radius\":[" + jnum(r0) + "," +
                 jnum(r1) + "],\"interval\":[0,1]}";
  return k;
}

std::string term(long c, const std::string& mono, bool first) {
  std::string s;
  if (first)
    s = c < 0 ? "-" : "";
  else
    s = c < 0 ? " - " : " + ";
  s += dec(std::labs(c));
  if (!mono.empty()) s += "*" + mono;
  return s;
}

Case make_graph_case() {
  Case k;
  k.family = 4;
  long a, b = rnd(-300, 300), c = rnd(-1000, 1000), d = rnd(-1000, 1000);
  do
    a = rnd(-300, 300);
  while (a == 0);
  Graph G{val(a), val(b), val(c), val(d)};
  long cx = rnd(-1500, 1500), cy = rnd(-1500, 1500), rho = rnd(300, 1500);
  k.target = pick_target();
  double base = G.at(val(cx), val(cy))[2] + val(rho) + 4;
  double s = place(
      [&](double sh) {
        V3 sc{val(cx), val(cy), base - 8 + sh}; // s = 8: start 4 above the tangent height
        FloatResult fr = float_graph(G, sc, val(rho), false);
        return fr.signed_gap();
      },
      k.target);
  long cz = std::lround((base - 8 + s) * 1000);
  V3 sc{val(cx), val(cy), val(cz)};
  double rr = val(rho);
  k.gB = [sc, rr](const V3& p) { return norm(sub(p, sc)) - rr; };
  FloatResult fr = float_graph(G, sc, rr, true);
  k.crossing = fr.neg && fr.pos;
  k.f = k.crossing ? 0 : fr.f;
  std::string eq = "z = " + term(a, "x^3", true) + (b ? term(b, "x*y^2", false) : "") +
                   (c ? term(c, "x", false) : "") + (d ? term(d, "", false) : "");
  k.cla = eq;
  k.ja = "\"" + eq + "\"";
  k.clb = k.jb =
      "{\"type\":\"sphere\",\"center\":" + jvec({cx, cy, cz}) + ",\"radius\":" + jnum(rho) + "}";
  return k;
}

const char* fam_name(int f) {
  switch (f) {
  case 1:
    return "ellipsoid vs torus";
  case 2:
    return "sphere/ellipsoid vs capsule";
  case 3:
    return "ellipsoid vs canal";
  default:
    return "cubic graph vs sphere";
  }
}

struct Stats {
  int n = 0, cert = 0, undecided = 0, other = 0, exc = 0, bugs = 0, stuck = 0, zero_susp = 0,
      crossing = 0, inside = 0, near = 0;
  std::vector<double> ms;
};

} // namespace

int main(int argc, char** argv) {
  long cases = argc > 1 ? std::atol(argv[1]) : 40;
  unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2026;
  long digits = argc > 3 ? std::atol(argv[3]) : 15;
  rng.seed(seed);
  Stats st[5];
  std::vector<std::string> reports, undecided_notes;
  for (int fam = 1; fam <= 4; ++fam) {
    for (long i = 0; i < cases; ++i) {
      Case k = fam == 1   ? make_torus_case()
               : fam == 2 ? make_capsule_case()
               : fam == 3 ? make_canal_case()
                          : make_graph_case();
      Stats& S = st[fam];
      ++S.n;
      S.crossing += k.crossing;
      S.inside += k.inside;
      S.near += !k.crossing && k.f < 0.05;
      certify::DistanceResult res;
      double ms = 0;
      std::string what;
      try {
        core::Surface A = core::io::read_surface(core::io::parse_json(k.ja, "a"), "a", "$");
        core::Surface B = core::io::read_surface(core::io::parse_json(k.jb, "b"), "b", "$");
        auto t0 = std::chrono::steady_clock::now();
        res = certify::surface_distance(A, B, digits, false);
        ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                 .count();
        S.ms.push_back(ms);
      } catch (const std::exception& e) {
        what = e.what();
      }
      char head[160];
      std::snprintf(head, sizeof head, "family %d (%s) case %ld", fam, fam_name(fam), i + 1);
      std::string repro = "build/app/surfcert distance '" + k.cla + "' '" + k.clb + "'";
      if (!what.empty()) {
        ++S.exc;
        reports.push_back(std::string("EXCEPTION ") + head + ": " + what + "\n  " + repro);
        std::fprintf(stderr, "[%d %ld/%ld] exception %s\n", fam, i + 1, cases, what.c_str());
        continue;
      }
      double lo = std::strtod(res.lower().c_str(), nullptr),
             up = std::strtod(res.upper().c_str(), nullptr);
      std::fprintf(stderr, "[%d %ld/%ld] %s %.1f ms [%s, %s] f=%.15g (target gap %.3f)%s\n", fam,
                   i + 1, cases, certify::to_string(res.status), ms, res.lower().c_str(),
                   res.upper().c_str(), k.f, k.target, k.crossing ? " (float: crossing)" : "");
      char buf[512];
      if (res.status == certify::Status::Certified) {
        ++S.cert;
        if (k.inside) continue; // float bound unusable
        if (lo > k.f + 1e-9) {
          ++S.bugs;
          std::snprintf(buf, sizeof buf,
                        "BUG %s: lower %s > f %.15g (+1e-9); enclosure [%s, %s], target gap "
                        "%.4f%s",
                        head, res.lower().c_str(), k.f, res.lower().c_str(), res.upper().c_str(),
                        k.target, k.crossing ? ", float sees crossing" : "");
          std::string r = buf;
          r += "\n  A = " + k.ja + "\n  B = " + k.jb + "\n  " + repro;
          for (const auto& pr : res.pairs) {
            std::snprintf(buf, sizeof buf,
                          "\n  library pair (%.9g, %.9g, %.9g) - (%.9g, %.9g, %.9g); float "
                          "g_B(point on A) = %.9g",
                          pr[0][0], pr[0][1], pr[0][2], pr[1][0], pr[1][1], pr[1][2], k.gB(pr[0]));
            r += buf;
          }
          reports.push_back(r);
        }
        if (k.f - up > 1e-6) {
          ++S.stuck;
          std::snprintf(buf, sizeof buf, "stuck (float above upper) %s: f %.12g, upper %s", head,
                        k.f, res.upper().c_str());
          std::string r = buf;
          for (const auto& pr : res.pairs) {
            std::snprintf(buf, sizeof buf, "; g_B(library point on A) = %.9g", k.gB(pr[0]));
            r += buf;
          }
          r += "\n  " + repro;
          reports.push_back(r);
        }
        if (up == 0 && k.f > 1e-3) {
          ++S.zero_susp;
          std::snprintf(buf, sizeof buf, "SUSPICIOUS %s: certified 0 but f = %.12g", head, k.f);
          reports.push_back(std::string(buf) + "\n  A = " + k.ja + "\n  B = " + k.jb + "\n  " +
                            repro);
        }
      } else {
        if (res.status == certify::Status::Undecided)
          ++S.undecided;
        else
          ++S.other;
        std::snprintf(buf, sizeof buf,
                      "%s %s (%.0f ms, f = %.6g%s): ", certify::to_string(res.status), head, ms,
                      k.f, k.crossing ? ", float crossing" : "");
        undecided_notes.push_back(std::string(buf) + res.note + "\n  " + repro);
      }
    }
  }
  std::printf("## shape_distance_check %ld %lu (digits %ld)\n\n", cases, seed, digits);
  std::printf("| family | cases | certified | undecided | other status | exceptions | BUG lower>f "
              "| float stuck | certified 0 with f>1e-3 | float crossing | near (f<0.05) | "
              "median ms | max ms |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int fam = 1; fam <= 4; ++fam) {
    Stats& S = st[fam];
    double med = 0, mx = 0;
    if (!S.ms.empty()) {
      auto t = S.ms;
      std::sort(t.begin(), t.end());
      med = t[t.size() / 2];
      mx = t.back();
    }
    std::printf("| %s | %d | %d | %d | %d | %d | %d | %d | %d | %d | %d | %.1f | %.1f |\n",
                fam_name(fam), S.n, S.cert, S.undecided, S.other, S.exc, S.bugs, S.stuck,
                S.zero_susp, S.crossing, S.near, med, mx);
    if (S.inside)
      std::printf("\n(%s: %d cases with the ellipsoid inside the canal per float; unchecked)\n",
                  fam_name(fam), S.inside);
  }
  if (!reports.empty()) {
    std::printf("\n### Findings\n\n");
    for (const auto& r : reports)
      std::printf("- %s\n", r.c_str());
  }
  if (!undecided_notes.empty()) {
    std::printf("\n### Not certified\n\n");
    for (const auto& r : undecided_notes)
      std::printf("- %s\n", r.c_str());
  }
  flint_cleanup();
  return 0;
}
