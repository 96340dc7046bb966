// libFuzzer target: .msh bytes -> meshgen::read_msh (gmsh's reader) -> build_mesh. gmsh is
// not instrumented; findings inside it are reported upstream, not fixed here (see
// docs/robustness.md). Inputs must load or throw stagger::Error.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "stagger/error.hpp"
#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = [] {
    auto directory = std::filesystem::temp_directory_path() / ("stagger_msh_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(directory);
    return directory / "mesh.msh";
  }();
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    const stagger::PolygonSoup soup = stagger::meshgen::read_msh(file.string());
    static_cast<void>(stagger::build_mesh(soup));
  } catch (const stagger::Error&) {
  }
  return 0;
}
