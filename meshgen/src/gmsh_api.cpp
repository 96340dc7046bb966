/// @file gmsh_api.cpp
/// Loads libstagger_gmsh_bridge (gmsh_api.hpp) from the directory of this library, where it
/// is built and installed.
#include "gmsh_api.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <string>

#include "stagger/error.hpp"

namespace stagger::meshgen {

const GmshApi& gmsh_api() {
  static const GmshApi* const api = [] {
    constexpr const char* kBridge = "libstagger_gmsh_bridge.so";
    std::string path = kBridge;
    Dl_info self{};
    if (::dladdr(reinterpret_cast<void*>(&gmsh_api), &self) != 0 && self.dli_fname) {
      const std::filesystem::path beside = std::filesystem::path(self.dli_fname).parent_path() / kBridge;
      std::error_code error;
      if (std::filesystem::exists(beside, error)) path = beside.string();
    }
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw Error(std::string("cannot load gmsh (") + ::dlerror() + ")");
    const auto entry = reinterpret_cast<const GmshApi* (*)()>(::dlsym(handle, "stagger_gmsh_bridge_api"));
    if (!entry) throw Error("cannot load gmsh: " + path + " lacks stagger_gmsh_bridge_api");
    return entry();
  }();
  return *api;
}

}  // namespace stagger::meshgen
