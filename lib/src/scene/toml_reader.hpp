#pragma once
// A strict reader over toml++ tables: every key a scene may hold is read through a
// Section, which remembers what it was asked for, so that finish() can reject every other
// key. Every error is one line: "FILE:LINE: key 'a.b': what is wrong; what to do".
#include <toml++/toml.h>

#include <array>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "expression.hpp"

namespace stagger::scene_detail {

/// "FILE:LINE" of a node ("--set a.b=v" for a value from the command line); `fallback`
/// is used when the node has no source (implicit tables, missing keys).
std::string where(const std::string& file, const toml::node* node, const toml::node* fallback = nullptr);

/// Short type name of a node for messages ("string", "integer", "table", ...).
std::string type_name(const toml::node& node);

// A number for messages: 10 significant digits, "nan"/"inf" spelt out (not std::to_string's
// fixed 6 decimals, which prints 1e-9 as 0.000000).
std::string show(double value);

/// Why `name` is not a safe output file stem ("" if it is): letters, digits, '_', '-', '.';
/// no leading '.', no "..", at most kMaxNameLength characters.
constexpr std::size_t kMaxNameLength = 64;
std::string unsafe_name_reason(std::string_view name);
/// `name` with every character outside the safe set replaced by '_' (and a leading '.'
/// too), truncated to kMaxNameLength; "scene" if nothing is left.
std::string safe_name(std::string_view name);

/// The deepest a key may nest (dotted parts, table headers and inline tables together): the
/// TOML parser recurses once a level, and a 50 000-deep key overflowed its stack.
constexpr std::size_t kMaxKeyDepth = 64;
/// Where TOML `text` nests deeper than kMaxKeyDepth, as "line N", or "" (a scan of the text,
/// outside strings and comments, before the parser sees it).
std::string too_deep_line(std::string_view text);

class Section {
 public:
  Section(std::string file, const toml::table& table, std::string path);

  const std::string& path() const { return path_; }
  std::string key_path(std::string_view key) const;
  const toml::table& table() const { return *table_; }

  /// The node at `key` (nullptr if absent); marks the key as known.
  const toml::node* find(std::string_view key);
  bool has(std::string_view key) { return find(key) != nullptr; }

  double number(std::string_view key);  // required
  double number(std::string_view key, double fallback);
  /// An integer (a whole float such as 1e3 is accepted). Every integer is range-checked:
  /// the plain forms allow [-2^53, 2^53] (what a double holds exactly), the *_in forms
  /// [min, max]; an error names the key, the limits and the value.
  long integer(std::string_view key);
  long integer(std::string_view key, long fallback);
  long integer_in(std::string_view key, long min, long max);
  long integer_in(std::string_view key, long fallback, long min, long max);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key);
  std::string string(std::string_view key, const std::string& fallback);
  /// A string that must be one of `allowed`.
  std::string choice(std::string_view key, std::initializer_list<const char*> allowed,
                     std::optional<std::string> fallback = std::nullopt);
  std::string choice(std::string_view key, const std::vector<const char*>& allowed,
                     std::optional<std::string> fallback = std::nullopt);
  /// An array of exactly `count` numbers (count 0: any length).
  std::vector<double> numbers(std::string_view key, std::size_t count);
  /// A finite number held by `node` (an array element); errors name `key_label`.
  double number_at(const toml::node& node, const std::string& key_label) const;
  std::vector<std::string> strings(std::string_view key);

  /// A number, or a string expression of `variables` checked to parse.
  struct ValueOrExpression {
    std::optional<double> constant;
    std::optional<Expression> expression;
    const toml::node* node = nullptr;
  };
  ValueOrExpression value_or_expression(std::string_view key, const std::vector<std::string>& variables);
  /// Same for an element `node` of an array at `key` (e.g. velocity = ["t", 0]).
  ValueOrExpression value_or_expression(const toml::node& node, const std::string& key_label,
                                        const std::vector<std::string>& variables);

  /// A sub-table (nullopt if absent; Error if `key` is not a table).
  std::optional<Section> subtable(std::string_view key);
  /// An array of tables ([[key]]); empty if absent.
  std::vector<Section> table_array(std::string_view key);

  /// Throws "WHERE: key 'path.key': what; todo" at the key's node (or the section).
  [[noreturn]] void fail(std::string_view key, const std::string& what, const std::string& todo = {}) const;
  [[noreturn]] void fail_at(const toml::node* node, const std::string& key_label, const std::string& what,
                            const std::string& todo = {}) const;

  /// Rejects every key that was never asked for, naming the known ones.
  void finish() const;

 private:
  const toml::node& require(std::string_view key);
  std::string file_;
  const toml::table* table_;
  std::string path_;
  std::set<std::string, std::less<>> known_;
};

}  // namespace stagger::scene_detail
