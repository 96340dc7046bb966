#pragma once
/// @file child_sandbox.hpp
/// The limits of the child process that runs gmsh on untrusted input (docs/mesh.md, "gmsh in
/// a child process" and "Commands that reach outside the mesh"): no core dumps, an
/// address-space limit, and a sandbox in which regular files cannot be written and programs
/// cannot be started. Each call applies to the calling process for the rest of its life.

namespace stagger::meshgen {

/// Whether limit_address_space sets a limit (not in AddressSanitizer builds, whose shadow
/// memory needs terabytes of address space): only then can a crash be put down to the
/// memory limit.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kMemoryLimitApplies = false;
#else
inline constexpr bool kMemoryLimitApplies = true;
#endif

/// No core file when the process crashes.
void disable_core_dumps();

/// Limits the address space (RLIMIT_AS) to `mib` MiB; 0: no limit. Does nothing where
/// kMemoryLimitApplies is false.
void limit_address_space(double mib);

/// Writes to regular files fail (file-size limit 0, SIGXFSZ ignored), and a seccomp filter
/// makes the system calls that start programs, open files for writing, or create, delete,
/// rename or change files fail with EPERM (threads may still be created). The filter is built
/// for x86-64 and AArch64 Linux; elsewhere only the file-size limit applies.
void enter_sandbox();

}  // namespace stagger::meshgen
