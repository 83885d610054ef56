#include "surfcert/certify/distance/minimizers.hpp"

namespace surfcert::certify {

std::string Minimizers::str() const {
  switch (kind_) {
  case Kind::Count:
    return std::to_string(n_);
  case Kind::Continuum:
    return "infinite";
  case Kind::NotAttained:
    return "0";
  case Kind::Undecided:
    return "undecided";
  default:
    return "";
  }
}

const char* Minimizers::proof_str() const {
  if (kind_ == Kind::Unknown) return "";
  if (kind_ == Kind::Undecided) return "unproven";
  return proof_ == Proof::Exact ? "exact" : "interval";
}

} // namespace surfcert::certify
