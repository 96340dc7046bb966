/// @file mesh_file.cpp
/// Mesh files by extension (read_mesh_file) and the check that a file exists (mesh_file.hpp).
#include "mesh_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::meshgen {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

}  // namespace

void require_file(const std::string& path, const std::string& what) {
  const std::string problem = file_problem(path);
  if (!problem.empty())
    throw Error(what + " '" + path + "' " + problem +
                (problem.rfind("not found", 0) == 0 ? "" : ", not a regular file") + "; check the path");
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

}  // namespace stagger::meshgen
