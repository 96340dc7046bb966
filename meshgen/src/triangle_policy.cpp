/// @file triangle_policy.cpp
/// Triangles in a soup (triangle_policy.hpp).
#include "triangle_policy.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "stagger/error.hpp"

namespace stagger::meshgen {

std::size_t count_triangles(const PolygonSoup& soup) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < soup.num_polygons(); ++f)
    n += soup.polygon_begin[f + 1] - soup.polygon_begin[f] == 3 ? 1 : 0;
  return n;
}

void subdivide_soup(PolygonSoup& soup) {
  if (count_triangles(soup) == 0) return;
  if (soup.x.size() >= (std::size_t{1} << 31)) throw Error(soup.source + ": too many points to subdivide");
  std::unordered_map<std::uint64_t, std::int64_t> midpoint;
  const auto key = [](std::int64_t a, std::int64_t b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
  };
  const auto add_point = [&](double x, double y) {
    soup.x.push_back(x);
    soup.y.push_back(y);
    return static_cast<std::int64_t>(soup.x.size() - 1);
  };
  const auto mid = [&](std::int64_t a, std::int64_t b) {
    const auto [it, fresh] = midpoint.emplace(key(a, b), 0);
    if (fresh) {
      const auto A = static_cast<std::size_t>(a), B = static_cast<std::size_t>(b);
      it->second = add_point(0.5 * (soup.x[A] + soup.x[B]), 0.5 * (soup.y[A] + soup.y[B]));
    }
    return it->second;
  };
  const std::vector<std::int64_t> begin = soup.polygon_begin, points = soup.polygon_points;
  const std::vector<int> region = soup.polygon_region;
  soup.polygon_begin = {0};
  soup.polygon_points.clear();
  soup.polygon_region.clear();
  for (std::size_t f = 0; f + 1 < begin.size(); ++f) {
    const auto b = begin[f], n = begin[f + 1] - begin[f];
    double cx = 0, cy = 0;
    for (auto k = b; k < b + n; ++k) {
      cx += soup.x[static_cast<std::size_t>(points[static_cast<std::size_t>(k)])];
      cy += soup.y[static_cast<std::size_t>(points[static_cast<std::size_t>(k)])];
    }
    const std::int64_t centre = add_point(cx / static_cast<double>(n), cy / static_cast<double>(n));
    const auto p = [&](std::int64_t k) { return points[static_cast<std::size_t>(b + (k + n) % n)]; };
    for (std::int64_t k = 0; k < n; ++k)
      soup.add_polygon({p(k), mid(p(k), p(k + 1)), centre, mid(p(k - 1), p(k))}, region.empty() ? 0 : region[f]);
  }
  std::vector<TaggedEdge> edges;
  for (const TaggedEdge& e : soup.tagged_edges) {
    const auto it = midpoint.find(key(e.a, e.b));
    if (it == midpoint.end()) {
      edges.push_back(e);
      continue;
    }
    edges.push_back({e.a, it->second, e.tag});
    edges.push_back({it->second, e.b, e.tag});
  }
  soup.tagged_edges = std::move(edges);
}

void apply_policy(const PolygonSoup& soup, TrianglePolicy policy) {
  if (policy != TrianglePolicy::reject) return;
  const std::size_t n = count_triangles(soup);
  if (n > 0)
    throw Error(soup.source + ": " + std::to_string(n) + " of " + std::to_string(soup.num_polygons()) +
                " zones are triangles and the triangle policy is 'reject'; use 'accept' "
                "(mixed zones) or 'subdivide' (all quads), or make the surface transfinite");
}

}  // namespace stagger::meshgen
