// The batch op "generate" (see generate.hpp): a batch line's fields read into a
// GenerateRequest, each refusal located at its JSON path, and the answer wrapping the lines.
#include "surfcert/app/generate.hpp"

#include "surfcert/core/error.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include <algorithm>
#include <string>

namespace surfcert::app {

using core::InputError;
using core::Rational;
using core::io::Json;

namespace {

InputError refusal(const Json& v, const std::string& source, const std::string& path,
                   const std::string& expected) {
  std::string found = core::io::type_name(v.type());
  if (v.is_string()) found = "\"" + v.text() + "\"";
  if (v.is_number()) found = core::io::dump(v);
  return InputError(core::io::json_location(v, source, path), expected, found);
}

// An integer in [lo, hi] from a JSON number (not a string: these are counts, not surfaces).
long read_int(const Json& v, const std::string& source, const std::string& path, long lo, long hi,
              const std::string& expected) {
  if (!v.is_number()) throw refusal(v, source, path, expected);
  const Rational r = core::io::read_number(v, source, path);
  if (!r.is_integer() || r < Rational(lo) || r > Rational(hi))
    throw refusal(v, source, path, expected);
  return std::stol(r.to_string());
}

} // namespace

GenerateRequest read_generate_line(const Json& doc, const std::string& source) {
  core::io::check_fields(doc, {"id", "op", "case", "count", "seed", "encoding", "family", "gaps"},
                         source, "$");
  GenerateRequest r;
  r.threads = 1; // batch lines already run in parallel
  if (const Json* c = doc.find("case")) {
    const char* expected = "a case: 1..35, \"all\", \"degenerate_pencil\", \"coincident\", "
                           "\"ellipsoid\", \"natural\" or \"distance\"";
    if (c->is_number()) {
      r.what = std::to_string(read_int(*c, source, "$.case", 1, 35, expected));
    } else if (c->is_string()) {
      r.what = c->text();
      bool known = r.what == "all" || r.what == "degenerate_pencil" || r.what == "coincident" ||
                   r.what == "ellipsoid" || r.what == "natural" || r.what == "distance";
      if (!known && !r.what.empty() && r.what.size() <= 2 &&
          r.what.find_first_not_of("0123456789") == std::string::npos) {
        const int n = std::stoi(r.what);
        known = n >= 1 && n <= 35;
        if (known) r.what = std::to_string(n);
      }
      if (!known) throw refusal(*c, source, "$.case", expected);
    } else {
      throw refusal(*c, source, "$.case", expected);
    }
  }
  if (const Json* n = doc.find("count"))
    r.count = read_int(*n, source, "$.count", 1, kBatchGenerateMaxCount,
                       "a count from 1 to " + std::to_string(kBatchGenerateMaxCount));
  if (const Json* s = doc.find("seed")) {
    const char* expected = "a seed: an integer from 0 to 2^64 - 1";
    if (!s->is_number()) throw refusal(*s, source, "$.seed", expected);
    const Rational v = core::io::read_number(*s, source, "$.seed");
    if (!v.is_integer() || v.sign() < 0 || v.num().bits() > 64)
      throw refusal(*s, source, "$.seed", expected);
    r.seed = std::stoull(v.to_string());
  }
  if (const Json* e = doc.find("encoding")) {
    const auto enc = e->is_string() ? parse_encoding(e->text()) : std::nullopt;
    if (!enc)
      throw refusal(*e, source, "$.encoding", "an encoding: \"exact\", \"double\" or \"shape\"");
    r.encoding = *enc;
  }
  if (const Json* f = doc.find("family")) {
    const auto& names = family_names();
    if (!f->is_string() ||
        (f->text() != "all" && std::find(names.begin(), names.end(), f->text()) == names.end()))
      throw refusal(*f, source, "$.family",
                    "a family: \"tangency\", \"node\", \"acnode\", \"cusp\", \"double_conic\", "
                    "\"touching\", \"nested\" or \"all\"");
    r.family = f->text();
  }
  if (const Json* g = doc.find("gaps")) {
    const char* expected = "gaps: a nonempty array of integers k from 1 to 1000 (gap 2^-k)";
    if (!g->is_array() || g->size() == 0) throw refusal(*g, source, "$.gaps", expected);
    r.gaps.clear();
    for (size_t i = 0; i < g->size(); ++i)
      r.gaps.push_back(static_cast<int>(read_int(
          g->items()[i], source, core::io::json_path_index("$.gaps", i), 1, 1000, expected)));
  }
  return r;
}

Json generate_envelope(const GenerateRequest& request, const Json& line,
                       const std::string& source) {
  std::vector<Json> cases;
  try {
    cases = generate(request);
  } catch (const InputError& e) {
    // read_generate_line has checked every field but what the encoding can hold.
    const Json* e_json = line.find("encoding");
    throw InputError(core::io::json_location(e_json ? *e_json : line, source, "$.encoding"),
                     e.expected(), e.found());
  }
  bool undecided = false;
  const Json* failed = nullptr;
  Json list = Json::array();
  for (const Json& c : cases) {
    const Json* label = c.find("label");
    const std::string status = label->find("status")->text();
    undecided = undecided || status == "undecided";
    if (status == "error" && !failed) failed = label;
    list.push_back(c);
  }
  Json env = Json::object();
  env.set("status", Json::string(failed ? "error" : undecided ? "undecided" : "certified"));
  if (failed) {
    Json err = Json::object();
    err.set("kind", Json::string("internal"));
    const Json* m = failed->find("message");
    err.set("message", m ? *m : Json::string("labelling a case failed"));
    env.set("error", err);
  }
  Json result = Json::object();
  result.set("count", Json::number(static_cast<long>(cases.size())));
  result.set("cases", list);
  env.set("result", result);
  return env;
}

} // namespace surfcert::app
