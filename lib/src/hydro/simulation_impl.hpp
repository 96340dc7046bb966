#pragma once
// The state behind stagger::Simulation: structure of arrays, contiguous corners, and the
// step assembled once from the problem ("skip what a scene doesn't need").
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "hydro/collective.hpp"
#include "hydro/kernels/viscosity_edge.hpp"  // EdgeContinuation
#include "hydro/walls.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

// Zones of one region, all of one material: the EOS and strength run as one tight loop.
struct ZoneRange {
  Index begin = 0, end = 0;
  int material = 0;
  bool ghost = false;  // a distributed run's ghost zones: computed, but their failures and dt are not this rank's
};

// A point with one or two velocity constraints n_i . v = g_i(t) (docs/algorithm.md §10).
struct PointConstraint {
  Index point = 0;
  int count = 0;                           // 1 or 2 independent normals
  std::array<double, 2> nx{}, ny{};        // unit normals
  std::array<int, 2> velocity_bc{-1, -1};  // index into velocity boundaries, -1 = wall (g = 0)
};

// Applied pressure on one boundary edge (a -> b, outward normal (dy, -dx)).
struct PressureEdge {
  Index a = 0, b = 0;
  int bc = 0;  // index into Problem::boundaries
};

std::string describe_zone(const Simulation::Impl& s, Index z);

// One entry of the physics digest a checkpoint carries (physics_digest.hpp): a number or
// a name as text, or the hex FNV-1a hash of an array.
struct DigestEntry {
  std::string section, key, value;
  bool hashed = false;
};

struct Simulation::Impl {
  Problem problem;
  const Mesh& mesh() const { return problem.mesh; }

  // Step configuration.
  bool any_strength = false, any_burn = false, all_quads = false;
  bool edge_viscosity = false;
  double dt_min = 0;

  // Topology: views of the mesh's arrays (the mesh lives in `problem`, which never moves).
  std::span<const Index> zone_corner_begin, corner_point, point_corner_begin, point_corners;
  std::vector<ZoneRange> ranges;

  // The state arrays: every point, zone and corner array below is listed in the state table
  // (state_fields.cpp), which sizes them (allocate_state), checkpoints, swaps and dumps them.
  // Points.
  std::vector<double> x, y;
  std::vector<double> x_half, y_half;  // only when strength, edge q or external forces need them
  std::vector<double> vx, vy, vx_new, vy_new, vx_star, vy_star;
  std::vector<double> point_mass;
  // Low parts of x and v (numerics.compensated_update only, docs/algorithm.md §20).
  std::vector<double> x_lo, y_lo, vx_lo, vy_lo, vx_lo_new, vy_lo_new;
  // Zones.
  std::vector<double> zone_mass, area, rho, e, e_new, p, q, c;  // c = full sound speed C
  std::vector<double> rho_half, c_half;                         // edge viscosity only
  // Strength zones only (sized to the number of zones when any material has strength).
  std::vector<double> sxx, syy, sxy, sxx_new, syy_new, sxy_new, sxx_half, syy_half, sxy_half;
  std::vector<double> plastic, plastic_new;
  std::vector<double> grad_xx, grad_xy, grad_yx, grad_yy;  // L(v) on the current geometry
  // Burn.
  std::vector<double> burn, burn_new, lighting_time, burn_length;
  // Corner forces: the last corrector's f^{n-1/2}, overwritten in place by f^{n+1/2}.
  std::vector<double> corner_fx, corner_fy;
  std::vector<double> corner_mass;      // constant subzone masses (the subzonal hourglass options only)
  std::vector<double> ale_corner_mass;  // median-mesh corner masses, the remap's subcells (ALE only)
  // Axisymmetric geometry (docs/algorithm.md §19): the acceleration of the (massless) axis
  // points with the last forces, and (set-up constants) their corners in CSR form: corner,
  // the two neighbours whose radii s_c measure its radial stretch, k_c = rho^0 A_c^0 s_c^0.
  std::vector<double> axis_ax, axis_ay;
  std::vector<Index> axis_points;  // points on x = 0 (rz)
  std::vector<Index> axis_corner_begin{0}, axis_corner, axis_ref_a, axis_ref_b;
  std::vector<double> axis_moment;
  bool rz = false;
  std::vector<EdgeContinuation> continuation;
  // Artificial heat flux (docs/algorithm.md §21): per corner the zone across its edge (same
  // material) or kNoHeatNeighbour; per zone (state table) the conductivity, centre and the
  // energy rate at t^n that steps 3 and 7 add, with its time-step limit.
  bool heat_flux = false;
  std::vector<Index> heat_neighbour;
  std::vector<double> heat_kappa, heat_cx, heat_cy, heat_rate;
  DtChoice heat_dt;

  // Boundary conditions.
  std::vector<PointConstraint> constraints;
  std::vector<int> velocity_bcs;  // Problem::boundaries indices of velocity BCs
  std::vector<std::vector<Index>> periodic_groups;
  std::vector<PressureEdge> pressure_edges;
  std::vector<WallEdge> wall_edges, wall_rays;  // walls fixed in space (boundary.cpp)
  WallGrid wall_grid;
  WallClearance wall_clearance;        // per-point budgets of the wall check (changes every step)
  std::vector<Index> external_points;  // points with external forces (pressure, sources)
  std::vector<double> ext_fx, ext_fy;  // applied-pressure force per point (when used)
  std::vector<double> src_fx, src_fy;  // momentum-source force per point (when used)
  std::vector<double> corner_scratch;  // corner areas for the momentum source
  std::vector<double> source_energy;   // energy added by the energy source this step, per zone
  bool has_external = false;
  std::vector<Index> constrained;        // points whose velocity constraints may change
  std::vector<double> free_vx, free_vy;  // their velocity before the constraints (sized by `constrained`)

  // Time and bookkeeping.
  double t = 0, dt_last = 0, dt_next = 0, dt_control_prev = 0;
  long cycle = 0;
  bool have_previous_forces = false;
  double energy_initial = 0, boundary_work = 0, source_work = 0;
  double ale_fixup = 0;  // kinetic energy the ALE remap's fix-up moved into internal energy (cumulative)
  enum class DtReason { cfl, growth, initial, maximum, retry, landing, heat_flux } dt_reason = DtReason::cfl;
  Index dt_zone = -1;  // zone that limited the last CFL/volume candidate

  // What defines the physics, fixed at set-up (checkpoints carry it; a restart compares it).
  std::vector<DigestEntry> digest;

  // A distributed run (docs/parallel.md): the other ranks, the global number of each local
  // zone and point, and which local ones are ghosts. Null and empty in a serial run.
  std::unique_ptr<Collective> collective;
  std::vector<Index> global_zone, global_point;
  std::vector<unsigned char> ghost_zone, ghost_point;

  std::shared_ptr<Remap> remap;
  std::function<void(const Simulation&)> observer;
  const Simulation* owner = nullptr;  // the Simulation holding this Impl (for the observer)

  explicit Impl(Problem prob);
  ~Impl();
  void step(double t_stop);
  bool try_step(double dt);  // false: a zone tangled, nothing committed
  // The calls of try_step (step.cpp; docs/algorithm.md §1).
  void predict_velocity(double dt, double t_half);
  std::int64_t zone_forces(const double* px, const double* py, double h_position, const double* qvx, const double* qvy,
                           double dt_half, double t_eval);
  void edge_forces(const double* px, const double* py, const double* qvx, const double* qvy);
  void correct_velocity(double dt, double t_new);
  std::int64_t end_of_step(double dt, double t_new);
  void account_boundary_work(double dt);
  void commit(double dt);
  void external_forces(double t_half);
  Index find_tangled_zone(double dt);
  // Geometry, density, pressure and sound speed from x and e (set-up, restore, remap, retry).
  void recompute_state();
  // Full force evaluation at the current state (first cycle, fresh predictor).
  void evaluate_forces_now();
  void weight_rz_forces(const double* px, double h_position);
  // The heat flux's rates and time-step limit (heat_dt) on the state at t^n.
  void heat_flux_rates_now();
  void setup_rz_masses();
  double kinetic_energy() const;
  double internal_energy() const;
};

}  // namespace stagger
