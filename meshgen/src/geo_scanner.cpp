/// @file geo_scanner.cpp
/// The scan of .geo text for commands that reach outside the mesh (find_outside_command,
/// docs/mesh.md, "Commands that reach outside the mesh").
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "stagger/meshgen.hpp"

namespace stagger::meshgen {
namespace {
// A .geo file is a program: gmsh 4.8's language can run shell commands, write, create and
// merge files, sleep and end the process. These are refused before gmsh runs unless the
// user allows them (GeoOptions::allow_commands); the child's sandbox (child_sandbox.hpp) is
// the second line of defence. The scanner follows gmsh's lexer (Parser/Gmsh.l): comments
// /* */ and //, strings in "..." or '...' without escapes, identifiers [A-Za-z_][A-Za-z0-9_]*,
// numbers, and keywords matched as whole identifiers, case-sensitively.

struct GeoToken {
  enum Kind { identifier, string, number, symbol } kind;
  std::string text;
  int line;
};

std::vector<GeoToken> geo_tokens(const std::string& text) {
  std::vector<GeoToken> tokens;
  const auto alpha = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  std::size_t i = 0;
  int line = 1;
  const std::size_t n = text.size();
  const auto exponent = [&](std::size_t k) {  // length of [Ee][-+]?digit+ at k, or 0
    if (k >= n || (text[k] != 'e' && text[k] != 'E')) return std::size_t{0};
    std::size_t j = k + 1;
    if (j < n && (text[j] == '+' || text[j] == '-')) ++j;
    if (j >= n || !digit(text[j])) return std::size_t{0};
    while (j < n && digit(text[j])) ++j;
    return j - k;
  };
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      const std::size_t close = text.find("*/", i + 2);
      const std::size_t stop = close == std::string::npos ? n : close + 2;
      line += static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(i),
                                          text.begin() + static_cast<std::ptrdiff_t>(stop), '\n'));
      i = stop;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '/') {
      while (i < n && text[i] != '\n') ++i;
    } else if (c == '"' || c == '\'') {
      const std::size_t close = text.find(c, i + 1);
      const std::size_t stop = close == std::string::npos ? n : close;
      tokens.push_back({GeoToken::string, text.substr(i + 1, stop - i - 1), line});
      line += static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(i),
                                          text.begin() + static_cast<std::ptrdiff_t>(stop), '\n'));
      i = stop == n ? n : stop + 1;
    } else if (alpha(c)) {
      std::size_t j = i;
      while (j < n && (alpha(text[j]) || digit(text[j]))) ++j;
      tokens.push_back({GeoToken::identifier, text.substr(i, j - i), line});
      i = j;
    } else if (digit(c) || (c == '.' && i + 1 < n && digit(text[i + 1]))) {
      // Longest of {digit}+, {digit}+"."{digit}*{exp}?, {digit}*"."{digit}+{exp}?, {digit}+{exp}.
      std::size_t j = i;
      while (j < n && digit(text[j])) ++j;
      if (j < n && text[j] == '.') {
        ++j;
        while (j < n && digit(text[j])) ++j;
      }
      j += exponent(j);
      tokens.push_back({GeoToken::number, text.substr(i, j - i), line});
      i = j;
    } else {
      tokens.push_back({GeoToken::symbol, std::string(1, c), line});
      ++i;
    }
  }
  return tokens;
}

/// What a command does, for the message; "" if the word is not refused.
std::string outside_command(const std::string& word) {
  static const std::map<std::string, std::string> commands = {
      {"SystemCall", "runs a shell command"},
      {"System", "runs a shell command"},
      {"NonBlockingSystemCall", "runs a shell command"},
      {"Shell", "runs a shell command"},
      {"OnelabRun", "runs an external program"},
      {"OnelabAction", "drives external programs"},
      {"SendToServer", "talks to an external program"},
      {"Exit", "ends the process"},
      {"Sleep", "pauses gmsh"},
      {"Save", "writes a file"},
      {"Print", "writes a file"},
      {"CreateDir", "creates a directory"},
      {"DeleteFile", "deletes a file"},
      {"RenameFile", "renames a file"},
      {"Plugin", "runs a gmsh plugin (plugins can write files)"},
  };
  const auto it = commands.find(word);
  return it == commands.end() ? std::string() : it->second;
}

void scan_geo_file(const std::filesystem::path& file, std::set<std::filesystem::path>& seen, int depth,
                   std::string& found) {
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(file, ec);
  if (!seen.insert(ec ? file : canonical).second) return;
  std::ifstream in(file, std::ios::binary);
  if (!in) return;  // gmsh reports a missing include itself
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::vector<GeoToken> tokens = geo_tokens(text);
  const std::string name = file.string();
  const auto at = [&](std::size_t k) { return name + ":" + std::to_string(tokens[k].line) + ": "; };
  const auto is_symbol = [&](std::size_t k, char c) {
    return k < tokens.size() && tokens[k].kind == GeoToken::symbol && tokens[k].text[0] == c;
  };
  for (std::size_t k = 0; k < tokens.size() && found.empty(); ++k) {
    if (tokens[k].kind != GeoToken::identifier) continue;
    const std::string& word = tokens[k].text;
    // Option names (Print.Format, Mesh.Algorithm) are not commands.
    if (is_symbol(k + 1, '.') || (k > 0 && is_symbol(k - 1, '.'))) continue;
    if (const std::string what = outside_command(word); !what.empty()) {
      found = at(k) + "'" + word + "' " + what;
      return;
    }
    if (word == "Printf" || word == "Error" || word == "Warning") {
      // Printf(...) > "file" and >> "file" write files.
      std::size_t j = k + 1;
      if (!is_symbol(j, '(')) continue;
      int depth_paren = 0;
      for (; j < tokens.size(); ++j) {
        if (is_symbol(j, '(')) ++depth_paren;
        if (is_symbol(j, ')') && --depth_paren == 0) break;
      }
      if (is_symbol(j + 1, '>')) {
        found = at(k) + "'" + word + "(...) >' writes a file";
        return;
      }
    }
    if (word == "Merge" || word == "MergeWithBoundingBox") {
      // CAD and mesh files are read (a .geo is scanned like an Include); gmsh may run
      // others (e.g. a .py through ONELAB), and a computed name cannot be checked.
      const bool literal = k + 1 < tokens.size() && tokens[k + 1].kind == GeoToken::string && is_symbol(k + 2, ';');
      std::string extension = literal ? std::filesystem::path(tokens[k + 1].text).extension().string() : "";
      std::transform(extension.begin(), extension.end(), extension.begin(),
                     [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
      static const std::set<std::string> readable = {".step", ".stp", ".iges", ".igs", ".brep",
                                                     ".brp",  ".msh", ".stl",  ".geo"};
      if (!literal || !readable.count(extension)) {
        found = at(k) + "'" + word + "' of " +
                (literal ? "a '" + extension + "' file, which gmsh may run" : std::string("a computed file name")) +
                " (stagger allows Merge of .step, .stp, .iges, .igs, .brep, .brp, .msh, .stl and .geo files named "
                "by one string)";
        return;
      }
      if (extension == ".geo") {
        std::filesystem::path merged(tokens[k + 1].text);
        if (merged.is_relative()) merged = file.parent_path() / merged;
        scan_geo_file(merged, seen, depth + 1, found);
      }
      continue;
    }
    if (word == "Include") {
      if (k + 1 >= tokens.size() || tokens[k + 1].kind != GeoToken::string || !is_symbol(k + 2, ';')) {
        found = at(k) + "'Include' with a computed file name cannot be checked; write the name as one string";
        return;
      }
      if (depth > 20) {
        found = at(k) + "'Include' nests more than 20 files deep";
        return;
      }
      std::filesystem::path included(tokens[k + 1].text);
      if (included.is_relative()) included = file.parent_path() / included;
      scan_geo_file(included, seen, depth + 1, found);
    }
  }
}

}  // namespace

std::string find_outside_command(const std::string& path) {
  std::set<std::filesystem::path> seen;
  std::string found;
  scan_geo_file(path, seen, 0, found);
  return found;
}

}  // namespace stagger::meshgen
