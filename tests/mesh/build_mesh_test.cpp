// Polygon soup -> Mesh: orientation repair, topology and geometry checks, array layout.
#include <gtest/gtest.h>

#include <algorithm>

#include "mesh_checks.hpp"
#include "stagger/error.hpp"
#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"

namespace stagger {
namespace {

using testing::expect_consistent;
using testing::expect_error;

/// Soup from explicit points and polygons, one region "domain".
PolygonSoup soup_of(const std::vector<std::pair<double, double>>& points,
                    const std::vector<std::vector<std::int64_t>>& polygons) {
  PolygonSoup soup;
  soup.source = "test-soup";
  soup.region_names = {"domain"};
  for (const auto& [x, y] : points) {
    soup.x.push_back(x);
    soup.y.push_back(y);
  }
  for (const auto& p : polygons) soup.add_polygon(p, 0);
  return soup;
}

PolygonSoup reversed_polygons(const PolygonSoup& soup, bool every_other) {
  PolygonSoup out = soup;
  out.polygon_points.clear();
  out.polygon_begin = {0};
  out.polygon_region.clear();
  for (std::size_t f = 0; f < soup.num_polygons(); ++f) {
    std::vector<std::int64_t> p(soup.polygon_points.begin() + soup.polygon_begin[f],
                                soup.polygon_points.begin() + soup.polygon_begin[f + 1]);
    if (!every_other || f % 2 == 0) std::reverse(p.begin(), p.end());
    out.add_polygon(p, soup.polygon_region[f]);
  }
  return out;
}

// side_twins on a mixed mesh (three quads, two triangles on a 3 x 3 grid of points): each
// interior side's twin runs back along it, twins pair up, and only the 8 perimeter sides have none.
TEST(BuildMesh, SideTwinsPairTheInteriorSides) {
  std::vector<std::pair<double, double>> pts;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) pts.push_back({i, j});
  const Mesh m = build_mesh(soup_of(pts, {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8}, {4, 8, 7}}));
  const std::vector<Index> twin = side_twins(m);
  ASSERT_EQ(twin.size(), static_cast<std::size_t>(m.num_corners()));
  const auto next = [&](Index c) {
    const Index z = m.corner_zone[c];
    return c + 1 == m.zone_corner_begin[z + 1] ? m.zone_corner_begin[z] : c + 1;
  };
  int boundary = 0;
  for (Index c = 0; c < m.num_corners(); ++c) {
    if (twin[c] < 0) {
      ++boundary;
      continue;
    }
    EXPECT_NE(m.corner_zone[twin[c]], m.corner_zone[c]);
    EXPECT_EQ(twin[twin[c]], c);
    EXPECT_EQ(m.corner_point[twin[c]], m.corner_point[next(c)]);
    EXPECT_EQ(m.corner_point[next(twin[c])], m.corner_point[c]);
  }
  EXPECT_EQ(boundary, 8);
  EXPECT_EQ(m.num_corners() - boundary, 10);
}

TEST(BuildMesh, ClockwiseSoupIsReversedToCounterClockwise) {
  const PolygonSoup soup = reversed_polygons(meshgen::rectangle(0, 3, 0, 2, 6, 4), false);
  MeshBuildReport report;
  const Mesh mesh = build_mesh(soup, {}, &report);
  expect_consistent(mesh);
  EXPECT_EQ(report.reoriented_zones, 24);
  EXPECT_FALSE(report.notes.empty());
  EXPECT_NEAR(testing::total_area(mesh), 6.0, 1e-13);
}

TEST(BuildMesh, MixedOrientationIsMadeConsistentAndCounterClockwise) {
  const PolygonSoup soup = reversed_polygons(meshgen::rectangle(0, 1, 0, 1, 4, 4), true);
  MeshBuildReport report;
  const Mesh mesh = build_mesh(soup, {}, &report);
  expect_consistent(mesh);
  EXPECT_EQ(report.reoriented_zones, 8);
}

TEST(BuildMesh, CornersKeepTheSoupOrderWhenAlreadyCounterClockwise) {
  const PolygonSoup soup = meshgen::rectangle(0, 1, 0, 1, 2, 1);
  MeshBuildReport report;
  const Mesh mesh = build_mesh(soup, {}, &report);
  EXPECT_EQ(report.reoriented_zones, 0);
  EXPECT_EQ(mesh.corner_point, (std::vector<Index>{0, 1, 4, 3, 1, 2, 5, 4}));
  // Point 4 = (1, 1) is corner 2 of zone 0 and corner 7 (last of zone 1).
  EXPECT_EQ(mesh.point_corners, (std::vector<Index>{0, 1, 4, 5, 3, 2, 7, 6}));
}

TEST(BuildMesh, TwoQuadsSharingOnlyAPointAreRejected) {
  // Squares [0,1]^2 and [1,2]x[1,2] touch at point 2 = (1, 1) only.
  const PolygonSoup soup =
      soup_of({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 1}, {2, 2}, {1, 2}}, {{0, 1, 2, 3}, {2, 4, 5, 6}});
  expect_error([&] { build_mesh(soup); }, {"non-manifold point 2", "(1, 1)", "test-soup"});
}

TEST(BuildMesh, EdgeSharedByThreeZonesIsRejected) {
  // Three triangles on the edge 0-1.
  const PolygonSoup soup = soup_of({{0, 0}, {1, 0}, {0.5, 1}, {0.5, -1}, {0.5, 2}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  expect_error([&] { build_mesh(soup); },
               {"non-manifold edge", "point 0 (0, 0)", "point 1 (1, 0)", "3 zones", "test-soup"});
}

TEST(BuildMesh, BowTieZoneIsRejected) {
  const PolygonSoup soup = soup_of({{0, 0}, {2, 0}, {0, 1}, {2, 2}}, {{0, 1, 2, 3}});
  expect_error([&] { build_mesh(soup); }, {"zone 0", "crosses itself", "point 3 (2, 2)"});
}

TEST(BuildMesh, ZeroAreaZoneIsRejected) {
  // Four distinct collinear points.
  const PolygonSoup flat = soup_of({{0, 0}, {1, 0}, {2, 0}, {3, 0}}, {{0, 1, 2, 3}});
  expect_error([&] { build_mesh(flat); }, {"zone 0", "zero area", "test-soup"});
}

TEST(BuildMesh, DuplicatePointsAreRejected) {
  // Two unit squares side by side whose shared side has its own copies of the points.
  const PolygonSoup soup =
      soup_of({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {1, 0}, {2, 0}, {2, 1}, {1, 1 + 1e-15}}, {{0, 1, 2, 3}, {4, 5, 6, 7}});
  expect_error([&] { build_mesh(soup); }, {"duplicate points", "point 1 (1, 0)", "point 4"});
}

TEST(BuildMesh, EmptySoupIsRejected) {
  PolygonSoup soup;
  soup.source = "nothing.msh";
  expect_error([&] { build_mesh(soup); }, {"empty", "nothing.msh"});
}

TEST(BuildMesh, OrphanPointsAreDroppedAndCounted) {
  const PolygonSoup soup = soup_of({{9, 9}, {0, 0}, {1, 0}, {5, 5}, {1, 1}, {0, 1}, {7, 7}}, {{1, 2, 4, 5}});
  MeshBuildReport report;
  const Mesh mesh = build_mesh(soup, {}, &report);
  expect_consistent(mesh);
  EXPECT_EQ(report.dropped_points, 3);
  ASSERT_EQ(mesh.num_points(), 4);
  EXPECT_EQ(mesh.x, (std::vector<double>{0, 1, 1, 0}));
  EXPECT_EQ(mesh.y, (std::vector<double>{0, 0, 1, 1}));
}

TEST(BuildMesh, ZonesAreSortedByRegionStably) {
  PolygonSoup soup = meshgen::rectangle(0, 4, 0, 1, 4, 1);
  soup.region_names = {"left", "right"};
  soup.polygon_region = {1, 0, 1, 0};
  const Mesh mesh = build_mesh(soup);
  expect_consistent(mesh);
  EXPECT_EQ(mesh.region_zone_begin, (std::vector<Index>{0, 2, 4}));
  // Region 0 holds soup zones 1 and 3 (x in [1,2] and [3,4]), in that order.
  EXPECT_EQ(mesh.x[mesh.corner_point[0]], 1.0);
  EXPECT_EQ(mesh.x[mesh.corner_point[4]], 3.0);
  EXPECT_EQ(mesh.x[mesh.corner_point[8]], 0.0);
  EXPECT_EQ(mesh.region_index("right"), 1);
  EXPECT_EQ(mesh.region_index("nowhere"), -1);
}

TEST(BuildMesh, QuadsOnlyRejectsOtherPolygonsWithTheirCount) {
  const PolygonSoup soup = meshgen::annulus_sector(0, 1, 0, 1, 6, 3);
  expect_error([&] { build_mesh(soup, {.quads_only = true}); }, {"6 of 18", "not quadrilaterals"});
  EXPECT_NO_THROW(build_mesh(meshgen::rectangle(0, 1, 0, 1, 2, 2), {.quads_only = true}));
}

TEST(BuildMesh, TaggedEdgeThatIsNotAMeshEdgeIsRejected) {
  PolygonSoup soup = meshgen::rectangle(0, 1, 0, 1, 2, 2);
  soup.tagged_edges.push_back({0, 4, 0});  // a diagonal of zone 0
  expect_error([&] { build_mesh(soup); }, {"edge 0-4", "tag 'left'", "not an edge of the mesh"});
}

TEST(BuildMesh, TagEdgesFollowTheZonesAndTagPointsAreSortedUnique) {
  PolygonSoup soup = meshgen::rectangle(0, 2, 0, 1, 2, 1);
  // Tag the top edges against the zone direction and twice.
  soup.tag_names = {"top"};
  soup.tagged_edges = {{3, 4, 0}, {4, 5, 0}, {5, 4, 0}};
  const Mesh mesh = build_mesh(soup);
  expect_consistent(mesh);
  ASSERT_EQ(mesh.tags.size(), 1U);
  const auto& top = mesh.tags[0];
  ASSERT_EQ(top.edges.size(), 2U);
  EXPECT_EQ(top.edges[0], (std::array<Index, 2>{4, 3}));
  EXPECT_EQ(top.edges[1], (std::array<Index, 2>{5, 4}));
  EXPECT_EQ(top.points, (std::vector<Index>{3, 4, 5}));
  EXPECT_EQ(mesh.tag_index("top"), 0);
}

TEST(BuildMesh, BoundaryLoopsAreReportedWithHoles) {
  // A 3x3 block of squares with the centre one missing: two boundary loops.
  PolygonSoup full = meshgen::rectangle(0, 3, 0, 3, 3, 3);
  PolygonSoup soup = full;
  soup.polygon_begin = {0};
  soup.polygon_points.clear();
  soup.polygon_region.clear();
  for (std::size_t f = 0; f < full.num_polygons(); ++f) {
    if (f == 4) continue;
    soup.add_polygon(
        {full.polygon_points.begin() + full.polygon_begin[f], full.polygon_points.begin() + full.polygon_begin[f + 1]},
        0);
  }
  MeshBuildReport report;
  const Mesh mesh = build_mesh(soup, {}, &report);
  expect_consistent(mesh);
  bool found = false;
  for (const auto& note : report.notes)
    found = found || note.find("2 boundary loop(s), 16 boundary edges, 4 of them untagged") != std::string::npos;
  EXPECT_TRUE(found);
}

TEST(MeshQuality, UnitSquaresAndANonConvexZone) {
  const Mesh squares = build_mesh(meshgen::rectangle(0, 2, 0, 1, 2, 1));
  const MeshQuality q = mesh_quality(squares);
  EXPECT_DOUBLE_EQ(q.min_area, 1.0);
  EXPECT_DOUBLE_EQ(q.max_area, 1.0);
  EXPECT_DOUBLE_EQ(q.max_aspect_ratio, 1.0);
  EXPECT_NEAR(q.min_angle_degrees, 90.0, 1e-12);
  EXPECT_EQ(q.non_convex_zones, 0);
  EXPECT_EQ(q.quads, 2);
  // An arrowhead: the corner (1, 0.5) is reflex (interior angle above 180 degrees).
  const PolygonSoup arrow = soup_of({{0, 0}, {2, 0}, {1, 0.5}, {1, 2}}, {{0, 1, 2, 3}});
  const MeshQuality qa = mesh_quality(build_mesh(arrow));
  EXPECT_EQ(qa.non_convex_zones, 1);
  EXPECT_DOUBLE_EQ(qa.min_area, 1.25);
}

}  // namespace
}  // namespace stagger
