#pragma once
// The building blocks of the option tables (stagger/option_table.hpp): rows made from pointers
// to members, and the definitions of Option's and OptionTable's members. An option set's table
// is defined where its physics lives (lib/src/hydro/option_table.cpp, a strength model's file
// in lib/src/strength/), which instantiates Option<S> and OptionTable<S> for its struct S.
#include <climits>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "stagger/error.hpp"
#include "stagger/option_table.hpp"

namespace stagger {

namespace option_rows {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A number for messages and docs: 10 significant digits, like the scene reader's show().
inline std::string number_text(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

// ---- rows from pointers to members ----

template <class Member>
struct MemberTraits;
template <class Object, class Value>
struct MemberTraits<Value Object::*> {
  using object = Object;
  using value = Value;
};
template <auto Member>
using ObjectOf = typename MemberTraits<decltype(Member)>::object;
template <auto Member>
using ValueOf = typename MemberTraits<decltype(Member)>::value;

template <auto Member>
double get_member(const ObjectOf<Member>& object) {
  if constexpr (std::is_enum_v<ValueOf<Member>>)
    return static_cast<double>(static_cast<int>(object.*Member));
  else
    return static_cast<double>(object.*Member);
}

template <auto Member>
void set_member(ObjectOf<Member>& object, double value) {
  using Value = ValueOf<Member>;
  if constexpr (std::is_enum_v<Value>)
    object.*Member = static_cast<Value>(static_cast<int>(value));
  else if constexpr (std::is_same_v<Value, bool>)
    object.*Member = value != 0;
  else
    object.*Member = static_cast<Value>(value);
}

template <auto Member>
Option<ObjectOf<Member>> row(const char* key, OptionType type, const char* unit, const char* doc) {
  Option<ObjectOf<Member>> option;
  option.key = key;
  option.type = type;
  option.get = &get_member<Member>;
  option.set = &set_member<Member>;
  option.unit = unit;
  option.doc = doc;
  return option;
}

inline OptionRange at_least(double low) {
  return {low, kInfinity, false, true};
}
inline OptionRange above(double low) {
  return {low, kInfinity, true, true};
}
inline const OptionRange kAnyValue{};

template <auto Member>
Option<ObjectOf<Member>> number(const char* key, OptionRange range, const char* unit, const char* doc) {
  static_assert(std::is_same_v<ValueOf<Member>, double>);
  auto option = row<Member>(key, OptionType::number, unit, doc);
  option.range = range;
  return option;
}

template <auto Member>
Option<ObjectOf<Member>> required_number(const char* key, OptionRange range, const char* unit, const char* doc) {
  auto option = number<Member>(key, range, unit, doc);
  option.required = true;
  return option;
}

template <auto Member>
Option<ObjectOf<Member>> integer(const char* key, OptionRange range, const char* unit, const char* doc) {
  using Value = ValueOf<Member>;
  static_assert(std::is_integral_v<Value> && !std::is_same_v<Value, bool>);
  auto option = row<Member>(key, OptionType::integer, unit, doc);
  option.range = range;
  option.integer_max = static_cast<double>(std::numeric_limits<Value>::max());
  return option;
}

template <auto Member>
Option<ObjectOf<Member>> flag(const char* key, const char* doc) {
  static_assert(std::is_same_v<ValueOf<Member>, bool>);
  return row<Member>(key, OptionType::flag, "-", doc);
}

template <auto Member>
Option<ObjectOf<Member>> choice(const char* key, std::vector<const char*> names, const char* doc) {
  static_assert(std::is_enum_v<ValueOf<Member>>);
  auto option = row<Member>(key, OptionType::choice, "-", doc);
  option.choices = std::move(names);
  return option;
}

}  // namespace option_rows

// ---- Option ----

template <class Options>
std::string Option<Options>::value_text(double value) const {
  switch (type) {
    case OptionType::flag:
      return value != 0 ? "true" : "false";
    case OptionType::choice: {
      const auto index = static_cast<std::size_t>(value);
      return value >= 0 && index < choices.size() ? std::string("\"") + choices[index] + "\""
                                                  : option_rows::number_text(value);
    }
    case OptionType::integer: {
      std::ostringstream out;
      out << static_cast<long long>(value);
      return out.str();
    }
    case OptionType::number:
      break;
  }
  return option_rows::number_text(value);
}

template <class Options>
std::string Option<Options>::check(double value) const {
  switch (type) {
    case OptionType::flag:
      return {};
    case OptionType::choice:
      if (value >= 0 && static_cast<std::size_t>(value) < choices.size()) return {};
      return "must be one of " + range_text() + ", got " + option_rows::number_text(value);
    case OptionType::integer:
      if (range.contains(value) && value > integer_max)
        return "must be at most " + value_text(integer_max) + ", got " + option_rows::number_text(value);
      [[fallthrough]];
    case OptionType::number:
      if (!range.contains(value)) return "must be " + range.text() + ", got " + option_rows::number_text(value);
      return {};
  }
  return {};
}

template <class Options>
std::string Option<Options>::range_text() const {
  switch (type) {
    case OptionType::flag:
      return "true or false";
    case OptionType::choice: {
      std::string text;
      for (std::size_t k = 0; k < choices.size(); ++k)
        text += std::string(k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + "\"" + choices[k] + "\"";
      return text;
    }
    case OptionType::integer:
    case OptionType::number: {
      const std::string text = range.text();
      return text.rfind("in ", 0) == 0 ? text.substr(3) : text;
    }
  }
  return {};
}

// ---- OptionTable ----

template <class Options>
void OptionTable<Options>::validate(const Options& values, const std::string& where) const {
  for (const auto& option : options) {
    const std::string problem = option.check(option.get(values));
    if (!problem.empty())
      throw Error((where.empty() ? std::string(section) + "." : where) + option.key + ": " + problem + "; " +
                  option.doc);
  }
}

template <class Options>
std::string OptionTable<Options>::echo(const Options& values) const {
  std::string text;
  for (const auto& option : options)
    text += (text.empty() ? "" : ", ") + std::string(option.key) + " = " + option.value_text(option.get(values));
  return text;
}

template <class Options>
std::string OptionTable<Options>::markdown() const {
  std::string text = "| key | type | default | admissible values | unit | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& option : options) {
    const char* type = option.type == OptionType::number    ? "number"
                       : option.type == OptionType::integer ? "integer"
                       : option.type == OptionType::flag    ? "bool"
                                                            : "string";
    // The default cell appended, not built by "`" + text: GCC 12's -Wrestrict false positive.
    std::string default_cell = "required";
    if (!option.required) default_cell = std::string("`").append(option.value_text(option.default_value())).append("`");
    text += "| `" + std::string(option.key) + "` | " + type + " | " + default_cell + " | " + option.range_text() +
            " | " + option.unit + " | " + option.doc + " |\n";
  }
  return text;
}

}  // namespace stagger
