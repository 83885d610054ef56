#include "surfcert/certify/distance/capsule_pair.hpp"

#include "surfcert/algebra/arb.hpp"
#include "surfcert/certify/distance/ball.hpp"

#include <cmath>

namespace surfcert::certify {

using core::Rational;
using V = std::array<Rational, 3>;

namespace {

Rational dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V sub(const V& a, const V& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
V along(const V& p, const V& u, const Rational& s) {
  return {p[0] + s * u[0], p[1] + s * u[1], p[2] + s * u[2]};
}
Rational clamp01(const Rational& x) {
  if (x.sign() < 0) return Rational(0);
  if (x > Rational(1)) return Rational(1);
  return x;
}
bool constant_from(const std::vector<Rational>& c, size_t k) {
  for (size_t i = k; i < c.size(); ++i)
    if (c[i].sign() != 0) return false;
  return true;
}

struct Capsule {
  V p, u; // segment p + s u, s in [0, 1]
  Rational r;
};

// The capsule of a canal surface with a spine of degree <= 1 and a constant radius.
std::optional<Capsule> capsule_of(const core::CanalSurface& c) {
  if (!constant_from(c.radius, 1)) return std::nullopt;
  for (const auto& x : c.spine)
    if (!constant_from(x, 2)) return std::nullopt;
  Capsule k;
  V q;
  for (size_t i = 0; i < 3; ++i) {
    k.p[i] = core::eval_poly(c.spine[i], c.t0);
    q[i] = core::eval_poly(c.spine[i], c.t1);
  }
  k.u = sub(q, k.p);
  k.r = c.radius.empty() ? Rational(0) : c.radius[0];
  return k;
}

} // namespace

std::optional<DistanceResult> capsule_pair_distance(const core::CanalSurface& a,
                                                    const core::CanalSurface& b, long digits) {
  const auto A = capsule_of(a), B = capsule_of(b);
  if (!A || !B) return std::nullopt;
  // Candidates (s, t) for min |p + s u - q - t v|^2 on [0, 1]^2, all exact.
  const V w = sub(A->p, B->p);
  const Rational uu = dot(A->u, A->u), vv = dot(B->u, B->u), uv = dot(A->u, B->u),
                 wu = dot(w, A->u), wv = dot(w, B->u);
  std::vector<std::pair<Rational, Rational>> cand;
  const Rational det = uu * vv - uv * uv; // 0: parallel (or a degenerate segment)
  if (det.sign() != 0) {
    const Rational s = (uv * wv - vv * wu) / det, t = (uu * wv - uv * wu) / det;
    if (s.sign() >= 0 && s <= Rational(1) && t.sign() >= 0 && t <= Rational(1))
      cand.push_back({s, t});
  }
  for (int e = 0; e < 2; ++e) { // s fixed at an end: t = clamp((w + s u).v / v.v)
    const Rational s(e);
    cand.push_back({s, vv.sign() ? clamp01((wv + s * uv) / vv) : Rational(0)});
    const Rational t(e); // t fixed: s = clamp((t v - w).u / u.u)
    cand.push_back({uu.sign() ? clamp01((t * uv - wu) / uu) : Rational(0), t});
  }
  Rational best;
  size_t bi = 0;
  for (size_t i = 0; i < cand.size(); ++i) {
    const V d = sub(along(A->p, A->u, cand[i].first), along(B->p, B->u, cand[i].second));
    const Rational d2 = dot(d, d);
    if (i == 0 || d2 < best) best = d2, bi = i;
  }
  const Rational rr = A->r + B->r;
  if (best <= rr * rr) return std::nullopt; // the solids meet (or touch): not decided here
  const long prec = bits_for(digits + 10);
  Ball D, r, dist;
  arb_set_fmpq(D.v, best.raw(), prec);
  arb_sqrt(D.v, D.v, prec);
  arb_set_fmpq(r.v, rr.raw(), prec);
  arb_sub(dist.v, D.v, r.v, prec);
  DistanceResult out;
  out.status = Status::Certified;
  set_distance_enclosure(out, dist.v, digits);
  // Parallel segments whose projections overlap in more than a point: a continuum.
  bool continuum = false;
  if (det.sign() == 0 && uu.sign() != 0 && vv.sign() != 0) {
    // project B's ends onto A's line: parameters (w' . u) / u.u with w' = B end - A.p
    const Rational t0 = -wu / uu, t1 = (dot(B->u, A->u) - wu) / uu;
    const Rational lo = t0 < t1 ? t0 : t1, hi = t0 < t1 ? t1 : t0;
    const Rational olo = lo.sign() > 0 ? lo : Rational(0),
                   ohi = hi < Rational(1) ? hi : Rational(1);
    continuum = olo < ohi;
  }
  out.minimizers = continuum ? Minimizers::continuum(Minimizers::Proof::Exact)
                             : Minimizers::count(1, Minimizers::Proof::Exact);
  out.critical_candidates = static_cast<int>(cand.size());
  const V pa = along(A->p, A->u, cand[bi].first), pb = along(B->p, B->u, cand[bi].second);
  const double Dd = std::sqrt(best.to_double_approx());
  std::array<std::array<double, 3>, 2> pr{};
  for (size_t i = 0; i < 3; ++i) {
    const double dir = (pb[i] - pa[i]).to_double_approx() / Dd;
    pr[0][i] = pa[i].to_double_approx() + A->r.to_double_approx() * dir;
    pr[1][i] = pb[i].to_double_approx() - B->r.to_double_approx() * dir;
  }
  out.pairs.push_back(pr);
  out.method = Method::CapsuleClosedForm;
  out.note = "two capsules with disjoint solids: segment-segment distance (exact rational square) "
             "minus both radii";
  return out;
}

} // namespace surfcert::certify
