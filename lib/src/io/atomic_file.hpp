#pragma once
/// @file atomic_file.hpp
/// Helpers for the write-to-temporary-then-rename protocol (internal to lib/src/io, lib/src/output and lib/src/driver).
#include <filesystem>
#include <string>

namespace stagger::io_detail {

/// The temporary name used for `path`: `.<name>.tmp.<pid>` in the same directory.
std::filesystem::path temporary_path(const std::filesystem::path& path);
/// Throws stagger::Error naming `path` unless its directory exists and is a directory, and
/// `path` itself is absent or a regular file (a device, directory or link is never replaced).
void require_directory_of(const std::filesystem::path& path);
/// Flushes `from` to disk (fdatasync: its data and size), then renames it onto `to` (atomic on POSIX within one
/// file system); on any failure removes `from` and throws naming `to` and the system error.
void replace_file(const std::filesystem::path& from, const std::filesystem::path& to);
/// Reads a whole file (binary); throws stagger::Error naming it.
std::string read_file(const std::string& path);

}  // namespace stagger::io_detail
