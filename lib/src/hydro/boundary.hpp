#pragma once
// Boundary-condition set-up and application (docs/algorithm.md §10).
#include <span>
#include <string>
#include <vector>

#include "hydro/simulation_impl.hpp"

namespace stagger {

// Builds constraints, periodic groups and pressure edges from the problem's boundaries.
void setup_boundaries(Simulation::Impl& s);

// Enforces periodic groups (mass-weighted common velocity) and then the normal constraints
// at time t on (vx, vy). Returns nothing; the caller accounts for the work.
void apply_constraints(const Simulation::Impl& s, std::span<double> vx, std::span<double> vy, double t);
// The same constraints on the low parts of a compensated velocity (docs/algorithm.md §20):
// no normal component on a one-direction constraint, zero where the velocity is set whole.
void constrain_low_parts(const Simulation::Impl& s, std::span<double> lo_x, std::span<double> lo_y);

// Sets (fx, fy) to the applied-pressure forces at time t on the positions (x, y): per unit
// depth, or in rz per radian (the geometry policy's scale_surface_forces; docs/algorithm.md §19).
void pressure_forces(const Simulation::Impl& s, std::span<const double> x, std::span<const double> y, double t,
                     std::span<double> fx, std::span<double> fy);

// No point through a wall (docs/algorithm.md §10): the lowest point whose step
// x^n -> x^n + dt v_bar (v_bar from vx/vy and vx_new/vy_new) leaves the domain through a wall
// edge, or through the continuation of an open wall end, by more than round-off; -1 if none.
Index find_wall_crossing(const Simulation::Impl& s, double dt);

// The same answer as find_wall_crossing, for the step being taken: only the points whose step
// is longer than their wall clearance budget are tested (WallClearance, walls.hpp). Its
// budgets assume the step is accepted; a rejected step must invalidate them (recompute_state).
Index step_wall_crossing(Simulation::Impl& s, double dt);

// What find_wall_crossing found for point p: the point, its path and the wall; empty if p
// does not cross one.
std::string describe_wall_crossing(const Simulation::Impl& s, Index p, double dt);

// The points whose velocity apply_constraints may change (for the constraint-work sum).
std::vector<Index> constrained_points(const Simulation::Impl& s);

}  // namespace stagger
