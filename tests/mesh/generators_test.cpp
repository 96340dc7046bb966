// Built-in generators: exact areas of the polygonal meshes, tags, counter-clockwise zones.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mesh_checks.hpp"
#include "stagger/meshgen.hpp"

namespace stagger {
namespace {

using testing::expect_consistent;
using testing::total_area;

const BoundaryTag& tag(const Mesh& m, const std::string& name) {
  const int t = m.tag_index(name);
  EXPECT_GE(t, 0) << "no tag " << name;
  return m.tags.at(static_cast<std::size_t>(std::max(t, 0)));
}

/// Area of the polygon inscribed in an annulus sector with n equal angular steps dtheta:
/// each zone is a trapezoid of area sin(dtheta)/2 (r_{j+1}^2 - r_j^2), and the radial
/// sums telescope: n sin(dtheta)/2 (r1^2 - r0^2).
double inscribed_sector_area(double r0, double r1, double dtheta, int n) {
  return n * std::sin(dtheta) / 2 * (r1 * r1 - r0 * r0);
}

TEST(Generators, RectangleHasTheExactAreaAndSideTags) {
  const Mesh m = build_mesh(meshgen::rectangle(-1, 2, 0.5, 1.5, 12, 5));
  expect_consistent(m);
  EXPECT_EQ(m.num_zones(), 60);
  EXPECT_EQ(m.num_points(), 13 * 6);
  EXPECT_TRUE(m.all_quads());
  EXPECT_NEAR(total_area(m), 3.0, 1e-14);
  EXPECT_EQ(m.region_names, std::vector<std::string>{"domain"});
  EXPECT_EQ(tag(m, "left").edges.size(), 5U);
  EXPECT_EQ(tag(m, "right").points.size(), 6U);
  EXPECT_EQ(tag(m, "bottom").edges.size(), 12U);
  EXPECT_EQ(tag(m, "top").points.size(), 13U);
  for (Index p : tag(m, "left").points) EXPECT_EQ(m.x[p], -1.0);
  for (Index p : tag(m, "top").points) EXPECT_EQ(m.y[p], 1.5);
}

TEST(Generators, AnnulusSectorHasTheExactInscribedArea) {
  const double r0 = 0.08, r1 = 0.1, t0 = 0.0, t1 = std::numbers::pi / 2;
  const Mesh m = build_mesh(meshgen::annulus_sector(r0, r1, t0, t1, 20, 16));
  expect_consistent(m);
  EXPECT_EQ(m.num_zones(), 320);
  EXPECT_TRUE(m.all_quads());
  const double exact = inscribed_sector_area(r0, r1, (t1 - t0) / 20, 20);
  EXPECT_NEAR(total_area(m), exact, 1e-14 * exact);
  EXPECT_EQ(tag(m, "inner").points.size(), 21U);
  EXPECT_EQ(tag(m, "outer").points.size(), 21U);
  EXPECT_EQ(tag(m, "start").points.size(), 17U);
  EXPECT_EQ(tag(m, "end").points.size(), 17U);
  for (Index p : tag(m, "inner").points) EXPECT_NEAR(std::hypot(m.x[p], m.y[p]), r0, 1e-15);
  for (Index p : tag(m, "start").points) EXPECT_EQ(m.y[p], 0.0);
}

TEST(Generators, SectorWithZeroInnerRadiusHasATriangleCentreAndNoInnerTag) {
  const Mesh m = build_mesh(meshgen::annulus_sector(0, 1, 0.25, 1.25, 8, 4));
  expect_consistent(m);
  const MeshQuality q = mesh_quality(m);
  EXPECT_EQ(q.triangles, 8);
  EXPECT_EQ(q.quads, 24);
  EXPECT_EQ(m.tag_index("inner"), -1);
  EXPECT_EQ(m.num_points(), 1 + 4 * 9);
  const double exact = inscribed_sector_area(0, 1, 1.0 / 8, 8);
  EXPECT_NEAR(total_area(m), exact, 1e-14 * exact);
}

TEST(Generators, AnnulusClosesWithoutASeam) {
  const Mesh m = build_mesh(meshgen::annulus(1, 2, 32, 4));
  expect_consistent(m);
  EXPECT_EQ(m.num_zones(), 128);
  EXPECT_EQ(m.num_points(), 32 * 5);
  const double exact = inscribed_sector_area(1, 2, 2 * std::numbers::pi / 32, 32);
  EXPECT_NEAR(total_area(m), exact, 1e-14 * exact);
  EXPECT_EQ(tag(m, "inner").edges.size(), 32U);
  EXPECT_EQ(tag(m, "outer").points.size(), 32U);
  EXPECT_EQ(m.tags.size(), 2U);
}

TEST(Generators, BadArgumentsAreErrors) {
  EXPECT_THROW(meshgen::rectangle(0, 1, 0, 1, 0, 3), Error);
  EXPECT_THROW(meshgen::annulus_sector(1, 0.5, 0, 1, 4, 4), Error);
  EXPECT_THROW(meshgen::annulus_sector(0.5, 1, 0, 2 * std::numbers::pi, 4, 4), Error);
  EXPECT_THROW(meshgen::annulus(0.5, 1, 2, 4), Error);
}

}  // namespace
}  // namespace stagger
