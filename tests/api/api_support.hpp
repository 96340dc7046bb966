#pragma once
// Problems built through the public API only (on the shared builders of tests/support/), and
// a bitwise comparison of two states.
#include <gtest/gtest.h>

#include <cstring>
#include <span>
#include <string>
#include <utility>

#include "stagger/problem.hpp"
#include "stagger/simulation.hpp"
#include "support/bitwise.hpp"
#include "support/gas_problem.hpp"

namespace stagger::api_test {

/// A rigid wall on boundary tag `tag`.
inline BoundaryCondition wall(const std::string& tag) {
  return testing::boundary(tag, BoundaryKind::wall);
}

/// A shock tube on [0,1]x[0,0.1], nx x 4 zones, walls all round (docs/verification.md §1
/// for the default states).
inline Problem shock_tube(int nx, double t_end, double rho_left = 1.0, double p_left = 1.0, double rho_right = 0.125,
                          double p_right = 0.1, double gamma = 1.4) {
  Problem problem = testing::shock_tube(nx, 4, t_end, {rho_left, p_left, rho_right, p_right}, gamma);
  problem.name = "shock_tube";
  problem.options.hourglass_coefficient = 0;
  return problem;
}

using testing::bitwise_equal;

/// Asserts that two simulations hold bitwise the same state, time, cycle and dt.
inline void expect_same_state(const Simulation& a, const Simulation& b) {
  EXPECT_EQ(a.cycle(), b.cycle());
  const double ta = a.time(), tb = b.time(), da = a.dt(), db = b.dt();
  EXPECT_EQ(std::memcmp(&ta, &tb, sizeof ta), 0) << ta << " vs " << tb;
  EXPECT_EQ(std::memcmp(&da, &db, sizeof da), 0) << da << " vs " << db;
  const std::pair<const char*, std::span<const double> (Simulation::*)() const> fields[] = {
      {"x", &Simulation::x},
      {"y", &Simulation::y},
      {"velocity_x", &Simulation::velocity_x},
      {"velocity_y", &Simulation::velocity_y},
      {"zone_area", &Simulation::zone_area},
      {"density", &Simulation::density},
      {"pressure", &Simulation::pressure},
      {"specific_internal_energy", &Simulation::specific_internal_energy},
      {"artificial_viscosity", &Simulation::artificial_viscosity},
      {"sound_speed", &Simulation::sound_speed},
      {"zone_mass", &Simulation::zone_mass},
      {"point_mass", &Simulation::point_mass},
  };
  for (const auto& [name, field] : fields) EXPECT_TRUE(bitwise_equal((a.*field)(), (b.*field)())) << name << " differs";
  const EnergyAudit ea = a.energy(), eb = b.energy();
  EXPECT_EQ(std::memcmp(&ea.relative_error, &eb.relative_error, sizeof(double)), 0);
}

}  // namespace stagger::api_test
