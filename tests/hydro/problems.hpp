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

// Sod (VERIFICATION problem 1) on nx x 5, defaults of NUMERICS (Q = 0 as the prototype).
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
