// The exact two-stiffened-gas Riemann solver (lib/src/verify/stiffened_riemann.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "stagger/verify.hpp"

namespace stagger {

TEST(StiffenedRiemann, IdealGasesGiveToroSolver) {
  const GasState left{1.0, 0.0, 1.0}, right{0.125, 0.0, 0.1};
  const StiffenedRiemann two({left, 1.4, 0.0}, {right, 1.4, 0.0});
  const ExactRiemann one(left, right, 1.4);
  EXPECT_NEAR(two.star_pressure(), one.star_pressure(), 1e-14);
  EXPECT_NEAR(two.star_velocity(), one.star_velocity(), 1e-14);
  for (double x = 0.005; x < 1; x += 0.01) {
    const GasState a = two.sample(x, 0.2), b = one.sample(x, 0.2);
    EXPECT_NEAR(a.density, b.density, 1e-13) << x;
    EXPECT_NEAR(a.velocity, b.velocity, 1e-13) << x;
    EXPECT_NEAR(a.pressure, b.pressure, 1e-13) << x;
  }
}

// Water (gamma 4.4, p_inf 6e8) at 1e9 Pa against air at 1e5 Pa: a rarefaction into the water,
// a shock into the air. The star state satisfies the Rankine-Hugoniot conditions of the air
// shock and the water isentrope p + p_inf ~ rho^gamma.
TEST(StiffenedRiemann, WaterAirSatisfiesJumpConditions) {
  const StiffenedSide water{{1000.0, 0.0, 1e9}, 4.4, 6e8}, air{{10.0, 0.0, 1e5}, 1.4, 0.0};
  const StiffenedRiemann solution(water, air, 0.7);
  const double p = solution.star_pressure(), u = solution.star_velocity();
  EXPECT_GT(p, 1e5);
  EXPECT_LT(p, 1e9);
  EXPECT_GT(u, 0.0);
  // Water isentrope.
  EXPECT_NEAR((p + 6e8) / (1e9 + 6e8), std::pow(solution.star_density_left() / 1000.0, 4.4), 1e-12);
  // Air shock: mass and momentum fluxes through the shock of speed S are continuous.
  const double rho1 = solution.star_density_right();
  const double speed = rho1 * u / (rho1 - 10.0);     // mass: rho0 S = rho1 (S - u)
  EXPECT_NEAR(10.0 * speed * u, p - 1e5, 1e-9 * p);  // momentum: rho0 S u = p1 - p0
  // Energy: e1 - e0 = (p1 + p0)/2 (1/rho0 - 1/rho1) (Hugoniot).
  const double e0 = 1e5 / (0.4 * 10.0), e1 = p / (0.4 * rho1);
  EXPECT_NEAR(e1 - e0, 0.5 * (p + 1e5) * (1 / 10.0 - 1 / rho1), 1e-9 * e1);
  // Sampling: contact between the star densities, pressure continuous there.
  const double t = 2e-4, x_contact = 0.7 + u * t;
  const GasState l = solution.sample(x_contact - 1e-9, t), r = solution.sample(x_contact + 1e-9, t);
  EXPECT_NEAR(l.pressure, p, 1e-6 * p);
  EXPECT_NEAR(r.pressure, p, 1e-6 * p);
  EXPECT_NEAR(l.density, solution.star_density_left(), 1e-9);
  EXPECT_NEAR(r.density, rho1, 1e-9);
  // Far field untouched; the water fan is continuous at its head.
  EXPECT_EQ(solution.sample(0.0, t).pressure, 1e9);
  EXPECT_EQ(solution.sample(1.0 + 0.0, t).pressure, 1e5);
  const double c_water = std::sqrt(4.4 * (1e9 + 6e8) / 1000.0);
  EXPECT_NEAR(solution.sample(0.7 - c_water * t + 1e-9, t).pressure, 1e9, 1e3);
}

}  // namespace stagger
