#pragma once
// The subcommands of `stagger`. Each returns the exit code; errors are thrown
// (stagger::Error, UsageError) and turned into one line on stderr by main().
#include <string>
#include <vector>

namespace stagger::cli {

int run_command(const std::vector<std::string>& args);
int check_command(const std::vector<std::string>& args);
int mesh_command(const std::vector<std::string>& args);

extern const char* const run_help;
extern const char* const check_help;
extern const char* const mesh_help;

}  // namespace stagger::cli
