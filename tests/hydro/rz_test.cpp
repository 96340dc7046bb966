// Axisymmetric (rz) geometry (docs/algorithm.md §19): total energy to round-off with strength,
// edge viscosity and applied pressure, the axis condition, the set-up error for a negative
// radius. The kernels (volumes, hoop stress) are tested in tests/kernels/rz_kernels_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "problems.hpp"
#include "stagger/error.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
using namespace testing;

namespace {

// A strong, sheared, hoop-straining flow of an elastic-plastic gas on a perturbed quarter
// [0, 1]^2 of the (r, z) plane: the axis on x = 0, a wall at z = 0, the rest free.
Problem rz_strength_problem(double t_end) {
  Mesh mesh = rectangle_mesh(1.0, 1.0, 12, 12);
  perturb_interior(mesh, 1.0 / 12, 1.0 / 12, 0.25, 3);
  Problem p = gas_problem(std::move(mesh), 1.4, t_end);
  p.materials[0].strength = Strength{2.0, 0.4};
  RegionSetup r = uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double y) { return 0.4 * x * (1 - 0.5 * y); };
  r.velocity_y = [](double x, double y) { return -0.3 * std::sin(M_PI * y) * (1 + x); };
  p.regions.push_back(r);
  walls(p, {"bottom"});
  p.options.geometry = CoordinateSystem::rz;
  p.options.hourglass = Hourglass::flanagan_belytschko;
  p.options.hourglass_coefficient = 0.5;
  return p;
}

}  // namespace

TEST(Rz, TotalEnergyIsExactWithStrengthAndTheAxisKeepsZeroRadialVelocity) {
  Simulation sim(rz_strength_problem(0.1));
  int axis_checks = 0;
  sim.set_observer([&](const Simulation& s) {
    for (std::size_t p = 0; p < s.x().size(); ++p)
      if (s.x()[p] == 0) {
        EXPECT_EQ(s.velocity_x()[p], 0.0) << "axis point " << p;
        ++axis_checks;
      }
  });
  sim.advance_to(0.1);
  EXPECT_GT(sim.cycle(), 20);
  EXPECT_GT(axis_checks, 13 * 20);  // 13 axis points every cycle
  // The flow did something: stress and plastic flow appeared.
  double largest_plastic = 0;
  for (double eps : sim.plastic_strain()) largest_plastic = std::max(largest_plastic, eps);
  EXPECT_GT(largest_plastic, 1e-3);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

TEST(Rz, EdgeViscosityAndAppliedPressureKeepTheAuditExact) {
  Problem p = rz_strength_problem(0.05);
  p.materials[0].strength.reset();
  p.options.viscosity = Viscosity::edge;
  p.boundaries.push_back(boundary("right", BoundaryKind::pressure));
  p.boundaries.back().pressure = [](double t) { return 2.0 + 10 * t; };
  Simulation sim(std::move(p));
  sim.advance_to(0.05);
  EXPECT_GT(std::abs(sim.energy().boundary_work), 1e-3);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

TEST(Rz, ANegativeRadiusIsASetUpErrorNamingThePoint) {
  Mesh mesh = build_mesh(meshgen::rectangle(-0.5, 1.0, 0, 1.0, 6, 4));
  Problem p = gas_problem(std::move(mesh), 1.4, 0.1);
  p.regions.push_back(uniform_region(1.0, 1.0));
  p.options.geometry = CoordinateSystem::rz;
  try {
    Simulation sim(std::move(p));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("negative radius"), std::string::npos) << what;
    EXPECT_NE(what.find("point 0 (-0.5, 0)"), std::string::npos) << what;
  }
}

TEST(Rz, AleIsRefusedUntilTheRemapIsAxisymmetric) {
  Problem p = rz_strength_problem(0.01);
  p.ale.mode = AleMode::ale;
  try {
    Simulation sim(std::move(p));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("runs Lagrangian only"), std::string::npos) << e.what();
  }
}

}  // namespace stagger
