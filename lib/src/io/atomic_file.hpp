#pragma once
/// @file atomic_file.hpp
/// Helpers for the write-to-temporary-then-rename protocol (internal to lib/src/io, lib/src/output and lib/src/driver).
#include <filesystem>
#include <string>

namespace stagger::io_detail {

/// The prefix of a writer's private directory: `.stagger-tmp.<pid>.XXXXXX` beside its target.
inline constexpr const char* private_directory_prefix = ".stagger-tmp.";

/// A private directory (mode 0700, made by mkdtemp: never an existing name, so nobody can
/// plant a link or a file at the temporary's name) beside a target file, holding the
/// temporary under the target's own file name (writers that choose the format by the
/// extension keep it). commit() renames the temporary onto the target; whatever is left
/// (a failed writer's file, the directory) is removed when the object dies.
class PrivateTemporary {
 public:
  /// Throws stagger::Error naming `target` if the directory cannot be made.
  explicit PrivateTemporary(const std::filesystem::path& target);
  ~PrivateTemporary();
  PrivateTemporary(const PrivateTemporary&) = delete;
  PrivateTemporary& operator=(const PrivateTemporary&) = delete;
  /// The temporary file's path (inside the private directory; not created).
  const std::filesystem::path& path() const { return file_; }
  /// Flushes the temporary and renames it onto the target (replace_file).
  void commit();

 private:
  std::filesystem::path target_, directory_, file_;
};
/// Throws stagger::Error naming `path` unless its directory exists and is a directory, and
/// `path` itself is absent or a regular file (a device, directory or link is never replaced).
void require_directory_of(const std::filesystem::path& path);
/// Flushes `from` to disk (fdatasync: its data and size), then renames it onto `to` (atomic on POSIX within one
/// file system); on any failure removes `from` and throws naming `to` and the system error.
void replace_file(const std::filesystem::path& from, const std::filesystem::path& to);
/// Reads a whole file (binary); throws stagger::Error naming it.
std::string read_file(const std::string& path);

}  // namespace stagger::io_detail
