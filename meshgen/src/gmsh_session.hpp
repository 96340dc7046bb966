#pragma once
/// @file gmsh_session.hpp
/// One gmsh session at a time. gmsh is a global singleton that is not thread-safe: every use
/// holds one mutex and one RAII session (initialize ... finalize), so no gmsh state leaks from
/// one call to the next. The session's log is where gmsh's errors are read from. Internal to
/// meshgen; gmsh's own headers stay in gmsh_session.cpp.
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>

#include "stagger/error.hpp"

namespace stagger::meshgen {

/// Whether the environment variable `name` is set, not empty and not "0".
bool env_flag(const char* name);

/// The lock every use of gmsh holds.
std::mutex& gmsh_mutex();

/// Loads gmsh (the bridge of gmsh_api.hpp) if it is not loaded yet; throws stagger::Error if it
/// cannot.
void load_gmsh();

/// One gmsh session: initialize, quiet terminal, logger on; finalize on destruction.
/// gm::initialize sets OpenMP to gmsh's own thread count (1): the caller's setting is
/// restored afterwards, so an in-process session does not leave stagger single-threaded.
class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// The first and last errors gmsh logged since the session started, or "".
  static std::string errors();

 private:
  int threads_;
};

/// Throws stagger::Error if gmsh logged an error while `doing` ("reading", "meshing", ...)
/// `path`.
void throw_if_gmsh_error(const std::string& path, const std::string& doing);

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

/// in_gmsh_session under the gmsh lock, in this process; running out of memory becomes
/// stagger::Error.
template <class Body>
auto with_gmsh(const std::string& path, Body body) {
  std::lock_guard lock(gmsh_mutex());
  try {
    return in_gmsh_session(path, body);
  } catch (const std::bad_alloc&) {
    throw Error("gmsh ran out of memory on " + path);
  }
}

}  // namespace stagger::meshgen
