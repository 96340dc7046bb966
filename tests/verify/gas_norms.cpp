// Error norms and mesh helpers of lib/src/verify/norms.cpp on hand-built meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <vector>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace {

using stagger::Index;

/// A structured nx x ny quad mesh of [x0,x1]x[y0,y1] with the arrays the norms read
/// (points, CCW zone corners); point (i, j) has id j (nx + 1) + i.
stagger::Mesh grid(int nx, int ny, double x0, double x1, double y0, double y1) {
  stagger::Mesh mesh;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      mesh.x.push_back(x0 + (x1 - x0) * i / nx);
      mesh.y.push_back(y0 + (y1 - y0) * j / ny);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Index p = j * (nx + 1) + i;
      for (Index q : {p, p + 1, p + nx + 2, p + nx + 1}) {
        mesh.corner_point.push_back(q);
        mesh.corner_zone.push_back(j * nx + i);
      }
      mesh.zone_corner_begin.push_back(static_cast<Index>(mesh.corner_point.size()));
    }
  return mesh;
}

TEST(Norms, AreaWeightedMeansMatchHandValues) {
  stagger::NamedValues errors;
  const std::vector<double> weights{1.0, 3.0, 0.0}, differences{2.0, -1.0, -5.0};
  stagger::append_norms(weights, differences, "density", errors);
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors[0].first, "L1_density");
  EXPECT_DOUBLE_EQ(errors[0].second, (1.0 * 2.0 + 3.0 * 1.0) / 4.0);
  EXPECT_EQ(errors[1].first, "L2_density");
  EXPECT_DOUBLE_EQ(errors[1].second, std::sqrt((1.0 * 4.0 + 3.0 * 1.0) / 4.0));
  EXPECT_EQ(errors[2].first, "Linf_density");
  EXPECT_DOUBLE_EQ(errors[2].second, 5.0);  // Linf ignores the weights
  EXPECT_THROW(stagger::append_norms(std::vector<double>{1.0}, differences, "x", errors), stagger::Error);
  EXPECT_THROW(stagger::append_norms(std::vector<double>{0.0}, std::vector<double>{1.0}, "x", errors), stagger::Error);
}

TEST(Norms, MedianDualAreasOfAUniformGridAreQuartersHalvesAndWholes) {
  const stagger::Mesh mesh = grid(4, 2, 0.0, 2.0, 0.0, 1.0);  // h = 0.5
  const auto areas = stagger::point_dual_areas(mesh, mesh.x, mesh.y);
  EXPECT_NEAR(areas[0], 0.0625, 1e-15);    // corner point
  EXPECT_NEAR(areas[1], 0.125, 1e-15);     // edge point
  EXPECT_NEAR(areas[5 + 1], 0.25, 1e-15);  // interior point (1, 1)
  EXPECT_NEAR(std::accumulate(areas.begin(), areas.end(), 0.0), 2.0, 1e-14);
  const auto zone_areas = stagger::zone_areas(mesh, mesh.x, mesh.y);
  for (double a : zone_areas) EXPECT_NEAR(a, 0.25, 1e-15);
  const auto centres = stagger::zone_centres(mesh, mesh.x, mesh.y);
  EXPECT_NEAR(centres[0][5], 0.75, 1e-15);
  EXPECT_NEAR(centres[1][5], 0.75, 1e-15);
}

TEST(Norms, DualAreasPartitionADistortedMesh) {
  stagger::Mesh mesh = grid(5, 4, 0.0, 1.0, 0.0, 1.0);
  // Move interior points (keeps every quad convex): the dual areas still sum to the domain.
  for (Index p = 0; p < mesh.num_points(); ++p) {
    const double x = mesh.x[p], y = mesh.y[p];
    if (x > 0 && x < 1 && y > 0 && y < 1) {
      mesh.x[p] += 0.04 * std::sin(7.0 * p);
      mesh.y[p] += 0.04 * std::cos(5.0 * p);
    }
  }
  const auto areas = stagger::point_dual_areas(mesh, mesh.x, mesh.y);
  const auto zones = stagger::zone_areas(mesh, mesh.x, mesh.y);
  EXPECT_NEAR(std::accumulate(areas.begin(), areas.end(), 0.0), 1.0, 1e-14);
  EXPECT_NEAR(std::accumulate(zones.begin(), zones.end(), 0.0), 1.0, 1e-14);
  for (double a : areas) EXPECT_GT(a, 0.0);
}

TEST(Norms, FrontCrossingInterpolatesBetweenNeighbourCentres) {
  const stagger::Mesh mesh = grid(10, 3, 0.0, 1.0, 0.0, 0.3);
  const auto centres = stagger::zone_centres(mesh, mesh.x, mesh.y);
  // A step from 4 to 1 between x = 0.55 and 0.65 (centres of zones 5 and 6 in each row).
  std::vector<double> density(mesh.num_zones());
  for (Index z = 0; z < mesh.num_zones(); ++z) density[z] = centres[0][z] < 0.6 ? 4.0 : 1.0;
  const auto front = stagger::front_crossing(mesh, mesh.x, mesh.y, density, 2.5, [](double x, double) { return x; });
  EXPECT_EQ(front.crossings, 3);  // one per row
  EXPECT_NEAR(front.position, 0.6, 1e-14);
  // A threshold the field never crosses gives no front.
  const auto none = stagger::front_crossing(mesh, mesh.x, mesh.y, density, 10.0, [](double x, double) { return x; });
  EXPECT_EQ(none.crossings, 0);
}

// The front search as it was first written (every edge listed and sorted): the point-by-point
// pairing must give the same crossings and the same sum, bit for bit.
stagger::FrontCrossing sorted_front(const stagger::Mesh& mesh, const std::vector<double>& position,
                                    const std::vector<double>& field, double threshold) {
  std::vector<std::tuple<Index, Index, Index>> edges;
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    for (Index c = begin; c < end; ++c) {
      const Index a = mesh.corner_point[c], b = mesh.corner_point[c + 1 < end ? c + 1 : begin];
      edges.emplace_back(std::min(a, b), std::max(a, b), z);
    }
  }
  std::sort(edges.begin(), edges.end());
  stagger::FrontCrossing front;
  double sum = 0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const auto [a0, b0, z0] = edges[i];
    const auto [a1, b1, z1] = edges[i + 1];
    if (a0 != a1 || b0 != b1) continue;
    const Index inner = position[z0] <= position[z1] ? z0 : z1, outer = inner == z0 ? z1 : z0;
    if (field[inner] >= threshold && field[outer] < threshold) {
      sum += position[inner] +
             (field[inner] - threshold) / (field[inner] - field[outer]) * (position[outer] - position[inner]);
      ++front.crossings;
    }
    ++i;
  }
  if (front.crossings > 0) front.position = sum / front.crossings;
  return front;
}

TEST(Norms, FrontCrossingPairsEdgesAsTheSortedEdgeListDid) {
  stagger::Mesh mesh = grid(23, 17, 0.0, 1.0, 0.0, 1.0);
  for (Index p = 0; p < mesh.num_points(); ++p) {  // a distorted mesh, a ragged circular front
    const double x = mesh.x[p], y = mesh.y[p];
    if (x > 0 && x < 1 && y > 0 && y < 1) mesh.x[p] += 0.01 * std::sin(7.0 * p), mesh.y[p] += 0.01 * std::cos(5.0 * p);
  }
  const auto centres = stagger::zone_centres(mesh, mesh.x, mesh.y);
  std::vector<double> density(mesh.num_zones()), position(mesh.num_zones());
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    position[z] = std::hypot(centres[0][z], centres[1][z]);
    density[z] = 1.0 + 3.0 * std::exp(-3.0 * position[z]) + 0.1 * std::sin(13.0 * z);
  }
  const auto radius = [](double x, double y) { return std::hypot(x, y); };
  for (double threshold : {1.5, 2.0, 2.5}) {
    const auto expected = sorted_front(mesh, position, density, threshold);
    ASSERT_GT(expected.crossings, 5);
    const auto front = stagger::front_crossing(mesh, mesh.x, mesh.y, density, threshold, radius);
    EXPECT_EQ(front.crossings, expected.crossings);
    EXPECT_EQ(front.position, expected.position);  // bitwise: the same pairs summed in the same order
  }
}

TEST(Norms, GroupingByValueChainsValuesWithinTheTolerance) {
  const std::vector<double> values{0.3, 0.1, 0.3 + 1e-12, 0.2, 0.1 - 1e-12};
  const auto groups = stagger::group_by_value(values, 1e-9);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0], (std::vector<Index>{4, 1}));
  EXPECT_EQ(groups[1], (std::vector<Index>{3}));
  EXPECT_EQ(groups[2], (std::vector<Index>{0, 2}));
}

}  // namespace
