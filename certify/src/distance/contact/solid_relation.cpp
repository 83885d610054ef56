#include "surfcert/certify/distance/solid_relation.hpp"

#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/convex_quadric.hpp"

#include <algorithm>
#include <vector>

namespace surfcert::certify {

using core::Rational;

namespace {

constexpr long kPrec = 256;

// Horner over balls: an enclosure of the polynomial (constant first) over the ball t.
void horner(arb_t out, const std::vector<Rational>& c, const arb_t t) {
  Ball x;
  arb_zero(out);
  for (size_t k = c.size(); k-- > 0;) {
    arb_mul(out, out, t, kPrec);
    arb_set_fmpq(x.v, c[k].raw(), kPrec);
    arb_add(out, out, x.v, kPrec);
  }
}

void interval(arb_t out, const Rational& lo, const Rational& hi) {
  Ball a;
  arb_set_fmpq(out, lo.raw(), kPrec);
  arb_set_fmpq(a.v, hi.raw(), kPrec);
  arb_union(out, out, a.v, kPrec);
}

bool ellipsoid(const core::Surface& s) {
  const auto* q = std::get_if<core::QuadricMatrix>(&s);
  return q && q->kind() == core::QuadricKind::Ellipsoid;
}

// The centre c = -M^-1 b of a central quadric (Cramer) and q(c).
void centre_of(const core::QuadricMatrix& q, std::array<Rational, 3>& c, Rational& qc) {
  auto det3 = [](const Rational(&m)[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  Rational M[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      M[i][j] = q(i, j);
  const Rational d = det3(M);
  for (int k = 0; k < 3; ++k) {
    Rational Mk[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        Mk[i][j] = j == k ? -q(i, 3) : M[i][j];
    c[static_cast<size_t>(k)] = det3(Mk) / d;
  }
  qc = q(3, 3);
  for (int i = 0; i < 3; ++i)
    qc += q(i, 3) * c[static_cast<size_t>(i)];
}

// A ball holding a genuine point of the surface.
bool boundary_point(const core::Surface& s, Ball (&p)[3]) {
  if (ellipsoid(s)) { // c + sqrt(-q(c) / M11) e1
    const auto& q = std::get<core::QuadricMatrix>(s);
    std::array<Rational, 3> c;
    Rational qc;
    centre_of(q, c, qc);
    const Rational s2 = -qc / q(0, 0);
    if (s2.sign() <= 0) return false;
    for (size_t i = 0; i < 3; ++i)
      arb_set_fmpq(p[i].v, c[i].raw(), kPrec);
    Ball t;
    arb_set_fmpq(t.v, s2.raw(), kPrec);
    arb_sqrt(t.v, t.v, kPrec);
    arb_add(p[0].v, p[0].v, t.v, kPrec);
    return true;
  }
  if (const auto* t = std::get_if<core::Torus>(&s)) { // c + (R + r) u / |u|, u orthogonal
    const std::array<Rational, 3> u = core::plane_frame(t->axis)[0];
    const Rational uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    Ball n, rr;
    arb_set_fmpq(n.v, uu.raw(), kPrec);
    arb_rsqrt(n.v, n.v, kPrec);
    const Rational Rr = t->R + t->r;
    arb_set_fmpq(rr.v, Rr.raw(), kPrec);
    arb_mul(n.v, n.v, rr.v, kPrec);
    for (size_t i = 0; i < 3; ++i) {
      Ball ui;
      arb_set_fmpq(ui.v, u[i].raw(), kPrec);
      arb_set_fmpq(p[i].v, t->centre[i].raw(), kPrec);
      arb_addmul(p[i].v, ui.v, n.v, kPrec);
    }
    return true;
  }
  if (const auto* c = std::get_if<core::CanalSurface>(&s))
    return canal_support_point(*c, {Rational(1), Rational(0), Rational(0)}, p);
  return false;
}

// +1 when the ball point is certainly inside the solid, -1 certainly outside, 0 unknown.
int inside(const core::Surface& s, const Ball (&p)[3]) {
  if (ellipsoid(s)) {
    const auto& q = std::get<core::QuadricMatrix>(s);
    std::array<Rational, 3> c;
    Rational qc;
    centre_of(q, c, qc);
    Ball v, X[4];
    for (size_t i = 0; i < 3; ++i)
      arb_set(X[i].v, p[i].v);
    arb_one(X[3].v);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        Ball m, t;
        arb_set_fmpq(m.v, q(i, j).raw(), kPrec);
        arb_mul(t.v, X[i].v, X[j].v, kPrec);
        arb_addmul(v.v, m.v, t.v, kPrec);
      }
    if (qc.sign() > 0) arb_neg(v.v, v.v); // the interior is where q has the sign of q(c)
    return arb_is_negative(v.v) ? 1 : arb_is_positive(v.v) ? -1 : 0;
  }
  if (const auto* t = std::get_if<core::Torus>(&s)) {
    Ball w2, s1, aa, tmp, T;
    for (size_t i = 0; i < 3; ++i) {
      Ball wi, ai;
      arb_set_fmpq(wi.v, t->centre[i].raw(), kPrec);
      arb_sub(wi.v, p[i].v, wi.v, kPrec);
      arb_set_fmpq(ai.v, t->axis[i].raw(), kPrec);
      arb_addmul(w2.v, wi.v, wi.v, kPrec);
      arb_addmul(s1.v, wi.v, ai.v, kPrec);
      arb_addmul(aa.v, ai.v, ai.v, kPrec);
    }
    const Rational K = t->R * t->R - t->r * t->r, R2 = Rational(4) * t->R * t->R;
    Ball k, r2;
    arb_set_fmpq(k.v, K.raw(), kPrec);
    arb_set_fmpq(r2.v, R2.raw(), kPrec);
    arb_add(T.v, w2.v, k.v, kPrec);
    arb_sqr(T.v, T.v, kPrec); // (|w|^2 + R^2 - r^2)^2 - 4 R^2 (|w|^2 - (w.a)^2 / |a|^2)
    arb_sqr(tmp.v, s1.v, kPrec);
    arb_div(tmp.v, tmp.v, aa.v, kPrec);
    arb_sub(tmp.v, w2.v, tmp.v, kPrec);
    arb_submul(T.v, r2.v, tmp.v, kPrec);
    return arb_is_negative(T.v) ? 1 : arb_is_positive(T.v) ? -1 : 0;
  }
  if (const auto* c = std::get_if<core::CanalSurface>(&s)) {
    // min over t of h(t) = |p - C(t)|^2 - r(t)^2: negative somewhere = inside.
    auto h = [&](arb_t out, const arb_t T) {
      Ball d, r;
      arb_zero(out);
      for (size_t i = 0; i < 3; ++i) {
        horner(d.v, c->spine[i], T);
        arb_sub(d.v, p[i].v, d.v, kPrec);
        arb_addmul(out, d.v, d.v, kPrec);
      }
      horner(r.v, c->radius, T);
      arb_submul(out, r.v, r.v, kPrec);
    };
    std::vector<std::pair<Rational, Rational>> live{{c->t0, c->t1}};
    for (int round = 0; round < 24 && !live.empty(); ++round) {
      std::vector<std::pair<Rational, Rational>> next;
      for (const auto& iv : live) {
        Ball T, m, v;
        const Rational mid = (iv.first + iv.second) * Rational(1, 2);
        arb_set_fmpq(m.v, mid.raw(), kPrec);
        h(v.v, m.v);
        if (arb_is_negative(v.v)) return 1;
        interval(T.v, iv.first, iv.second);
        h(v.v, T.v);
        if (arb_is_positive(v.v)) continue;
        next.emplace_back(iv.first, mid);
        next.emplace_back(mid, iv.second);
      }
      if (next.size() > 4096) return 0;
      live = std::move(next);
    }
    return live.empty() ? -1 : 0;
  }
  return 0;
}

} // namespace

bool canal_support_point(const core::CanalSurface& c, const std::array<Rational, 3>& e,
                         Ball (&p)[3]) {
  // C(t*) + r(t*) e, t* maximising C(t).e + r(t) (branch and bound: the survivors' hull holds
  // every maximiser, so the ball holds the support point).
  size_t n = c.radius.size();
  for (const auto& q : c.spine)
    n = std::max(n, q.size());
  std::vector<Rational> phi(n, Rational(0));
  for (size_t k = 0; k < n; ++k) {
    for (size_t i = 0; i < 3; ++i)
      if (k < c.spine[i].size()) phi[k] += c.spine[i][k] * e[i];
    if (k < c.radius.size()) phi[k] += c.radius[k];
  }
  std::vector<std::pair<Rational, Rational>> live{{c.t0, c.t1}};
  for (int round = 0; round < 60 && live.size() < 64; ++round) {
    arf_t best;
    arf_init(best);
    arf_neg_inf(best);
    std::vector<Ball> up(live.size());
    for (size_t i = 0; i < live.size(); ++i) {
      Ball T, m, v;
      interval(T.v, live[i].first, live[i].second);
      horner(up[i].v, phi, T.v);
      const Rational mid = (live[i].first + live[i].second) * Rational(1, 2);
      arb_set_fmpq(m.v, mid.raw(), kPrec);
      horner(v.v, phi, m.v);
      arf_t lb;
      arf_init(lb);
      arb_get_lbound_arf(lb, v.v, kPrec);
      if (arf_cmp(lb, best) > 0) arf_set(best, lb);
      arf_clear(lb);
    }
    std::vector<std::pair<Rational, Rational>> next;
    for (size_t i = 0; i < live.size(); ++i) {
      arf_t ub;
      arf_init(ub);
      arb_get_ubound_arf(ub, up[i].v, kPrec);
      if (arf_cmp(ub, best) >= 0) {
        const Rational mid = (live[i].first + live[i].second) * Rational(1, 2);
        next.emplace_back(live[i].first, mid);
        next.emplace_back(mid, live[i].second);
      }
      arf_clear(ub);
    }
    arf_clear(best);
    live = std::move(next);
  }
  if (live.empty()) return false;
  Rational lo = live.front().first, hi = live.front().second;
  for (const auto& iv : live) {
    lo = std::min(lo, iv.first);
    hi = std::max(hi, iv.second);
  }
  Ball T, r;
  interval(T.v, lo, hi);
  for (size_t i = 0; i < 3; ++i)
    horner(p[i].v, c.spine[i], T.v);
  horner(r.v, c.radius, T.v);
  for (size_t i = 0; i < 3; ++i) {
    Ball ei;
    arb_set_fmpq(ei.v, e[i].raw(), kPrec);
    arb_addmul(p[i].v, r.v, ei.v, kPrec);
  }
  return true;
}

int side_of(const core::Surface& s, const Ball (&p)[3]) {
  if (is_closed_surface(s)) return -inside(s, p);
  Ball v;
  if (const auto* q = std::get_if<core::QuadricMatrix>(&s)) {
    Ball X[4];
    for (size_t i = 0; i < 3; ++i)
      arb_set(X[i].v, p[i].v);
    arb_one(X[3].v);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        Ball m, t;
        arb_set_fmpq(m.v, (*q)(i, j).raw(), kPrec);
        arb_mul(t.v, X[i].v, X[j].v, kPrec);
        arb_addmul(v.v, m.v, t.v, kPrec);
      }
  } else if (const auto* im = std::get_if<core::ImplicitSurface>(&s)) {
    for (const auto& [e, c] : im->f.terms()) {
      Ball t, x;
      arb_set_fmpq(t.v, c.raw(), kPrec);
      for (size_t i = 0; i < 3; ++i) {
        arb_pow_ui(x.v, p[i].v, static_cast<ulong>(e[i]), kPrec);
        arb_mul(t.v, t.v, x.v, kPrec);
      }
      arb_add(v.v, v.v, t.v, kPrec);
    }
  } else {
    return 0;
  }
  return arb_is_positive(v.v) ? 1 : arb_is_negative(v.v) ? -1 : 0;
}

bool is_closed_surface(const core::Surface& s) {
  return ellipsoid(s) || std::holds_alternative<core::Torus>(s) ||
         std::holds_alternative<core::CanalSurface>(s);
}

int solids_nested(const core::Surface& a, const core::Surface& b) {
  if (!is_closed_surface(a) || !is_closed_surface(b)) return 0;
  Ball pa[3], pb[3];
  if (!boundary_point(a, pa) || !boundary_point(b, pb)) return 0;
  const int ab = inside(b, pa), ba = inside(a, pb);
  if (ab > 0 || ba > 0) return 1;
  if (ab < 0 && ba < 0) return -1;
  return 0;
}

namespace {

// An ellipsoid E and an elliptic cylinder or paraboloid Q (solid: its convex side,
// s q <= 0 with s the sign of the trace of Q's quadratic block), their surfaces known to be
// disjoint (or touching at finitely many points without crossing: the same argument on the
// surface minus those points; -1 then means the solids meet only there): +1 when E's solid
// lies inside Q's, -1 when the solids are disjoint, 0 otherwise
// (another pair of surfaces). Decided by the exact side of E's centre c: E's surface is
// connected and misses Q's, so it lies wholly inside or wholly outside Q's solid. Inside: E's
// solid (the convex hull of its surface) is inside the convex solid of Q; and c inside Q's
// solid forces that (else the rays from c inside Q's unbounded solid would leave E through
// points of E's surface inside Q). c outside: E's surface is outside, and Q's unbounded
// connected solid cannot meet E's solid without crossing E's surface: disjoint solids, whose
// distance is that of their boundaries.
int ellipsoid_in_convex_quadric(const core::Surface& a, const core::Surface& b) {
  const auto* qa = std::get_if<core::QuadricMatrix>(&a);
  const auto* qb = std::get_if<core::QuadricMatrix>(&b);
  if (qa == nullptr || qb == nullptr) return 0;
  for (bool e_is_a : {true, false}) {
    const core::QuadricMatrix& e = e_is_a ? *qa : *qb;
    const core::QuadricMatrix& q = e_is_a ? *qb : *qa;
    if (e.kind() != core::QuadricKind::Ellipsoid) continue;
    const auto k = convex_kind(q);
    if (!k || *k == ConvexQuadric::Kind::Ellipsoid) continue;
    const auto ce = convex_quadric(e);
    if (!ce) return 0;
    const Rational trace = q(0, 0) + q(1, 1) + q(2, 2);
    Rational v = q(3, 3);
    for (int i = 0; i < 3; ++i) {
      const Rational& ci = ce->c[static_cast<size_t>(i)];
      v += Rational(2) * q(i, 3) * ci;
      for (int j = 0; j < 3; ++j)
        v += ci * q(i, j) * ce->c[static_cast<size_t>(j)];
    }
    const int side = v.sign() * trace.sign();
    return side < 0 ? 1 : side > 0 ? -1 : 0;
  }
  return 0;
}

} // namespace

void apply_solid_option(DistanceResult& r, const core::Surface& a, const core::Surface& b) {
  r.solid = true;
  auto plane = [](const core::Surface& s) {
    const auto* q = std::get_if<core::QuadricMatrix>(&s);
    return q != nullptr && q->is_plane();
  };
  if ((plane(a) && (plane(b) || is_closed_surface(b))) || (plane(b) && is_closed_surface(a))) {
    if (r.status == Status::Certified && r.distance && !r.distance->is_zero())
      r.note += std::string(r.note.empty() ? "" : "; ") +
                "a plane bounds no solid: the solid distance is the surface distance";
    return;
  }
  // One solid inside the other: solid distance 0, a continuum of common points.
  auto nested = [&r](const std::string& why, Minimizers::Proof proof) {
    const std::string was = "[" + r.lower() + ", " + r.upper() + "]";
    r.distance = Enclosure::zero();
    r.minimizers = Minimizers::continuum(proof);
    r.pairs.clear();
    r.ties = Ties::None;
    r.note = "solid distance: " + why + " (surface distance " + was + ")";
  };
  if (r.status == Status::Certified && r.distance && r.distance->is_zero() &&
      r.minimizers.is_count()) {
    // The surfaces touch at finitely many points and cross nowhere, so each surface minus
    // those points (still connected) lies on one side of the other: either one solid contains
    // the other (a continuum of common points) or the solids meet only where the surfaces
    // touch (the count stands). The same sides as for disjoint surfaces decide it.
    const int e = ellipsoid_in_convex_quadric(a, b);
    const int n = e != 0 ? e : solids_nested(a, b);
    if (n > 0) {
      nested("one solid contains the other, their surfaces touching",
             e != 0 ? Minimizers::Proof::Exact : Minimizers::Proof::Interval);
      return;
    }
    if (n < 0) {
      r.note += std::string(r.note.empty() ? "" : "; ") +
                "solid distance: the solids meet only where the surfaces touch";
      return;
    }
    r.minimizers = Minimizers::undecided(r.minimizers.value());
    r.note += std::string(r.note.empty() ? "" : "; ") +
              "solid distance 0 (the surfaces touch); whether one solid contains the other "
              "was not decided, so the number of common points of the solids is not proven";
    return;
  }
  if (r.status == Status::Certified && r.distance && !r.distance->is_zero()) {
    const int n = ellipsoid_in_convex_quadric(a, b);
    if (n > 0) {
      nested("the ellipsoid lies inside the convex solid of the other quadric (its centre "
             "inside, exactly)",
             Minimizers::Proof::Exact);
      return;
    }
    if (n < 0) {
      r.note += std::string(r.note.empty() ? "" : "; ") +
                "the solids are disjoint (the ellipsoid's centre lies outside the other's "
                "convex solid, exactly): the solid distance is the surface distance";
      return;
    }
  }
  if (!is_closed_surface(a) || !is_closed_surface(b)) {
    // The solids of other surfaces are not modelled, so the surface distance is no answer to
    // this query (verify read it as the solid distance: x^4 + y^4 + z^4 = 1 inside a sphere
    // was certified 'separated', solids not colliding). What stays established when the
    // surfaces are apart: 0 <= solid distance <= surface distance (each surface lies in any
    // solid it bounds); surfaces that meet give 0 either way.
    std::string note = "solid distance: supported for closed surfaces (ellipsoids, tori, canal "
                       "surfaces) only";
    if (r.status == Status::Certified && r.distance && !r.distance->is_zero()) {
      note += " (the surface distance is [" + r.lower() + ", " + r.upper() + "])";
      r.status = Status::Undecided;
      r.distance = Enclosure::up_to(r.distance->upper_arf(), r.distance->digits());
    }
    r.note += std::string(r.note.empty() ? "" : "; ") + note;
    return;
  }
  if (r.status != Status::Certified || r.distance->is_zero())
    return; // meeting surfaces: 0 either way
  const int n = solids_nested(a, b);
  if (n > 0) {
    nested("one solid contains the other", Minimizers::Proof::Interval);
  } else if (n < 0) {
    r.note += std::string(r.note.empty() ? "" : "; ") +
              "the solids are disjoint: the solid distance is the surface distance";
  } else {
    r.status = Status::Undecided;
    // 0 <= solid distance <= surface distance: what stays established.
    r.distance = Enclosure::up_to(r.distance->upper_arf(), r.distance->digits());
    r.note += std::string(r.note.empty() ? "" : "; ") +
              "solid distance: whether one solid contains the other was not decided";
  }
}

} // namespace surfcert::certify
