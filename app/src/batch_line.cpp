#include "surfcert/app/batch_line.hpp"

#include "surfcert/core/io/json.hpp"

namespace surfcert::app {

using core::io::Json;

BatchLineAnswer answer_batch_line(const std::string& line, long line_no, certify::Mode default_mode,
                                  double default_budget_ms, certify::Detail default_detail) {
  BatchLineAnswer a;
  const Json r = process_batch_line(line, line_no, default_mode, &a.fallback, default_budget_ms,
                                    default_detail);
  if (const Json* s = r.find("status")) a.status = s->text();
  if (const Json* e = r.find("error"))
    if (const Json* k = e->is_object() ? e->find("kind") : nullptr)
      if (k->is_string()) a.error_kind = k->text();
  a.text = core::io::dump(r);
  return a;
}

} // namespace surfcert::app
