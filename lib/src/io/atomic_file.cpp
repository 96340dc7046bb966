// Every output file is written to a temporary in a private directory beside it and renamed, so a
// crash or kill -9 at any moment leaves either the old complete file or the new one. Every
// system call's result is checked: a full disk (ENOSPC, often reported only by fdatasync or
// close) is an error naming the file, never a "completed" run with truncated output.
#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "stagger/error.hpp"
#include "stagger/output.hpp"

namespace stagger {
namespace io_detail {

namespace fs = std::filesystem;

namespace {
fs::path directory_of(const fs::path& path) {
  const fs::path parent = path.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

std::string system_error(int code) {
  std::string text = std::strerror(code);
  if (code == ENOSPC || code == EDQUOT || code == EFBIG) text += "; the disk (or quota, or file size limit) is full";
  return text;
}

[[noreturn]] void fail_and_remove(const fs::path& temporary, const std::string& target, const std::string& what,
                                  int code) {
  std::error_code ignored;
  fs::remove(temporary, ignored);
  throw Error("cannot write '" + target + "': " + what + " failed (" + system_error(code) +
              "); free space or choose another output directory");
}

// Writes all of `text` to `fd`, retrying short writes and EINTR; returns 0 or an errno.
int write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  return 0;
}
}  // namespace

PrivateTemporary::PrivateTemporary(const fs::path& target) : target_(target) {
  std::string pattern = (directory_of(target) / private_directory_prefix).string();
  pattern.append(std::to_string(::getpid())).append(".XXXXXX");
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw Error("cannot write '" + target.string() + "': creating a temporary directory beside it failed (" +
                system_error(errno) + "); check that the output directory is writable");
  }
  directory_ = pattern;
  file_ = directory_ / target.filename();
}

PrivateTemporary::~PrivateTemporary() {
  // Only what this object made: the temporary (if a writer left it) and the directory.
  std::error_code ignored;
  fs::remove(file_, ignored);
  fs::remove(directory_, ignored);
}

void PrivateTemporary::commit() {
  replace_file(file_, target_);
}

void require_directory_of(const fs::path& path) {
  const fs::path directory = directory_of(path);
  std::error_code ec;
  const auto status = fs::status(directory, ec);
  if (!fs::exists(status)) {
    throw Error("cannot write '" + path.string() + "': directory '" + directory.string() +
                "' does not exist; create it or choose another output directory");
  }
  if (!fs::is_directory(status)) {
    throw Error("cannot write '" + path.string() + "': '" + directory.string() +
                "' is not a directory; choose another output directory");
  }
  // rename() would replace a device node or a symbolic link itself: write only regular files.
  const auto target = fs::symlink_status(path, ec);
  if (fs::exists(target) && !fs::is_regular_file(target)) {
    throw Error("cannot write '" + path.string() + "': it exists and is not a regular file (" +
                (fs::is_directory(target) ? "a directory"
                 : fs::is_symlink(target) ? "a symbolic link"
                                          : "a device or special file") +
                "); choose another file name");
  }
}

void replace_file(const fs::path& from, const fs::path& to) {
  const int fd = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail_and_remove(from, to.string(), "reopening the temporary file", errno);
  if (::fdatasync(fd) != 0) {
    const int code = errno;
    ::close(fd);
    fail_and_remove(from, to.string(), "flushing to disk (fdatasync)", code);
  }
  if (::close(fd) != 0) fail_and_remove(from, to.string(), "closing", errno);
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(from, ignored);
    throw Error("cannot write '" + to.string() + "': renaming the temporary file failed (" + ec.message() +
                "); check the output directory's permissions");
  }
}

std::string read_file(const std::string& path) {
  // A device or a FIFO (e.g. /dev/zero) would never end or never come: regular files only.
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    throw Error("cannot read '" + path + "': not a regular file; check the path");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error("cannot read '" + path + "': " + std::strerror(errno) + "; check the path");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw Error("cannot read '" + path + "': read error");
  return buffer.str();
}

}  // namespace io_detail

namespace {
void write_through_temporary(const std::string& path, const std::function<void(const std::string&)>& write,
                             std::string_view expected_tail);
}  // namespace

void write_file_atomically(const std::string& path, const std::string& text) {
  write_through_temporary(path,
                          [&](const std::string& temporary) {
                            const int fd =
                                ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
                            if (fd < 0) {
                              throw Error("cannot write '" + path + "': " + std::strerror(errno) +
                                          "; check that the output directory is writable");
                            }
                            if (const int code = io_detail::write_all(fd, text.data(), text.size()); code != 0) {
                              ::close(fd);
                              io_detail::fail_and_remove(temporary, path, "writing", code);
                            }
                            if (::close(fd) != 0) io_detail::fail_and_remove(temporary, path, "closing", errno);
                          },
                          {});
}

void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write,
                           std::string_view expected_tail) {
  // The temporary keeps the target's name (in a private directory): some writers (gmsh)
  // choose the format by the extension.
  write_through_temporary(path, write, expected_tail);
}

namespace {
void write_through_temporary(const std::string& path, const std::function<void(const std::string&)>& write,
                             std::string_view expected_tail) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  io_detail::require_directory_of(target);
  io_detail::PrivateTemporary scratch(target);
  const fs::path& temporary = scratch.path();
  write(temporary.string());
  if (!expected_tail.empty()) {
    // A writer that does not check its own writes (e.g. a library's fprintf) leaves a
    // truncated file on a full disk: its last bytes show whether it is complete.
    std::ifstream in(temporary, std::ios::binary | std::ios::ate);
    const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
    std::string tail(expected_tail.size(), '\0');
    bool complete = size >= static_cast<std::streamoff>(tail.size());
    if (complete) {
      in.seekg(size - static_cast<std::streamoff>(tail.size()));
      complete =
          static_cast<bool>(in.read(tail.data(), static_cast<std::streamsize>(tail.size()))) && tail == expected_tail;
    }
    if (!complete) {
      throw Error("cannot write '" + path + "': the file came out incomplete (" + std::to_string(size < 0 ? 0 : size) +
                  " bytes; is the disk full?); free space or choose another output directory");
    }
  }
  scratch.commit();
}
}  // namespace

}  // namespace stagger
