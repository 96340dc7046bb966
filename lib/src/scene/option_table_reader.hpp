#pragma once
// Reads one option set of a scene through its option table (stagger/option_table.hpp):
// every row's key is read with its type, defaulting to the value already in `values` (the
// struct's default), and range-checked; an error names the file, line and key.
#include <string>

#include "stagger/option_table.hpp"
#include "toml_reader.hpp"

namespace stagger::scene_detail {

template <class Options>
void read_options(Section& section, const OptionTable<Options>& table, Options& values) {
  for (const auto& option : table.options) {
    const double current = option.get(values);
    double value = current;
    switch (option.type) {
      case OptionType::number:
        value = option.required ? section.number(option.key) : section.number(option.key, current);
        break;
      case OptionType::integer:
        value = static_cast<double>(option.required ? section.integer(option.key)
                                                    : section.integer(option.key, static_cast<long>(current)));
        break;
      case OptionType::flag:
        value = section.boolean(option.key, current != 0) ? 1.0 : 0.0;
        break;
      case OptionType::choice: {
        const std::string name = section.string(option.key, option.choices.at(static_cast<std::size_t>(current)));
        value = -1;
        for (std::size_t k = 0; k < option.choices.size(); ++k)
          if (name == option.choices[k]) value = static_cast<double>(k);
        if (value < 0) {
          std::string list;  // the wording of Section::choice
          for (const char* allowed : option.choices)
            list += std::string(list.empty() ? "" : ", ") + "\"" + allowed + "\"";
          section.fail(option.key, "unknown value \"" + name + "\"", "use one of " + list);
        }
        break;
      }
    }
    const std::string problem = option.check(value);
    if (!problem.empty()) section.fail(option.key, problem, option.doc);
    option.set(values, value);
  }
}

}  // namespace stagger::scene_detail
