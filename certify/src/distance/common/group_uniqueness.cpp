#include "surfcert/certify/distance/group_uniqueness.hpp"

#include <algorithm>
#include <cmath>

namespace surfcert::certify {

namespace {

// Halvings of a hull and evaluations per hull (a hull of width 1/8 reaches 2^-20), and the
// doublings / halvings of s from 1 while bracketing s* (s* between 2^-400 and 2^400).
constexpr int kGroupProofDepth = 17;
constexpr int kGroupProofBudget = 2048;
constexpr int kMaxScaleSteps = 400;
// Bisection steps of the bracket of s*, and of each of its ends once the midpoint's sign is
// not decided.
constexpr int kBracketSteps = 80;
constexpr int kBracketEndSteps = 8;

// Labels of the pieces of the ball T, left to right, for g = sign f: '+' when g' > 0 over the
// piece, '-' when g' < 0, 'C' when g'' > 0 (g strictly convex there); a piece with none of
// these is halved, down to `depth` halvings and `budget` evaluations in all (false then).
bool label_pieces(const Derivatives& derivs, const arb_t T, int sign, int depth, int& budget,
                  std::string& labels) {
  if (--budget < 0) return false;
  Ball d1, d2;
  derivs(d1.v, d2.v, T);
  if (sign < 0) {
    arb_neg(d1.v, d1.v);
    arb_neg(d2.v, d2.v);
  }
  if (arb_is_positive(d1.v)) {
    labels += '+';
    return true;
  }
  if (arb_is_negative(d1.v)) {
    labels += '-';
    return true;
  }
  if (arb_is_positive(d2.v)) {
    labels += 'C';
    return true;
  }
  if (depth == 0) return false;
  // the halves [lo, mid] and [mid, hi] as balls (outward: their union covers T)
  Ball lo, hi, mid, a, b;
  arb_set_arf(mid.v, arb_midref(T));
  // The ends rounded outward (floor, ceiling) at any precision keep the cover; the precision
  // only keeps the halves tight. arb_rel_accuracy_bits is -ARF_PREC_EXACT (= -WORD_MAX) for a
  // hull centred at t = 0 exactly (a minimizer at t = 0 written around 0): doubling it
  // overflowed a slong (undefined behaviour), so it is clamped first.
  const slong acc = std::clamp<slong>(arb_rel_accuracy_bits(T), 0, 1L << 20);
  Arf l, h;
  arb_get_lbound_arf(l.v, T, 2 * acc + 64);
  arb_get_ubound_arf(h.v, T, 2 * acc + 64);
  arb_set_arf(lo.v, l.v);
  arb_set_arf(hi.v, h.v);
  arb_union(a.v, lo.v, mid.v, ARF_PREC_EXACT);
  arb_union(b.v, mid.v, hi.v, ARF_PREC_EXACT);
  return label_pieces(derivs, a.v, sign, depth - 1, budget, labels) &&
         label_pieces(derivs, b.v, sign, depth - 1, budget, labels);
}

// How many zeros g' may have over the labelled pieces (consecutive pieces share an endpoint,
// g' is continuous): none in a '+' or '-' piece; at most one in a maximal run of 'C' pieces
// (g' strictly increasing over the run), and none when the run is preceded by a '+' piece (g'
// > 0 at the run's left end, so over it) or followed by a '-' piece (g' < 0 at its right end).
int possible_zeros(const std::string& labels) {
  int n = 0;
  for (size_t i = 0; i < labels.size();) {
    if (labels[i] != 'C') {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < labels.size() && labels[j] == 'C')
      ++j;
    const bool up_before = i > 0 && labels[i - 1] == '+';
    const bool down_after = j < labels.size() && labels[j] == '-';
    if (!up_before && !down_after) ++n;
    i = j;
  }
  return n;
}

} // namespace

bool prove_one_per_group(DistanceResult& res, const std::vector<Ball>& hulls,
                         const Derivatives& derivs, int sign, const std::string& what) {
  for (const Ball& hull : hulls) {
    int budget = kGroupProofBudget;
    std::string labels;
    if (label_pieces(derivs, hull.v, sign, kGroupProofDepth, budget, labels) &&
        possible_zeros(labels) <= 1)
      continue;
    res.count_unproven = true;
    res.note += std::string(res.note.empty() ? "" : "; ") + what +
                " may hold more than one minimizer (the distance is not proven strictly " +
                (sign > 0 ? "convex" : "concave") + " near its critical points there)";
    return false;
  }
  return true;
}

namespace {

// For s fixed (a ball): with A = M + s I, z = A^-1 y, w = A^-1 z (series of length n):
// q = y.z, zz = z.z, zw = z.w; then G = s q - s, G_s = q - s zz - 1, G_ss = 2 s zw - 2 zz
// (d/ds A^-1 = -A^-2). A^-1 = adj(A) / det(A), det(A) >= s^3 > 0 for M semidefinite.
struct Forms {
  Series q, zz, zw;
};

void mat_vec(Series (&out)[3], const Series (&adj)[3][3], const Series& det, const Series (&x)[3],
             slong n, long prec) {
  for (size_t i = 0; i < 3; ++i) {
    Series acc, t;
    for (size_t j = 0; j < 3; ++j) {
      arb_poly_mullow(t.p, adj[i][j].p, x[j].p, n, prec);
      arb_poly_add(acc.p, acc.p, t.p, prec);
    }
    arb_poly_div_series(out[i].p, acc.p, det.p, n, prec);
  }
}

void dot(Series& out, const Series (&a)[3], const Series (&b)[3], slong n, long prec) {
  Series t;
  arb_poly_zero(out.p);
  for (size_t i = 0; i < 3; ++i) {
    arb_poly_mullow(t.p, a[i].p, b[i].p, n, prec);
    arb_poly_add(out.p, out.p, t.p, prec);
  }
}

bool forms(Forms& f, const Series (&y)[3], const Series (&M)[3][3], const arb_t s, slong n,
           long prec) {
  Series A[3][3], adj[3][3], det, t;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      arb_poly_set(A[i][j].p, M[i][j].p);
      if (i == j) {
        Series c;
        arb_poly_set_arb(c.p, s);
        arb_poly_add(A[i][j].p, A[i][j].p, c.p, prec);
      }
    }
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      // adj[j][i] = cofactor (i, j)
      const size_t i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      arb_poly_mullow(adj[j][i].p, A[i1][j1].p, A[i2][j2].p, n, prec);
      arb_poly_mullow(t.p, A[i1][j2].p, A[i2][j1].p, n, prec);
      arb_poly_sub(adj[j][i].p, adj[j][i].p, t.p, prec);
    }
  for (size_t j = 0; j < 3; ++j) {
    arb_poly_mullow(t.p, A[0][j].p, adj[j][0].p, n, prec);
    arb_poly_add(det.p, det.p, t.p, prec);
  }
  Ball d0;
  arb_poly_get_coeff_arb(d0.v, det.p, 0);
  if (!arb_is_positive(d0.v)) return false;
  Series z[3], w[3];
  mat_vec(z, adj, det, y, n, prec);
  mat_vec(w, adj, det, z, n, prec);
  dot(f.q, y, z, n, prec);
  dot(f.zz, z, z, n, prec);
  dot(f.zw, z, w, n, prec);
  return true;
}

// The sign of G_s(t, s) for every t in the series' ball: +1, -1, or 0 (not decided).
int gs_sign(const Series (&y)[3], const Series (&M)[3][3], const arf_t s_exact, long prec) {
  Ball s, v, t;
  arb_set_arf(s.v, s_exact);
  Forms f;
  if (!forms(f, y, M, s.v, 1, prec)) return 0;
  arb_poly_get_coeff_arb(v.v, f.q.p, 0);
  arb_poly_get_coeff_arb(t.v, f.zz.p, 0);
  arb_submul(v.v, s.v, t.v, prec);
  arb_sub_ui(v.v, v.v, 1, prec);
  return arb_is_positive(v.v) ? 1 : arb_is_negative(v.v) ? -1 : 0;
}

// The double estimate of s* at the middle of the series' ball: G_s = y^T M (M + s I)^-2 y -
// 1 (decreasing in s) solved by bisection in log s; 0 when it fails (y inside E, not finite).
double s_estimate(const Series (&y)[3], const Series (&M)[3][3]) {
  double yd[3], Md[3][3];
  for (size_t i = 0; i < 3; ++i) {
    Ball c;
    arb_poly_get_coeff_arb(c.v, y[i].p, 0);
    yd[i] = arf_get_d(arb_midref(c.v), ARF_RND_NEAR);
    for (size_t j = 0; j < 3; ++j) {
      arb_poly_get_coeff_arb(c.v, M[i][j].p, 0);
      Md[i][j] = arf_get_d(arb_midref(c.v), ARF_RND_NEAR);
    }
  }
  auto gs = [&](double s) { // y^T M A^-2 y - 1 = x^T M x - 1 with x = A^-1 y (Cramer)
    double A[3][3];
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        A[i][j] = Md[i][j] + (i == j ? s : 0.0);
    const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                       A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                       A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    double x[3];
    for (size_t c = 0; c < 3; ++c) {
      double B[3][3];
      for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j)
          B[i][j] = j == c ? yd[i] : A[i][j];
      x[c] = (B[0][0] * (B[1][1] * B[2][2] - B[1][2] * B[2][1]) -
              B[0][1] * (B[1][0] * B[2][2] - B[1][2] * B[2][0]) +
              B[0][2] * (B[1][0] * B[2][1] - B[1][1] * B[2][0])) /
             det;
    }
    double v = -1;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        v += x[i] * Md[i][j] * x[j];
    return v;
  };
  double a = 1, b = 1;
  for (int k = 0; !(gs(b) < 0); ++k) {
    if (k == 200) return 0;
    b *= 2;
  }
  for (int k = 0; !(gs(a) > 0); ++k) {
    if (k == 200) return 0;
    a *= 0.5;
  }
  for (int k = 0; k < 200 && b - a > 0x1p-52 * b; ++k) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    (gs(m) > 0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

// A certified bracket [lo, hi] of s*(t) for every t in the ball (G_s(lo) > 0 > G_s(hi))
// around the estimate: s0 (1 -+ 2^k) for k = -48, -44, ... (the caller's bisection narrows
// it); false when the estimate fails or a side is not found.
bool guess_bracket(Arf& lo, Arf& hi, const Series (&y)[3], const Series (&M)[3][3], long prec) {
  const double s0 = s_estimate(y, M);
  if (!(s0 > 0) || !std::isfinite(s0)) return false;
  Arf c;
  arf_set_d(c.v, s0);
  for (int side = -1; side <= 1; side += 2) {
    Arf& end = side < 0 ? lo : hi;
    bool found = false;
    for (int k = -48; k <= 0 && !found; k += 4) {
      // s = s0 (1 + side 2^k), exact (dyadic); at k = 0 the low side is 0: not tried
      if (side < 0 && k == 0) break;
      Arf e;
      arf_mul_2exp_si(e.v, c.v, k);
      if (side < 0)
        arf_sub(end.v, c.v, e.v, ARF_PREC_EXACT, ARF_RND_DOWN);
      else
        arf_add(end.v, c.v, e.v, ARF_PREC_EXACT, ARF_RND_DOWN);
      found = gs_sign(y, M, end.v, prec) == -side;
    }
    if (!found) {
      // s0 itself is off, or far above / below: walk by doublings from the last try
      for (int k = 0; k < 64 && !found; ++k) {
        arf_mul_2exp_si(end.v, end.v, side);
        found = gs_sign(y, M, end.v, prec) == -side;
      }
      if (!found) return false;
    }
  }
  return true;
}

} // namespace

void ellipsoid_dist2_derivatives(arb_t d1, arb_t d2, const Series (&y)[3], const Series (&M)[3][3],
                                 long prec) {
  arb_indeterminate(d1);
  arb_indeterminate(d2);
  Arf lo, hi, mid;
  // G_s is decreasing in s > 0: bracket its zero for every t at once, by certified signs,
  // first around the double estimate s0 at the middle of T (it only proposes where to test),
  // else from s = 1 outwards.
  int k = 0;
  if (!guess_bracket(lo, hi, y, M, prec)) {
    arf_one(hi.v);
    for (; gs_sign(y, M, hi.v, prec) >= 0; ++k) {
      if (k == kMaxScaleSteps) return;
      arf_mul_2exp_si(hi.v, hi.v, 1);
    }
    arf_one(lo.v);
    for (k = 0; gs_sign(y, M, lo.v, prec) <= 0; ++k) {
      if (k == kMaxScaleSteps) return;
      arf_mul_2exp_si(lo.v, lo.v, -1);
    }
  }
  // Bisection while the midpoint's sign is decided; then, once a midpoint m falls where the
  // sign is not decided (s*(t) for some t in T, or the enclosure too loose there), each end
  // alone on its side ([lo, m] for lo, [m, hi] for hi): stopping at m would keep the whole
  // previous bracket, however narrow the undecided region is.
  Arf m_lo, m_hi;
  bool split = false;
  for (k = 0; k < kBracketSteps; ++k) {
    arf_add(mid.v, lo.v, hi.v, ARF_PREC_EXACT, ARF_RND_DOWN);
    arf_mul_2exp_si(mid.v, mid.v, -1);
    const int sg = gs_sign(y, M, mid.v, prec);
    if (sg > 0) {
      arf_swap(lo.v, mid.v);
    } else if (sg < 0) {
      arf_swap(hi.v, mid.v);
    } else {
      split = true;
      arf_set(m_lo.v, mid.v);
      arf_set(m_hi.v, mid.v);
      break;
    }
  }
  for (k = 0; split && k < kBracketEndSteps; ++k) {
    // lo: G_s > 0 there; m_lo: not decided > 0
    arf_add(mid.v, lo.v, m_lo.v, ARF_PREC_EXACT, ARF_RND_DOWN);
    arf_mul_2exp_si(mid.v, mid.v, -1);
    if (gs_sign(y, M, mid.v, prec) > 0)
      arf_swap(lo.v, mid.v);
    else
      arf_swap(m_lo.v, mid.v);
    // hi: G_s < 0 there; m_hi: not decided < 0
    arf_add(mid.v, m_hi.v, hi.v, ARF_PREC_EXACT, ARF_RND_DOWN);
    arf_mul_2exp_si(mid.v, mid.v, -1);
    if (gs_sign(y, M, mid.v, prec) < 0)
      arf_swap(hi.v, mid.v);
    else
      arf_swap(m_hi.v, mid.v);
  }
  Ball S, a, b;
  arb_set_arf(a.v, lo.v);
  arb_set_arf(b.v, hi.v);
  arb_union(S.v, a.v, b.v, prec);
  Forms f;
  if (!forms(f, y, M, S.v, 3, prec)) return;
  Ball q2, zz0, zz1, zw0, q1, Gtt, Gts, Gss;
  // D' = G_t = s [q]_1 (envelope: G_s = 0 along s*)
  arb_poly_get_coeff_arb(q1.v, f.q.p, 1);
  arb_mul(d1, q1.v, S.v, prec);
  // G_tt = 2 s [q]_2; G_ts = [q]_1 - s [zz]_1; G_ss = 2 s [zw]_0 - 2 [zz]_0
  arb_poly_get_coeff_arb(q2.v, f.q.p, 2);
  arb_mul(Gtt.v, q2.v, S.v, prec);
  arb_mul_2exp_si(Gtt.v, Gtt.v, 1);
  arb_poly_get_coeff_arb(zz1.v, f.zz.p, 1);
  arb_set(Gts.v, q1.v);
  arb_submul(Gts.v, S.v, zz1.v, prec);
  arb_poly_get_coeff_arb(zw0.v, f.zw.p, 0);
  arb_poly_get_coeff_arb(zz0.v, f.zz.p, 0);
  arb_mul(Gss.v, S.v, zw0.v, prec);
  arb_sub(Gss.v, Gss.v, zz0.v, prec);
  arb_mul_2exp_si(Gss.v, Gss.v, 1);
  if (!arb_is_negative(Gss.v)) return;
  arb_sqr(d2, Gts.v, prec);
  arb_div(d2, d2, Gss.v, prec);
  arb_sub(d2, Gtt.v, d2, prec);
}

} // namespace surfcert::certify
