#include "toml_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "hydro/option_rows.hpp"
#include "stagger/error.hpp"

namespace stagger::scene_detail {

std::string where(const std::string& file, const toml::node* node, const toml::node* fallback) {
  for (const toml::node* candidate : {node, fallback}) {
    if (candidate == nullptr) continue;
    const auto& source = candidate->source();
    if (source.path && source.path->rfind("--set", 0) == 0) return *source.path;
    if (source.begin.line > 0) return file + ":" + std::to_string(source.begin.line);
  }
  return file;
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

// The option tables' number text (10 significant digits), so that a scene error and the option
// table's own messages print a value alike.
std::string show(double value) {
  return option_rows::number_text(value);
}

namespace {
bool safe_name_character(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
}
}  // namespace

std::string unsafe_name_reason(std::string_view name) {
  if (name.empty()) return "is empty";
  if (name.size() > kMaxNameLength)
    return "is " + std::to_string(name.size()) + " characters long (at most " + std::to_string(kMaxNameLength) + ")";
  for (std::size_t i = 0; i < name.size(); ++i)
    if (!safe_name_character(name[i])) {
      const auto code = static_cast<unsigned char>(name[i]);
      std::string text = "has ";
      if (code >= 0x80)
        text.append("a non-ASCII byte");
      else if (code < 0x20 || code == 0x7f)
        text.append("a control character");
      else
        text.append(1, '\'').append(1, name[i]).append(1, '\'');
      return text.append(" at position ").append(std::to_string(i));
    }
  if (name.front() == '.') return "starts with '.'";
  if (name.find("..") != std::string_view::npos) return "contains '..'";
  return {};
}

std::string too_deep_line(std::string_view text) {
  // Dots between a line start, '[', '{', ',' or '=' and the next of these are a key's dotted
  // parts (a float's one dot after '=' counts too, harmlessly); '{' opens a nested table.
  std::size_t dots = 0, braces = 0, line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"' || c == '\'') {
      const bool multi = text.substr(i, 3) == std::string(3, c);
      const std::string_view close = multi ? text.substr(i, 3) : text.substr(i, 1);
      std::size_t j = i + close.size();
      while (j < text.size() && text.substr(j, close.size()) != close) {
        if (c == '"' && text[j] == '\\') ++j;  // an escape in a basic string
        if (j < text.size() && text[j] == '\n') {
          if (!multi) break;  // an unclosed string: the parser reports it
          ++line;
        }
        ++j;
      }
      const bool cut = !multi && j < text.size() && text[j] == '\n';
      i = cut ? j - 1 : std::min(j + close.size(), text.size()) - 1;
    } else if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
    } else if (c == '\n' || c == '[' || c == ',' || c == '=' || c == '{' || c == '}') {
      if (c == '\n') ++line;
      if (c == '{' && ++braces >= kMaxKeyDepth) return "line " + std::to_string(line);
      if (c == '}' && braces > 0) --braces;
      dots = 0;
    } else if (c == '.') {
      if (++dots + braces >= kMaxKeyDepth) return "line " + std::to_string(line);
    }
  }
  return {};
}

std::string safe_name(std::string_view name) {
  std::string result;
  for (char c : name.substr(0, kMaxNameLength)) result += safe_name_character(c) ? c : '_';
  if (!result.empty() && result.front() == '.') result.front() = '_';
  for (std::size_t at; (at = result.find("..")) != std::string::npos;) result[at + 1] = '_';
  return result.empty() ? "scene" : result;
}

namespace {
// Levenshtein distance, to suggest the key a typo was meant to be.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}
}  // namespace

Section::Section(std::string file, const toml::table& table, std::string path)
    : file_(std::move(file)), table_(&table), path_(std::move(path)) {}

std::string Section::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

const toml::node* Section::find(std::string_view key) {
  known_.emplace(key);
  return table_->get(key);
}

void Section::fail_at(const toml::node* node, const std::string& key_label, const std::string& what,
                      const std::string& todo) const {
  std::string message = where(file_, node, table_) + ": key '" + key_label + "': " + what;
  if (!todo.empty()) message += "; " + todo;
  throw Error(message);
}

void Section::fail(std::string_view key, const std::string& what, const std::string& todo) const {
  fail_at(table_->get(key), key_path(key), what, todo);
}

const toml::node& Section::require(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) {
    std::string section = path_.empty() ? "the top level" : "[" + path_ + "]";
    // A missing key is often a misspelt one: name an unread key one or two edits away
    // (not for one-letter keys, nor pairs such as R1/R2 that differ in a final digit).
    for (const auto& [other, other_node] : *table_) {
      const std::string_view name = other.str();
      const bool digit_pair = name.size() == key.size() &&
                              name.substr(0, name.size() - 1) == key.substr(0, key.size() - 1) &&
                              std::isdigit(static_cast<unsigned char>(name.back())) != 0;
      if (key.size() >= 2 && known_.count(name) == 0 && !digit_pair &&
          edit_distance(name, key) <= std::max<std::size_t>(1, key.size() / 3))
        fail_at(&other_node, key_path(key),
                "missing (is '" + std::string(name) + "' on this line a misspelling of it?)",
                "rename it to '" + std::string(key) + "', or add the key to " + section);
    }
    fail_at(nullptr, key_path(key), "missing", "add it to " + section + " (see docs/scenes.md)");
  }
  return *node;
}

namespace {
std::string format_number(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}
}  // namespace

double Section::number(std::string_view key) {
  const toml::node& node = require(key);
  if (!node.is_number())
    fail(key, "expected a number, got " + type_name(node), "write e.g. " + std::string(key) + " = 1.0");
  const double value = *node.value<double>();
  if (!std::isfinite(value)) fail(key, "must be finite, got " + format_number(value));
  return value;
}

double Section::number(std::string_view key, double fallback) {
  return find(key) ? number(key) : fallback;
}

namespace {
// Integers beyond 2^53 do not survive the trip through a double (expressions, --set of a
// float): the default limit of a plain integer key.
constexpr long kIntegerLimit = 1L << 53;
}  // namespace

long Section::integer(std::string_view key) {
  return integer_in(key, -kIntegerLimit, kIntegerLimit);
}

long Section::integer(std::string_view key, long fallback) {
  return find(key) ? integer(key) : fallback;
}

long Section::integer_in(std::string_view key, long min, long max) {
  const toml::node& node = require(key);
  // Built by appending: GCC 12 at -O3 warns falsely (-Wrestrict) on "[" + std::string.
  std::string range(1, '[');
  range.append(std::to_string(min)).append(", ").append(std::to_string(max)).append("]");
  if (const auto* integer_node = node.as_integer()) {
    const std::int64_t value = integer_node->get();
    if (value < min || value > max) fail(key, "must be in " + range + ", got " + std::to_string(value));
    return static_cast<long>(value);
  }
  if (const auto* floating = node.as_floating_point()) {
    const double value = floating->get();
    if (!std::isfinite(value)) fail(key, "must be a finite integer in " + range + ", got " + show(value));
    if (value == std::round(value)) {
      // Compare as doubles first: casting an out-of-range double to long is undefined.
      if (value < static_cast<double>(min) || value > static_cast<double>(max))
        fail(key, "must be in " + range + ", got " + show(value));
      return static_cast<long>(value);
    }
    fail(key, "expected an integer, got " + show(value), "write e.g. " + std::string(key) + " = 10");
  }
  fail(key, "expected an integer, got " + type_name(node), "write e.g. " + std::string(key) + " = 10");
}

long Section::integer_in(std::string_view key, long fallback, long min, long max) {
  return find(key) ? integer_in(key, min, max) : fallback;
}

bool Section::boolean(std::string_view key, bool fallback) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  if (const auto* flag = node->as_boolean()) return flag->get();
  fail(key, "expected true or false, got " + type_name(*node));
}

std::string Section::string(std::string_view key) {
  const toml::node& node = require(key);
  if (const auto* text = node.as_string()) return text->get();
  fail(key, "expected a string, got " + type_name(node), "quote it: " + std::string(key) + " = \"...\"");
}

std::string Section::string(std::string_view key, const std::string& fallback) {
  return find(key) ? string(key) : fallback;
}

std::string Section::choice(std::string_view key, std::initializer_list<const char*> allowed,
                            std::optional<std::string> fallback) {
  return choice(key, std::vector<const char*>(allowed), std::move(fallback));
}

std::string Section::choice(std::string_view key, const std::vector<const char*>& allowed,
                            std::optional<std::string> fallback) {
  std::string list;
  for (const char* option : allowed) list += std::string(list.empty() ? "" : ", ") + "\"" + option + "\"";
  if (!find(key) && fallback) return *fallback;
  const std::string value = string(key);
  for (const char* option : allowed)
    if (value == option) return value;
  fail(key, "unknown value \"" + value + "\"", "use one of " + list);
}

std::vector<double> Section::numbers(std::string_view key, std::size_t count) {
  const toml::node& node = require(key);
  const auto* array = node.as_array();
  const std::string example = count == 2 ? " = [0.0, 1.0]" : " = [...]";
  if (array == nullptr)
    fail(key, "expected an array of numbers, got " + type_name(node), "write e.g. " + std::string(key) + example);
  if (count != 0 && array->size() != count)
    fail(key, "expected " + std::to_string(count) + " numbers, got " + std::to_string(array->size()),
         "write e.g. " + std::string(key) + example);
  std::vector<double> values;
  for (const toml::node& element : *array) {
    if (!element.is_number() || !std::isfinite(*element.value<double>()))
      fail_at(&element, key_path(key),
              "element " + std::to_string(values.size()) + " is " + type_name(element) + ", not a finite number");
    values.push_back(*element.value<double>());
  }
  return values;
}

double Section::number_at(const toml::node& node, const std::string& key_label) const {
  if (!node.is_number()) fail_at(&node, key_label, "expected a number, got " + type_name(node));
  const double value = *node.value<double>();
  if (!std::isfinite(value)) fail_at(&node, key_label, "must be finite, got " + show(value));
  return value;
}

std::vector<std::string> Section::strings(std::string_view key) {
  const toml::node& node = require(key);
  const auto* array = node.as_array();
  if (array == nullptr)
    fail(key, "expected an array of strings, got " + type_name(node), "write e.g. " + std::string(key) + " = [\"a\"]");
  std::vector<std::string> values;
  for (const toml::node& element : *array) {
    if (!element.is_string())
      fail_at(&element, key_path(key),
              "element " + std::to_string(values.size()) + " is " + type_name(element) + ", not a string");
    values.push_back(*element.value<std::string>());
  }
  return values;
}

Section::ValueOrExpression Section::value_or_expression(const toml::node& node, const std::string& key_label,
                                                        const std::vector<std::string>& variables) {
  ValueOrExpression result;
  result.node = &node;
  std::string names;
  for (const auto& variable : variables) names += (names.empty() ? "" : ", ") + variable;
  if (node.is_number()) {
    result.constant = *node.value<double>();
    if (!std::isfinite(*result.constant)) fail_at(&node, key_label, "must be finite");
    return result;
  }
  if (const auto* text = node.as_string()) {
    try {
      result.expression.emplace(text->get(), variables);
    } catch (const ExpressionError& error) {
      fail_at(&node, key_label, "expression \"" + text->get() + "\" does not parse: " + error.message,
              "use the variables " + names + ", pi, +-*/^, ?:, and functions such as sin, sqrt, exp");
    }
    return result;
  }
  fail_at(&node, key_label, "expected a number or a string expression of " + names + ", got " + type_name(node));
}

Section::ValueOrExpression Section::value_or_expression(std::string_view key,
                                                        const std::vector<std::string>& variables) {
  return value_or_expression(require(key), key_path(key), variables);
}

std::optional<Section> Section::subtable(std::string_view key) {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const auto* sub = node->as_table();
  if (sub == nullptr) fail(key, "expected a table, got " + type_name(*node), "write it as [" + key_path(key) + "]");
  return Section(file_, *sub, key_path(key));
}

std::vector<Section> Section::table_array(std::string_view key) {
  std::vector<Section> result;
  const toml::node* node = find(key);
  if (node == nullptr) return result;
  const auto* array = node->as_array();
  if (array == nullptr || !array->is_array_of_tables())
    fail(key, "expected an array of tables, got " + type_name(*node), "write each entry as [[" + key_path(key) + "]]");
  for (std::size_t i = 0; i < array->size(); ++i)
    result.emplace_back(file_, *array->get(i)->as_table(), key_path(key) + "[" + std::to_string(i) + "]");
  return result;
}

void Section::finish() const {
  for (const auto& [key, node] : *table_) {
    if (known_.count(key.str()) != 0) continue;
    std::string list;
    for (const auto& name : known_) list += (list.empty() ? "" : ", ") + name;
    std::string message = where(file_, &node, table_) + ": key '" + key_path(key.str()) + "': unknown key";
    message += list.empty() ? "; remove it" : "; expected one of " + list;
    throw Error(message);
  }
}

}  // namespace stagger::scene_detail
