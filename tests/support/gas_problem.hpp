#pragma once
// Gas problems built in code for the tests (no scene files needed): a rectangle mesh, the
// ideal gas "gas" filling the region "domain", boundary conditions by tag, Sod's tube and
// Sedov's quarter-plane blast.
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>

#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/problem.hpp"

namespace stagger::testing {

/// The four sides of a rectangle mesh, as meshgen::rectangle tags them.
inline constexpr std::initializer_list<const char*> kBoxSides = {"left", "right", "bottom", "top"};

/// The rectangle [0,x1]x[0,y1] in nx x ny zones.
inline Mesh rectangle_mesh(double x1, double y1, int nx, int ny) {
  return build_mesh(meshgen::rectangle(0, x1, 0, y1, nx, ny));
}

/// The rectangle [x0,x1]x[y0,y1] in nx x ny zones, built with `options`.
inline Mesh rectangle_mesh(double x0, double x1, double y0, double y1, int nx, int ny,
                           const MeshBuildOptions& options) {
  return build_mesh(meshgen::rectangle(x0, x1, y0, y1, nx, ny), options);
}

/// Build options without the topology check (the meshes of rectangles need none).
inline MeshBuildOptions unchecked() {
  MeshBuildOptions options;
  options.check_topology = false;
  return options;
}

/// One material "gas", an ideal gas; no regions, no boundaries yet.
inline Problem gas_problem(Mesh mesh, double gamma, double t_end, std::string name = "test") {
  Problem p;
  p.name = std::move(name);
  p.mesh = std::move(mesh);
  Material gas;
  gas.name = "gas";
  gas.eos = IdealGas{gamma};
  p.materials.push_back(gas);
  p.t_end = t_end;
  return p;
}

/// The gas in the region "domain" with the given density; the caller sets the pressure or
/// the specific internal energy (and the velocity if not at rest).
inline RegionSetup gas_region(SpaceFunction density) {
  RegionSetup r;
  r.region = "domain";
  r.material = "gas";
  r.density = std::move(density);
  return r;
}

/// The gas at rest (or moving uniformly) at constant density and pressure.
inline RegionSetup uniform_region(double rho, double p, double vx = 0, double vy = 0) {
  RegionSetup r = gas_region(constant_field(rho));
  r.pressure = constant_field(p);
  r.velocity_x = constant_field(vx);
  r.velocity_y = constant_field(vy);
  return r;
}

inline BoundaryCondition boundary(const std::string& tag, BoundaryKind kind) {
  BoundaryCondition bc;
  bc.tag = tag;
  bc.kind = kind;
  return bc;
}

/// The same kind of boundary on each of `tags`.
inline void boundaries(Problem& p, std::initializer_list<const char*> tags, BoundaryKind kind) {
  for (const char* t : tags) p.boundaries.push_back(boundary(t, kind));
}

/// Rigid walls on `tags` (all four sides of a rectangle by default).
inline void walls(Problem& p, std::initializer_list<const char*> tags = kBoxSides) {
  boundaries(p, tags, BoundaryKind::wall);
}

/// The left and right states of a shock tube (Sod's by default, docs/verification.md §1).
struct ShockTubeStates {
  double rho_left = 1.0, p_left = 1.0, rho_right = 0.125, p_right = 0.1;
};

/// The gas of a shock tube with its diaphragm at x = 0.5.
inline RegionSetup shock_tube_region(const ShockTubeStates& s = {}) {
  RegionSetup r = gas_region([s](double x, double) { return x < 0.5 ? s.rho_left : s.rho_right; });
  r.pressure = [s](double x, double) { return x < 0.5 ? s.p_left : s.p_right; };
  return r;
}

/// A shock tube on [0,1]x[0,0.1] in nx x ny zones, walls all round.
inline Problem shock_tube(int nx, int ny, double t_end, const ShockTubeStates& states = {}, double gamma = 1.4) {
  Problem p = gas_problem(rectangle_mesh(1.0, 0.1, nx, ny), gamma, t_end);
  p.regions.push_back(shock_tube_region(states));
  walls(p);
  return p;
}

/// Sod (docs/verification.md §1) on nx x 5 with the defaults of the prototype's runs (Q = 0;
/// docs/algorithm.md §16.1).
inline Problem sod_problem(int nx, double t_end = 0.2) {
  Problem p = shock_tube(nx, 5, t_end);
  p.options.hourglass_coefficient = 0;
  return p;
}

/// Sedov's point blast (docs/verification.md) in the quarter plane [0,1.2]^2 on n x n zones:
/// cold gas of density 1, the blast energy at the origin, walls all round.
inline Problem sedov_quarter_problem(int n, double t_end, const MeshBuildOptions& options = {}) {
  Problem p = gas_problem(rectangle_mesh(0, 1.2, 0, 1.2, n, n, options), 1.4, t_end, "sedov");
  RegionSetup r = gas_region(constant_field(1.0));
  r.specific_internal_energy = constant_field(1e-10);
  p.regions.push_back(r);
  walls(p);
  p.deposits.push_back({0, 0, 0.244816});
  return p;
}

/// A spherical blast in rz (docs/ale.md, "ALE in rz") on an equal-angle quarter disc of radius
/// 1.2 (`angles` x `rings` zones): the shock at r = 1 at t = 1 (0.398 at t = 0.1, the end time).
inline Problem rz_blast_problem(int angles, int rings) {
  Problem p = gas_problem(build_mesh(meshgen::annulus_sector(0, 1.2, 0, M_PI / 2, angles, rings)), 1.4, 0.1);
  p.regions.push_back(uniform_region(1.0, 1e-10 * 0.4));
  walls(p, {"start", "end", "outer"});
  p.deposits.push_back({0.0, 0.0, 0.0677262});
  p.options.geometry = CoordinateSystem::rz;
  p.options.viscosity = Viscosity::edge;
  p.options.hourglass = Hourglass::gamma;
  p.options.hourglass_coefficient = 0.1;
  p.options.cfl = 0.15;
  return p;
}

}  // namespace stagger::testing
