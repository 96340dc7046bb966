/// @file geo_scanner.cpp
/// The scan of .geo text for commands that reach outside the mesh (find_outside_command,
/// docs/mesh.md, "Commands that reach outside the mesh").
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "geo_scanner.hpp"
#include "input_file.hpp"
#include "stagger/error.hpp"
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

/// The tokens of .geo text, one at a time (a file's tokens are never all held: a file of
/// a million ';' would take tens of bytes a character), with a look-ahead of a few tokens.
class GeoLexer {
 public:
  explicit GeoLexer(const std::string& text) : text_(text) {}
  /// The token `k` places ahead (0: the next), or nullptr past the end.
  const GeoToken* peek(std::size_t k) {
    while (ahead_.size() <= k) {
      GeoToken token;
      if (!produce(token)) return nullptr;
      ahead_.push_back(std::move(token));
    }
    return &ahead_[k];
  }
  bool next(GeoToken& token) {
    if (!peek(0)) return false;
    token = std::move(ahead_.front());
    ahead_.pop_front();
    return true;
  }

 private:
  static bool alpha(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
  static bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
  /// Length of [Ee][-+]?digit+ at k, or 0.
  std::size_t exponent(std::size_t k) const {
    const std::size_t n = text_.size();
    if (k >= n || (text_[k] != 'e' && text_[k] != 'E')) return 0;
    std::size_t j = k + 1;
    if (j < n && (text_[j] == '+' || text_[j] == '-')) ++j;
    if (j >= n || !digit(text_[j])) return 0;
    while (j < n && digit(text_[j])) ++j;
    return j - k;
  }
  void count_lines(std::size_t from, std::size_t to) {
    line_ += static_cast<int>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(from),
                                         text_.begin() + static_cast<std::ptrdiff_t>(to), '\n'));
  }
  bool produce(GeoToken& token) {
    const std::string& text = text_;
    const std::size_t n = text.size();
    std::size_t& i = i_;
    while (i < n) {
      const char c = text[i];
      if (c == '\n') {
        ++line_;
        ++i;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++i;
      } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
        const std::size_t close = text.find("*/", i + 2);
        const std::size_t stop = close == std::string::npos ? n : close + 2;
        count_lines(i, stop);
        i = stop;
      } else if (c == '/' && i + 1 < n && text[i + 1] == '/') {
        while (i < n && text[i] != '\n') ++i;
      } else if (c == '"' || c == '\'') {
        const std::size_t close = text.find(c, i + 1);
        const std::size_t stop = close == std::string::npos ? n : close;
        token = {GeoToken::string, text.substr(i + 1, stop - i - 1), line_};
        count_lines(i, stop);
        i = stop == n ? n : stop + 1;
        return true;
      } else if (alpha(c)) {
        std::size_t j = i;
        while (j < n && (alpha(text[j]) || digit(text[j]))) ++j;
        token = {GeoToken::identifier, text.substr(i, j - i), line_};
        i = j;
        return true;
      } else if (digit(c) || (c == '.' && i + 1 < n && digit(text[i + 1]))) {
        // Longest of {digit}+, {digit}+"."{digit}*{exp}?, {digit}*"."{digit}+{exp}?, {digit}+{exp}.
        std::size_t j = i;
        while (j < n && digit(text[j])) ++j;
        if (j < n && text[j] == '.') {
          ++j;
          while (j < n && digit(text[j])) ++j;
        }
        j += exponent(j);
        token = {GeoToken::number, text.substr(i, j - i), line_};
        i = j;
        return true;
      } else {
        token = {GeoToken::symbol, std::string(1, c), line_};
        ++i;
        return true;
      }
    }
    return false;
  }

  const std::string& text_;
  std::size_t i_ = 0;
  int line_ = 1;
  std::deque<GeoToken> ahead_;
};

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

/// The scan of one .geo and the files it includes or merges.
class GeoScan {
 public:
  explicit GeoScan(bool refuse_commands) : refuse_commands_(refuse_commands) {}

  /// The first refused command of `file` or of what it includes, or "". Throws for a file
  /// that cannot be scanned (not a regular file, too large, an include cycle).
  std::string scan(const std::filesystem::path& file) {
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(file, ec);
    const std::filesystem::path key = ec ? file : canonical;
    if (done_.count(key)) return "";
    std::vector<Target> targets;
    {
      // Regular files only, opened without blocking (an Include of a FIFO or /dev/zero).
      InputFile in(file.string(), "geometry file");
      if (in.size() > kMaxFileBytes || total_bytes_ + in.size() > kMaxTotalBytes)
        throw Error(printable(file.string()) + ": the .geo files to scan (this one " + std::to_string(in.size() >> 10) +
                    " KiB) exceed stagger's limit of " + std::to_string(kMaxFileBytes >> 20) + " MiB a file and " +
                    std::to_string(kMaxTotalBytes >> 20) + " MiB in all");
      const std::string text = in.read_all(kMaxFileBytes);
      total_bytes_ += text.size();
      if (std::string found = scan_text(file, text, targets); !found.empty()) return found;
    }
    chain_.push_back(key);
    for (const Target& target : targets)
      if (std::string found = follow(target); !found.empty()) return found;
    chain_.pop_back();
    done_.insert(key);
    return "";
  }

 private:
  static constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{16} << 20;
  static constexpr std::uintmax_t kMaxTotalBytes = std::uintmax_t{64} << 20;

  /// A file that an Include or a Merge names, followed once its file is scanned.
  struct Target {
    std::filesystem::path path;
    std::string at;  // "FILE:LINE: "
    std::string word;
    std::string extension;  // lower case
  };

  std::string follow(const Target& target) {
    const std::string name = printable(target.path.string());
    const std::string problem = file_problem(target.path.string());
    if (problem.rfind("not found", 0) == 0) return "";  // gmsh reports a missing file itself
    if (!problem.empty())
      throw Error(target.at + "'" + target.word + "' of '" + name + "': it " + problem +
                  "; only regular files can be read");
    if (target.extension == ".msh") {
      if (!refuse_commands_) return "";  // an allowed file may run scripts anyway
      try {
        check_msh_file(target.path.string());
      } catch (const Error& error) {
        throw Error(target.at + "'" + target.word +
                    "' of a .msh that is not a mesh gmsh reads as one: " + error.what());
      }
      return "";
    }
    if (target.extension != ".geo") return "";  // CAD and STL files: gmsh's readers
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(target.path, ec);
    const auto cycle = std::find(chain_.begin(), chain_.end(), ec ? target.path : canonical);
    if (cycle != chain_.end()) {
      std::string loop;
      for (auto it = cycle; it != chain_.end(); ++it) loop += printable(it->filename().string()) + " -> ";
      throw Error(target.at + "'" + target.word + "' of '" + name + "' " +
                  (cycle + 1 == chain_.end() ? "includes the file itself" : "includes a file that includes this one") +
                  ": an include cycle (" + loop + printable(target.path.filename().string()) + "); remove the " +
                  target.word);
    }
    if (chain_.size() > 20) throw Error(target.at + "'" + target.word + "' nests more than 20 files deep");
    return scan(target.path);
  }

  /// Scans one file's text; the files it names are added to `targets`.
  std::string scan_text(const std::filesystem::path& file, const std::string& text, std::vector<Target>& targets) {
    GeoLexer lexer(text);
    const std::string name = printable(file.string());
    const auto at = [&](int line) { return name + ":" + std::to_string(line) + ": "; };
    const auto is_symbol = [](const GeoToken* t, char c) {
      return t && t->kind == GeoToken::symbol && t->text[0] == c;
    };
    // Printf(...) > "file" and >> "file" write files: the paren depth at each open Printf.
    std::vector<int> printf_depths;
    int depth = 0;
    bool after_dot = false;
    GeoToken token;
    while (lexer.next(token)) {
      const bool follows_dot = after_dot;
      after_dot = token.kind == GeoToken::symbol && token.text[0] == '.';
      if (token.kind == GeoToken::symbol) {
        if (token.text[0] == '(') ++depth;
        if (token.text[0] == ')') {
          --depth;
          if (!printf_depths.empty() && depth == printf_depths.back()) {
            printf_depths.pop_back();
            if (refuse_commands_ && is_symbol(lexer.peek(0), '>'))
              return at(token.line) + "'Printf(...) >' writes a file";
          }
        }
        continue;
      }
      if (token.kind != GeoToken::identifier) continue;
      const std::string& word = token.text;
      // Option names (Print.Format, Mesh.Algorithm) are not commands.
      if (is_symbol(lexer.peek(0), '.') || follows_dot) continue;
      if (const std::string what = outside_command(word); !what.empty() && refuse_commands_)
        return at(token.line) + "'" + word + "' " + what;
      if ((word == "Printf" || word == "Error" || word == "Warning") && is_symbol(lexer.peek(0), '('))
        printf_depths.push_back(depth);
      const bool merge = word == "Merge" || word == "MergeWithBoundingBox";
      if (!merge && word != "Include") continue;
      const GeoToken* next = lexer.peek(0);
      const bool literal = next && next->kind == GeoToken::string && is_symbol(lexer.peek(1), ';');
      if (!literal) {
        if (!refuse_commands_) continue;
        return at(token.line) +
               (merge ? "'" + word +
                            "' of a computed file name (stagger allows Merge of .step, .stp, .iges, .igs, .brep, "
                            ".brp, .msh, .stl and .geo files named by one string)"
                      : std::string("'Include' with a computed file name cannot be checked; write the name as "
                                    "one string"));
      }
      std::filesystem::path target(next->text);
      if (target.is_relative()) target = file.parent_path() / target;
      const std::string raw = target.extension().string();
      std::string extension = raw;
      std::transform(extension.begin(), extension.end(), extension.begin(),
                     [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
      std::string upper = raw;
      std::transform(upper.begin(), upper.end(), upper.begin(),
                     [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
      if (merge) {
        // gmsh picks its CAD and STL readers by the extension, in lower or upper case; any
        // other file (a mixed-case extension too) it runs as a script unless it starts like
        // a mesh (checked in follow).
        static const std::set<std::string> readable = {".step", ".stp", ".iges", ".igs", ".brep",
                                                       ".brp",  ".msh", ".stl",  ".geo"};
        if (refuse_commands_ && (!readable.count(extension) || (raw != extension && raw != upper)))
          return at(token.line) + "'" + word + "' of a '" + printable(raw) +
                 "' file, which gmsh may run (stagger allows Merge of .step, .stp, .iges, .igs, .brep, .brp, "
                 ".msh, .stl and .geo files named by one string)";
      } else {
        extension = ".geo";  // an Include is a .geo whatever its name
      }
      targets.push_back({target, at(token.line), word, extension});
    }
    return "";
  }

  bool refuse_commands_;
  std::set<std::filesystem::path> done_;
  std::vector<std::filesystem::path> chain_;
  std::uintmax_t total_bytes_ = 0;
};

}  // namespace

std::string find_outside_command(const std::string& path) {
  return scan_geo(path, true);
}

std::string scan_geo(const std::string& path, bool refuse_commands) {
  if (file_problem(path).rfind("not found", 0) == 0) return "";  // the readers say so
  return GeoScan(refuse_commands).scan(path);
}

}  // namespace stagger::meshgen
