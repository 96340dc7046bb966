#pragma once
// The state behind stagger::Simulation: structure of arrays, contiguous corners, and the
// step assembled once from the problem ("skip what a scene doesn't need").
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "stagger/simulation.hpp"

namespace stagger {

// Zones of one region, all of one material: the EOS and strength run as one tight loop.
struct ZoneRange {
  Index begin = 0, end = 0;
  int material = 0;
};

// A point with one or two velocity constraints n_i . v = g_i(t) (NUMERICS section 9).
struct PointConstraint {
  Index point = 0;
  int count = 0;                       // 1 or 2 independent normals
  std::array<double, 2> nx{}, ny{};    // unit normals
  std::array<int, 2> velocity_bc{-1, -1};  // index into velocity boundaries, -1 = wall (g = 0)
};

// Applied pressure on one boundary edge (a -> b, outward normal (dy, -dx)).
struct PressureEdge {
  Index a = 0, b = 0;
  int bc = 0;  // index into Problem::boundaries
};

// Neighbour information for the edge viscosity's Christensen limiter, per corner c (the
// edge from corner_point[c] to the next point of the zone): what continues the edge beyond
// each end. A point id (>= 0); kContinuationFree (ratio 0: free or pressure boundary);
// kContinuationOpen (ratio 1: periodic side); or mirror_code(w): the edge ends on a wall,
// symmetry plane or piston edge whose other end point is w, and the continuation is the
// edge's mirror image in it.
constexpr Index kContinuationFree = -1, kContinuationOpen = -2;
constexpr Index mirror_code(Index wall_end) { return -3 - wall_end; }
constexpr Index mirror_wall_end(Index code) { return -3 - code; }

struct EdgeContinuation {
  Index ahead = kContinuationFree, behind = kContinuationFree;
};

std::string describe_zone(const Simulation::Impl& s, Index z);

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

  // Points.
  std::vector<double> x, y;
  std::vector<double> x_half, y_half;  // only when strength, edge q or external forces need them
  std::vector<double> vx, vy, vx_new, vy_new, vx_star, vy_star;
  std::vector<double> point_mass;
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
  std::vector<double> corner_mass;  // constant subzone masses (the subzonal hourglass options only)
  std::vector<EdgeContinuation> continuation;

  // Boundary conditions.
  std::vector<PointConstraint> constraints;
  std::vector<int> velocity_bcs;  // Problem::boundaries indices of velocity BCs
  std::vector<std::vector<Index>> periodic_groups;
  std::vector<PressureEdge> pressure_edges;
  std::vector<Index> external_points;          // points with external forces (pressure, sources)
  std::vector<double> ext_fx, ext_fy;          // applied-pressure force per point (when used)
  std::vector<double> src_fx, src_fy;          // momentum-source force per point (when used)
  std::vector<double> corner_scratch;          // corner areas for the momentum source
  std::vector<double> source_energy;           // energy added by the energy source this step, per zone
  bool has_external = false;
  std::vector<Index> constrained;              // points whose velocity constraints may change
  std::vector<double> free_vx, free_vy;        // their velocity before the constraints

  // Time and bookkeeping.
  double t = 0, dt_last = 0, dt_next = 0, dt_control_prev = 0;
  long cycle = 0;
  bool have_previous_forces = false;
  double energy_initial = 0, boundary_work = 0, source_work = 0;
  enum class DtReason { cfl, growth, initial, maximum, retry, landing } dt_reason = DtReason::cfl;
  Index dt_zone = -1;  // zone that limited the last CFL/volume candidate

  std::shared_ptr<Remap> remap;
  std::function<void(const Simulation&)> observer;
  const Simulation* owner = nullptr;  // the Simulation holding this Impl (for the observer)

  explicit Impl(Problem prob);
  void step(double t_stop);
  bool try_step(double dt);  // false: a zone tangled, nothing committed
  void external_forces(double t_half);
  Index find_tangled_zone(double dt);
  // Geometry, density, pressure and sound speed from x and e (set-up, restore, remap, retry).
  void recompute_state();
  // Full force evaluation at the current state (first cycle, fresh predictor).
  void evaluate_forces_now();
  double kinetic_energy() const;
  double internal_energy() const;
};

}  // namespace stagger
