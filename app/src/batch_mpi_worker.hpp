// surfcert::app (private to `batch --mpi`, batch_mpi.hpp) the lines a worker holds and the
// compute child process that answers them.
//
// What it represents: a LineWorker owns one compute child (`surfcert batch --mpi-child`, a
// fork + exec of the executable: a child that dies takes nothing of the worker with it), feeds
// it the lines it is given and collects their answers. When the child dies, every line it held
// is reported lost (answered by nobody) and a new child is started for the next lines.
// want() is the scheduling rule: a worker asks for as many lines as keep its threads busy
// plus a prefetch sized so that the prefetched lines take about 20 ms by the recent lines'
// measured times (0 to 16): fast lines come in groups, slow ones one at a time. The child
// gets one line per thread (two while the lines are fast); the prefetched rest waits in the
// worker, and when every thread of the child is on a slow line those lines are given back to
// rank 0, so a slow line holds up at most the one line queued behind it in the child. No MPI
// here.
#pragma once

#include "surfcert/app/batch_mpi.hpp"

#include <sys/types.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace surfcert::app::mpi_batch {

struct WorkLine {
  long no = 0;      ///< 1-based input line number
  std::string text; ///< the JSON line
};

struct WorkAnswer {
  long no = 0;
  std::string status, kind; ///< kind: the error's "kind", or empty
  bool fallback = false;
  double micros = 0; ///< the line's compute time in the child
  std::string text;  ///< the answer line (no newline)
};

/// One compute child and its two pipes (a writer thread feeds it, a reader thread collects).
class ComputeChild {
public:
  explicit ComputeChild(const std::vector<std::string>& command);
  ~ComputeChild();
  ComputeChild(const ComputeChild&) = delete;
  ComputeChild& operator=(const ComputeChild&) = delete;

  void send(const WorkLine& line);
  /// Moves the answers received so far into out; false once the child has ended (its answers
  /// all taken).
  bool take(std::vector<WorkAnswer>& out);
  /// Waits up to d for an answer or the child's end.
  void wait_for(std::chrono::microseconds d);
  pid_t pid() const { return pid_; }

private:
  void reader_loop();
  void writer_loop();

  pid_t pid_ = -1;
  int to_child_ = -1, from_child_ = -1;
  std::mutex m_;
  std::condition_variable answers_cv_, lines_cv_;
  std::vector<WorkAnswer> answers_;
  std::deque<std::string> lines_;
  bool ended_ = false, closing_ = false;
  std::thread reader_, writer_;
};

class LineWorker {
public:
  LineWorker(const std::vector<std::string>& command, int threads);

  /// How many more lines to give now (0: none; see above).
  int want() const;
  void give(std::vector<WorkLine> lines);
  /// Appends the answers since the last call, the lines lost by a child that died (a new
  /// child is then started), and the lines given back (waiting here while every thread of the
  /// child is on a slow line). True when something was appended.
  bool poll(std::vector<WorkAnswer>& answers, std::vector<long>& lost, std::vector<long>& returned);
  size_t held() const { return queue_.size() + in_child_.size(); }
  void wait_for(std::chrono::microseconds d) { child_->wait_for(d); }

private:
  using Clock = std::chrono::steady_clock;
  void feed();
  /// A line running longer than this (the larger of 50 ms and 4 mean lines) is slow.
  double stall_micros() const;
  bool stalled(Clock::time_point now) const;

  std::vector<std::string> command_;
  int threads_;
  std::unique_ptr<ComputeChild> child_;
  std::deque<WorkLine> queue_;                 ///< given, not yet sent to the child
  std::map<long, Clock::time_point> in_child_; ///< sent to the child, and when
  double mean_micros_ = 5000;                  ///< moving mean of the lines' compute times
  bool answered_ = false;                      ///< the current child has answered a line
  int silent_deaths_ = 0; ///< children in a row that died without answering a line
};

} // namespace surfcert::app::mpi_batch
