#pragma once
/// @file geo_parameters.hpp
/// Parameters of a .geo, like `gmsh -setnumber NAME VALUE` (GeoOptions::parameters).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace stagger::meshgen {

/// gmsh 4.8 keeps -setnumber values passed to gm::initialize in a static table that
/// finalize() does not clear, so they would leak into every later file of the process.
/// Instead, a small wrapper file defines the parameters and includes the .geo: DefineConstant
/// keeps a value that is already defined, exactly as with -setnumber, and open() clears the
/// parser variables each time. The wrapper lives in a private directory (mkdtemp, mode 0700),
/// so no other user can plant or read it, and the .geo's path is quoted with a delimiter it
/// does not contain (gmsh strings have no escapes).
class ParameterWrapper {
 public:
  /// Checks the parameter names against the file and writes the wrapper; without parameters
  /// the file is `path` itself. Throws stagger::Error naming `path`.
  ParameterWrapper(const std::string& path, const std::vector<std::pair<std::string, double>>& parameters);
  /// Removes the wrapper and its directory.
  ~ParameterWrapper();
  ParameterWrapper(const ParameterWrapper&) = delete;
  ParameterWrapper& operator=(const ParameterWrapper&) = delete;
  /// The file for gmsh to open.
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::filesystem::path directory_;
};

}  // namespace stagger::meshgen
