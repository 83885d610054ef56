#include "surfcert/certify/distance/common_apex.hpp"

#include "surfcert/algebra/upoly.hpp"
#include "surfcert/certify/distance/at_infinity.hpp"
#include "surfcert/certify/distance/ball.hpp"
#include "surfcert/certify/distance/quadratic_forms.hpp"
#include "surfcert/core/torus.hpp"

#include <flint/fmpq_mat.h>
#include <flint/fmpz_mat.h>

#include <array>

namespace surfcert::certify {

using core::Rational;

namespace {

using V3 = RVec3;
using M3 = RMat3;

// A common real affine singular point: a kernel vector (p, w), w != 0, of both 4x4 matrices.
std::optional<V3> common_singular_point(const core::QuadricMatrix& a,
                                        const core::QuadricMatrix& b) {
  for (const auto& k : common_kernel(a, b, 4))
    if (!k[3].is_zero()) return V3{k[0] / k[3], k[1] / k[3], k[2] / k[3]};
  return std::nullopt;
}

// x^T g x at the certified real points of the conic x^T f x = 0 on the lines w + t e (w, e
// small integer vectors; exact discriminant > 0, roots as Arb balls): true when both strict
// signs are seen.
bool sign_change_on_conic(const M3& f, const M3& g) {
  const long prec = 128;
  bool pos = false, neg = false;
  const std::array<V3, 3> es{{{Rational(1), Rational(0), Rational(0)},
                              {Rational(0), Rational(1), Rational(0)},
                              {Rational(0), Rational(0), Rational(1)}}};
  for (const auto& e : es) {
    const Rational qa = bilinear(f, e, e);
    if (qa.is_zero()) continue;
    for (long i = -3; i <= 3; ++i)
      for (long j = -3; j <= 3; ++j)
        for (long k = -3; k <= 3; ++k) {
          const V3 w{Rational(i), Rational(j), Rational(k)};
          const Rational qb = bilinear(f, w, e) * Rational(2), qc = bilinear(f, w, w);
          const Rational disc = qb * qb - Rational(4) * qa * qc;
          if (disc.sign() <= 0) continue;
          Ball sq, t, v[3], val, tmp;
          arb_set_fmpq(sq.v, disc.raw(), prec);
          arb_sqrt(sq.v, sq.v, prec);
          for (int sgn : {-1, 1}) {
            // t = (-qb +- sqrt(disc)) / (2 qa)
            arb_set_fmpq(t.v, qb.raw(), prec);
            arb_neg(t.v, t.v);
            if (sgn > 0)
              arb_add(t.v, t.v, sq.v, prec);
            else
              arb_sub(t.v, t.v, sq.v, prec);
            arb_set_fmpq(tmp.v, qa.raw(), prec);
            arb_mul_2exp_si(tmp.v, tmp.v, 1);
            arb_div(t.v, t.v, tmp.v, prec);
            for (size_t c = 0; c < 3; ++c) {
              arb_set_fmpq(v[c].v, e[c].raw(), prec);
              arb_mul(v[c].v, v[c].v, t.v, prec);
              arb_set_fmpq(tmp.v, w[c].raw(), prec);
              arb_add(v[c].v, v[c].v, tmp.v, prec);
            }
            arb_zero(val.v);
            for (size_t r = 0; r < 3; ++r)
              for (size_t c = 0; c < 3; ++c) {
                arb_mul(tmp.v, v[r].v, v[c].v, prec);
                Ball gij;
                arb_set_fmpq(gij.v, g[r][c].raw(), prec);
                arb_addmul(val.v, tmp.v, gij.v, prec);
              }
            pos = pos || arb_is_positive(val.v);
            neg = neg || arb_is_negative(val.v);
            if (pos && neg) return true;
          }
        }
  }
  return false;
}

int rank3(const M3& m) {
  fmpq_mat_t x;
  fmpz_mat_t z;
  fmpq_mat_init(x, 3, 3);
  fmpz_mat_init(z, 3, 3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      fmpq_set(fmpq_mat_entry(x, i, j), m[static_cast<size_t>(i)][static_cast<size_t>(j)].raw());
  fmpq_mat_get_fmpz_mat_rowwise(z, nullptr, x); // rows scaled: the same rank
  const slong r = fmpz_mat_rank(z);
  fmpz_mat_clear(z);
  fmpq_mat_clear(x);
  return static_cast<int>(r);
}

// A rank-1 symmetric form c l l^T: its line l.x = 0 (l a nonzero row). True when the conic
// x^T f x = 0 has a real point on that line (binary form on the line not definite).
bool double_line_meets(const M3& d, const M3& f) {
  V3 l = d[0];
  for (const auto& row : d)
    if (!(row[0].is_zero() && row[1].is_zero() && row[2].is_zero())) l = row;
  const auto fr = core::plane_frame(l);
  const Rational f11 = bilinear(f, fr[0], fr[0]), f12 = bilinear(f, fr[0], fr[1]),
                 f22 = bilinear(f, fr[1], fr[1]);
  return (f11 * f22 - f12 * f12).sign() <= 0; // real root of the binary form (or all zero)
}

// A common real line through the apex, proven by a rank-1 member of the pencil.
bool common_line_by_double_line(const M3& A, const M3& B) {
  if (rank3(A) == 1 && double_line_meets(A, B)) return true;
  if (rank3(B) == 1 && double_line_meets(B, A)) return true;
  // det(B - l A) as a cubic in l (exact, by interpolation at l = 0..3).
  std::vector<Rational> xs, ys;
  for (long l = 0; l <= 3; ++l) {
    M3 m;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        m[i][j] = B[i][j] - Rational(l) * A[i][j];
    const Rational det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    xs.push_back(Rational(l));
    ys.push_back(det);
  }
  // Lagrange interpolation over Q.
  algebra::UPolyQ p;
  for (size_t i = 0; i < 4; ++i) {
    algebra::UPolyQ term(ys[i]);
    for (size_t j = 0; j < 4; ++j)
      if (j != i)
        term =
            term * algebra::UPolyQ::linear(Rational(1) / (xs[i] - xs[j]), -xs[j] / (xs[i] - xs[j]));
    p = p + term;
  }
  if (p.is_zero()) return false; // every member singular: not this test's case
  for (const auto& l : algebra::rational_roots(p)) {
    M3 m;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        m[i][j] = B[i][j] - l * A[i][j];
    if (rank3(m) == 1 && double_line_meets(m, A)) return true;
  }
  return false;
}

} // namespace

std::optional<DistanceResult> common_apex_contact(const core::QuadricMatrix& a,
                                                  const core::QuadricMatrix& b) {
  const auto p = common_singular_point(a, b);
  if (!p) return std::nullopt;
  DistanceResult out;
  out.method = Method::CommonApex;
  out.distance = Enclosure::zero();
  const std::array<double, 3> w{(*p)[0].to_double_approx(), (*p)[1].to_double_approx(),
                                (*p)[2].to_double_approx()};
  out.pairs.push_back({w, w});
  const M3 A = quadratic_block(a), B = quadratic_block(b);
  const std::string apex = "the surfaces share the singular point (" + (*p)[0].to_string() + ", " +
                           (*p)[1].to_string() + ", " + (*p)[2].to_string() + ")";
  if (real_conics_disjoint(A, B)) {
    out.status = Status::Certified;
    out.minimizers = Minimizers::count(1, Minimizers::Proof::Exact);
    out.note = apex + " and meet nowhere else (their direction conics have no common real "
                      "point)";
  } else if (sign_change_on_conic(A, B) || sign_change_on_conic(B, A) ||
             common_line_by_double_line(A, B)) {
    out.status = Status::Certified;
    out.minimizers = Minimizers::continuum(Minimizers::Proof::Exact);
    out.note = apex + " and common real lines through it (proven)";
  } else {
    out.status = Status::Undecided;
    out.note = apex + " (distance 0, exact); whether they share lines through it is not decided";
  }
  return out;
}

} // namespace surfcert::certify
