// write_all: every byte of a buffer to a file descriptor, the one loop the batch's output
// buffer (batch_stream.cpp), rank 0's output and the MPI worker's pipe to its compute child
// (batch_mpi*.cpp) share.
//
// Contract: retries short writes and EINTR; returns false on any other write error, after
// which the rest is dropped (the reader is gone: nobody would read it).
#pragma once

#include <cerrno>
#include <cstddef>

#include <unistd.h>

namespace surfcert::app {

inline bool write_all(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

} // namespace surfcert::app
