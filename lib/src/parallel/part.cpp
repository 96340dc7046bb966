// One rank's part of a distributed run (docs/parallel.md, "Ghost layers"): the ghost layers
// around its owned zones, its local numbering and its mesh's names and tags.
#include "parallel/part.hpp"

#include <utility>

namespace stagger::parallel {

Part make_part(const Mesh& m, const std::vector<int>& owner, int rank, int layers) {
  const Index nz = m.num_zones(), np = m.num_points();
  std::vector<unsigned char> in(nz, 0), point_done(np, 0);
  std::vector<Index> frontier, next;
  for (Index z = 0; z < nz; ++z)
    if (owner[z] == rank) in[z] = 1, frontier.push_back(z);
  for (int layer = 0; layer < layers; ++layer) {
    next.clear();
    for (Index z : frontier)
      for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) {
        const Index p = m.corner_point[c];
        if (point_done[p]) continue;
        point_done[p] = 1;
        for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k) {
          const Index other = m.corner_zone[m.point_corners[k]];
          if (!in[other]) in[other] = 1, next.push_back(other);
        }
      }
    frontier.swap(next);
  }
  Part part;
  part.zone_local.assign(nz, -1);
  part.point_local.assign(np, -1);
  std::vector<unsigned char> point_in(np, 0);
  for (Index z = 0; z < nz; ++z) {
    if (!in[z]) continue;
    part.zone_local[z] = static_cast<Index>(part.zones.size());
    part.zones.push_back(z);
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) point_in[m.corner_point[c]] = 1;
  }
  for (Index p = 0; p < np; ++p)
    if (point_in[p]) part.point_local[p] = static_cast<Index>(part.points.size()), part.points.push_back(p);
  return part;
}

void number_part(Part& part, Index global_zones, Index global_points) {
  part.zone_local.assign(global_zones, -1);
  part.point_local.assign(global_points, -1);
  for (std::size_t i = 0; i < part.zones.size(); ++i) part.zone_local[part.zones[i]] = static_cast<Index>(i);
  for (std::size_t i = 0; i < part.points.size(); ++i) part.point_local[part.points[i]] = static_cast<Index>(i);
}

Mesh part_names(const Mesh& m, const Part& part) {
  Mesh local;
  local.source = m.source;
  local.region_names = m.region_names;
  for (const BoundaryTag& tag : m.tags) {
    BoundaryTag t;
    t.name = tag.name;
    for (const auto& e : tag.edges) {
      const Index a = part.point_local[e[0]], b = part.point_local[e[1]];
      if (a < 0 || b < 0) continue;
      bool mine = false;
      for (Index k = m.point_corner_begin[e[0]]; k < m.point_corner_begin[e[0] + 1] && !mine; ++k) {
        const Index c = m.point_corners[k], z = m.corner_zone[c];
        const Index next = c + 1 == m.zone_corner_begin[z + 1] ? m.zone_corner_begin[z] : c + 1;
        mine = part.zone_local[z] >= 0 && m.corner_point[next] == e[1];
      }
      if (mine) t.edges.push_back({a, b});
    }
    if (tag.edges.empty()) {
      for (Index p : tag.points)
        if (part.point_local[p] >= 0) t.points.push_back(part.point_local[p]);
    } else {
      for (const auto& e : t.edges) t.points.push_back(e[0]), t.points.push_back(e[1]);
      std::sort(t.points.begin(), t.points.end());
      t.points.erase(std::unique(t.points.begin(), t.points.end()), t.points.end());
    }
    local.tags.push_back(std::move(t));
  }
  return local;
}

}  // namespace stagger::parallel
