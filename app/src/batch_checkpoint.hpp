// surfcert::app (private to `batch --mpi`, batch_mpi.hpp) the checkpoint file: the answers of
// a run, appended as they arrive, read back by a restarted run.
//
// What it represents: one record per answer, "<line_no> <hash> <pass> <status> <kind|->
// <fallback>\t<answer>\n" (hash: FNV-1a 64 of the input line, in hex; pass 1 or 2, the second
// pass of --retry-undecided). A later record of a line supersedes an earlier one. Opening
// reads every whole record and cuts a torn last one (a run killed while writing); append()
// writes at once (write(2): a killed process loses nothing appended) and fsyncs at most every
// 0.2 s, and at close.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>

namespace surfcert::app::mpi_batch {

struct CheckpointRecord {
  std::uint64_t hash = 0;
  int pass = 1;
  std::string status, kind;
  bool fallback = false;
  std::string text;
};

std::uint64_t line_hash(const std::string& line);

class Checkpoint {
public:
  /// Opens (creates) path; the records already there are in records(). Throws InputError when
  /// the file cannot be opened or holds something that is not a record.
  explicit Checkpoint(const std::string& path);
  ~Checkpoint();
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;

  const std::map<long, CheckpointRecord>& records() const { return records_; }
  void append(long line_no, const CheckpointRecord& r);
  /// Writes what append() gathered since the last write; fsyncs when 0.2 s have passed.
  void write_pending(bool force_sync = false);

private:
  std::string path_;
  int fd_ = -1;
  std::map<long, CheckpointRecord> records_;
  std::string pending_;
  std::chrono::steady_clock::time_point last_sync_;
  bool unsynced_ = false;
};

} // namespace surfcert::app::mpi_batch
