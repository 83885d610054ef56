// surfcert::app batch streaming: JSON lines in, one answer line out per input line, through a
// TBB pipeline (serial read -> parallel answer -> serial write; with one thread the same
// stages in turn on the calling thread, without starting TBB), on streams or on raw file
// descriptors.
//
// What it represents: the machinery of `surfcert batch` around the answer of one line
// (process_batch_line, batch_line.hpp). Contract:
//   - every input line ('\n'-separated; a last line without '\n' counts) gets exactly one
//     answer line, in input order when ordered (else as completed); at most `threads` lines
//     are answered at once. Lines travel in chunks (up to 64 lines or 32 KB, cut short where
//     the next line has not arrived yet) and at most 4 * threads chunks are in flight; an
//     answer is handed to the output as soon as it and (ordered) every earlier answer are
//     complete, whether or not the rest of its chunk is;
//   - an exception escaping the answer function gives that line an "internal" error line;
//   - on file descriptors, answers are buffered and written (write(2)) when the input has no
//     more data immediately available (so a caller that sends a line and waits for its answer
//     gets it at once), when the oldest unwritten completed answer is `max_delay` old, when the
//     buffer is large, and at the end: a completed answer never waits longer than max_delay
//     for its write. A full buffer (256 KB) is written by the buffer's flusher thread while the
//     answering threads go on (they wait only if the next buffer fills before that write
//     ends); the writes keep the answers' order. With flush_on_signal, SIGTERM, SIGINT and
//     SIGHUP first write every completed answer, then end the process by that signal (a
//     `timeout`-killed batch has written every line it completed). The signals are taken by a
//     dedicated thread (sigwait), not an asynchronous handler, so the buffer is written under
//     its lock, never concurrently with the writing stage.
#pragma once

#include "surfcert/app/scene.hpp"

#include <chrono>
#include <functional>
#include <string>
#include <string_view>

namespace surfcert::app {

/// One answered line: the JSON answer (one line, no newline) and what the statistics need.
struct BatchLineAnswer {
  std::string text;
  std::string status;     ///< the answer's "status" ("certified", "undecided", "error", ...)
  std::string error_kind; ///< the "kind" of its "error" ("input", "internal"), else empty
  bool fallback = false;  ///< the filtered decision fell back to exact arithmetic
};

/// How a batch answers one line, as text (default: answer_batch_line, batch_line.hpp).
using BatchTextAnswer =
    std::function<BatchLineAnswer(const std::string& line, long line_no, certify::Mode mode)>;

struct BatchStreamOptions {
  int threads = 1;
  bool ordered = true; ///< false: each answer is written as soon as it is done
  /// Longest time a completed answer waits in the buffer (file descriptors only).
  std::chrono::milliseconds max_delay{20};
  /// Take SIGTERM, SIGINT and SIGHUP while the batch runs (see above; for the CLI).
  bool flush_on_signal = false;
  /// Called after each written line with the counts so far (one call at a time).
  std::function<void(const BatchStats&)> progress;
};

/// Reads JSON lines from file descriptor in_fd until end of input, writes the answers to
/// out_fd (see above).
BatchStats process_batch_fd(int in_fd, int out_fd, certify::Mode default_mode,
                            const BatchTextAnswer& answer, const BatchStreamOptions& options);

namespace detail {
/// What a line source gives: a line, the end of input, or (asked not to wait) "the next line
/// has not arrived yet".
enum class NextLine { Line, End, WouldBlock };

/// The pipeline shared by process_batch and process_batch_fd: next_line(line, may_wait) gives
/// the next line (with may_wait false it may answer WouldBlock instead of waiting for input) as
/// a view valid until the next call; the read stage copies it into its chunk's one block of
/// text (no allocation per line), and the answering thread copies it from there into a string
/// of its own (padded for the parser) on the core that answers it. write receives the answers
/// (in input order when ordered), one call at a time.
BatchStats
run_batch_pipeline(const std::function<NextLine(std::string_view& line, bool may_wait)>& next_line,
                   const std::function<void(const BatchLineAnswer&)>& write,
                   certify::Mode default_mode, const BatchTextAnswer& answer, int threads,
                   bool ordered, const std::function<void(const BatchStats&)>& progress);
} // namespace detail

} // namespace surfcert::app
