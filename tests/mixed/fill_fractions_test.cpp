// Fill volume fractions (lib/src/mixed/fill_fractions.hpp): circles and polygons exact to
// round-off, level sets within 1e-6 of the zone area (docs/scenes.md, "[[fill]]").
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mixed/fill_fractions.hpp"

namespace stagger::mixed {

namespace {

// The zones of an n x n Cartesian mesh of the unit square, counter-clockwise.
std::vector<Polygon> unit_square_zones(int n) {
  std::vector<Polygon> zones;
  const double h = 1.0 / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      zones.push_back({{i * h, j * h}, {(i + 1) * h, j * h}, {(i + 1) * h, (j + 1) * h}, {i * h, (j + 1) * h}});
  return zones;
}

}  // namespace

TEST(FillFractions, CircleOn64x64SumsToPiRSquared) {
  const double r = 0.3;
  double total = 0;
  int mixed = 0;
  for (const Polygon& zone : unit_square_zones(64)) {
    const double area = disc_intersection_area(zone, {0.5, 0.47}, r);
    EXPECT_GE(area, -1e-18);
    EXPECT_LE(area, signed_area(zone) * (1 + 1e-12));  // round-off of the centre-relative coordinates
    total += area;
    mixed += area > 1e-14 && area < signed_area(zone) * (1 - 1e-12);
  }
  EXPECT_NEAR(total, std::numbers::pi * r * r, 1e-12);
  EXPECT_GT(mixed, 100);  // the boundary cuts zones: they become mixed
}

TEST(FillFractions, CircleCutByTheDomainEdgeIsHalfADisc) {
  double total = 0;
  for (const Polygon& zone : unit_square_zones(64)) total += disc_intersection_area(zone, {0.5, 0.0}, 0.25);
  EXPECT_NEAR(total, 0.5 * std::numbers::pi * 0.25 * 0.25, 1e-12);
}

TEST(FillFractions, NonConvexPolygonOnAMeshSumsToItsArea) {
  // An L-shaped hexagon (area 0.5 * 0.6 - 0.3 * 0.3) at off-grid coordinates, clockwise.
  const Polygon shape{{0.11, 0.13}, {0.11, 0.73}, {0.41, 0.73}, {0.41, 0.43}, {0.61, 0.43}, {0.61, 0.13}};
  double total = 0;
  for (const Polygon& zone : unit_square_zones(64)) total += intersection_area(zone, shape);
  EXPECT_NEAR(total, std::abs(signed_area(shape)), 1e-13);
  EXPECT_NEAR(std::abs(signed_area(shape)), 0.5 * 0.6 - 0.2 * 0.3, 1e-15);
}

TEST(FillFractions, NonConvexZoneAgainstAHalfPlane) {
  // A dart (non-convex quadrilateral) and a large square covering its right half x > 0.
  const Polygon dart{{-1, -1}, {0, -0.2}, {1, -1}, {0, 1}};
  const Polygon right{{0, -5}, {5, -5}, {5, 5}, {0, 5}};
  EXPECT_NEAR(intersection_area(dart, right), 0.5 * std::abs(signed_area(dart)), 1e-15);
  EXPECT_NEAR(disc_intersection_area(dart, {0, 0}, 100.0), std::abs(signed_area(dart)), 1e-13);
}

TEST(FillFractions, LevelSetWithinOneMillionthOfTheZoneArea) {
  const double r = 0.3;
  const Point c{0.5, 0.47};
  const auto level = [&](double x, double y) { return r * r - (x - c[0]) * (x - c[0]) - (y - c[1]) * (y - c[1]); };
  double total = 0, worst = 0, worst_bound = 0;
  for (const Polygon& zone : unit_square_zones(32)) {
    double bound = 0;
    const double area = level_set_area(zone, level, 8, &bound);
    const double exact = disc_intersection_area(zone, c, r);
    const double zone_area = signed_area(zone);
    worst = std::max(worst, std::abs(area - exact) / zone_area);
    worst_bound = std::max(worst_bound, bound / zone_area);
    total += area;
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(worst_bound, 1e-6);
  EXPECT_GT(worst_bound, 0.1 * worst);  // the a-posteriori estimate is of the size of the error
  EXPECT_NEAR(total, std::numbers::pi * r * r, 1e-6 * 0.3);
  // A straight zero line is exact.
  const auto half = [](double x, double y) { return 0.3 * x + 0.7 * y - 0.41; };
  double straight = 0;
  for (const Polygon& zone : unit_square_zones(16)) straight += level_set_area(zone, half, 4);
  const Polygon below_line{{0, 0}, {1, 0}, {1, (0.41 - 0.3) / 0.7}, {0, 0.41 / 0.7}};
  EXPECT_NEAR(straight, 1.0 - signed_area(below_line), 1e-14);
}

}  // namespace stagger::mixed
