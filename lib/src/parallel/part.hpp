#pragma once
// One rank's part of a distributed run (docs/parallel.md, "Ghost layers"): its owned zones
// and the ghost layers around them, and its mesh, restricted and renumbered in the serial
// (global) order, so that each point's corners stay in the serial order.
#include <algorithm>
#include <vector>

#include "stagger/mesh.hpp"

namespace stagger::parallel {

struct Part {
  std::vector<Index> zones, points;            // local -> global (ascending)
  std::vector<Index> zone_local, point_local;  // global -> local, -1 when absent
};

// Owned zones and `layers` layers of zones around them (a layer: the zones sharing a point
// with the previous ones). docs/parallel.md, "Ghost layers", gives the depth the step needs.
Part make_part(const Mesh& m, const std::vector<int>& owner, int rank, int layers);

// The global-to-local maps of `part` over a mesh of `global_zones` zones and `global_points`
// points, from its local-to-global lists.
void number_part(Part& part, Index global_zones, Index global_points);

// The local number of global zone or point `id` in a part's ascending global numbers (-1 when
// absent): a binary search, no map of the whole problem.
inline Index local_index(const std::vector<Index>& global, Index id) {
  const auto at = std::lower_bound(global.begin(), global.end(), id);
  return at != global.end() && *at == id ? static_cast<Index>(at - global.begin()) : -1;
}

// A part's mesh without its arrays: the source, the region names and the tags (the edges of
// the part's zones, in the serial order).
Mesh part_names(const Mesh& m, const Part& part);

// The arrays of a part's mesh. They are made one at a time and handed to `each(member, array)`
// in the order part_arrays() (part_transfer.cpp) sends them, so that rank 0 holds one array of
// a part beside the whole problem, not the part's mesh (docs/parallel.md, "Memory").
template <class F>
void part_mesh_arrays(const Mesh& m, const Part& part, F&& each) {
  const auto np = static_cast<Index>(part.points.size());
  {
    std::vector<double> v;
    v.reserve(part.points.size());
    for (Index p : part.points) v.push_back(m.x[p]);
    each(&Mesh::x, v);
    v.clear();
    for (Index p : part.points) v.push_back(m.y[p]);
    each(&Mesh::y, v);
  }
  std::vector<Index> v;
  v.reserve(part.zones.size() + 1);
  v.push_back(0);
  for (Index z : part.zones) v.push_back(v.back() + m.zone_corner_begin[z + 1] - m.zone_corner_begin[z]);
  const std::size_t corners = static_cast<std::size_t>(v.back());
  each(&Mesh::zone_corner_begin, v);
  const auto for_corners = [&](auto&& body) {  // (local zone, whole-mesh corner)
    for (std::size_t i = 0; i < part.zones.size(); ++i)
      for (Index c = m.zone_corner_begin[part.zones[i]]; c < m.zone_corner_begin[part.zones[i] + 1]; ++c)
        body(static_cast<Index>(i), c);
  };
  v.clear();
  v.reserve(corners);
  for_corners([&](Index, Index c) { v.push_back(part.point_local[m.corner_point[c]]); });
  each(&Mesh::corner_point, v);
  v.clear();
  for_corners([&](Index z, Index) { v.push_back(z); });
  each(&Mesh::corner_zone, v);
  std::vector<Index> begin(np + 1, 0);
  for_corners([&](Index, Index c) { ++begin[part.point_local[m.corner_point[c]] + 1]; });
  for (Index p = 0; p < np; ++p) begin[p + 1] += begin[p];
  v = begin;
  each(&Mesh::point_corner_begin, v);
  v.assign(corners, 0);
  Index local_corner = 0;
  for_corners([&](Index, Index c) { v[begin[part.point_local[m.corner_point[c]]]++] = local_corner++; });
  begin = {};
  each(&Mesh::point_corners, v);
  v.clear();
  for (Index z : part.zones) v.push_back(m.zone_region[z]);
  each(&Mesh::zone_region, v);
  v.assign(m.num_regions() + 1, 0);
  for (Index z : part.zones) ++v[m.zone_region[z] + 1];
  for (Index r = 0; r < m.num_regions(); ++r) v[r + 1] += v[r];
  each(&Mesh::region_zone_begin, v);
}

}  // namespace stagger::parallel
