/// @file msh_check.cpp
/// The check of a .msh file's text before gmsh reads it (check_msh_file, meshgen.hpp).
/// gmsh decides by the first line, not the extension, whether a file is a mesh: anything
/// that does not start with $MeshFormat (or an old header) is run as a .geo script, without
/// the scan for commands (geo_scanner.cpp). And gmsh reads as many entries as a section's
/// count says, so a low count drops the rest of the section without a word.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "input_file.hpp"
#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::meshgen {
namespace {

/// The lines of a file, read in blocks (a mesh may be large); trailing white space removed.
class LineReader {
 public:
  LineReader(InputFile& file, const std::string& path) : file_(file), path_(path) {}
  /// The next line, or false at the end of the file.
  bool next(std::string& line) {
    for (;;) {
      const std::size_t end = buffer_.find('\n', position_);
      if (end != std::string::npos || at_end_) {
        if (end == std::string::npos && position_ >= buffer_.size()) return false;
        const std::size_t stop = end == std::string::npos ? buffer_.size() : end;
        line.assign(buffer_, position_, stop - position_);
        position_ = end == std::string::npos ? buffer_.size() : end + 1;
        ++number_;
        const std::size_t last = line.find_last_not_of(" \t\r\f\v");
        line.erase(last == std::string::npos ? 0 : last + 1);
        return true;
      }
      if (buffer_.size() - position_ > kMaxLine)
        throw Error(path_ + ":" + std::to_string(number_ + 1) + ": a line longer than 1 MiB; not a gmsh mesh");
      buffer_.erase(0, position_);
      position_ = 0;
      char block[65536];
      const std::size_t n = file_.read(block, sizeof block);
      if (n == 0) at_end_ = true;
      buffer_.append(block, n);
    }
  }
  /// The number of the line last returned (from 1).
  int number() const { return number_; }

 private:
  static constexpr std::size_t kMaxLine = 1 << 20;
  InputFile& file_;
  std::string path_, buffer_;
  std::size_t position_ = 0;
  bool at_end_ = false;
  int number_ = 0;
};

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string word; in >> word;) out.push_back(word);
  return out;
}

/// A line for a message: quoted, at most 60 characters, control characters and other
/// bytes outside printable ASCII as \xNN (they must not reach the terminal).
std::string quoted(const std::string& line) {
  std::string text(1, '\'');
  text += printable(line.substr(0, 60));
  return text.append(line.size() > 60 ? "...'" : "'");
}

/// `text` as a count (a non-negative integer below 2^63), or -1.
long long count_of(const std::string& text) {
  if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stoll(text);
}

class MshCheck {
 public:
  MshCheck(const std::string& path, InputFile& file) : path_(path), in_(file, path) {}

  void run() {
    std::string line;
    if (!in_.next(line) || line != "$MeshFormat")
      fail(1, std::string(line.empty() ? "the file is empty or" : "it") +
                  " does not start with $MeshFormat, so it is not a gmsh mesh (gmsh would run it as a .geo "
                  "script); export the mesh from gmsh as MSH 2.2 or 4.1");
    const bool binary = read_format();
    while (next_section(line)) {
      const std::string name = line.substr(1);
      if (name == "PhysicalNames") {
        counted_section(name, 1);
      } else if (binary) {
        return;  // the other sections of a binary file are binary: gmsh checks them
      } else if (name == "Nodes") {
        if (version_ < 4)
          counted_section(name, 1);
        else
          block_section(name, version_ == 40 ? 1 : 2);
      } else if (name == "Elements") {
        if (version_ < 4)
          counted_section(name, 1);
        else
          block_section(name, 1);
      } else {
        skip_section(name);
      }
    }
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(line) + ": " + what);
  }

  /// The version line; true for a binary file.
  bool read_format() {
    std::string line;
    if (!in_.next(line)) fail(in_.number() + 1, "the file ends inside $MeshFormat");
    const std::vector<std::string> w = words(line);
    static const std::set<std::string> versions = {"2", "2.0", "2.1", "2.2", "4", "4.0", "4.1"};
    if (w.size() != 3 || !versions.count(w[0]) || (w[1] != "0" && w[1] != "1"))
      fail(in_.number(), "$MeshFormat " + quoted(line) +
                             " is not a format gmsh 4.8 reads (version 2.2, 4.0 or 4.1, file type 0 (ASCII) or 1 "
                             "(binary), data size)");
    version_ = w[0][0] == '2' ? 2 : w[0] == "4.1" ? 41 : 40;
    const bool binary = w[1] == "1";
    for (int k = 0; k < 3; ++k) {  // a binary file has one binary integer (1) before the end
      if (!in_.next(line)) break;
      if (line == "$EndMeshFormat") return binary;
      if (!binary) break;
    }
    fail(in_.number(), "$MeshFormat is not closed by $EndMeshFormat");
  }

  /// The next section's opening line ("$Name"); false at the end of the file.
  bool next_section(std::string& line) {
    while (in_.next(line))
      if (!line.empty() && line[0] == '$') {
        if (line.rfind("$End", 0) == 0) fail(in_.number(), "'" + line + "' closes no section");
        return true;
      }
    return false;
  }

  void skip_section(const std::string& name) {
    // (gmsh skips a section it does not know to the next '$' line; a missing end is its own)
    std::string line;
    while (in_.next(line))
      if (line == "$End" + name) return;
  }

  /// A section of a count line and `lines` lines an entry ($PhysicalNames, MSH 2 $Nodes and
  /// $Elements).
  void counted_section(const std::string& name, int lines) {
    const int opened = in_.number();
    std::string line;
    if (!next_entry(line, name, opened)) fail(opened, "$" + name + " has no count line");
    const std::vector<std::string> w = words(line);
    const long long count = w.size() == 1 ? count_of(w[0]) : -1;
    const int count_line = in_.number();
    if (count < 0) fail(count_line, "the $" + name + " count " + quoted(line) + " is not a count");
    long long entries = 0;
    while (next_entry(line, name, opened)) ++entries;
    if (entries != count * lines) {
      std::ostringstream what;
      what << '$' << name << " says " << count << " entries but " << entries / lines << " follow (up to "
           << end_of(name) << "); gmsh would "
           << (entries > count * lines ? "drop the rest without a word" : "misread the file") << ": fix the count";
      fail(count_line, what.str());
    }
  }

  /// A MSH 4 section of blocks: a header "blocks total ...", then per block a line whose last
  /// number is its entry count, and `lines` lines an entry ($Nodes: tags then coordinates).
  void block_section(const std::string& name, int lines) {
    const int opened = in_.number();
    std::string line;
    if (!next_entry(line, name, opened)) fail(opened, "$" + name + " has no header line");
    std::vector<std::string> w = words(line);
    const int header_line = in_.number();
    const long long blocks = w.size() >= 2 ? count_of(w[0]) : -1, total = w.size() >= 2 ? count_of(w[1]) : -1;
    if (blocks < 0 || total < 0)
      fail(header_line, "the $" + name + " header " + quoted(line) + " does not start with two counts");
    long long seen_blocks = 0, seen_entries = 0;
    int block_line = 0;
    while (next_entry(line, name, opened)) {
      w = words(line);
      const long long n = w.size() == 4 ? count_of(w[3]) : -1;
      if (n < 0)
        fail(in_.number(), quoted(line) + " is not a $" + name + " block header" +
                               (seen_blocks > 0 ? " (is the count of the block at line " + std::to_string(block_line) +
                                                      " lower than its entries?)"
                                                : std::string()));
      block_line = in_.number();
      ++seen_blocks;
      seen_entries += n;
      for (long long k = 0; k < n * lines; ++k)
        if (!next_entry(line, name, opened)) {
          std::ostringstream what;
          what << "the $" << name << " block says " << n << " entries but they end first (at " << end_of(name)
               << "): fix the count";
          fail(block_line, what.str());
        }
    }
    if (seen_blocks != blocks || seen_entries != total) {
      std::ostringstream what;  // (GCC 12 warns falsely about "..." + std::string&& here)
      what << '$' << name << " says " << blocks << " blocks of " << total << " entries but " << seen_blocks
           << " blocks of " << seen_entries << " follow (up to " << end_of(name)
           << "); gmsh would misread the file: fix the counts";
      fail(header_line, what.str());
    }
  }

  /// The next non-blank line of section `name`, or false at its end line.
  bool next_entry(std::string& line, const std::string& name, int opened) {
    while (in_.next(line)) {
      if (line.find_first_not_of(" \t") == std::string::npos) continue;
      if (line[0] == '$') {
        if (line == "$End" + name) return false;
        fail(in_.number(), quoted(line) + " inside $" + name + " (opened at line " + std::to_string(opened) +
                               "); the section is cut short or its count is wrong");
      }
      return true;
    }
    // gmsh reads a section to its count and needs no end line after the last one: a file
    // that ends there is checked by its count alone.
    ended_ = true;
    return false;
  }

  /// Where a section's entries ended, for messages.
  std::string end_of(const std::string& name) const {
    return ended_ ? "the end of the file at line " + std::to_string(in_.number())
                  : "$End" + name + " at line " + std::to_string(in_.number());
  }

  std::string path_;
  LineReader in_;
  int version_ = 2;     // 2, 40 or 41
  bool ended_ = false;  // the file ended inside a section
};

}  // namespace

void check_msh_file(const std::string& path) {
  InputFile file(path, "mesh file");
  MshCheck(path, file).run();
}

}  // namespace stagger::meshgen
