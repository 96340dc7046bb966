// The output directory of a run. Nothing here follows a link planted in the directory, and
// nothing removes a file this program did not write: the files it removes are a run's own
// outputs (by their exact name patterns) and the private directories of its dead writers.
#include "driver/output_directory.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <set>
#include <string_view>

#include "io/atomic_file.hpp"
#include "stagger/error.hpp"

namespace stagger::driver_detail {

namespace fs = std::filesystem;

namespace {
constexpr const char* lock_file_name = ".stagger.lock";
// Files every run writes under the same name, whatever its scene.
constexpr const char* shared_files[] = {"history.csv", "summary.json", "ranks.csv"};

bool all_digits(std::string_view text) {
  return !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
}

// The scene a summary.json names ("scene": "..."), or "" if there is none or it is unreadable.
std::string scene_of_summary(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(path, ec))) return {};
  std::string text;
  try {
    text = io_detail::read_file(path.string());
  } catch (const Error&) {
    return {};
  }
  const std::string key = "\"scene\": \"";
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return {};
  const std::size_t end = text.find('"', at + key.size());
  return end == std::string::npos ? std::string() : text.substr(at + key.size(), end - at - key.size());
}

// The stem of a file that marks a run's results in a directory: NAME.pvd or NAME.checkpoint.
std::string run_name_of(const std::string& file) {
  for (const std::string_view suffix : {std::string_view(".pvd"), std::string_view(".checkpoint")})
    if (file.size() > suffix.size() && file.ends_with(suffix)) return file.substr(0, file.size() - suffix.size());
  return {};
}
}  // namespace

bool is_output_of(const std::string& name, const std::string& file) {
  if (!file.starts_with(name)) return false;
  const std::string_view rest = std::string_view(file).substr(name.size());
  if (rest == ".pvd" || rest == ".checkpoint") return true;
  // NAME.checkpoint.P.rRRRR (a distributed checkpoint's pieces)
  if (rest.starts_with(".checkpoint.") && rest.size() > 15) {
    const std::string_view piece = rest.substr(12);
    return (piece[0] == '0' || piece[0] == '1') && piece.substr(1, 2) == ".r" && all_digits(piece.substr(3));
  }
  // NAME_NNNNNN.vtu, NAME_NNNNNN.pvtu, NAME_NNNNNN_rRRRR.vtu
  if (!rest.starts_with('_')) return false;
  const std::size_t suffix = rest.ends_with(".pvtu") ? 5 : rest.ends_with(".vtu") ? 4 : 0;
  if (suffix == 0) return false;
  std::string_view digits = rest.substr(1, rest.size() - 1 - suffix);
  const std::size_t piece = digits.find("_r");
  if (suffix == 4 && piece != std::string_view::npos && all_digits(digits.substr(piece + 2)))
    digits = digits.substr(0, piece);
  return digits.size() >= 6 && all_digits(digits);
}

OutputDirectory::OutputDirectory(fs::path directory) : directory_(std::move(directory)) {}

OutputDirectory::~OutputDirectory() {
  if (lock_fd_ < 0) return;
  // Unlinked while still held: a run waiting on this file finds it replaced and locks anew.
  ::unlink((directory_ / lock_file_name).c_str());
  ::close(lock_fd_);
}

void OutputDirectory::prepare() const {
  std::error_code ec;
  fs::create_directories(directory_, ec);
  if (ec || !fs::is_directory(directory_)) {
    throw Error("cannot create output directory '" + directory_.string() +
                "': " + (ec ? ec.message() : std::string("a file of that name exists")) +
                "; choose a writable output directory (--out)");
  }
  // Permissions alone do not tell (read-only mounts, ACLs): make and remove a private directory.
  std::string probe = (directory_ / io_detail::private_directory_prefix).string();
  probe.append(std::to_string(::getpid())).append(".XXXXXX");
  if (::mkdtemp(probe.data()) == nullptr) {
    throw Error("output directory '" + directory_.string() + "' is not writable (" + std::strerror(errno) +
                "); choose a writable output directory (--out)");
  }
  ::rmdir(probe.c_str());
  remove_stale_private_directories();
}

void OutputDirectory::remove_stale_private_directories() const {
  const std::string prefix = io_detail::private_directory_prefix;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory_, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with(prefix)) continue;
    const std::size_t dot = name.find('.', prefix.size());
    if (dot == std::string::npos || name.size() != dot + 7 ||
        !all_digits(std::string_view(name).substr(prefix.size(), dot - prefix.size())))
      continue;
    const long pid = std::stol(name.substr(prefix.size(), dot - prefix.size()));
    struct stat info {};
    // A directory of ours (not a link, owned by this user) whose writer is gone.
    if (::lstat(entry.path().c_str(), &info) != 0 || !S_ISDIR(info.st_mode) || info.st_uid != ::geteuid()) continue;
    if (pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    for (const auto& inner : fs::directory_iterator(entry.path(), ignored))
      if (fs::is_regular_file(inner.symlink_status(ignored))) fs::remove(inner.path(), ignored);
    fs::remove(entry.path(), ignored);  // only if now empty
  }
}

void OutputDirectory::lock() {
  const fs::path path = directory_ / lock_file_name;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) {
      const int code = errno;
      throw Error("cannot lock output directory '" + directory_.string() + "': " +
                  (code == ELOOP ? std::string("'") + lock_file_name + "' is a symbolic link" : std::strerror(code)) +
                  "; remove it or choose another output directory (--out)");
    }
    struct stat held {};
    if (::fstat(fd, &held) != 0 || !S_ISREG(held.st_mode)) {
      ::close(fd);
      throw Error("cannot lock output directory '" + directory_.string() + "': '" + lock_file_name +
                  "' is not a regular file; remove it or choose another output directory (--out)");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int code = errno;
      std::string owner;
      char buffer[32] = {};
      if (::pread(fd, buffer, sizeof buffer - 1, 0) > 0) owner = buffer;
      while (!owner.empty() && (owner.back() == '\n' || owner.back() == ' ')) owner.pop_back();
      ::close(fd);
      if (code == EWOULDBLOCK) {
        throw Error("output directory '" + directory_.string() + "' is in use by another stagger run" +
                    (owner.empty() ? std::string() : " (pid " + owner + ")") +
                    "; wait for it to finish or choose another output directory (--out)");
      }
      throw Error("cannot lock output directory '" + directory_.string() + "': " + std::strerror(code));
    }
    // The previous owner unlinks the file as it ends: a lock on a file no longer at the
    // path locks nothing, so open the path again.
    struct stat now {};
    if (::lstat(path.c_str(), &now) != 0 || now.st_ino != held.st_ino || now.st_dev != held.st_dev) {
      ::close(fd);
      continue;
    }
    lock_fd_ = fd;
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(lock_fd_, 0) != 0 ||
        ::pwrite(lock_fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
      throw Error("cannot write the lock file '" + path.string() + "': " + std::strerror(errno) +
                  "; free space or choose another output directory");
    }
    return;
  }
  throw Error("cannot lock output directory '" + directory_.string() +
              "': its lock file keeps being replaced; choose another output directory (--out)");
}

std::vector<fs::path> OutputDirectory::files_of(const std::string& name) const {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory_, ec))
    if (is_output_of(name, entry.path().filename().string()) && entry.is_regular_file(ec))
      files.push_back(entry.path());
  return files;
}

void OutputDirectory::remove_outputs_of(const std::string& name) const {
  for (const auto& path : files_of(name)) {
    std::error_code ec;
    fs::remove(path, ec);
    if (ec) {
      throw Error("cannot remove the previous run's output '" + path.string() + "': " + ec.message() +
                  "; remove it by hand or choose another output directory (--out)");
    }
  }
}

void OutputDirectory::claim(const std::string& name, const std::string& scene, bool replace) const {
  std::set<std::string> others;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory_, ec)) {
    const std::string other = run_name_of(entry.path().filename().string());
    if (!other.empty() && other != name && entry.is_regular_file(ec)) others.insert(other);
  }
  if (const std::string summarised = scene_of_summary(directory_ / "summary.json");
      !summarised.empty() && summarised != scene)
    others.insert(summarised);
  if (others.empty()) return;
  std::string list;
  for (const auto& other : others) list += (list.empty() ? "'" : ", '") + other + "'";
  if (!replace) {
    throw Error("output directory '" + directory_.string() + "' holds the results of scene " + list + ", not '" + name +
                "'; run into another directory (--out), or pass --replace to remove those results "
                "(their .pvd, dumps, checkpoints, history.csv and summary.json)");
  }
  for (const auto& other : others) remove_outputs_of(other);
  for (const char* shared : shared_files) {
    const fs::path path = directory_ / shared;
    if (fs::is_regular_file(fs::symlink_status(path, ec))) fs::remove(path, ec);
  }
}

bool OutputDirectory::holds(const std::string& file) const {
  std::error_code ec;
  return fs::is_regular_file(fs::symlink_status(directory_ / file, ec));
}

}  // namespace stagger::driver_detail
