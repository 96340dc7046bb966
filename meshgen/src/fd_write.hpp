#pragma once
/// @file fd_write.hpp
/// Writing a whole buffer to a file descriptor (a pipe or a file), without stdio.
#include <cerrno>
#include <cstddef>
#include <string>

#include <unistd.h>

namespace stagger::meshgen {

/// Writes all of `bytes` to `fd`, retrying after signals; false if a write fails.
inline bool write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace stagger::meshgen
