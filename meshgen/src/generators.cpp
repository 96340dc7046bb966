/// @file generators.cpp
/// Structured generators (no gmsh): rectangle, equal-angle annulus sector, full annulus.
/// Zones are counter-clockwise; regions and tags are named as in meshgen.hpp and as in the
/// matching .geo files of geometries/.
#include <cmath>
#include <numbers>
#include <string>

#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::meshgen {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error(message);
}

int add_tag(PolygonSoup& soup, const std::string& name) {
  soup.tag_names.push_back(name);
  return static_cast<int>(soup.tag_names.size()) - 1;
}

}  // namespace

PolygonSoup rectangle(double x0, double x1, double y0, double y1, int nx, int ny) {
  require(nx > 0 && ny > 0,
          "rectangle: nx and ny must be positive (got " + std::to_string(nx) + " x " + std::to_string(ny) + ")");
  require(x1 > x0 && y1 > y0, "rectangle: need x0 < x1 and y0 < y1");
  PolygonSoup soup;
  soup.source = "rectangle(" + std::to_string(nx) + "x" + std::to_string(ny) + ")";
  soup.region_names = {"domain"};
  const auto id = [nx](int i, int j) { return static_cast<std::int64_t>(j) * (nx + 1) + i; };
  soup.x.reserve(static_cast<std::size_t>(nx + 1) * (ny + 1));
  soup.y.reserve(soup.x.capacity());
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      // Endpoints exactly at x1/y1 (no accumulated rounding on the boundary).
      soup.x.push_back(i == nx ? x1 : x0 + (x1 - x0) * i / nx);
      soup.y.push_back(j == ny ? y1 : y0 + (y1 - y0) * j / ny);
    }
  }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) soup.add_polygon({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}, 0);
  const int left = add_tag(soup, "left"), right = add_tag(soup, "right");
  const int bottom = add_tag(soup, "bottom"), top = add_tag(soup, "top");
  for (int j = 0; j < ny; ++j) {
    soup.tagged_edges.push_back({id(0, j), id(0, j + 1), left});
    soup.tagged_edges.push_back({id(nx, j), id(nx, j + 1), right});
  }
  for (int i = 0; i < nx; ++i) {
    soup.tagged_edges.push_back({id(i, 0), id(i + 1, 0), bottom});
    soup.tagged_edges.push_back({id(i, ny), id(i + 1, ny), top});
  }
  return soup;
}

namespace {

// Equal-angle polar mesh: n_theta x n_r zones between radii r0 and r1 and angles theta0 and
// theta1, shared by the sector and the full ring (closed: angle index n_theta is index 0).
// r0 = 0 makes the centre ring triangles around one centre point. Tags inner (unless
// r0 = 0) and outer; the sector adds start and end.
PolygonSoup polar_mesh(const std::string& source, double r0, double r1, double theta0, double theta1, int n_theta,
                       int n_r, bool closed) {
  PolygonSoup soup;
  soup.source = source;
  soup.region_names = {"domain"};
  const bool centre = r0 == 0;
  const int per_ring = closed ? n_theta : n_theta + 1;
  // Point (i, j): angle index i, radius index j in [0, n_r]; with r0 = 0 the whole ring
  // j = 0 is one centre point.
  const auto id = [&](int i, int j) -> std::int64_t {
    if (closed) i %= n_theta;
    if (centre) return j == 0 ? 0 : 1 + static_cast<std::int64_t>(j - 1) * per_ring + i;
    return static_cast<std::int64_t>(j) * per_ring + i;
  };
  for (int j = 0; j <= n_r; ++j) {
    const double r = j == n_r ? r1 : r0 + (r1 - r0) * j / n_r;
    if (centre && j == 0) {
      soup.x.push_back(0);
      soup.y.push_back(0);
      continue;
    }
    for (int i = 0; i < per_ring; ++i) {
      const double t = i == n_theta ? theta1 : theta0 + (theta1 - theta0) * i / n_theta;
      soup.x.push_back(r * std::cos(t));
      soup.y.push_back(r * std::sin(t));
    }
  }
  // (r, theta) is a right-handed pair, so r first then theta gives counter-clockwise zones.
  for (int j = 0; j < n_r; ++j) {
    for (int i = 0; i < n_theta; ++i) {
      if (centre && j == 0)
        soup.add_polygon({id(i, 0), id(i, 1), id(i + 1, 1)}, 0);
      else
        soup.add_polygon({id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)}, 0);
    }
  }
  const int inner = centre ? -1 : add_tag(soup, "inner");
  const int outer = add_tag(soup, "outer");
  for (int i = 0; i < n_theta; ++i) {
    if (!centre) soup.tagged_edges.push_back({id(i, 0), id(i + 1, 0), inner});
    soup.tagged_edges.push_back({id(i, n_r), id(i + 1, n_r), outer});
  }
  if (!closed) {
    const int start = add_tag(soup, "start"), end = add_tag(soup, "end");
    for (int j = 0; j < n_r; ++j) {
      soup.tagged_edges.push_back({id(0, j), id(0, j + 1), start});
      soup.tagged_edges.push_back({id(n_theta, j), id(n_theta, j + 1), end});
    }
  }
  return soup;
}

}  // namespace

PolygonSoup annulus_sector(double r0, double r1, double theta0, double theta1, int n_theta, int n_r) {
  require(n_theta > 0 && n_r > 0, "annulus_sector: n_theta and n_r must be positive");
  require(r0 >= 0 && r1 > r0, "annulus_sector: need 0 <= r0 < r1");
  require(theta1 > theta0 && theta1 - theta0 < 2 * std::numbers::pi,
          "annulus_sector: need theta0 < theta1 < theta0 + 2 pi (use annulus for a full ring)");
  return polar_mesh("annulus_sector(" + std::to_string(n_theta) + "x" + std::to_string(n_r) + ")", r0, r1, theta0,
                    theta1, n_theta, n_r, false);
}

PolygonSoup annulus(double r0, double r1, int n_theta, int n_r) {
  require(n_theta >= 3 && n_r > 0, "annulus: need n_theta >= 3 and n_r > 0");
  require(r0 >= 0 && r1 > r0, "annulus: need 0 <= r0 < r1");
  return polar_mesh("annulus(" + std::to_string(n_theta) + "x" + std::to_string(n_r) + ")", r0, r1, 0.0,
                    2 * std::numbers::pi, n_theta, n_r, true);
}

}  // namespace stagger::meshgen
