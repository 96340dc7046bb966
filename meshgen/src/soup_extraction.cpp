/// @file soup_extraction.cpp
/// gmsh model -> polygon soup + tags (soup_extraction.hpp), in named steps: regions and their
/// zones, elements outside every region, tagged curves, points, and the zones' and edges'
/// point indices.
#include "soup_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

#include "gmsh_api.hpp"
#include "msh_element_types.hpp"
#include "number_text.hpp"
#include "stagger/error.hpp"

namespace stagger::meshgen {
namespace {

/// Regions by name, with their surface entities.
using Regions = std::vector<std::pair<std::string, std::vector<int>>>;

/// gmsh node tags of the soup's zones and tagged edges, translated to point indices at the end.
struct NodeTags {
  std::vector<std::size_t> polygon;  ///< every zone's corners, zone after zone
  std::vector<std::size_t> edge;     ///< two per tagged edge
  std::vector<int> edge_tag;         ///< the tag of each edge
};

/// The soup's points: the gmsh node tags they come from, in increasing order, and each tag's
/// point index.
struct PointNumbers {
  std::vector<std::size_t> used;
  std::unordered_map<std::size_t, std::int64_t> index;
};

/// Every node of the gmsh model: tags and x, y, z.
struct ModelNodes {
  std::vector<std::size_t> tags;
  std::vector<double> coord;
};

std::string physical_name(int dim, int tag) {
  std::string name;
  gm::model::getPhysicalName(dim, tag, name);
  if (!name.empty()) return name;
  return (dim == 2 ? "surface_" : "curve_") + std::to_string(tag);
}

std::string element_name(int type) {
  std::string name;
  int dim = 0, order = 0, nodes = 0, primary = 0;
  std::vector<double> local;
  gm::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
  return name;
}

/// Regions: the physical surfaces `groups` by name; without any, every surface entity is a
/// region.
Regions surface_regions(const gmsh::vectorpair& groups) {
  Regions regions;
  if (groups.empty()) {
    gmsh::vectorpair entities;
    gm::model::getEntities(entities, 2);
    for (const auto& [dim, tag] : entities) regions.push_back({"surface_" + std::to_string(tag), {tag}});
  } else {
    for (const auto& [dim, tag] : groups) {
      std::vector<int> entities;
      gm::model::getEntitiesForPhysicalGroup(dim, tag, entities);
      regions.push_back({physical_name(dim, tag), entities});
    }
  }
  return regions;
}

/// Adds the regions and the zones of their surfaces to `soup`; returns each surface entity's
/// region.
std::map<int, std::string> add_zones(const std::string& path, const Regions& regions, PolygonSoup& soup,
                                     NodeTags& nodes) {
  std::map<int, std::string> entity_region;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    soup.region_names.push_back(regions[r].first);
    for (int entity : regions[r].second) {
      const auto [it, fresh] = entity_region.emplace(entity, regions[r].first);
      if (!fresh)
        throw Error(path + ": surface " + std::to_string(entity) +
                    " is in two physical "
                    "surfaces, '" +
                    it->second + "' and '" + regions[r].first + "'; a zone can belong to one region only");
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gm::model::mesh::getElements(types, element_tags, node_tags, 2, entity);
      for (std::size_t k = 0; k < types.size(); ++k) {
        const std::size_t n = types[k] == kTriangle3 ? 3 : types[k] == kQuad4 ? 4 : 0;
        if (n == 0)
          throw Error(path + ": surface " + std::to_string(entity) + " has elements of type '" +
                      element_name(types[k]) +
                      "'; only first-order triangles and quadrangles are supported "
                      "(set Mesh.ElementOrder = 1)");
        const auto& corners = node_tags[k];
        for (std::size_t e = 0; e + n <= corners.size(); e += n) {
          soup.polygon_begin.push_back(soup.polygon_begin.back() + static_cast<std::int64_t>(n));
          soup.polygon_region.push_back(static_cast<int>(r));
          nodes.polygon.insert(nodes.polygon.end(), corners.begin() + static_cast<std::ptrdiff_t>(e),
                               corners.begin() + static_cast<std::ptrdiff_t>(e + n));
        }
      }
    }
  }
  return entity_region;
}

/// 2D elements in surfaces outside every physical surface are left out: say so.
void note_unassigned_elements(const std::map<int, std::string>& entity_region, PolygonSoup& soup) {
  gmsh::vectorpair surfaces;
  gm::model::getEntities(surfaces, 2);
  std::int64_t left_out = 0, kept = static_cast<std::int64_t>(soup.polygon_region.size());
  std::string which;
  for (const auto& [dim, tag] : surfaces) {
    if (entity_region.count(tag)) continue;
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gm::model::mesh::getElements(types, element_tags, node_tags, 2, tag);
    std::int64_t here = 0;
    for (const auto& tags : element_tags) here += static_cast<std::int64_t>(tags.size());
    if (here == 0) continue;
    left_out += here;
    if (which.size() < 60) which += (which.empty() ? "" : ", ") + std::to_string(tag);
  }
  soup.unassigned_elements = left_out;
  if (left_out > 0)
    soup.notes.push_back(std::to_string(left_out) + " of " + std::to_string(left_out + kept) +
                         " 2D elements belong to no physical surface (surface(s) " + which +
                         ") and were left out; add them to a Physical Surface to keep them");
}

/// Tags: physical curves, their 2-node line elements.
void add_tagged_edges(const std::string& path, PolygonSoup& soup, NodeTags& nodes) {
  gmsh::vectorpair curves;
  gm::model::getPhysicalGroups(curves, 1);
  for (const auto& [dim, tag] : curves) {
    const int t = static_cast<int>(soup.tag_names.size());
    soup.tag_names.push_back(physical_name(dim, tag));
    std::vector<int> entities;
    gm::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    std::size_t interfaces = 0, kept_entities = 0;
    for (int entity : entities) {
      // A partitioned mesh has curves between partitions (their parent is a surface, not
      // a model curve): they are no boundary, so they are no tag.
      std::vector<int> partitions;
      gm::model::getPartitions(1, entity, partitions);
      if (!partitions.empty()) {
        int parent_dim = -1, parent_tag = -1;
        gm::model::getParent(1, entity, parent_dim, parent_tag);
        if (parent_dim != 1) {
          ++interfaces;
          continue;
        }
      }
      ++kept_entities;
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gm::model::mesh::getElements(types, element_tags, node_tags, 1, entity);
      for (std::size_t k = 0; k < types.size(); ++k) {
        if (types[k] != kLine2)
          throw Error(path + ": curve " + std::to_string(entity) + " of physical curve '" + soup.tag_names.back() +
                      "' has elements of type '" + element_name(types[k]) + "'; only 2-node lines are supported");
        for (std::size_t e = 0; e + 2 <= node_tags[k].size(); e += 2) {
          nodes.edge.push_back(node_tags[k][e]);
          nodes.edge.push_back(node_tags[k][e + 1]);
          nodes.edge_tag.push_back(t);
        }
      }
    }
    if (interfaces > 0) {
      soup.notes.push_back("physical curve '" + soup.tag_names.back() + "': " + std::to_string(interfaces) +
                           " partition interface curve(s) are not boundaries and were left out" +
                           (kept_entities == 0 ? std::string(" (and so was the tag)") : std::string()));
      if (kept_entities == 0) soup.tag_names.pop_back();
    }
  }
}

/// Points: only the nodes that zones use (gmsh also returns orphans such as circle
/// centres), numbered in increasing gmsh tag order (tags need not be contiguous).
PointNumbers number_points(const std::vector<std::size_t>& polygon_nodes) {
  PointNumbers numbers;
  numbers.used = polygon_nodes;
  std::sort(numbers.used.begin(), numbers.used.end());
  numbers.used.erase(std::unique(numbers.used.begin(), numbers.used.end()), numbers.used.end());
  numbers.index.reserve(numbers.used.size());
  for (std::size_t i = 0; i < numbers.used.size(); ++i)
    numbers.index.emplace(numbers.used[i], static_cast<std::int64_t>(i));
  return numbers;
}

ModelNodes model_nodes() {
  ModelNodes nodes;
  std::vector<double> parametric;
  gm::model::mesh::getNodes(nodes.tags, nodes.coord, parametric, -1, -1, false, false);
  return nodes;
}

/// The soup's x and y from the model's nodes; every used node must have coordinates.
void set_coordinates(const std::string& path, const PointNumbers& numbers, const ModelNodes& model, PolygonSoup& soup) {
  soup.x.assign(numbers.used.size(), 0.0);
  soup.y.assign(numbers.used.size(), 0.0);
  std::vector<char> found(numbers.used.size(), 0);
  for (std::size_t k = 0; k < model.tags.size(); ++k) {
    const auto it = numbers.index.find(model.tags[k]);
    if (it == numbers.index.end()) continue;
    const auto i = static_cast<std::size_t>(it->second);
    soup.x[i] = model.coord[3 * k];
    soup.y[i] = model.coord[3 * k + 1];
    found[i] = 1;
  }
  for (std::size_t i = 0; i < numbers.used.size(); ++i)
    if (!found[i]) throw Error(path + ": element node " + std::to_string(numbers.used[i]) + " has no coordinates");
}

/// The mesh must lie in a plane z = const: x-y is dropped otherwise (and an x-z mesh would
/// collapse into duplicate points).
void require_xy_plane(const std::string& path, const PointNumbers& numbers, const ModelNodes& model) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  std::size_t z_low = 0, z_high = 0;
  for (std::size_t k = 0; k < model.tags.size(); ++k) {
    if (!numbers.index.count(model.tags[k])) continue;
    for (int d = 0; d < 3; ++d) {
      const double v = model.coord[3 * k + static_cast<std::size_t>(d)];
      if (v < lo[d]) {
        lo[d] = v;
        if (d == 2) z_low = model.tags[k];
      }
      if (v > hi[d]) {
        hi[d] = v;
        if (d == 2) z_high = model.tags[k];
      }
    }
  }
  const double span = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double tol = 1e-10 * span;
  if (hi[2] - lo[2] > tol) {
    const auto range = [&](int d) { return number_text(lo[d]) + " to " + number_text(hi[d]); };
    if (hi[1] - lo[1] <= tol || hi[0] - lo[0] <= tol) {
      const bool xz = hi[1] - lo[1] <= tol;
      throw Error(path + ": the mesh lies in the " + (xz ? "x-z" : "y-z") + " plane (" + (xz ? "y" : "x") + " = " +
                  number_text(xz ? lo[1] : lo[0]) + " everywhere, z from " + range(2) +
                  "); stagger meshes lie in the x-y plane: rotate the geometry (e.g. Rotate in the .geo) "
                  "or re-export it");
    }
    throw Error(path + ": the mesh is not flat in the x-y plane: z varies from " + range(2) + " (nodes " +
                std::to_string(z_low) + " and " + std::to_string(z_high) + "); stagger meshes are 2D, with z constant");
  }
}

/// The zones' corners and the tagged edges as point indices; a tagged edge must join points
/// of zones.
void connect(const std::string& path, const NodeTags& nodes, const PointNumbers& numbers, PolygonSoup& soup) {
  const auto& index = numbers.index;
  soup.polygon_points.reserve(nodes.polygon.size());
  for (std::size_t node : nodes.polygon) soup.polygon_points.push_back(index.at(node));
  for (std::size_t e = 0; e < nodes.edge_tag.size(); ++e) {
    const auto a = index.find(nodes.edge[2 * e]), b = index.find(nodes.edge[2 * e + 1]);
    if (a == index.end() || b == index.end())
      throw Error(path + ": physical curve '" + soup.tag_names[static_cast<std::size_t>(nodes.edge_tag[e])] +
                  "' has an edge (nodes " + std::to_string(nodes.edge[2 * e]) + ", " +
                  std::to_string(nodes.edge[2 * e + 1]) +
                  ") that bounds no zone of a physical surface; tag only curves of the meshed domain");
    soup.tagged_edges.push_back({a->second, b->second, nodes.edge_tag[e]});
  }
}

}  // namespace

void require_planar_model(const std::string& path, bool volume_entities_count) {
  gmsh::vectorpair volumes;
  gm::model::getEntities(volumes, 3);
  if (volumes.empty()) return;
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gm::model::mesh::getElements(types, element_tags, node_tags, 3, -1);
  std::size_t elements = 0;
  for (const auto& tags : element_tags) elements += tags.size();
  if (elements == 0 && !volume_entities_count) return;
  throw Error(path + ": a 3D model (" + std::to_string(volumes.size()) + " volume(s)" +
              (elements > 0 ? ", " + std::to_string(elements) + " volume elements" : std::string()) +
              "); stagger is 2D: give it surfaces in the x-y plane (z = 0) only");
}

PolygonSoup extract_soup(const std::string& path) {
  PolygonSoup soup;
  soup.source = path;
  NodeTags nodes;
  gmsh::vectorpair groups;
  gm::model::getPhysicalGroups(groups, 2);
  const std::map<int, std::string> entity_region = add_zones(path, surface_regions(groups), soup, nodes);
  if (!groups.empty()) note_unassigned_elements(entity_region, soup);
  if (nodes.polygon.empty())
    throw Error("empty mesh: " + path + " gave no 2D elements" +
                (groups.empty() ? std::string(" (and it defines no physical surface)")
                                : std::string(" in its physical surfaces")) +
                "; check the geometry and its Physical Surface definitions");
  add_tagged_edges(path, soup, nodes);
  const PointNumbers numbers = number_points(nodes.polygon);
  const ModelNodes model = model_nodes();
  set_coordinates(path, numbers, model, soup);
  require_xy_plane(path, numbers, model);
  connect(path, nodes, numbers, soup);
  return soup;
}

}  // namespace stagger::meshgen
