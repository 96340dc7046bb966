#pragma once
// A small command-line parser: positional arguments, flags, options with a value
// (`--out DIR` or `--out=DIR`), repeatable options (`--set k=v`). Errors throw UsageError.
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace stagger::cli {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  std::string name;   ///< "--out" (or "-o")
  std::string alias;  ///< "" or "-o"
  bool takes_value = false;
  bool repeatable = false;
};

class Arguments {
 public:
  /// Parses args (after the subcommand) for `command` ("stagger run").
  Arguments(const std::string& command, const std::vector<std::string>& args, const std::vector<OptionSpec>& specs);
  bool flag(const std::string& name) const { return values_.count(name) != 0; }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  const std::string& value(const std::string& name) const { return values_.at(name).back(); }
  std::vector<std::string> values(const std::string& name) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::vector<std::string>> values_;
  std::vector<std::string> positional_;
};

/// Splits "key=value" (Error naming `option` when there is no '=').
std::pair<std::string, std::string> split_assignment(const std::string& option, const std::string& text);

}  // namespace stagger::cli
