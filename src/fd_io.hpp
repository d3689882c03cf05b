// Whole writes and reads on a file descriptor (a pipe to or from a child process), retried
// after a signal interrupts them: shared by `certcyl query`'s isolated lines, the study's child
// processes and `certcyl judge --exec`. Internal to the command.
#pragma once

#include <cerrno>
#include <cstddef>

#include <unistd.h>

namespace certcyl::cli {

// Every byte of `size` at `data` to fd; false when the reader has gone (EPIPE: SIGPIPE must be
// ignored or blocked) or on another error.
inline bool write_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n, size -= static_cast<std::size_t>(n);
  }
  return true;
}

// Exactly `size` bytes from fd into `data`; false at an end of file first, or on an error.
inline bool read_all(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::read(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n, size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace certcyl::cli
