#pragma once
// The `stagger` executable of this build tree (bin/stagger), run through the shell.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/files.hpp"

namespace stagger::testing {

inline std::string stagger_binary() {
  return std::string(STAGGER_BINARY_DIR) + "/bin/stagger";
}

struct CommandResult {
  int status = -1;  ///< the exit status, or -1 if it did not exit normally
  std::string out, err;
};

/// Runs `stagger ARGS` with stdin closed and stdout and stderr captured in files of
/// `directory` (stdout.txt, stderr.txt).
inline CommandResult run_stagger(const std::string& args, const std::filesystem::path& directory) {
  const std::filesystem::path out = directory / "stdout.txt", err = directory / "stderr.txt";
  const std::string command =
      stagger_binary() + " " + args + " >" + out.string() + " 2>" + err.string() + " </dev/null";
  const int raw = std::system(command.c_str());
  CommandResult result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.out = read_text(out);
  result.err = read_text(err);
  return result;
}

}  // namespace stagger::testing
