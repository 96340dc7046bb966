#pragma once
// The evolving state of a problem: one flat array per field, named by entity (point, zone,
// corner), every array listed once in the state table (state_table.hpp), which sizes,
// swaps, checkpoints, exchanges, remaps and dumps them. Phases (the Lagrangian step, the ALE
// remap, the halo exchange) read and write these arrays; what never changes (topology) and
// the step's configuration live elsewhere (StepConfig below, the mesh).
#include <vector>

namespace stagger {

struct State {
  // Points.
  std::vector<double> x, y;
  std::vector<double> x_half, y_half;  // only when strength, edge q or external forces need them
  std::vector<double> vx, vy, vx_new, vy_new, vx_star, vy_star;
  std::vector<double> point_mass;
  // Low parts of x and v (numerics.compensated_update only, docs/algorithm.md §20).
  std::vector<double> x_lo, y_lo, vx_lo, vy_lo, vx_lo_new, vy_lo_new;
  std::vector<double> ext_fx, ext_fy;  // applied-pressure force per point (when used)
  std::vector<double> src_fx, src_fy;  // momentum-source force per point (when used)
  // Axisymmetric geometry: the acceleration of the (massless) axis points with the last forces.
  std::vector<double> axis_ax, axis_ay;

  // Zones.
  std::vector<double> zone_mass, area, rho, e, e_new, p, q, c;  // c = full sound speed C
  std::vector<double> rho_half, c_half;                         // edge viscosity only
  // Strength zones only (sized to the number of zones when any material has strength).
  std::vector<double> sxx, syy, sxy, sxx_new, syy_new, sxy_new, sxx_half, syy_half, sxy_half;
  std::vector<double> plastic, plastic_new;
  std::vector<double> grad_xx, grad_xy, grad_yx, grad_yy;  // L(v) on the current geometry
  // Burn.
  std::vector<double> burn, burn_new, lighting_time, burn_length;
  std::vector<double> source_energy;  // energy added by the energy source this step, per zone
  // Artificial heat flux (docs/algorithm.md §21): conductivity, centre and the energy rate at t^n.
  std::vector<double> heat_kappa, heat_cx, heat_cy, heat_rate;

  // Corners.
  // The last corrector's f^{n-1/2}, overwritten in place by f^{n+1/2}.
  std::vector<double> corner_fx, corner_fy;
  std::vector<double> corner_scratch;   // corner areas for the momentum source
  std::vector<double> corner_mass;      // constant subzone masses (the subzonal hourglass options only)
  std::vector<double> ale_corner_mass;  // median-mesh corner masses, the remap's subcells (ALE only)
};

// What the scene needs, derived once at set-up from the problem: which arrays of the state
// table exist (state_table.hpp, Presence) and which branches of the step run.
struct StepConfig {
  bool any_strength = false;         // some material has strength
  bool any_burn = false;             // some material has a programmed burn
  bool all_quads = false;            // the quad fast path of the zone kernels
  bool edge_viscosity = false;       // numerics.viscosity = "edge"
  bool rz = false;                   // numerics.geometry = "rz"
  bool heat_flux = false;            // numerics.heat_flux_c1 or heat_flux_c2 > 0
  bool has_external = false;         // applied pressure or a momentum source
  bool has_sources = false;          // manufactured sources of any kind
  bool has_momentum_source = false;  // a manufactured momentum source
  bool has_energy_source = false;    // a manufactured energy source
  bool subzonal = false;             // numerics.hourglass = "subzonal" or "subzonal_triangles"
  bool ale = false;                  // ale.mode is not "lagrangian"
  bool compensated = false;          // numerics.compensated_update
  double dt_min = 0;                 // the time step below which a run stops
};

}  // namespace stagger
