/// @file gmsh_io.cpp
/// .geo and .msh files through the gmsh 4.8 C++ API, and MSH 4.1 output. gmsh is a global
/// singleton that is not thread-safe: every use holds one mutex and one RAII session
/// (initialize ... finalize), so no gmsh state leaks from one call to the next. Reading and
/// meshing run in a forked child process (docs/mesh.md, "gmsh in a child process").
#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <mutex>
#include <new>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include <fcntl.h>
#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/sched.h>
#include <linux/seccomp.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "gmsh_api.hpp"
#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::meshgen {
namespace {
// Whether the child's address-space limit is set (not in AddressSanitizer builds, below): only
// then can a crash be put down to the memory limit.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kMemoryLimitApplies = false;
#else
constexpr bool kMemoryLimitApplies = true;
#endif

// MSH element types (gmsh reference manual, "MSH file format").
constexpr int kLine2 = 1, kTriangle3 = 2, kQuad4 = 3;

std::mutex& gmsh_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::string number_text(double value) {
  std::ostringstream s;
  s.precision(17);
  s << value;
  return s.str();
}

bool env_flag(const char* name) {
  const char* value = std::getenv(name);
  return value && *value && *value != '0';
}

/// One gmsh session: initialize, quiet terminal, logger on; finalize on destruction.
/// gm::initialize sets OpenMP to gmsh's own thread count (1): the caller's setting is
/// restored afterwards, so an in-process session does not leave stagger single-threaded.
class GmshSession {
 public:
  GmshSession() : threads_(omp_get_max_threads()) {
    gm::initialize(0, nullptr, false);
    // STAGGER_GMSH_VERBOSE=1 shows gmsh's own messages (debugging a .geo).
    gm::option::setNumber("General.Terminal", env_flag("STAGGER_GMSH_VERBOSE") ? 1 : 0);
    // Errors are read from the logger after each step: with the default (2) gmsh throws
    // from inside its mesher, where an exception can end in std::terminate.
    gm::option::setNumber("General.AbortOnError", 0);
    gm::logger::start();
  }
  ~GmshSession() {
    try {
      gm::logger::stop();
      gm::finalize();
    } catch (...) {  // a destructor must not throw; gmsh throws std::string
    }
    omp_set_num_threads(threads_);
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// The first and last errors gmsh logged since the session started, or "".
  static std::string errors() {
    std::vector<std::string> log;
    gm::logger::get(log);
    std::string first;
    for (const auto& line : log)
      if (line.rfind("Error", 0) == 0) {
        first = line;
        break;
      }
    std::string last;
    gm::logger::getLastError(last);
    for (std::string* text : {&first, &last}) {
      for (const char* prefix : {"Error   : ", "Error : ", "Error: "})
        if (text->rfind(prefix, 0) == 0) text->erase(0, std::string(prefix).size());
    }
    std::string text = first.empty()                                           ? last
                       : last.empty() || first.find(last) != std::string::npos ? first
                                                                               : first + " ... " + last;
    // gmsh quotes the offending text of the file: control characters (a vertical tab, an
    // escape sequence) must not reach the user's terminal or split the one error line.
    std::string clean;
    for (const char ch : text) {
      const auto byte = static_cast<unsigned char>(ch);
      if (byte < 0x20 || byte == 0x7f) {
        char escaped[8];
        std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
        clean += escaped;
      } else {
        clean += ch;
      }
    }
    return clean;
  }

 private:
  int threads_;
};

/// Runs `body` in a gmsh session, turning gmsh's std::string exceptions and logged errors
/// into stagger::Error naming the file. std::bad_alloc passes through (the caller knows
/// the memory limit).
template <class Body>
auto in_gmsh_session(const std::string& path, Body body) {
  GmshSession session;
  try {
    return body();
  } catch (const std::string& message) {
    const std::string logged = GmshSession::errors();
    throw Error("gmsh failed on " + path + ": " + (logged.empty() ? message : logged));
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    // A corrupt count (e.g. an unknown element type) also ends here, after gmsh logged it.
    const std::string logged = GmshSession::errors();
    if (logged.empty()) throw;
    throw Error("gmsh failed on " + path + ": " + logged + "; the file is corrupt or not a valid MSH/.geo file");
  } catch (const std::exception& failure) {
    // gmsh's readers trust the file: a corrupt count or element type ends in e.g.
    // std::bad_array_new_length (found by fuzzing read_msh).
    const std::string logged = GmshSession::errors();
    throw Error("gmsh failed on " + path + ": " + (logged.empty() ? std::string(failure.what()) : logged) +
                "; the file is corrupt or not a valid MSH/.geo file");
  }
}

template <class Body>
auto with_gmsh(const std::string& path, Body body) {
  std::lock_guard lock(gmsh_mutex());
  try {
    return in_gmsh_session(path, body);
  } catch (const std::bad_alloc&) {
    throw Error("gmsh ran out of memory on " + path);
  }
}

// --- .geo commands that reach outside the mesh -----------------------------------------
// A .geo file is a program: gmsh 4.8's language can run shell commands, write, create and
// merge files, sleep and end the process. These are refused before gmsh runs unless the
// user allows them (GeoOptions::allow_commands); the child's sandbox (below) is the second
// line of defence. The scanner follows gmsh's lexer (Parser/Gmsh.l): comments /* */ and
// //, strings in "..." or '...' without escapes, identifiers [A-Za-z_][A-Za-z0-9_]*,
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

// --- Reading and meshing in a child process ---------------------------------------------
// gmsh 4.8 trusts its input: a corrupt .msh, or a .geo that sets Mesh.Algorithm = 8 on a
// surface, can crash it (segfault, double free); a .geo can loop for ever or exhaust
// memory; and gm::initialize resets OpenMP to one thread. gmsh therefore runs in a forked
// child that sends the soup (or the error) back through a pipe, under an address-space limit
// (setrlimit RLIMIT_AS) and a wall-time limit (the parent kills it), with stdout silenced
// unless STAGGER_GMSH_VERBOSE=1. Without allow_commands the child also runs in a seccomp
// sandbox that refuses to start programs, open files for writing, or create, delete or
// rename files. STAGGER_GMSH_IN_PROCESS=1 runs gmsh in-process (debugging; no limits).

class Packer {
 public:
  template <class T>
  void value(const T& v) {
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T>
  void vector(const std::vector<T>& v) {
    value<std::uint64_t>(v.size());
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void string(const std::string& s) {
    value<std::uint64_t>(s.size());
    out_ += s;
  }
  void strings(const std::vector<std::string>& v) {
    value<std::uint64_t>(v.size());
    for (const auto& s : v) string(s);
  }
  const std::string& bytes() const { return out_; }

 private:
  std::string out_;
};

class Unpacker {
 public:
  explicit Unpacker(const std::string& in) : in_(in) {}
  template <class T>
  T value() {
    T v{};
    take(&v, sizeof(T));
    return v;
  }
  template <class T>
  std::vector<T> vector() {
    const auto n = value<std::uint64_t>();
    if (n > (in_.size() - pos_) / sizeof(T)) throw std::runtime_error("truncated");
    std::vector<T> v(n);
    take(v.data(), n * sizeof(T));
    return v;
  }
  std::string string() {
    const auto n = value<std::uint64_t>();
    if (n > in_.size() - pos_) throw std::runtime_error("truncated");
    std::string s = in_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::vector<std::string> strings() {
    const auto n = value<std::uint64_t>();
    if (n > in_.size() - pos_) throw std::runtime_error("truncated");
    std::vector<std::string> v;
    for (std::uint64_t i = 0; i < n; ++i) v.push_back(string());
    return v;
  }
  bool at_end() const { return pos_ == in_.size(); }

 private:
  void take(void* to, std::size_t n) {
    if (n > in_.size() - pos_) throw std::runtime_error("truncated");
    std::memcpy(to, in_.data() + pos_, n);
    pos_ += n;
  }
  const std::string& in_;
  std::size_t pos_ = 0;
};

std::string pack(const PolygonSoup& soup) {
  Packer p;
  p.value<std::uint8_t>(0);
  p.vector(soup.x);
  p.vector(soup.y);
  p.vector(soup.polygon_begin);
  p.vector(soup.polygon_points);
  p.vector(soup.polygon_region);
  p.strings(soup.region_names);
  p.value<std::uint64_t>(soup.tagged_edges.size());
  for (const auto& e : soup.tagged_edges) {
    p.value(e.a);
    p.value(e.b);
    p.value(e.tag);
  }
  p.strings(soup.tag_names);
  p.string(soup.source);
  p.value(soup.unassigned_elements);
  p.strings(soup.notes);
  return p.bytes();
}

PolygonSoup unpack(const std::string& bytes) {
  Unpacker u(bytes);
  if (u.value<std::uint8_t>() != 0) throw Error(u.string());
  PolygonSoup soup;
  soup.x = u.vector<double>();
  soup.y = u.vector<double>();
  soup.polygon_begin = u.vector<std::int64_t>();
  soup.polygon_points = u.vector<std::int64_t>();
  soup.polygon_region = u.vector<int>();
  soup.region_names = u.strings();
  const auto nedges = u.value<std::uint64_t>();
  if (nedges > bytes.size()) throw std::runtime_error("truncated");
  for (std::uint64_t e = 0; e < nedges; ++e) {
    TaggedEdge edge;
    edge.a = u.value<std::int64_t>();
    edge.b = u.value<std::int64_t>();
    edge.tag = u.value<int>();
    soup.tagged_edges.push_back(edge);
  }
  soup.tag_names = u.strings();
  soup.source = u.string();
  soup.unassigned_elements = u.value<std::int64_t>();
  soup.notes = u.strings();
  if (!u.at_end()) throw std::runtime_error("trailing data");
  return soup;
}

bool write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

/// The sandbox of a child that runs gmsh on untrusted input: a seccomp filter that makes
/// the system calls that start programs, open files for writing, or create, delete, rename
/// or change files fail with EPERM (threads may still be created). Returns false where it
/// is not supported; the time and memory limits still apply there.
bool install_sandbox() {
#if defined(__x86_64__) || defined(__aarch64__)
#if defined(__x86_64__)
  constexpr std::uint32_t arch = AUDIT_ARCH_X86_64;
#else
  constexpr std::uint32_t arch = AUDIT_ARCH_AARCH64;
#endif
  enum Label { deny, no_system_call, open_check, openat_check, clone_check, kill };
  std::vector<sock_filter> code;
  std::vector<std::pair<std::size_t, Label>> fixups;
  std::map<Label, std::size_t> labels;
  const auto stmt = [&](std::uint16_t op, std::uint32_t k) { code.push_back(BPF_STMT(op, k)); };
  const auto jump_if = [&](std::uint16_t test, std::uint32_t k, Label to) {
    code.push_back(BPF_JUMP(BPF_JMP | test | BPF_K, k, 0, 0));
    fixups.emplace_back(code.size() - 1, to);
  };
  const auto label = [&](Label l) { labels[l] = code.size(); };
  const auto argument = [](int i) {
    return static_cast<std::uint32_t>(offsetof(seccomp_data, args) + 8 * static_cast<std::size_t>(i));
  };
  constexpr std::uint32_t write_flags = O_WRONLY | O_RDWR | O_CREAT | O_TRUNC | O_APPEND;
  stmt(BPF_LD | BPF_W | BPF_ABS, static_cast<std::uint32_t>(offsetof(seccomp_data, arch)));
  code.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, arch, 1, 0));
  stmt(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS);
  stmt(BPF_LD | BPF_W | BPF_ABS, static_cast<std::uint32_t>(offsetof(seccomp_data, nr)));
#if defined(__x86_64__)
  jump_if(BPF_JGE, 0x40000000U, kill);  // the x32 ABI: not used by stagger
#endif
  const long denied[] = {
    SYS_execve,
    SYS_execveat,
    SYS_unlinkat,
    SYS_renameat,
    SYS_mkdirat,
    SYS_linkat,
    SYS_symlinkat,
    SYS_fchmod,
    SYS_fchmodat,
    SYS_fchown,
    SYS_fchownat,
    SYS_truncate,
    SYS_mknodat,
    SYS_socket,
    SYS_ptrace,
    SYS_kill,
    SYS_process_vm_writev,
    SYS_open_by_handle_at,
#if defined(__x86_64__)
    SYS_fork,
    SYS_vfork,
    SYS_creat,
    SYS_unlink,
    SYS_rmdir,
    SYS_rename,
    SYS_mkdir,
    SYS_link,
    SYS_symlink,
    SYS_chmod,
    SYS_chown,
    SYS_lchown,
    SYS_mknod,
#endif
#ifdef SYS_renameat2
    SYS_renameat2,
#endif
  };
  for (const long nr : denied) jump_if(BPF_JEQ, static_cast<std::uint32_t>(nr), deny);
#ifdef SYS_clone3
  jump_if(BPF_JEQ, SYS_clone3, no_system_call);  // glibc then falls back to clone
#endif
#ifdef SYS_openat2
  jump_if(BPF_JEQ, SYS_openat2, no_system_call);
#endif
#if defined(__x86_64__)
  jump_if(BPF_JEQ, SYS_open, open_check);
#endif
  jump_if(BPF_JEQ, SYS_openat, openat_check);
  jump_if(BPF_JEQ, SYS_clone, clone_check);
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ALLOW);
  label(deny);
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | (EPERM & SECCOMP_RET_DATA));
  label(no_system_call);
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | (ENOSYS & SECCOMP_RET_DATA));
  label(kill);
  stmt(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS);
  label(open_check);  // open(path, flags, mode)
  stmt(BPF_LD | BPF_W | BPF_ABS, argument(1));
  code.push_back(BPF_JUMP(BPF_JMP | BPF_JSET | BPF_K, write_flags, 1, 0));
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ALLOW);
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | (EPERM & SECCOMP_RET_DATA));
  label(openat_check);  // openat(dirfd, path, flags, mode)
  stmt(BPF_LD | BPF_W | BPF_ABS, argument(2));
  code.push_back(BPF_JUMP(BPF_JMP | BPF_JSET | BPF_K, write_flags, 1, 0));
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ALLOW);
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | (EPERM & SECCOMP_RET_DATA));
  label(clone_check);  // threads (CLONE_THREAD) yes, processes no
  stmt(BPF_LD | BPF_W | BPF_ABS, argument(0));
  code.push_back(BPF_JUMP(BPF_JMP | BPF_JSET | BPF_K, CLONE_THREAD, 1, 0));
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | (EPERM & SECCOMP_RET_DATA));
  stmt(BPF_RET | BPF_K, SECCOMP_RET_ALLOW);
  for (const auto& [at, to] : fixups) {  // forward jumps only (BPF has no others)
    const std::size_t offset = labels.at(to) - at - 1;
    if (labels.at(to) <= at || offset > 255) return false;
    code[at].jt = static_cast<std::uint8_t>(offset);
  }
  sock_fprog program{};
  program.len = static_cast<unsigned short>(code.size());
  program.filter = code.data();
  if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return false;
  return ::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &program) == 0;
#else
  return false;
#endif
}

/// Limits and wording of one child run.
struct ChildRun {
  std::string path;        ///< the user's file, for messages
  std::string doing;       ///< "meshing" or "reading"
  double seconds = 0;      ///< wall-time limit, 0: none
  double mib = 0;          ///< address-space limit, 0: none
  bool sandbox = true;     ///< install the seccomp filter
  std::string crash_hint;  ///< appended to a crash message
};

std::string limit_text(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

/// The child's answer when operator new fails: built before gmsh runs, written without
/// allocating.
const std::string* out_of_memory_message = nullptr;

void out_of_memory() {
  if (out_of_memory_message) write_all(3, *out_of_memory_message);
  ::_exit(4);
}

[[noreturn]] void child_main(int out_fd, const ChildRun& run, const std::function<PolygonSoup()>& read) {
  // Die with the parent (e.g. stagger interrupted), in a process group of our own so that
  // the time limit also ends whatever the .geo started (allowed commands).
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  ::setpgid(0, 0);
  const int null_fd = ::open("/dev/null", O_RDWR);
  if (null_fd >= 0) {
    ::dup2(null_fd, STDIN_FILENO);
    // Quiet unless asked: also stderr, where glibc reports e.g. a double free in gmsh
    // (the parent's error line says that gmsh crashed).
    if (!env_flag("STAGGER_GMSH_VERBOSE")) {
      ::dup2(null_fd, STDOUT_FILENO);
      ::dup2(null_fd, STDERR_FILENO);
    }
  }
  ::dup2(out_fd, 3);
  ::fcntl(3, F_SETFD, FD_CLOEXEC);  // programs the .geo may start (allowed) do not hold the pipe
  // gmsh is loaded here, in the child alone (gmsh_api.hpp), before the limits below.
  try {
    gmsh_api();
  } catch (const Error& error) {
    Packer p;
    p.value<std::uint8_t>(1);
    p.string(error.what());
    ::_exit(write_all(3, p.bytes()) ? 0 : 3);
  }
  ::close_range(4, ~0U, 0);  // no inherited files (outputs, checkpoints) stay open
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  // A crash in gmsh gets the kernel's verdict (SIGSEGV, not a sanitizer's abort), so that the
  // message is the same in every build.
  ::signal(SIGSEGV, SIG_DFL);
  ::signal(SIGBUS, SIG_DFL);
  // AddressSanitizer reserves terabytes of address space for its shadow memory: an
  // address-space limit would fail every allocation, so sanitizer builds go without it.
#if !defined(__SANITIZE_ADDRESS__)
  if (run.mib > 0) {
    const auto bytes = static_cast<rlim_t>(std::min(run.mib * 1048576.0, 1e18));
    const rlimit memory{bytes, bytes};
    ::setrlimit(RLIMIT_AS, &memory);
  }
#endif
  if (run.sandbox) {
    const rlimit no_files{0, 0};  // writes to regular files fail (pipes are not files)
    ::setrlimit(RLIMIT_FSIZE, &no_files);
    ::signal(SIGXFSZ, SIG_IGN);
    install_sandbox();
  }
  std::string message;
  const auto failure = [](const std::string& text) {
    Packer p;
    p.value<std::uint8_t>(1);
    p.string(text);
    return p.bytes();
  };
  const std::string out_of_memory_text =
      failure("gmsh ran out of memory " + run.doing + " " + run.path +
              (run.mib > 0 ? " (memory limit " + limit_text(run.mib) +
                                 " MiB: scene key mesh.gmsh_memory_limit, stagger mesh "
                                 "--gmsh-memory-limit); coarsen the mesh or raise the limit"
                           : std::string()));
  out_of_memory_message = &out_of_memory_text;
  std::set_new_handler(out_of_memory);
  try {
    message = pack(in_gmsh_session(run.path, read));
  } catch (const Error& error) {
    message = failure(error.what());
  } catch (const std::bad_alloc&) {
    message = out_of_memory_text;
  } catch (...) {
    message = failure("gmsh failed on " + run.path + ": unexpected exception");
  }
  ::_exit(write_all(3, message) ? 0 : 3);  // no atexit handlers, no stdio flush
}

/// Runs `read` (which returns a soup) in a gmsh session in a child process.
PolygonSoup read_isolated(const ChildRun& run, const std::function<PolygonSoup()>& read) {
  if (env_flag("STAGGER_GMSH_IN_PROCESS")) return with_gmsh(run.path, read);
  // Hold the gmsh lock across the fork: no other thread is inside gmsh, and the child
  // (whose only thread is this one) must not lock it again.
  std::lock_guard lock(gmsh_mutex());
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw Error("cannot run gmsh on " + run.path + ": pipe() failed");
  // The child starts with this address space and resident set (MiB): with its peak resident
  // set they estimate its address space when it died (ru_maxrss), to tell a crash from
  // running out of memory where gmsh does not check an allocation.
  double start_vm_mib = 0, start_rss_mib = 0;
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
    unsigned long pages = 0, resident = 0;
    if (std::fscanf(statm, "%lu %lu", &pages, &resident) == 2) {
      const double page_mib = static_cast<double>(::sysconf(_SC_PAGESIZE)) / 1048576.0;
      start_vm_mib = static_cast<double>(pages) * page_mib;
      start_rss_mib = static_cast<double>(resident) * page_mib;
    }
    std::fclose(statm);
  }
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error("cannot run gmsh on " + run.path + ": fork() failed");
  }
  if (child == 0) {
    ::close(fds[0]);
    child_main(fds[1], run, read);
  }
  ::close(fds[1]);
  std::string bytes;
  char buffer[65536];
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(run.seconds > 0 ? run.seconds : 0);
  bool timed_out = false;
  for (;;) {
    int wait_ms = -1;
    if (run.seconds > 0) {
      const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
      if (left <= 0) {
        timed_out = true;
        break;
      }
      wait_ms = static_cast<int>(std::min(std::ceil(left * 1000), 60000.0));
    }
    pollfd pfd{fds[0], POLLIN, 0};
    const int ready = ::poll(&pfd, 1, wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;  // re-check the deadline
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) {
    ::kill(-child, SIGKILL);  // its process group
    ::kill(child, SIGKILL);
  }
  int status = 0;
  rusage usage{};
  while (::wait4(child, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  if (timed_out || (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU))
    throw Error("gmsh did not finish " + run.doing + " " + run.path + " within " + limit_text(run.seconds) +
                " s (time limit: scene key mesh.gmsh_time_limit, stagger mesh --gmsh-time-limit); the file may "
                "loop or sleep, or the mesh is very fine: raise the limit if it only needs longer");
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const double peak_rss_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB
    const double used_mib = start_vm_mib + std::max(0.0, peak_rss_mib - start_rss_mib);
    std::string why = run.crash_hint;
    // A failed allocation can be as large as what is already used (a doubling array), so
    // growing through a good part of the room left is enough to suspect memory.
    const double room_mib = run.mib - start_vm_mib;
    if (kMemoryLimitApplies && run.mib > 0 &&
        (used_mib > 0.8 * run.mib || (room_mib > 0 && used_mib - start_vm_mib > 0.3 * room_mib)))
      why = "it probably ran out of memory (about " + limit_text(std::round(used_mib)) + " MiB of its " +
            limit_text(run.mib) + " MiB limit: scene key mesh.gmsh_memory_limit, stagger mesh --gmsh-memory-limit)";
    throw Error("gmsh crashed (signal " + std::to_string(signal) + ", " + strsignal(signal) + ") " + run.doing + " " +
                run.path + (why.empty() ? std::string() : ": " + why));
  }
  try {
    return unpack(bytes);
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    throw Error("gmsh ended before it finished " + run.doing + " " + run.path + " (exit status " +
                std::to_string(code) + ", no mesh)" +
                (run.doing == "meshing" ? "; does the .geo end gmsh (Exit)?" : std::string()));
  }
}

void throw_if_gmsh_error(const std::string& path, const std::string& doing) {
  const std::string logged = GmshSession::errors();
  if (!logged.empty())
    throw Error("gmsh failed " + doing + " " + path + ": " + logged +
                (doing == "reading" ? "; fix the file (STAGGER_GMSH_VERBOSE=1 shows gmsh's messages)" : ""));
}

void require_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(what + " '" + path + "' not found (or not a regular file); check the path");
}

std::string physical_name(int dim, int tag) {
  std::string name;
  gm::model::getPhysicalName(dim, tag, name);
  if (!name.empty()) return name;
  return (dim == 2 ? "surface_" : "curve_") + std::to_string(tag);
}

std::string element_name(int type) {
  std::string name;
  int dim = 0, order = 0, nodes = 0, primary = 0;
  std::vector<double> local;
  gm::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
  return name;
}

/// The current gmsh model's physical surfaces and curves as a polygon soup.
PolygonSoup extract_soup(const std::string& path) {
  PolygonSoup soup;
  soup.source = path;
  std::vector<std::size_t> poly_nodes;  // gmsh node tags, translated at the end
  std::vector<std::size_t> edge_nodes;
  std::vector<int> edge_tag;

  // Regions: physical surfaces by name; without any, every surface entity is a region.
  gmsh::vectorpair groups;
  gm::model::getPhysicalGroups(groups, 2);
  std::vector<std::pair<std::string, std::vector<int>>> regions;
  if (groups.empty()) {
    gmsh::vectorpair entities;
    gm::model::getEntities(entities, 2);
    for (const auto& [dim, tag] : entities) regions.push_back({"surface_" + std::to_string(tag), {tag}});
  } else {
    for (const auto& [dim, tag] : groups) {
      std::vector<int> entities;
      gm::model::getEntitiesForPhysicalGroup(dim, tag, entities);
      regions.push_back({physical_name(dim, tag), entities});
    }
  }
  std::map<int, std::string> entity_region;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    soup.region_names.push_back(regions[r].first);
    for (int entity : regions[r].second) {
      const auto [it, fresh] = entity_region.emplace(entity, regions[r].first);
      if (!fresh)
        throw Error(path + ": surface " + std::to_string(entity) +
                    " is in two physical "
                    "surfaces, '" +
                    it->second + "' and '" + regions[r].first + "'; a zone can belong to one region only");
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gm::model::mesh::getElements(types, element_tags, node_tags, 2, entity);
      for (std::size_t k = 0; k < types.size(); ++k) {
        const std::size_t n = types[k] == kTriangle3 ? 3 : types[k] == kQuad4 ? 4 : 0;
        if (n == 0)
          throw Error(path + ": surface " + std::to_string(entity) + " has elements of type '" +
                      element_name(types[k]) +
                      "'; only first-order triangles and quadrangles are supported "
                      "(set Mesh.ElementOrder = 1)");
        const auto& nodes = node_tags[k];
        for (std::size_t e = 0; e + n <= nodes.size(); e += n) {
          soup.polygon_begin.push_back(soup.polygon_begin.back() + static_cast<std::int64_t>(n));
          soup.polygon_region.push_back(static_cast<int>(r));
          poly_nodes.insert(poly_nodes.end(), nodes.begin() + static_cast<std::ptrdiff_t>(e),
                            nodes.begin() + static_cast<std::ptrdiff_t>(e + n));
        }
      }
    }
  }
  // 2D elements in surfaces outside every physical surface are left out: say so.
  if (!groups.empty()) {
    gmsh::vectorpair surfaces;
    gm::model::getEntities(surfaces, 2);
    std::int64_t left_out = 0, kept = static_cast<std::int64_t>(soup.polygon_region.size());
    std::string which;
    for (const auto& [dim, tag] : surfaces) {
      if (entity_region.count(tag)) continue;
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gm::model::mesh::getElements(types, element_tags, node_tags, 2, tag);
      std::int64_t here = 0;
      for (const auto& tags : element_tags) here += static_cast<std::int64_t>(tags.size());
      if (here == 0) continue;
      left_out += here;
      if (which.size() < 60) which += (which.empty() ? "" : ", ") + std::to_string(tag);
    }
    soup.unassigned_elements = left_out;
    if (left_out > 0)
      soup.notes.push_back(std::to_string(left_out) + " of " + std::to_string(left_out + kept) +
                           " 2D elements belong to no physical surface (surface(s) " + which +
                           ") and were left out; add them to a Physical Surface to keep them");
  }
  if (poly_nodes.empty())
    throw Error("empty mesh: " + path + " gave no 2D elements" +
                (groups.empty() ? std::string(" (and it defines no physical surface)")
                                : std::string(" in its physical surfaces")) +
                "; check the geometry and its Physical Surface definitions");

  // Tags: physical curves, their 2-node line elements.
  gmsh::vectorpair curves;
  gm::model::getPhysicalGroups(curves, 1);
  for (const auto& [dim, tag] : curves) {
    const int t = static_cast<int>(soup.tag_names.size());
    soup.tag_names.push_back(physical_name(dim, tag));
    std::vector<int> entities;
    gm::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    std::size_t interfaces = 0, kept_entities = 0;
    for (int entity : entities) {
      // A partitioned mesh has curves between partitions (their parent is a surface, not
      // a model curve): they are no boundary, so they are no tag.
      std::vector<int> partitions;
      gm::model::getPartitions(1, entity, partitions);
      if (!partitions.empty()) {
        int parent_dim = -1, parent_tag = -1;
        gm::model::getParent(1, entity, parent_dim, parent_tag);
        if (parent_dim != 1) {
          ++interfaces;
          continue;
        }
      }
      ++kept_entities;
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gm::model::mesh::getElements(types, element_tags, node_tags, 1, entity);
      for (std::size_t k = 0; k < types.size(); ++k) {
        if (types[k] != kLine2)
          throw Error(path + ": curve " + std::to_string(entity) + " of physical curve '" + soup.tag_names.back() +
                      "' has elements of type '" + element_name(types[k]) + "'; only 2-node lines are supported");
        for (std::size_t e = 0; e + 2 <= node_tags[k].size(); e += 2) {
          edge_nodes.push_back(node_tags[k][e]);
          edge_nodes.push_back(node_tags[k][e + 1]);
          edge_tag.push_back(t);
        }
      }
    }
    if (interfaces > 0) {
      soup.notes.push_back("physical curve '" + soup.tag_names.back() + "': " + std::to_string(interfaces) +
                           " partition interface curve(s) are not boundaries and were left out" +
                           (kept_entities == 0 ? std::string(" (and so was the tag)") : std::string()));
      if (kept_entities == 0) soup.tag_names.pop_back();
    }
  }

  // Points: only the nodes that zones use (gmsh also returns orphans such as circle
  // centres), numbered in increasing gmsh tag order (tags need not be contiguous).
  std::vector<std::size_t> used = poly_nodes;
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::size_t, std::int64_t> index;
  index.reserve(used.size());
  for (std::size_t i = 0; i < used.size(); ++i) index.emplace(used[i], static_cast<std::int64_t>(i));
  std::vector<std::size_t> node_tags;
  std::vector<double> coord, parametric;
  gm::model::mesh::getNodes(node_tags, coord, parametric, -1, -1, false, false);
  soup.x.assign(used.size(), 0.0);
  soup.y.assign(used.size(), 0.0);
  std::vector<char> found(used.size(), 0);
  for (std::size_t k = 0; k < node_tags.size(); ++k) {
    const auto it = index.find(node_tags[k]);
    if (it == index.end()) continue;
    const auto i = static_cast<std::size_t>(it->second);
    soup.x[i] = coord[3 * k];
    soup.y[i] = coord[3 * k + 1];
    found[i] = 1;
  }
  for (std::size_t i = 0; i < used.size(); ++i)
    if (!found[i]) throw Error(path + ": element node " + std::to_string(used[i]) + " has no coordinates");
  // The mesh must lie in a plane z = const: x-y is dropped otherwise (and an x-z mesh would
  // collapse into duplicate points).
  {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    std::size_t z_low = 0, z_high = 0;
    for (std::size_t k = 0; k < node_tags.size(); ++k) {
      if (!index.count(node_tags[k])) continue;
      for (int d = 0; d < 3; ++d) {
        const double v = coord[3 * k + static_cast<std::size_t>(d)];
        if (v < lo[d]) {
          lo[d] = v;
          if (d == 2) z_low = node_tags[k];
        }
        if (v > hi[d]) {
          hi[d] = v;
          if (d == 2) z_high = node_tags[k];
        }
      }
    }
    const double span = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const double tol = 1e-10 * span;
    if (hi[2] - lo[2] > tol) {
      const auto range = [&](int d) { return number_text(lo[d]) + " to " + number_text(hi[d]); };
      if (hi[1] - lo[1] <= tol || hi[0] - lo[0] <= tol) {
        const bool xz = hi[1] - lo[1] <= tol;
        throw Error(path + ": the mesh lies in the " + (xz ? "x-z" : "y-z") + " plane (" + (xz ? "y" : "x") + " = " +
                    number_text(xz ? lo[1] : lo[0]) + " everywhere, z from " + range(2) +
                    "); stagger meshes lie in the x-y plane: rotate the geometry (e.g. Rotate in the .geo) "
                    "or re-export it");
      }
      throw Error(path + ": the mesh is not flat in the x-y plane: z varies from " + range(2) + " (nodes " +
                  std::to_string(z_low) + " and " + std::to_string(z_high) +
                  "); stagger meshes are 2D, with z constant");
    }
  }
  soup.polygon_points.reserve(poly_nodes.size());
  for (std::size_t node : poly_nodes) soup.polygon_points.push_back(index.at(node));
  for (std::size_t e = 0; e < edge_tag.size(); ++e) {
    const auto a = index.find(edge_nodes[2 * e]), b = index.find(edge_nodes[2 * e + 1]);
    if (a == index.end() || b == index.end())
      throw Error(path + ": physical curve '" + soup.tag_names[static_cast<std::size_t>(edge_tag[e])] +
                  "' has an edge (nodes " + std::to_string(edge_nodes[2 * e]) + ", " +
                  std::to_string(edge_nodes[2 * e + 1]) +
                  ") that bounds no zone of a physical surface; tag only curves of the meshed domain");
    soup.tagged_edges.push_back({a->second, b->second, edge_tag[e]});
  }
  return soup;
}

std::size_t count_triangles(const PolygonSoup& soup) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < soup.num_polygons(); ++f)
    n += soup.polygon_begin[f + 1] - soup.polygon_begin[f] == 3 ? 1 : 0;
  return n;
}

/// Counts triangles in the current gmsh mesh of dimension 2.
std::size_t gmsh_triangles() {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gm::model::mesh::getElements(types, element_tags, node_tags, 2, -1);
  std::size_t n = 0;
  for (std::size_t k = 0; k < types.size(); ++k)
    if (types[k] == kTriangle3) n += element_tags[k].size();
  return n;
}

/// A 2D code needs a 2D model: volumes are refused up front (a 3D model's surfaces would
/// otherwise be projected onto z = 0 and collapse into "duplicate points"). A .msh may list
/// the volume entities of the model it came from: there only volume elements count.
void require_planar_model(const std::string& path, bool volume_entities_count) {
  gmsh::vectorpair volumes;
  gm::model::getEntities(volumes, 3);
  if (volumes.empty()) return;
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gm::model::mesh::getElements(types, element_tags, node_tags, 3, -1);
  std::size_t elements = 0;
  for (const auto& tags : element_tags) elements += tags.size();
  if (elements == 0 && !volume_entities_count) return;
  throw Error(path + ": a 3D model (" + std::to_string(volumes.size()) + " volume(s)" +
              (elements > 0 ? ", " + std::to_string(elements) + " volume elements" : std::string()) +
              "); stagger is 2D: give it surfaces in the x-y plane (z = 0) only");
}

/// All-quad subdivision of a soup, the same as gmsh's (Mesh.SubdivisionAlgorithm = 1): an
/// n-gon becomes n quads around its centroid through its edge midpoints (a triangle 3, a
/// quad 4). Only if there are triangles. A tagged edge is split at its midpoint.
void subdivide_soup(PolygonSoup& soup) {
  if (count_triangles(soup) == 0) return;
  if (soup.x.size() >= (std::size_t{1} << 31)) throw Error(soup.source + ": too many points to subdivide");
  std::unordered_map<std::uint64_t, std::int64_t> midpoint;
  const auto key = [](std::int64_t a, std::int64_t b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
  };
  const auto add_point = [&](double x, double y) {
    soup.x.push_back(x);
    soup.y.push_back(y);
    return static_cast<std::int64_t>(soup.x.size() - 1);
  };
  const auto mid = [&](std::int64_t a, std::int64_t b) {
    const auto [it, fresh] = midpoint.emplace(key(a, b), 0);
    if (fresh) {
      const auto A = static_cast<std::size_t>(a), B = static_cast<std::size_t>(b);
      it->second = add_point(0.5 * (soup.x[A] + soup.x[B]), 0.5 * (soup.y[A] + soup.y[B]));
    }
    return it->second;
  };
  const std::vector<std::int64_t> begin = soup.polygon_begin, points = soup.polygon_points;
  const std::vector<int> region = soup.polygon_region;
  soup.polygon_begin = {0};
  soup.polygon_points.clear();
  soup.polygon_region.clear();
  for (std::size_t f = 0; f + 1 < begin.size(); ++f) {
    const auto b = begin[f], n = begin[f + 1] - begin[f];
    double cx = 0, cy = 0;
    for (auto k = b; k < b + n; ++k) {
      cx += soup.x[static_cast<std::size_t>(points[static_cast<std::size_t>(k)])];
      cy += soup.y[static_cast<std::size_t>(points[static_cast<std::size_t>(k)])];
    }
    const std::int64_t centre = add_point(cx / static_cast<double>(n), cy / static_cast<double>(n));
    const auto p = [&](std::int64_t k) { return points[static_cast<std::size_t>(b + (k + n) % n)]; };
    for (std::int64_t k = 0; k < n; ++k)
      soup.add_polygon({p(k), mid(p(k), p(k + 1)), centre, mid(p(k - 1), p(k))}, region.empty() ? 0 : region[f]);
  }
  std::vector<TaggedEdge> edges;
  for (const TaggedEdge& e : soup.tagged_edges) {
    const auto it = midpoint.find(key(e.a, e.b));
    if (it == midpoint.end()) {
      edges.push_back(e);
      continue;
    }
    edges.push_back({e.a, it->second, e.tag});
    edges.push_back({it->second, e.b, e.tag});
  }
  soup.tagged_edges = std::move(edges);
}

/// Subdivide policy after meshing: if triangles are left, split every element into quads
/// (gmsh's all-quad subdivision: each quad into 4, each triangle into 3, so the element
/// size halves).
void subdivide_if_triangles() {
  if (gmsh_triangles() == 0) return;
  gm::option::setNumber("Mesh.SubdivisionAlgorithm", 1);
  gm::model::mesh::refine();
}

void apply_policy(const PolygonSoup& soup, TrianglePolicy policy) {
  if (policy != TrianglePolicy::reject) return;
  const std::size_t n = count_triangles(soup);
  if (n > 0)
    throw Error(soup.source + ": " + std::to_string(n) + " of " + std::to_string(soup.num_polygons()) +
                " zones are triangles and the triangle policy is 'reject'; use 'accept' "
                "(mixed zones) or 'subdivide' (all quads), or make the surface transfinite");
}

/// Parameters of a .geo, like `gmsh -setnumber NAME VALUE`. gmsh 4.8 keeps -setnumber values
/// passed to gm::initialize in a static table that finalize() does not clear, so they
/// would leak into every later file of the process. Instead, a small wrapper file defines
/// the parameters and includes the .geo: DefineConstant keeps a value that is already
/// defined, exactly as with -setnumber, and open() clears the parser variables each time.
/// The wrapper lives in a private directory (mkdtemp, mode 0700), so no other user can plant
/// or read it, and the .geo's path is quoted with a delimiter it does not contain (gmsh
/// strings have no escapes).
class ParameterWrapper {
 public:
  ParameterWrapper(const std::string& path, const std::vector<std::pair<std::string, double>>& parameters) {
    if (parameters.empty()) {
      file_ = path;
      return;
    }
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ostringstream wrapper;
    for (const auto& [name, value] : parameters) {
      const bool identifier =
          !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
          std::all_of(name.begin(), name.end(), [](unsigned char ch) { return std::isalnum(ch) || ch == '_'; });
      if (!identifier) throw Error(path + ": parameter name '" + name + "' is not a valid .geo identifier");
      if (!contains_word(text, name))
        throw Error(path + ": unknown parameter '" + name + "' (the file never mentions it; check the spelling)");
      wrapper << name << " = " << number_text(value) << ";\n";
    }
    const std::string absolute = std::filesystem::absolute(path).lexically_normal().string();
    const bool control =
        std::any_of(absolute.begin(), absolute.end(), [](unsigned char ch) { return ch < 0x20 || ch == 0x7f; });
    const char quote = absolute.find('"') == std::string::npos ? '"' : '\'';
    if (control || absolute.find(quote) != std::string::npos || absolute.size() > 1000)
      throw Error(path + ": gmsh cannot include this path with parameters (it " +
                  (control                  ? std::string("contains a control character such as a newline")
                   : absolute.size() > 1000 ? std::string("is longer than 1000 characters")
                                            : std::string("contains both \" and ' quotes")) +
                  "); rename the file or its directories");
    wrapper << "Include " << quote << absolute << quote << ";\n";
    std::string directory = (std::filesystem::temp_directory_path() / "stagger-geo-XXXXXX").string();
    if (!::mkdtemp(directory.data()))
      throw Error(path +
                  ": cannot create a private temporary directory for the parameter wrapper: " + std::strerror(errno));
    directory_ = directory;
    file_ = (directory_ / "parameters.geo").string();
    const int fd = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    const std::string bytes = wrapper.str();
    const bool written = fd >= 0 && write_all(fd, bytes);
    if (fd >= 0) ::close(fd);
    if (!written) throw Error(path + ": cannot write the parameter wrapper in " + directory_.string());
  }
  ~ParameterWrapper() {
    std::error_code ec;
    if (!directory_.empty()) std::filesystem::remove_all(directory_, ec);
  }
  ParameterWrapper(const ParameterWrapper&) = delete;
  ParameterWrapper& operator=(const ParameterWrapper&) = delete;
  const std::string& file() const { return file_; }

 private:
  static bool contains_word(const std::string& text, const std::string& word) {
    const auto is_id = [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; };
    for (auto pos = text.find(word); pos != std::string::npos; pos = text.find(word, pos + 1)) {
      const bool left = pos == 0 || !is_id(text[pos - 1]);
      const bool right = pos + word.size() == text.size() || !is_id(text[pos + word.size()]);
      if (left && right) return true;
    }
    return false;
  }
  std::string file_;
  std::filesystem::path directory_;
};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

}  // namespace

std::string find_outside_command(const std::string& path) {
  std::set<std::filesystem::path> seen;
  std::string found;
  scan_geo_file(path, seen, 0, found);
  return found;
}

PolygonSoup read_geo(const std::string& path, const GeoOptions& options) {
  require_file(path, "geometry file");
  // STAGGER_GEO_SCAN=0 skips the scan but keeps the sandbox (tests of the sandbox).
  const char* scan = std::getenv("STAGGER_GEO_SCAN");
  if (!options.allow_commands && !(scan && std::string(scan) == "0")) {
    const std::string found = find_outside_command(path);
    if (!found.empty())
      throw Error(found +
                  "; stagger refuses .geo commands that reach outside the mesh (set "
                  "mesh.allow_geo_commands = true, or stagger mesh --allow-geo-commands, to allow them: "
                  "that runs arbitrary code)");
  }
  const ParameterWrapper wrapper(path, options.parameters);
  ChildRun run;
  run.path = path;
  run.doing = "meshing";
  run.seconds = options.time_limit_seconds;
  run.mib = options.memory_limit_mib;
  run.sandbox = !options.allow_commands;
  run.crash_hint =
      "gmsh 4.8 crashes on some inputs, e.g. MeshAlgorithm Surface{...} = 8 (use 6 there) or a command "
      "after which it does not recover from an error; run 'gmsh -2 " +
      path + "' to see where it fails";
  PolygonSoup soup = read_isolated(run, [&] {
    gm::open(wrapper.file());
    throw_if_gmsh_error(path, "reading");
    // Options after open(): the file may set its own. Algorithm 8 segfaults in Debian's
    // gmsh 4.8, so fall back to 6 (Frontal-Delaunay) and recombine.
    double algorithm = 0;
    gm::option::getNumber("Mesh.Algorithm", algorithm);
    if (algorithm == 8) gm::option::setNumber("Mesh.Algorithm", 6);
    if (options.recombine) {
      gm::option::setNumber("Mesh.RecombineAll", 1);
      // 1: blossom. The full-quad variants (2, 3) fail ("1D mesh cannot be divided by 2")
      // on transfinite curves with an odd number of segments, so the subdivide policy
      // recombines with blossom too and then subdivides if triangles are left.
      gm::option::setNumber("Mesh.RecombinationAlgorithm", 1);
    }
    require_planar_model(path, true);
    gm::model::mesh::generate(2);
    throw_if_gmsh_error(path, "meshing");
    if (options.triangles == TrianglePolicy::subdivide) {
      subdivide_if_triangles();
      throw_if_gmsh_error(path, "subdividing");
    }
    return extract_soup(path);
  });
  apply_policy(soup, options.triangles);
  return soup;
}

PolygonSoup read_msh(const std::string& path, TrianglePolicy triangles) {
  GeoOptions options;
  options.triangles = triangles;
  return read_msh(path, options);
}

PolygonSoup read_msh(const std::string& path, const GeoOptions& options) {
  require_file(path, "mesh file");
  ChildRun run;
  run.path = path;
  run.doing = "reading";
  run.seconds = options.time_limit_seconds;
  run.mib = options.memory_limit_mib;
  run.sandbox = true;  // a .msh holds no commands
  run.crash_hint =
      "the file is corrupt (e.g. an element refers to a node that $Nodes does not define); "
      "check it with 'gmsh " +
      path + " -0' or re-export it";
  PolygonSoup soup = read_isolated(run, [&] {
    gm::open(path);
    throw_if_gmsh_error(path, "reading");
    require_planar_model(path, false);
    return extract_soup(path);
  });
  // gmsh's subdivision of a discrete (file) mesh duplicates nodes where entities meet, so a
  // .msh is subdivided here, on the soup.
  if (options.triangles == TrianglePolicy::subdivide) subdivide_soup(soup);
  apply_policy(soup, options.triangles);
  return soup;
}

PolygonSoup read_mesh_file(const std::string& path, const GeoOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == ".geo") return read_geo(path, options);
  if (ext == ".msh") {
    if (!options.parameters.empty())
      throw Error(path + ": parameters (" + options.parameters.front().first +
                  " ...) only apply to .geo files, not to a .msh mesh");
    return read_msh(path, options);
  }
  throw Error("'" + path + "': unknown mesh file extension '" + ext + "'; use .geo or .msh");
}

void write_msh(const std::string& path, const Mesh& mesh) {
  if (mesh.num_zones() == 0) throw Error("write_msh: the mesh has no zones (" + path + ")");
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index n = mesh.zone_corner_begin[z + 1] - mesh.zone_corner_begin[z];
    if (n != 3 && n != 4)
      throw Error("write_msh " + path + ": zone " + std::to_string(z) + " has " + std::to_string(n) +
                  " corners; MSH stores only triangles and quadrangles");
  }
  with_gmsh(path, [&] {
    gm::model::add("stagger");
    // One discrete surface per region (tag r+1), one discrete curve per boundary tag.
    // All nodes live on the first region's surface; elements may use any node.
    const Index nregions = mesh.num_regions();
    for (Index r = 0; r < nregions; ++r) gm::model::addDiscreteEntity(2, r + 1);
    const int node_entity = mesh.zone_region[0] + 1;
    std::vector<std::size_t> node_tags(static_cast<std::size_t>(mesh.num_points()));
    std::vector<double> coord(3 * node_tags.size(), 0.0);
    for (std::size_t p = 0; p < node_tags.size(); ++p) {
      node_tags[p] = p + 1;
      coord[3 * p] = mesh.x[p];
      coord[3 * p + 1] = mesh.y[p];
    }
    gm::model::mesh::addNodes(2, node_entity, node_tags, coord);
    std::size_t element = 1;
    for (Index r = 0; r < nregions; ++r) {
      std::vector<std::size_t> tri_tags, tri_nodes, quad_tags, quad_nodes;
      for (Index z = mesh.region_zone_begin[r]; z < mesh.region_zone_begin[r + 1]; ++z) {
        const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
        auto& tags = e - b == 3 ? tri_tags : quad_tags;
        auto& nodes = e - b == 3 ? tri_nodes : quad_nodes;
        tags.push_back(element++);
        for (Index c = b; c < e; ++c) nodes.push_back(static_cast<std::size_t>(mesh.corner_point[c]) + 1);
      }
      if (!tri_tags.empty()) gm::model::mesh::addElementsByType(r + 1, kTriangle3, tri_tags, tri_nodes);
      if (!quad_tags.empty()) gm::model::mesh::addElementsByType(r + 1, kQuad4, quad_tags, quad_nodes);
      gm::model::addPhysicalGroup(2, {r + 1}, r + 1);
      gm::model::setPhysicalName(2, r + 1, mesh.region_names[static_cast<std::size_t>(r)]);
    }
    for (std::size_t t = 0; t < mesh.tags.size(); ++t) {
      const int entity = static_cast<int>(t) + 1;
      gm::model::addDiscreteEntity(1, entity);
      std::vector<std::size_t> line_tags, line_nodes;
      for (const auto& edge : mesh.tags[t].edges) {
        line_tags.push_back(element++);
        line_nodes.push_back(static_cast<std::size_t>(edge[0]) + 1);
        line_nodes.push_back(static_cast<std::size_t>(edge[1]) + 1);
      }
      if (!line_tags.empty()) gm::model::mesh::addElementsByType(entity, kLine2, line_tags, line_nodes);
      gm::model::addPhysicalGroup(1, {entity}, entity);
      gm::model::setPhysicalName(1, entity, mesh.tags[t].name);
    }
    gm::option::setNumber("Mesh.MshFileVersion", 4.1);
    gm::option::setNumber("Mesh.Binary", 1);  // exact doubles (ASCII MSH prints 16 digits)
    gm::write(path);
    throw_if_gmsh_error(path, "writing");
  });
}

}  // namespace stagger::meshgen
