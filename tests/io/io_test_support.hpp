#pragma once
// Helpers of the io tests: a tiny Sod-like problem and scratch directories (on the shared
// builders of tests/support/), and a minimal JSON parser (enough to check summary.json is
// well formed) and a .pvd reader.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stagger/problem.hpp"
#include "support/files.hpp"
#include "support/gas_problem.hpp"
#include "support/scratch_directory.hpp"

namespace stagger::io_test {

/// Sod's shock tube on nx x 1 zones of [0,1] x [0,0.1] with walls all round.
inline Problem sod_problem(int nx, double t_end) {
  Problem problem = testing::shock_tube(nx, 1, t_end);
  problem.name = "sod_io";
  return problem;
}

/// A fresh, empty directory for one test (<temp>/stagger_io_<name>_<pid>), removed afterwards.
class ScratchDirectory : public testing::ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& name) : testing::ScratchDirectory("io_" + name) {}
};

using testing::read_text;
using testing::split_lines;

/// Names of files in `directory` that look like leftovers of an interrupted atomic write.
inline std::vector<std::string> temporary_files(const std::filesystem::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp.") != std::string::npos || name.find("stagger-tmp.") != std::string::npos ||
        name.find("write-probe") != std::string::npos) {
      names.push_back(name);
    }
  }
  return names;
}

/// A JSON value; objects keep their keys in order.
struct Json {
  enum class Kind { null, boolean, number, string, array, object } kind = Kind::null;
  double number = 0;
  bool boolean = false;
  std::string text;
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> members;

  bool has(const std::string& key) const {
    for (const auto& [name, value] : members) {
      if (name == key) return true;
    }
    return false;
  }
  const Json& operator[](const std::string& key) const {
    for (const auto& [name, value] : members) {
      if (name == key) return value;
    }
    throw std::runtime_error("missing key " + key);
  }
};

/// Strict enough for our own output: throws std::runtime_error on malformed text.
class JsonParser {
 public:
  explicit JsonParser(std::string text) : text_(std::move(text)) {}
  Json parse() {
    Json value = parse_value();
    skip_space();
    if (position_ != text_.size()) fail("trailing characters");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(position_));
  }
  void skip_space() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_]))) ++position_;
  }
  char peek() {
    skip_space();
    if (position_ >= text_.size()) fail("unexpected end");
    return text_[position_];
  }
  void expect(char ch) {
    if (peek() != ch) fail(std::string("expected '") + ch + "'");
    ++position_;
  }
  bool literal(const std::string& word) {
    if (text_.compare(position_, word.size(), word) == 0) {
      position_ += word.size();
      return true;
    }
    return false;
  }
  std::string parse_string() {
    expect('"');
    std::string out;
    while (true) {
      if (position_ >= text_.size()) fail("unterminated string");
      const char ch = text_[position_++];
      if (ch == '"') return out;
      if (static_cast<unsigned char>(ch) < 0x20) fail("control character in string");
      if (ch != '\\') {
        out += ch;
        continue;
      }
      if (position_ >= text_.size()) fail("bad escape");
      const char escape = text_[position_++];
      switch (escape) {
        case '"':
          out += '"';
          break;
        case '\\':
          out += '\\';
          break;
        case '/':
          out += '/';
          break;
        case 'n':
          out += '\n';
          break;
        case 't':
          out += '\t';
          break;
        case 'r':
          out += '\r';
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'u': {
          if (position_ + 4 > text_.size()) fail("bad \\u escape");
          out += static_cast<char>(std::stoi(text_.substr(position_, 4), nullptr, 16));
          position_ += 4;
          break;
        }
        default:
          fail("bad escape");
      }
    }
  }
  Json parse_value() {
    Json value;
    const char ch = peek();
    if (ch == '{') {
      value.kind = Json::Kind::object;
      ++position_;
      if (peek() == '}') {
        ++position_;
        return value;
      }
      while (true) {
        std::string key = parse_string();
        expect(':');
        value.members.emplace_back(std::move(key), parse_value());
        if (peek() == ',') {
          ++position_;
          continue;
        }
        expect('}');
        return value;
      }
    }
    if (ch == '[') {
      value.kind = Json::Kind::array;
      ++position_;
      if (peek() == ']') {
        ++position_;
        return value;
      }
      while (true) {
        value.items.push_back(parse_value());
        if (peek() == ',') {
          ++position_;
          continue;
        }
        expect(']');
        return value;
      }
    }
    if (ch == '"') {
      value.kind = Json::Kind::string;
      value.text = parse_string();
      return value;
    }
    if (literal("null")) return value;
    if (literal("true") || literal("false")) {
      value.kind = Json::Kind::boolean;
      value.boolean = text_[position_ - 1] == 'e' && text_[position_ - 2] == 'u';
      return value;
    }
    const std::size_t start = position_;
    while (position_ < text_.size() && std::strchr("+-0123456789.eE", text_[position_]) != nullptr) ++position_;
    if (position_ == start) fail("unexpected character");
    value.kind = Json::Kind::number;
    std::size_t used = 0;
    value.number = std::stod(text_.substr(start, position_ - start), &used);
    if (used != position_ - start) fail("bad number");
    return value;
  }

  std::string text_;
  std::size_t position_ = 0;
};

inline Json parse_json_file(const std::string& path) {
  return JsonParser(read_text(path)).parse();
}

/// (timestep, file) of every DataSet in a .pvd, in file order.
inline std::vector<std::pair<double, std::string>> read_pvd(const std::string& path) {
  const std::string text = read_text(path);
  std::vector<std::pair<double, std::string>> entries;
  std::size_t at = 0;
  while ((at = text.find("<DataSet", at)) != std::string::npos) {
    const std::size_t end = text.find("/>", at);
    const std::string element = text.substr(at, end - at);
    const auto attribute = [&](const std::string& name) {
      const std::size_t begin = element.find(name + "=\"") + name.size() + 2;
      return element.substr(begin, element.find('"', begin) - begin);
    };
    entries.emplace_back(std::stod(attribute("timestep")), attribute("file"));
    at = end;
  }
  return entries;
}

}  // namespace stagger::io_test
