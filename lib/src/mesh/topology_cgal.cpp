/// @file topology_cgal.cpp
/// The only translation unit that includes CGAL (Surface_mesh + Polygon_mesh_processing).
/// It orients a polygon soup consistently, makes it counter-clockwise per connected
/// component, rejects non-manifold edges and points, and finds the boundary loops.
#include "topology_cgal.hpp"

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <sstream>

#include "polygon.hpp"
#include "stagger/error.hpp"

namespace stagger::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Simple_cartesian<double>;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
using Polygon = std::vector<std::size_t>;

/// What CGAL's orientation visitor saw; the visitor itself is copied by value, so it keeps
/// a pointer to this record.
struct OrientationRecord {
  bool has_edge = false, has_vertex = false;
  std::size_t edge_a = 0, edge_b = 0, edge_count = 0;
  std::size_t vertex = 0, vertex_fans = 0;
  std::vector<std::uint8_t>* reversed = nullptr;
};

struct RecordingVisitor : PMP::Default_orientation_visitor {
  explicit RecordingVisitor(OrientationRecord* r) : record(r) {}
  OrientationRecord* record;
  void non_manifold_edge(std::size_t a, std::size_t b, std::size_t count) {
    if (!record->has_edge) {
      record->has_edge = true;
      record->edge_a = a;
      record->edge_b = b;
      record->edge_count = count;
    }
  }
  void non_manifold_vertex(std::size_t v, std::size_t fans) {
    if (!record->has_vertex) {
      record->has_vertex = true;
      record->vertex = v;
      record->vertex_fans = fans;
    }
  }
  void duplicated_vertex(std::size_t, std::size_t) {}
  void vertex_id_in_polygon_replaced(std::size_t, std::size_t, std::size_t) {}
  void polygon_orientation_reversed(std::size_t p) { (*record->reversed)[p] ^= 1U; }
};

std::string point_text(const TopologyInput& in, std::size_t p) {
  std::ostringstream s;
  s.precision(12);
  s << "point " << in.point_ids[p] << " (" << in.x[p] << ", " << in.y[p] << ")";
  return s.str();
}

/// Shoelace formula: twice the signed area, positive for counter-clockwise.
double twice_signed_area(const TopologyInput& in, const Polygon& polygon) {
  return polygon_twice_area(
      static_cast<int>(polygon.size()), [&](int k) { return in.x[polygon[k]]; },
      [&](int k) { return in.y[polygon[k]]; });
}

}  // namespace

TopologyResult orient_and_check_topology(const TopologyInput& in) {
  const std::size_t npoints = in.x.size();
  const std::size_t npoly = in.polygon_begin.size() - 1;
  TopologyResult result;
  result.reversed.assign(npoly, 0);

  std::vector<Point3> points;
  points.reserve(npoints);
  for (std::size_t p = 0; p < npoints; ++p) points.emplace_back(in.x[p], in.y[p], 0.0);
  std::vector<Polygon> polygons(npoly);
  for (std::size_t f = 0; f < npoly; ++f)
    polygons[f].assign(in.polygon_points.begin() + in.polygon_begin[f],
                       in.polygon_points.begin() + in.polygon_begin[f + 1]);

  // 1. Consistent orientation. CGAL duplicates points where the soup is not a manifold
  //    surface and tells the visitor which edges/points those are: we reject instead.
  OrientationRecord record;
  record.reversed = &result.reversed;
  const bool oriented =
      PMP::orient_polygon_soup(points, polygons, CGAL::parameters::visitor(RecordingVisitor(&record)));
  if (record.has_edge) {
    throw Error("non-manifold edge between " + point_text(in, record.edge_a) + " and " + point_text(in, record.edge_b) +
                " in " + in.source + ": it is shared by " + std::to_string(record.edge_count) +
                " zones (at most 2 allowed); remove the overlapping or duplicated zones");
  }
  if (record.has_vertex) {
    throw Error("non-manifold " + point_text(in, record.vertex) + " in " + in.source + ": its zones form " +
                std::to_string(record.vertex_fans) +
                " fans that touch only at this point; zones must connect through edges "
                "(merge the meshes along an edge or split the point)");
  }
  if (!oriented || points.size() != npoints) {
    throw Error("the polygon soup of " + in.source +
                " cannot be oriented consistently (non-orientable or non-manifold)");
  }

  // 2. A Surface_mesh with vertex i = point i and face f = polygon f (the soup builder
  //    adds them in order; checked below).
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (mesh.number_of_vertices() != npoints || mesh.number_of_faces() != npoly) {
    throw Error("internal: CGAL mesh of " + in.source + " has " + std::to_string(mesh.number_of_vertices()) +
                " vertices and " + std::to_string(mesh.number_of_faces()) + " faces, expected " +
                std::to_string(npoints) + " and " + std::to_string(npoly));
  }

  // 3. Counter-clockwise per connected component: orient_polygon_soup only makes the
  //    orientation consistent, so flip a component whose total signed area is negative.
  auto component = mesh.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:component", 0).first;
  const std::size_t ncomponents = PMP::connected_components(mesh, component);
  result.components = static_cast<int>(ncomponents);
  std::vector<double> component_area(ncomponents, 0.0);
  std::vector<double> polygon_area(npoly);
  for (std::size_t f = 0; f < npoly; ++f) {
    polygon_area[f] = twice_signed_area(in, polygons[f]);
    component_area[component[SurfaceMesh::Face_index(static_cast<SurfaceMesh::size_type>(f))]] += polygon_area[f];
  }
  std::vector<SurfaceMesh::Face_index> to_flip;
  for (std::size_t f = 0; f < npoly; ++f) {
    const SurfaceMesh::Face_index face(static_cast<SurfaceMesh::size_type>(f));
    if (component_area[component[face]] < 0) {
      to_flip.push_back(face);
      result.reversed[f] ^= 1U;
      polygon_area[f] = -polygon_area[f];
    }
  }
  for (double a : component_area) result.flipped_components += a < 0 ? 1 : 0;
  if (!to_flip.empty()) PMP::reverse_face_orientations(to_flip, mesh);

  // A zone still clockwise after its component is counter-clockwise is folded over.
  for (std::size_t f = 0; f < npoly; ++f) {
    if (polygon_area[f] <= 0) {
      std::string pts;
      for (std::size_t p : polygons[f]) pts += (pts.empty() ? "" : ", ") + point_text(in, p);
      throw Error("zone " + std::to_string(in.polygon_ids[f]) + " of " + in.source +
                  " is inverted relative to its neighbours (the mesh folds over there): " + pts);
    }
  }

  // 4. Boundary loops: one border halfedge per loop from CGAL; a border cycle runs with the
  //    hole on its left, so reverse it to have the mesh interior on the left.
  std::vector<SurfaceMesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  for (const auto h : cycles) {
    std::vector<std::int64_t> loop;
    for (const auto h2 : CGAL::halfedges_around_face(h, mesh))
      loop.push_back(static_cast<std::int64_t>(static_cast<std::size_t>(mesh.target(h2))));
    std::reverse(loop.begin(), loop.end());
    result.boundary_loops.push_back(std::move(loop));
  }
  return result;
}

}  // namespace stagger::detail
