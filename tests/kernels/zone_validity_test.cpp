// The crossing-zone test of docs/verification.md ("crossing zone"), on hand-made polygons.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <utility>

#include "hydro/kernels/zone_validity.hpp"

namespace stagger {
namespace {

ZoneVertices polygon(std::initializer_list<std::pair<double, double>> points) {
  ZoneVertices v;
  for (const auto& [x, y] : points) {
    v.x[v.n] = x;
    v.y[v.n] = y;
    ++v.n;
  }
  return v;
}

TEST(ZoneValidity, UnitSquareIsAZone) {
  EXPECT_FALSE(zone_crosses(polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}})));
  EXPECT_FALSE(zone_crosses<4>(polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}})));
}

TEST(ZoneValidity, ClockwiseSquareHasNegativeArea) {
  EXPECT_TRUE(zone_crosses(polygon({{0, 0}, {0, 1}, {1, 1}, {1, 0}})));
}

TEST(ZoneValidity, NonConvexArrowIsStillAZone) {
  // A dart: the vertex (0.5, 0.3) is reflex, the area positive, no edges cross.
  EXPECT_FALSE(zone_crosses(polygon({{0, 0}, {0.5, 0.3}, {1, 0}, {0.5, 1}})));
}

TEST(ZoneValidity, BowTieWithPositiveAreaCrosses) {
  // Edges 0-1 and 2-3 cross at (1, 0.5); the left lobe (area 1) outweighs the right one
  // (area 0.25), so the signed area is positive and only the edge test catches it.
  const ZoneVertices v = polygon({{0, 0}, {1.5, 0.75}, {1.5, 0.25}, {0, 1}});
  ASSERT_GT(PlanarGeometry::area(v), 0);
  EXPECT_TRUE(zone_crosses(v));
}

TEST(ZoneValidity, PentagonWithAFoldedVertexCrosses) {
  // Vertex 0 of a regular pentagon pushed through the opposite edge 2-3 (x = cos 144 deg).
  ZoneVertices v;
  v.n = 5;
  for (int k = 0; k < 5; ++k) {
    v.x[k] = std::cos(2 * M_PI * k / 5);
    v.y[k] = std::sin(2 * M_PI * k / 5);
  }
  ASSERT_FALSE(zone_crosses(v));
  v.x[0] = -1.0;  // edges 4-0 and 0-1 now cut through edge 2-3; the area stays positive
  v.y[0] = 0.0;
  ASSERT_GT(PlanarGeometry::area(v), 0);
  EXPECT_TRUE(zone_crosses(v));
}

TEST(ZoneValidity, TouchingIsNotAProperCrossing) {
  // A vertex lying exactly on a non-adjacent edge: degenerate, but the area test decides.
  EXPECT_FALSE(segments_cross(0, 0, 2, 0, 1, 0, 1, 1));
  EXPECT_TRUE(segments_cross(0, 0, 2, 0, 1, -1, 1, 1));
}

}  // namespace
}  // namespace stagger
