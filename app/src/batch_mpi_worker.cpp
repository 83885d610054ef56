#include "batch_mpi_worker.hpp"
#include "write_all.hpp"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace surfcert::app::mpi_batch {

namespace {

// "<line_no> <status> <kind|-> <fallback> <micros>\t<answer>" (run_batch_child); false when
// the frame is malformed.
bool parse_answer(const std::string& frame, WorkAnswer& a) {
  const size_t tab = frame.find('\t');
  if (tab == std::string::npos) return false;
  char status[64], kind[64];
  int fallback = 0;
  double micros = 0;
  if (std::sscanf(frame.c_str(), "%ld %63s %63s %d %lf", &a.no, status, kind, &fallback, &micros) !=
      5)
    return false;
  a.status = status;
  a.kind = std::strcmp(kind, "-") == 0 ? "" : kind;
  a.fallback = fallback != 0;
  a.micros = micros;
  a.text.assign(frame, tab + 1, std::string::npos);
  return true;
}

} // namespace

ComputeChild::ComputeChild(const std::vector<std::string>& command) {
  // A child that dies must not kill the worker with SIGPIPE when it writes the next line.
  std::signal(SIGPIPE, SIG_IGN);
  int in[2], out[2];
  if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0)
    throw std::runtime_error("batch --mpi: cannot create the compute child's pipes");
  std::vector<char*> argv;
  for (const std::string& a : command)
    argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("batch --mpi: cannot fork the compute child");
  if (pid_ == 0) {
    // Only async-signal-safe calls until exec. The child dies with its worker.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    ::dup2(in[0], 0);
    ::dup2(out[1], 1);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(in[0]);
  ::close(out[1]);
  to_child_ = in[1];
  from_child_ = out[0];
  reader_ = std::thread([this] { reader_loop(); });
  writer_ = std::thread([this] { writer_loop(); });
}

ComputeChild::~ComputeChild() {
  {
    std::lock_guard<std::mutex> lock(m_);
    closing_ = true;
    lines_.clear(); // lines not yet written are abandoned
  }
  lines_cv_.notify_all();
  writer_.join(); // closes the child's input: it answers what it holds, then ends
  bool ended;
  {
    std::lock_guard<std::mutex> lock(m_);
    ended = ended_;
  }
  // Lines still held are abandoned (the run is over or the worker is stopping).
  if (!ended) ::kill(pid_, SIGKILL);
  reader_.join();
  ::close(from_child_);
  int st;
  while (::waitpid(pid_, &st, 0) < 0 && errno == EINTR) {
  }
}

void ComputeChild::send(const WorkLine& line) {
  std::string frame = std::to_string(line.no);
  frame += '\t';
  frame += line.text;
  frame += '\n';
  {
    std::lock_guard<std::mutex> lock(m_);
    lines_.push_back(std::move(frame));
  }
  lines_cv_.notify_one();
}

bool ComputeChild::take(std::vector<WorkAnswer>& out) {
  std::lock_guard<std::mutex> lock(m_);
  for (WorkAnswer& a : answers_)
    out.push_back(std::move(a));
  answers_.clear();
  return !ended_;
}

void ComputeChild::wait_for(std::chrono::microseconds d) {
  std::unique_lock<std::mutex> lock(m_);
  answers_cv_.wait_for(lock, d, [this] { return ended_ || !answers_.empty(); });
}

void ComputeChild::writer_loop() {
  std::unique_lock<std::mutex> lock(m_);
  for (;;) {
    lines_cv_.wait(lock, [this] { return closing_ || !lines_.empty(); });
    if (lines_.empty()) break; // closing, everything written
    std::string batch;
    while (!lines_.empty()) {
      batch += lines_.front();
      lines_.pop_front();
    }
    lock.unlock();
    const bool ok = write_all(to_child_, batch.data(), batch.size());
    lock.lock();
    if (!ok) break; // the child is gone: the reader sees its end
  }
  ::close(to_child_);
}

void ComputeChild::reader_loop() {
  std::string buf, frame;
  std::vector<char> block(1 << 16);
  std::vector<WorkAnswer> got;
  for (;;) {
    const ssize_t n = ::read(from_child_, block.data(), block.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    buf.append(block.data(), static_cast<size_t>(n));
    size_t start = 0, nl;
    while ((nl = buf.find('\n', start)) != std::string::npos) {
      frame.assign(buf, start, nl - start);
      start = nl + 1;
      WorkAnswer a;
      if (parse_answer(frame, a)) got.push_back(std::move(a));
    }
    buf.erase(0, start);
    if (!got.empty()) {
      {
        std::lock_guard<std::mutex> lock(m_);
        for (WorkAnswer& a : got)
          answers_.push_back(std::move(a));
      }
      got.clear();
      answers_cv_.notify_all();
    }
  }
  {
    std::lock_guard<std::mutex> lock(m_);
    ended_ = true;
  }
  answers_cv_.notify_all();
  lines_cv_.notify_all();
}

LineWorker::LineWorker(const std::vector<std::string>& command, int threads)
    : command_(command), threads_(std::max(1, threads)),
      child_(std::make_unique<ComputeChild>(command)) {}

double LineWorker::stall_micros() const {
  return std::max(50000.0, 4 * mean_micros_);
}

bool LineWorker::stalled(Clock::time_point now) const {
  if (static_cast<int>(in_child_.size()) < threads_) return false;
  for (const auto& [no, sent] : in_child_)
    if (std::chrono::duration<double, std::micro>(now - sent).count() < stall_micros())
      return false;
  return true;
}

int LineWorker::want() const {
  if (stalled(Clock::now())) return 0; // every thread is on a slow line: take nothing more
  // Prefetch: lines worth about 20 ms at the recent pace, at most 16; none for slow lines.
  const int prefetch =
      static_cast<int>(std::clamp(20000.0 / std::max(mean_micros_, 1.0), 0.0, 16.0));
  const int held = static_cast<int>(this->held());
  const int target = threads_ + prefetch;
  // Ask when a thread is idle, or when half the prefetch is used up (so that fast lines come
  // in groups, not one message each).
  if (held < threads_ || held <= threads_ + prefetch / 2) return std::min(16, target - held);
  return 0;
}

void LineWorker::feed() {
  // One line per thread in the child, two when the lines are fast (so that a thread never
  // waits for the pipe's round trip); the rest wait here, where they can still be given back.
  const size_t depth = static_cast<size_t>(threads_) * (mean_micros_ < 2000 ? 2 : 1);
  const auto now = Clock::now();
  while (in_child_.size() < depth && !queue_.empty()) {
    child_->send(queue_.front());
    in_child_[queue_.front().no] = now;
    queue_.pop_front();
  }
}

void LineWorker::give(std::vector<WorkLine> lines) {
  for (WorkLine& l : lines)
    queue_.push_back(std::move(l));
  feed();
}

bool LineWorker::poll(std::vector<WorkAnswer>& answers, std::vector<long>& lost,
                      std::vector<long>& returned) {
  const size_t before = answers.size(), lost_before = lost.size(),
               returned_before = returned.size();
  const bool alive = child_->take(answers);
  if (!alive) child_->take(answers); // the last answers it wrote before it died
  for (size_t i = before; i < answers.size(); ++i) {
    in_child_.erase(answers[i].no);
    mean_micros_ = 0.8 * mean_micros_ + 0.2 * answers[i].micros;
    answered_ = true;
  }
  if (!alive) {
    // A child that keeps dying before it answers anything (cannot start, e.g. the executable
    // is gone) would be started again forever: that ends the worker instead.
    silent_deaths_ = answered_ ? 0 : silent_deaths_ + 1;
    if (silent_deaths_ >= 3)
      throw std::runtime_error("batch --mpi: the compute child (" + command_[0] +
                               " batch --mpi-child) died three times without answering a line");
    // The lines in the child are lost; those waiting here go to the next child.
    for (const auto& [no, sent] : in_child_)
      lost.push_back(no);
    in_child_.clear();
    child_.reset();
    child_ = std::make_unique<ComputeChild>(command_);
    answered_ = false;
  }
  // Every thread on a slow line: the lines waiting behind them go back to rank 0 (others
  // answer them meanwhile).
  if (!queue_.empty() && stalled(Clock::now())) {
    for (const WorkLine& l : queue_)
      returned.push_back(l.no);
    queue_.clear();
  }
  feed();
  return answers.size() > before || lost.size() > lost_before || returned.size() > returned_before;
}

} // namespace surfcert::app::mpi_batch
