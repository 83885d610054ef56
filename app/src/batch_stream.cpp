#include "surfcert/app/batch_stream.hpp"
#include "write_all.hpp"

#include <flint/flint.h>
#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_group.h>
#include <tbb/task_scheduler_observer.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <csignal>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
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

// The answers not yet written, and when to write them (batch_stream.hpp). A flusher thread
// writes the buffer once its oldest answer is max_delay old, and every full buffer (kFlushBytes)
// the answering threads hand it: they swap it for an empty one and go on answering while the
// flusher is in write(2) (a write of 256 KB to a file is ~0.1 ms of kernel time; done by an
// answering thread under the buffer's lock, it also held back the other threads' answers).
// Writes that a caller waits for (the input is idle, a flush, a signal) are made by the caller,
// after the flusher's write under way, so the bytes keep their order.
class OutputBuffer {
public:
  OutputBuffer(int fd, std::chrono::milliseconds max_delay)
      : fd_(fd), max_delay_(max_delay), flusher_([this] { flusher_loop(); }) {
    // Room for the most a buffer holds (two full buffers while the flusher still writes the
    // previous one, see append_line) and its last line, kept (clear() keeps it): grown by
    // doubling, a buffer is copied into fresh pages at each step (~130 page faults of ~30 µs
    // each on this VM, per buffer, at 256 KB; at two threads, where the flusher shares the
    // cores with the answering threads and so falls behind, both buffers grew past 256 KB).
    // Pages reserved and never filled are never touched.
    std::lock_guard<std::mutex> lock(m_);
    buf_.reserve(2 * kFlushBytes + kLineRoom);
    out_.reserve(2 * kFlushBytes + kLineRoom);
  }
  ~OutputBuffer() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    flusher_.join(); // it wrote its hand-over, if any
    write_locked();  // the rest: no other thread is left
  }

  void append_line(const std::string& text) {
    std::unique_lock<std::mutex> lock(m_);
    // A full buffer waits while the flusher still writes the previous one (the reader of the
    // output is slower than the answers: as when the write blocked an answering thread).
    if (buf_.size() >= 2 * kFlushBytes)
      cv_.wait(lock, [this] { return !handed_over_ || buf_.size() < 2 * kFlushBytes; });
    const bool was_empty = buf_.empty();
    buf_ += text;
    buf_ += '\n';
    if (input_idle_) {
      write_now(lock);
    } else if (buf_.size() >= kFlushBytes) {
      if (!handed_over_) {
        hand_over();
        cv_.notify_all();
      }
    } else if (was_empty) {
      oldest_ = std::chrono::steady_clock::now();
      // A flusher in a timed wait wakes by its deadline, that of an older answer (handed over
      // since), and then waits for this one's: only one waiting for an answer needs waking.
      // It is still woken once per full buffer, to write it.
      if (flusher_idle_) cv_.notify_all();
    }
  }

  // The reader is about to wait for input (idle = true) or got some (false): while it waits,
  // every answer is written as soon as it completes.
  void set_input_idle(bool idle) {
    std::unique_lock<std::mutex> lock(m_);
    input_idle_ = idle;
    if (idle) write_now(lock);
  }

  void flush() {
    std::unique_lock<std::mutex> lock(m_);
    write_now(lock);
  }

  // Writes what is buffered and keeps the lock: the caller ends the process next (a signal),
  // so no later answer is written half.
  void flush_and_hold() {
    std::unique_lock<std::mutex> lock(m_);
    write_now(lock);
    lock.release();
  }

private:
  static constexpr size_t kFlushBytes = 1 << 18;
  static constexpr size_t kLineRoom = 1 << 14;

  // buf_ becomes the flusher's to write (as out_); buf_ takes out_'s capacity.
  void hand_over() {
    buf_.swap(out_);
    handed_over_ = true;
  }

  // Writes the buffer now, after the flusher's hand-over under way (lock holds m_).
  void write_now(std::unique_lock<std::mutex>& lock) {
    cv_.wait(lock, [this] { return !handed_over_; });
    write_locked();
  }

  void write_locked() {
    if (buf_.empty()) return;
    if (ok_) ok_ = write_all(fd_, buf_.data(), buf_.size());
    buf_.clear();
  }

  void flusher_loop() {
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      if (handed_over_) {
        bool ok = ok_; // after a failed write, the rest is dropped (write_all.hpp)
        lock.unlock(); // out_ is this thread's until handed_over_ is false
        if (ok) ok = write_all(fd_, out_.data(), out_.size());
        out_.clear();
        lock.lock();
        ok_ = ok_ && ok;
        handed_over_ = false;
        cv_.notify_all(); // a caller of write_now, or an append waiting for room
        continue;
      }
      if (stop_) return;
      if (buf_.empty()) {
        flusher_idle_ = true;
        cv_.wait(lock, [this] { return stop_ || handed_over_ || !buf_.empty(); });
        flusher_idle_ = false;
        continue;
      }
      const auto due = oldest_ + max_delay_;
      if (std::chrono::steady_clock::now() >= due) {
        hand_over();
        continue;
      }
      cv_.wait_until(lock, due);
    }
  }

  int fd_;
  std::chrono::milliseconds max_delay_;
  std::mutex m_; ///< guards the members below but out_ while handed_over_
  std::condition_variable cv_;
  std::string buf_;
  std::string out_; ///< the flusher writes it while handed_over_
  std::chrono::steady_clock::time_point oldest_;
  bool input_idle_ = false, stop_ = false, ok_ = true;
  bool handed_over_ = false;  ///< out_ holds bytes for the flusher to write (before buf_'s)
  bool flusher_idle_ = false; ///< the flusher waits for an answer (without a deadline)
  std::thread flusher_;       // last: started once the members above exist
};

// Lines of a file descriptor, read in large blocks. Before it would block, it tells the output
// buffer that the input is idle (so answers already computed are written, not held).
class FdLineReader {
public:
  // The buffer is not zeroed (a vector<char> would be): its pages are touched only as input
  // arrives (16 page faults of ~40 µs each on an empty input, otherwise).
  FdLineReader(int fd, OutputBuffer& out)
      : fd_(fd), out_(out), buf_(new char[kInitialSize]), size_(kInitialSize) {}

  // The next line, as a view into the buffer valid until the next call; without may_wait,
  // only a line whose bytes have already arrived (else WouldBlock: the caller hands over the
  // lines it holds before it waits).
  detail::NextLine next(std::string_view& line, bool may_wait) {
    for (;;) {
      if (const void* nl = std::memchr(buf_.get() + begin_, '\n', end_ - begin_)) {
        const size_t e = static_cast<size_t>(static_cast<const char*>(nl) - buf_.get());
        line = std::string_view(buf_.get() + begin_, e - begin_);
        begin_ = e + 1;
        return detail::NextLine::Line;
      }
      if (eof_) {
        if (begin_ == end_) return detail::NextLine::End;
        line = std::string_view(buf_.get() + begin_, end_ - begin_); // the last line: no '\n'
        begin_ = end_;
        return detail::NextLine::Line;
      }
      if (!fill(may_wait)) return detail::NextLine::WouldBlock;
    }
  }

private:
  // Reads what is there; false when nothing is there and may_wait is false.
  bool fill(bool may_wait) {
    // Keep the partial line, make room behind it.
    if (begin_ > 0) {
      std::memmove(buf_.get(), buf_.get() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    if (end_ == size_) {
      std::unique_ptr<char[]> bigger(new char[2 * size_]);
      std::memcpy(bigger.get(), buf_.get(), end_);
      buf_ = std::move(bigger);
      size_ *= 2;
    }
    pollfd p{fd_, POLLIN, 0};
    const bool ready = ::poll(&p, 1, 0) > 0;
    if (!ready && !may_wait) return false;
    if (!ready) out_.set_input_idle(true);
    ssize_t n;
    do
      n = ::read(fd_, buf_.get() + end_, size_ - end_);
    while (n < 0 && errno == EINTR);
    if (!ready) out_.set_input_idle(false);
    if (n <= 0) {
      eof_ = true; // end of input (a read error ends it too)
      out_.set_input_idle(true);
      return true;
    }
    end_ += static_cast<size_t>(n);
    return true;
  }

  int fd_;
  OutputBuffer& out_;
  static constexpr size_t kInitialSize = 1 << 16;
  std::unique_ptr<char[]> buf_; // [0, size_): [begin_, end_) read and not yet returned
  size_t size_;
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

namespace {

// Lines handed from stage to stage together (one TBB token per chunk, not per line: the
// hand-over cost a few µs per line, as much as a classify answer). A chunk ends at kChunkLines
// lines, kChunkBytes bytes, the end of input, or where the next line has not arrived yet (a
// caller waiting for its answer is not held back by a chunk that waits to fill up).
constexpr size_t kChunkLines = 64;
constexpr size_t kChunkBytes = 1 << 15;
constexpr size_t kChunkRoom = 1 << 12; ///< a chunk's text past kChunkBytes: its last line
constexpr size_t kLinePadding = 64;    ///< bytes behind a line's end that its parser may read

struct BatchItem {
  size_t begin = 0, size = 0; ///< the line: text[begin, begin + size) of its chunk
  long line_no = 0;
  BatchLineAnswer answer;
};

struct Chunk {
  // The chunk's lines one after the other, copied in by the read stage: one block of text that
  // keeps its capacity (a string per line cost an allocation per line, and with 4 N chunks in
  // flight and lines of varying lengths ~250 more page faults at two threads, ~30 µs each).
  std::string text;
  std::vector<BatchItem> items; // the first n are this chunk's; the rest keep their capacity
  size_t n = 0;
  long seq = 0;
  std::atomic<size_t> next{0}; ///< the next line to answer (claimed by fetch_add)
  std::mutex m;                ///< guards complete and the advance of done
  std::vector<char> complete;  ///< complete[i]: answer i is complete
  std::atomic<size_t> done{0}; ///< answers [0, done) are complete
  size_t written = 0;          ///< answers [0, written) are written (under Writer::m)

  // Answer i is complete: advance done over the complete prefix.
  void completed(size_t i) {
    std::lock_guard<std::mutex> lock(m);
    complete[i] = 1;
    size_t d = done.load();
    while (d < n && complete[d])
      ++d;
    done.store(d);
  }
};

// Chunks for reuse: their strings keep their capacity, so a line costs no allocation.
class ChunkPool {
public:
  Chunk* take() {
    {
      std::lock_guard<std::mutex> lock(m_);
      if (!free_.empty()) {
        Chunk* c = free_.back().release();
        free_.pop_back();
        return c;
      }
    }
    return new Chunk();
  }
  void give(Chunk* c) {
    c->text.clear();
    std::fill(c->complete.begin(), c->complete.begin() + static_cast<std::ptrdiff_t>(c->n), 0);
    c->n = 0;
    c->next.store(0, std::memory_order_relaxed);
    c->done.store(0, std::memory_order_relaxed);
    c->written = 0;
    std::lock_guard<std::mutex> lock(m_);
    free_.emplace_back(c);
  }

private:
  std::mutex m_;
  std::vector<std::unique_ptr<Chunk>> free_;
};

// Writes answers as soon as they may be written: unordered, each when complete; ordered, the
// complete answers of the oldest chunk not yet written (the head), in order, whichever stage
// completes them. So a line completed in a chunk is written as it would have been alone (a
// slow line later in its chunk does not hold it back), and a signal finds it in the output.
class Writer {
public:
  Writer(const std::function<void(const BatchLineAnswer&)>& write, bool ordered,
         const std::function<void(const BatchStats&)>& progress)
      : write_(write), progress_(progress), ordered_(ordered) {}

  // Stage 1, in input order: c is in flight.
  void enter(Chunk* c) {
    if (!ordered_) return;
    std::lock_guard<std::mutex> lock(m_);
    in_flight_.push_back(c);
  }

  // Stage 2, once answer i of c is complete (c->done already advanced).
  void answered(Chunk* c, size_t i) {
    if (!ordered_) {
      std::lock_guard<std::mutex> lock(m_);
      write_locked(c->items[i].answer);
      return;
    }
    // seq_cst on both sides (done / head here, head / done in leave()): either this sees c
    // as the head or leave() sees the new done, so no complete answer is left unwritten.
    if (head_.load() != c->seq) return;
    std::lock_guard<std::mutex> lock(m_);
    write_done_locked(c);
  }

  // Stage 3, in input order (ordered) once every answer of c is complete.
  void leave(Chunk* c) {
    if (!ordered_) return; // every answer was written when complete
    std::lock_guard<std::mutex> lock(m_);
    write_done_locked(c);
    in_flight_.pop_front(); // c: chunks leave in input order
    head_.store(c->seq + 1);
    if (!in_flight_.empty()) write_done_locked(in_flight_.front());
  }

  const BatchStats& stats() const { return st_; }

private:
  // Ordered: the complete answers of c not yet written (c is the head).
  void write_done_locked(Chunk* c) {
    const size_t d = c->done.load();
    for (; c->written < d; ++c->written)
      write_locked(c->items[c->written].answer);
  }

  void write_locked(const BatchLineAnswer& a) {
    write_(a);
    ++st_.lines;
    if (a.status == "error") ++st_.errors;
    if (a.status == "error" && a.error_kind == "internal") ++st_.internal;
    if (a.status == "undecided") ++st_.undecided;
    if (a.status == "certified") ++st_.certified;
    st_.fallbacks += a.fallback ? 1 : 0;
    if (progress_) progress_(st_);
  }

  const std::function<void(const BatchLineAnswer&)>& write_;
  const std::function<void(const BatchStats&)>& progress_;
  const bool ordered_;
  std::mutex m_;
  std::deque<Chunk*> in_flight_; // ordered: the chunks read and not yet left, oldest first
  std::atomic<long> head_{0};    // ordered: the seq of in_flight_.front()
  BatchStats st_;
};

} // namespace

BatchStats
run_batch_pipeline(const std::function<NextLine(std::string_view& line, bool may_wait)>& next_line,
                   const std::function<void(const BatchLineAnswer&)>& write,
                   certify::Mode default_mode, const BatchTextAnswer& answer, int threads,
                   bool ordered, const std::function<void(const BatchStats&)>& progress) {
  install_flint_abort_handler();
  if (threads < 1) threads = 1;
  ChunkPool pool;
  Writer writer(write, ordered, progress);
  long next_no = 1, next_seq = 0;
  bool ended = false;
  // Stage 1, in input order: the next chunk of lines, or null at the end of input.
  auto read_chunk = [&]() -> Chunk* {
    if (ended) return nullptr;
    Chunk* c = pool.take();
    if (c->text.capacity() < kChunkBytes + kChunkRoom) c->text.reserve(kChunkBytes + kChunkRoom);
    while (c->n < kChunkLines && c->text.size() < kChunkBytes) {
      if (c->items.size() == c->n) {
        c->items.emplace_back();
        c->complete.push_back(0);
      }
      BatchItem& item = c->items[c->n];
      // The first line may wait for input; later ones only if already there.
      std::string_view line;
      const NextLine r = next_line(line, c->n == 0);
      if (r == NextLine::End) ended = true;
      if (r != NextLine::Line) break;
      item.line_no = next_no++;
      item.begin = c->text.size();
      item.size = line.size();
      c->text.append(line);
      ++c->n;
    }
    if (c->n == 0) {
      pool.give(c);
      return nullptr;
    }
    c->seq = next_seq++;
    writer.enter(c);
    return c;
  };
  // Stage 2: answer i of c, written as soon as it may be.
  auto answer_line = [default_mode, &answer, &writer](Chunk* c, size_t i) {
    BatchItem& item = c->items[i];
    // The line in a string of this thread's, with room behind it for a parser's padding (the
    // fast line reader, batch_line.cpp, reads 64 bytes past the end): no copy there. Its
    // capacity stays, so a line costs no allocation. Should an answer ever wait inside TBB (and
    // so run another line on this thread meanwhile), that inner line takes a string of its own.
    thread_local std::string own;
    thread_local bool own_in_use = false;
    std::string other;
    const bool nested = own_in_use;
    std::string& line = nested ? other : own;
    own_in_use = true;
    struct Release {
      bool nested;
      ~Release() {
        if (!nested) own_in_use = false;
      }
    } release{nested};
    if (line.capacity() < item.size + kLinePadding) line.reserve(item.size + kLinePadding);
    line.assign(c->text, item.begin, item.size);
    try { // the per-line guard: nothing escapes into the pipeline
      item.answer = answer(line, item.line_no, default_mode);
    } catch (const std::exception& e) {
      item.answer = {core::io::dump(internal_error_line(core::io::Json::null(), e.what())), "error",
                     "internal", false};
    } catch (...) {
      item.answer = {
          core::io::dump(internal_error_line(core::io::Json::null(), "unknown exception")), "error",
          "internal", false};
    }
    c->completed(i);
    writer.answered(c, i);
  };
  // Stage 3, in input order (ordered): c is done.
  auto leave = [&](Chunk* c) {
    writer.leave(c);
    pool.give(c);
  };
  if (threads == 1) {
    // One thread: the stages in turn on this thread, as TBB's pipeline runs them with one
    // thread (a chunk read, answered line by line, left; then the next), without starting
    // TBB's scheduler and allocator (~85 page faults, ~3 ms of every process's start: the
    // common `surfcert batch --threads 1` of short runs; bench/results/double_path.md).
    // Nothing below the app layer uses TBB, so nothing else is held to one thread here.
    while (Chunk* c = read_chunk()) {
      for (size_t i = c->next.fetch_add(1); i < c->n; i = c->next.fetch_add(1))
        answer_line(c, i);
      leave(c);
    }
    return writer.stats();
  }
  // --threads N: at most N threads answer lines, and at most 4 N chunks are in flight (read,
  // being answered, or waiting for an earlier chunk to be written).
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(threads));
  // One observer for the process, never destroyed: TBB keeps an internal proxy per observer
  // that a destroyed local observer leaked (LeakSanitizer); the static pointer keeps it
  // reachable (volatile: an optimised build dropped the store of a pointer never read, and
  // LeakSanitizer reported the observer at -O1).
  static FlintCleanupObserver* volatile cleanup = new FlintCleanupObserver();
  (void)cleanup;
  tbb::parallel_pipeline(
      static_cast<size_t>(4 * threads),
      tbb::make_filter<void, Chunk*>(tbb::filter_mode::serial_in_order,
                                     [&](tbb::flow_control& fc) -> Chunk* {
                                       Chunk* c = read_chunk();
                                       if (!c) fc.stop();
                                       return c;
                                     }) &
          tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::parallel,
                                           [&answer_line](Chunk* c) {
                                             // The lines are answered in turn by this thread; a
                                             // helper task, stolen only by an idle thread, answers
                                             // lines of the chunk too (and leaves another helper
                                             // behind each line it takes), so a slow line does not
                                             // hold back the lines after it in its chunk while a
                                             // thread is free (unordered output writes them at
                                             // once).
                                             tbb::task_group helpers;
                                             std::function<void()> help = [&] {
                                               for (;;) {
                                                 const size_t i = c->next.fetch_add(1);
                                                 if (i >= c->n) return;
                                                 if (i + 1 < c->n) helpers.run([&] { help(); });
                                                 answer_line(c, i);
                                               }
                                             };
                                             if (c->n > 1) helpers.run([&] { help(); });
                                             for (;;) {
                                               const size_t i = c->next.fetch_add(1);
                                               if (i >= c->n) break;
                                               answer_line(c, i);
                                             }
                                             helpers.wait();
                                             return c;
                                           }) &
          tbb::make_filter<Chunk*, void>(ordered ? tbb::filter_mode::serial_in_order
                                                 : tbb::filter_mode::serial_out_of_order,
                                         leave));
  return writer.stats();
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
      [&](std::string_view& line, bool may_wait) { return in.next(line, may_wait); },
      [&](const BatchLineAnswer& a) { out.append_line(a.text); }, default_mode, answer,
      options.threads, options.ordered, options.progress);
  out.flush(); // while the signals are still taken
  return st;
}

} // namespace surfcert::app
