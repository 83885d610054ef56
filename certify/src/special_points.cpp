#include "surfcert/certify/special_points.hpp"

#include "surfcert/algebra/form_restriction.hpp"
#include "surfcert/algebra/inertia.hpp"
#include "surfcert/algebra/kernel.hpp"

#include <flint/fmpq_mat.h>

#include <optional>

namespace surfcert::certify {

using algebra::QuadraticNumber;
using core::Integer;
using core::Mat4;
using core::Rational;

namespace {

using Vec4 = std::array<Rational, 4>;
using QVec4 = std::array<QuadraticNumber, 4>;

// The kernel point of theta A - B (rank 3, theta = a + b sqrt d) when it lies on Q_A: the
// first nonzero row of the adjugate (its rows span the kernel of a rank-3 symmetric matrix).
std::optional<QVec4> quadratic_vertex(const algebra::PencilFacts& f, const QuadraticNumber& th) {
  const Integer& d = th.d;
  std::array<std::array<QuadraticNumber, 4>, 4> m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = {th.a * f.a[i][j] - f.b[i][j], th.b * f.a[i][j], d};
  auto minor = [&](size_t r, size_t c) { // det of m without row r and column c
    std::array<size_t, 3> rs{}, cs{};
    for (size_t i = 0, k = 0; i < 4; ++i)
      if (i != r) rs[k++] = i;
    for (size_t j = 0, k = 0; j < 4; ++j)
      if (j != c) cs[k++] = j;
    auto e = [&](size_t i, size_t j) { return m[rs[i]][cs[j]]; };
    auto m2 = [&](size_t i1, size_t j1, size_t i2, size_t j2) {
      return algebra::quadratic_add(algebra::quadratic_mul(e(i1, j1), e(i2, j2)),
                                    algebra::quadratic_mul(e(i1, j2), e(i2, j1)), -1);
    };
    QuadraticNumber t = algebra::quadratic_mul(e(0, 0), m2(1, 1, 2, 2));
    t = algebra::quadratic_add(t, algebra::quadratic_mul(e(0, 1), m2(1, 0, 2, 2)), -1);
    return algebra::quadratic_add(t, algebra::quadratic_mul(e(0, 2), m2(1, 0, 2, 1)));
  };
  for (size_t r = 0; r < 4; ++r) {
    QVec4 x;
    bool zero = true;
    for (size_t c = 0; c < 4; ++c) {
      x[c] = minor(r, c);
      if ((r + c) % 2) x[c] = {-x[c].a, -x[c].b, d};
      zero = zero && x[c].a.is_zero() && x[c].b.is_zero();
    }
    if (zero) continue;
    QuadraticNumber q{Rational(0), Rational(0), d}; // x^T A x
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        q = algebra::quadratic_add(q, algebra::quadratic_mul(algebra::quadratic_mul(x[i], x[j]),
                                                             {f.a[i][j], Rational(0), d}));
    if (!(q.a.is_zero() && q.b.is_zero())) return std::nullopt;
    return x;
  }
  return std::nullopt;
}

SpecialPoint make_point(const std::string& kind, const QVec4& x, const Integer& d) {
  SpecialPoint p;
  p.kind = kind;
  p.exact = true;
  bool w_zero = x[3].a.is_zero() && x[3].b.is_zero();
  p.at_infinity = w_zero;
  p.numbers.emplace();
  // d's square factors found once for the three coordinates (normalized() per coordinate
  // repeated the trial division: 15% of a cone-plane pair posed in doubles).
  std::optional<QuadraticNumber::SquareSplit> split;
  for (size_t i = 0; i < 3; ++i) {
    QuadraticNumber c = w_zero ? x[i] : algebra::quadratic_div(x[i], x[3]);
    c.d = d;
    (*p.numbers)[i] = c;
    if (!c.b.is_zero() && d.sign() > 0 && !split) split = algebra::square_split(d);
    if (split) c = c.normalized(*split);
    p.coords[i] = c.to_string();
    p.approx[i] = c.to_double_approx();
  }
  return p;
}

QVec4 lift(const Vec4& v, const Integer& d) {
  QVec4 r;
  for (size_t i = 0; i < 4; ++i)
    r[i] = QuadraticNumber{v[i], Rational(0), d};
  return r;
}

const char* vertex_kind(int c) {
  switch (c) {
  case 5:
  case 8:
    return "crunode";
  case 6:
  case 7:
    return "acnode";
  case 9:
    return "cusp";
  case 10:
    return "line_meets_cubic";
  case 12:
    return "tangency_point";
  case 23:
    return "lines_crossing";
  case 24:
  case 25:
    return "isolated_point";
  default:
    return "singular_point";
  }
}

const char* line_kind(int c) {
  switch (c) {
  case 13:
  case 18:
    return "crossing";
  case 15:
    return "isolated_point";
  case 19:
    return "contact";
  case 20:
    return "isolated_point";
  case 23:
  case 24:
  case 25:
    return "line_meets_conic";
  case 26:
    return "lines_cross_on_conic";
  case 27:
    return "tangency_point";
  case 28:
    return "vertex";
  case 30:
    return "isolated_point";
  default:
    return "singular_point";
  }
}

} // namespace

std::vector<SpecialPoint> special_points(const algebra::PencilFacts& f, int tu_case,
                                         bool& complete) {
  std::vector<SpecialPoint> out;
  complete = true;
  const Integer one(1);
  for (const auto& root : f.real_roots) {
    if (root.multiplicity < 2) continue;
    if (!root.rational_value) {
      // A conjugate pair of multiple roots theta = a +- b sqrt(d): where theta A - B has rank
      // 3 its kernel (a row of its adjugate, over Q(sqrt d)) is the singular point (a
      // cubic's crossings with its secant line, case 10); a kernel line would need a square
      // root over Q(sqrt d): not computed.
      if (root.quadratic && root.rank == 3) {
        if (auto x = quadratic_vertex(f, *root.quadratic))
          out.push_back(make_point(vertex_kind(tu_case), *x, root.quadratic->d));
        continue;
      }
      complete = false;
      continue;
    }
    Mat4 m;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j)
        m[i][j] = *root.rational_value * f.a[i][j] - f.b[i][j];
    auto ker = algebra::kernel_basis(m);
    if (ker.size() == 1) {
      if (algebra::bilinear(f.a.get(), ker[0], ker[0]).is_zero())
        out.push_back(make_point(vertex_kind(tu_case), lift(ker[0], one), one));
    } else if (ker.size() == 2) {
      const Vec4& u = ker[0];
      const Vec4& v = ker[1];
      Rational al = algebra::bilinear(f.a.get(), u, u), be = algebra::bilinear(f.a.get(), u, v),
               ga = algebra::bilinear(f.a.get(), v, v);
      if (al.is_zero() && be.is_zero() && ga.is_zero()) continue; // the line is a component
      const char* kind = line_kind(tu_case);
      if (al.is_zero()) {
        // q(s, t) = t (2 be s + ga t): points u, and (if be != 0) s = -ga / (2 be), t = 1.
        out.push_back(make_point(kind, lift(u, one), one));
        if (!be.is_zero()) {
          Rational s = -ga / (Rational(2) * be);
          Vec4 x;
          for (size_t i = 0; i < 4; ++i)
            x[i] = s * u[i] + v[i];
          out.push_back(make_point(kind, lift(x, one), one));
        }
        continue;
      }
      // al s^2 + 2 be s + ga = 0 (t = 1): s = (-be +- sqrt(disc)) / al, disc = be^2 - al ga.
      Rational disc = be * be - al * ga;
      if (disc.sign() < 0) continue;
      Integer dn = (disc.num() * disc.den()); // sqrt(p/q) = sqrt(p q) / q
      Integer root_int;
      fmpz_sqrt(root_int.raw_mut(), dn.raw());
      bool square = root_int * root_int == dn;
      for (int sg : {1, -1}) {
        if (disc.is_zero() && sg < 0) break;
        QuadraticNumber s;
        if (square) {
          Rational sq = Rational(root_int, disc.den());
          s = {(-be + Rational(sg) * sq) / al, Rational(0), one};
        } else {
          s = {-be / al, Rational(sg) / (al * Rational(disc.den())), dn};
        }
        Integer d = square ? one : dn;
        QVec4 x;
        for (size_t i = 0; i < 4; ++i)
          x[i] = QuadraticNumber{s.a * u[i] + v[i], s.b * u[i], d};
        out.push_back(make_point(kind, x, d));
      }
    } else if (ker.size() == 3) {
      // theta*A - B = c n n^T: the pole of the plane n.X = 0 w.r.t. A is where the two
      // (double) lines of Q_A in that plane cross (cases 32, 33); none for a double conic.
      Vec4 n;
      for (size_t i = 0;
           i < 4 && n[0].is_zero() && n[1].is_zero() && n[2].is_zero() && n[3].is_zero(); ++i)
        if (!(m[i][0].is_zero() && m[i][1].is_zero() && m[i][2].is_zero() && m[i][3].is_zero()))
          n = {m[i][0], m[i][1], m[i][2], m[i][3]};
      fmpq_mat_t qa, qn, qx;
      fmpq_mat_init(qa, 4, 4);
      fmpq_mat_init(qn, 4, 1);
      fmpq_mat_init(qx, 4, 1);
      for (slong i = 0; i < 4; ++i) {
        for (slong j = 0; j < 4; ++j)
          fmpq_set(fmpq_mat_entry(qa, i, j),
                   f.a[static_cast<size_t>(i)][static_cast<size_t>(j)].raw());
        fmpq_set(fmpq_mat_entry(qn, i, 0), n[static_cast<size_t>(i)].raw());
      }
      fmpq_mat_solve_fraction_free(qx, qa, qn);
      Vec4 p;
      for (size_t i = 0; i < 4; ++i)
        fmpq_set(p[i].raw_mut(), fmpq_mat_entry(qx, static_cast<slong>(i), 0));
      fmpq_mat_clear(qa);
      fmpq_mat_clear(qn);
      fmpq_mat_clear(qx);
      if (algebra::bilinear(f.a.get(), p, p).is_zero())
        out.push_back(make_point(tu_case == 33 ? "isolated_point" : "double_lines_crossing",
                                 lift(p, one), one));
    }
  }
  return out;
}

} // namespace surfcert::certify
