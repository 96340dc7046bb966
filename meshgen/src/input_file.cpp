/// @file input_file.cpp
/// Input files opened as regular files only, without blocking (input_file.hpp).
#include "input_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::meshgen {
namespace {

/// What a file of mode `mode` is, or "" for a regular file.
std::string kind_problem(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "is a character device";
  if (S_ISBLK(mode)) return "is a block device";
  if (S_ISSOCK(mode)) return "is a socket";
  return "is not a regular file";
}

std::string errno_problem(int code) {
  switch (code) {
    case ENOENT:
      return "not found";
    case ENOTDIR:
      return "not found (a part of the path is not a directory)";
    case ELOOP:
      return "is a symbolic link loop (or a chain of more than 40 links)";
    case EACCES:
      return "cannot be read (permission denied)";
    case ENAMETOOLONG:
      return "has a name that is too long";
    default:
      return std::string("cannot be read (") + std::strerror(code) + ")";
  }
}

}  // namespace

std::string file_problem(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return errno_problem(errno);
  return kind_problem(info.st_mode);
}

InputFile::InputFile(const std::string& path, const std::string& what) : path_(path), what_(what) {
  // A FIFO opened O_NONBLOCK does not wait for a writer; it is refused by fstat below.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd_ < 0) throw Error(what + " '" + path + "' " + errno_problem(errno) + "; check the path");
  struct stat info {};
  std::string problem = ::fstat(fd_, &info) != 0 ? errno_problem(errno) : kind_problem(info.st_mode);
  if (!problem.empty()) {
    ::close(fd_);
    throw Error(what + " '" + path + "' " + problem + ", not a regular file; check the path");
  }
  size_ = static_cast<std::uintmax_t>(info.st_size);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t InputFile::read(char* buffer, std::size_t count) {
  for (;;) {
    const ssize_t n = ::read(fd_, buffer, count);
    if (n >= 0) return static_cast<std::size_t>(n);
    if (errno != EINTR) throw Error("cannot read " + what_ + " '" + path_ + "': " + std::strerror(errno));
  }
}

std::string InputFile::read_all(std::uintmax_t max_bytes) {
  const auto too_large = [&] {
    return Error(what_ + " '" + path_ + "' is larger than " + std::to_string(max_bytes >> 20) +
                 " MiB; stagger reads no larger " + what_ + "s");
  };
  if (size_ > max_bytes) throw too_large();
  std::string text;
  char buffer[65536];
  for (std::size_t n; (n = read(buffer, sizeof buffer)) > 0;) {
    text.append(buffer, n);
    if (text.size() > max_bytes) throw too_large();  // it grew while being read
  }
  return text;
}

std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte >= 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace stagger::meshgen
