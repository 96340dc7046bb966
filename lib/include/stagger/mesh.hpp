#pragma once
/// @file mesh.hpp
/// Plain-array meshes: the polygon soup that importers produce, and the checked,
/// counter-clockwise, flat-array Mesh that the physics runs on.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace stagger {

/// Index of a point, zone, corner or region in a Mesh.
using Index = std::int32_t;

/// A boundary curve segment (two point ids) with the index of its tag name.
struct TaggedEdge {
  std::int64_t a = 0, b = 0;  ///< point ids in the soup
  int tag = 0;                ///< index into PolygonSoup::tag_names
};

/// Polygons as they come from a file or a generator: any orientation, possibly with
/// orphan points. Regions (physical surfaces) and boundary tags (physical curves) by name.
struct PolygonSoup {
  std::vector<double> x, y;                    ///< point coordinates
  std::vector<std::int64_t> polygon_begin{0};  ///< offsets into polygon_points (size npoly+1)
  std::vector<std::int64_t> polygon_points;    ///< point ids of each polygon, in order
  std::vector<int> polygon_region;             ///< region index of each polygon
  std::vector<std::string> region_names;       ///< region index -> name
  std::vector<TaggedEdge> tagged_edges;        ///< boundary segments with tag indices
  std::vector<std::string> tag_names;          ///< tag index -> name
  std::string source = "<memory>";             ///< file name (or description) for messages
  /// 2D elements of the file that belong to no physical surface (left out of the soup);
  /// build_mesh notes them, and rejects them under quads_only.
  std::int64_t unassigned_elements = 0;
  std::vector<std::string> notes;  ///< what the importer left out or changed, for the user

  /// Appends a polygon; returns its index.
  std::size_t add_polygon(const std::vector<std::int64_t>& points, int region);
  /// Number of polygons.
  std::size_t num_polygons() const { return polygon_begin.size() - 1; }
};

/// A named boundary: its edges (each oriented as the zone it belongs to, CCW) and points.
struct BoundaryTag {
  std::string name;                         ///< physical curve name (e.g. "left")
  std::vector<std::array<Index, 2>> edges;  ///< point pairs, in the zone's CCW order
  std::vector<Index> points;                ///< sorted, unique
};

/// The checked mesh. Zones are counter-clockwise polygons sorted by region; each zone's
/// corners are contiguous; corner c belongs to zone corner_zone[c] and point corner_point[c].
/// The side of corner c is the edge from corner_point[c] to the next corner's point.
struct Mesh {
  std::vector<double> x, y;                  ///< point positions
  std::vector<Index> zone_corner_begin{0};   ///< size nzones+1
  std::vector<Index> corner_point;           ///< size ncorners
  std::vector<Index> corner_zone;            ///< size ncorners
  std::vector<Index> point_corner_begin{0};  ///< CSR point -> corners, size npoints+1
  std::vector<Index> point_corners;          ///< corners of each point, ascending
  std::vector<Index> zone_region;            ///< region index of each zone
  std::vector<Index> region_zone_begin{0};   ///< zones of region r: [begin[r], begin[r+1])
  std::vector<std::string> region_names;     ///< region index -> name
  std::vector<BoundaryTag> tags;             ///< named boundaries
  std::string source = "<memory>";           ///< where the mesh came from, for messages

  /// @name Sizes
  ///@{
  Index num_points() const { return static_cast<Index>(x.size()); }
  Index num_zones() const { return static_cast<Index>(zone_corner_begin.size()) - 1; }
  Index num_corners() const { return static_cast<Index>(corner_point.size()); }
  Index num_regions() const { return static_cast<Index>(region_names.size()); }
  ///@}
  bool all_quads() const;  ///< every zone has four corners
  /// Index of the region with this name, or -1.
  int region_index(const std::string& name) const;
  /// Index into `tags` of the tag with this name, or -1.
  int tag_index(const std::string& name) const;
};

/// What build_mesh repaired or dropped, for the user to read.
struct MeshBuildReport {
  int reoriented_zones = 0;        ///< clockwise zones turned counter-clockwise
  int dropped_points = 0;          ///< orphan points removed
  double topology_seconds = 0;     ///< wall time of the CGAL topology check (0 when skipped)
  std::vector<std::string> notes;  ///< one line per repair, for the user
};

/// Options of the soup -> mesh import.
struct MeshBuildOptions {
  bool quads_only = false;  ///< reject any zone that is not a quadrilateral
  /// Check manifoldness and orientation consistency with CGAL and find boundary loops. The
  /// built-in generators are valid by construction and may skip it (saves time and the
  /// peak memory of CGAL's halfedge structure on 10^6-zone meshes); the geometric checks
  /// (duplicate points, zero-area and bow-tie zones, orientation by signed area) always run.
  bool check_topology = true;
};

/// Checks a polygon soup with CGAL and builds the flat arrays: orientation made consistent
/// and counter-clockwise, non-manifold points/edges, degenerate or self-intersecting zones
/// and duplicate points rejected (stagger::Error naming the zone/point and the source),
/// orphan points dropped, zones sorted by region, tagged edges matched to mesh edges.
Mesh build_mesh(const PolygonSoup& soup, const MeshBuildOptions& options = {}, MeshBuildReport* report = nullptr);

/// Mesh quality figures (user report, `stagger mesh --check`).
struct MeshQuality {
  double min_area = 0, max_area = 0;                   ///< zone areas
  double max_aspect_ratio = 0;                         ///< longest edge / shortest edge over zones
  double min_angle_degrees = 0;                        ///< smallest interior angle
  Index non_convex_zones = 0;                          ///< zones with an interior angle above 180 degrees
  Index triangles = 0, quads = 0, other_polygons = 0;  ///< zones by vertex count
};
/// Computes the quality figures of a mesh (at its stored positions).
MeshQuality mesh_quality(const Mesh& mesh);

/// Signed area of zone z (positive for CCW).
double zone_area(const Mesh& mesh, Index z);
/// Centre of zone z: the average of its vertices (where initial fields are evaluated).
std::array<double, 2> zone_centre(const Mesh& mesh, Index z);

/// The twin of each corner's side (the side of corner c runs from corner_point[c] to the next
/// corner's point): the corner of the zone across whose side runs back along it, so it sits at
/// the far end of c's side; -1 where the side is on the boundary. One pass over the
/// point-corner lists, no map; the heat flux, the edge viscosity's continuation and the remap
/// take their neighbours across sides from it.
std::vector<Index> side_twins(const Mesh& mesh);

}  // namespace stagger
