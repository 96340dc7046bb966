#pragma once
/// @file topology_cgal.hpp
/// Private plain-array interface to the one translation unit that includes CGAL.
/// Nothing here exposes a CGAL type, so `-frounding-math` and CGAL's compile cost stay in
/// topology_cgal.cpp.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace stagger::detail {

/// A compacted polygon soup: every point is used by at least one polygon and no two
/// points coincide (build_mesh checks both before calling).
struct TopologyInput {
  std::span<const double> x, y;
  std::span<const std::int64_t> polygon_begin;   ///< size npoly+1
  std::span<const std::int64_t> polygon_points;  ///< compact point ids
  std::span<const std::int64_t> point_ids;       ///< soup id of each compact point (messages)
  std::span<const std::int64_t> polygon_ids;     ///< soup index of each polygon (messages)
  std::string source;                            ///< file name for messages
};

struct TopologyResult {
  /// 1 where the polygon's final (counter-clockwise) order is the reverse of its input order.
  std::vector<std::uint8_t> reversed;
  /// Boundary loops as compact point ids, walked with the mesh interior on the left
  /// (outer boundaries counter-clockwise, holes clockwise).
  std::vector<std::vector<std::int64_t>> boundary_loops;
  int components = 0;          ///< edge-connected components of the mesh
  int flipped_components = 0;  ///< components that were clockwise as a whole and were flipped
};

/// Makes the orientation consistent with CGAL's orient_polygon_soup, then counter-clockwise
/// per connected component (by signed area), rejects non-manifold edges and points and
/// folded zones (stagger::Error naming the point/edge/zone and the source) and finds the
/// boundary loops on a CGAL Surface_mesh.
TopologyResult orient_and_check_topology(const TopologyInput& input);

}  // namespace stagger::detail
