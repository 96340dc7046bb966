#pragma once
/// @file gmsh_child.hpp
/// Reading and meshing in a child process (docs/mesh.md, "gmsh in a child process"). gmsh
/// 4.8 trusts its input: a corrupt .msh, or a .geo that sets Mesh.Algorithm = 8 on a surface,
/// can crash it (segfault, double free); a .geo can loop for ever or exhaust memory; and
/// gm::initialize resets OpenMP to one thread. gmsh therefore runs in a forked child that
/// sends the soup (or the error) back through a pipe (child_protocol.hpp), under an
/// address-space limit (setrlimit RLIMIT_AS) and a wall-time limit (the parent kills it), with
/// stdout silenced unless STAGGER_GMSH_VERBOSE=1. Without allow_commands the child also runs
/// in a seccomp sandbox (child_sandbox.hpp) that refuses to start programs, open files for
/// writing, or create, delete or rename files. STAGGER_GMSH_IN_PROCESS=1 runs gmsh in-process
/// (debugging; no limits).
#include <functional>
#include <string>

#include "stagger/mesh.hpp"

namespace stagger::meshgen {

/// Limits and wording of one child run.
struct ChildRun {
  std::string path;        ///< the user's file, for messages
  std::string doing;       ///< "meshing" or "reading"
  double seconds = 0;      ///< wall-time limit, 0: none
  double mib = 0;          ///< address-space limit, 0: none
  bool sandbox = true;     ///< install the seccomp filter
  std::string crash_hint;  ///< appended to a crash message
};

/// Runs `read` (which returns a soup) in a gmsh session in a child process. A crash, a
/// timeout, running out of memory or gmsh's own error becomes stagger::Error naming the file.
PolygonSoup read_isolated(const ChildRun& run, const std::function<PolygonSoup()>& read);

}  // namespace stagger::meshgen
