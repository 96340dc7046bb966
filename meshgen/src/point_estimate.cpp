/// @file point_estimate.cpp
/// The mesh size estimate before meshing (point_estimate.hpp).
#include "point_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

#include "gmsh_api.hpp"
#include "gmsh_session.hpp"
#include "msh_element_types.hpp"
#include "stagger/error.hpp"

namespace stagger::meshgen {
namespace {

struct SurfaceEstimate {
  int tag = 0;
  double area = 0, longest = 0, shortest = 0, points = 0;
};

/// Each surface's area (the shoelace sum over its oriented boundary's segments) and longest
/// boundary segment, from the curves' mesh.
std::vector<SurfaceEstimate> surface_estimates() {
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, parametric;
  gm::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
  std::unordered_map<std::size_t, std::pair<double, double>> at;
  for (std::size_t k = 0; k < node_tags.size(); ++k) at[node_tags[k]] = {coords[3 * k], coords[3 * k + 1]};
  gmsh::vectorpair surfaces;
  gm::model::getEntities(surfaces, 2);
  std::vector<SurfaceEstimate> estimates;
  for (const auto& surface : surfaces) {
    gmsh::vectorpair boundary;
    gm::model::getBoundary({surface}, boundary, false, true, false);
    SurfaceEstimate e;
    e.tag = surface.second;
    double twice_area = 0;
    for (const auto& [dim, signed_tag] : boundary) {
      if (dim != 1) continue;
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, element_nodes;
      gm::model::mesh::getElements(types, element_tags, element_nodes, 1, std::abs(signed_tag));
      for (std::size_t t = 0; t < types.size(); ++t) {
        if (types[t] != kLine2) continue;
        const std::vector<std::size_t>& nodes = element_nodes[t];
        for (std::size_t k = 0; k + 1 < nodes.size(); k += 2) {
          const auto a = at.find(nodes[k]), b = at.find(nodes[k + 1]);
          if (a == at.end() || b == at.end()) continue;
          const auto [x0, y0] = a->second;
          const auto [x1, y1] = b->second;
          twice_area += (signed_tag < 0 ? -1.0 : 1.0) * (x0 * y1 - x1 * y0);
          const double length = std::hypot(x1 - x0, y1 - y0);
          e.longest = std::max(e.longest, length);
          e.shortest = e.shortest > 0 ? std::min(e.shortest, length) : length;
        }
      }
    }
    e.area = 0.5 * std::abs(twice_area);
    if (e.longest > 0) e.points = e.area / (e.longest * e.longest);
    estimates.push_back(e);
  }
  return estimates;
}

std::string number(double value) {
  std::ostringstream s;
  s.precision(3);
  s << value;
  return s.str();
}

/// Throws if the curves' mesh now in the model gives more than `limit` points; `floor` > 0:
/// that mesh was made with sizes raised to at least `floor`.
void refuse_above(const std::string& path, double limit, double floor) {
  const std::vector<SurfaceEstimate> estimates = surface_estimates();
  double total = 0;
  bool raised = false;  // a segment at the floor: the sizes asked for are smaller there
  const SurfaceEstimate* largest = nullptr;
  for (const SurfaceEstimate& e : estimates) {
    total += e.points;
    raised = raised || (floor > 0 && e.shortest > 0 && e.shortest < 1.01 * floor);
    if (!largest || e.points > largest->points) largest = &e;
  }
  if (total <= limit || !largest) return;
  throw Error(path + ": its mesh would have at least about " + number(total) + " points (surface " +
              std::to_string(largest->tag) + ": area " + number(largest->area) + ", boundary segments up to " +
              number(largest->longest) + " long, about " + number(largest->points) + " points" +
              (raised ? "; counted with the mesh sizes raised to at least " + number(floor) +
                            ": the sizes asked for are smaller still"
                      : std::string()) +
              "), more than the limit of " + number(limit) +
              " (scene key mesh.max_points, stagger mesh --max-points; 0: no limit); check the mesh sizes "
              "(characteristic lengths, Mesh.MeshSizeFactor) or raise the limit");
}

}  // namespace

void check_point_estimate(const std::string& path, double limit) {
  if (!(limit > 0)) return;
  double extend = 1;
  gm::option::getNumber("Mesh.MeshSizeExtendFromBoundary", extend);
  if (extend == 0) return;
  // Sizes so small that the curves' mesh itself would be huge (a size of 1e-8 on a unit
  // square: 4e8 boundary points, minutes and gigabytes): first a pass with sizes raised to
  // a floor that a mesh within the limit does not go below. Raised sizes only lower the
  // estimate, so a refusal then is still right; otherwise that mesh is cleared.
  double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
  gm::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
  const double box = (x1 - x0) * (y1 - y0);
  double size_min = 0;
  gm::option::getNumber("Mesh.MeshSizeMin", size_min);
  const double floor = std::sqrt(box / limit) / 2;
  if (std::isfinite(floor) && floor > size_min) {
    gm::option::setNumber("Mesh.MeshSizeMin", floor);
    gm::model::mesh::generate(1);
    gm::option::setNumber("Mesh.MeshSizeMin", size_min);
    throw_if_gmsh_error(path, "meshing");
    refuse_above(path, limit, floor);
    gm::model::mesh::clear();
  }
  gm::model::mesh::generate(1);
  throw_if_gmsh_error(path, "meshing");
  refuse_above(path, limit, 0);
}

}  // namespace stagger::meshgen
