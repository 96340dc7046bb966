/// @file gmsh_child.cpp
/// The gmsh child process and its parent's side (gmsh_child.hpp): fork, pipe, limits, the
/// time limit, and the error that says how the child ended.
#include "gmsh_child.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <new>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "child_protocol.hpp"
#include "child_sandbox.hpp"
#include "fd_write.hpp"
#include "gmsh_session.hpp"
#include "stagger/error.hpp"

namespace stagger::meshgen {
namespace {

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

[[noreturn]] void child_main(int out_fd, pid_t parent, const ChildRun& run, const std::function<PolygonSoup()>& read) {
  // Die with the parent (e.g. stagger killed by SIGKILL), in a process group of our own so
  // that the time limit also ends whatever the .geo started (allowed commands). A parent that
  // died before the prctl has left us to another process already: then end at once.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(5);
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
    load_gmsh();
  } catch (const Error& error) {
    ::_exit(write_all(3, pack_failure(error.what())) ? 0 : 3);
  }
  ::close_range(4, ~0U, 0);  // no inherited files (outputs, checkpoints) stay open
  disable_core_dumps();
  // A crash in gmsh gets the kernel's verdict (SIGSEGV, not a sanitizer's abort), so that the
  // message is the same in every build.
  ::signal(SIGSEGV, SIG_DFL);
  ::signal(SIGBUS, SIG_DFL);
  limit_address_space(run.mib);
  if (run.sandbox) enter_sandbox();
  std::string message;
  const std::string out_of_memory_text =
      pack_failure("gmsh ran out of memory " + run.doing + " " + run.path +
                   (run.mib > 0 ? " (memory limit " + limit_text(run.mib) +
                                      " MiB: scene key mesh.gmsh_memory_limit, stagger mesh "
                                      "--gmsh-memory-limit); coarsen the mesh or raise the limit"
                                : std::string()));
  out_of_memory_message = &out_of_memory_text;
  std::set_new_handler(out_of_memory);
  try {
    message = pack(in_gmsh_session(run.path, read));
  } catch (const Error& error) {
    message = pack_failure(error.what());
  } catch (const std::bad_alloc&) {
    message = out_of_memory_text;
  } catch (...) {
    message = pack_failure("gmsh failed on " + run.path + ": unexpected exception");
  }
  ::_exit(write_all(3, message) ? 0 : 3);  // no atexit handlers, no stdio flush
}

/// A process's address space and resident set (MiB).
struct MemoryUse {
  double vm_mib = 0;
  double rss_mib = 0;
};

/// This process's memory use from /proc/self/statm; zeros if it cannot be read.
MemoryUse own_memory_use() {
  MemoryUse use;
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
    unsigned long pages = 0, resident = 0;
    if (std::fscanf(statm, "%lu %lu", &pages, &resident) == 2) {
      const double page_mib = static_cast<double>(::sysconf(_SC_PAGESIZE)) / 1048576.0;
      use.vm_mib = static_cast<double>(pages) * page_mib;
      use.rss_mib = static_cast<double>(resident) * page_mib;
    }
    std::fclose(statm);
  }
  return use;
}

/// Appends what the child writes to `fd` to `bytes` until it closes the pipe. Returns false if
/// the wall-time limit `seconds` (0: none) passes first.
bool read_answer(int fd, double seconds, std::string& bytes) {
  char buffer[65536];
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds > 0 ? seconds : 0);
  for (;;) {
    int wait_ms = -1;
    if (seconds > 0) {
      const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
      if (left <= 0) return false;
      wait_ms = static_cast<int>(std::min(std::ceil(left * 1000), 60000.0));
    }
    pollfd pfd{fd, POLLIN, 0};
    const int ready = ::poll(&pfd, 1, wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;  // re-check the deadline
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

/// The error of a child killed by `signal`. `at_fork` is the memory the child started with:
/// with its peak resident set (ru_maxrss) it estimates the child's address space when it
/// died, to tell a crash from running out of memory where gmsh does not check an allocation.
[[noreturn]] void throw_crash(const ChildRun& run, int signal, const rusage& usage, const MemoryUse& at_fork) {
  const double peak_rss_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB
  const double used_mib = at_fork.vm_mib + std::max(0.0, peak_rss_mib - at_fork.rss_mib);
  std::string why = run.crash_hint;
  // A failed allocation can be as large as what is already used (a doubling array), so
  // growing through a good part of the room left is enough to suspect memory.
  const double room_mib = run.mib - at_fork.vm_mib;
  if (kMemoryLimitApplies && run.mib > 0 &&
      (used_mib > 0.8 * run.mib || (room_mib > 0 && used_mib - at_fork.vm_mib > 0.3 * room_mib)))
    why = "it probably ran out of memory (about " + limit_text(std::round(used_mib)) + " MiB of its " +
          limit_text(run.mib) + " MiB limit: scene key mesh.gmsh_memory_limit, stagger mesh --gmsh-memory-limit)";
  throw Error("gmsh crashed (signal " + std::to_string(signal) + ", " + strsignal(signal) + ") " + run.doing + " " +
              run.path + (why.empty() ? std::string() : ": " + why));
}

}  // namespace

PolygonSoup read_isolated(const ChildRun& run, const std::function<PolygonSoup()>& read) {
  if (env_flag("STAGGER_GMSH_IN_PROCESS")) return with_gmsh(run.path, read);
  // Hold the gmsh lock across the fork: no other thread is inside gmsh, and the child
  // (whose only thread is this one) must not lock it again.
  std::lock_guard lock(gmsh_mutex());
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw Error("cannot run gmsh on " + run.path + ": pipe() failed");
  // The child starts with this address space and resident set (throw_crash).
  const MemoryUse at_fork = own_memory_use();
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error("cannot run gmsh on " + run.path + ": fork() failed");
  }
  if (child == 0) {
    ::close(fds[0]);
    child_main(fds[1], parent, run, read);
  }
  ::close(fds[1]);
  std::string bytes;
  const bool timed_out = !read_answer(fds[0], run.seconds, bytes);
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
  if (WIFSIGNALED(status)) throw_crash(run, WTERMSIG(status), usage, at_fork);
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

}  // namespace stagger::meshgen
