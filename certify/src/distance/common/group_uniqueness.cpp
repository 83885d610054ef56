#include "surfcert/certify/distance/group_uniqueness.hpp"

namespace surfcert::certify {

namespace {

// f'' of the sign over the ball T, or over both halves (a wide hull: the enclosure of f'' over
// the whole ball may be too loose), up to `budget` evaluations in all.
bool signed_over(const SecondDerivative& second, const arb_t T, int sign, int depth, int& budget) {
  if (--budget < 0) return false;
  Ball d2;
  if (second(d2.v, T) && (sign > 0 ? arb_is_positive(d2.v) : arb_is_negative(d2.v))) return true;
  if (depth == 0) return false;
  // the halves [lo, mid] and [mid, hi] as balls (outward: their union covers T)
  Ball lo, hi, mid, a, b;
  arb_set_arf(mid.v, arb_midref(T));
  Arf l, h;
  arb_get_lbound_arf(l.v, T, 2 * arb_rel_accuracy_bits(T) + 64);
  arb_get_ubound_arf(h.v, T, 2 * arb_rel_accuracy_bits(T) + 64);
  arb_set_arf(lo.v, l.v);
  arb_set_arf(hi.v, h.v);
  arb_union(a.v, lo.v, mid.v, ARF_PREC_EXACT);
  arb_union(b.v, mid.v, hi.v, ARF_PREC_EXACT);
  return signed_over(second, a.v, sign, depth - 1, budget) &&
         signed_over(second, b.v, sign, depth - 1, budget);
}

} // namespace

bool prove_one_per_group(DistanceResult& res, const std::vector<Ball>& hulls,
                         const SecondDerivative& second, int sign, const std::string& what) {
  for (const Ball& hull : hulls) {
    int budget = 512;
    if (signed_over(second, hull.v, sign, 12, budget)) continue;
    res.count_unproven = true;
    res.note += std::string(res.note.empty() ? "" : "; ") + what +
                " may hold more than one minimizer (the distance is not proven strictly " +
                (sign > 0 ? "convex" : "concave") + " there)";
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

} // namespace

bool ellipsoid_dist2_second(arb_t d2, const Series (&y)[3], const Series (&M)[3][3], long prec) {
  Arf lo, hi, mid;
  // G_s is decreasing in s > 0: bracket its zero for every t at once, by certified signs.
  arf_one(hi.v);
  int k = 0;
  for (; gs_sign(y, M, hi.v, prec) >= 0; ++k) {
    if (k == 400) return false;
    arf_mul_2exp_si(hi.v, hi.v, 1);
  }
  arf_one(lo.v);
  for (k = 0; gs_sign(y, M, lo.v, prec) <= 0; ++k) {
    if (k == 400) return false;
    arf_mul_2exp_si(lo.v, lo.v, -1);
  }
  for (k = 0; k < 80; ++k) {
    arf_add(mid.v, lo.v, hi.v, ARF_PREC_EXACT, ARF_RND_DOWN);
    arf_mul_2exp_si(mid.v, mid.v, -1);
    const int sg = gs_sign(y, M, mid.v, prec);
    if (sg > 0)
      arf_swap(lo.v, mid.v);
    else if (sg < 0)
      arf_swap(hi.v, mid.v);
    else
      break; // as narrow as the t-ball allows
  }
  Ball S, a, b;
  arb_set_arf(a.v, lo.v);
  arb_set_arf(b.v, hi.v);
  arb_union(S.v, a.v, b.v, prec);
  Forms f;
  if (!forms(f, y, M, S.v, 3, prec)) return false;
  Ball q2, zz0, zz1, zw0, q1, Gtt, Gts, Gss;
  // G_tt = 2 s [q]_2; G_ts = [q]_1 - s [zz]_1; G_ss = 2 s [zw]_0 - 2 [zz]_0
  arb_poly_get_coeff_arb(q2.v, f.q.p, 2);
  arb_mul(Gtt.v, q2.v, S.v, prec);
  arb_mul_2exp_si(Gtt.v, Gtt.v, 1);
  arb_poly_get_coeff_arb(q1.v, f.q.p, 1);
  arb_poly_get_coeff_arb(zz1.v, f.zz.p, 1);
  arb_set(Gts.v, q1.v);
  arb_submul(Gts.v, S.v, zz1.v, prec);
  arb_poly_get_coeff_arb(zw0.v, f.zw.p, 0);
  arb_poly_get_coeff_arb(zz0.v, f.zz.p, 0);
  arb_mul(Gss.v, S.v, zw0.v, prec);
  arb_sub(Gss.v, Gss.v, zz0.v, prec);
  arb_mul_2exp_si(Gss.v, Gss.v, 1);
  if (!arb_is_negative(Gss.v)) return false;
  arb_sqr(d2, Gts.v, prec);
  arb_div(d2, d2, Gss.v, prec);
  arb_sub(d2, Gtt.v, d2, prec);
  return arb_is_finite(d2) != 0;
}

} // namespace surfcert::certify
