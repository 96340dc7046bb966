// Norms and reference solutions evaluated on a Simulation's state (no time step taken:
// the initial state is set by the problem, so every expected value is known by hand).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "stagger/meshgen.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"
#include "support/gas_problem.hpp"
#include "support/named_values.hpp"

namespace {

using stagger::testing::as_map;

/// A gas on the rectangle [x0,x1]x[y0,y1] (nx x ny zones), free boundaries (the initial
/// velocities stay as given).
stagger::Problem gas_box(double x1, double y1, int nx, int ny, stagger::RegionSetup setup, double gamma = 1.4) {
  namespace support = stagger::testing;
  stagger::Problem problem = support::gas_problem(support::rectangle_mesh(x1, y1, nx, ny), gamma, 1.0, "verify_gas");
  setup.region = "domain";
  setup.material = "gas";
  problem.regions.push_back(setup);
  support::boundaries(problem, support::kBoxSides, stagger::BoundaryKind::free);
  return problem;
}

// 4 x 2 zones on the unit square: zone centres x = 1/8, 3/8, 5/8, 7/8 (equal areas); point
// rows y = 0, 1/2, 1 with median-dual areas 1/4, 1/2, 1/4 of the square.
TEST(SimulationNorms, ZoneAndPointNormsMatchHandValues) {
  stagger::RegionSetup setup;
  setup.density = [](double x, double) { return 1.0 + x; };
  setup.pressure = stagger::constant_field(1.0);
  setup.velocity_x = [](double, double y) { return y; };
  const stagger::Simulation simulation(gas_box(1.0, 1.0, 4, 2, setup));
  stagger::NamedValues errors;
  stagger::zone_field_errors(
      simulation, simulation.density(), [](double, double) { return 1.0; }, "density", errors);
  stagger::point_field_errors(
      simulation, simulation.velocity_x(), [](double, double) { return 0.0; }, "velocity", errors);
  const auto e = as_map(errors);
  EXPECT_NEAR(e.at("L1_density"), 0.5, 1e-14);
  EXPECT_NEAR(e.at("L2_density"), std::sqrt((1.0 + 9.0 + 25.0 + 49.0) / 64.0 / 4.0), 1e-14);
  EXPECT_NEAR(e.at("Linf_density"), 0.875, 1e-14);
  EXPECT_NEAR(e.at("L1_velocity"), 0.5 * 0.5 + 0.25 * 1.0, 1e-14);
  EXPECT_NEAR(e.at("L2_velocity"), std::sqrt(0.5 * 0.25 + 0.25 * 1.0), 1e-14);
  EXPECT_NEAR(e.at("Linf_velocity"), 1.0, 1e-14);
}

TEST(SimulationNorms, ShockTubeReferenceVanishesOnTheInitialSodState) {
  stagger::RegionSetup setup;
  setup.density = [](double x, double) { return x < 0.5 ? 1.0 : 0.125; };
  setup.pressure = [](double x, double) { return x < 0.5 ? 1.0 : 0.1; };
  const stagger::Simulation simulation(gas_box(1.0, 0.1, 10, 2, setup));
  stagger::NamedValues errors, diagnostics;
  stagger::shock_tube_reference({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.5)(simulation, errors, diagnostics);
  const auto e = as_map(errors);
  for (const char* key : {"L1_density", "L1_velocity", "L1_pressure", "Linf_density", "Linf_pressure"})
    EXPECT_EQ(e.at(key), 0.0) << key;
  EXPECT_EQ(as_map(diagnostics).at("max_y_variation"), 0.0);
}

TEST(SimulationNorms, TaylorGreenReferenceVanishesOnTheExactInitialState) {
  stagger::RegionSetup setup;
  setup.density = stagger::constant_field(1.0);
  setup.pressure = [](double x, double y) { return stagger::taylor_green_pressure(x, y); };
  setup.velocity_x = [](double x, double y) { return stagger::taylor_green_velocity(x, y)[0]; };
  setup.velocity_y = [](double x, double y) { return stagger::taylor_green_velocity(x, y)[1]; };
  const stagger::Simulation simulation(gas_box(1.0, 1.0, 4, 4, setup, 5.0 / 3.0));
  stagger::NamedValues errors, diagnostics;
  stagger::taylor_green_reference()(simulation, errors, diagnostics);
  const auto e = as_map(errors);
  EXPECT_NEAR(e.at("L2_velocity"), 0.0, 1e-15);
  EXPECT_NEAR(e.at("L2_pressure"), 0.0, 1e-15);
  EXPECT_NEAR(e.at("Linf_density"), 0.0, 1e-15);
}

}  // namespace
