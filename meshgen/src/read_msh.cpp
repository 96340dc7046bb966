/// @file read_msh.cpp
/// .msh files (MSH 2.2 and 4.1) read by gmsh in the gmsh child (read_msh, gmsh_child.hpp).
#include <string>

#include "gmsh_api.hpp"
#include "gmsh_child.hpp"
#include "gmsh_session.hpp"
#include "mesh_file.hpp"
#include "soup_extraction.hpp"
#include "stagger/meshgen.hpp"
#include "triangle_policy.hpp"

namespace stagger::meshgen {

PolygonSoup read_msh(const std::string& path, TrianglePolicy triangles) {
  GeoOptions options;
  options.triangles = triangles;
  return read_msh(path, options);
}

PolygonSoup read_msh(const std::string& path, const GeoOptions& options) {
  require_file(path, "mesh file");
  // Before gmsh sees it: gmsh runs a file that does not start like a mesh as a .geo script.
  check_msh_file(path);
  ChildRun run;
  run.path = path;
  run.doing = "reading";
  run.seconds = options.time_limit_seconds;
  run.mib = options.memory_limit_mib;
  run.sandbox = true;  // a .msh holds no commands
  run.crash_hint =
      "the file is corrupt (e.g. an element refers to a node that $Nodes does not define); "
      "check it with 'gmsh " +
      path + " -0' or re-export it";
  PolygonSoup soup = read_isolated(run, [&] {
    gm::open(path);
    throw_if_gmsh_error(path, "reading");
    require_planar_model(path, false);
    return extract_soup(path);
  });
  // gmsh's subdivision of a discrete (file) mesh duplicates nodes where entities meet, so a
  // .msh is subdivided here, on the soup.
  if (options.triangles == TrianglePolicy::subdivide) subdivide_soup(soup);
  apply_policy(soup, options.triangles);
  return soup;
}

}  // namespace stagger::meshgen
