#include "surfcert/app/batch_stream.hpp"

#include <flint/flint.h>
#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_scheduler_observer.h>

#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <csignal>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <poll.h>
#include <pthread.h>
#include <unistd.h>

namespace surfcert::app {

namespace {

// Frees FLINT's thread-local caches when a TBB worker leaves the scheduler (as the old worker
// threads did with flint_cleanup before they ended).
class FlintCleanupObserver : public tbb::task_scheduler_observer {
public:
  FlintCleanupObserver() { observe(true); }
  ~FlintCleanupObserver() override { observe(false); }
  void on_scheduler_exit(bool is_worker) override {
    if (is_worker) flint_cleanup();
  }
};

struct BatchItem {
  std::string line;
  long line_no = 0;
  BatchLineAnswer answer;
};

// Writes all of [p, p + n) to fd; false on an error (the rest is then dropped: nobody reads).
bool write_all(int fd, const char* p, size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += w;
    n -= static_cast<size_t>(w);
  }
  return true;
}

// The answers not yet written, and when to write them (batch_stream.hpp). All members are
// guarded by m; a flusher thread writes the buffer once its oldest answer is max_delay old.
class OutputBuffer {
public:
  OutputBuffer(int fd, std::chrono::milliseconds max_delay)
      : fd_(fd), max_delay_(max_delay), flusher_([this] { flusher_loop(); }) {}
  ~OutputBuffer() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
      flush_locked();
    }
    cv_.notify_all();
    flusher_.join();
  }

  void append_line(const std::string& text) {
    std::lock_guard<std::mutex> lock(m_);
    const bool was_empty = buf_.empty();
    buf_ += text;
    buf_ += '\n';
    if (input_idle_ || buf_.size() >= kFlushBytes) {
      flush_locked();
    } else if (was_empty) {
      oldest_ = std::chrono::steady_clock::now();
      cv_.notify_all();
    }
  }

  // The reader is about to wait for input (idle = true) or got some (false): while it waits,
  // every answer is written as soon as it completes.
  void set_input_idle(bool idle) {
    std::lock_guard<std::mutex> lock(m_);
    input_idle_ = idle;
    if (idle) flush_locked();
  }

  void flush() {
    std::lock_guard<std::mutex> lock(m_);
    flush_locked();
  }

  // Writes what is buffered and keeps the lock: the caller ends the process next (a signal),
  // so no later answer is written half.
  void flush_and_hold() {
    m_.lock();
    flush_locked();
  }

private:
  static constexpr size_t kFlushBytes = 1 << 16;

  void flush_locked() {
    if (buf_.empty()) return;
    if (ok_) ok_ = write_all(fd_, buf_.data(), buf_.size());
    buf_.clear();
  }

  void flusher_loop() {
    std::unique_lock<std::mutex> lock(m_);
    while (!stop_) {
      if (buf_.empty()) {
        cv_.wait(lock, [this] { return stop_ || !buf_.empty(); });
        continue;
      }
      const auto due = oldest_ + max_delay_;
      if (std::chrono::steady_clock::now() >= due) {
        flush_locked();
        continue;
      }
      cv_.wait_until(lock, due);
    }
  }

  int fd_;
  std::chrono::milliseconds max_delay_;
  std::mutex m_;
  std::condition_variable cv_;
  std::string buf_;
  std::chrono::steady_clock::time_point oldest_;
  bool input_idle_ = false, stop_ = false, ok_ = true;
  std::thread flusher_; // last: started once the members above exist
};

// Lines of a file descriptor, read in large blocks. Before it would block, it tells the output
// buffer that the input is idle (so answers already computed are written, not held).
class FdLineReader {
public:
  FdLineReader(int fd, OutputBuffer& out) : fd_(fd), out_(out), buf_(1 << 16) {}

  bool next(std::string& line) {
    for (;;) {
      if (const void* nl = std::memchr(buf_.data() + begin_, '\n', end_ - begin_)) {
        const size_t e = static_cast<size_t>(static_cast<const char*>(nl) - buf_.data());
        // Room behind the line for a parser's padding (the fast line reader, batch_line.cpp,
        // reads 64 bytes past the end): no copy there.
        line.reserve(e - begin_ + 64);
        line.assign(buf_.data() + begin_, e - begin_);
        begin_ = e + 1;
        return true;
      }
      if (eof_) {
        if (begin_ == end_) return false;
        line.assign(buf_.data() + begin_, end_ - begin_); // the last line has no '\n'
        begin_ = end_;
        return true;
      }
      fill();
    }
  }

private:
  void fill() {
    // Keep the partial line, make room behind it.
    if (begin_ > 0) {
      std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    if (end_ == buf_.size()) buf_.resize(2 * buf_.size());
    pollfd p{fd_, POLLIN, 0};
    const bool ready = ::poll(&p, 1, 0) > 0;
    if (!ready) out_.set_input_idle(true);
    ssize_t n;
    do
      n = ::read(fd_, buf_.data() + end_, buf_.size() - end_);
    while (n < 0 && errno == EINTR);
    if (!ready) out_.set_input_idle(false);
    if (n <= 0) {
      eof_ = true; // end of input (a read error ends it too)
      out_.set_input_idle(true);
      return;
    }
    end_ += static_cast<size_t>(n);
  }

  int fd_;
  OutputBuffer& out_;
  std::vector<char> buf_;
  size_t begin_ = 0, end_ = 0;
  bool eof_ = false;
};

// SIGTERM, SIGINT, SIGHUP while the batch runs: blocked in every thread (threads started
// after the block inherit it: the output's flusher and TBB's workers) and taken by a thread of
// their own with sigwait, so the answers are written under the buffer's lock; then the
// process ends by the same signal.
class SignalBlock {
public:
  SignalBlock() {
    sigemptyset(&set_);
    for (int s : {SIGTERM, SIGINT, SIGHUP})
      sigaddset(&set_, s);
    pthread_sigmask(SIG_BLOCK, &set_, &old_);
  }
  ~SignalBlock() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  const sigset_t& set() const { return set_; }

private:
  sigset_t set_{}, old_{};
};

class SignalFlusher {
public:
  SignalFlusher(const SignalBlock& block, OutputBuffer& out) : set_(block.set()), out_(out) {
    thread_ = std::thread([this] { loop(); });
  }
  ~SignalFlusher() {
    stop_ = true;
    pthread_kill(thread_.native_handle(), SIGTERM);
    thread_.join();
  }

private:
  void loop() {
    int sig = 0;
    while (sigwait(&set_, &sig) != 0) {
    }
    if (stop_) return;
    out_.flush_and_hold();
    std::signal(sig, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, sig);
    pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
    ::raise(sig);
    _exit(128 + sig); // not reached
  }

  sigset_t set_;
  OutputBuffer& out_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

} // namespace

namespace detail {

BatchStats run_batch_pipeline(const std::function<bool(std::string& line)>& next_line,
                              const std::function<void(const BatchLineAnswer&)>& write,
                              certify::Mode default_mode, const BatchTextAnswer& answer,
                              int threads, bool ordered,
                              const std::function<void(const BatchStats&)>& progress) {
  install_flint_abort_handler();
  BatchStats st;
  if (threads < 1) threads = 1;
  // --threads N: at most N threads answer lines, and at most 4 N lines are in flight (read,
  // being answered, or waiting for an earlier line to be written).
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(threads));
  // One observer for the process, never destroyed: TBB keeps an internal proxy per observer
  // that a destroyed local observer leaked (LeakSanitizer); the static pointer keeps it
  // reachable.
  static FlintCleanupObserver* const cleanup = new FlintCleanupObserver();
  (void)cleanup;
  long next_no = 1;
  tbb::parallel_pipeline(
      static_cast<size_t>(4 * threads),
      tbb::make_filter<void, std::shared_ptr<BatchItem>>(
          tbb::filter_mode::serial_in_order,
          [&](tbb::flow_control& fc) -> std::shared_ptr<BatchItem> {
            auto item = std::make_shared<BatchItem>();
            if (!next_line(item->line)) {
              fc.stop();
              return nullptr;
            }
            item->line_no = next_no++;
            return item;
          }) &
          tbb::make_filter<std::shared_ptr<BatchItem>, std::shared_ptr<BatchItem>>(
              tbb::filter_mode::parallel,
              [default_mode, &answer](std::shared_ptr<BatchItem> item) {
                try { // the per-line guard: nothing escapes into the pipeline
                  item->answer = answer(item->line, item->line_no, default_mode);
                } catch (const std::exception& e) {
                  item->answer = {
                      core::io::dump(internal_error_line(core::io::Json::null(), e.what())),
                      "error", "internal", false};
                } catch (...) {
                  item->answer = {core::io::dump(internal_error_line(core::io::Json::null(),
                                                                     "unknown exception")),
                                  "error", "internal", false};
                }
                return item;
              }) &
          tbb::make_filter<std::shared_ptr<BatchItem>, void>(
              ordered ? tbb::filter_mode::serial_in_order : tbb::filter_mode::serial_out_of_order,
              [&](std::shared_ptr<BatchItem> item) {
                const BatchLineAnswer& a = item->answer;
                write(a);
                ++st.lines;
                if (a.status == "error") ++st.errors;
                if (a.status == "error" && a.error_kind == "internal") ++st.internal;
                if (a.status == "undecided") ++st.undecided;
                if (a.status == "certified") ++st.certified;
                st.fallbacks += a.fallback ? 1 : 0;
                if (progress) progress(st);
              }));
  return st;
}

} // namespace detail

BatchStats process_batch_fd(int in_fd, int out_fd, certify::Mode default_mode,
                            const BatchTextAnswer& answer, const BatchStreamOptions& options) {
  std::optional<SignalBlock> block; // before any thread starts, so that all inherit it
  if (options.flush_on_signal) block.emplace();
  OutputBuffer out(out_fd, options.max_delay);
  std::optional<SignalFlusher> signals;
  if (block) signals.emplace(*block, out);
  FdLineReader in(in_fd, out);
  BatchStats st = detail::run_batch_pipeline(
      [&](std::string& line) { return in.next(line); },
      [&](const BatchLineAnswer& a) { out.append_line(a.text); }, default_mode, answer,
      options.threads, options.ordered, options.progress);
  out.flush(); // while the signals are still taken
  return st;
}

} // namespace surfcert::app
