// Batch streaming (app/batch_stream.hpp): a batch killed by SIGTERM has written every answer it
// completed (through `timeout` on the real executable, and with answers held back by a long
// write delay so that only the signal path can write them); a caller that sends a line and
// waits gets its answer while the input stays open; --threads 1 (the stages in turn, without
// TBB) answers like the TBB pipeline, long lines included, and does not start TBB.
#include "surfcert/app/batch_stream.hpp"
#include "surfcert/core/io/json.hpp"

#include <gtest/gtest.h>

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using surfcert::app::BatchLineAnswer;
using surfcert::app::BatchStreamOptions;
using surfcert::core::io::Json;

namespace {

std::string tmp_path(const std::string& name) {
  return (::testing::TempDir().empty() ? std::string("/tmp/") : ::testing::TempDir()) +
         "surfcert_batch_stream_" + std::to_string(getpid()) + "_" + name;
}

std::string slurp(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The ids of the answer lines; every line must be a whole JSON object.
std::vector<std::string> ids_of(const std::string& out) {
  std::vector<std::string> ids;
  std::istringstream lines(out);
  std::string l;
  while (std::getline(lines, l)) {
    const Json o = surfcert::core::io::parse_json(l, "out");
    ids.push_back(surfcert::core::io::dump(*o.find("id")));
  }
  return ids;
}

// A fast line (two spheres) with id i.
std::string fast_line(int i) {
  return "{\"id\":" + std::to_string(i) +
         R"(,"op":"classify","a":{"type":"sphere","center":[0,0,0],"radius":1},)"
         R"("b":{"type":"sphere","center":[0.5,0.25,0],"radius":0.75},"detail":"topology"})";
}

// Two tori 1e-20 apart: the distance's branch and bound runs for seconds (3.7 s on the
// development machine) before it gives up undecided.
const char* kSlowLine =
    R"({"id":"slow","op":"distance","a":{"type":"torus","center":[0,0,0],"axis":[0,0,1],)"
    R"("major_radius":3,"minor_radius":1},"b":{"type":"torus","center":)"
    R"(["799999999999999999999/100000000000000000000",0,0],"axis":[0,0,1],"major_radius":3,)"
    R"("minor_radius":1},"budget_ms":600000})";

} // namespace

// Answers held in the buffer (a write delay of an hour, more input behind the blocked line so
// that the reader never waits): only the SIGTERM path can write them, and it must write all.
TEST(BatchStream, SigtermWritesEveryCompletedAnswer) {
  int in[2], out[2], started[2];
  ASSERT_EQ(pipe(in), 0);
  ASSERT_EQ(pipe(out), 0);
  ASSERT_EQ(pipe(started), 0);
  const int kFast = 40;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(in[1]);
    close(out[0]);
    close(started[0]);
    BatchStreamOptions opt;
    opt.threads = 1;
    opt.max_delay = std::chrono::hours(1);
    opt.flush_on_signal = true;
    surfcert::app::process_batch_fd(
        in[0], out[1], surfcert::certify::Mode::Filtered,
        [&](const std::string& line, long no, surfcert::certify::Mode) {
          if (line == "block") {
            (void)!write(started[1], "s", 1);
            for (;;)
              pause();
          }
          return BatchLineAnswer{"{\"id\":" + std::to_string(no) + "}", "certified", "", false};
        },
        opt);
    _exit(0);
  }
  close(in[0]);
  close(out[1]);
  close(started[1]);
  std::string text;
  for (int i = 1; i <= kFast; ++i)
    text += "x\n";
  text += "block\n";
  // More input behind the blocked line, so that the reader is not waiting for input (which
  // would write the answers at once); the pipe is left open.
  for (int i = 0; i < 100; ++i)
    text += "x\n";
  ASSERT_EQ(write(in[1], text.data(), text.size()), static_cast<ssize_t>(text.size()));
  char c;
  ASSERT_EQ(read(started[0], &c, 1), 1); // every line before "block" is answered by now
  ASSERT_EQ(kill(child, SIGTERM), 0);
  std::string got;
  char buf[4096];
  ssize_t n;
  while ((n = read(out[0], buf, sizeof buf)) > 0)
    got.append(buf, static_cast<size_t>(n));
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  close(in[1]);
  const auto ids = ids_of(got);
  ASSERT_EQ(ids.size(), static_cast<size_t>(kFast)) << got;
  for (int i = 0; i < kFast; ++i)
    EXPECT_EQ(ids[static_cast<size_t>(i)], std::to_string(i + 1));
}

// The executable under `timeout`: many fast lines, a slow one, more fast lines. In input order
// the answers are exactly the lines before the slow one; unordered (two threads) they are all
// the fast lines. Either way no line is cut.
TEST(BatchStream, TimeoutKilledBatchWroteEveryCompletedLine) {
  const int kBefore = 1500, kAfter = 300;
  std::string text;
  for (int i = 0; i < kBefore; ++i)
    text += fast_line(i) + "\n";
  text += std::string(kSlowLine) + "\n";
  for (int i = kBefore; i < kBefore + kAfter; ++i)
    text += fast_line(i) + "\n";
  const std::string in = tmp_path("in"), out = tmp_path("out"), slow = tmp_path("slow");
  std::ofstream(in) << text;
  // The kill must come while the slow line runs, whatever this machine's speed (it takes
  // ~3.7 s on one, far longer under ASan): time it alone and kill at half that, at most 4 s.
  // The time only chooses when to kill; what is asserted is what was written by then.
  std::ofstream(slow) << kSlowLine << "\n";
  const auto t0 = std::chrono::steady_clock::now();
  const int alone = std::system((std::string("timeout -s TERM 8 ") + SURFCERT_BINARY +
                                 " batch --threads 1 <" + slow + " >/dev/null 2>&1")
                                    .c_str());
  const double t_slow =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(WIFEXITED(alone)) << alone;
  char kill_after[32];
  std::snprintf(kill_after, sizeof kill_after, "%.2f", std::clamp(t_slow / 2, 0.5, 4.0));
  for (const bool ordered : {true, false}) {
    const std::string cmd = std::string("timeout -s TERM ") + kill_after + " " + SURFCERT_BINARY +
                            " batch " + (ordered ? "--threads 1" : "--threads 2 --unordered") +
                            " <" + in + " >" + out + " 2>/dev/null";
    const int st = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 124) << st; // killed by timeout
    const auto ids = ids_of(slurp(out));
    if (ordered) {
      ASSERT_EQ(ids.size(), static_cast<size_t>(kBefore));
      for (int i = 0; i < kBefore; ++i)
        EXPECT_EQ(ids[static_cast<size_t>(i)], std::to_string(i));
    } else {
      std::set<std::string> want, got(ids.begin(), ids.end());
      for (int i = 0; i < kBefore + kAfter; ++i)
        want.insert(std::to_string(i));
      EXPECT_EQ(got, want);
      EXPECT_EQ(ids.size(), want.size());
    }
  }
  std::remove(in.c_str());
  std::remove(out.c_str());
  std::remove(slow.c_str());
}

// Request and response through pipes with the input left open: each answer arrives without
// more input or the end of input (a caller may wait for it before sending the next line).
TEST(BatchStream, AnswersArriveWhileTheInputStaysOpen) {
  for (int threads : {1, 2}) {
    int in[2], out[2];
    ASSERT_EQ(pipe(in), 0);
    ASSERT_EQ(pipe(out), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(in[1]);
      close(out[0]);
      BatchStreamOptions opt;
      opt.threads = threads;
      opt.max_delay = std::chrono::hours(1); // only the waiting reader can release answers
      surfcert::app::process_batch_fd(
          in[0], out[1], surfcert::certify::Mode::Filtered,
          [](const std::string& line, long, surfcert::certify::Mode) {
            return BatchLineAnswer{"{\"id\":" + line + "}", "certified", "", false};
          },
          opt);
      _exit(0);
    }
    close(in[0]);
    close(out[1]);
    for (int i = 0; i < 20; ++i) {
      const std::string l = std::to_string(i) + "\n";
      ASSERT_EQ(write(in[1], l.data(), l.size()), static_cast<ssize_t>(l.size()));
      std::string got;
      while (got.find('\n') == std::string::npos) {
        pollfd p{out[0], POLLIN, 0};
        ASSERT_GT(poll(&p, 1, 60000), 0) << "no answer to line " << i; // a hang, not a timing
        char buf[256];
        const ssize_t n = read(out[0], buf, sizeof buf);
        ASSERT_GT(n, 0);
        got.append(buf, static_cast<size_t>(n));
      }
      EXPECT_EQ(got, "{\"id\":" + std::to_string(i) + "}\n");
    }
    close(in[1]);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    close(out[0]);
  }
}

namespace {

// The command's output with every "time_ms" removed (the one field that differs between runs).
std::string untimed(const std::string& out) {
  static const std::regex time_field(R"(,"time_ms":[0-9.eE+-]+)");
  return std::regex_replace(out, time_field, "");
}

std::string run_batch(const std::string& args, const std::string& in) {
  const std::string out = tmp_path("run_out");
  const std::string cmd =
      std::string(SURFCERT_BINARY) + " batch " + args + " <" + in + " >" + out + " 2>/dev/null";
  const int st = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << cmd;
  std::string text = slurp(out);
  std::remove(out.c_str());
  return text;
}

} // namespace

// --threads 1 runs the pipeline's stages in turn without TBB (batch_stream.cpp); --threads 2
// through TBB's pipeline: the same answers in the same order, over several chunks (64 lines
// each), a line of 200 KB (the reader's buffer, 64 KB, grows: the line's answer is the one
// of the same line without its padding) and a last line without '\n'.
TEST(BatchStream, OneThreadAnswersLikeTheTbbPipeline) {
  std::string text;
  const int kLines = 300;
  for (int i = 0; i < kLines; ++i) {
    std::string l = fast_line(i);
    if (i == 150) l.insert(1, std::string(200000, ' ')); // JSON whitespace
    text += l + (i + 1 < kLines ? "\n" : "");
  }
  const std::string in = tmp_path("same_in");
  std::ofstream(in) << text;
  const std::string one = untimed(run_batch("--threads 1", in));
  const std::string two = untimed(run_batch("--threads 2", in));
  const std::string one_unordered = untimed(run_batch("--threads 1 --unordered", in));
  std::remove(in.c_str());
  EXPECT_EQ(one, two);
  EXPECT_EQ(one_unordered, one); // one thread: completion order is input order
  const auto ids = ids_of(one);
  ASSERT_EQ(ids.size(), static_cast<size_t>(kLines));
  for (int i = 0; i < kLines; ++i)
    EXPECT_EQ(ids[static_cast<size_t>(i)], std::to_string(i));
  std::vector<std::string> lines;
  std::istringstream ls(one);
  for (std::string l; std::getline(ls, l);)
    lines.push_back(l);
  const std::string padded = lines[150], plain = lines[149];
  EXPECT_EQ(padded.substr(padded.find(',')), plain.substr(plain.find(','))); // bar the id
}

// --threads 1 does not start TBB's scheduler: its allocator (libtbbmalloc, loaded by libtbb when
// the scheduler starts) stays unloaded; --threads 2 loads it (the check sees it).
TEST(BatchStream, OneThreadDoesNotStartTbb) {
  const std::string in = tmp_path("tbb_in"), err = tmp_path("tbb_err");
  std::ofstream(in) << fast_line(1) << "\n" << fast_line(2) << "\n";
  for (int threads : {1, 2}) {
    const std::string cmd = "LD_DEBUG=files " + std::string(SURFCERT_BINARY) + " batch --threads " +
                            std::to_string(threads) + " <" + in + " >/dev/null 2>" + err;
    const int st = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << cmd;
    const std::string loaded = slurp(err);
    ASSERT_NE(loaded.find("libtbb.so"), std::string::npos) << loaded; // LD_DEBUG reported
    if (threads == 1)
      EXPECT_EQ(loaded.find("libtbbmalloc"), std::string::npos) << loaded;
    else
      EXPECT_NE(loaded.find("libtbbmalloc"), std::string::npos) << loaded;
  }
  std::remove(in.c_str());
  std::remove(err.c_str());
}

// A completed answer is written by its deadline (max_delay) while a later line of the same
// chunk still runs and the reader is not waiting for input (the flusher's timed path, not the
// idle-input path). Line 1 alone first (written as the reader waits for input), then, once the
// flusher has had time to wait for an answer again, lines 2 and 3 in one chunk: line 2 answers
// at once, line 3 blocks until the test has seen answer 2.
TEST(BatchStream, AnswerIsWrittenByItsDeadlineWhileALaterLineRuns) {
  for (int threads : {1, 2}) {
    int in[2], out[2], go[2];
    ASSERT_EQ(pipe(in), 0);
    ASSERT_EQ(pipe(out), 0);
    ASSERT_EQ(pipe(go), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(in[1]);
      close(out[0]);
      close(go[1]);
      BatchStreamOptions opt;
      opt.threads = threads;
      opt.max_delay = std::chrono::milliseconds(20);
      surfcert::app::process_batch_fd(
          in[0], out[1], surfcert::certify::Mode::Filtered,
          [&](const std::string& line, long no, surfcert::certify::Mode) {
            if (line == "wait") {
              char c;
              (void)!read(go[0], &c, 1);
            }
            return BatchLineAnswer{"{\"id\":" + std::to_string(no) + "}", "certified", "", false};
          },
          opt);
      _exit(0);
    }
    close(in[0]);
    close(out[1]);
    close(go[0]);
    std::string got;
    auto read_line = [&] {
      const size_t lines = static_cast<size_t>(std::count(got.begin(), got.end(), '\n'));
      while (static_cast<size_t>(std::count(got.begin(), got.end(), '\n')) == lines) {
        pollfd p{out[0], POLLIN, 0};
        if (poll(&p, 1, 60000) <= 0) return false; // a hang, not a timing
        char buf[256];
        const ssize_t n = read(out[0], buf, sizeof buf);
        if (n <= 0) return false;
        got.append(buf, static_cast<size_t>(n));
      }
      return true;
    };
    ASSERT_EQ(write(in[1], "x\n", 2), 2);
    ASSERT_TRUE(read_line());
    usleep(100000); // the flusher waits for an answer again (else this test checks less)
    // Both lines in one write: one chunk. The input stays open, so the reader does not see the
    // end of input (which would write the answers) before the test has looked.
    ASSERT_EQ(write(in[1], "y\nwait\n", 7), 7);
    ASSERT_TRUE(read_line()) << "answer 2 not written while line 3 runs";
    EXPECT_EQ(got, "{\"id\":1}\n{\"id\":2}\n") << threads;
    ASSERT_EQ(write(go[1], "g", 1), 1);
    close(in[1]);
    char buf[256];
    ssize_t n;
    while ((n = read(out[0], buf, sizeof buf)) > 0)
      got.append(buf, static_cast<size_t>(n));
    EXPECT_EQ(got, "{\"id\":1}\n{\"id\":2}\n{\"id\":3}\n") << threads;
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    close(out[0]);
    close(go[1]);
  }
}

// Output of many full buffers (2,000 answers of 2 KB: 4 MB, the buffer is 256 KB) through a
// pipe read slowly, so that the flusher is still writing one buffer while the next fills and
// the writes that callers wait for (the input turning idle, the end) come after it: every
// answer arrives whole, once, in input order, for one and two threads.
TEST(BatchStream, ManyFullBuffersThroughASlowPipeKeepTheirOrder) {
  const int kLines = 2000;
  std::string expected;
  for (int i = 1; i <= kLines; ++i)
    expected +=
        "{\"id\":" + std::to_string(i) + ",\"pad\":\"" + std::string(2000, 'a' + i % 26) + "\"}\n";
  for (int threads : {1, 2}) {
    int in[2], out[2];
    ASSERT_EQ(pipe(in), 0);
    ASSERT_EQ(pipe(out), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(in[1]);
      close(out[0]);
      BatchStreamOptions opt;
      opt.threads = threads;
      surfcert::app::process_batch_fd(
          in[0], out[1], surfcert::certify::Mode::Filtered,
          [](const std::string&, long no, surfcert::certify::Mode) {
            return BatchLineAnswer{"{\"id\":" + std::to_string(no) + ",\"pad\":\"" +
                                       std::string(2000, 'a' + no % 26) + "\"}",
                                   "certified", "", false};
          },
          opt);
      _exit(0);
    }
    close(in[0]);
    close(out[1]);
    // The input in a few bursts (the reader turns idle between them: writes callers wait for).
    const pid_t feeder = fork();
    ASSERT_GE(feeder, 0);
    if (feeder == 0) {
      close(out[0]);
      for (int burst = 0; burst < 4; ++burst) {
        std::string text;
        for (int i = 0; i < kLines / 4; ++i)
          text += "x\n";
        if (write(in[1], text.data(), text.size()) != static_cast<ssize_t>(text.size())) _exit(1);
        usleep(20000);
      }
      _exit(0);
    }
    close(in[1]);
    std::string got;
    char buf[8192];
    ssize_t n;
    int reads = 0;
    while ((n = read(out[0], buf, sizeof buf)) > 0) {
      got.append(buf, static_cast<size_t>(n));
      if (++reads % 16 == 0) usleep(1000); // a slow reader: the pipe fills, write(2) blocks
    }
    int status = 0;
    ASSERT_EQ(waitpid(feeder, &status, 0), feeder);
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    close(out[0]);
    EXPECT_EQ(got.size(), expected.size()) << threads;
    EXPECT_TRUE(got == expected) << threads; // not printed: 4 MB
  }
}

// Every line reaches the answer function exactly as it was in the input, with its number and
// the parser's padding behind it, whatever the boundaries: the reader's reads (a feeder writes
// odd-sized pieces through a pipe, pausing between some, so lines straddle reads and chunks end
// where the next line has not arrived), the chunks' blocks of text (32 KB: thousands of lines
// of 0-3000 bytes), a 200 KB line (longer than a chunk and than the reader's first buffer),
// empty lines, a '\r' before the '\n' (kept: the line's own byte), and a last line without '\n'.
// The answer echoes the line; the expected output is built from the input independently.
TEST(BatchStream, LinesReachTheAnswerIntactAcrossReadAndChunkBoundaries) {
  std::vector<std::string> lines;
  unsigned x = 12345;
  for (int i = 0; i < 6000; ++i) {
    x = x * 1103515245u + 12345u;
    const size_t len = (x >> 8) % 3001;
    std::string l;
    for (size_t k = 0; k < len; ++k)
      l += static_cast<char>('a' + (k * 7 + static_cast<size_t>(i)) % 26);
    if (i % 97 == 0) l.clear();
    if (i % 89 == 0) l += '\r';
    if (i == 3000) l = std::string(200000, 'L') + "end";
    lines.push_back(l);
  }
  lines.push_back("last line, no newline");
  std::string text, expected;
  for (size_t i = 0; i < lines.size(); ++i) {
    text += lines[i] + (i + 1 < lines.size() ? "\n" : "");
    expected +=
        std::to_string(i + 1) + ":" + std::to_string(lines[i].size()) + ":" + lines[i] + "\n";
  }
  for (int threads : {1, 2}) {
    for (bool ordered : {true, false}) {
      if (threads == 1 && !ordered) continue;
      int in[2], out[2];
      ASSERT_EQ(pipe(in), 0);
      ASSERT_EQ(pipe(out), 0);
      const pid_t child = fork();
      ASSERT_GE(child, 0);
      if (child == 0) {
        close(in[1]);
        close(out[0]);
        BatchStreamOptions opt;
        opt.threads = threads;
        opt.ordered = ordered;
        surfcert::app::process_batch_fd(
            in[0], out[1], surfcert::certify::Mode::Filtered,
            [](const std::string& line, long no, surfcert::certify::Mode) {
              const bool padded = line.capacity() - line.size() >= 64;
              return BatchLineAnswer{std::to_string(no) + ":" + std::to_string(line.size()) + ":" +
                                         (padded ? line : std::string("unpadded")),
                                     "certified", "", false};
            },
            opt);
        _exit(0);
      }
      close(in[0]);
      close(out[1]);
      const pid_t feeder = fork();
      ASSERT_GE(feeder, 0);
      if (feeder == 0) {
        close(out[0]);
        size_t at = 0;
        for (int piece = 0; at < text.size(); ++piece) {
          const size_t n = std::min(text.size() - at, static_cast<size_t>(7001 + 13 * piece));
          if (write(in[1], text.data() + at, n) != static_cast<ssize_t>(n)) _exit(1);
          at += n;
          if (piece % 50 == 0) usleep(2000);
        }
        _exit(0);
      }
      close(in[1]);
      std::string got;
      char buf[65536];
      ssize_t n;
      while ((n = read(out[0], buf, sizeof buf)) > 0)
        got.append(buf, static_cast<size_t>(n));
      close(out[0]);
      int status = 0;
      ASSERT_EQ(waitpid(feeder, &status, 0), feeder);
      ASSERT_EQ(waitpid(child, &status, 0), child);
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
      if (!ordered) { // completion order: the same lines, each once
        std::vector<std::string> g, e;
        std::istringstream gs(got), es(expected);
        for (std::string l; std::getline(gs, l);)
          g.push_back(l);
        for (std::string l; std::getline(es, l);)
          e.push_back(l);
        std::sort(g.begin(), g.end());
        std::sort(e.begin(), e.end());
        EXPECT_TRUE(g == e) << threads;
      } else {
        EXPECT_EQ(got.size(), expected.size()) << threads;
        EXPECT_TRUE(got == expected) << threads; // not printed: 9 MB
      }
    }
  }
}
