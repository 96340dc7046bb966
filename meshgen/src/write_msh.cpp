/// @file write_msh.cpp
/// A checked mesh written as MSH 4.1 through gmsh, in this process (write_msh).
#include <cstddef>
#include <string>
#include <vector>

#include "gmsh_api.hpp"
#include "gmsh_session.hpp"
#include "msh_element_types.hpp"
#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::meshgen {

void write_msh(const std::string& path, const Mesh& mesh) {
  if (mesh.num_zones() == 0) throw Error("write_msh: the mesh has no zones (" + path + ")");
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index n = mesh.zone_corner_begin[z + 1] - mesh.zone_corner_begin[z];
    if (n != 3 && n != 4)
      throw Error("write_msh " + path + ": zone " + std::to_string(z) + " has " + std::to_string(n) +
                  " corners; MSH stores only triangles and quadrangles");
  }
  with_gmsh(path, [&] {
    gm::model::add("stagger");
    // One discrete surface per region (tag r+1), one discrete curve per boundary tag.
    // All nodes live on the first region's surface; elements may use any node.
    const Index nregions = mesh.num_regions();
    for (Index r = 0; r < nregions; ++r) gm::model::addDiscreteEntity(2, r + 1);
    const int node_entity = mesh.zone_region[0] + 1;
    std::vector<std::size_t> node_tags(static_cast<std::size_t>(mesh.num_points()));
    std::vector<double> coord(3 * node_tags.size(), 0.0);
    for (std::size_t p = 0; p < node_tags.size(); ++p) {
      node_tags[p] = p + 1;
      coord[3 * p] = mesh.x[p];
      coord[3 * p + 1] = mesh.y[p];
    }
    gm::model::mesh::addNodes(2, node_entity, node_tags, coord);
    std::size_t element = 1;
    for (Index r = 0; r < nregions; ++r) {
      std::vector<std::size_t> tri_tags, tri_nodes, quad_tags, quad_nodes;
      for (Index z = mesh.region_zone_begin[r]; z < mesh.region_zone_begin[r + 1]; ++z) {
        const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
        auto& tags = e - b == 3 ? tri_tags : quad_tags;
        auto& nodes = e - b == 3 ? tri_nodes : quad_nodes;
        tags.push_back(element++);
        for (Index c = b; c < e; ++c) nodes.push_back(static_cast<std::size_t>(mesh.corner_point[c]) + 1);
      }
      if (!tri_tags.empty()) gm::model::mesh::addElementsByType(r + 1, kTriangle3, tri_tags, tri_nodes);
      if (!quad_tags.empty()) gm::model::mesh::addElementsByType(r + 1, kQuad4, quad_tags, quad_nodes);
      gm::model::addPhysicalGroup(2, {r + 1}, r + 1);
      gm::model::setPhysicalName(2, r + 1, mesh.region_names[static_cast<std::size_t>(r)]);
    }
    for (std::size_t t = 0; t < mesh.tags.size(); ++t) {
      const int entity = static_cast<int>(t) + 1;
      gm::model::addDiscreteEntity(1, entity);
      std::vector<std::size_t> line_tags, line_nodes;
      for (const auto& edge : mesh.tags[t].edges) {
        line_tags.push_back(element++);
        line_nodes.push_back(static_cast<std::size_t>(edge[0]) + 1);
        line_nodes.push_back(static_cast<std::size_t>(edge[1]) + 1);
      }
      if (!line_tags.empty()) gm::model::mesh::addElementsByType(entity, kLine2, line_tags, line_nodes);
      gm::model::addPhysicalGroup(1, {entity}, entity);
      gm::model::setPhysicalName(1, entity, mesh.tags[t].name);
    }
    gm::option::setNumber("Mesh.MshFileVersion", 4.1);
    gm::option::setNumber("Mesh.Binary", 1);  // exact doubles (ASCII MSH prints 16 digits)
    gm::write(path);
    throw_if_gmsh_error(path, "writing");
  });
}

}  // namespace stagger::meshgen
