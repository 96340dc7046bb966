#pragma once
// `--set a.b=value` overrides applied to the parsed TOML before it is interpreted.
#include <toml++/toml.h>

#include <string>

namespace stagger::scene_detail {

/// Sets `path` (dotted keys, `name[i]` to index an array of tables) to `value` parsed as a
/// TOML value (number, bool, string, array, inline table); a value that is not valid TOML
/// is taken as a string. Missing tables are created; whether the key is allowed is checked
/// later by the interpretation (errors then point at "--set path=value").
void apply_override(toml::table& root, const std::string& path, const std::string& value);

}  // namespace stagger::scene_detail
