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
  s << "point " << p << " (" << soup.x[static_cast<std::size_t>(p)] << ", " << soup.y[static_cast<std::size_t>(p)]
    << ")";
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
  const auto A = static_cast<std::size_t>(a), B = static_cast<std::size_t>(b), C = static_cast<std::size_t>(c);
  return (s.x[B] - s.x[A]) * (s.y[C] - s.y[A]) - (s.y[B] - s.y[A]) * (s.x[C] - s.x[A]);
}

bool on_segment(const PolygonSoup& s, std::int64_t a, std::int64_t b, std::int64_t p) {
  const auto A = static_cast<std::size_t>(a), B = static_cast<std::size_t>(b), P = static_cast<std::size_t>(p);
  return std::min(s.x[A], s.x[B]) <= s.x[P] && s.x[P] <= std::max(s.x[A], s.x[B]) &&
         std::min(s.y[A], s.y[B]) <= s.y[P] && s.y[P] <= std::max(s.y[A], s.y[B]);
}

/// Open segments (a,b) and (c,d) cross at one interior point of both.
bool segments_cross(const PolygonSoup& s, std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) {
  const double o1 = orient(s, a, b, c), o2 = orient(s, a, b, d);
  const double o3 = orient(s, c, d, a), o4 = orient(s, c, d, b);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

/// Closed segments [a,b] and [c,d] touch (an end point of one lies on the other).
bool segments_touch(const PolygonSoup& s, std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) {
  return (orient(s, a, b, c) == 0 && on_segment(s, a, b, c)) || (orient(s, a, b, d) == 0 && on_segment(s, a, b, d)) ||
         (orient(s, c, d, a) == 0 && on_segment(s, c, d, a)) || (orient(s, c, d, b) == 0 && on_segment(s, c, d, b));
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
  if (soup.x.size() != soup.y.size()) throw Error("polygon soup " + src + ": x and y have different sizes");
  if (soup.polygon_begin.empty() || soup.polygon_begin.front() != 0 ||
      soup.polygon_begin.back() != static_cast<std::int64_t>(soup.polygon_points.size()))
    throw Error("polygon soup " + src +
                ": polygon_begin must start at 0 and end at the size "
                "of polygon_points");
  const std::size_t npoly = soup.num_polygons();
  if (npoly == 0) throw Error("empty mesh: " + src + " has no zones");
  // Offsets must not decrease, or a zone would reach past polygon_points (found by fuzzing).
  for (std::size_t f = 0; f < npoly; ++f)
    if (soup.polygon_begin[f + 1] < soup.polygon_begin[f])
      throw Error("polygon soup " + src + ": polygon_begin decreases at zone " + std::to_string(f) + " (" +
                  std::to_string(soup.polygon_begin[f]) + " then " + std::to_string(soup.polygon_begin[f + 1]) +
                  "); offsets must be non-decreasing");
  if (!soup.polygon_region.empty() && soup.polygon_region.size() != npoly)
    throw Error("polygon soup " + src + ": polygon_region has " + std::to_string(soup.polygon_region.size()) +
                " entries for " + std::to_string(npoly) + " zones");
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
      throw Error("zone " + std::to_string(f) + " of " + src + " has " + std::to_string(end - begin) +
                  " points; a zone needs at least 3");
    for (auto k = begin; k < end; ++k) {
      const auto p = soup.polygon_points[k];
      if (p < 0 || p >= npoints)
        throw Error("zone " + std::to_string(f) + " of " + src + " refers to point " + std::to_string(p) +
                    ", but there are " + std::to_string(npoints) + " points");
      for (auto l = begin; l < k; ++l)
        if (soup.polygon_points[l] == p)
          throw Error("zone " + std::to_string(f) + " of " + src + " uses " + point_text(soup, p) +
                      " twice; remove the repeated corner");
    }
    const int region = soup.polygon_region.empty() ? 0 : soup.polygon_region[f];
    if (region < 0)
      throw Error("zone " + std::to_string(f) + " of " + src + " has negative region " + std::to_string(region));
    // Unnamed regions are allowed (named region_<i>), but an index far beyond the names
    // and the zone count is corruption, and would allocate that many names.
    const std::size_t region_limit = soup.region_names.size() + npoly;
    if (static_cast<std::size_t>(region) >= region_limit)
      throw Error("zone " + std::to_string(f) + " of " + src + " has region index " + std::to_string(region) +
                  ", beyond the " + std::to_string(soup.region_names.size()) + " region names and " +
                  std::to_string(npoly) + " zones; check polygon_region");
    max_region = std::max(max_region, region);
  }
  std::vector<std::string> names = soup.region_names;
  for (int r = static_cast<int>(names.size()); r <= max_region; ++r) names.push_back("region_" + std::to_string(r));
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
  const double tol =
      1e-12 * std::max({xmax - xmin, ymax - ymin, std::abs(xmax), std::abs(xmin), std::abs(ymax), std::abs(ymin)});
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
            return std::to_string(pt(i)) + "-" + std::to_string(pt(i + 1)) + " and " + std::to_string(pt(j)) + "-" +
                   std::to_string(pt(j + 1));
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
      throw Error(zone +
                  " has zero area (its points are collinear or it folds onto itself): " + zone_points_text(soup, f));
    if (const std::string edges = find_pair(segments_touch); !edges.empty())
      throw Error(zone + " touches itself: its edges " + edges +
                  " meet; split it into simple polygons: " + zone_points_text(soup, f));
  }
}

/// Zones that overlap: no two edges may cross or touch except at a shared corner, and no
/// point may lie inside a zone it is not a corner of. A uniform grid of about one cell per
/// edge keeps this O(n) for meshes of even size (each edge and zone is tested against those
/// in the cells its bounding box covers). CGAL's orientation check finds folds inside one
/// connected piece; this also finds separate pieces on top of each other, and meshes that
/// wind round more than once.
void check_overlaps(const Mesh& mesh, const std::vector<std::size_t>& polygon_of_zone,
                    const std::vector<std::int64_t>& soup_point) {
  const Index nzones = mesh.num_zones();
  const auto next_corner = [&](Index k) {
    const Index z = mesh.corner_zone[k];
    return k + 1 == mesh.zone_corner_begin[z + 1] ? mesh.zone_corner_begin[z] : k + 1;
  };
  // Each edge once: an interior edge is kept from the corner whose side runs from the lower
  // to the higher point id.
  std::vector<Index> side;  // corner whose side is the edge
  for (Index k = 0; k < mesh.num_corners(); ++k) {
    const Index a = mesh.corner_point[k], b = mesh.corner_point[next_corner(k)];
    if (a < b) {
      side.push_back(k);
      continue;
    }
    bool twin = false;
    for (Index j = mesh.point_corner_begin[b]; j < mesh.point_corner_begin[b + 1] && !twin; ++j)
      twin = mesh.corner_point[next_corner(mesh.point_corners[j])] == a;
    if (!twin) side.push_back(k);
  }
  double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
  for (Index p = 0; p < mesh.num_points(); ++p) {
    xmin = std::min(xmin, mesh.x[p]);
    xmax = std::max(xmax, mesh.x[p]);
    ymin = std::min(ymin, mesh.y[p]);
    ymax = std::max(ymax, mesh.y[p]);
  }
  const double width = std::max(xmax - xmin, 1e-300), height = std::max(ymax - ymin, 1e-300);
  const double cells_wanted = std::max(1.0, static_cast<double>(side.size()));
  const double h = std::sqrt(width * height / cells_wanted);
  // Extents that overflow (points near +-1e308 in different zones) get one cell.
  const bool gridded = std::isfinite(width) && std::isfinite(height) && std::isfinite(h) && h > 0;
  const auto cells = [&](double extent) {
    return gridded ? static_cast<std::int64_t>(std::clamp(std::ceil(extent / h), 1.0, 65536.0)) : std::int64_t{1};
  };
  const std::int64_t nx = cells(width), ny = cells(height);
  const auto cell_of = [](double t, std::int64_t n) {  // t in [0, 1] -> 0..n-1 (NaN -> 0)
    const double c = std::floor(t * static_cast<double>(n));
    return c >= 0 ? static_cast<std::int64_t>(std::min(c, static_cast<double>(n - 1))) : std::int64_t{0};
  };
  const auto cell_x = [&](double x) { return cell_of((x - xmin) / width, nx); };
  const auto cell_y = [&](double y) { return cell_of((y - ymin) / height, ny); };
  // Buckets (CSR) of items by the cells their bounding boxes cover.
  struct Box {
    std::int64_t i0, i1, j0, j1;
  };
  const auto buckets = [&](std::size_t count, auto box_of, std::vector<std::int64_t>& begin,
                           std::vector<Index>& items) {
    begin.assign(static_cast<std::size_t>(nx * ny) + 1, 0);
    // Counts in begin[cell + 1]; the fill advances begin[cell] itself and the shift back
    // restores the starts (no second array of the grid's size: the peak of a large mesh).
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) {
        for (std::size_t c = 1; c < begin.size(); ++c) begin[c] += begin[c - 1];
        items.resize(static_cast<std::size_t>(begin.back()));
      }
      for (std::size_t item = 0; item < count; ++item) {
        const Box b = box_of(item);
        for (std::int64_t j = b.j0; j <= b.j1; ++j)
          for (std::int64_t i = b.i0; i <= b.i1; ++i) {
            const auto cell = static_cast<std::size_t>(j * nx + i);
            if (pass == 0)
              ++begin[cell + 1];
            else
              items[static_cast<std::size_t>(begin[cell]++)] = static_cast<Index>(item);
          }
      }
    }
    for (std::size_t c = begin.size() - 1; c > 0; --c) begin[c] = begin[c - 1];
    begin[0] = 0;
  };
  const auto point_text = [&](Index p) {
    std::ostringstream t;
    t.precision(12);
    t << "point " << soup_point[static_cast<std::size_t>(p)] << " (" << mesh.x[p] << ", " << mesh.y[p] << ")";
    return t.str();
  };
  const auto zone_text = [&](Index z) {
    return "zone " + std::to_string(polygon_of_zone[static_cast<std::size_t>(z)]);
  };
  const auto edge_text = [&](Index k) {
    return "edge " + std::to_string(soup_point[static_cast<std::size_t>(mesh.corner_point[k])]) + "-" +
           std::to_string(soup_point[static_cast<std::size_t>(mesh.corner_point[next_corner(k)])]) + " of " +
           zone_text(mesh.corner_zone[k]);
  };
  const auto orient = [&](Index a, Index b, Index c) {
    return (mesh.x[b] - mesh.x[a]) * (mesh.y[c] - mesh.y[a]) - (mesh.y[b] - mesh.y[a]) * (mesh.x[c] - mesh.x[a]);
  };
  const auto on_segment = [&](Index a, Index b, Index p) {  // p collinear with a-b: within it?
    return std::min(mesh.x[a], mesh.x[b]) <= mesh.x[p] && mesh.x[p] <= std::max(mesh.x[a], mesh.x[b]) &&
           std::min(mesh.y[a], mesh.y[b]) <= mesh.y[p] && mesh.y[p] <= std::max(mesh.y[a], mesh.y[b]);
  };
  const std::string fix = "; zones must not overlap: check the mesh (or the mesh transform)";

  std::vector<std::int64_t> begin;
  std::vector<Index> items;
  buckets(
      side.size(),
      [&](std::size_t s) {
        const Index a = mesh.corner_point[side[s]], b = mesh.corner_point[next_corner(side[s])];
        return Box{cell_x(std::min(mesh.x[a], mesh.x[b])), cell_x(std::max(mesh.x[a], mesh.x[b])),
                   cell_y(std::min(mesh.y[a], mesh.y[b])), cell_y(std::max(mesh.y[a], mesh.y[b]))};
      },
      begin, items);
  for (std::size_t cell = 0; cell + 1 < begin.size(); ++cell)
    for (auto u = begin[cell]; u < begin[cell + 1]; ++u)
      for (auto v = u + 1; v < begin[cell + 1]; ++v) {
        const Index k1 = side[static_cast<std::size_t>(items[static_cast<std::size_t>(u)])];
        const Index k2 = side[static_cast<std::size_t>(items[static_cast<std::size_t>(v)])];
        const Index a = mesh.corner_point[k1], b = mesh.corner_point[next_corner(k1)];
        const Index c = mesh.corner_point[k2], d = mesh.corner_point[next_corner(k2)];
        const int shared = (a == c) + (a == d) + (b == c) + (b == d);
        if (shared == 2) continue;
        const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
        if (shared == 0 && ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
          throw Error("zones overlap in " + mesh.source + ": " + edge_text(k1) + " crosses " + edge_text(k2) + " (" +
                      point_text(a) + " to " + point_text(b) + ")" + fix);
        // An end point on the other edge (not a shared corner): a hanging node or a fold.
        const auto touches = [&](Index p, double o, Index e0, Index e1) {
          return p != e0 && p != e1 && o == 0 && on_segment(e0, e1, p);
        };
        Index p = -1, k = -1;
        if (touches(c, o1, a, b))
          p = c, k = k1;
        else if (touches(d, o2, a, b))
          p = d, k = k1;
        else if (touches(a, o3, c, d))
          p = a, k = k2;
        else if (touches(b, o4, c, d))
          p = b, k = k2;
        if (p >= 0)
          throw Error("zones overlap or do not connect in " + mesh.source + ": " + point_text(p) + " lies on " +
                      edge_text(k) + " but is not a corner of that zone" + fix);
      }
  // Containment: a point strictly inside a zone it is not a corner of.
  buckets(
      static_cast<std::size_t>(nzones),
      [&](std::size_t z) {
        double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
        for (Index k = mesh.zone_corner_begin[z]; k < mesh.zone_corner_begin[z + 1]; ++k) {
          const Index p = mesh.corner_point[k];
          x0 = std::min(x0, mesh.x[p]);
          x1 = std::max(x1, mesh.x[p]);
          y0 = std::min(y0, mesh.y[p]);
          y1 = std::max(y1, mesh.y[p]);
        }
        return Box{cell_x(x0), cell_x(x1), cell_y(y0), cell_y(y1)};
      },
      begin, items);
  for (Index p = 0; p < mesh.num_points(); ++p) {
    const auto cell = static_cast<std::size_t>(cell_y(mesh.y[p]) * nx + cell_x(mesh.x[p]));
    for (auto u = begin[cell]; u < begin[cell + 1]; ++u) {
      const Index z = items[static_cast<std::size_t>(u)];
      bool corner = false, inside = true;
      for (Index k = mesh.zone_corner_begin[z]; k < mesh.zone_corner_begin[z + 1]; ++k) {
        const Index a = mesh.corner_point[k], b = mesh.corner_point[next_corner(k)];
        if (a == p) corner = true;
        if (!(orient(a, b, p) > 0)) inside = false;  // convex test first: cheap and exact enough
      }
      if (corner) continue;
      if (!inside) {
        // Non-convex zones: crossing number.
        bool odd = false;
        for (Index k = mesh.zone_corner_begin[z]; k < mesh.zone_corner_begin[z + 1]; ++k) {
          const Index a = mesh.corner_point[k], b = mesh.corner_point[next_corner(k)];
          if ((mesh.y[a] > mesh.y[p]) != (mesh.y[b] > mesh.y[p]) &&
              mesh.x[p] < mesh.x[a] + (mesh.x[b] - mesh.x[a]) * (mesh.y[p] - mesh.y[a]) / (mesh.y[b] - mesh.y[a]))
            odd = !odd;
        }
        inside = odd;
      }
      if (inside)
        throw Error("zones overlap in " + mesh.source + ": " + point_text(p) + " lies inside " + zone_text(z) +
                    ", which it is not a corner of" + fix);
    }
  }
}

// quads_only: every 2D element in a physical surface and every zone a quadrilateral.
void check_quads_only(const PolygonSoup& soup) {
  const std::size_t npoly = soup.num_polygons();
  if (soup.unassigned_elements > 0)
    throw Error("quads only: " + std::to_string(soup.unassigned_elements) + " 2D elements of " + soup.source +
                " belong to no physical surface; add them to a Physical Surface (or remove them)");
  {
    std::size_t non_quads = 0, first = npoly;
    for (std::size_t f = 0; f < npoly; ++f)
      if (soup.polygon_begin[f + 1] - soup.polygon_begin[f] != 4) {
        if (non_quads++ == 0) first = f;
      }
    if (non_quads > 0)
      throw Error("quads only: " + std::to_string(non_quads) + " of " + std::to_string(npoly) + " zones of " +
                  soup.source + " are not quadrilaterals (first: zone " + std::to_string(first) + ": " +
                  zone_points_text(soup, first) +
                  "); use the triangle policy 'subdivide' (scene: triangles = \"subdivide\"; "
                  "stagger mesh --triangles subdivide) or allow mixed zones");
  }
}

// The soup's points used by some zone, in their relative order: `used` lists them (soup
// numbers), `compact` maps a soup point to its mesh number (-1: dropped).
struct UsedPoints {
  std::vector<Index> compact;
  std::vector<std::int64_t> used;
};

UsedPoints used_points(const PolygonSoup& soup, MeshBuildReport& rep) {
  // Orphan points are dropped; the others keep their relative order.
  const std::size_t nsoup_points = soup.x.size();
  UsedPoints u;
  std::vector<Index>& compact = u.compact;
  compact.assign(nsoup_points, -1);
  for (auto p : soup.polygon_points) compact[static_cast<std::size_t>(p)] = 0;
  std::vector<std::int64_t>& used = u.used;
  for (std::size_t p = 0; p < nsoup_points; ++p)
    if (compact[p] == 0) {
      compact[p] = static_cast<Index>(used.size());
      used.push_back(static_cast<std::int64_t>(p));
    }
  rep.dropped_points = static_cast<int>(nsoup_points - used.size());
  if (rep.dropped_points > 0)
    rep.notes.push_back(std::to_string(rep.dropped_points) + " points used by no zone were dropped");

  return u;
}

// Orientation of every zone: CGAL's topology check (consistent counter-clockwise orientation,
// manifoldness, boundary loops), or, for a trusted topology, each zone's signed area.
detail::TopologyResult orient_zones(const PolygonSoup& soup, const MeshBuildOptions& options,
                                    const std::vector<double>& cx, const std::vector<double>& cy,
                                    const std::vector<std::int64_t>& cpoints, const std::vector<std::int64_t>& used,
                                    MeshBuildReport& rep) {
  const std::size_t npoly = soup.num_polygons();
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
      const double twice = polygon_twice_area(
          static_cast<int>(soup.polygon_begin[f + 1] - begin), [&](int k) { return cx[point(k)]; },
          [&](int k) { return cy[point(k)]; });
      topo.reversed[f] = twice < 0 ? 1 : 0;
    }
    // All clockwise is a mirror image; some clockwise is a fold, not something to repair.
    const auto clockwise = static_cast<std::size_t>(std::count(topo.reversed.begin(), topo.reversed.end(), 1));
    if (clockwise > 0 && clockwise < npoly) {
      const auto f = static_cast<std::size_t>(
          std::find(topo.reversed.begin(), topo.reversed.end(), clockwise * 2 < npoly ? 1 : 0) - topo.reversed.begin());
      throw Error("zone " + std::to_string(f) + " of " + soup.source + " is inverted relative to the other " +
                  "zones (the mesh folds over there): " + zone_points_text(soup, f));
    }
  }
  return topo;
}

// Zones sorted by region and their corners: fills the mesh's zone and corner arrays and
// returns the soup polygon of each zone.
std::vector<std::size_t> sort_zones(const PolygonSoup& soup, const detail::TopologyResult& topo,
                                    const std::vector<std::int64_t>& cpoints, Mesh& mesh) {
  const std::size_t npoly = soup.num_polygons();
  const auto region_of = [&](std::size_t f) { return soup.polygon_region.empty() ? 0 : soup.polygon_region[f]; };
  // Zones sorted by region (stable: equal regions keep the soup order).
  const auto nregions = static_cast<Index>(mesh.region_names.size());
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
  return polygon_of_zone;
}

// The point -> corners CSR; filling in corner order keeps each list ascending.
void index_point_corners(Mesh& mesh) {
  const auto ncorners = static_cast<Index>(mesh.corner_point.size());
  const Index npoints = mesh.num_points();
  mesh.point_corner_begin.assign(static_cast<std::size_t>(npoints) + 1, 0);
  for (Index k = 0; k < ncorners; ++k) ++mesh.point_corner_begin[mesh.corner_point[k] + 1];
  for (Index p = 0; p < npoints; ++p) mesh.point_corner_begin[p + 1] += mesh.point_corner_begin[p];
  mesh.point_corners.resize(static_cast<std::size_t>(ncorners));
  {
    std::vector<Index> next(mesh.point_corner_begin.begin(), mesh.point_corner_begin.end() - 1);
    for (Index k = 0; k < ncorners; ++k) mesh.point_corners[next[mesh.corner_point[k]]++] = k;
  }
}

// The boundary tags; returns the key of every tagged edge.
std::unordered_set<std::uint64_t> attach_tags(const PolygonSoup& soup, const std::vector<Index>& compact, Mesh& mesh) {
  const std::size_t nsoup_points = soup.x.size();
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
      throw Error("tagged edge " + std::to_string(e.a) + "-" + std::to_string(e.b) + " of " + soup.source +
                  " has tag index " + std::to_string(e.tag) + ", but there are " +
                  std::to_string(soup.tag_names.size()) + " tag names");
    const std::string what = "edge " + std::to_string(e.a) + "-" + std::to_string(e.b) + " of tag '" +
                             soup.tag_names[static_cast<std::size_t>(e.tag)] + "' in " + soup.source;
    const auto in_range = [&](std::int64_t p) {
      return p >= 0 && static_cast<std::size_t>(p) < nsoup_points && compact[static_cast<std::size_t>(p)] >= 0;
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
      throw Error(what + " is not an edge of the mesh: " + point_text(soup, e.a) + " and " + point_text(soup, e.b) +
                  " are not consecutive corners of any zone");
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

  return tagged;
}

// The report's notes on CGAL's boundary loops and on flipped components.
void report_boundary(const detail::TopologyResult& topo, const std::unordered_set<std::uint64_t>& tagged,
                     const MeshBuildOptions& options, MeshBuildReport& rep) {
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
                        std::to_string(boundary_edges) + " boundary edges, " + std::to_string(untagged) +
                        " of them untagged");
  if (topo.flipped_components > 0)
    rep.notes.push_back(std::to_string(topo.flipped_components) + " of " + std::to_string(topo.components) +
                        " connected component(s) were clockwise as a whole and were flipped");
}

}  // namespace

Mesh build_mesh(const PolygonSoup& soup, const MeshBuildOptions& options, MeshBuildReport* report) {
  MeshBuildReport local_report;
  MeshBuildReport& rep = report ? *report : local_report;
  rep = MeshBuildReport{};
  const std::vector<std::string> region_names = check_structure(soup);
  const std::size_t npoly = soup.num_polygons();

  for (const auto& note : soup.notes) rep.notes.push_back(note);
  if (options.quads_only) check_quads_only(soup);
  UsedPoints points = used_points(soup, rep);
  const std::vector<std::int64_t>& used = points.used;
  const std::vector<Index>& compact = points.compact;

  check_duplicates(soup, used);
  check_zone_geometry(soup);

  std::vector<double> cx(used.size()), cy(used.size());
  for (std::size_t i = 0; i < used.size(); ++i) {
    cx[i] = soup.x[static_cast<std::size_t>(used[i])];
    cy[i] = soup.y[static_cast<std::size_t>(used[i])];
  }
  std::vector<std::int64_t> cpoints(soup.polygon_points.size());
  for (std::size_t k = 0; k < cpoints.size(); ++k)
    cpoints[k] = compact[static_cast<std::size_t>(soup.polygon_points[k])];
  const detail::TopologyResult topo = orient_zones(soup, options, cx, cy, cpoints, used, rep);
  for (auto r : topo.reversed) rep.reoriented_zones += r;
  if (rep.reoriented_zones > 0)
    rep.notes.push_back(std::to_string(rep.reoriented_zones) + " of " + std::to_string(npoly) +
                        " zones were clockwise and were reoriented counter-clockwise");

  Mesh mesh;
  mesh.source = soup.source;
  mesh.x = std::move(cx);
  mesh.y = std::move(cy);
  mesh.region_names = region_names;
  const std::vector<std::size_t> polygon_of_zone = sort_zones(soup, topo, cpoints, mesh);
  // Drop what the corners were read from before the checks below allocate (peak memory).
  cpoints = {};
  index_point_corners(mesh);
  const std::unordered_set<std::uint64_t> tagged = attach_tags(soup, compact, mesh);
  check_overlaps(mesh, polygon_of_zone, used);
  report_boundary(topo, tagged, options, rep);
  return mesh;
}

}  // namespace stagger
