#include "surfcert/certify/detail.hpp"

namespace surfcert::certify {

const char* to_string(Detail d) {
  switch (d) {
  case Detail::Value:
    return "value";
  case Detail::Topology:
    return "topology";
  case Detail::Certificate:
    return "certificate";
  case Detail::Full:
    return "full";
  }
  return "?";
}

std::optional<Detail> parse_detail(std::string_view s) {
  if (s == "value") return Detail::Value;
  if (s == "topology") return Detail::Topology;
  if (s == "certificate") return Detail::Certificate;
  if (s == "full") return Detail::Full;
  return std::nullopt;
}

bool detail_accepted(std::string_view op, Detail d) {
  if (op == "distance") return d == Detail::Value || d == Detail::Full;
  if (op == "classify" || op == "intersect") return d != Detail::Value;
  return false;
}

const char* detail_spellings(std::string_view op) {
  if (op == "distance") return "\"value\" or \"full\"";
  if (op == "classify" || op == "intersect") return "\"topology\", \"certificate\" or \"full\"";
  return "no detail (only classify, intersect and distance have detail levels)";
}

Detail detail_for_op(std::string_view op, Detail d) {
  if (op == "distance") return d == Detail::Full ? Detail::Full : Detail::Value;
  return d == Detail::Value ? Detail::Topology : d;
}

} // namespace surfcert::certify
