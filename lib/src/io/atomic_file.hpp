#pragma once
/// @file atomic_file.hpp
/// Helpers for the write-to-temporary-then-rename protocol (internal to lib/src/io, driver).
#include <filesystem>
#include <string>

namespace stagger::io_detail {

/// The temporary name used for `path`: `.<name>.tmp.<pid>` in the same directory.
std::filesystem::path temporary_path(const std::filesystem::path& path);
/// Throws stagger::Error naming `path` unless its directory exists and is a directory.
void require_directory_of(const std::filesystem::path& path);
/// Renames `from` onto `to` (atomic on POSIX within one file system); throws naming `to`.
void replace_file(const std::filesystem::path& from, const std::filesystem::path& to);
/// Reads a whole file (binary); throws stagger::Error naming it.
std::string read_file(const std::string& path);

}  // namespace stagger::io_detail
