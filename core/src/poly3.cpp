#include "surfcert/core/poly3.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace surfcert::core {

namespace {

// One context for the whole program: three variables, lexicographic (x > y > z). FLINT
// contexts are read-only after initialisation, so sharing it between threads is safe.
struct Ctx {
  fmpq_mpoly_ctx_t c;
  Ctx() { fmpq_mpoly_ctx_init(c, 3, ORD_LEX); }
  ~Ctx() { fmpq_mpoly_ctx_clear(c); }
};

fmpq_mpoly_ctx_struct* shared_ctx() {
  static Ctx ctx;
  return ctx.c;
}

std::array<ulong, 3> unsigned_exponent(const Poly3::Exponent& e) {
  if (e[0] < 0 || e[1] < 0 || e[2] < 0) throw std::invalid_argument("Poly3: negative exponent");
  return {static_cast<ulong>(e[0]), static_cast<ulong>(e[1]), static_cast<ulong>(e[2])};
}

} // namespace

const fmpq_mpoly_ctx_struct* Poly3::ctx() {
  return shared_ctx();
}

Poly3::Poly3() {
  fmpq_mpoly_init(v_, shared_ctx());
}
Poly3::Poly3(long c) : Poly3() {
  fmpq_mpoly_set_si(v_, c, shared_ctx());
}
Poly3::Poly3(const Integer& c) : Poly3() {
  fmpq_mpoly_set_fmpz(v_, c.raw(), shared_ctx());
}
Poly3::Poly3(const Rational& c) : Poly3() {
  fmpq_mpoly_set_fmpq(v_, c.raw(), shared_ctx());
}
Poly3::Poly3(const Terms& t) : Poly3() {
  // Integer coefficients over the common denominator pushed into zpoly, then one
  // canonicalisation: linear in the number of terms (term-by-term adds would be quadratic).
  Integer den(1);
  for (const auto& [e, c] : t)
    fmpz_lcm(den.raw_mut(), den.raw(), fmpq_denref(c.raw()));
  fmpz_mpoly_struct* z = v_->zpoly;
  Integer k;
  for (const auto& [e, c] : t) {
    if (c.is_zero()) continue;
    fmpz_divexact(k.raw_mut(), den.raw(), fmpq_denref(c.raw()));
    fmpz_mul(k.raw_mut(), k.raw(), fmpq_numref(c.raw()));
    std::array<ulong, 3> u = unsigned_exponent(e);
    fmpz_mpoly_push_term_fmpz_ui(z, k.raw(), u.data(), shared_ctx()->zctx);
  }
  fmpz_mpoly_sort_terms(z, shared_ctx()->zctx);
  fmpz_mpoly_combine_like_terms(z, shared_ctx()->zctx);
  fmpq_set_fmpz_frac(v_->content, Integer(1).raw(), den.raw());
  fmpq_mpoly_reduce(v_, shared_ctx());
}
Poly3::Poly3(const Poly3& o) : Poly3() {
  fmpq_mpoly_set(v_, o.v_, shared_ctx());
}
Poly3::Poly3(Poly3&& o) noexcept : Poly3() {
  fmpq_mpoly_swap(v_, o.v_, shared_ctx());
}
Poly3& Poly3::operator=(const Poly3& o) {
  if (this != &o) fmpq_mpoly_set(v_, o.v_, shared_ctx());
  return *this;
}
Poly3& Poly3::operator=(Poly3&& o) noexcept {
  fmpq_mpoly_swap(v_, o.v_, shared_ctx());
  return *this;
}
Poly3::~Poly3() {
  fmpq_mpoly_clear(v_, shared_ctx());
}

Poly3 Poly3::variable(int var) {
  if (var < 0 || var > 2) throw std::invalid_argument("Poly3::variable: var must be 0, 1 or 2");
  Poly3 p;
  fmpq_mpoly_gen(p.v_, var, shared_ctx());
  return p;
}

bool Poly3::is_zero() const {
  return fmpq_mpoly_is_zero(v_, shared_ctx());
}
bool Poly3::is_constant() const {
  return fmpq_mpoly_is_fmpq(v_, shared_ctx());
}
int Poly3::total_degree() const {
  return static_cast<int>(fmpq_mpoly_total_degree_si(v_, shared_ctx()));
}
int Poly3::degree(int var) const {
  return static_cast<int>(fmpq_mpoly_degree_si(v_, var, shared_ctx()));
}
long Poly3::length() const {
  return fmpq_mpoly_length(v_, shared_ctx());
}

void Poly3::term(long i, Exponent& e, Rational& c) const {
  slong x[3];
  fmpq_mpoly_get_term_exp_si(x, v_, i, shared_ctx());
  for (size_t k = 0; k < 3; ++k)
    e[k] = static_cast<int>(x[k]);
  fmpq_mpoly_get_term_coeff_fmpq(c.raw_mut(), v_, i, shared_ctx());
}

Poly3::Terms Poly3::terms() const {
  Terms t;
  // FLINT's order is descending, so each insertion goes to the front (amortised constant).
  for_each_term([&](const Exponent& e, const Rational& c) { t.emplace_hint(t.begin(), e, c); });
  return t;
}

Rational Poly3::coeff(int i, int j, int k) const {
  Rational c;
  const std::array<ulong, 3> u = unsigned_exponent({i, j, k});
  fmpq_mpoly_get_coeff_fmpq_ui(c.raw_mut(), v_, u.data(), shared_ctx());
  return c;
}

void Poly3::add_term(const Exponent& e, const Rational& c) {
  if (c.is_zero()) return;
  const std::array<ulong, 3> u = unsigned_exponent(e);
  Rational s;
  fmpq_mpoly_get_coeff_fmpq_ui(s.raw_mut(), v_, u.data(), shared_ctx());
  s += c;
  fmpq_mpoly_set_coeff_fmpq_ui(v_, s.raw(), u.data(), shared_ctx());
}

Poly3 Poly3::derivative(int var) const {
  Poly3 r;
  fmpq_mpoly_derivative(r.v_, v_, var, shared_ctx());
  return r;
}

Poly3 operator+(const Poly3& a, const Poly3& b) {
  Poly3 r;
  fmpq_mpoly_add(r.v_, a.v_, b.v_, shared_ctx());
  return r;
}

Poly3 operator-(const Poly3& a, const Poly3& b) {
  Poly3 r;
  fmpq_mpoly_sub(r.v_, a.v_, b.v_, shared_ctx());
  return r;
}

Poly3 operator*(const Poly3& a, const Poly3& b) {
  Poly3 r;
  fmpq_mpoly_mul(r.v_, a.v_, b.v_, shared_ctx());
  return r;
}

Poly3 Poly3::operator-() const {
  Poly3 r;
  fmpq_mpoly_neg(r.v_, v_, shared_ctx());
  return r;
}

Poly3 Poly3::scaled(const Rational& s) const {
  Poly3 r;
  fmpq_mpoly_scalar_mul_fmpq(r.v_, v_, s.raw(), shared_ctx());
  return r;
}

Poly3 Poly3::pow(unsigned n) const {
  Poly3 r;
  if (!fmpq_mpoly_pow_ui(r.v_, v_, n, shared_ctx()))
    throw std::overflow_error("Poly3::pow: exponent too large");
  return r;
}

bool operator==(const Poly3& a, const Poly3& b) {
  return fmpq_mpoly_equal(a.v_, b.v_, shared_ctx());
}

Rational Poly3::evaluate(const Rational& x, const Rational& y, const Rational& z) const {
  Rational v[3] = {x, y, z}; // FLINT takes non-const pointers (it does not write them)
  fmpq* p[3] = {v[0].raw_mut(), v[1].raw_mut(), v[2].raw_mut()};
  Rational s;
  if (!fmpq_mpoly_evaluate_all_fmpq(s.raw_mut(), v_, p, shared_ctx()))
    throw std::overflow_error("Poly3::evaluate: value too large");
  return s;
}

Poly3 Poly3::substitute(const std::array<Poly3, 3>& xyz) const {
  Poly3 r;
  // FLINT takes non-const pointers to the substituted polynomials; it only reads them.
  fmpq_mpoly_struct* c[3];
  for (size_t i = 0; i < 3; ++i)
    c[i] = const_cast<fmpq_mpoly_struct*>(xyz[i].raw());
  if (!fmpq_mpoly_compose_fmpq_mpoly(r.v_, v_, c, shared_ctx(), shared_ctx()))
    throw std::overflow_error("Poly3::substitute: result too large");
  return r;
}

std::string Poly3::to_string() const {
  if (is_zero()) return "0";
  // Highest total degree first, then lexicographic (x before y before z).
  std::vector<std::pair<Exponent, Rational>> v;
  v.reserve(static_cast<size_t>(length()));
  for_each_term([&](const Exponent& e, const Rational& c) { v.emplace_back(e, c); });
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) {
    int da = a.first[0] + a.first[1] + a.first[2], db = b.first[0] + b.first[1] + b.first[2];
    if (da != db) return da > db;
    return a.first > b.first;
  });
  std::string s;
  const char* names[3] = {"x", "y", "z"};
  bool first = true;
  for (const auto& [e, c] : v) {
    Rational a = abs(c);
    if (first)
      s += c.sign() < 0 ? "-" : "";
    else
      s += c.sign() < 0 ? " - " : " + ";
    first = false;
    std::string mono;
    for (int i = 0; i < 3; ++i) {
      int k = e[static_cast<size_t>(i)];
      if (k == 0) continue;
      if (!mono.empty()) mono += "*";
      mono += names[i];
      if (k > 1) mono += "^" + std::to_string(k);
    }
    if (mono.empty())
      s += a.to_string();
    else if (a == Rational(1))
      s += mono;
    else
      s += a.to_string() + "*" + mono;
  }
  return s;
}

Poly3 dot(const std::array<Poly3, 3>& a, const std::array<Poly3, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

std::array<Poly3, 3> cross(const std::array<Poly3, 3>& a, const std::array<Poly3, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

} // namespace surfcert::core
