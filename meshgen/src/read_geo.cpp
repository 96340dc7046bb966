/// @file read_geo.cpp
/// .geo files meshed by gmsh (read_geo): the scan for outside commands (geo_scanner.cpp), the
/// parameters (geo_parameters.hpp), then open, mesh and extract in the gmsh child
/// (gmsh_child.hpp).
#include <cstddef>
#include <cstdlib>
#include <string>
#include <vector>

#include "geo_parameters.hpp"
#include "geo_scanner.hpp"
#include "gmsh_api.hpp"
#include "gmsh_child.hpp"
#include "gmsh_session.hpp"
#include "mesh_file.hpp"
#include "msh_element_types.hpp"
#include "point_estimate.hpp"
#include "soup_extraction.hpp"
#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"
#include "triangle_policy.hpp"

namespace stagger::meshgen {
namespace {

/// Counts triangles in the current gmsh mesh of dimension 2.
std::size_t gmsh_triangles() {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gm::model::mesh::getElements(types, element_tags, node_tags, 2, -1);
  std::size_t n = 0;
  for (std::size_t k = 0; k < types.size(); ++k)
    if (types[k] == kTriangle3) n += element_tags[k].size();
  return n;
}

/// Subdivide policy after meshing: if triangles are left, split every element into quads
/// (gmsh's all-quad subdivision: each quad into 4, each triangle into 3, so the element
/// size halves).
void subdivide_if_triangles() {
  if (gmsh_triangles() == 0) return;
  gm::option::setNumber("Mesh.SubdivisionAlgorithm", 1);
  gm::model::mesh::refine();
}

/// In the gmsh session: opens `file` (the .geo or its parameter wrapper), meshes it as
/// `options` say and extracts the soup of `path`.
PolygonSoup mesh_geo(const std::string& path, const std::string& file, const GeoOptions& options) {
  gm::open(file);
  throw_if_gmsh_error(path, "reading");
  // Options after open(): the file may set its own. Algorithm 8 segfaults in Debian's
  // gmsh 4.8, so fall back to 6 (Frontal-Delaunay) and recombine.
  double algorithm = 0;
  gm::option::getNumber("Mesh.Algorithm", algorithm);
  if (algorithm == 8) gm::option::setNumber("Mesh.Algorithm", 6);
  if (options.recombine) {
    gm::option::setNumber("Mesh.RecombineAll", 1);
    // 1: blossom. The full-quad variants (2, 3) fail ("1D mesh cannot be divided by 2")
    // on transfinite curves with an odd number of segments, so the subdivide policy
    // recombines with blossom too and then subdivides if triangles are left.
    gm::option::setNumber("Mesh.RecombinationAlgorithm", 1);
  }
  require_planar_model(path, true);
  check_point_estimate(path, options.max_points);  // meshes the curves first
  gm::model::mesh::generate(2);
  throw_if_gmsh_error(path, "meshing");
  if (options.triangles == TrianglePolicy::subdivide) {
    subdivide_if_triangles();
    throw_if_gmsh_error(path, "subdividing");
  }
  return extract_soup(path);
}

}  // namespace

PolygonSoup read_geo(const std::string& path, const GeoOptions& options) {
  require_file(path, "geometry file");
  // STAGGER_GEO_SCAN=0 skips the scan but keeps the sandbox (tests of the sandbox).
  // Allowed commands are not refused, but the files included are still checked (regular
  // files, no include cycle).
  const char* scan = std::getenv("STAGGER_GEO_SCAN");
  if (!(scan && std::string(scan) == "0")) {
    const std::string found = scan_geo(path, !options.allow_commands);
    if (!found.empty())
      throw Error(found +
                  "; stagger refuses .geo commands that reach outside the mesh (set "
                  "mesh.allow_geo_commands = true, or stagger mesh --allow-geo-commands, to allow them: "
                  "that runs arbitrary code)");
  }
  const ParameterWrapper wrapper(path, options.parameters);
  ChildRun run;
  run.path = path;
  run.doing = "meshing";
  run.seconds = options.time_limit_seconds;
  run.mib = options.memory_limit_mib;
  run.sandbox = !options.allow_commands;
  run.crash_hint =
      "gmsh 4.8 crashes on some inputs, e.g. MeshAlgorithm Surface{...} = 8 (use 6 there) or a command "
      "after which it does not recover from an error; run 'gmsh -2 " +
      path + "' to see where it fails";
  PolygonSoup soup = read_isolated(run, [&] { return mesh_geo(path, wrapper.file(), options); });
  apply_policy(soup, options.triangles);
  return soup;
}

}  // namespace stagger::meshgen
