// `surfcert batch --mpi` (batch_mpi.hpp): rank 0's scheduler (BatchMaster), the workers' loop,
// and the MPI messages between them.
//
// Messages (MPI_BYTE, each sent with MPI_Isend so that a worker and rank 0 sending to each
// other at once never wait on each other):
//   worker -> 0, kReport: how many lines it wants now (0: none), the answers completed since
//     its last report, the lines its compute child lost by dying, and the lines it gives back
//     unstarted (every thread of its child is on a slow line);
//   0 -> worker, kWork: a group of lines (line number, text); kStop: the run is over.
// A worker has at most one request open; rank 0 answers it as soon as it has lines.
// With Open MPI's recovery (batch_mpi.hpp) also: kBeat both ways (empty, when nothing else
// was sent for a heartbeat interval), and the end's handshake: 0 -> worker kStop, worker -> 0
// kBye (so that no message is still on its way when the processes leave without
// MPI_Finalize: over TCP an eager send that has "completed" may not have left yet).
#include "surfcert/app/batch_mpi.hpp"

#include "batch_checkpoint.hpp"
#include "batch_mpi_worker.hpp"
#include "write_all.hpp"

#include "surfcert/core/error.hpp"
#include "surfcert/core/io/json.hpp"

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <iostream>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>
#include <utility>

#include <unistd.h>

namespace surfcert::app {

namespace mpi_batch {

namespace {

using Clock = std::chrono::steady_clock;
using core::io::Json;

enum Tag { kWork = 1, kStop = 2, kReport = 3, kBeat = 4, kBye = 5 };
constexpr int kMaxGroup = 16;

void put_i64(std::string& b, std::int64_t v) {
  b.append(reinterpret_cast<const char*>(&v), 8);
}
void put_str(std::string& b, const std::string& s) {
  put_i64(b, static_cast<std::int64_t>(s.size()));
  b += s;
}

struct Unpacker {
  const std::string& b;
  size_t at = 0;
  std::int64_t i64() {
    std::int64_t v = 0;
    if (at + 8 > b.size()) throw std::runtime_error("batch --mpi: truncated message");
    std::memcpy(&v, b.data() + at, 8);
    at += 8;
    return v;
  }
  std::string str() {
    const auto n = static_cast<size_t>(i64());
    if (at + n > b.size()) throw std::runtime_error("batch --mpi: truncated message");
    std::string s = b.substr(at, n);
    at += n;
    return s;
  }
};

// The input's lines, read by a thread of its own so that the scheduler never blocks on stdin
// (at most kAhead lines wait in memory).
class InputThread {
public:
  explicit InputThread(int fd) : fd_(fd), thread_([this] { loop(); }) {}
  ~InputThread() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    // A thread still blocked in read(2) (the run ended on an error) is left to the process's end.
    if (ended_)
      thread_.join();
    else
      thread_.detach();
  }

  /// Moves up to max lines into out; false once the input has ended and every line was taken.
  bool take(std::deque<std::string>& out, size_t max) {
    std::lock_guard<std::mutex> lock(m_);
    while (max-- > 0 && !lines_.empty()) {
      out.push_back(std::move(lines_.front()));
      lines_.pop_front();
    }
    cv_.notify_all();
    return !(ended_ && lines_.empty());
  }

private:
  static constexpr size_t kAhead = 8192;

  void loop() {
    std::string buf;
    std::vector<char> block(1 << 16);
    for (;;) {
      const ssize_t n = ::read(fd_, block.data(), block.size());
      if (n < 0 && errno == EINTR) continue;
      std::unique_lock<std::mutex> lock(m_);
      if (n <= 0) {
        if (!buf.empty()) lines_.push_back(std::move(buf)); // a last line without '\n'
        ended_ = true;
        return;
      }
      buf.append(block.data(), static_cast<size_t>(n));
      size_t start = 0, nl;
      while ((nl = buf.find('\n', start)) != std::string::npos) {
        lines_.push_back(buf.substr(start, nl - start));
        start = nl + 1;
      }
      buf.erase(0, start);
      cv_.wait(lock, [this] { return stop_ || lines_.size() < kAhead; });
      if (stop_) return;
    }
  }

  int fd_;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::string> lines_;
  std::atomic<bool> ended_{false};
  bool stop_ = false;
  std::thread thread_; // last: started once the members above exist
};

bool budget_undecided(const std::string& status, const std::string& text) {
  if (status != "undecided") return false;
  try {
    const Json j = core::io::parse_json(text, "answer");
    const Json* r = j.find("reason");
    return r && r->is_string() && r->text() == "budget";
  } catch (const std::exception&) {
    return false;
  }
}

// The line with "budget_ms" set to budget_ms (the second pass of --retry-undecided).
std::string with_budget(const std::string& line, double budget_ms) {
  Json doc = core::io::parse_json(line, "<stdin>");
  char ms[64];
  std::snprintf(ms, sizeof ms, "%.17g", budget_ms);
  doc.set("budget_ms", Json::number_text(ms));
  return core::io::dump(doc);
}

Json id_of(const std::string& line) {
  try {
    const Json doc = core::io::parse_json(line, "<stdin>");
    if (const Json* id = doc.find("id")) return *id;
  } catch (const std::exception&) {
  }
  return Json::null();
}

// Rank 0's bookkeeping: the lines read and not yet answered for good, the queues they wait in,
// the answers waiting for their turn in the output, the checkpoint and the statistics.
class BatchMaster {
public:
  BatchMaster(int in_fd, int out_fd, const MpiBatchOptions& o, int workers)
      : o_(o), out_fd_(out_fd), workers_(workers), input_(in_fd) {
    if (!o.checkpoint.empty()) checkpoint_.emplace(o.checkpoint);
  }

  // Reads lines until kAhead wait to be sent.
  void pump_input() {
    if (input_ended_ || fresh_.size() >= kAhead) return;
    std::deque<std::string> got;
    const bool more = input_.take(got, kAhead - fresh_.size());
    for (std::string& text : got)
      add_line(++read_, std::move(text));
    if (!more) {
      input_ended_ = true;
      if (checkpoint_ && !checkpoint_->records().empty() &&
          checkpoint_->records().rbegin()->first > read_)
        throw core::InputError(
            core::Location{o_.checkpoint, 0, 0, ""}, "a checkpoint of this input",
            "answers for line " + std::to_string(checkpoint_->records().rbegin()->first) +
                " of an input of " + std::to_string(read_) + " lines");
    }
  }

  /// Up to want (at most kMaxGroup) lines for worker w: lost lines first (not to the worker
  /// that lost them, when there are others), then first-pass lines, then, once every line has
  /// been read and sent, the second pass.
  std::vector<WorkLine> take_lines(int w, int want) {
    std::vector<WorkLine> out;
    want = std::min(want, kMaxGroup);
    for (auto it = lost_.begin(); it != lost_.end() && static_cast<int>(out.size()) < want;) {
      const Open& l = open_.at(*it);
      if (l.avoid == w && workers_ > 1) {
        ++it;
        continue;
      }
      out.push_back(line_for(*it, l));
      it = lost_.erase(it);
    }
    while (static_cast<int>(out.size()) < want && !fresh_.empty()) {
      out.push_back(line_for(fresh_.front(), open_.at(fresh_.front())));
      fresh_.pop_front();
    }
    if (input_ended_ && fresh_.empty())
      while (static_cast<int>(out.size()) < want && !second_.empty()) {
        out.push_back(line_for(second_.front(), open_.at(second_.front())));
        second_.pop_front();
      }
    for (const WorkLine& l : out)
      open_.at(l.no).holder = w;
    return out;
  }

  /// A worker's answers, the lines its compute child lost by dying, and the lines it gave
  /// back unstarted (they go first to the next worker that asks).
  void on_answers(int w, std::vector<WorkAnswer>& answers, const std::vector<long>& lost,
                  const std::vector<long>& returned) {
    for (auto it = returned.rbegin(); it != returned.rend(); ++it)
      if (auto l = open_.find(*it); l != open_.end()) {
        l->second.holder = -1;
        fresh_.push_front(*it);
      }
    report_.returned += static_cast<long>(returned.size());
    for (WorkAnswer& a : answers) {
      auto it = open_.find(a.no);
      if (it == open_.end()) continue; // already answered (cannot happen: each line has one holder)
      Open& l = it->second;
      CheckpointRecord r{l.hash, l.pass, a.status, a.kind, a.fallback, std::move(a.text)};
      if (checkpoint_) checkpoint_->append(a.no, r);
      if (r.pass == 1 && o_.retry_budget_ms > 0 && budget_undecided(r.status, r.text)) {
        l.pass = 2;
        l.losses = 0;
        l.holder = -1;
        second_.push_back(a.no);
        ++report_.second_pass;
        continue;
      }
      finalize(a.no, r);
      open_.erase(it);
    }
    for (long no : lost)
      lose(w, no);
    if (checkpoint_) checkpoint_->write_pending();
  }

  /// Worker w (a rank) is dead: the lines it held are lost, as by a compute child that died,
  /// and it counts no more among the workers.
  void on_rank_dead(int w) {
    std::vector<long> held;
    for (const auto& [no, l] : open_)
      if (l.holder == w) held.push_back(no);
    std::sort(held.begin(), held.end());
    for (long no : held)
      lose(w, no);
    workers_ = std::max(0, workers_ - 1);
    ++report_.dead_ranks;
    if (checkpoint_) checkpoint_->write_pending();
  }

  bool done() const { return input_ended_ && open_.empty(); }

  /// Writes the answers ready for output (always when idle or forced, else when the buffer is
  /// large or 20 ms old).
  void flush(bool idle) {
    const auto now = Clock::now();
    if (!out_.empty() && (idle || out_.size() >= (1u << 16) || now - last_flush_ > kDelay)) {
      if (out_ok_) out_ok_ = write_all(out_fd_, out_.data(), out_.size());
      out_.clear();
      last_flush_ = now;
    }
    if (checkpoint_ && idle) checkpoint_->write_pending();
  }

  void finish() {
    flush(true);
    if (checkpoint_) checkpoint_->write_pending(true);
  }

  const BatchStats& stats() const { return stats_; }
  const MpiBatchReport& report() const { return report_; }
  /// Rank 0 is about to answer the remaining lines itself, no worker being left.
  void note_local_fallback() { report_.local_fallback = true; }

private:
  static constexpr size_t kAhead = 4096;
  static constexpr auto kDelay = std::chrono::milliseconds(20);

  struct Open {
    std::string text;
    std::uint64_t hash = 0;
    int pass = 1, losses = 0, avoid = -1;
    int holder = -1; ///< the worker (rank) the line was sent to, until answered, lost or given back
  };

  // Line no, held by w, was lost (its compute child or its rank died): sent again once to
  // another worker, then answered with an "internal" error line.
  void lose(int w, long no) {
    auto it = open_.find(no);
    if (it == open_.end()) return;
    Open& l = it->second;
    l.holder = -1;
    if (++l.losses < 2) {
      l.avoid = w;
      lost_.push_back(no);
      ++report_.retried;
      return;
    }
    // Lost twice: the line itself is the likely cause (out of memory, a crash).
    CheckpointRecord r{l.hash,
                       l.pass,
                       "error",
                       "internal",
                       false,
                       core::io::dump(internal_error_line(
                           id_of(l.text), "the compute process answering this line died "
                                          "twice (killed, or out of memory)"))};
    if (checkpoint_) checkpoint_->append(no, r);
    finalize(no, r);
    open_.erase(it);
    ++report_.lost_twice;
  }

  WorkLine line_for(long no, const Open& l) const {
    return {no, l.pass == 2 ? with_budget(l.text, o_.retry_budget_ms) : l.text};
  }

  void add_line(long no, std::string text) {
    const std::uint64_t h = line_hash(text);
    if (checkpoint_) {
      const auto& recs = checkpoint_->records();
      auto it = recs.find(no);
      if (it != recs.end()) {
        const CheckpointRecord& r = it->second;
        if (r.hash != h)
          throw core::InputError(core::Location{o_.checkpoint, 0, 0, ""},
                                 "a checkpoint of this input",
                                 "another line " + std::to_string(no) + " (its hash differs)");
        ++report_.resumed;
        if (r.pass == 1 && o_.retry_budget_ms > 0 && budget_undecided(r.status, r.text)) {
          open_[no] = Open{std::move(text), h, 2, 0, -1, -1};
          second_.push_back(no);
          ++report_.second_pass;
        } else {
          finalize(no, r);
        }
        return;
      }
    }
    open_[no] = Open{std::move(text), h, 1, 0, -1, -1};
    fresh_.push_back(no);
  }

  void finalize(long no, const CheckpointRecord& r) {
    ++stats_.lines;
    if (r.status == "error") ++stats_.errors;
    if (r.status == "error" && r.kind == "internal") ++stats_.internal;
    if (r.status == "undecided") ++stats_.undecided;
    if (r.status == "certified") ++stats_.certified;
    stats_.fallbacks += r.fallback ? 1 : 0;
    if (!o_.ordered) {
      out_ += r.text;
      out_ += '\n';
      return;
    }
    if (no != next_out_) {
      ready_[no] = r.text;
      return;
    }
    out_ += r.text;
    out_ += '\n';
    ++next_out_;
    for (auto it = ready_.begin(); it != ready_.end() && it->first == next_out_;
         it = ready_.erase(it), ++next_out_) {
      out_ += it->second;
      out_ += '\n';
    }
  }

  const MpiBatchOptions& o_;
  int out_fd_;
  int workers_;
  InputThread input_;
  std::optional<Checkpoint> checkpoint_;
  std::unordered_map<long, Open> open_;
  std::deque<long> fresh_, second_;
  std::list<long> lost_;
  std::map<long, std::string> ready_;
  long next_out_ = 1, read_ = 0;
  bool input_ended_ = false, out_ok_ = true;
  std::string out_;
  Clock::time_point last_flush_ = Clock::now();
  BatchStats stats_;
  MpiBatchReport report_;
};

// Sends in flight: their buffers live until MPI is done with them.
class Sends {
public:
  /// False when MPI refused the send (with recovery's MPI_ERRORS_RETURN: the peer is gone).
  bool send(std::string buf, int dest, int tag) {
    auto& s = pending_.emplace_back();
    s.buf = std::move(buf);
    s.dest = dest;
    if (MPI_Isend(s.buf.data(), static_cast<int>(s.buf.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD,
                  &s.req) != MPI_SUCCESS) {
      pending_.pop_back();
      failed_.push_back(dest);
      return false;
    }
    return true;
  }
  void reap() {
    for (auto it = pending_.begin(); it != pending_.end();) {
      int done = 0;
      if (MPI_Test(&it->req, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS) {
        failed_.push_back(it->dest);
        done = 1;
      }
      it = done ? pending_.erase(it) : std::next(it);
    }
  }
  void wait_all() {
    for (auto& s : pending_)
      MPI_Wait(&s.req, MPI_STATUS_IGNORE);
    pending_.clear();
  }
  /// Waits until deadline for the sends to the ranks not dead; the others are abandoned: a
  /// send to a dead rank never completes, and MPI may still read its buffer, so the buffer is
  /// kept (reachable, never freed) until the process ends.
  void wait_live(const std::vector<char>& dead, Clock::time_point deadline) {
    for (;;) {
      reap();
      const bool live_left = std::any_of(pending_.begin(), pending_.end(), [&](const Pending& p) {
        return !dead[static_cast<size_t>(p.dest)];
      });
      if (!live_left || Clock::now() > deadline) break;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    static auto* abandoned = new std::list<Pending>;
    abandoned->splice(abandoned->end(), pending_);
  }
  /// The ranks a send to which failed since the last call.
  std::vector<int> take_failed() { return std::exchange(failed_, {}); }

private:
  struct Pending {
    std::string buf;
    int dest = 0;
    MPI_Request req;
  };
  std::list<Pending> pending_;
  std::vector<int> failed_;
};

// With Open MPI's recovery: whether the job runs with it (mpirun --enable-recovery, or the
// MCA parameter set another way, which Open MPI passes to the ranks in their environment).
bool recovery_enabled() {
  const char* e = std::getenv("OMPI_MCA_orte_enable_recovery");
  if (!e) return false;
  std::string v(e);
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return std::tolower(c); });
  return v == "1" || v == "true" || v == "yes" || v == "on" || v == "enabled";
}

// The heartbeat's timing: a rank silent for `timeout` is dead; each rank speaks at least every
// `interval` (min(1 s, timeout / 5)), so a live rank misses the timeout only when it is stalled
// for 4 intervals and more.
struct Heartbeat {
  Clock::duration interval, timeout;
  explicit Heartbeat(double timeout_s)
      : interval(std::chrono::duration_cast<Clock::duration>(
            std::chrono::duration<double>(std::min(1.0, timeout_s / 5)))),
        timeout(
            std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s))) {
  }
  /// Called once per loop round: a round that came more than timeout / 2 after the last one
  /// means this rank itself was stalled (blocked writing its output, say), when it could not
  /// hear anyone: the silence is then not the others'.
  bool self_stalled(Clock::time_point now) {
    const bool stalled = now - last_round_ > timeout / 2;
    last_round_ = now;
    return stalled;
  }

private:
  Clock::time_point last_round_ = Clock::now();
};

std::string recv_bytes(const MPI_Status& probed) {
  int n = 0;
  MPI_Get_count(&probed, MPI_BYTE, &n);
  std::string buf(static_cast<size_t>(n), '\0');
  MPI_Recv(buf.data(), n, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return buf;
}

// Sleeps a little longer each idle round (20 us to 1 ms): MPI can only be polled.
class Backoff {
public:
  std::chrono::microseconds next() {
    const auto d = d_;
    d_ = std::min(d_ * 2, std::chrono::microseconds(1000));
    return d;
  }
  void reset() { d_ = std::chrono::microseconds(20); }

private:
  std::chrono::microseconds d_{20};
};

// One rank: rank 0 drives its own compute child.
void run_single(BatchMaster& master, const MpiBatchOptions& o) {
  LineWorker lw(o.child_command, o.threads);
  std::vector<WorkAnswer> answers;
  std::vector<long> lost, returned;
  for (;;) {
    master.pump_input();
    answers.clear();
    lost.clear();
    returned.clear();
    bool progressed = lw.poll(answers, lost, returned);
    if (progressed) master.on_answers(0, answers, lost, returned);
    if (const int want = lw.want(); want > 0) {
      std::vector<WorkLine> lines = master.take_lines(0, want);
      progressed = progressed || !lines.empty();
      lw.give(std::move(lines));
    }
    master.flush(!progressed);
    if (master.done()) break;
    if (!progressed) lw.wait_for(std::chrono::microseconds(500));
  }
  master.finish();
}

// Rank 0 with workers. With recovery (batch_mpi.hpp): heartbeats, dead workers' lines to the
// others, rank 0 alone once none is left, and the end's stop/goodbye handshake.
void run_root(BatchMaster& master, int size, const MpiBatchOptions& o, bool recovery) {
  const auto n = static_cast<size_t>(size);
  std::vector<int> want(n, 0); // open requests
  std::vector<char> dead(n, 0);
  std::vector<Clock::time_point> heard(n, Clock::now()), told(n, Clock::now());
  int alive = size - 1;
  Heartbeat hb(o.rank_timeout_s);
  Sends sends;
  Backoff backoff;
  const auto declare_dead = [&](int w, const char* why) {
    const auto i = static_cast<size_t>(w);
    if (dead[i]) return;
    dead[i] = 1;
    want[i] = 0;
    --alive;
    // One write(2): Open MPI's messages share this stderr (see cmd_batch_mpi's summary).
    const std::string msg = "surfcert batch --mpi: rank " + std::to_string(w) + " " + why +
                            ": its lines go to the others (" + std::to_string(alive) +
                            " workers left)\n";
    write_all(STDERR_FILENO, msg.data(), msg.size());
    master.on_rank_dead(w);
  };
  // One round of heartbeats (recovery only): the silent are dead, the others hear from rank 0.
  const auto beat = [&](bool ending) {
    auto now = Clock::now();
    if (hb.self_stalled(now)) std::fill(heard.begin(), heard.end(), now);
    for (int w = 1; w < size; ++w) {
      const auto i = static_cast<size_t>(w);
      if (dead[i]) continue;
      if (now - heard[i] > hb.timeout) {
        declare_dead(w, "is silent past --rank-timeout");
      } else if (!ending && now - told[i] >= hb.interval) {
        sends.send(std::string(), w, kBeat);
        told[i] = now;
      }
    }
    sends.reap();
    for (int w : sends.take_failed())
      declare_dead(w, "cannot be reached (a send to it failed)");
  };
  for (;;) {
    master.pump_input();
    bool progressed = false;
    int flag = 0;
    MPI_Status st;
    while (MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st), flag) {
      const std::string buf = recv_bytes(st);
      const int w = st.MPI_SOURCE;
      // A rank found dead that was not (stalled past the timeout): its lines went to others,
      // what it says now is dropped, and without heartbeats from rank 0 it leaves.
      if (dead[static_cast<size_t>(w)]) continue;
      heard[static_cast<size_t>(w)] = Clock::now();
      if (st.MPI_TAG != kReport) continue; // a heartbeat
      Unpacker u{buf};
      const auto asked = static_cast<int>(u.i64());
      std::vector<WorkAnswer> answers(static_cast<size_t>(u.i64()));
      for (WorkAnswer& a : answers) {
        a.no = u.i64();
        a.status = u.str();
        a.kind = u.str();
        a.fallback = u.i64() != 0;
        a.text = u.str();
      }
      std::vector<long> lost(static_cast<size_t>(u.i64()));
      for (long& l : lost)
        l = u.i64();
      std::vector<long> returned(static_cast<size_t>(u.i64()));
      for (long& l : returned)
        l = u.i64();
      if (asked > 0) want[static_cast<size_t>(w)] = asked;
      master.on_answers(w, answers, lost, returned);
      progressed = true;
    }
    for (int w = 1; w < size; ++w) {
      if (want[static_cast<size_t>(w)] == 0) continue;
      std::vector<WorkLine> lines = master.take_lines(w, want[static_cast<size_t>(w)]);
      if (lines.empty()) continue;
      std::string buf;
      put_i64(buf, static_cast<std::int64_t>(lines.size()));
      for (const WorkLine& l : lines) {
        put_i64(buf, l.no);
        put_str(buf, l.text);
      }
      sends.send(std::move(buf), w, kWork);
      told[static_cast<size_t>(w)] = Clock::now();
      want[static_cast<size_t>(w)] = 0;
      progressed = true;
    }
    sends.reap();
    if (recovery) {
      beat(false);
      if (alive == 0) break;
    }
    master.flush(!progressed);
    if (master.done()) break;
    if (progressed) {
      backoff.reset();
    } else {
      std::this_thread::sleep_for(backoff.next());
    }
  }
  if (!recovery) {
    for (int w = 1; w < size; ++w)
      sends.send(std::string(), w, kStop);
    sends.wait_all();
    master.finish();
    return;
  }
  if (!master.done()) {
    // Every worker is dead: rank 0 answers the remaining lines through a compute child of
    // its own (as with one rank).
    std::cerr << "surfcert batch --mpi: no worker left: rank 0 answers the remaining lines\n";
    master.note_local_fallback(); // the summary's local_fallback=1
    run_single(master, o);
  } else {
    master.finish(); // every answer written before the handshake
  }
  // The handshake: stop to every live worker, until each said goodbye or fell silent.
  std::vector<char> bye(n, 0);
  for (int w = 1; w < size; ++w)
    if (!dead[static_cast<size_t>(w)]) sends.send(std::string(), w, kStop);
  for (;;) {
    int flag = 0;
    MPI_Status st;
    while (MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st), flag) {
      recv_bytes(st);
      const auto i = static_cast<size_t>(st.MPI_SOURCE);
      if (dead[i]) continue;
      heard[i] = Clock::now();
      if (st.MPI_TAG == kBye) bye[i] = 1;
    }
    beat(true);
    bool waiting = false;
    for (int w = 1; w < size; ++w)
      waiting = waiting || (!dead[static_cast<size_t>(w)] && !bye[static_cast<size_t>(w)]);
    if (!waiting) break;
    std::this_thread::sleep_for(backoff.next());
  }
  sends.wait_live(dead, Clock::now() + hb.timeout);
}

// A worker: a relay between rank 0 and its compute child (it computes nothing itself, which is
// why its silence means death). With recovery it sends heartbeats, leaves when rank 0 falls
// silent, and ends with the handshake.
void run_worker(const MpiBatchOptions& o, bool recovery) {
  LineWorker lw(o.child_command, o.threads);
  Sends sends;
  Backoff backoff;
  Heartbeat hb(o.rank_timeout_s);
  bool requested = false;
  std::vector<WorkAnswer> outbox;
  std::vector<long> lost, returned;
  Clock::time_point oldest, heard_root = Clock::now(), last_sent = Clock::now();
  for (;;) {
    const size_t had = outbox.size();
    bool progressed = lw.poll(outbox, lost, returned);
    if (had == 0 && outbox.size() > 0) oldest = Clock::now();
    const int want = requested ? 0 : lw.want();
    // Answers go back in groups (at most 2 ms late) unless a request or a loss goes anyway.
    if (want > 0 || !lost.empty() || !returned.empty() || outbox.size() >= kMaxGroup ||
        (!outbox.empty() &&
         (lw.held() == 0 || Clock::now() - oldest >= std::chrono::milliseconds(2)))) {
      std::string buf;
      put_i64(buf, want);
      put_i64(buf, static_cast<std::int64_t>(outbox.size()));
      for (const WorkAnswer& a : outbox) {
        put_i64(buf, a.no);
        put_str(buf, a.status);
        put_str(buf, a.kind);
        put_i64(buf, a.fallback ? 1 : 0);
        put_str(buf, a.text);
      }
      put_i64(buf, static_cast<std::int64_t>(lost.size()));
      for (long l : lost)
        put_i64(buf, l);
      put_i64(buf, static_cast<std::int64_t>(returned.size()));
      for (long l : returned)
        put_i64(buf, l);
      sends.send(std::move(buf), 0, kReport);
      last_sent = Clock::now();
      outbox.clear();
      lost.clear();
      returned.clear();
      if (want > 0) requested = true;
      progressed = true;
    }
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (flag) {
      const std::string buf = recv_bytes(st);
      heard_root = Clock::now();
      if (st.MPI_TAG == kStop) break;
      if (st.MPI_TAG == kWork) {
        Unpacker u{buf};
        std::vector<WorkLine> lines(static_cast<size_t>(u.i64()));
        for (WorkLine& l : lines) {
          l.no = u.i64();
          l.text = u.str();
        }
        lw.give(std::move(lines));
        requested = false;
        progressed = true;
      }
    }
    sends.reap();
    if (recovery) {
      const auto now = Clock::now();
      if (hb.self_stalled(now)) heard_root = now;
      if (now - heard_root > hb.timeout) {
        int rank = 0;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        std::cerr << "surfcert batch --mpi: rank " << rank
                  << ": rank 0 is silent past --rank-timeout: leaving\n";
        sends.wait_live(std::vector<char>(1, 1), now); // rank 0 counts as dead: abandon
        return;
      }
      if (now - last_sent >= hb.interval) {
        sends.send(std::string(), 0, kBeat);
        last_sent = now;
      }
    }
    if (progressed) {
      backoff.reset();
    } else {
      lw.wait_for(backoff.next());
    }
  }
  if (!recovery) {
    sends.wait_all();
    return;
  }
  sends.send(std::string(), 0, kBye);
  sends.wait_live(std::vector<char>(1, 0), Clock::now() + hb.timeout);
}

} // namespace

} // namespace mpi_batch

const char* mpi_executable() {
  return nullptr; // this executable (surfcert-mpi) runs batch --mpi itself
}

bool mpi_available() {
  return true;
}

BatchStats run_batch_mpi(int out_fd, const MpiBatchOptions& options, bool* is_root,
                         MpiBatchReport* report) {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  *is_root = rank == 0;
  // With recovery a failed send to a dead rank must return an error, not end this process;
  // and no rank calls MPI_Finalize (it would wait for the dead ranks forever).
  const bool recovery = size > 1 && mpi_batch::recovery_enabled();
  if (recovery) MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  BatchStats st;
  if (rank != 0) {
    try {
      mpi_batch::run_worker(options, recovery);
    } catch (const std::exception& e) {
      std::cerr << "surfcert: internal error: rank " << rank << ": " << e.what() << "\n";
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    if (!recovery) MPI_Finalize();
    return st;
  }
  try {
    mpi_batch::BatchMaster master(0, out_fd, options, std::max(1, size - 1));
    if (size == 1) {
      mpi_batch::run_single(master, options);
    } else {
      mpi_batch::run_root(master, size, options, recovery);
    }
    st = master.stats();
    if (report) {
      *report = master.report();
      report->recovery = recovery;
    }
  } catch (const core::InputError& e) {
    if (size == 1) {
      MPI_Finalize();
      throw;
    }
    std::cerr << "surfcert: error: " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 2);
  } catch (const std::exception& e) {
    if (size == 1) {
      MPI_Finalize();
      throw;
    }
    std::cerr << "surfcert: internal error: " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  if (!recovery) MPI_Finalize();
  return st;
}

} // namespace surfcert::app
