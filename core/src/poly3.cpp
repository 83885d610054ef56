#include "surfcert/core/poly3.hpp"

#include <algorithm>
#include <vector>

namespace surfcert::core {

Poly3::Poly3(const Rational& c) {
  if (!c.is_zero()) terms_.emplace(Exponent{0, 0, 0}, c);
}

Poly3 Poly3::variable(int var) {
  Poly3 p;
  Exponent e{0, 0, 0};
  e[static_cast<size_t>(var)] = 1;
  p.terms_.emplace(e, Rational(1));
  return p;
}

int Poly3::total_degree() const {
  int d = -1;
  for (const auto& [e, c] : terms_)
    d = std::max(d, e[0] + e[1] + e[2]);
  return d;
}

Rational Poly3::coeff(int i, int j, int k) const {
  auto it = terms_.find(Exponent{i, j, k});
  return it == terms_.end() ? Rational(0) : it->second;
}

void Poly3::add_term(const Exponent& e, const Rational& c) {
  if (c.is_zero()) return;
  auto it = terms_.find(e);
  if (it == terms_.end()) {
    terms_.emplace(e, c);
    return;
  }
  it->second += c;
  if (it->second.is_zero()) terms_.erase(it);
}

Poly3 operator+(const Poly3& a, const Poly3& b) {
  Poly3 r = a;
  for (const auto& [e, c] : b.terms_)
    r.add_term(e, c);
  return r;
}

Poly3 operator-(const Poly3& a, const Poly3& b) {
  return a + (-b);
}

Poly3 operator*(const Poly3& a, const Poly3& b) {
  Poly3 r;
  for (const auto& [ea, ca] : a.terms_)
    for (const auto& [eb, cb] : b.terms_)
      r.add_term(Poly3::Exponent{ea[0] + eb[0], ea[1] + eb[1], ea[2] + eb[2]}, ca * cb);
  return r;
}

Poly3 Poly3::operator-() const {
  Poly3 r = *this;
  for (auto& [e, c] : r.terms_)
    c = -c;
  return r;
}

Poly3 Poly3::scaled(const Rational& s) const {
  if (s.is_zero()) return Poly3();
  Poly3 r = *this;
  for (auto& [e, c] : r.terms_)
    c *= s;
  return r;
}

Poly3 Poly3::pow(unsigned n) const {
  Poly3 result(Rational(1)), base = *this;
  while (n) {
    if (n & 1u) result = result * base;
    n >>= 1u;
    if (n) base = base * base;
  }
  return result;
}

Rational Poly3::evaluate(const Rational& x, const Rational& y, const Rational& z) const {
  Rational s;
  const Rational* v[3] = {&x, &y, &z};
  for (const auto& [e, c] : terms_) {
    Rational t = c;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < e[static_cast<size_t>(i)]; ++k)
        t *= *v[i];
    s += t;
  }
  return s;
}

std::string Poly3::to_string() const {
  if (terms_.empty()) return "0";
  // Highest total degree first, then lexicographic (x before y before z).
  std::vector<std::pair<Exponent, Rational>> v(terms_.begin(), terms_.end());
  std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) {
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

Poly3 Poly3::substitute(const std::array<Poly3, 3>& xyz) const {
  Poly3 out;
  for (const auto& [e, c] : terms_)
    out = out + (xyz[0].pow(static_cast<unsigned>(e[0])) * xyz[1].pow(static_cast<unsigned>(e[1])) *
                 xyz[2].pow(static_cast<unsigned>(e[2])))
                    .scaled(c);
  return out;
}

} // namespace surfcert::core
