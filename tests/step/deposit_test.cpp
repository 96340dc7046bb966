// Energy deposits with a radius (docs/scenes.md `[[deposit]]`): a Gaussian in specific energy
// that puts exactly the deposit's energy into the zones, equal on zones at equal distance,
// and a clear error when the radius reaches no zone centre.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "stagger/error.hpp"
#include "stagger/simulation.hpp"
#include "support/gas_problem.hpp"

namespace stagger {

namespace {

constexpr int kN = 16;
constexpr double kAmbient = 1e-3;

Problem deposit_problem(double radius) {
  Problem p = testing::gas_problem(testing::rectangle_mesh(1, 1, kN, kN), 1.4, 1, "deposit");
  RegionSetup r = testing::gas_region(constant_field(2.0));
  r.specific_internal_energy = constant_field(kAmbient);
  p.regions.push_back(r);
  testing::walls(p);
  EnergyDeposit d;
  d.energy = 0.5;
  d.radius = radius;
  p.deposits.push_back(d);
  return p;
}

}  // namespace

TEST(EnergyDeposit, GaussianPutsItsEnergyAndDependsOnDistanceOnly) {
  const double radius = 0.15, h = 1.0 / kN;
  Simulation sim(deposit_problem(radius));
  const auto e = sim.specific_internal_energy();
  const auto mass = sim.zone_mass();
  double added = 0;
  for (int z = 0; z < kN * kN; ++z) added += mass[z] * (e[z] - kAmbient);
  EXPECT_NEAR(added, 0.5, 1e-14);
  // Zone (i, j) of the row-major grid, centre ((i + 1/2) h, (j + 1/2) h): its deposit relative
  // to the corner zone's is exp(-(d^2 - d0^2) / R^2), and (i, j) and (j, i) get the same.
  const double e0 = e[0] - kAmbient, d0 = 0.5 * h * h;
  int resolved = 0;
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const double ez = e[j * kN + i] - kAmbient;
      const double d2 = ((i + 0.5) * (i + 0.5) + (j + 0.5) * (j + 0.5)) * h * h;
      const double expected = std::exp(-(d2 - d0) / (radius * radius));
      if (expected < 1e-6) continue;  // below the ambient's round-off
      ++resolved;
      EXPECT_NEAR(ez / e0, expected, 1e-9 * expected) << i << " " << j;
      EXPECT_EQ(ez, e[i * kN + j] - kAmbient) << i << " " << j;
    }
  EXPECT_GT(resolved, 20);
}

TEST(EnergyDeposit, RadiusReachingNoZoneCentreIsOneClearError) {
  try {
    Simulation sim(deposit_problem(1e-4));
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("radius"), std::string::npos) << error.what();
  }
}

}  // namespace stagger
