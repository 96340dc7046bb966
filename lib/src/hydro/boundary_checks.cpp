// Boundary conditions checked against the geometry they land on (boundary_checks.hpp).
#include "hydro/boundary_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace stagger {

namespace {

// Whether the side a-b has a zone on each side: two of a's corners have b as a neighbour
// (the tagged edges only are looked at: no table of every side).
bool interior_edge(const Mesh& mesh, Index a, Index b) {
  int zones = 0;
  for (Index j = mesh.point_corner_begin[a]; j < mesh.point_corner_begin[a + 1]; ++j) {
    const Index c = mesh.point_corners[j], z = mesh.corner_zone[c];
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    const Index next = mesh.corner_point[c + 1 < end ? c + 1 : begin],
                prev = mesh.corner_point[c > begin ? c - 1 : end - 1];
    zones += next == b || prev == b;
  }
  return zones >= 2;
}

std::string edge_text(const Mesh& mesh, const std::array<Index, 2>& edge) {
  std::ostringstream out;
  out.precision(6);
  out << "from (" << mesh.x[edge[0]] << ", " << mesh.y[edge[0]] << ") to (" << mesh.x[edge[1]] << ", "
      << mesh.y[edge[1]] << ")";
  return out.str();
}

// The edges of `tag` for which `test` holds: their count and the first one.
template <class Test>
std::size_t count_edges(const BoundaryTag& tag, Test&& test, std::array<Index, 2>& first) {
  std::size_t count = 0;
  for (const auto& edge : tag.edges)
    if (test(edge) && count++ == 0) first = edge;
  return count;
}

std::string head(const BoundaryCondition& bc) {
  return std::string("boundary '") + bc.tag + "' (type " + boundary_kind_name(bc.kind) + ")";
}

// In rz: a velocity or pressure condition on the axis, a periodic pair that is not an axial
// translation.
std::string rz_problem(const Mesh& mesh, const BoundaryCondition& bc) {
  const double tol = axis_tolerance(mesh);
  const auto on_axis = [&](const std::array<Index, 2>& e) {
    return std::abs(mesh.x[e[0]]) <= tol && std::abs(mesh.x[e[1]]) <= tol;
  };
  const BoundaryTag& tag = mesh.tags[mesh.tag_index(bc.tag)];
  std::array<Index, 2> first{};
  std::ostringstream msg;
  msg.precision(6);
  if (bc.kind == BoundaryKind::velocity || bc.kind == BoundaryKind::pressure || bc.kind == BoundaryKind::transmitting) {
    const std::size_t n = count_edges(tag, on_axis, first);
    if (n == 0) return {};
    msg << head(bc) << ": " << n << " of its " << tag.edges.size() << " edges lie on the axis x = 0 of "
        << "numerics.geometry = \"rz\" (e.g. " << edge_text(mesh, first) << "); ";
    if (bc.kind == BoundaryKind::velocity)
      msg << "the axis keeps v_r = 0 by itself and a velocity condition there can only prescribe v_r (the energy "
             "audit would not close): give the axis type = \"wall\" or \"free\" (both leave it the symmetry line)";
    else
      msg << "the axis is a line of zero area (r = 0), so a " << boundary_kind_name(bc.kind)
          << " condition there does nothing: give the axis type = \"free\" or \"wall\"";
    return msg.str();
  }
  if (bc.kind != BoundaryKind::periodic || mesh.tag_index(bc.partner) < 0) return {};
  const BoundaryTag& other = mesh.tags[mesh.tag_index(bc.partner)];
  for (const BoundaryTag* side : {&tag, &other})
    if (count_edges(*side, on_axis, first) > 0) {
      msg << head(bc) << " with '" << bc.partner << "': '" << side->name << "' lies on the axis x = 0 of "
          << "numerics.geometry = \"rz\" (e.g. " << edge_text(mesh, first)
          << "); the axis has no periodic partner (r = 0 is a symmetry line): give it type = \"wall\" or \"free\"";
      return msg.str();
    }
  // The translation between the sides (as the set-up measures it): radial is no symmetry.
  if (tag.points.empty() || other.points.empty()) return {};
  double ax = 0, bx = 0, extent = 0;
  for (Index p : tag.points) ax += mesh.x[p], extent = std::max({extent, std::abs(mesh.x[p]), std::abs(mesh.y[p])});
  for (Index p : other.points) bx += mesh.x[p];
  const double tx = bx / static_cast<double>(other.points.size()) - ax / static_cast<double>(tag.points.size());
  if (std::abs(tx) <= 1e-9 * extent) return {};
  msg << head(bc) << " with '" << bc.partner << "': the sides are " << tx
      << " apart in x, which is the radius in numerics.geometry = \"rz\"; only a translation along the axis (in y) "
         "is a symmetry of an axisymmetric problem: pair sides that differ in y only";
  return msg.str();
}

}  // namespace

double axis_tolerance(const Mesh& mesh) {
  double extent = 0;
  for (Index p = 0; p < mesh.num_points(); ++p) extent = std::max({extent, std::abs(mesh.x[p]), std::abs(mesh.y[p])});
  return 1e-12 * extent;
}

std::optional<BoundaryGeometryProblem> boundary_geometry_problem(const Problem& problem) {
  const Mesh& mesh = problem.mesh;
  if (problem.boundaries.empty()) return std::nullopt;
  for (std::size_t i = 0; i < problem.boundaries.size(); ++i) {
    const BoundaryCondition& bc = problem.boundaries[i];
    const int t = mesh.tag_index(bc.tag);
    if (t < 0) continue;  // validate names it
    const BoundaryTag& tag = mesh.tags[t];
    std::array<Index, 2> first{};
    const std::size_t n = count_edges(
        tag, [&](const std::array<Index, 2>& e) { return interior_edge(mesh, e[0], e[1]); }, first);
    if (n > 0) {
      std::ostringstream msg;
      msg << head(bc) << ": " << n << " of its " << tag.edges.size()
          << " edges are interior (a zone on each side; e.g. " << edge_text(mesh, first)
          << "); a boundary condition holds on the mesh's boundary only: remove them from the tag (its Physical "
             "Curve)";
      return BoundaryGeometryProblem{i, msg.str()};
    }
    if (problem.options.geometry == CoordinateSystem::rz)
      if (std::string why = rz_problem(mesh, bc); !why.empty()) return BoundaryGeometryProblem{i, why};
  }
  return std::nullopt;
}

const char* boundary_kind_name(BoundaryKind kind) {
  switch (kind) {
    case BoundaryKind::wall:
      return "wall";
    case BoundaryKind::velocity:
      return "velocity";
    case BoundaryKind::free:
      return "free";
    case BoundaryKind::pressure:
      return "pressure";
    case BoundaryKind::periodic:
      return "periodic";
    case BoundaryKind::transmitting:
      return "transmitting";
    case BoundaryKind::fixed:
      return "fixed";
  }
  return "?";
}

}  // namespace stagger
