// The mixed-zone closure alone (lib/src/mixed/closure.hpp): its energy shares sum to the
// zone's compatible change, uniform strain of identical components is the one-material
// update, and pressure relaxation brings two gases to a common pressure.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mixed/closure.hpp"

namespace stagger::mixed {

namespace {

double internal_energy(const std::vector<Component>& components) {
  double total = 0;
  for (const Component& k : components) total += k.mass * k.e;
  return total;
}

// A zone of volume v with components (eos, fraction, rho, e), states evaluated.
std::vector<Component> zone(double v,
                            const std::vector<std::tuple<const EquationOfState*, double, double, double>>& parts) {
  std::vector<Component> components;
  for (const auto& [eos, fraction, rho, e] : parts) components.push_back({eos, rho * fraction * v, fraction, e});
  ZoneMixture mixture;
  EXPECT_TRUE(evaluate_components(v, components, mixture));
  return components;
}

}  // namespace

TEST(MixedClosure, UniformStrainOfIdenticalComponentsIsTheOneMaterialUpdate) {
  const EquationOfState air = IdealGas{1.4};
  const double v0 = 0.01, v1 = 0.0093, rho = 1.2, e = 2.5e5;
  auto components = zone(v0, {{&air, 0.3, rho, e}, {&air, 0.7, rho, e}});
  const double p = components[0].p, mass = rho * v0;
  const double d_energy = -(p + 1234.5) * (v1 - v0);  // p dV and some q work
  ASSERT_TRUE(advance_components(Closure::uniform_strain, v0, v1, d_energy, components));
  const double e_pure = e + d_energy / mass;
  for (const Component& k : components) {
    EXPECT_NEAR(k.e, e_pure, 1e-12 * e_pure);
    EXPECT_NEAR(k.rho, mass / v1, 1e-12 * rho);
  }
  ZoneMixture mixture;
  ASSERT_TRUE(evaluate_components(v1, components, mixture));
  EXPECT_NEAR(mixture.p, 0.4 * (mass / v1) * e_pure, 1e-12 * mixture.p);
  EXPECT_NEAR(internal_energy(components), mass * e + d_energy, 1e-15 * mass * e);
}

TEST(MixedClosure, EqualPressuresStayEqual) {
  // Air and helium at the same pressure, translating (no volume change, no work): nothing moves.
  const EquationOfState air = IdealGas{1.4}, helium = IdealGas{1.648};
  const double p = 1e5;
  auto components = zone(1.0, {{&air, 0.4, 1.0, p / (0.4 * 1.0)}, {&helium, 0.6, 0.182, p / (0.648 * 0.182)}});
  for (Closure closure : {Closure::pressure_relaxation, Closure::uniform_strain}) {
    for (int step = 0; step < 50; ++step) ASSERT_TRUE(advance_components(closure, 1.0, 1.0, 0.0, components));
    for (const Component& k : components) EXPECT_NEAR(k.p, p, 1e-12 * p);
  }
}

TEST(MixedClosure, PressureRelaxationReachesACommonPressureAndKeepsTheEnergy) {
  const EquationOfState air = IdealGas{1.4}, water = StiffenedGas{4.4, 6e8};
  auto components =
      zone(1e-4, {{&air, 0.5, 10.0, 3e6 / (0.4 * 10.0)}, {&water, 0.5, 1000.0, (2e6 + 4.4 * 6e8) / 3400.0}});
  const double energy = internal_energy(components);
  for (int step = 0; step < 40; ++step)
    ASSERT_TRUE(advance_components(Closure::pressure_relaxation, 1e-4, 1e-4, 0.0, components));
  EXPECT_NEAR(components[0].p, components[1].p, 1e-10 * components[1].p);
  EXPECT_NEAR(internal_energy(components), energy, 1e-14 * energy);
  EXPECT_NEAR(components[0].fraction + components[1].fraction, 1.0, 1e-15);
  EXPECT_GT(components[0].fraction, 0.5);  // the gas at the higher pressure expanded
}

}  // namespace stagger::mixed
