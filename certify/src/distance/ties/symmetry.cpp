#include "surfcert/certify/distance/symmetry.hpp"

#include "surfcert/algebra/upoly.hpp"
#include "surfcert/certify/distance/ball.hpp"

#include <algorithm>
#include <functional>
#include <sstream>

namespace surfcert::certify {

using core::Integer;
using core::Rational;
using V3 = std::array<Rational, 3>;
using M3 = std::array<std::array<Rational, 3>, 3>;

std::array<Rational, 3> Isometry::apply(const std::array<Rational, 3>& x) const {
  V3 y = t;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      y[i] += P[i][j] * x[j];
  return y;
}

namespace {

bool is_zero(const V3& v) {
  return v[0].is_zero() && v[1].is_zero() && v[2].is_zero();
}

V3 cross(const V3& x, const V3& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}

Rational dot(const V3& x, const V3& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

V3 mul(const M3& P, const V3& x) {
  V3 y{Rational(0), Rational(0), Rational(0)};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      y[i] += P[i][j] * x[j];
  return y;
}

// The primitive integer multiple of v whose first nonzero entry is positive (so two candidate
// directions compare equal exactly when they span the same line).
V3 normalised(const V3& v) {
  Integer l(1);
  for (const auto& x : v)
    if (!x.is_zero()) {
      Integer d = x.den(), g;
      fmpz_lcm(g.raw_mut(), l.raw(), d.raw());
      l = g;
    }
  std::array<Integer, 3> z;
  Integer g(0);
  for (size_t i = 0; i < 3; ++i) {
    const Rational s = v[i] * Rational(l);
    z[i] = s.num();
    Integer h;
    fmpz_gcd(h.raw_mut(), g.raw(), z[i].raw());
    g = h;
  }
  int sign = 0;
  for (const auto& x : z)
    if (sign == 0) sign = x.sign();
  V3 out;
  for (size_t i = 0; i < 3; ++i)
    out[i] = Rational(z[i], g) * Rational(sign);
  return out;
}

std::string text(const V3& v) {
  std::ostringstream os;
  os << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return os.str();
}

// The rational eigenvectors of the symmetric 3x3 block: one per one-dimensional rational
// eigenspace, a basis of each two-dimensional one (its planes of symmetry contain the axis,
// found through the cross products of candidates).
void quadric_directions(const core::QuadricMatrix& q, std::vector<V3>& dirs) {
  M3 M;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      M[i][j] = q(static_cast<int>(i), static_cast<int>(j));
  const Rational tr = M[0][0] + M[1][1] + M[2][2];
  const Rational m2 = M[0][0] * M[1][1] - M[0][1] * M[1][0] + M[0][0] * M[2][2] -
                      M[0][2] * M[2][0] + M[1][1] * M[2][2] - M[1][2] * M[2][1];
  const Rational det = dot(M[0], cross(M[1], M[2]));
  // det(l I - M) = l^3 - tr l^2 + m2 l - det.
  const algebra::UPolyQ chi = algebra::UPolyQ::from_coeffs({-det, m2, -tr, Rational(1)});
  for (const Rational& l : algebra::rational_roots(chi)) {
    M3 A = M;
    for (size_t i = 0; i < 3; ++i)
      A[i][i] -= l;
    V3 v{Rational(0), Rational(0), Rational(0)};
    for (size_t i = 0; i < 3 && is_zero(v); ++i)
      for (size_t j = i + 1; j < 3 && is_zero(v); ++j)
        v = cross(A[i], A[j]);
    if (!is_zero(v)) { // rank 2: the eigenvector
      dirs.push_back(v);
      continue;
    }
    for (const V3& r : A) // rank 1: the plane orthogonal to the nonzero row
      if (!is_zero(r)) {
        for (size_t k = 0; k < 3; ++k) {
          V3 e{Rational(0), Rational(0), Rational(0)};
          e[k] = Rational(1);
          const V3 c = cross(r, e);
          if (!is_zero(c)) dirs.push_back(c);
        }
        break;
      }
  }
}

// A rational centre of symmetry candidate: the centre of a central quadric, of a torus, the
// middle of a canal spine.
void centres_and_directions(const core::Surface& s, std::vector<V3>& centres,
                            std::vector<V3>& dirs) {
  if (const auto* q = std::get_if<core::QuadricMatrix>(&s)) {
    quadric_directions(*q, dirs);
    core::Mat4 m = q->matrix();
    M3 M;
    V3 b;
    for (size_t i = 0; i < 3; ++i) {
      b[i] = m[i][3];
      for (size_t j = 0; j < 3; ++j)
        M[i][j] = m[i][j];
    }
    const Rational det = dot(M[0], cross(M[1], M[2]));
    if (!det.is_zero()) { // c = -M^-1 b (Cramer)
      V3 c;
      for (size_t k = 0; k < 3; ++k) {
        M3 Mk = M;
        for (size_t i = 0; i < 3; ++i)
          Mk[i][k] = b[i];
        c[k] = -dot(Mk[0], cross(Mk[1], Mk[2])) / det;
      }
      centres.push_back(c);
    }
  } else if (const auto* t = std::get_if<core::Torus>(&s)) {
    centres.push_back(t->centre);
    dirs.push_back(t->axis);
  } else if (const auto* c = std::get_if<core::CanalSurface>(&s)) {
    const Rational mid = (c->t0 + c->t1) * Rational(1, 2);
    V3 m;
    for (size_t i = 0; i < 3; ++i)
      m[i] = core::eval_poly(c->spine[i], mid);
    centres.push_back(m);
    size_t deg = 0;
    for (const auto& p : c->spine)
      deg = std::max(deg, p.size());
    for (size_t k = 1; k < deg; ++k) { // coefficient vectors of t^k
      V3 v;
      for (size_t i = 0; i < 3; ++i)
        v[i] = k < c->spine[i].size() ? c->spine[i][k] : Rational(0);
      if (!is_zero(v)) dirs.push_back(v);
    }
  }
}

core::Poly3 compose(const core::Poly3& f, const Isometry& g) {
  std::array<core::Poly3, 3> L; // the coordinates of g(x) as affine polynomials
  for (size_t i = 0; i < 3; ++i) {
    L[i] = core::Poly3(g.t[i]);
    for (size_t j = 0; j < 3; ++j)
      L[i] = L[i] + core::Poly3::variable(static_cast<int>(j)).scaled(g.P[i][j]);
  }
  return f.substitute(L);
}

algebra::UPolyQ upoly(const std::vector<Rational>& c) {
  return c.empty() ? algebra::UPolyQ(0) : algebra::UPolyQ::from_coeffs(c);
}

bool canal_kept(const Isometry& g, const core::CanalSurface& c) {
  std::array<algebra::UPolyQ, 3> C, gC;
  for (size_t i = 0; i < 3; ++i)
    C[i] = upoly(c.spine[i]);
  for (size_t i = 0; i < 3; ++i) {
    gC[i] = algebra::UPolyQ(g.t[i]);
    for (size_t j = 0; j < 3; ++j)
      gC[i] = gC[i] + C[j] * algebra::UPolyQ(g.P[i][j]);
  }
  if (gC[0] == C[0] && gC[1] == C[1] && gC[2] == C[2]) return true; // the spine pointwise fixed
  // Reversed: g(C(t)) = C(t0 + t1 - t) and r(t) = r(t0 + t1 - t).
  const algebra::UPolyQ rev = algebra::UPolyQ::linear(Rational(-1), c.t0 + c.t1);
  auto reversed = [&](const algebra::UPolyQ& p) {
    algebra::UPolyQ out;
    fmpq_poly_compose(out.raw_mut(), p.raw(), rev.raw());
    return out;
  };
  const algebra::UPolyQ r = upoly(c.radius);
  if (!(reversed(r) == r)) return false;
  for (size_t i = 0; i < 3; ++i)
    if (!(gC[i] == reversed(C[i]))) return false;
  return true;
}

Isometry make(const M3& P, const V3& centre, std::string name) {
  Isometry g;
  g.P = P;
  const V3 pc = mul(P, centre);
  for (size_t i = 0; i < 3; ++i)
    g.t[i] = centre[i] - pc[i]; // g(centre) = centre
  g.name = std::move(name);
  return g;
}

} // namespace

bool preserves(const Isometry& g, const core::Surface& s) {
  if (const auto* q = std::get_if<core::QuadricMatrix>(&s)) {
    core::Mat4 T;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        T[i][j] = Rational(i == 3 && j == 3 ? 1 : 0);
    for (size_t i = 0; i < 3; ++i) {
      for (size_t j = 0; j < 3; ++j)
        T[i][j] = g.P[i][j];
      T[i][3] = g.t[i];
    }
    const core::Mat4 m = q->congruent(T).matrix();
    return m == q->matrix() || m == core::scaled(q->matrix(), Rational(-1));
  }
  if (const auto* t = std::get_if<core::Torus>(&s)) {
    if (g.apply(t->centre) != t->centre) return false;
    const V3 pa = mul(g.P, t->axis);
    return pa == t->axis || pa == V3{-t->axis[0], -t->axis[1], -t->axis[2]};
  }
  if (const auto* c = std::get_if<core::CanalSurface>(&s)) return canal_kept(g, *c);
  if (const auto* im = std::get_if<core::ImplicitSurface>(&s)) {
    const core::Poly3 h = compose(im->f, g);
    return h == im->f || h == -im->f;
  }
  return false;
}

std::vector<Isometry> common_symmetries(const core::Surface& a, const core::Surface& b) {
  std::vector<Isometry> out;
  if (std::holds_alternative<core::ParametricSurface>(a) ||
      std::holds_alternative<core::ParametricSurface>(b))
    return out;
  std::vector<V3> centres, dirs;
  centres_and_directions(a, centres, dirs);
  centres_and_directions(b, centres, dirs);
  for (size_t i = 0; i < centres.size(); ++i)
    for (size_t j = i + 1; j < centres.size(); ++j) {
      V3 d;
      for (size_t k = 0; k < 3; ++k)
        d[k] = centres[i][k] - centres[j][k];
      if (!is_zero(d)) dirs.push_back(d);
    }
  // The coordinate axes and the normals e_i +- e_j of the mirrors that swap two coordinates
  // (symmetric polynomials such as x^3 + y^3 + z^3 have those).
  for (size_t k = 0; k < 3; ++k) {
    V3 e{Rational(0), Rational(0), Rational(0)};
    e[k] = Rational(1);
    dirs.push_back(e);
    for (size_t l = k + 1; l < 3; ++l)
      for (int sg : {1, -1}) {
        V3 d{Rational(0), Rational(0), Rational(0)};
        d[k] = Rational(1);
        d[l] = Rational(sg);
        dirs.push_back(d);
      }
  }
  auto unique = [](std::vector<V3>& v) {
    for (auto& x : v)
      x = normalised(x);
    std::vector<V3> u;
    for (const auto& x : v)
      if (std::find(u.begin(), u.end(), x) == u.end()) u.push_back(x);
    v = std::move(u);
  };
  unique(dirs);
  const size_t n0 = std::min<size_t>(dirs.size(), 16); // bounded work: 16 + 120 directions
  for (size_t i = 0; i < n0; ++i)
    for (size_t j = i + 1; j < n0; ++j) {
      const V3 c = cross(dirs[i], dirs[j]);
      if (!is_zero(c)) dirs.push_back(c);
    }
  unique(dirs);
  if (centres.empty()) centres.push_back(V3{Rational(0), Rational(0), Rational(0)});
  {
    std::vector<V3> u;
    for (const auto& c : centres)
      if (std::find(u.begin(), u.end(), c) == u.end()) u.push_back(c);
    centres = std::move(u);
  }
  // Linear parts: -I, and per direction n the reflection I - 2 n n^T / |n|^2 and the
  // half-turn 2 n n^T / |n|^2 - I.
  std::vector<std::pair<M3, std::string>> parts;
  {
    M3 minus;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        minus[i][j] = Rational(i == j ? -1 : 0);
    parts.emplace_back(minus, "point reflection through ");
  }
  for (const V3& n : dirs) {
    const Rational nn = dot(n, n);
    M3 R, H;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const Rational p = Rational(2) * n[i] * n[j] / nn;
        R[i][j] = Rational(i == j ? 1 : 0) - p;
        H[i][j] = -R[i][j];
      }
    parts.emplace_back(R, "reflection in the plane with normal " + text(n) + " through ");
    parts.emplace_back(H, "half-turn about the axis " + text(n) + " through ");
  }
  for (const auto& [P, name] : parts)
    for (const V3& c : centres) {
      Isometry g = make(P, c, name + text(c));
      bool seen = false;
      for (const Isometry& h : out)
        seen = seen || (h.P == g.P && h.t == g.t);
      if (!seen && preserves(g, a) && preserves(g, b)) out.push_back(std::move(g));
    }
  return out;
}

void prove_ties(DistanceResult& r, const core::Surface& a, const core::Surface& b) {
  const size_t n = r.tie_regions.size();
  if (r.minimizers.is_continuum()) { // a continuum: ties between listed points mean nothing
    const std::string unproven = std::string("; ") + kUnprovenTiesNote;
    const size_t at = r.note.find(unproven);
    if (at != std::string::npos) r.note.erase(at, unproven.size());
    r.ties = Ties::None;
    return;
  }
  if (r.ties != Ties::Unproven || n < 2) return;
  for (const auto& reg : r.tie_regions)
    if (reg.empty() || reg.size() % 3 != 0 || reg.size() != r.tie_regions[0].size()) return;
  const std::vector<Isometry> G = common_symmetries(a, b);
  if (G.empty()) return;
  const long prec = 128;
  const size_t dim = r.tie_regions[0].size();
  // Regions as exact balls (the double endpoints are exact binary numbers).
  std::vector<std::vector<Ball>> box(n);
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < dim; ++k) {
      Ball x;
      arf_t lo, hi;
      arf_init(lo);
      arf_init(hi);
      arf_set_d(lo, r.tie_regions[i][k][0]);
      arf_set_d(hi, r.tie_regions[i][k][1]);
      arb_set_interval_arf(x.v, lo, hi, prec);
      arf_clear(lo);
      arf_clear(hi);
      box[i].push_back(std::move(x));
    }
  // reach[i][j]: a minimizer in region i implies one in region j.
  std::vector<std::vector<bool>> reach(n, std::vector<bool>(n, false));
  std::vector<std::string> used;
  for (const Isometry& g : G) {
    Ball P[3][3], t[3];
    for (size_t i = 0; i < 3; ++i) {
      arb_set_fmpq(t[i].v, g.t[i].raw(), prec);
      if (r.tie_directions || r.tie_lines) arb_zero(t[i].v); // directions: n -> P n
      for (size_t j = 0; j < 3; ++j)
        arb_set_fmpq(P[i][j].v, g.P[i][j].raw(), prec);
    }
    bool useful = false;
    for (size_t i = 0; i < n; ++i) {
      std::vector<Ball> img(dim);
      for (size_t o = 0; o < dim; o += 3)
        for (size_t l = 0; l < 3; ++l) {
          arb_set(img[o + l].v, t[l].v);
          for (size_t m = 0; m < 3; ++m)
            arb_addmul(img[o + l].v, P[l][m].v, box[i][o + m].v, prec);
        }
      size_t hits = 0, j = n;
      for (size_t k = 0; k < n; ++k) {
        bool meets = true;
        for (size_t c = 0; c < dim && meets; ++c)
          meets = arb_overlaps(img[c].v, box[k][c].v);
        if (!meets && r.tie_lines) { // a line's direction up to sign: the image negated
          meets = true;
          for (size_t c = 0; c < dim && meets; ++c) {
            Ball neg;
            arb_neg(neg.v, img[c].v);
            meets = arb_overlaps(neg.v, box[k][c].v);
          }
        }
        if (meets) {
          ++hits;
          j = k;
        }
      }
      if (hits == 1 && j != i && !reach[i][j]) {
        reach[i][j] = true;
        useful = true;
      }
    }
    if (useful) used.push_back(g.name);
  }
  // Transitive closure: every region must reach every other one.
  for (size_t k = 0; k < n; ++k)
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j)
        if (reach[i][k] && reach[k][j]) reach[i][j] = true;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j)
      if (i != j && !reach[i][j]) return;
  r.ties = Ties::Proven;
  const std::string unproven = kUnprovenTiesNote;
  const size_t at = r.note.find(unproven);
  std::string proven = "the " + std::to_string(n) +
                       " minimizing pairs are at exactly the same distance (proven: each is the "
                       "image of another under a common symmetry of both surfaces: ";
  for (size_t i = 0; i < used.size(); ++i)
    proven += (i ? "; " : "") + used[i];
  proven += ")";
  if (at != std::string::npos)
    r.note.replace(at, unproven.size(), proven);
  else
    r.note += (r.note.empty() ? "" : "; ") + proven;
}

} // namespace surfcert::certify
