// surfcert::certify::cubic_and_line: exact line and cubic parametrisation (see cubic_line.hpp).
#include "surfcert/certify/cubic_line.hpp"

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/kernel.hpp"
#include "surfcert/algebra/pencil.hpp"
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/algebra/upoly.hpp"

#include <flint/fmpq_mat.h>
#include <flint/fmpz_poly.h>

#include <vector>

namespace surfcert::certify {

using core::Mat4;
using core::Rational;

namespace {

using Vec4 = std::array<Rational, 4>;
// A binary form of degree c.size() - 1: c[k] is the coefficient of s^(d-k) t^k.
using Form = std::vector<Rational>;

Form mul(const Form& x, const Form& y) {
  Form r(x.size() + y.size() - 1);
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = 0; j < y.size(); ++j)
      r[i + j] += x[i] * y[j];
  return r;
}

Form sub(const Form& x, const Form& y) { // equal degrees
  Form r = x;
  for (size_t i = 0; i < r.size(); ++i)
    r[i] -= y[i];
  return r;
}

Mat4 mat_of(const fmpq_mat_t m) {
  Mat4 r;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      fmpq_set(r[i][j].raw_mut(), fmpq_mat_entry(m, static_cast<slong>(i), static_cast<slong>(j)));
  return r;
}

void set_mat(fmpq_mat_t out, const Mat4& m) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      fmpq_set(fmpq_mat_entry(out, static_cast<slong>(i), static_cast<slong>(j)), m[i][j].raw());
}

// B A'^-1 B + p1 B + p0 A' (the kernel of p(A'^-1 B), p = l^2 + p1 l + p0).
Mat4 line_matrix(const Mat4& ap, const Mat4& b, const Rational& p1, const Rational& p0) {
  fmpq_mat_t ma, mb, inv, t, r;
  fmpq_mat_init(ma, 4, 4);
  fmpq_mat_init(mb, 4, 4);
  fmpq_mat_init(inv, 4, 4);
  fmpq_mat_init(t, 4, 4);
  fmpq_mat_init(r, 4, 4);
  set_mat(ma, ap);
  set_mat(mb, b);
  fmpq_mat_inv(inv, ma); // ap is regular (checked by the caller)
  fmpq_mat_mul(t, mb, inv);
  fmpq_mat_mul(r, t, mb);
  Mat4 out = mat_of(r) + core::scaled(b, p1) + core::scaled(ap, p0);
  for (auto* m : {&ma, &mb, &inv, &t, &r})
    fmpq_mat_clear(*m);
  return out;
}

// Distinct real roots (s : t) of a nonzero binary form.
int real_roots_p1(const Form& f) {
  const size_t d = f.size() - 1;
  int at_t_infinity = f[d].is_zero() ? 1 : 0; // s = 0 is a root
  std::vector<Rational> c(f.size());
  for (size_t k = 0; k <= d; ++k)
    c[k] = f[k]; // f(1, t) = sum c[k] t^k
  const algebra::UPolyQ p = algebra::UPolyQ::from_coeffs(c);
  if (p.degree() <= 0) return at_t_infinity;
  algebra::UPolyZ z = p.primitive_integer(), dz = z.derivative(), g, sq;
  fmpz_poly_gcd(g.raw_mut(), z.raw(), dz.raw());
  fmpz_poly_div(sq.raw_mut(), z.raw(), g.raw());
  return at_t_infinity + static_cast<int>(algebra::count_real_roots(sq.primitive_part()));
}

} // namespace

CubicAndLine cubic_and_line(const Mat4& a, const Mat4& b) {
  CubicAndLine out;
  // A regular member A' = A + k B (the curve is that of (A', B)).
  Mat4 ap;
  bool regular = false;
  for (long k : {0L, 1L, -1L, 2L, -2L, 3L, -3L, 5L}) {
    ap = a + core::scaled(b, Rational(k));
    if (!core::det(ap).is_zero()) {
      regular = true;
      break;
    }
  }
  if (!regular) {
    out.reason = "no regular member found among A + k B";
    return out;
  }
  const algebra::UPolyQ f = algebra::pencil_char_poly(ap, b);
  if (f.degree() != 4) {
    out.reason = "det(l A' - B) does not have degree 4";
    return out;
  }
  // f / lc = p^2 with p = l^2 + p1 l + p0 monic (exactly, or these are not the cases).
  const Rational lc = f.coeff(4);
  const Rational a3 = f.coeff(3) / lc, a2 = f.coeff(2) / lc;
  const Rational p1 = a3 / Rational(2), p0 = (a2 - p1 * p1) / Rational(2);
  const algebra::UPolyQ p = algebra::UPolyQ::from_coeffs({p0, p1, Rational(1)});
  if (!(p * p * algebra::UPolyQ(lc) == f)) {
    out.reason = "det(l A - B) is not a constant times a square: not a cubic and a line";
    return out;
  }
  const std::vector<Vec4> ker = algebra::kernel_basis(line_matrix(ap, b, p1, p0));
  if (ker.size() != 2) {
    out.reason = "ker p(A'^-1 B) is not two-dimensional: not a cubic and a line";
    return out;
  }
  for (const Mat4* q : {&a, &b})
    for (size_t i = 0; i < 2; ++i)
      for (size_t j = i; j < 2; ++j)
        if (!algebra::bilinear(*q, ker[i], ker[j]).is_zero()) {
          out.reason = "the kernel line does not lie on both quadrics";
          return out;
        }
  out.line = {ker[0], ker[1]};
  // Complete to a basis of Q^4 with two unit vectors.
  Vec4 e3, e4;
  bool basis = false;
  for (size_t i = 0; i < 4 && !basis; ++i)
    for (size_t j = i + 1; j < 4 && !basis; ++j) {
      Mat4 m;
      for (size_t r = 0; r < 4; ++r) {
        m[r][0] = ker[0][r];
        m[r][1] = ker[1][r];
        m[r][2] = Rational(r == i ? 1 : 0);
        m[r][3] = Rational(r == j ? 1 : 0);
      }
      if (!core::det(m).is_zero()) {
        for (size_t r = 0; r < 4; ++r) {
          e3[r] = m[r][2];
          e4[r] = m[r][3];
        }
        basis = true;
      }
    }
  // Residual line of each quadric in the plane span(line, w), w = s e3 + t e4, in the plane's
  // coordinates (x = a l0 + b l1 + c w): 2 a (l0.Q.w) + 2 b (l1.Q.w) + c (w.Q.w) = 0.
  auto coeffs = [&](const Mat4& q) {
    const Rational two(2);
    std::array<Form, 3> u;
    u[0] = {two * algebra::bilinear(q, ker[0], e3), two * algebra::bilinear(q, ker[0], e4)};
    u[1] = {two * algebra::bilinear(q, ker[1], e3), two * algebra::bilinear(q, ker[1], e4)};
    u[2] = {algebra::bilinear(q, e3, e3), two * algebra::bilinear(q, e3, e4),
            algebra::bilinear(q, e4, e4)};
    return u;
  };
  const auto u = coeffs(a), v = coeffs(b);
  const Form ca = sub(mul(u[1], v[2]), mul(u[2], v[1])); // degree 3
  const Form cb = sub(mul(u[2], v[0]), mul(u[0], v[2])); // degree 3
  const Form cc = sub(mul(u[0], v[1]), mul(u[1], v[0])); // degree 2
  const Form cs = mul(cc, Form{Rational(1), Rational(0)}),
             ct = mul(cc, Form{Rational(0), Rational(1)});
  Mat4 coef; // coef[i][k]
  for (size_t i = 0; i < 4; ++i)
    for (size_t k = 0; k < 4; ++k)
      coef[i][k] = ca[k] * ker[0][i] + cb[k] * ker[1][i] + cs[k] * e3[i] + ct[k] * e4[i];
  if (core::det(coef).is_zero()) {
    out.reason = "the residual points do not span a twisted cubic";
    return out;
  }
  // Exact check: Q(X(s, t)) == 0 identically for both quadrics.
  std::array<Form, 4> x;
  for (size_t i = 0; i < 4; ++i)
    x[i] = Form(coef[i].begin(), coef[i].end());
  for (const Mat4* q : {&a, &b}) {
    Form sum(7);
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) {
        if ((*q)[i][j].is_zero()) continue;
        const Form pr = mul(x[i], x[j]);
        for (size_t k = 0; k < 7; ++k)
          sum[k] += (*q)[i][j] * pr[k];
      }
    for (const auto& c : sum)
      if (!c.is_zero()) {
        out.reason = "the residual cubic does not lie on both quadrics";
        return out;
      }
  }
  out.cubic = coef;
  out.meet = {cc[0], cc[1], cc[2]};
  // Affine facts.
  const Vec4 &l0 = ker[0], &l1 = ker[1];
  out.line_at_infinity = l0[3].is_zero() && l1[3].is_zero();
  if (!out.line_at_infinity) {
    const Vec4& pnt = l0[3].is_zero() ? l1 : l0;
    const Vec4& oth = l0[3].is_zero() ? l0 : l1;
    for (size_t k = 0; k < 3; ++k) {
      out.line_point[k] = pnt[k] / pnt[3];
      out.line_direction[k] = oth[k] * pnt[3] - pnt[k] * oth[3];
    }
  }
  out.cubic_points_at_infinity = real_roots_p1(x[3]);
  out.found = true;
  return out;
}

} // namespace surfcert::certify
