#include "overrides.hpp"

#include <cctype>
#include <vector>

#include "stagger/error.hpp"
#include "toml_reader.hpp"

namespace stagger::scene_detail {

namespace {

struct Segment {
  std::string name;
  std::vector<std::size_t> indices;
};

[[noreturn]] void fail(const std::string& label, const std::string& what) {
  throw Error(label + ": " + what);
}

// A label cut to 80 characters (a path or value 50 000 levels deep is 100 000 of them).
std::string shortened(const std::string& label) {
  return label.size() > 80 ? label.substr(0, 80) + "..." : label;
}

std::vector<Segment> split_path(const std::string& path, const std::string& label) {
  std::vector<Segment> segments;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    std::string piece = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    Segment segment;
    const std::size_t bracket = piece.find('[');
    segment.name = piece.substr(0, bracket);
    if (segment.name.empty()) fail(label, "empty key in '" + path + "'; write --set section.key=value");
    for (char c : segment.name)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
        fail(label, "invalid key '" + segment.name + "'; keys are letters, digits, '_' and '-'");
    std::size_t position = bracket;
    while (position != std::string::npos && position < piece.size()) {
      const std::size_t close = piece.find(']', position);
      if (piece[position] != '[' || close == std::string::npos || close == position + 1)
        fail(label, "malformed index in '" + piece + "'; write e.g. region[0].density=2");
      const std::string digits = piece.substr(position + 1, close - position - 1);
      for (char c : digits)
        if (!std::isdigit(static_cast<unsigned char>(c))) fail(label, "index '" + digits + "' is not a number");
      // No scene has a million entries in one array; the bound also keeps the number in range.
      if (digits.size() > 6) fail(label, "index " + digits + " is out of range (at most 999999)");
      segment.indices.push_back(std::stoul(digits));
      position = close + 1;
    }
    segments.push_back(segment);
    if (segments.size() > kMaxKeyDepth)
      fail(shortened(label),
           "the key nests more than " + std::to_string(kMaxKeyDepth) + " levels deep; no scene key is that deep");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return segments;
}

// Digits with an optional sign, point and exponent: meant as a number, not a bare word.
bool looks_numeric(const std::string& value) {
  std::size_t i = value.find_first_not_of("+-");
  if (i == std::string::npos || i > 1 || !std::isdigit(static_cast<unsigned char>(value[i]))) return false;
  return value.find_first_not_of("0123456789+-._eE", i) == std::string::npos;
}

// Parses `key = value` as a one-line document whose nodes carry the source "--set ...".
toml::table parse_assignment(const std::string& keys, const std::string& value, const std::string& label) {
  if (!too_deep_line(keys + " = " + value).empty())
    fail(shortened(label), "the value nests more than " + std::to_string(kMaxKeyDepth) +
                               " levels deep (dotted keys and inline tables); no scene key is that deep");
  try {
    return toml::parse(keys + " = " + value, label);
  } catch (const toml::parse_error&) {
    // A number TOML cannot hold (an integer beyond 64 bits) is an error, not a string.
    if (looks_numeric(value))
      fail(label, "'" + value +
                      "' is not a valid TOML number (out of range: integers must fit in 64 bits, floats "
                      "in a double)");
    // Not a TOML value: take it as a literal string (e.g. --set numerics.viscosity=edge).
    if (value.find('\'') != std::string::npos || value.find('\n') != std::string::npos)
      fail(label, "'" + value + "' is not a TOML value; quote strings");
    return toml::parse(keys + " = '" + value + "'", label);
  }
}

}  // namespace

void apply_override(toml::table& root, const std::string& path, const std::string& value) {
  const std::string label = "--set " + path + "=" + value;
  const std::vector<Segment> segments = split_path(path, label);
  toml::table* current = &root;
  std::string walked;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& segment = segments[i];
    const bool last = i + 1 == segments.size();
    walked += (walked.empty() ? "" : ".") + segment.name;
    toml::node* node = current->get(segment.name);
    if (node == nullptr || (last && segment.indices.empty())) {
      if (!segment.indices.empty())
        fail(label, "'" + walked + "' does not exist in the scene, so it cannot be indexed");
      // Create what is missing from here on as dotted keys of a one-line document.
      std::string keys;
      for (std::size_t j = i; j < segments.size(); ++j) {
        if (!segments[j].indices.empty())
          fail(label, "'" + segments[j].name + "' does not exist in the scene, so it cannot be indexed");
        keys += (keys.empty() ? "" : ".") + segments[j].name;
      }
      toml::table parsed = parse_assignment(keys, value, label);
      toml::node* created = parsed.get(segment.name);
      current->insert_or_assign(segment.name, std::move(*created));
      return;
    }
    for (std::size_t index : segment.indices) {
      auto* array = node->as_array();
      if (array == nullptr) fail(label, "'" + walked + "' is not an array, so it cannot be indexed");
      if (index >= array->size())
        fail(label, "'" + walked + "' has " + std::to_string(array->size()) + " entries (index from 0)");
      node = array->get(index);
      walked.append("[").append(std::to_string(index)).append("]");
    }
    if (last) fail(label, "cannot replace a whole array element; set one of its keys");
    if (node->is_array_of_tables() && segment.indices.empty())
      fail(label,
           "'" + walked + "' is an array of tables; pick one entry, e.g. " + walked + "[0]." + segments[i + 1].name);
    current = node->as_table();
    if (current == nullptr)
      fail(label, "'" + walked + "' is not a table, so it has no key '" + segments[i + 1].name + "'");
  }
}

}  // namespace stagger::scene_detail
