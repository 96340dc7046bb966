/// @file norms.cpp
/// Error norms of docs/verification.md §11: area-weighted L1 and L2 means
/// and the maximum, at zone centres (vertex average) and at points (median-dual areas, the
/// corner areas of docs/algorithm.md §2), plus the mesh helpers the reference solutions share.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "mesh/polygon.hpp"
#include "stagger/error.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

void check_positions(const Mesh& mesh, std::span<const double> x, std::span<const double> y) {
  if (x.size() != static_cast<std::size_t>(mesh.num_points()) || y.size() != x.size()) {
    std::ostringstream message;
    message << "verify: position arrays of size " << x.size() << " and " << y.size() << " do not match the "
            << mesh.num_points() << " points of mesh " << mesh.source;
    throw Error(message.str());
  }
}

}  // namespace

std::array<std::vector<double>, 2> zone_centres(const Mesh& mesh, std::span<const double> x,
                                                std::span<const double> y) {
  check_positions(mesh, x, y);
  const Index zones = mesh.num_zones();
  std::array<std::vector<double>, 2> centres{std::vector<double>(zones), std::vector<double>(zones)};
  for (Index z = 0; z < zones; ++z) {
    const Index begin = mesh.zone_corner_begin[z];
    const auto [cx, cy] = polygon_centre(
        static_cast<int>(mesh.zone_corner_begin[z + 1] - begin), [&](int k) { return x[mesh.corner_point[begin + k]]; },
        [&](int k) { return y[mesh.corner_point[begin + k]]; });
    centres[0][z] = cx;
    centres[1][z] = cy;
  }
  return centres;
}

std::vector<double> zone_areas(const Mesh& mesh, std::span<const double> x, std::span<const double> y) {
  check_positions(mesh, x, y);
  const Index zones = mesh.num_zones();
  std::vector<double> areas(zones);
  for (Index z = 0; z < zones; ++z) {
    const Index begin = mesh.zone_corner_begin[z];
    areas[z] = polygon_area(
        static_cast<int>(mesh.zone_corner_begin[z + 1] - begin), [&](int k) { return x[mesh.corner_point[begin + k]]; },
        [&](int k) { return y[mesh.corner_point[begin + k]]; });
  }
  return areas;
}

std::vector<double> point_dual_areas(const Mesh& mesh, std::span<const double> x, std::span<const double> y) {
  const auto centres = zone_centres(mesh, x, y);
  std::vector<double> areas(mesh.num_points(), 0.0);
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    for (Index c = begin; c < end; ++c) {
      const Index p = mesh.corner_point[c];
      const Index next = mesh.corner_point[c + 1 < end ? c + 1 : begin];
      const Index prev = mesh.corner_point[c > begin ? c - 1 : end - 1];
      // Corner quadrilateral (point, mid-edge to next, centre, mid-edge to previous).
      const double qx[4] = {x[p], 0.5 * (x[p] + x[next]), centres[0][z], 0.5 * (x[p] + x[prev])};
      const double qy[4] = {y[p], 0.5 * (y[p] + y[next]), centres[1][z], 0.5 * (y[p] + y[prev])};
      areas[p] += polygon_area(
          4, [&](int k) { return qx[k]; }, [&](int k) { return qy[k]; });
    }
  }
  return areas;
}

void append_norms(std::span<const double> weights, std::span<const double> differences, const std::string& name,
                  NamedValues& errors) {
  if (weights.size() != differences.size()) {
    std::ostringstream message;
    message << "append_norms(" << name << "): " << weights.size() << " weights for " << differences.size() << " values";
    throw Error(message.str());
  }
  double total = 0, l1 = 0, l2 = 0, linf = 0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const double d = std::abs(differences[i]);
    linf = std::max(linf, d);
    if (weights[i] > 0) {
      total += weights[i];
      l1 += weights[i] * d;
      l2 += weights[i] * d * d;
    }
  }
  if (!(total > 0)) throw Error("append_norms(" + name + "): the total weight (area) is not positive");
  errors.emplace_back("L1_" + name, l1 / total);
  errors.emplace_back("L2_" + name, std::sqrt(l2 / total));
  errors.emplace_back("Linf_" + name, linf);
}

void zone_field_errors(const Simulation& simulation, std::span<const double> field,
                       const std::function<double(double, double)>& exact, const std::string& name,
                       NamedValues& errors) {
  const Mesh& mesh = simulation.mesh();
  if (field.size() != static_cast<std::size_t>(mesh.num_zones()))
    throw Error("zone_field_errors(" + name + "): the field does not have one value per zone");
  // The centres zone by zone (as zone_centres), without two arrays of them: the summary of a
  // large distributed run computes this on rank 0 (docs/parallel.md, "Memory").
  const auto x = simulation.x(), y = simulation.y();
  check_positions(mesh, x, y);
  std::vector<double> differences(field.size());
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index begin = mesh.zone_corner_begin[z];
    const auto [cx, cy] = polygon_centre(
        static_cast<int>(mesh.zone_corner_begin[z + 1] - begin), [&](int k) { return x[mesh.corner_point[begin + k]]; },
        [&](int k) { return y[mesh.corner_point[begin + k]]; });
    differences[z] = field[z] - exact(cx, cy);
  }
  append_norms(simulation.zone_area(), differences, name, errors);
}

void point_field_errors(const Simulation& simulation, std::span<const double> field,
                        const std::function<double(double, double)>& exact, const std::string& name,
                        NamedValues& errors) {
  const Mesh& mesh = simulation.mesh();
  if (field.size() != static_cast<std::size_t>(mesh.num_points()))
    throw Error("point_field_errors(" + name + "): the field does not have one value per point");
  const auto x = simulation.x(), y = simulation.y();
  std::vector<double> differences(field.size());
  for (std::size_t p = 0; p < field.size(); ++p) differences[p] = field[p] - exact(x[p], y[p]);
  append_norms(point_dual_areas(mesh, x, y), differences, name, errors);
}

void point_velocity_errors(const Simulation& simulation,
                           const std::function<std::array<double, 2>(double, double)>& exact, const std::string& name,
                           NamedValues& errors) {
  const auto x = simulation.x(), y = simulation.y();
  const auto vx = simulation.velocity_x(), vy = simulation.velocity_y();
  std::vector<double> differences(x.size());
  for (std::size_t p = 0; p < x.size(); ++p) {
    const auto v = exact(x[p], y[p]);
    differences[p] = std::hypot(vx[p] - v[0], vy[p] - v[1]);
  }
  append_norms(point_dual_areas(simulation.mesh(), x, y), differences, name, errors);
}

FrontCrossing front_crossing(const Mesh& mesh, std::span<const double> x, std::span<const double> y,
                             std::span<const double> field, double threshold,
                             const std::function<double(double, double)>& coordinate, double min_position) {
  if (field.size() != static_cast<std::size_t>(mesh.num_zones()))
    throw Error("front_crossing: the field does not have one value per zone");
  // The centres zone by zone (as zone_centres), without two arrays of them.
  check_positions(mesh, x, y);
  std::vector<double> position(field.size());
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index begin = mesh.zone_corner_begin[z];
    const auto [cx, cy] = polygon_centre(
        static_cast<int>(mesh.zone_corner_begin[z + 1] - begin), [&](int k) { return x[mesh.corner_point[begin + k]]; },
        [&](int k) { return y[mesh.corner_point[begin + k]]; });
    position[z] = coordinate(cx, cy);
  }
  // Edges (a, b), a < b, in ascending (a, b) order, each with its zones in ascending order:
  // point a's edges to higher points from its own corners (no list of every edge, which a
  // 10^6-zone mesh makes 48 MB; docs/parallel.md, "Memory"). An interior edge has two zones.
  // A mesh built by hand may lack the point-to-corner lists: then they are made here.
  const auto points = static_cast<std::size_t>(mesh.num_points());
  std::span<const Index> point_begin = mesh.point_corner_begin, point_corners = mesh.point_corners;
  std::vector<Index> made_begin, made_corners;
  if (point_begin.size() != points + 1 || point_corners.size() != mesh.corner_point.size()) {
    made_begin.assign(points + 1, 0);
    for (Index p : mesh.corner_point) ++made_begin[static_cast<std::size_t>(p) + 1];
    for (std::size_t p = 0; p < points; ++p) made_begin[p + 1] += made_begin[p];
    made_corners.resize(mesh.corner_point.size());
    std::vector<Index> next(made_begin.begin(), made_begin.end() - 1);
    for (Index c = 0; c < mesh.num_corners(); ++c) made_corners[next[mesh.corner_point[c]]++] = c;
    point_begin = made_begin, point_corners = made_corners;
  }
  FrontCrossing front;
  double sum = 0;
  std::vector<std::pair<Index, Index>> around;  // (b, zone) of point a's edges
  for (Index a = 0; a < mesh.num_points(); ++a) {
    around.clear();
    for (Index j = point_begin[a]; j < point_begin[a + 1]; ++j) {
      const Index c = point_corners[j], z = mesh.corner_zone[c];
      const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
      const Index next = mesh.corner_point[c + 1 < end ? c + 1 : begin];
      const Index prev = mesh.corner_point[c > begin ? c - 1 : end - 1];
      if (next > a) around.emplace_back(next, z);
      if (prev > a) around.emplace_back(prev, z);
    }
    std::sort(around.begin(), around.end());
    for (std::size_t i = 0; i + 1 < around.size(); ++i) {
      const auto [b0, z0] = around[i];
      const auto [b1, z1] = around[i + 1];
      if (b0 != b1) continue;
      const Index inner = position[z0] <= position[z1] ? z0 : z1;
      const Index outer = inner == z0 ? z1 : z0;
      if (field[inner] >= threshold && field[outer] < threshold) {
        const double fraction = (field[inner] - threshold) / (field[inner] - field[outer]);
        const double crossing = position[inner] + fraction * (position[outer] - position[inner]);
        if (crossing >= min_position) {
          sum += crossing;
          ++front.crossings;
        }
      }
      ++i;  // the pair is consumed
    }
  }
  if (front.crossings > 0) front.position = sum / front.crossings;
  return front;
}

std::vector<std::vector<Index>> group_by_value(std::span<const double> values, double tolerance) {
  std::vector<Index> order(values.size());
  std::iota(order.begin(), order.end(), Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return values[a] < values[b]; });
  std::vector<std::vector<Index>> groups;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || values[order[k]] - values[order[k - 1]] > tolerance) groups.emplace_back();
    groups.back().push_back(order[k]);
  }
  return groups;
}

}  // namespace stagger
