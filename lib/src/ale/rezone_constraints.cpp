// The rezone's constraints (rezone.hpp; docs/ale.md, "Rezone"): what each point may do, the
// Winslow stencils with their least-squares weights, and the colouring that makes a
// Gauss-Seidel sweep parallel.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "ale/norm2.hpp"
#include "ale/rezone.hpp"
#include "hydro/kernels/zone_validity.hpp"
#include "stagger/error.hpp"

namespace stagger {
namespace {

// The Winslow stencil of one point (Knupp 1999): its zones in counter-clockwise order, each
// given an equal sector of the logical plane (2 pi / k around an interior point, pi / k at a
// boundary point); a zone's two edge neighbours sit on the sector's sides at unit distance,
// its other vertices where a regular polygon with that corner puts them (u + v for a quad).
// Returns false if the zones do not form one fan (then the point gets no stencil).
bool winslow_fan(const Mesh& mesh, Index p, std::vector<Index>& points, std::vector<double>& xi,
                 std::vector<double>& eta, std::vector<int>& key) {
  struct Fan {
    Index corner, u, v;
    int m;
  };
  Fan fan[64];
  const Index cb = mesh.point_corner_begin[p], ce = mesh.point_corner_begin[p + 1];
  const int k = static_cast<int>(ce - cb);
  if (k == 0 || k > 64) return false;
  for (int i = 0; i < k; ++i) {
    const Index c = mesh.point_corners[cb + i], z = mesh.corner_zone[c];
    const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
    fan[i] = {c, mesh.corner_point[c + 1 == e ? b : c + 1], mesh.corner_point[c == b ? e - 1 : c - 1],
              static_cast<int>(e - b)};
    if (e - b > kMaxZoneVertices) return false;
  }
  // The first zone of an open fan is the one whose u no other zone has as v.
  int start = 0;
  bool closed = true;
  for (int i = 0; i < k && closed; ++i) {
    bool found = false;
    for (int j = 0; j < k; ++j) found = found || fan[j].v == fan[i].u;
    if (!found) {
      start = i;
      closed = false;
    }
  }
  int order[64];
  order[0] = start;
  for (int t = 1; t < k; ++t) {
    order[t] = -1;
    for (int j = 0; j < k; ++j)
      if (fan[j].u == fan[order[t - 1]].v) order[t] = j;
    if (order[t] < 0) return false;
  }
  if (closed && fan[order[k - 1]].v != fan[order[0]].u) return false;
  const double phi = (closed ? 2 : 1) * std::numbers::pi / k;
  points.clear();
  xi.clear();
  eta.clear();
  key.assign(1, closed ? 1 : 0);
  // Logical offsets that are integers up to rounding (the quad fans: cos(pi/2)) are made
  // exact, so that the weights reproduce a uniform mesh to the last bit where they can.
  const auto snap = [](double v) { return std::abs(v - std::round(v)) < 1e-12 ? std::round(v) : v; };
  const auto add = [&](Index q, double a, double b) {
    a = snap(a);
    b = snap(b);
    points.push_back(q);
    xi.push_back(a);
    eta.push_back(b);
  };
  for (int t = 0; t < k; ++t) {
    const Fan& f = fan[order[t]];
    key.push_back(f.m);
    const double ux = std::cos(t * phi), uy = std::sin(t * phi);
    const double vx = std::cos((t + 1) * phi), vy = std::sin((t + 1) * phi);
    add(f.u, ux, uy);
    const Index z = mesh.corner_zone[f.corner], b = mesh.zone_corner_begin[z];
    if (f.m == 4) {
      add(mesh.corner_point[b + (f.corner - b + 2) % 4], ux + vx, uy + vy);
    } else if (f.m > 4) {
      // Regular m-gon with vertex 0 at the origin, vertex 1 at (1, 0), counter-clockwise;
      // the linear map taking its corner edges to (u, v) places the other vertices.
      const double ext = 2 * std::numbers::pi / f.m, alpha = std::numbers::pi - ext;
      const double ca = std::cos(alpha), sa = std::sin(alpha);
      double rx = 1, ry = 0;
      for (int j = 2; j <= f.m - 2; ++j) {
        rx += std::cos((j - 1) * ext);
        ry += std::sin((j - 1) * ext);
        // (rx, ry) = a e1 + c (ca, sa)  ->  a u + c v.
        const double c = ry / sa, a = rx - c * ca;
        add(mesh.corner_point[b + (f.corner - b + j) % f.m], a * ux + c * vx, a * uy + c * vy);
      }
    }
    if (!closed && t == k - 1) add(f.v, vx, vy);
  }
  return true;
}

// Least-squares derivative weights of a logical layout: x_i - x_0 ~ a x_xi + b x_eta +
// a^2/2 x_xixi + a b x_xieta + b^2/2 x_etaeta. A small penalty on the second derivatives
// makes under-determined fans (few neighbours) solvable and leaves linear maps exact (their
// second derivatives are zero, so the penalty costs nothing there).
// Returns false (no weights appended) if the first derivatives are not determined: a fan whose
// logical neighbours lie on one line (a point in the middle of a straight side of its only zone).
bool winslow_weights(const std::vector<double>& xi, const std::vector<double>& eta, std::vector<double>& out) {
  const int n = static_cast<int>(xi.size());
  Eigen::MatrixXd a(n, 5);
  for (int i = 0; i < n; ++i) a.row(i) << xi[i], eta[i], 0.5 * xi[i] * xi[i], xi[i] * eta[i], 0.5 * eta[i] * eta[i];
  Eigen::Matrix<double, 5, 5> m = a.transpose() * a;
  for (int k = 2; k < 5; ++k) m(k, k) += 1e-4;
  const Eigen::LDLT<Eigen::Matrix<double, 5, 5>> ldlt(m);
  const auto d = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(d.minCoeff() > 1e-10 * d.maxCoeff())) return false;
  const Eigen::MatrixXd pinv = ldlt.solve(a.transpose());  // 5 x n
  if (!pinv.allFinite()) return false;
  // Stored per neighbour as (xixi, xieta, etaeta, xi, eta), then the row sums.
  const int row[5] = {2, 3, 4, 0, 1};
  double sum[5] = {0, 0, 0, 0, 0};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 5; ++k) {
      out.push_back(pinv(row[k], i));
      sum[k] += pinv(row[k], i);
    }
  for (int k = 0; k < 5; ++k) out.push_back(sum[k]);
  return true;
}

// The reference layout of point p's fan (WinslowLayout::reference): the initial offsets in
// units of the mean initial edge (the edge neighbours are the regular layout's points at unit
// distance) into xi, eta, and as the weights' key into `offsets` (after key[0], whether the
// fan is closed). Offsets that are integers to rounding are made exact, so that the points of
// a uniform mesh share one weight set. False if the mean edge is not positive (no stencil).
bool reference_offsets(const Mesh& mesh, Index p, const std::vector<Index>& fan_points, const std::vector<int>& key,
                       std::vector<double>& xi, std::vector<double>& eta, std::vector<double>& offsets) {
  double length = 0;
  int edges = 0;
  for (std::size_t i = 0; i < fan_points.size(); ++i)
    if (std::abs(xi[i] * xi[i] + eta[i] * eta[i] - 1) < 1e-9) {
      length += norm2(mesh.x[fan_points[i]] - mesh.x[p], mesh.y[fan_points[i]] - mesh.y[p]);
      ++edges;
    }
  length /= std::max(edges, 1);
  const auto snap = [](double v) { return std::abs(v - std::round(v)) < 1e-9 ? std::round(v) : v; };
  offsets.assign(1, key[0]);
  for (std::size_t i = 0; i < fan_points.size(); ++i) {
    xi[i] = snap((mesh.x[fan_points[i]] - mesh.x[p]) / length);
    eta[i] = snap((mesh.y[fan_points[i]] - mesh.y[p]) / length);
    offsets.push_back(xi[i]);
    offsets.push_back(eta[i]);
  }
  return length > 0;
}

// Boundary edges: sides that no other zone has (in the opposite direction). Returns each
// point's count of them and sets the first two boundary neighbours of each point.
std::vector<int> boundary_edge_counts(const Mesh& mesh, std::vector<std::array<Index, 2>>& neighbours) {
  const Index np = mesh.num_points(), nz = mesh.num_zones();
  std::vector<std::uint64_t> keys;
  keys.reserve(mesh.num_corners());
  for (Index z = 0; z < nz; ++z) {
    const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
    for (Index c = b; c < e; ++c) {
      const Index p = mesh.corner_point[c], q = mesh.corner_point[c + 1 == e ? b : c + 1];
      keys.push_back((std::uint64_t(std::min(p, q)) << 32) | std::uint64_t(std::max(p, q)));
    }
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> boundary_edges(np, 0);
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    if (j - i == 1) {
      const Index p = Index(keys[i] >> 32), q = Index(keys[i] & 0xffffffffu);
      for (const auto& [a, o] : {std::pair{p, q}, std::pair{q, p}}) {
        const int k = boundary_edges[a]++;
        if (k < 2) neighbours[a][k] = o;
      }
    }
    i = j;
  }
  return boundary_edges;
}

// Tags: the number of tags on each point (saturating at 255); the points of periodic tags are
// marked fixed, so that partner points stay matched, and those of clamped (type "fixed") tags,
// which the material holds in place.
std::vector<std::uint8_t> tag_counts(const Mesh& mesh, std::span<const BoundaryCondition> boundaries,
                                     std::vector<std::uint8_t>& fixed) {
  std::vector<std::uint8_t> tag_count(mesh.num_points(), 0);
  for (const BoundaryTag& tag : mesh.tags) {
    bool held = false;  // periodic or clamped
    for (const BoundaryCondition& bc : boundaries)
      if (bc.tag == tag.name && (bc.kind == BoundaryKind::periodic || bc.kind == BoundaryKind::fixed)) held = true;
    for (const BoundaryCondition& bc : boundaries)
      if (bc.partner == tag.name && bc.kind == BoundaryKind::periodic) held = true;
    for (const Index p : tag.points) {
      if (tag_count[p] < 255) ++tag_count[p];
      if (held) fixed[p] = 1;
    }
  }
  return tag_count;
}

// Each point's kind: fixed (already marked, or on a material interface, in no zone, on two or
// more tags, on a tagged interior curve, or a pinch point of the boundary), slide (two
// boundary edges) or interior; with the counts.
template <class Material>
void classify_points(const Mesh& mesh, const Material& material, const std::vector<int>& boundary_edges,
                     const std::vector<std::uint8_t>& tag_count, std::vector<std::uint8_t>& fixed,
                     RezoneConstraints& rc) {
  const Index np = mesh.num_points();
  for (Index p = 0; p < np; ++p) {
    // Material interface: the point's zones do not all share one material.
    const Index cb = mesh.point_corner_begin[p], ce = mesh.point_corner_begin[p + 1];
    for (Index i = cb; i < ce; ++i)
      if (material(mesh.corner_zone[mesh.point_corners[i]]) != material(mesh.corner_zone[mesh.point_corners[cb]]))
        fixed[p] = 1;
    if (ce == cb) fixed[p] = 1;
    if (tag_count[p] >= 2) fixed[p] = 1;
    if (boundary_edges[p] == 0) {
      // A tag on an interior curve: keep its points where they are.
      if (tag_count[p] > 0) fixed[p] = 1;
    } else if (boundary_edges[p] != 2) {
      fixed[p] = 1;  // a pinch point of the boundary
    }
    if (fixed[p]) {
      rc.kind[p] = RezonePointKind::fixed;
      rc.boundary_neighbours[p] = {-1, -1};
      ++rc.num_fixed;
    } else if (boundary_edges[p] == 2) {
      rc.kind[p] = RezonePointKind::slide;
      ++rc.num_slide;
    } else {
      rc.boundary_neighbours[p] = {-1, -1};
      ++rc.num_interior;
    }
  }
}

// Winslow stencils of the points that may move; fans with the same logical layout (the same
// zone sizes, or the same reference offsets) share weights.
void winslow_stencils(const Mesh& mesh, WinslowLayout layout, RezoneConstraints& rc) {
  const Index np = mesh.num_points();
  rc.stencil_id.assign(np, -1);
  rc.stencil_begin.assign(1, 0);
  std::map<std::vector<int>, Index> known;
  std::map<std::vector<double>, Index> known_reference;
  std::vector<Index> fan_points;
  std::vector<double> xi, eta, offsets;
  std::vector<int> key;
  // known: layout -> weight set, or -1 for a fan without usable weights.
  const auto weights_of = [&](auto& table, const auto& k) {
    auto it = table.find(k);
    if (it == table.end()) {
      const bool ok = winslow_weights(xi, eta, rc.stencil_weights);
      const Index id = ok ? static_cast<Index>(rc.weights_begin.size()) - 1 : -1;
      if (ok) rc.weights_begin.push_back(static_cast<Index>(rc.stencil_weights.size()));
      it = table.emplace(k, id).first;
    }
    return it->second;
  };
  for (Index p = 0; p < np; ++p) {
    if (rc.kind[p] != RezonePointKind::fixed && winslow_fan(mesh, p, fan_points, xi, eta, key)) {
      if (layout == WinslowLayout::regular) {
        rc.stencil_id[p] = weights_of(known, key);  // fans with the same zone sizes share weights
      } else {
        rc.stencil_id[p] =
            reference_offsets(mesh, p, fan_points, key, xi, eta, offsets) ? weights_of(known_reference, offsets) : -1;
      }
      if (rc.stencil_id[p] >= 0)
        rc.stencil_points.insert(rc.stencil_points.end(), fan_points.begin(), fan_points.end());
    }
    rc.stencil_begin.push_back(static_cast<Index>(rc.stencil_points.size()));
  }
}

// Greedy colouring of the points that may move: no two points of one colour share a zone.
void colour_points(const Mesh& mesh, RezoneConstraints& rc) {
  const Index np = mesh.num_points();
  std::vector<int> colour(np, -1);
  std::vector<Index> seen;  // seen[c] == p: colour c is taken by a zone neighbour of p
  int colours = 0;
  for (Index p = 0; p < np; ++p) {
    if (rc.kind[p] == RezonePointKind::fixed) continue;
    for (Index i = mesh.point_corner_begin[p]; i < mesh.point_corner_begin[p + 1]; ++i) {
      const Index z = mesh.corner_zone[mesh.point_corners[i]];
      for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) {
        const int k = colour[mesh.corner_point[c]];
        if (k >= 0) seen[k] = p;
      }
    }
    int k = 0;
    while (k < colours && seen[k] == p) ++k;
    if (k == colours) {
      ++colours;
      seen.push_back(-1);
    }
    colour[p] = k;
  }
  rc.colour_begin.assign(colours + 1, 0);
  for (Index p = 0; p < np; ++p)
    if (colour[p] >= 0) ++rc.colour_begin[colour[p] + 1];
  for (int k = 0; k < colours; ++k) rc.colour_begin[k + 1] += rc.colour_begin[k];
  rc.colour_points.resize(rc.colour_begin[colours]);
  std::vector<Index> fill(rc.colour_begin.begin(), rc.colour_begin.end() - 1);
  for (Index p = 0; p < np; ++p)
    if (colour[p] >= 0) rc.colour_points[fill[colour[p]]++] = p;
}

}  // namespace

// The stages: boundary edges, tags, each point's kind, the Winslow stencils, the colours.
RezoneConstraints make_rezone_constraints(const Mesh& mesh, std::span<const BoundaryCondition> boundaries,
                                          std::span<const Index> zone_material, WinslowLayout layout) {
  const Index np = mesh.num_points(), nz = mesh.num_zones();
  if (!zone_material.empty() && static_cast<Index>(zone_material.size()) != nz)
    throw Error("rezone constraints: zone_material has " + std::to_string(zone_material.size()) +
                " entries, the mesh " + mesh.source + " has " + std::to_string(nz) + " zones");
  const auto material = [&](Index z) { return zone_material.empty() ? mesh.zone_region[z] : zone_material[z]; };

  RezoneConstraints rc;
  rc.kind.assign(np, RezonePointKind::interior);
  rc.boundary_neighbours.assign(np, {-1, -1});
  std::vector<std::uint8_t> fixed(np, 0);
  // The points of zones with more vertices than the validity checks take stay.
  for (Index z = 0; z < nz; ++z)
    if (mesh.zone_corner_begin[z + 1] - mesh.zone_corner_begin[z] > kMaxZoneVertices)
      for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) fixed[mesh.corner_point[c]] = 1;
  const std::vector<int> boundary_edges = boundary_edge_counts(mesh, rc.boundary_neighbours);
  const std::vector<std::uint8_t> tag_count = tag_counts(mesh, boundaries, fixed);
  classify_points(mesh, material, boundary_edges, tag_count, fixed, rc);
  winslow_stencils(mesh, layout, rc);
  colour_points(mesh, rc);
  return rc;
}

}  // namespace stagger
