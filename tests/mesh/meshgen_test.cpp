// .geo and .msh files through gmsh: counts, tags, parameters, repair, triangle policy, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "mesh_checks.hpp"
#include "stagger/meshgen.hpp"

namespace stagger {
namespace {

using testing::expect_consistent;
using testing::expect_error;

std::string geometry(const std::string& name) {
  return std::string(STAGGER_SOURCE_DIR) + "/geometries/" + name;
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::path(STAGGER_BINARY_DIR) / "test_mesh_scratch";
  std::filesystem::create_directories(dir);
  return dir / name;
}

const BoundaryTag& tag(const Mesh& m, const std::string& name) {
  const int t = m.tag_index(name);
  EXPECT_GE(t, 0) << "no tag " << name;
  return m.tags.at(static_cast<std::size_t>(std::max(t, 0)));
}

TEST(Meshgen, QuarterShellGeoHas320CounterClockwiseQuadsAndItsTags) {
  MeshBuildReport report;
  const Mesh m = build_mesh(meshgen::read_geo(geometry("quarter_shell.geo")), {}, &report);
  expect_consistent(m);
  EXPECT_EQ(m.num_zones(), 320);
  EXPECT_EQ(m.num_points(), 21 * 17);
  EXPECT_TRUE(m.all_quads());
  EXPECT_EQ(report.reoriented_zones, 0);
  EXPECT_EQ(report.dropped_points, 0);  // the arc centre is not a mesh node
  EXPECT_EQ(m.region_names, std::vector<std::string>{"shell"});
  EXPECT_EQ(tag(m, "inner").points.size(), 21U);
  EXPECT_EQ(tag(m, "outer").points.size(), 21U);
  EXPECT_EQ(tag(m, "start").points.size(), 17U);
  EXPECT_EQ(tag(m, "end").points.size(), 17U);
  EXPECT_EQ(tag(m, "inner").edges.size(), 20U);
  for (Index p : tag(m, "start").points) EXPECT_NEAR(m.y[p], 0.0, 1e-15);
  for (Index p : tag(m, "end").points) EXPECT_NEAR(m.x[p], 0.0, 1e-15);
  for (Index p : tag(m, "outer").points) EXPECT_NEAR(std::hypot(m.x[p], m.y[p]), 0.1, 1e-14);
  // Equal angles: the transfinite mesh is the generator's mesh, so the same area.
  const double exact = 20 * std::sin(std::numbers::pi / 40) / 2 * (0.1 * 0.1 - 0.08 * 0.08);
  EXPECT_NEAR(testing::total_area(m), exact, 1e-12 * exact);
}

TEST(Meshgen, ParameterOverrideWorksLikeSetNumber) {
  meshgen::GeoOptions options;
  options.parameters = {{"n_theta", 40}};
  const Mesh m = build_mesh(meshgen::read_geo(geometry("quarter_shell.geo"), options));
  EXPECT_EQ(m.num_zones(), 640);
  EXPECT_EQ(tag(m, "inner").points.size(), 41U);
  options.parameters = {{"n_theta", 8}, {"n_r", 2}, {"ri", 0.5}, {"ro", 1.0}};
  const Mesh small = build_mesh(meshgen::read_geo(geometry("quarter_shell.geo"), options));
  EXPECT_EQ(small.num_zones(), 16);
  for (Index p : tag(small, "inner").points) EXPECT_NEAR(std::hypot(small.x[p], small.y[p]), 0.5, 1e-14);
  // Overrides do not leak into the next read of the same file.
  EXPECT_EQ(build_mesh(meshgen::read_geo(geometry("quarter_shell.geo"))).num_zones(), 320);
}

TEST(Meshgen, QuarterShellMeshesAtHighAngularResolution) {
  // Entity ids grow with n_theta and n_r: fixed ids once collided from n_theta = 495 on and
  // gmsh crashed with a double free.
  meshgen::GeoOptions options;
  options.parameters = {{"n_theta", 1200}, {"n_r", 2}};
  const Mesh m = build_mesh(meshgen::read_geo(geometry("quarter_shell.geo"), options));
  EXPECT_EQ(m.num_zones(), 2400);
  EXPECT_EQ(tag(m, "outer").points.size(), 1201U);
  for (Index p : tag(m, "outer").points) EXPECT_NEAR(std::hypot(m.x[p], m.y[p]), 0.1, 1e-15);
}

TEST(Meshgen, UnknownParameterIsAnError) {
  meshgen::GeoOptions options;
  options.parameters = {{"n_thetta", 40}};
  expect_error([&] { meshgen::read_geo(geometry("quarter_shell.geo"), options); },
               {"quarter_shell.geo", "unknown parameter 'n_thetta'"});
  options.parameters = {{"x;Point(9)", 1}};
  expect_error([&] { meshgen::read_geo(geometry("quarter_shell.geo"), options); }, {"not a valid .geo identifier"});
}

TEST(Meshgen, ClockwiseGeoIsRepaired) {
  const PolygonSoup soup = meshgen::read_geo(geometry("clockwise_square.geo"));
  MeshBuildReport report;
  const Mesh m = build_mesh(soup, {}, &report);
  expect_consistent(m);
  EXPECT_EQ(m.num_zones(), 16);
  EXPECT_EQ(report.reoriented_zones, 16);
  EXPECT_NEAR(testing::total_area(m), 1.0, 1e-14);
  EXPECT_EQ(tag(m, "left").points.size(), 5U);
}

TEST(Meshgen, LeftoverTrianglesFollowThePolicy) {
  meshgen::GeoOptions options;
  options.triangles = meshgen::TrianglePolicy::reject;
  expect_error([&] { meshgen::read_geo(geometry("triangles_left.geo"), options); },
               {"triangles_left.geo", "are triangles", "reject"});

  options.triangles = meshgen::TrianglePolicy::accept;
  const Mesh mixed = build_mesh(meshgen::read_geo(geometry("triangles_left.geo"), options));
  expect_consistent(mixed);
  const MeshQuality q = mesh_quality(mixed);
  EXPECT_GT(q.triangles, 0);
  EXPECT_GT(q.quads, q.triangles);
  EXPECT_NEAR(testing::total_area(mixed), 0.5, 1e-13);

  options.triangles = meshgen::TrianglePolicy::subdivide;
  const Mesh quads = build_mesh(meshgen::read_geo(geometry("triangles_left.geo"), options), {.quads_only = true});
  expect_consistent(quads);
  EXPECT_TRUE(quads.all_quads());
  EXPECT_NEAR(testing::total_area(quads), 0.5, 1e-13);
}

TEST(Meshgen, EveryGeometryMeshes) {
  for (const auto& entry : std::filesystem::directory_iterator(geometry(""))) {
    if (entry.path().extension() != ".geo") continue;
    SCOPED_TRACE(entry.path().string());
    const Mesh m = build_mesh(meshgen::read_geo(entry.path().string()));
    expect_consistent(m);
    EXPECT_GT(m.num_zones(), 0);
    EXPECT_FALSE(m.tags.empty());
  }
}

TEST(Meshgen, PlateWithHolesIsUnstructuredWithTwoTagsAndFourLoops) {
  MeshBuildReport report;
  const Mesh m = build_mesh(meshgen::read_geo(geometry("plate_with_holes.geo")), {}, &report);
  expect_consistent(m);
  EXPECT_EQ(m.region_names, std::vector<std::string>{"plate"});
  EXPECT_GT(tag(m, "outer").edges.size(), 0U);
  EXPECT_GT(tag(m, "holes").edges.size(), 0U);
  EXPECT_GT(mesh_quality(m).quads, 500);
  bool loops = false;
  for (const auto& note : report.notes) loops = loops || note.find("4 boundary loop(s)") != std::string::npos;
  EXPECT_TRUE(loops);
  // Plate minus the holes, up to the polygonal approximation of the circles.
  const double pi = std::numbers::pi;
  const double exact = 2.0 - pi * (0.2 * 0.2 + 0.12 * 0.12 + 0.15 * 0.15);
  EXPECT_NEAR(testing::total_area(m), exact, 0.01 * exact);
}

TEST(Meshgen, ShockTubeAndTubeHaveTheirCounts) {
  const Mesh tube_shock = build_mesh(meshgen::read_geo(geometry("shock_tube.geo")));
  EXPECT_EQ(tube_shock.num_zones(), 500);
  EXPECT_EQ(tag(tube_shock, "left").points.size(), 6U);
  EXPECT_EQ(tag(tube_shock, "top").edges.size(), 100U);
  const Mesh tube = build_mesh(meshgen::read_geo(geometry("tube.geo")));
  EXPECT_EQ(tube.num_zones(), 64 * 8);
  EXPECT_EQ(tag(tube, "inner").points.size(), 64U);
  EXPECT_EQ(tag(tube, "outer").edges.size(), 64U);
}

TEST(Meshgen, MissingFileIsAnErrorNamingIt) {
  expect_error([] { meshgen::read_geo("/no/such/shell.geo"); }, {"/no/such/shell.geo", "not found"});
  expect_error([] { meshgen::read_msh("/no/such/mesh.msh"); }, {"/no/such/mesh.msh", "not found"});
  expect_error([] { meshgen::read_mesh_file("mesh.stl"); }, {"mesh.stl", "extension"});
}

TEST(Meshgen, GeoSyntaxErrorIsAClearError) {
  const auto path = scratch("broken.geo");
  std::ofstream(path) << "Point(1) = {0, 0, 0};\nLine(1) = {1, oops;\n";
  expect_error([&] { meshgen::read_geo(path.string()); }, {"broken.geo", "gmsh"});
}

TEST(Meshgen, GeoWithoutSurfacesIsAnEmptyMeshError) {
  const auto path = scratch("points_only.geo");
  std::ofstream(path) << "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0};\nLine(1) = {1, 2};\n";
  expect_error([&] { meshgen::read_geo(path.string()); }, {"empty mesh", "points_only.geo"});
}

TEST(Meshgen, MshRoundTripKeepsCountsRegionsAndTags) {
  meshgen::GeoOptions options;
  const Mesh original = build_mesh(meshgen::read_geo(geometry("plate_with_holes.geo"), options));
  const auto path = scratch("plate_round_trip.msh");
  meshgen::write_msh(path.string(), original);
  const Mesh back = build_mesh(meshgen::read_msh(path.string()));
  expect_consistent(back);
  EXPECT_EQ(back.num_zones(), original.num_zones());
  EXPECT_EQ(back.num_points(), original.num_points());
  EXPECT_EQ(back.corner_point, original.corner_point);
  EXPECT_EQ(back.x, original.x);
  EXPECT_EQ(back.region_names, original.region_names);
  ASSERT_EQ(back.tags.size(), original.tags.size());
  for (std::size_t t = 0; t < back.tags.size(); ++t) {
    EXPECT_EQ(back.tags[t].name, original.tags[t].name);
    EXPECT_EQ(back.tags[t].points, original.tags[t].points);
  }
}

TEST(Meshgen, Msh22FileIsRead) {
  // Two unit squares, MSH 2.2 ASCII, physical surface "metal" (tag 7) and curve "wall" (3).
  const auto path = scratch("two_quads.msh");
  std::ofstream(path) << R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 3 "wall"
2 7 "metal"
$EndPhysicalNames
$Nodes
7
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
5 1 1 0
6 2 1 0
9 5 5 0
$EndNodes
$Elements
3
1 3 2 7 1 1 2 5 4
2 3 2 7 1 2 3 6 5
3 1 2 3 2 1 4
$EndElements
)";
  MeshBuildReport report;
  const Mesh m = build_mesh(meshgen::read_msh(path.string()), {}, &report);
  expect_consistent(m);
  EXPECT_EQ(m.num_zones(), 2);
  EXPECT_EQ(m.num_points(), 6);  // node 9 is an orphan
  EXPECT_EQ(m.region_names, std::vector<std::string>{"metal"});
  EXPECT_EQ(tag(m, "wall").points, (std::vector<Index>{0, 3}));
}

}  // namespace
}  // namespace stagger
