// surfcert::app::generate: test cases with certified labels, written as batch lines
// (`surfcert generate`).
//
// What it represents: a deterministic function of a GenerateRequest (the seed included) to a
// list of JSON objects, each a valid `batch` / `verify` input line ({"id", "op", "a", "b"})
// plus a "label": the answer surfcert's certified classifier (op classify) or distance engine
// (op distance) gives on exactly the surfaces written in the line (the line is read back
// through the input reader before it is labelled, so the label is of what a reader gets,
// never of the construction). The label's "construction" says how the case was built (the
// recipe and the Tu case it was built for, the gap of a family point, the expected distance
// of a closed form, the encoding and how its numbers read exactly): a certified label that
// disagrees with its construction is a bug, of the construction or of the classifier (the
// tests assert they agree).
// Sets: the 35 Tu cases from their real canonical forms (algebra/canonical_pencil.hpp),
// scrambled by random congruences and pencil bases; degenerate pencils and coincident pairs;
// pairs of actual ellipsoids realising the ellipsoid topologies of seed 002; natural-quadric
// pairs (seed 002 Table 7's ellipsoid-cylinder and ellipsoid-cone configurations; cylinders,
// cones, paraboloids, hyperboloids and spheres against each other), each aimed at a Tu case or
// a degenerate pencil; distance pairs with closed-form answers.
// Families: a path B0 + g D through a degeneracy, sampled at g = -2^-k, 0, +2^-k for the
// requested k.
// Encodings: exact (integers and "p/q" strings), double (every number a binary64 whose
// decimal text is its exact value: read as doubles or as exact decimals, the same surface),
// shape (a shape with centre, radii and a quaternion of small integers, all binary64, where
// the construction is a shape; otherwise the double matrix, and the label says so).
// Contract: the same request gives the same lines, byte for byte, on every platform (the
// draws are algebra::Rng's; labelling runs in parallel but lines keep their order).
#pragma once

#include "surfcert/core/error.hpp"
#include "surfcert/core/io/json.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace surfcert::app {

enum class Encoding { Exact, Double, Shape };
std::optional<Encoding> parse_encoding(const std::string& s);
const char* to_string(Encoding e);

struct GenerateRequest {
  /// "1".."35", "all" (the 35 cases, degenerate_pencil and coincident), "degenerate_pencil",
  /// "coincident", "ellipsoid", "natural" or "distance". Ignored when `family` is set.
  std::string what = "all";
  /// "" (none), one of family_names(), or "all".
  std::string family;
  std::vector<int> gaps{10, 20, 40}; ///< family points at g = +-2^-k (and g = 0)
  long count = 1;                    ///< random instances per case (poses per family point)
  std::uint64_t seed = 1;
  Encoding encoding = Encoding::Exact;
  int threads = 1; ///< labelling threads (the output does not depend on it)
};

/// The families: pencil paths (op classify) "tangency", "node", "acnode", "cusp",
/// "double_conic"; distance paths (op distance) "touching", "nested".
const std::vector<std::string>& family_names();

/// What generate() throws for a request it cannot meet: an InputError located on the command
/// line (as `surfcert generate` reports it) that also names the option at fault by the JSON
/// path it has as a field of a batch line or a Python keyword: "$.case", "$.count",
/// "$.family", "$.gaps" or "$.gaps[i]", "$.encoding" (a case the double encoding cannot hold).
class GenerateRefusal : public core::InputError {
public:
  GenerateRefusal(std::string option_path, const std::string& expected, const std::string& found)
      : core::InputError(core::Location{"<command line>", 0, 0, ""}, expected, found),
        option_path_(std::move(option_path)) {}
  const std::string& option_path() const { return option_path_; }

private:
  std::string option_path_;
};

/// The lines of the request, labelled, in a fixed order. Throws GenerateRefusal for a
/// request that cannot be met (unknown case or family, k outside 1..1000, a family point the
/// double encoding cannot hold exactly), before anything is labelled.
std::vector<core::io::Json> generate(const GenerateRequest& request);

/// The batch op "generate": the request of a batch line {"id", "op": "generate", "case",
/// "count", "seed", "encoding", "family", "gaps"} (every field but "op" optional, defaults as
/// GenerateRequest's; "count" at most kBatchGenerateMaxCount, labelling on the line's own
/// thread). Throws core::InputError located at the offending field's JSON path ($.case,
/// $.count, ...) for an unknown field or a value generate() would refuse.
GenerateRequest read_generate_line(const core::io::Json& line, const std::string& source);
constexpr long kBatchGenerateMaxCount = 1000;

/// The fields of the answer to a generate line: "status" (certified when every label is,
/// undecided when some is, error with an "internal" error when labelling some case failed) and
/// "result": {"count": n, "cases": [the n objects generate() gives, in its order]}; the cases
/// are exactly the lines `surfcert generate` prints for the same options. A request the
/// encoding cannot hold throws core::InputError at `source` $.encoding.
core::io::Json generate_envelope(const GenerateRequest& request, const core::io::Json& line,
                                 const std::string& source);

} // namespace surfcert::app
