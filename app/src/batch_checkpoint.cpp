#include "batch_checkpoint.hpp"

#include "surfcert/core/error.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace surfcert::app::mpi_batch {

namespace {

core::InputError checkpoint_error(const std::string& path, long line, const std::string& what) {
  return core::InputError(core::Location{path, static_cast<int>(line), 0, ""},
                          "a checkpoint of `surfcert batch --mpi`", what);
}

} // namespace

std::uint64_t line_hash(const std::string& line) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : line) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

Checkpoint::Checkpoint(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw checkpoint_error(path, 0, std::string("cannot open it: ") + std::strerror(errno));
  std::string all;
  std::vector<char> block(1 << 16);
  for (;;) {
    const ssize_t n = ::read(fd_, block.data(), block.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw checkpoint_error(path, 0, "cannot read it");
    if (n == 0) break;
    all.append(block.data(), static_cast<size_t>(n));
  }
  size_t start = 0, nl;
  long record_no = 0;
  while ((nl = all.find('\n', start)) != std::string::npos) {
    ++record_no;
    const std::string rec = all.substr(start, nl - start);
    start = nl + 1;
    const size_t tab = rec.find('\t');
    long no = 0;
    unsigned long long hash = 0;
    int pass = 0, fallback = 0;
    char status[64], kind[64];
    if (tab == std::string::npos ||
        std::sscanf(rec.c_str(), "%ld %llx %d %63s %63s %d", &no, &hash, &pass, status, kind,
                    &fallback) != 6 ||
        no < 1 || (pass != 1 && pass != 2))
      throw checkpoint_error(path, record_no, "a line that is not a record");
    CheckpointRecord r{hash,          pass,
                       status,        std::strcmp(kind, "-") == 0 ? "" : kind,
                       fallback != 0, rec.substr(tab + 1)};
    records_[no] = std::move(r);
  }
  // A torn last record (no newline): the run was killed while writing it. Cut it off.
  if (start < all.size() && ::ftruncate(fd_, static_cast<off_t>(start)) != 0)
    throw checkpoint_error(path, 0, "cannot cut its torn last record");
  ::lseek(fd_, 0, SEEK_END);
  last_sync_ = std::chrono::steady_clock::now();
}

Checkpoint::~Checkpoint() {
  if (fd_ < 0) return;
  try {
    write_pending(true);
  } catch (...) {
  }
  ::close(fd_);
}

void Checkpoint::append(long line_no, const CheckpointRecord& r) {
  char head[128];
  std::snprintf(head, sizeof head, "%ld %016llx %d %s %s %d\t", line_no,
                static_cast<unsigned long long>(r.hash), r.pass, r.status.c_str(),
                r.kind.empty() ? "-" : r.kind.c_str(), r.fallback ? 1 : 0);
  pending_ += head;
  pending_ += r.text;
  pending_ += '\n';
}

void Checkpoint::write_pending(bool force_sync) {
  const char* p = pending_.data();
  size_t n = pending_.size();
  while (n > 0) {
    const ssize_t w = ::write(fd_, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w < 0) throw std::runtime_error("cannot write the checkpoint " + path_);
    p += w;
    n -= static_cast<size_t>(w);
    unsynced_ = true;
  }
  pending_.clear();
  const auto now = std::chrono::steady_clock::now();
  if (unsynced_ && (force_sync || now - last_sync_ >= std::chrono::milliseconds(200))) {
    ::fsync(fd_);
    unsynced_ = false;
    last_sync_ = now;
  }
}

} // namespace surfcert::app::mpi_batch
