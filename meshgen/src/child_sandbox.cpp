/// @file child_sandbox.cpp
/// The gmsh child's resource limits and seccomp sandbox (child_sandbox.hpp).
#include "child_sandbox.hpp"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/sched.h>
#include <linux/seccomp.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>

namespace stagger::meshgen {
namespace {

#if defined(__x86_64__) || defined(__aarch64__)
/// The system calls that fail with EPERM whatever their arguments.
std::vector<long> denied_system_calls() {
  return {
    SYS_execve, SYS_execveat, SYS_unlinkat, SYS_renameat, SYS_mkdirat, SYS_linkat, SYS_symlinkat, SYS_fchmod,
        SYS_fchmodat, SYS_fchown, SYS_fchownat, SYS_truncate, SYS_mknodat, SYS_socket, SYS_ptrace, SYS_kill,
        SYS_process_vm_writev, SYS_open_by_handle_at,
#if defined(__x86_64__)
        SYS_fork, SYS_vfork, SYS_creat, SYS_unlink, SYS_rmdir, SYS_rename, SYS_mkdir, SYS_link, SYS_symlink, SYS_chmod,
        SYS_chown, SYS_lchown, SYS_mknod,
#endif
#ifdef SYS_renameat2
        SYS_renameat2,
#endif
  };
}

/// The sandbox's BPF program, or an empty one if a jump does not fit in BPF's 8-bit offsets.
std::vector<sock_filter> sandbox_filter() {
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
  for (const long nr : denied_system_calls()) jump_if(BPF_JEQ, static_cast<std::uint32_t>(nr), deny);
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
    if (labels.at(to) <= at || offset > 255) return {};
    code[at].jt = static_cast<std::uint8_t>(offset);
  }
  return code;
}
#endif

/// Installs the seccomp filter of enter_sandbox. Returns false where it is not supported; the
/// time and memory limits still apply there.
bool install_seccomp_filter() {
#if defined(__x86_64__) || defined(__aarch64__)
  std::vector<sock_filter> code = sandbox_filter();
  if (code.empty()) return false;
  sock_fprog program{};
  program.len = static_cast<unsigned short>(code.size());
  program.filter = code.data();
  if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return false;
  return ::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &program) == 0;
#else
  return false;
#endif
}

}  // namespace

void disable_core_dumps() {
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
}

void limit_address_space([[maybe_unused]] double mib) {
  // AddressSanitizer reserves terabytes of address space for its shadow memory: an
  // address-space limit would fail every allocation, so sanitizer builds go without it.
#if !defined(__SANITIZE_ADDRESS__)
  if (mib > 0) {
    const auto bytes = static_cast<rlim_t>(std::min(mib * 1048576.0, 1e18));
    const rlimit memory{bytes, bytes};
    ::setrlimit(RLIMIT_AS, &memory);
  }
#endif
}

void enter_sandbox() {
  const rlimit no_files{0, 0};  // writes to regular files fail (pipes are not files)
  ::setrlimit(RLIMIT_FSIZE, &no_files);
  ::signal(SIGXFSZ, SIG_IGN);
  install_seccomp_filter();
}

}  // namespace stagger::meshgen
