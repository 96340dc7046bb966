#pragma once
// Boundary-condition set-up and application (docs/algorithm.md §10).
#include <span>
#include <vector>

#include "hydro/simulation_impl.hpp"

namespace stagger {

// Builds constraints, periodic groups and pressure edges from the problem's boundaries.
void setup_boundaries(Simulation::Impl& s);

// Enforces periodic groups (mass-weighted common velocity) and then the normal constraints
// at time t on (vx, vy). Returns nothing; the caller accounts for the work.
void apply_constraints(const Simulation::Impl& s, std::span<double> vx, std::span<double> vy, double t);

// Adds the applied-pressure forces at time t on the positions (x, y) into (fx, fy).
void add_pressure_forces(const Simulation::Impl& s, std::span<const double> x, std::span<const double> y, double t,
                         std::span<double> fx, std::span<double> fy);

// The points whose velocity apply_constraints may change (for the constraint-work sum).
std::vector<Index> constrained_points(const Simulation::Impl& s);

}  // namespace stagger
