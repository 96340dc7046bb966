#pragma once
// A fresh, empty directory for one test, removed afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

#include "support/files.hpp"

namespace stagger::testing {

/// The running test's name (without its suite).
inline std::string current_test_name() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

class ScratchDirectory {
 public:
  /// <temp>/stagger_<name>_<pid>: the pid keeps concurrent runs (several build trees on one
  /// machine) apart.
  explicit ScratchDirectory(const std::string& name)
      : ScratchDirectory(std::filesystem::temp_directory_path() /
                         ("stagger_" + name + "_" + std::to_string(::getpid()))) {}
  /// Exactly at `path` (e.g. under the build tree).
  explicit ScratchDirectory(std::filesystem::path path) : path_(std::move(path)) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  /// Writes `text` to the file `name` (its folders created); returns its path.
  std::string write(const std::string& name, const std::string& text) const { return write_text(path_ / name, text); }

 private:
  std::filesystem::path path_;
};

}  // namespace stagger::testing
