// surfcert::core::InputError: bad input, the user's fault, with where it was found.
//
// Every parser and constructor of user-facing objects reports bad input by throwing
// InputError (never by printing or exiting). It carries a Location (source name, 1-based
// line and column when known, and the JSON path when the input came from JSON), what was
// expected and what was found. The CLI maps it to exit code 2. InternalError is our bug.
#pragma once

#include <stdexcept>
#include <string>

namespace surfcert::core {

struct Location {
  std::string source;    ///< file name, "<stdin>", "<argument 1>", ...
  int line = 0;          ///< 1-based; 0 = unknown
  int column = 0;        ///< 1-based; 0 = unknown
  std::string json_path; ///< e.g. "$.surfaces[1].radii[2]"; empty when not JSON

  /// "file:3:17 ($.a.matrix[0][1])" with the parts that are known.
  std::string to_string() const;
};

class InputError : public std::runtime_error {
public:
  InputError(Location where, std::string expected, std::string found);
  const Location& where() const { return where_; }
  const std::string& expected() const { return expected_; }
  const std::string& found() const { return found_; }

private:
  Location where_;
  std::string expected_;
  std::string found_;
};

class InternalError : public std::logic_error {
public:
  using std::logic_error::logic_error;
};

} // namespace surfcert::core
