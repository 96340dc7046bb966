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
#include "state/clock.hpp"
#include "state/state.hpp"

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
  int bc = 0;          // index into Problem::boundaries
  Index zone = -1;     // transmitting: the zone beside the edge (-1: an applied pressure)
  double ambient = 0;  // transmitting: its far-field pressure, the zone's at t = 0
};

std::string describe_zone(const Simulation::Impl& s, Index z);

// One entry of the physics digest a checkpoint carries (physics_digest.hpp): a number or
// a name as text, or the hex FNV-1a hash of an array.
struct DigestEntry {
  std::string section, key, value;
  bool hashed = false;
};

// The Lagrangian phase's view of a running problem: the state (arrays), the clock (scalars)
// and the step's configuration, inherited so that the step's code names them directly, plus
// the topology, the boundary conditions and the installed remap and observer.
struct Simulation::Impl : State, Clock, StepConfig {
  Problem problem;
  const Mesh& mesh() const { return problem.mesh; }

  // Topology: views of the mesh's arrays (the mesh lives in `problem`, which never moves).
  std::span<const Index> zone_corner_begin, corner_point, point_corner_begin, point_corners;
  std::vector<ZoneRange> ranges;

  // Axisymmetric geometry (docs/algorithm.md §19), set-up constants: the corners of the axis
  // points in CSR form: corner, the two neighbours whose radii s_c measure its radial stretch,
  // k_c = rho^0 A_c^0 s_c^0.
  std::vector<Index> axis_points;  // points on x = 0 (rz)
  std::vector<Index> axis_corner_begin{0}, axis_corner, axis_ref_a, axis_ref_b;
  std::vector<double> axis_moment;
  std::vector<EdgeContinuation> continuation;
  // Artificial heat flux (docs/algorithm.md §21): per corner the zone across its edge (same
  // material) or kNoHeatNeighbour, and the time-step limit of the rates at t^n.
  std::vector<Index> heat_neighbour;
  DtChoice heat_dt;

  // Boundary conditions.
  std::vector<PointConstraint> constraints;
  std::vector<int> velocity_bcs;  // Problem::boundaries indices of velocity BCs
  std::vector<std::vector<Index>> periodic_groups;
  std::vector<PressureEdge> pressure_edges;
  std::vector<WallEdge> wall_edges, wall_rays;  // walls fixed in space (boundary.cpp)
  WallGrid wall_grid;
  WallClearance wall_clearance;          // per-point budgets of the wall check (changes every step)
  std::vector<Index> external_points;    // points with external forces (pressure, sources)
  std::vector<Index> constrained;        // points whose velocity constraints may change
  std::vector<double> free_vx, free_vy;  // their velocity before the constraints (sized by `constrained`)

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
  // The stages of the set-up (setup.cpp; docs/algorithm.md §2).
  struct RegionIndex {
    std::vector<int> setup, material;  // per mesh region: its problem.regions and problem.materials entries
  };
  RegionIndex assign_materials();
  void set_initial_zones(const RegionIndex& regions);
  void check_point_masses();
  void deposit_energy();
  void set_initial_velocities();
  void set_up_burn();
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
