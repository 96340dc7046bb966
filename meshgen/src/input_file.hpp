#pragma once
/// @file input_file.hpp
/// Reading input files that may be hostile (a .geo and its includes, a .msh): regular files
/// only, opened without blocking (a FIFO would wait for a writer forever), with a size limit.
#include <cstdint>
#include <string>

namespace stagger::meshgen {

/// A file opened for reading: its descriptor (closed by the destructor) and size.
class InputFile {
 public:
  /// Opens `path` (O_NONBLOCK: a FIFO never blocks the open); throws stagger::Error
  /// "WHAT 'PATH' is a directory; ..." unless it is a readable regular file.
  InputFile(const std::string& path, const std::string& what);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  int fd() const { return fd_; }
  std::uintmax_t size() const { return size_; }
  /// Reads up to `count` bytes into `buffer`; 0 at the end; throws naming the file on error.
  std::size_t read(char* buffer, std::size_t count);
  /// The whole file; throws naming the file if it is larger than `max_bytes`.
  std::string read_all(std::uintmax_t max_bytes);

 private:
  std::string path_, what_;
  int fd_ = -1;
  std::uintmax_t size_ = 0;
};

/// Text from an input file for a message: control characters and bytes outside printable
/// ASCII as \xNN (a file name or line must not reach the terminal as an escape sequence).
std::string printable(const std::string& text);

}  // namespace stagger::meshgen
