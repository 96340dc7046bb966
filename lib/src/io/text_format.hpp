#pragma once
/// @file text_format.hpp
/// Locale-independent number and string formatting shared by the text writers
/// (history.csv, summary.json, .pvd). Internal to lib/src/io, lib/src/output and lib/src/driver.
#include <string>

namespace stagger::io_detail {

/// The shortest text that reads back to exactly `value` (at most 17 significant digits,
/// '.' whatever the locale); "nan"/"inf" as is.
std::string format_double(double value);
/// JSON number: like format_double, but non-finite values become null.
std::string json_number(double value);
/// JSON string literal with quotes, escaping quotes, backslashes and control characters.
std::string json_string(const std::string& text);
/// XML attribute value (without quotes): escapes & < > " '.
std::string xml_attribute(const std::string& text);

}  // namespace stagger::io_detail
