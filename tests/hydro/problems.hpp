#pragma once
// Small problems built in code for the hydro tests (no scene files needed).
#include <cmath>

#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/problem.hpp"

namespace stagger::testing {

inline Mesh rectangle_mesh(double x1, double y1, int nx, int ny) {
  return build_mesh(meshgen::rectangle(0, x1, 0, y1, nx, ny));
}

inline Problem gas_problem(Mesh mesh, double gamma, double t_end) {
  Problem p;
  p.name = "test";
  p.mesh = std::move(mesh);
  Material gas;
  gas.name = "gas";
  gas.eos = IdealGas{gamma};
  p.materials.push_back(gas);
  p.t_end = t_end;
  return p;
}

inline void walls(Problem& p, std::initializer_list<const char*> tags) {
  for (const char* t : tags) {
    BoundaryCondition bc;
    bc.tag = t;
    bc.kind = BoundaryKind::wall;
    p.boundaries.push_back(bc);
  }
}

// Sod (docs/verification.md §1) on nx x 5 with the defaults of the prototype's runs (Q = 0;
// docs/algorithm.md §16.1).
inline Problem sod_problem(int nx, double t_end = 0.2) {
  Problem p = gas_problem(rectangle_mesh(1.0, 0.1, nx, 5), 1.4, t_end);
  RegionSetup r;
  r.region = "domain";
  r.material = "gas";
  r.density = [](double x, double) { return x < 0.5 ? 1.0 : 0.125; };
  r.pressure = [](double x, double) { return x < 0.5 ? 1.0 : 0.1; };
  p.regions.push_back(r);
  walls(p, {"left", "right", "bottom", "top"});
  p.options.hourglass_coefficient = 0;
  return p;
}

}  // namespace stagger::testing

namespace stagger::testing {

inline RegionSetup uniform_region(double rho, double p, double vx = 0, double vy = 0) {
  RegionSetup r;
  r.region = "domain";
  r.material = "gas";
  r.density = constant_field(rho);
  r.pressure = constant_field(p);
  r.velocity_x = constant_field(vx);
  r.velocity_y = constant_field(vy);
  return r;
}

// Moves interior points by up to `fraction` of the spacing (deterministic pseudo-random).
inline void perturb_interior(Mesh& m, double dx, double dy, double fraction, unsigned seed = 1) {
  std::vector<char> boundary(m.num_points(), 0);
  for (const auto& tag : m.tags)
    for (Index p : tag.points) boundary[p] = 1;
  unsigned state = seed;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / double(1u << 24) * 2 - 1;
  };
  for (Index p = 0; p < m.num_points(); ++p) {
    const double rx = next(), ry = next();
    if (boundary[p]) continue;
    m.x[p] += fraction * dx * rx;
    m.y[p] += fraction * dy * ry;
  }
}

inline BoundaryCondition boundary(const char* tag, BoundaryKind kind) {
  BoundaryCondition bc;
  bc.tag = tag;
  bc.kind = kind;
  return bc;
}

}  // namespace stagger::testing
