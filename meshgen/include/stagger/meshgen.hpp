#pragma once
/// @file meshgen.hpp
/// Geometries to polygon soups: .geo files meshed by gmsh, .msh files (MSH 2.2 and 4.1)
/// read by gmsh, and built-in structured generators. gmsh is a global singleton: every
/// function here serializes its use with a mutex (safe to call from several threads, but
/// not in parallel).
#include <string>
#include <utility>
#include <vector>

#include "stagger/mesh.hpp"

namespace stagger::meshgen {

/// What to do with triangles left after recombination.
enum class TrianglePolicy {
  accept,     ///< keep mixed quad/triangle zones (the kernels handle polygons)
  subdivide,  ///< split every element into quads (gmsh's all-quad subdivision)
  reject,     ///< stagger::Error naming the file and the number of triangles
};

/// How read_geo meshes a .geo file (and read_msh reads a .msh). gmsh runs in a child process
/// (docs/mesh.md, "gmsh in a child process"): the limits below bound it, and a crash, a
/// timeout or running out of memory becomes a stagger::Error naming the file.
struct GeoOptions {
  std::vector<std::pair<std::string, double>> parameters;  ///< like gmsh -setnumber
  bool recombine = true;                                   ///< recombine triangles into quads
  TrianglePolicy triangles = TrianglePolicy::accept;       ///< what to do with leftover triangles
  double time_limit_seconds = 600;                         ///< wall-time limit of the gmsh child; 0: none
  double memory_limit_mib = 8192;                          ///< address-space limit of the gmsh child (MiB); 0: none
  /// Refuse a .geo whose mesh would have more points than this (estimated from its boundary
  /// mesh before the surfaces are meshed; 0: no limit). A mesh of 1e6 points took more than
  /// 600 s (the time limit) on a 2-core machine.
  double max_points = 5e6;
  /// Allow .geo commands that reach outside the mesh (SystemCall, Printf > file, Exit, Sleep,
  /// Save, Merge of a script, ...). They run arbitrary code; by default they are refused
  /// before gmsh runs.
  bool allow_commands = false;
};

/// Why `path` cannot be read as a mesh or geometry file, or "" if it can: "not found", "is a
/// directory", "is a FIFO (named pipe)", "is a character device", "is a symbolic link loop",
/// ... (links are followed, so a link to a regular file is one).
std::string file_problem(const std::string& path);

/// Throws stagger::Error "FILE:LINE: what is wrong" unless `path` is a mesh gmsh reads as one:
/// it starts with $MeshFormat, version 2.x or 4.0/4.1, ASCII or binary (gmsh runs any other
/// .msh as a .geo script), and in an ASCII file every $PhysicalNames, $Nodes and $Elements
/// count matches its entries (gmsh drops the entries beyond a low count without a word).
void check_msh_file(const std::string& path);

/// The first .geo command of `path` (or of a file it includes) that reaches outside the
/// mesh, as "FILE:LINE: what", or "" if there is none (docs/mesh.md lists the commands).
std::string find_outside_command(const std::string& path);

/// Meshes a .geo file with gmsh; physical surfaces become regions, physical curves tags.
PolygonSoup read_geo(const std::string& path, const GeoOptions& options = {});
/// Reads a .msh file (MSH 2.2 or 4.1) through gmsh.
PolygonSoup read_msh(const std::string& path, TrianglePolicy triangles = TrianglePolicy::accept);
/// Reads a .msh file with the triangle policy and child-process limits of `options`.
PolygonSoup read_msh(const std::string& path, const GeoOptions& options);
/// Dispatches on the extension (.geo or .msh).
PolygonSoup read_mesh_file(const std::string& path, const GeoOptions& options = {});
/// Writes a mesh as MSH 4.1 (regions as physical surfaces, tags as physical curves).
void write_msh(const std::string& path, const Mesh& mesh);

/// Rectangle [x0,x1]x[y0,y1], nx x ny quads; region "domain"; tags left, right, bottom, top.
PolygonSoup rectangle(double x0, double x1, double y0, double y1, int nx, int ny);
/// Equal-angle annulus sector r0..r1, theta0..theta1 (radians), n_theta x n_r zones; region
/// "domain"; tags inner, outer, start (theta0 side), end (theta1 side). r0 = 0 makes the
/// centre ring triangles (no "inner" tag).
PolygonSoup annulus_sector(double r0, double r1, double theta0, double theta1, int n_theta, int n_r);
/// Full annulus (tube) r0..r1, n_theta x n_r; region "domain"; tags inner, outer.
PolygonSoup annulus(double r0, double r1, int n_theta, int n_r);

}  // namespace stagger::meshgen
