#include "io/text_format.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace stagger::io_detail {

std::string format_double(double value) {
  // std::to_chars ignores the C locale, unlike printf: a decimal point is always '.'.
  // Without a precision it gives the shortest text that reads back to the same double
  // (at most 17 significant digits): 0.004, not 0.0040000000000000001.
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

std::string json_number(double value) {
  if (!std::isfinite(value)) return "null";
  return format_double(value);
}

std::string json_string(const std::string& text) {
  std::string out;
  out.reserve(text.size() + 2);
  out += '"';
  for (const char ch : text) {
    const auto code = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (code < 0x20) {
          std::array<char, 8> escaped{};
          std::snprintf(escaped.data(), escaped.size(), "\\u%04x", static_cast<unsigned>(code));
          out += escaped.data();
        } else {
          out += ch;
        }
    }
  }
  out += '"';
  return out;
}

std::string xml_attribute(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

}  // namespace stagger::io_detail
