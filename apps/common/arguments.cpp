#include "arguments.hpp"

namespace stagger::cli {

Arguments::Arguments(const std::string& command, const std::vector<std::string>& args,
                     const std::vector<OptionSpec>& specs) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg.size() < 2 || arg[0] != '-' || (arg[1] >= '0' && arg[1] <= '9') || arg[1] == '.') {
      positional_.push_back(arg);
      continue;
    }
    std::string name = arg, inline_value;
    bool has_inline = false;
    if (const auto equals = arg.find('='); equals != std::string::npos && arg.rfind("--", 0) == 0) {
      name = arg.substr(0, equals);
      inline_value = arg.substr(equals + 1);
      has_inline = true;
    }
    const OptionSpec* spec = nullptr;
    for (const auto& candidate : specs)
      if (candidate.name == name || (!candidate.alias.empty() && candidate.alias == name)) spec = &candidate;
    if (spec == nullptr)
      throw UsageError("unknown option '" + name + "' for '" + command + "'; see '" + command + " --help'");
    if (!spec->takes_value) {
      if (has_inline) throw UsageError("option '" + name + "' of '" + command + "' takes no value");
      values_[spec->name].push_back("");
      continue;
    }
    if (!has_inline) {
      if (i + 1 >= args.size()) throw UsageError("option '" + name + "' of '" + command + "' needs a value");
      inline_value = args[++i];
    }
    auto& slot = values_[spec->name];
    if (!slot.empty() && !spec->repeatable) throw UsageError("option '" + name + "' of '" + command + "' given twice");
    slot.push_back(inline_value);
  }
}

std::vector<std::string> Arguments::values(const std::string& name) const {
  const auto found = values_.find(name);
  return found == values_.end() ? std::vector<std::string>{} : found->second;
}

std::pair<std::string, std::string> split_assignment(const std::string& option, const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw UsageError(option + " '" + text + "' is not of the form key=value; write e.g. " + option + " mesh.refine=2");
  return {text.substr(0, equals), text.substr(equals + 1)};
}

}  // namespace stagger::cli
