// Boundary conditions: walls and symmetry planes of any orientation, prescribed normal
// velocity, applied pressure and periodic pairs (docs/algorithm.md §10).
#include "hydro/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include "hydro/kernels/compensated.hpp"
#include "hydro/kernels/geometry.hpp"
#include "stagger/error.hpp"

namespace stagger {

namespace {

struct Candidate {
  double nx, ny;
  int velocity_bc;  // -1: wall
};

// Union-find for periodic point groups.
Index find_root(std::vector<Index>& parent, Index i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

void add_candidate(std::vector<Candidate>& list, Candidate c) {
  // Normals closer than 30 degrees are one (curved wall): average them; else keep both.
  for (auto& existing : list) {
    const double dot = existing.nx * c.nx + existing.ny * c.ny;
    if (dot > std::cos(M_PI / 6) && existing.velocity_bc == c.velocity_bc) {
      const double sx = existing.nx + c.nx, sy = existing.ny + c.ny;
      const double norm = std::hypot(sx, sy);
      existing.nx = sx / norm;
      existing.ny = sy / norm;
      return;
    }
  }
  list.push_back(c);
}

// The zone whose side runs a -> b (the boundary edge's zone, in its CCW order).
Index edge_zone(const Mesh& mesh, Index a, Index b) {
  for (Index j = mesh.point_corner_begin[a]; j < mesh.point_corner_begin[a + 1]; ++j) {
    const Index c = mesh.point_corners[j], z = mesh.corner_zone[c];
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    if (mesh.corner_point[c + 1 < end ? c + 1 : begin] == b) return z;
  }
  throw Error("boundary edge " + std::to_string(a) + "-" + std::to_string(b) + " is the side of no zone");
}

// A wall edge a -> b of the initial mesh (CCW zone order: the domain is on its left).
WallEdge wall_edge(const Mesh& mesh, Index a, Index b, int bc) {
  WallEdge w;
  w.a = a, w.b = b, w.bc = bc;
  w.ax = mesh.x[a], w.ay = mesh.y[a];
  const double dx = mesh.x[b] - w.ax, dy = mesh.y[b] - w.ay;
  w.length = std::hypot(dx, dy);
  w.tx = dx / w.length, w.ty = dy / w.length;
  w.nx = w.ty, w.ny = -w.tx;
  // Round-off of a point kept on the wall by its constraint: relative to the coordinates.
  w.tol = 1e-9 * std::max({w.length, std::abs(w.ax), std::abs(w.ay), std::abs(mesh.x[b]), std::abs(mesh.y[b])});
  return w;
}

// The points q for which the side p-q lies on the mesh's boundary (in one zone only).
std::vector<Index> boundary_neighbours(const Mesh& m, Index p) {
  std::map<Index, int> sides;
  for (Index j = m.point_corner_begin[p]; j < m.point_corner_begin[p + 1]; ++j) {
    const Index c = m.point_corners[j], z = m.corner_zone[c], b = m.zone_corner_begin[z];
    const Index n = m.zone_corner_begin[z + 1] - b, k = c - b;
    ++sides[m.corner_point[b + (k + 1) % n]];
    ++sides[m.corner_point[b + (k + n - 1) % n]];
  }
  std::vector<Index> out;
  for (const auto& [q, count] : sides)
    if (count == 1) out.push_back(q);
  return out;
}

// The mesh's own boundary goes on from the open end `end` of a wall along the ray's direction
// (tx, ty), within the 30 degrees of a curved wall: the wall stops there, no ray (a ray would
// call the material of that boundary moving out "through the wall").
bool boundary_continues_the_wall(const Mesh& m, Index end, Index other, double tx, double ty) {
  for (Index q : boundary_neighbours(m, end)) {
    if (q == other) continue;
    const double dx = m.x[q] - m.x[end], dy = m.y[q] - m.y[end];
    if (dx * tx + dy * ty > std::cos(M_PI / 6) * std::hypot(dx, dy)) return true;
  }
  return false;
}

// Rays at the open ends of the walls and the grid over the wall edges (docs/algorithm.md §10).
void setup_wall_check(Simulation::Impl& s) {
  std::vector<WallEdge>& edges = s.wall_edges;
  if (edges.empty()) return;
  // An end point of one wall edge only is an open end: the wall goes on along that edge,
  // unless the mesh's boundary itself goes on along its line there.
  std::map<Index, int> uses;
  for (const WallEdge& w : edges) ++uses[w.a], ++uses[w.b];
  for (const WallEdge& w : edges) {
    for (const bool at_a : {true, false}) {
      if (uses[at_a ? w.a : w.b] != 1) continue;
      if (at_a ? boundary_continues_the_wall(s.mesh(), w.a, w.b, -w.tx, -w.ty)
               : boundary_continues_the_wall(s.mesh(), w.b, w.a, w.tx, w.ty))
        continue;
      WallEdge ray = w;
      ray.b = -1;
      if (at_a) {
        ray.tx = -w.tx, ray.ty = -w.ty;
      } else {
        ray.a = w.b;
        ray.ax = w.ax + w.length * w.tx, ray.ay = w.ay + w.length * w.ty;
      }
      ray.length = std::numeric_limits<double>::infinity();
      s.wall_rays.push_back(ray);
    }
  }
  // Square cells about one wall edge long, at most 1024 a side.
  WallGrid& g = s.wall_grid;
  g.x0 = g.y0 = std::numeric_limits<double>::infinity();
  g.x1 = g.y1 = -g.x0;
  double total = 0, tol = 0;
  for (const WallEdge& w : edges) {
    const double bx = w.ax + w.length * w.tx, by = w.ay + w.length * w.ty;
    g.x0 = std::min({g.x0, w.ax, bx}), g.x1 = std::max({g.x1, w.ax, bx});
    g.y0 = std::min({g.y0, w.ay, by}), g.y1 = std::max({g.y1, w.ay, by});
    total += w.length;
    tol = std::max(tol, w.tol);
  }
  g.x0 -= tol, g.y0 -= tol, g.x1 += tol, g.y1 += tol;
  // A crossing path comes within 2 tol of its edge (or ray); the rest covers round-off.
  for (const WallEdge& w : s.wall_rays) tol = std::max(tol, w.tol);
  s.wall_clearance.slack = 8 * tol;
  const double extent = std::max(g.x1 - g.x0, g.y1 - g.y0);
  const double h = std::max(total / static_cast<double>(edges.size()), extent / 1024);
  g.inv_h = 1 / h;
  g.nx = std::clamp(static_cast<int>(std::ceil((g.x1 - g.x0) * g.inv_h)), 1, 1024);
  g.ny = std::clamp(static_cast<int>(std::ceil((g.y1 - g.y0) * g.inv_h)), 1, 1024);
  const auto cells = [&](const WallEdge& w, auto&& f) {
    const double bx = w.ax + w.length * w.tx, by = w.ay + w.length * w.ty;
    const int i0 = std::clamp(static_cast<int>((std::min(w.ax, bx) - w.tol - g.x0) * g.inv_h), 0, g.nx - 1);
    const int i1 = std::clamp(static_cast<int>((std::max(w.ax, bx) + w.tol - g.x0) * g.inv_h), 0, g.nx - 1);
    const int j0 = std::clamp(static_cast<int>((std::min(w.ay, by) - w.tol - g.y0) * g.inv_h), 0, g.ny - 1);
    const int j1 = std::clamp(static_cast<int>((std::max(w.ay, by) + w.tol - g.y0) * g.inv_h), 0, g.ny - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) f(j * g.nx + i);
  };
  g.cell_begin.assign(static_cast<std::size_t>(g.nx) * g.ny + 1, 0);
  for (const WallEdge& w : edges) cells(w, [&](int c) { ++g.cell_begin[c + 1]; });
  for (std::size_t c = 1; c < g.cell_begin.size(); ++c) g.cell_begin[c] += g.cell_begin[c - 1];
  g.items.resize(g.cell_begin.back());
  std::vector<Index> fill(g.cell_begin.begin(), g.cell_begin.end() - 1);
  for (std::size_t e = 0; e < edges.size(); ++e)
    cells(edges[e], [&](int c) { g.items[fill[c]++] = static_cast<Index>(e); });
}

// Point p's step (x0, y0) -> (x1, y1) leaves the domain through w: it starts inside or on the
// wall's line and ends beyond round-off outside, crossing the line within the edge (or ray).
bool passes_through(const WallEdge& w, Index p, double x0, double y0, double x1, double y1) {
  const double d1 = (x1 - w.ax) * w.nx + (y1 - w.ay) * w.ny;
  if (!(d1 > w.tol) || p == w.a || p == w.b) return false;  // the wall's own points slide along it
  const double d0 = (x0 - w.ax) * w.nx + (y0 - w.ay) * w.ny;
  if (d0 > w.tol) return false;  // already beyond the line (a non-convex domain): not through it now
  const double f = d0 < 0 ? d0 / (d0 - d1) : 0.0;
  const double u = (x0 + f * (x1 - x0) - w.ax) * w.tx + (y0 + f * (y1 - y0) - w.ay) * w.ty;
  return u >= -w.tol && u <= w.length + w.tol;
}

// The wall edge (or ray) point p's step passes through; null if none.
const WallEdge* crossed_wall(const Simulation::Impl& s, Index p, double x0, double y0, double x1, double y1) {
  for (const WallEdge& w : s.wall_rays)
    if (passes_through(w, p, x0, y0, x1, y1)) return &w;
  const WallGrid& g = s.wall_grid;
  const double lo_x = std::min(x0, x1), hi_x = std::max(x0, x1), lo_y = std::min(y0, y1), hi_y = std::max(y0, y1);
  if (!(hi_x >= g.x0 && lo_x <= g.x1 && hi_y >= g.y0 && lo_y <= g.y1)) return nullptr;  // also NaN
  const int i0 = std::max(static_cast<int>((lo_x - g.x0) * g.inv_h), 0);
  const int i1 = std::min(static_cast<int>((hi_x - g.x0) * g.inv_h), g.nx - 1);
  const int j0 = std::max(static_cast<int>((lo_y - g.y0) * g.inv_h), 0);
  const int j1 = std::min(static_cast<int>((hi_y - g.y0) * g.inv_h), g.ny - 1);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      for (Index k = g.cell_begin[j * g.nx + i]; k < g.cell_begin[j * g.nx + i + 1]; ++k)
        if (passes_through(s.wall_edges[g.items[k]], p, x0, y0, x1, y1)) return &s.wall_edges[g.items[k]];
  return nullptr;
}

// Squared distance from (px, py) to w (an edge, or a ray when its length is infinite).
double squared_distance_to_wall(const WallEdge& w, double px, double py) {
  const double dx = px - w.ax, dy = py - w.ay;
  const double u = std::clamp(dx * w.tx + dy * w.ty, 0.0, w.length);
  const double ex = dx - u * w.tx, ey = dy - u * w.ty;
  return ex * ex + ey * ey;
}

// A lower bound of the distance from point p at (px, py) to every wall edge and ray it could
// cross (not its own: passes_through skips them): exact for the rays and for the edges binned
// in the 5 x 5 grid cells about the point; the edges of other cells are at least as far as the
// searched block's sides (or beyond the grid's box). NaN for a non-finite point.
double wall_clearance(const Simulation::Impl& s, Index p, double px, double py) {
  if (!std::isfinite(px) || !std::isfinite(py)) return std::numeric_limits<double>::quiet_NaN();
  double d2 = std::numeric_limits<double>::infinity();
  for (const WallEdge& w : s.wall_rays)
    if (w.a != p) d2 = std::min(d2, squared_distance_to_wall(w, px, py));
  const WallGrid& g = s.wall_grid;
  // Every edge lies in the grid's box.
  const double out_x = std::max({g.x0 - px, px - g.x1, 0.0}), out_y = std::max({g.y0 - py, py - g.y1, 0.0});
  constexpr int kReach = 2;
  const double fi = std::floor((px - g.x0) * g.inv_h), fj = std::floor((py - g.y0) * g.inv_h);
  if (out_x > 0 || out_y > 0 || fi < 0 || fj < 0 || fi >= g.nx || fj >= g.ny)
    return std::sqrt(std::min(d2, out_x * out_x + out_y * out_y));
  const int ci = static_cast<int>(fi), cj = static_cast<int>(fj);
  const int i0 = std::max(ci - kReach, 0), i1 = std::min(ci + kReach, g.nx - 1);
  const int j0 = std::max(cj - kReach, 0), j1 = std::min(cj + kReach, g.ny - 1);
  const double h = 1 / g.inv_h;
  // The unsearched cells lie beyond the block's sides that are not the grid's own.
  double beyond = std::numeric_limits<double>::infinity();
  if (i0 > 0) beyond = std::min(beyond, px - (g.x0 + i0 * h));
  if (i1 < g.nx - 1) beyond = std::min(beyond, g.x0 + (i1 + 1) * h - px);
  if (j0 > 0) beyond = std::min(beyond, py - (g.y0 + j0 * h));
  if (j1 < g.ny - 1) beyond = std::min(beyond, g.y0 + (j1 + 1) * h - py);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      for (Index k = g.cell_begin[j * g.nx + i]; k < g.cell_begin[j * g.nx + i + 1]; ++k) {
        const WallEdge& w = s.wall_edges[g.items[k]];
        if (w.a != p && w.b != p) d2 = std::min(d2, squared_distance_to_wall(w, px, py));
      }
  return std::min(std::sqrt(d2), beyond);
}

// v rounded down to a float (NaN stays NaN: the point is then always tested).
float round_down(double v) {
  float f = static_cast<float>(v);
  if (f > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

Index step_wall_crossing(Simulation::Impl& s, double dt) {
  if (s.wall_edges.empty()) return -1;
  const Index np = s.mesh().num_points();
  WallClearance& c = s.wall_clearance;
  const bool fresh = !c.valid || s.cycle - c.cycle >= WallClearance::kRefreshCycles;
  if (c.budget.size() != static_cast<std::size_t>(np)) c.budget.assign(np, 0.0f);
  float* budget = c.budget.data();
  const double *x = s.x.data(), *y = s.y.data(), *vx = s.vx.data(), *vy = s.vy.data();
  const double *ux = s.vx_new.data(), *uy = s.vy_new.data();
  const double *x_lo = s.x_lo.empty() ? nullptr : s.x_lo.data(), *y_lo = s.y_lo.empty() ? nullptr : s.y_lo.data();
  // x^{n+1} = x^n + dt v_bar, as Z2 and the commit form it.
  const double half_dt = dt * 0.5;
  const Index blocks = (np + WallClearance::kBlock - 1) / WallClearance::kBlock;
  if (c.block_spent.size() != static_cast<std::size_t>(blocks)) c.block_spent.assign(blocks, 1);
  unsigned char* spent = c.block_spent.data();
  if (!fresh) {
    // Every budget less the step's length (|step| <= |dx| + |dy|): a step shorter than the
    // budget cannot reach a wall; a non-positive (or NaN) result marks the point for the test,
    // and its block for the scan below. Branch-free, so that it vectorises.
#pragma omp parallel for schedule(static) if (np > 20000)
    for (Index k = 0; k < blocks; ++k) {
      const Index p1 = std::min(np, (k + 1) * WallClearance::kBlock);
      int out = 0;
      for (Index p = k * WallClearance::kBlock; p < p1; ++p) {
        const double x1 = advanced(x[p], half_dt * (vx[p] + ux[p]), x_lo, p);
        const double y1 = advanced(y[p], half_dt * (vy[p] + uy[p]), y_lo, p);
        const double left = budget[p] - (std::abs(x1 - x[p]) + std::abs(y1 - y[p]));
        // Rounded down: a float rounds by at most 2^-24 relative.
        const float b = static_cast<float>(left - std::abs(left) * 0x1p-22);
        budget[p] = b;
        out |= !(b > 0);
      }
      spent[k] = static_cast<unsigned char>(out);
    }
  }
  const double slack = c.slack;
  Index first = np;
#pragma omp parallel for schedule(static) reduction(min : first) if (np > 20000)
  for (Index k = 0; k < blocks; ++k) {
    if (!fresh && !spent[k]) continue;  // every budget of the block left: nothing to test
    const Index p1 = std::min(np, (k + 1) * WallClearance::kBlock);
    for (Index p = k * WallClearance::kBlock; p < p1; ++p) {
      if (!fresh && budget[p] > 0) continue;
      if (!s.ghost_point.empty() && s.ghost_point[p]) continue;  // a distributed run: this rank's points
      const double x1 = advanced(x[p], half_dt * (vx[p] + ux[p]), x_lo, p);
      const double y1 = advanced(y[p], half_dt * (vy[p] + uy[p]), y_lo, p);
      if (crossed_wall(s, p, x[p], y[p], x1, y1)) first = std::min(first, p);
      budget[p] = round_down(wall_clearance(s, p, x1, y1) - slack - 1e-12 * (std::abs(x1) + std::abs(y1)));
    }
  }
  // A step that crosses a wall is rejected (recompute_state invalidates the budgets).
  c.valid = true;
  if (fresh) c.cycle = s.cycle;
  return first < np ? first : -1;
}

Index find_wall_crossing(const Simulation::Impl& s, double dt) {
  if (s.wall_edges.empty()) return -1;
  const Index np = s.mesh().num_points();
  const double *x = s.x.data(), *y = s.y.data(), *vx = s.vx.data(), *vy = s.vy.data();
  const double *ux = s.vx_new.data(), *uy = s.vy_new.data();
  const double *x_lo = s.x_lo.empty() ? nullptr : s.x_lo.data(), *y_lo = s.y_lo.empty() ? nullptr : s.y_lo.data();
  Index first = np;
#pragma omp parallel for schedule(static) reduction(min : first) if (np > 20000)
  for (Index p = 0; p < np; ++p) {
    if (!s.ghost_point.empty() && s.ghost_point[p]) continue;  // a distributed run: this rank's points
    // x^{n+1} = x^n + dt v_bar, as Z2 and the commit form it.
    const double x1 = advanced(x[p], dt * 0.5 * (vx[p] + ux[p]), x_lo, p);
    const double y1 = advanced(y[p], dt * 0.5 * (vy[p] + uy[p]), y_lo, p);
    if (crossed_wall(s, p, x[p], y[p], x1, y1)) first = std::min(first, p);
  }
  return first < np ? first : -1;
}

std::string describe_wall_crossing(const Simulation::Impl& s, Index p, double dt) {
  const double *x_lo = s.x_lo.empty() ? nullptr : s.x_lo.data(), *y_lo = s.y_lo.empty() ? nullptr : s.y_lo.data();
  const double x1 = advanced(s.x[p], dt * 0.5 * (s.vx[p] + s.vx_new[p]), x_lo, p);
  const double y1 = advanced(s.y[p], dt * 0.5 * (s.vy[p] + s.vy_new[p]), y_lo, p);
  const WallEdge* w = crossed_wall(s, p, s.x[p], s.y[p], x1, y1);
  if (!w) return {};
  const Mesh& mesh = s.mesh();
  // A distributed run numbers points globally; a wall point off this rank is -2 - its number.
  const auto number = [&](Index q) { return q < 0 ? -2 - q : s.global_point.empty() ? q : s.global_point[q]; };
  const auto at = [&](Index q, double x, double y) {
    std::ostringstream text;
    text << "(" << (q >= 0 ? mesh.x[q] : x) << ", " << (q >= 0 ? mesh.y[q] : y) << ")";
    return text.str();
  };
  std::ostringstream msg;
  msg << "point " << number(p) << " moved from (" << s.x[p] << ", " << s.y[p] << ") to (" << x1 << ", " << y1
      << ") through the wall '" << s.problem.boundaries[w->bc].tag << "' (";
  if (w->b != -1)
    msg << "its edge from point " << number(w->a) << " " << at(w->a, w->ax, w->ay) << " to point " << number(w->b)
        << " " << at(w->b, w->ax + w->length * w->tx, w->ay + w->length * w->ty);
  else
    msg << "its continuation beyond its open end, point " << number(w->a) << " at (" << w->ax << ", " << w->ay << ")";
  msg << ", outward normal (" << w->nx << ", " << w->ny << "))";
  return msg.str();
}

void setup_boundaries(Simulation::Impl& s) {
  const Mesh& mesh = s.mesh();
  const auto& bcs = s.problem.boundaries;
  std::map<Index, std::vector<Candidate>> candidates;
  std::vector<Index> parent(mesh.num_points());
  std::iota(parent.begin(), parent.end(), 0);
  bool any_periodic = false;
  std::vector<Index> fixed_points;

  for (std::size_t b = 0; b < bcs.size(); ++b) {
    const BoundaryCondition& bc = bcs[b];
    const BoundaryTag& tag = mesh.tags[mesh.tag_index(bc.tag)];
    switch (bc.kind) {
      case BoundaryKind::free:
        break;
      case BoundaryKind::fixed:
        fixed_points.insert(fixed_points.end(), tag.points.begin(), tag.points.end());
        break;
      case BoundaryKind::pressure:
        for (const auto& edge : tag.edges) s.pressure_edges.push_back({edge[0], edge[1], static_cast<int>(b)});
        break;
      case BoundaryKind::transmitting:
        for (const auto& edge : tag.edges)
          s.pressure_edges.push_back({edge[0], edge[1], static_cast<int>(b), edge_zone(mesh, edge[0], edge[1])});
        break;
      case BoundaryKind::wall:
      case BoundaryKind::velocity: {
        int velocity_index = -1;
        if (bc.kind == BoundaryKind::velocity) {
          velocity_index = static_cast<int>(s.velocity_bcs.size());
          s.velocity_bcs.push_back(static_cast<int>(b));
        }
        for (const auto& edge : tag.edges) {
          const double dx = mesh.x[edge[1]] - mesh.x[edge[0]], dy = mesh.y[edge[1]] - mesh.y[edge[0]];
          const double len = std::hypot(dx, dy);
          for (Index p : {edge[0], edge[1]}) add_candidate(candidates[p], {dy / len, -dx / len, velocity_index});
          if (bc.kind == BoundaryKind::wall)
            s.wall_edges.push_back(wall_edge(mesh, edge[0], edge[1], static_cast<int>(b)));
        }
        break;
      }
      case BoundaryKind::periodic: {
        any_periodic = true;
        const BoundaryTag& other = mesh.tags[mesh.tag_index(bc.partner)];
        if (tag.points.size() != other.points.size()) {
          std::ostringstream msg;
          msg << "periodic boundary '" << bc.tag << "' has " << tag.points.size() << " points but its partner '"
              << bc.partner << "' has " << other.points.size() << ": the two sides must match point for point";
          throw Error(msg.str());
        }
        // Translation between the two sides: difference of their centroids.
        double ax = 0, ay = 0, bx = 0, by = 0, extent = 0;
        for (Index p : tag.points) ax += mesh.x[p], ay += mesh.y[p];
        for (Index p : other.points) bx += mesh.x[p], by += mesh.y[p];
        const double n = static_cast<double>(tag.points.size());
        const double tx = (bx - ax) / n, ty = (by - ay) / n;
        for (Index p : tag.points) extent = std::max({extent, std::abs(mesh.x[p]), std::abs(mesh.y[p])});
        const double tol = 1e-9 * std::max(extent, std::hypot(tx, ty));
        for (Index p : tag.points) {
          Index match = -1;
          for (Index q : other.points)
            if (std::abs(mesh.x[q] - mesh.x[p] - tx) <= tol && std::abs(mesh.y[q] - mesh.y[p] - ty) <= tol) match = q;
          if (match < 0) {
            std::ostringstream msg;
            msg << "periodic boundary '" << bc.tag << "': point " << p << " (" << mesh.x[p] << ", " << mesh.y[p]
                << ") has no partner on '" << bc.partner << "' at translation (" << tx << ", " << ty << ")";
            throw Error(msg.str());
          }
          parent[find_root(parent, p)] = find_root(parent, match);
        }
        break;
      }
    }
  }

  // rz: the axis x = 0 keeps v_r = 0 (a symmetry plane; docs/algorithm.md §19).
  if (s.rz)
    for (Index p = 0; p < mesh.num_points(); ++p)
      if (mesh.x[p] == 0) add_candidate(candidates[p], {-1.0, 0.0, -1});
  // A fixed (clamped) point: v = 0, whatever else holds there (two normals, both g = 0).
  for (Index p : fixed_points) candidates[p] = {{1.0, 0.0, -1}, {0.0, 1.0, -1}};

  for (auto& [point, list] : candidates) {
    PointConstraint c;
    c.point = point;
    for (const auto& cand : list) {
      if (c.count == 2) break;
      if (c.count == 1) {
        const double cross = c.nx[0] * cand.ny - c.ny[0] * cand.nx;
        if (std::abs(cross) < 1e-8) continue;  // parallel normals count once
      }
      c.nx[c.count] = cand.nx;
      c.ny[c.count] = cand.ny;
      c.velocity_bc[c.count] = cand.velocity_bc;
      ++c.count;
    }
    s.constraints.push_back(c);
  }

  setup_wall_check(s);

  if (any_periodic) {
    std::map<Index, std::vector<Index>> groups;
    for (Index p = 0; p < mesh.num_points(); ++p) {
      const Index r = find_root(parent, p);
      if (r != p || groups.count(r)) groups[r].push_back(p);
    }
    for (auto& [root, members] : groups) {
      if (std::find(members.begin(), members.end(), root) == members.end()) members.push_back(root);
      std::sort(members.begin(), members.end());
      if (members.size() > 1) s.periodic_groups.push_back(members);
    }
  }
}

void apply_constraints(const Simulation::Impl& s, std::span<double> vx, std::span<double> vy, double t) {
  for (const auto& group : s.periodic_groups) {
    double mass = 0, px = 0, py = 0;
    for (Index p : group) {
      mass += s.point_mass[p];
      px += s.point_mass[p] * vx[p];
      py += s.point_mass[p] * vy[p];
    }
    if (!(mass > 0)) {
      // rz: the copies of an axis point (an axially periodic cylinder) carry no mass (r = 0);
      // each moved by its own corners' acceleration, they share the mean (was 0 / 0 = NaN).
      mass = static_cast<double>(group.size()), px = py = 0;
      for (Index p : group) px += vx[p], py += vy[p];
    }
    for (Index p : group) {
      vx[p] = px / mass;
      vy[p] = py / mass;
    }
  }
  if (s.constraints.empty()) return;
  // Prescribed velocities u(t) of each velocity boundary, evaluated once per call.
  double ux[16] = {}, uy[16] = {};
  std::vector<double> ux_big, uy_big;
  double* uxp = ux;
  double* uyp = uy;
  if (s.velocity_bcs.size() > 16) {
    ux_big.resize(s.velocity_bcs.size());
    uy_big.resize(s.velocity_bcs.size());
    uxp = ux_big.data();
    uyp = uy_big.data();
  }
  for (std::size_t i = 0; i < s.velocity_bcs.size(); ++i) {
    const auto& bc = s.problem.boundaries[s.velocity_bcs[i]];
    uxp[i] = bc.velocity_x(t);
    uyp[i] = bc.velocity_y(t);
    if (!std::isfinite(uxp[i]) || !std::isfinite(uyp[i])) {
      std::ostringstream msg;
      msg << "boundary '" << bc.tag << "': the prescribed velocity is not finite at t = " << t << " (" << uxp[i] << ", "
          << uyp[i] << "): fix its expression";
      throw Error(msg.str());
    }
  }
  for (const auto& c : s.constraints) {
    double g[2];
    for (int k = 0; k < c.count; ++k) {
      const int v = c.velocity_bc[k];
      g[k] = v < 0 ? 0.0 : uxp[v] * c.nx[k] + uyp[v] * c.ny[k];
    }
    const Index p = c.point;
    if (c.count == 1) {
      const double excess = vx[p] * c.nx[0] + vy[p] * c.ny[0] - g[0];
      vx[p] -= excess * c.nx[0];
      vy[p] -= excess * c.ny[0];
    } else {
      // [n1; n2] v = [g1; g2]
      const double det = c.nx[0] * c.ny[1] - c.ny[0] * c.nx[1];
      vx[p] = (g[0] * c.ny[1] - c.ny[0] * g[1]) / det;
      vy[p] = (c.nx[0] * g[1] - g[0] * c.nx[1]) / det;
    }
  }
}

void constrain_low_parts(const Simulation::Impl& s, std::span<double> lo_x, std::span<double> lo_y) {
  for (const auto& group : s.periodic_groups)
    for (Index p : group) lo_x[p] = lo_y[p] = 0;  // the group's mean velocity is a new value
  for (const auto& c : s.constraints) {
    const Index p = c.point;
    if (c.count == 1) {
      const double normal = lo_x[p] * c.nx[0] + lo_y[p] * c.ny[0];
      lo_x[p] -= normal * c.nx[0];
      lo_y[p] -= normal * c.ny[0];
    } else {
      lo_x[p] = lo_y[p] = 0;
    }
  }
}

namespace {
template <class Geometry>
void pressure_forces_in(const Simulation::Impl& s, std::span<const double> x, std::span<const double> y, double t,
                        std::span<double> fx, std::span<double> fy) {
  std::fill(fx.begin(), fx.end(), 0.0);
  std::fill(fy.begin(), fy.end(), 0.0);
  for (const auto& edge : s.pressure_edges) {
    const BoundaryCondition& bc = s.problem.boundaries[edge.bc];
    double p = edge.zone >= 0 && bc.far_field_from_initial_state ? edge.ambient : bc.pressure(t);
    if (edge.zone >= 0) {
      // Transmitting: p0 + rho c u.n, u.n the edge's outward normal velocity at t^n (the
      // impedance of the zone beside it: an outgoing plane wave leaves without reflection).
      const double nx = y[edge.b] - y[edge.a], ny = x[edge.a] - x[edge.b], len = std::hypot(nx, ny);
      const double un = 0.5 * ((s.vx[edge.a] + s.vx[edge.b]) * nx + (s.vy[edge.a] + s.vy[edge.b]) * ny) / len;
      p += s.rho[edge.zone] * s.c[edge.zone] * un;
    }
    if (!std::isfinite(p)) {
      std::ostringstream msg;
      msg << "boundary '" << bc.tag << "': the applied pressure is not finite at t = " << t << " (" << p
          << "): fix its expression";
      throw Error(msg.str());
    }
    const double dx = x[edge.b] - x[edge.a], dy = y[edge.b] - y[edge.a];
    // -p times the outward normal times the length, half to each end point.
    const double gx = -0.5 * p * dy, gy = 0.5 * p * dx;
    fx[edge.a] += gx;
    fy[edge.a] += gy;
    fx[edge.b] += gx;
    fy[edge.b] += gy;
  }
  Geometry::scale_surface_forces(x, fx, fy);
}
}  // namespace

void pressure_forces(const Simulation::Impl& s, std::span<const double> x, std::span<const double> y, double t,
                     std::span<double> fx, std::span<double> fy) {
  if (s.rz) {
    pressure_forces_in<RzGeometry>(s, x, y, t, fx, fy);
  } else {
    pressure_forces_in<PlanarGeometry>(s, x, y, t, fx, fy);
  }
}

std::vector<Index> constrained_points(const Simulation::Impl& s) {
  std::vector<Index> out;
  for (const auto& c : s.constraints) out.push_back(c.point);
  for (const auto& g : s.periodic_groups) out.insert(out.end(), g.begin(), g.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace stagger
