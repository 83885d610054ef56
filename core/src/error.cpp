#include "surfcert/core/error.hpp"

namespace surfcert::core {

std::string Location::to_string() const {
  std::string s = source.empty() ? "<input>" : source;
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  if (!json_path.empty()) s += " (" + json_path + ")";
  return s;
}

static std::string compose(const Location& w, const std::string& expected,
                           const std::string& found) {
  return w.to_string() + ": expected " + expected + ", found " + found;
}

InputError::InputError(Location where, std::string expected, std::string found)
    : std::runtime_error(compose(where, expected, found)), where_(std::move(where)),
      expected_(std::move(expected)), found_(std::move(found)) {}

} // namespace surfcert::core
