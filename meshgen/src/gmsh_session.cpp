/// @file gmsh_session.cpp
/// The gmsh session (gmsh_session.hpp): start-up options, shut-down, and the errors it logged.
#include "gmsh_session.hpp"

#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "gmsh_api.hpp"

namespace stagger::meshgen {

bool env_flag(const char* name) {
  const char* value = std::getenv(name);
  return value && *value && *value != '0';
}

std::mutex& gmsh_mutex() {
  static std::mutex mutex;
  return mutex;
}

void load_gmsh() {
  gmsh_api();
}

GmshSession::GmshSession() : threads_(omp_get_max_threads()) {
  gm::initialize(0, nullptr, false);
  // STAGGER_GMSH_VERBOSE=1 shows gmsh's own messages (debugging a .geo).
  gm::option::setNumber("General.Terminal", env_flag("STAGGER_GMSH_VERBOSE") ? 1 : 0);
  // Errors are read from the logger after each step: with the default (2) gmsh throws
  // from inside its mesher, where an exception can end in std::terminate.
  gm::option::setNumber("General.AbortOnError", 0);
  gm::logger::start();
}

GmshSession::~GmshSession() {
  try {
    gm::logger::stop();
    gm::finalize();
  } catch (...) {  // a destructor must not throw; gmsh throws std::string
  }
  omp_set_num_threads(threads_);
}

std::string GmshSession::errors() {
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

void throw_if_gmsh_error(const std::string& path, const std::string& doing) {
  const std::string logged = GmshSession::errors();
  if (!logged.empty())
    throw Error("gmsh failed " + doing + " " + path + ": " + logged +
                (doing == "reading" ? "; fix the file (STAGGER_GMSH_VERBOSE=1 shows gmsh's messages)" : ""));
}

}  // namespace stagger::meshgen
