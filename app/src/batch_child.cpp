// The compute child of `surfcert batch --mpi` (batch_mpi.hpp): the single-process batch
// pipeline (batch_stream.hpp) on framed lines, answers framed with their line number, status
// and compute time, written as completed.
#include "surfcert/app/batch_line.hpp"
#include "surfcert/app/batch_mpi.hpp"
#include "surfcert/app/batch_stream.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace surfcert::app {

BatchStats run_batch_child(int in_fd, int out_fd, const MpiBatchOptions& options) {
  const double budget = options.budget_ms;
  const certify::Detail detail = options.detail;
  BatchStreamOptions opt;
  opt.threads = options.threads;
  opt.ordered = false;
  return process_batch_fd(
      in_fd, out_fd, options.mode,
      [budget, detail](const std::string& frame, long, certify::Mode mode) {
        const size_t tab = frame.find('\t');
        const long no = std::strtol(frame.c_str(), nullptr, 10);
        std::string line;
        line.reserve(frame.size() + 64); // the fast reader's padding (batch_line.cpp)
        if (tab != std::string::npos) line.assign(frame, tab + 1, std::string::npos);
        const auto t0 = std::chrono::steady_clock::now();
        BatchLineAnswer a;
        // The pipeline's own guard would lose the line number: the same internal error line
        // (null id, as the single-process batch writes it) is made here.
        try {
          a = answer_batch_line(line, no, mode, budget, detail);
        } catch (const std::exception& e) {
          a = {core::io::dump(internal_error_line(core::io::Json::null(), e.what())), "error",
               "internal", false};
        } catch (...) {
          a = {core::io::dump(internal_error_line(core::io::Json::null(), "unknown exception")),
               "error", "internal", false};
        }
        const double us =
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0)
                .count();
        char head[160];
        std::snprintf(head, sizeof head, "%ld %s %s %d %.0f\t", no, a.status.c_str(),
                      a.error_kind.empty() ? "-" : a.error_kind.c_str(), a.fallback ? 1 : 0, us);
        a.text.insert(0, head);
        return a;
      },
      opt);
}

} // namespace surfcert::app
