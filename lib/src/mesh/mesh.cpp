/// @file mesh.cpp
/// Small Mesh/PolygonSoup members, zone areas and the mesh quality report.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "stagger/mesh.hpp"

#include "mesh/polygon.hpp"

namespace stagger {

std::size_t PolygonSoup::add_polygon(const std::vector<std::int64_t>& points, int region) {
  if (polygon_begin.empty()) polygon_begin.push_back(0);
  polygon_points.insert(polygon_points.end(), points.begin(), points.end());
  polygon_begin.push_back(static_cast<std::int64_t>(polygon_points.size()));
  polygon_region.push_back(region);
  return polygon_begin.size() - 2;
}

bool Mesh::all_quads() const {
  for (Index z = 0; z < num_zones(); ++z)
    if (zone_corner_begin[z + 1] - zone_corner_begin[z] != 4) return false;
  return true;
}

int Mesh::region_index(const std::string& name) const {
  const auto it = std::find(region_names.begin(), region_names.end(), name);
  return it == region_names.end() ? -1 : static_cast<int>(it - region_names.begin());
}

int Mesh::tag_index(const std::string& name) const {
  for (std::size_t t = 0; t < tags.size(); ++t)
    if (tags[t].name == name) return static_cast<int>(t);
  return -1;
}

double zone_area(const Mesh& mesh, Index z) {
  const Index begin = mesh.zone_corner_begin[z];
  const int n = static_cast<int>(mesh.zone_corner_begin[z + 1] - begin);
  return polygon_area(
      n, [&](int k) { return mesh.x[mesh.corner_point[begin + k]]; },
      [&](int k) { return mesh.y[mesh.corner_point[begin + k]]; });
}

std::array<double, 2> zone_centre(const Mesh& mesh, Index z) {
  const Index begin = mesh.zone_corner_begin[z];
  const int n = static_cast<int>(mesh.zone_corner_begin[z + 1] - begin);
  return polygon_centre(
      n, [&](int k) { return mesh.x[mesh.corner_point[begin + k]]; },
      [&](int k) { return mesh.y[mesh.corner_point[begin + k]]; });
}

std::vector<Index> side_twins(const Mesh& m) {
  std::vector<Index> twin(m.num_corners(), -1);
  for (Index z = 0; z < m.num_zones(); ++z) {
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    for (Index k = 0; k < n; ++k) {
      const Index p0 = m.corner_point[b + k], p1 = m.corner_point[b + (k + 1 == n ? 0 : k + 1)];
      // The corner of another zone at p1 whose side runs back to p0 (a checked mesh is
      // manifold: at most one).
      for (Index i = m.point_corner_begin[p1]; i < m.point_corner_begin[p1 + 1]; ++i) {
        const Index c = m.point_corners[i], zn = m.corner_zone[c];
        if (zn == z) continue;
        const Index bn = m.zone_corner_begin[zn], nn = m.zone_corner_begin[zn + 1] - bn;
        if (m.corner_point[c + 1 == bn + nn ? bn : c + 1] == p0) {
          twin[b + k] = c;
          break;
        }
      }
    }
  }
  return twin;
}

MeshQuality mesh_quality(const Mesh& mesh) {
  MeshQuality q;
  if (mesh.num_zones() == 0) return q;
  q.min_area = std::numeric_limits<double>::max();
  q.max_area = std::numeric_limits<double>::lowest();
  q.min_angle_degrees = 360;
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    const Index n = end - begin;
    if (n == 3)
      ++q.triangles;
    else if (n == 4)
      ++q.quads;
    else
      ++q.other_polygons;
    const double area = zone_area(mesh, z);
    q.min_area = std::min(q.min_area, area);
    q.max_area = std::max(q.max_area, area);
    double shortest = std::numeric_limits<double>::max(), longest = 0;
    bool convex = true;
    for (Index k = 0; k < n; ++k) {
      const Index prev = mesh.corner_point[begin + (k + n - 1) % n];
      const Index here = mesh.corner_point[begin + k];
      const Index next = mesh.corner_point[begin + (k + 1) % n];
      const double ax = mesh.x[next] - mesh.x[here], ay = mesh.y[next] - mesh.y[here];
      const double bx = mesh.x[prev] - mesh.x[here], by = mesh.y[prev] - mesh.y[here];
      const double length = std::hypot(ax, ay);
      shortest = std::min(shortest, length);
      longest = std::max(longest, length);
      // Interior angle of a counter-clockwise polygon, from the next edge round to the
      // previous one: in (0, 360) degrees; above 180 the zone is not convex.
      double angle = std::atan2(ax * by - ay * bx, ax * bx + ay * by);
      if (angle < 0) angle += 2 * std::numbers::pi;
      const double degrees = angle * 180 / std::numbers::pi;
      q.min_angle_degrees = std::min(q.min_angle_degrees, degrees);
      if (degrees > 180) convex = false;
    }
    if (!convex) ++q.non_convex_zones;
    if (shortest > 0) q.max_aspect_ratio = std::max(q.max_aspect_ratio, longest / shortest);
  }
  return q;
}

}  // namespace stagger
