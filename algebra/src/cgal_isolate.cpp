// The only translation unit that includes CGAL's Algebraic_kernel_d_1 (about 20 s to compile).
#include "surfcert/algebra/real_roots.hpp"

#include <CGAL/Algebraic_kernel_d_1.h>
#include <CGAL/Gmpz.h>

#include <flint/fmpq.h>

#include <iterator>
#include <vector>

namespace surfcert::algebra {

namespace {
using AK = CGAL::Algebraic_kernel_d_1<CGAL::Gmpz>;

Rational from_gmpq(const CGAL::Gmpq& q) {
  Rational r;
  fmpq_set_mpq(r.raw_mut(), q.mpq());
  return r;
}
} // namespace

RootSeparation isolate_real_roots_cgal(const UPolyZ& p) {
  RootSeparation out;
  std::vector<CGAL::Gmpz> coeffs;
  for (long i = 0; i <= p.degree(); ++i) {
    mpz_t t;
    mpz_init(t);
    fmpz_get_mpz(t, p.coeff(i).raw());
    coeffs.emplace_back(t);
    mpz_clear(t);
  }
  AK ak;
  AK::Polynomial_1 poly(coeffs.begin(), coeffs.end());
  std::vector<AK::Algebraic_real_1> roots;
  ak.solve_1_object()(poly, true, std::back_inserter(roots));
  if (roots.empty()) {
    out.separators = {Rational(0)};
    return out;
  }
  auto bound_between = ak.bound_between_1_object();
  out.separators.push_back(from_gmpq(CGAL::Gmpq(roots.front().low())) - Rational(1));
  for (size_t i = 0; i + 1 < roots.size(); ++i)
    out.separators.push_back(from_gmpq(bound_between(roots[i], roots[i + 1])));
  out.separators.push_back(from_gmpq(CGAL::Gmpq(roots.back().high())) + Rational(1));
  return out;
}

} // namespace surfcert::algebra
