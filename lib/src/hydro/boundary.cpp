// Boundary conditions: walls and symmetry planes of any orientation, prescribed normal
// velocity, applied pressure and periodic pairs (docs/algorithm.md §10).
#include "hydro/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

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

}  // namespace

void setup_boundaries(Simulation::Impl& s) {
  const Mesh& mesh = s.mesh();
  const auto& bcs = s.problem.boundaries;
  std::map<Index, std::vector<Candidate>> candidates;
  std::vector<Index> parent(mesh.num_points());
  std::iota(parent.begin(), parent.end(), 0);
  bool any_periodic = false;

  for (std::size_t b = 0; b < bcs.size(); ++b) {
    const BoundaryCondition& bc = bcs[b];
    const BoundaryTag& tag = mesh.tags[mesh.tag_index(bc.tag)];
    switch (bc.kind) {
      case BoundaryKind::free:
        break;
      case BoundaryKind::pressure:
        for (const auto& edge : tag.edges) s.pressure_edges.push_back({edge[0], edge[1], static_cast<int>(b)});
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

void add_pressure_forces(const Simulation::Impl& s, std::span<const double> x, std::span<const double> y, double t,
                         std::span<double> fx, std::span<double> fy) {
  for (const auto& edge : s.pressure_edges) {
    const double p = s.problem.boundaries[edge.bc].pressure(t);
    if (!std::isfinite(p)) {
      std::ostringstream msg;
      msg << "boundary '" << s.problem.boundaries[edge.bc].tag << "': the applied pressure is not finite at t = " << t
          << " (" << p << "): fix its expression";
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
