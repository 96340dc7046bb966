#pragma once
/// Invariants every built Mesh must satisfy (shared by the mesh tests).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "stagger/error.hpp"
#include "stagger/mesh.hpp"

namespace stagger::testing {

/// CSR, corner, region and tag consistency; every zone strictly counter-clockwise.
inline void expect_consistent(const Mesh& m) {
  const Index nz = m.num_zones(), nc = m.num_corners(), np = m.num_points();
  ASSERT_EQ(m.zone_corner_begin.size(), static_cast<std::size_t>(nz) + 1);
  ASSERT_EQ(m.zone_corner_begin.front(), 0);
  ASSERT_EQ(m.zone_corner_begin.back(), nc);
  ASSERT_EQ(m.corner_zone.size(), static_cast<std::size_t>(nc));
  ASSERT_EQ(m.zone_region.size(), static_cast<std::size_t>(nz));
  for (Index z = 0; z < nz; ++z) {
    ASSERT_GE(m.zone_corner_begin[z + 1] - m.zone_corner_begin[z], 3) << "zone " << z;
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) ASSERT_EQ(m.corner_zone[c], z);
    EXPECT_GT(zone_area(m, z), 0) << "zone " << z << " is not counter-clockwise";
  }
  // Point -> corners CSR: every corner once, under its own point, ascending.
  ASSERT_EQ(m.point_corner_begin.size(), static_cast<std::size_t>(np) + 1);
  ASSERT_EQ(m.point_corner_begin.back(), nc);
  std::vector<int> seen(static_cast<std::size_t>(nc), 0);
  for (Index p = 0; p < np; ++p) {
    EXPECT_LT(m.point_corner_begin[p], m.point_corner_begin[p + 1]) << "orphan point " << p;
    for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k) {
      const Index c = m.point_corners[k];
      ASSERT_EQ(m.corner_point[c], p);
      ++seen[c];
      if (k > m.point_corner_begin[p]) {
        EXPECT_LT(m.point_corners[k - 1], c);
      }
    }
  }
  for (int s : seen) ASSERT_EQ(s, 1);
  // Zones sorted by region, matching region_zone_begin.
  ASSERT_EQ(m.region_zone_begin.size(), m.region_names.size() + 1);
  ASSERT_EQ(m.region_zone_begin.back(), nz);
  for (Index r = 0; r < m.num_regions(); ++r)
    for (Index z = m.region_zone_begin[r]; z < m.region_zone_begin[r + 1]; ++z) ASSERT_EQ(m.zone_region[z], r);
  // Directed zone edges: each tagged edge is one of them (CCW), tag points match edges.
  std::set<std::pair<Index, Index>> directed;
  for (Index z = 0; z < nz; ++z) {
    const Index b = m.zone_corner_begin[z], e = m.zone_corner_begin[z + 1];
    for (Index c = b; c < e; ++c) directed.insert({m.corner_point[c], m.corner_point[c + 1 == e ? b : c + 1]});
  }
  for (const BoundaryTag& tag : m.tags) {
    std::vector<Index> points;
    for (const auto& edge : tag.edges) {
      EXPECT_TRUE(directed.contains({edge[0], edge[1]})) << "tag " << tag.name << " edge " << edge[0] << "-" << edge[1];
      points.push_back(edge[0]);
      points.push_back(edge[1]);
    }
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    EXPECT_EQ(points, tag.points) << "tag " << tag.name;
  }
}

inline double total_area(const Mesh& m) {
  double sum = 0;
  for (Index z = 0; z < m.num_zones(); ++z) sum += zone_area(m, z);
  return sum;
}

/// Runs `f`, expects a stagger::Error whose message contains every one of `parts`.
template <class F>
void expect_error(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "expected stagger::Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    for (const auto& part : parts) EXPECT_NE(what.find(part), std::string::npos) << "'" << part << "' not in: " << what;
  }
}

}  // namespace stagger::testing
