/// @file build_mesh.cpp
/// Polygon soup -> checked flat-array Mesh. The checks that need no topology (structure,
/// duplicate points, degenerate and self-intersecting zones) live here; orientation,
/// manifoldness and boundary loops are done by CGAL in topology_cgal.cpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_set>

#include "mesh/polygon.hpp"
#include "stagger/error.hpp"
#include "stagger/mesh.hpp"
#include "topology_cgal.hpp"

namespace stagger {
namespace {

std::string point_text(const PolygonSoup& soup, std::int64_t p) {
  std::ostringstream s;
  s.precision(12);
  s << "point " << p << " (" << soup.x[static_cast<std::size_t>(p)] << ", "
    << soup.y[static_cast<std::size_t>(p)] << ")";
  return s.str();
}

std::string zone_points_text(const PolygonSoup& soup, std::size_t f) {
  std::string text;
  for (auto k = soup.polygon_begin[f]; k < soup.polygon_begin[f + 1]; ++k)
    text += (text.empty() ? "" : ", ") + point_text(soup, soup.polygon_points[k]);
  return text;
}

/// Sign of the turn a -> b -> c (twice the signed triangle area).
double orient(const PolygonSoup& s, std::int64_t a, std::int64_t b, std::int64_t c) {
  const auto A = static_cast<std::size_t>(a), B = static_cast<std::size_t>(b),
             C = static_cast<std::size_t>(c);
  return (s.x[B] - s.x[A]) * (s.y[C] - s.y[A]) - (s.y[B] - s.y[A]) * (s.x[C] - s.x[A]);
}

bool on_segment(const PolygonSoup& s, std::int64_t a, std::int64_t b, std::int64_t p) {
  const auto A = static_cast<std::size_t>(a), B = static_cast<std::size_t>(b),
             P = static_cast<std::size_t>(p);
  return std::min(s.x[A], s.x[B]) <= s.x[P] && s.x[P] <= std::max(s.x[A], s.x[B]) &&
         std::min(s.y[A], s.y[B]) <= s.y[P] && s.y[P] <= std::max(s.y[A], s.y[B]);
}

/// Open segments (a,b) and (c,d) cross at one interior point of both.
bool segments_cross(const PolygonSoup& s, std::int64_t a, std::int64_t b, std::int64_t c,
                    std::int64_t d) {
  const double o1 = orient(s, a, b, c), o2 = orient(s, a, b, d);
  const double o3 = orient(s, c, d, a), o4 = orient(s, c, d, b);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

/// Closed segments [a,b] and [c,d] touch (an end point of one lies on the other).
bool segments_touch(const PolygonSoup& s, std::int64_t a, std::int64_t b, std::int64_t c,
                    std::int64_t d) {
  return (orient(s, a, b, c) == 0 && on_segment(s, a, b, c)) ||
         (orient(s, a, b, d) == 0 && on_segment(s, a, b, d)) ||
         (orient(s, c, d, a) == 0 && on_segment(s, c, d, a)) ||
         (orient(s, c, d, b) == 0 && on_segment(s, c, d, b));
}

std::uint64_t edge_key(Index a, Index b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (hi << 32) | lo;
}

/// Structure of the soup: sizes, offsets, point ids, regions. Returns the region names
/// (missing names filled in as "region_<i>").
std::vector<std::string> check_structure(const PolygonSoup& soup) {
  const std::string& src = soup.source;
  if (soup.x.size() != soup.y.size())
    throw Error("polygon soup " + src + ": x and y have different sizes");
  if (soup.polygon_begin.empty() || soup.polygon_begin.front() != 0 ||
      soup.polygon_begin.back() != static_cast<std::int64_t>(soup.polygon_points.size()))
    throw Error("polygon soup " + src + ": polygon_begin must start at 0 and end at the size "
                "of polygon_points");
  const std::size_t npoly = soup.num_polygons();
  if (npoly == 0) throw Error("empty mesh: " + src + " has no zones");
  // Offsets must not decrease, or a zone would reach past polygon_points (found by fuzzing).
  for (std::size_t f = 0; f < npoly; ++f)
    if (soup.polygon_begin[f + 1] < soup.polygon_begin[f])
      throw Error("polygon soup " + src + ": polygon_begin decreases at zone " + std::to_string(f) +
                  " (" + std::to_string(soup.polygon_begin[f]) + " then " +
                  std::to_string(soup.polygon_begin[f + 1]) + "); offsets must be non-decreasing");
  if (!soup.polygon_region.empty() && soup.polygon_region.size() != npoly)
    throw Error("polygon soup " + src + ": polygon_region has " +
                std::to_string(soup.polygon_region.size()) + " entries for " +
                std::to_string(npoly) + " zones");
  if (soup.x.size() > static_cast<std::size_t>(std::numeric_limits<Index>::max()) ||
      soup.polygon_points.size() > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
    throw Error("mesh " + src + " is too large for 32-bit indices");
  const auto npoints = static_cast<std::int64_t>(soup.x.size());
  for (std::size_t p = 0; p < soup.x.size(); ++p)
    if (!std::isfinite(soup.x[p]) || !std::isfinite(soup.y[p]))
      throw Error("point " + std::to_string(p) + " of " + src + " has a non-finite coordinate");
  int max_region = -1;
  for (std::size_t f = 0; f < npoly; ++f) {
    const auto begin = soup.polygon_begin[f], end = soup.polygon_begin[f + 1];
    if (end - begin < 3)
      throw Error("zone " + std::to_string(f) + " of " + src + " has " +
                  std::to_string(end - begin) + " points; a zone needs at least 3");
    for (auto k = begin; k < end; ++k) {
      const auto p = soup.polygon_points[k];
      if (p < 0 || p >= npoints)
        throw Error("zone " + std::to_string(f) + " of " + src + " refers to point " +
                    std::to_string(p) + ", but there are " + std::to_string(npoints) + " points");
      for (auto l = begin; l < k; ++l)
        if (soup.polygon_points[l] == p)
          throw Error("zone " + std::to_string(f) + " of " + src + " uses " +
                      point_text(soup, p) + " twice; remove the repeated corner");
    }
    const int region = soup.polygon_region.empty() ? 0 : soup.polygon_region[f];
    if (region < 0)
      throw Error("zone " + std::to_string(f) + " of " + src + " has negative region " +
                  std::to_string(region));
    // Unnamed regions are allowed (named region_<i>), but an index far beyond the names
    // and the zone count is corruption, and would allocate that many names.
    const std::size_t region_limit = soup.region_names.size() + npoly;
    if (static_cast<std::size_t>(region) >= region_limit)
      throw Error("zone " + std::to_string(f) + " of " + src + " has region index " +
                  std::to_string(region) + ", beyond the " + std::to_string(soup.region_names.size()) +
                  " region names and " + std::to_string(npoly) + " zones; check polygon_region");
    max_region = std::max(max_region, region);
  }
  std::vector<std::string> names = soup.region_names;
  for (int r = static_cast<int>(names.size()); r <= max_region; ++r)
    names.push_back("region_" + std::to_string(r));
  return names;
}

/// Duplicate points (same coordinates to 1e-12 of the mesh size) among the used points.
void check_duplicates(const PolygonSoup& soup, const std::vector<std::int64_t>& used) {
  double xmin = std::numeric_limits<double>::max(), xmax = std::numeric_limits<double>::lowest();
  double ymin = xmin, ymax = xmax;
  for (auto p : used) {
    const auto i = static_cast<std::size_t>(p);
    xmin = std::min(xmin, soup.x[i]);
    xmax = std::max(xmax, soup.x[i]);
    ymin = std::min(ymin, soup.y[i]);
    ymax = std::max(ymax, soup.y[i]);
  }
  const double tol = 1e-12 * std::max({xmax - xmin, ymax - ymin, std::abs(xmax), std::abs(xmin),
                                       std::abs(ymax), std::abs(ymin)});
  std::vector<std::int64_t> order = used;
  std::sort(order.begin(), order.end(), [&](std::int64_t a, std::int64_t b) {
    return soup.x[static_cast<std::size_t>(a)] < soup.x[static_cast<std::size_t>(b)];
  });
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto a = static_cast<std::size_t>(order[i]);
    for (std::size_t j = i + 1; j < order.size(); ++j) {
      const auto b = static_cast<std::size_t>(order[j]);
      if (soup.x[b] - soup.x[a] > tol) break;
      if (std::abs(soup.y[b] - soup.y[a]) <= tol) {
        const auto lo = std::min(order[i], order[j]), hi = std::max(order[i], order[j]);
        throw Error("duplicate points in " + soup.source + ": " + point_text(soup, lo) + " and " +
                    point_text(soup, hi) +
                    " coincide (to 1e-12 relative); merge them so the zones around them connect");
      }
    }
  }
}

/// Self-intersecting (bow-tie) and zero-area zones. Every pair of non-adjacent edges must be
/// disjoint (O(n^2) per zone, n is small): crossings first (a symmetric bow-tie also has
/// zero area, and "crosses itself" is the better message), then the area, then touching.
void check_zone_geometry(const PolygonSoup& soup) {
  for (std::size_t f = 0; f < soup.num_polygons(); ++f) {
    const auto begin = soup.polygon_begin[f];
    const auto n = soup.polygon_begin[f + 1] - begin;
    const auto pt = [&](std::int64_t k) { return soup.polygon_points[begin + (k % n)]; };
    const auto find_pair = [&](auto meets) -> std::string {
      for (std::int64_t i = 0; i < n; ++i)
        for (std::int64_t j = i + 2; j < n; ++j) {
          if (i == 0 && j == n - 1) continue;  // adjacent through the closing corner
          if (meets(soup, pt(i), pt(i + 1), pt(j), pt(j + 1)))
            return std::to_string(pt(i)) + "-" + std::to_string(pt(i + 1)) + " and " +
                   std::to_string(pt(j)) + "-" + std::to_string(pt(j + 1));
        }
      return {};
    };
    const std::string zone = "zone " + std::to_string(f) + " of " + soup.source;
    if (const std::string edges = find_pair(segments_cross); !edges.empty())
      throw Error(zone + " crosses itself (bow-tie): its edges " + edges +
                  " intersect; reorder its points: " + zone_points_text(soup, f));
    const double twice_area = polygon_twice_area(
        static_cast<int>(n), [&](int k) { return soup.x[static_cast<std::size_t>(pt(k))]; },
        [&](int k) { return soup.y[static_cast<std::size_t>(pt(k))]; });
    double longest2 = 0;
    for (std::int64_t k = 0; k < n; ++k) {
      const auto a = static_cast<std::size_t>(pt(k)), b = static_cast<std::size_t>(pt(k + 1));
      const double dx = soup.x[b] - soup.x[a], dy = soup.y[b] - soup.y[a];
      longest2 = std::max(longest2, dx * dx + dy * dy);
    }
    // Coordinates near the largest double overflow the shoelace sum (found by fuzzing):
    // NaN compares false, so test finiteness first.
    if (!std::isfinite(twice_area) || !std::isfinite(longest2))
      throw Error(zone + " is so large that its area overflows (coordinates of magnitude near 1e308): " +
                  zone_points_text(soup, f) + "; rescale the mesh");
    if (!(std::abs(0.5 * twice_area) > 1e-12 * longest2))
      throw Error(zone + " has zero area (its points are collinear or it folds onto itself): " +
                  zone_points_text(soup, f));
    if (const std::string edges = find_pair(segments_touch); !edges.empty())
      throw Error(zone + " touches itself: its edges " + edges +
                  " meet; split it into simple polygons: " + zone_points_text(soup, f));
  }
}

}  // namespace

Mesh build_mesh(const PolygonSoup& soup, const MeshBuildOptions& options,
                MeshBuildReport* report) {
  MeshBuildReport local_report;
  MeshBuildReport& rep = report ? *report : local_report;
  rep = MeshBuildReport{};
  const std::vector<std::string> region_names = check_structure(soup);
  const std::size_t npoly = soup.num_polygons();
  const auto region_of = [&](std::size_t f) {
    return soup.polygon_region.empty() ? 0 : soup.polygon_region[f];
  };

  if (options.quads_only) {
    std::size_t non_quads = 0, first = npoly;
    for (std::size_t f = 0; f < npoly; ++f)
      if (soup.polygon_begin[f + 1] - soup.polygon_begin[f] != 4) {
        if (non_quads++ == 0) first = f;
      }
    if (non_quads > 0)
      throw Error("quads only: " + std::to_string(non_quads) + " of " + std::to_string(npoly) +
                  " zones of " + soup.source + " are not quadrilaterals (first: zone " +
                  std::to_string(first) + ": " + zone_points_text(soup, first) +
                  "); use the triangle policy 'subdivide' (scene: triangles = \"subdivide\"; "
                  "stagger mesh --triangles subdivide) or allow mixed zones");
  }

  // Orphan points are dropped; the others keep their relative order.
  const std::size_t nsoup_points = soup.x.size();
  std::vector<Index> compact(nsoup_points, -1);
  for (auto p : soup.polygon_points) compact[static_cast<std::size_t>(p)] = 0;
  std::vector<std::int64_t> used;
  for (std::size_t p = 0; p < nsoup_points; ++p)
    if (compact[p] == 0) {
      compact[p] = static_cast<Index>(used.size());
      used.push_back(static_cast<std::int64_t>(p));
    }
  rep.dropped_points = static_cast<int>(nsoup_points - used.size());
  if (rep.dropped_points > 0)
    rep.notes.push_back(std::to_string(rep.dropped_points) +
                        " points used by no zone were dropped");

  check_duplicates(soup, used);
  check_zone_geometry(soup);

  // Topology (CGAL): consistent counter-clockwise orientation, manifoldness, loops.
  std::vector<double> cx(used.size()), cy(used.size());
  for (std::size_t i = 0; i < used.size(); ++i) {
    cx[i] = soup.x[static_cast<std::size_t>(used[i])];
    cy[i] = soup.y[static_cast<std::size_t>(used[i])];
  }
  std::vector<std::int64_t> cpoints(soup.polygon_points.size());
  for (std::size_t k = 0; k < cpoints.size(); ++k)
    cpoints[k] = compact[static_cast<std::size_t>(soup.polygon_points[k])];
  std::vector<std::int64_t> polygon_ids(npoly);
  std::iota(polygon_ids.begin(), polygon_ids.end(), std::int64_t{0});
  detail::TopologyResult topo;
  if (options.check_topology) {
    const auto start = std::chrono::steady_clock::now();
    topo = detail::orient_and_check_topology({cx, cy, soup.polygon_begin, cpoints, used, polygon_ids, soup.source});
    rep.topology_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } else {
    // Trusted topology (the built-in generators): orientation from each zone's signed area.
    topo.reversed.assign(npoly, 0);
    for (std::size_t f = 0; f < npoly; ++f) {
      const auto begin = soup.polygon_begin[f];
      const auto point = [&](int k) { return static_cast<std::size_t>(cpoints[static_cast<std::size_t>(begin + k)]); };
      const double twice = polygon_twice_area(static_cast<int>(soup.polygon_begin[f + 1] - begin),
                                              [&](int k) { return cx[point(k)]; }, [&](int k) { return cy[point(k)]; });
      topo.reversed[f] = twice < 0 ? 1 : 0;
    }
  }
  polygon_ids = {};
  for (auto r : topo.reversed) rep.reoriented_zones += r;
  if (rep.reoriented_zones > 0)
    rep.notes.push_back(std::to_string(rep.reoriented_zones) + " of " + std::to_string(npoly) +
                        " zones were clockwise and were reoriented counter-clockwise");

  Mesh mesh;
  mesh.source = soup.source;
  mesh.x = std::move(cx);
  mesh.y = std::move(cy);
  mesh.region_names = region_names;

  // Zones sorted by region (stable: equal regions keep the soup order).
  const auto nregions = static_cast<Index>(region_names.size());
  mesh.region_zone_begin.assign(static_cast<std::size_t>(nregions) + 1, 0);
  for (std::size_t f = 0; f < npoly; ++f) ++mesh.region_zone_begin[region_of(f) + 1];
  for (Index r = 0; r < nregions; ++r) mesh.region_zone_begin[r + 1] += mesh.region_zone_begin[r];
  std::vector<Index> zone_of_polygon(npoly);
  {
    std::vector<Index> next(mesh.region_zone_begin.begin(), mesh.region_zone_begin.end() - 1);
    for (std::size_t f = 0; f < npoly; ++f) zone_of_polygon[f] = next[region_of(f)]++;
  }
  std::vector<std::size_t> polygon_of_zone(npoly);
  for (std::size_t f = 0; f < npoly; ++f) polygon_of_zone[zone_of_polygon[f]] = f;

  // Corners: contiguous per zone, counter-clockwise, starting at the soup's first point.
  const auto ncorners = static_cast<Index>(soup.polygon_points.size());
  mesh.zone_corner_begin.assign(npoly + 1, 0);
  mesh.corner_point.resize(static_cast<std::size_t>(ncorners));
  mesh.corner_zone.resize(static_cast<std::size_t>(ncorners));
  mesh.zone_region.resize(npoly);
  Index c = 0;
  for (std::size_t z = 0; z < npoly; ++z) {
    const std::size_t f = polygon_of_zone[z];
    const auto begin = soup.polygon_begin[f];
    const auto n = soup.polygon_begin[f + 1] - begin;
    for (std::int64_t k = 0; k < n; ++k) {
      const auto src = topo.reversed[f] ? (n - k) % n : k;
      mesh.corner_point[c] = static_cast<Index>(cpoints[static_cast<std::size_t>(begin + src)]);
      mesh.corner_zone[c] = static_cast<Index>(z);
      ++c;
    }
    mesh.zone_corner_begin[z + 1] = c;
    mesh.zone_region[z] = region_of(f);
  }

  // CSR point -> corners; filling in corner order keeps each list ascending.
  const Index npoints = mesh.num_points();
  mesh.point_corner_begin.assign(static_cast<std::size_t>(npoints) + 1, 0);
  for (Index k = 0; k < ncorners; ++k) ++mesh.point_corner_begin[mesh.corner_point[k] + 1];
  for (Index p = 0; p < npoints; ++p) mesh.point_corner_begin[p + 1] += mesh.point_corner_begin[p];
  mesh.point_corners.resize(static_cast<std::size_t>(ncorners));
  {
    std::vector<Index> next(mesh.point_corner_begin.begin(), mesh.point_corner_begin.end() - 1);
    for (Index k = 0; k < ncorners; ++k) mesh.point_corners[next[mesh.corner_point[k]]++] = k;
  }

  // Tags: every tagged edge must be an edge of some zone; it takes that zone's
  // counter-clockwise direction (the first zone, for an interior edge).
  const auto next_corner = [&](Index k) {
    const Index z = mesh.corner_zone[k];
    return k + 1 == mesh.zone_corner_begin[z + 1] ? mesh.zone_corner_begin[z] : k + 1;
  };
  const auto prev_corner = [&](Index k) {
    const Index z = mesh.corner_zone[k];
    return k == mesh.zone_corner_begin[z] ? mesh.zone_corner_begin[z + 1] - 1 : k - 1;
  };
  mesh.tags.resize(soup.tag_names.size());
  for (std::size_t t = 0; t < soup.tag_names.size(); ++t) mesh.tags[t].name = soup.tag_names[t];
  std::vector<std::unordered_set<std::uint64_t>> seen(soup.tag_names.size());
  std::unordered_set<std::uint64_t> tagged;
  for (const TaggedEdge& e : soup.tagged_edges) {
    if (e.tag < 0 || static_cast<std::size_t>(e.tag) >= soup.tag_names.size())
      throw Error("tagged edge " + std::to_string(e.a) + "-" + std::to_string(e.b) + " of " +
                  soup.source + " has tag index " + std::to_string(e.tag) + ", but there are " +
                  std::to_string(soup.tag_names.size()) + " tag names");
    const std::string what = "edge " + std::to_string(e.a) + "-" + std::to_string(e.b) +
                             " of tag '" + soup.tag_names[static_cast<std::size_t>(e.tag)] +
                             "' in " + soup.source;
    const auto in_range = [&](std::int64_t p) {
      return p >= 0 && static_cast<std::size_t>(p) < nsoup_points &&
             compact[static_cast<std::size_t>(p)] >= 0;
    };
    if (!in_range(e.a) || !in_range(e.b))
      throw Error(what + " is not an edge of the mesh (an end point is used by no zone)");
    const Index a = compact[static_cast<std::size_t>(e.a)], b = compact[static_cast<std::size_t>(e.b)];
    std::array<Index, 2> oriented{-1, -1};
    for (Index k = mesh.point_corner_begin[a]; k < mesh.point_corner_begin[a + 1]; ++k) {
      const Index corner = mesh.point_corners[k];
      if (mesh.corner_point[next_corner(corner)] == b) {
        oriented = {a, b};
        break;
      }
      if (mesh.corner_point[prev_corner(corner)] == b) {
        oriented = {b, a};
        break;
      }
    }
    if (oriented[0] < 0)
      throw Error(what + " is not an edge of the mesh: " + point_text(soup, e.a) + " and " +
                  point_text(soup, e.b) + " are not consecutive corners of any zone");
    if (!seen[static_cast<std::size_t>(e.tag)].insert(edge_key(a, b)).second) continue;
    tagged.insert(edge_key(a, b));
    BoundaryTag& tag = mesh.tags[static_cast<std::size_t>(e.tag)];
    tag.edges.push_back(oriented);
    tag.points.push_back(a);
    tag.points.push_back(b);
  }
  for (BoundaryTag& tag : mesh.tags) {
    std::sort(tag.points.begin(), tag.points.end());
    tag.points.erase(std::unique(tag.points.begin(), tag.points.end()), tag.points.end());
  }

  // Boundary loops from CGAL: count them and the boundary edges no tag covers.
  std::size_t untagged = 0, boundary_edges = 0;
  for (const auto& loop : topo.boundary_loops) {
    for (std::size_t k = 0; k < loop.size(); ++k) {
      ++boundary_edges;
      const auto a = static_cast<Index>(loop[k]), b = static_cast<Index>(loop[(k + 1) % loop.size()]);
      if (!tagged.contains(edge_key(a, b))) ++untagged;
    }
  }
  if (options.check_topology)
    rep.notes.push_back(std::to_string(topo.boundary_loops.size()) + " boundary loop(s), " +
                      std::to_string(boundary_edges) + " boundary edges, " +
                      std::to_string(untagged) + " of them untagged");
  if (topo.flipped_components > 0)
    rep.notes.push_back(std::to_string(topo.flipped_components) + " of " +
                        std::to_string(topo.components) +
                        " connected component(s) were clockwise as a whole and were flipped");
  return mesh;
}

}  // namespace stagger
