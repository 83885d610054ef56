// surfcert::certify::Minimizers: how many pairs of points realise a minimum distance, and what
// proves it (the JSON "minimizers" and "minimizers_proof" fields).
//
// Contract: a value is one of
//   - a proven finite count n >= 1            JSON "n",
//   - a continuum (a curve or surface of minimizers)   "infinite",
//   - an infimum that is not attained                  "0",
//   - undecided: the count is not proven (several candidates whose equality or distinctness
//     is not established); `candidates()` says how many were left    "undecided",
//   - unknown (nothing established, e.g. an error answer): the field is absent.
// Every established value says how it was proven: Exact (exact arithmetic: closed forms,
// exact roots, exact decisions on the input) or Interval (rigorous enclosures: separated
// boxes, Krawczyk uniqueness, sign changes at certified points). An undecided value is
// unproven by definition. There is no constructor from text: a count is stated by the route
// that proved it.
#pragma once

#include <ostream>
#include <string>
#include <string_view>

namespace surfcert::certify {

class Minimizers {
public:
  enum class Kind { Unknown, Count, Continuum, NotAttained, Undecided };
  enum class Proof { None, Exact, Interval };

  Minimizers() = default;
  /// n >= 1 minimizers, proven distinct and all at the minimum.
  static Minimizers count(long n, Proof p) { return {Kind::Count, n, p}; }
  static Minimizers continuum(Proof p) { return {Kind::Continuum, 0, p}; }
  static Minimizers not_attained(Proof p) { return {Kind::NotAttained, 0, p}; }
  /// The count is not proven; `candidates` candidates were not separated from the minimum.
  static Minimizers undecided(long candidates) {
    return {Kind::Undecided, candidates, Proof::None};
  }

  Kind kind() const { return kind_; }
  Proof proof() const { return proof_; }
  bool empty() const { return kind_ == Kind::Unknown; }
  bool is_count() const { return kind_ == Kind::Count; }
  bool is_continuum() const { return kind_ == Kind::Continuum; }
  bool is_undecided() const { return kind_ == Kind::Undecided; }
  /// The proven count (Count) or the number of candidates (Undecided); 0 otherwise.
  long value() const { return n_; }

  /// The JSON spelling: "3", "infinite", "0", "undecided" ("" when unknown).
  std::string str() const;
  /// "exact", "interval", "unproven" ("" when unknown).
  const char* proof_str() const;

  friend bool operator==(const Minimizers& a, const Minimizers& b) {
    return a.kind_ == b.kind_ && a.n_ == b.n_;
  }
  friend bool operator!=(const Minimizers& a, const Minimizers& b) { return !(a == b); }
  /// Comparison with the JSON spelling (tests and readers of answers).
  friend bool operator==(const Minimizers& a, std::string_view s) { return a.str() == s; }
  friend bool operator!=(const Minimizers& a, std::string_view s) { return a.str() != s; }
  friend std::ostream& operator<<(std::ostream& o, const Minimizers& m) { return o << m.str(); }

private:
  Minimizers(Kind k, long n, Proof p) : kind_(k), n_(n), proof_(p) {}
  Kind kind_ = Kind::Unknown;
  long n_ = 0;
  Proof proof_ = Proof::None;
};

} // namespace surfcert::certify
