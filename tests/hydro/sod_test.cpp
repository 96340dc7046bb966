// Sod shock tube: energy audit, the prototype's figures (regression anchors, docs/algorithm.md
// §16), first-order convergence against the exact solution, symmetry across y.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "problems.hpp"
#include "stagger/error.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"
#include "support/sod_error.hpp"

namespace stagger {

namespace {
constexpr auto l1_density = testing::sod_l1_density;
}  // namespace

TEST(Sod, ReproducesThePrototypeAt400ZonesWithEnergyAtRoundOff) {
  Simulation sim(testing::sod_problem(400));
  sim.advance_to(0.2);
  EXPECT_DOUBLE_EQ(sim.time(), 0.2);
  // Regression anchor: the independent prototype of the scheme measured 1783 cycles and
  // L1_density = 1.467e-3 here, with these defaults (docs/algorithm.md §16.1-16.2 give the origin;
  // docs/verification.md §1 the exact-solution comparison). The scheme is deterministic, so the
  // cycle count must match exactly and the error to the four digits quoted: a change of the
  // discrete scheme (even one that keeps first order) moves them. A deliberate change updates
  // this test and docs/algorithm.md §16 together.
  EXPECT_EQ(sim.cycle(), 1783);
  EXPECT_NEAR(l1_density(sim), 1.467e-3, 0.0005e-3);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-13);
  RecordProperty("cycles", static_cast<int>(sim.cycle()));
  std::printf("sod400: cycles %ld L1 %.6e audit %.3e\n", sim.cycle(), l1_density(sim), sim.energy().relative_error);
}

}  // namespace stagger

namespace stagger {

TEST(Sod, ConvergesAtFirstOrderWithNoVariationAcrossTheTube) {
  double previous = 0;
  for (int nx : {100, 200, 400}) {
    Simulation sim(testing::sod_problem(nx));
    sim.advance_to(0.2);
    NamedValues errors, diagnostics;
    shock_tube_reference({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.5)(sim, errors, diagnostics);
    double l1 = 0, y_variation = 1;
    for (const auto& [k, v] : errors)
      if (k == "L1_density") l1 = v;
    for (const auto& [k, v] : diagnostics)
      if (k == "max_y_variation") y_variation = v;
    EXPECT_LT(y_variation, 1e-10) << nx << " zones";
    if (previous > 0) {
      const double order = std::log2(previous / l1);
      std::printf("sod %d: L1_density %.4e order %.3f\n", nx, l1, order);
      EXPECT_GT(order, 0.8);
      EXPECT_LT(order, 1.3);
    }
    previous = l1;
  }
}

}  // namespace stagger

namespace stagger {

// Material::min_energy (`min_energy` of a [[material]]) is a floor enforced on every state the
// step commits, and on the initial state. Sod starts with e = 2.5 (left) and 2.0 (right); the
// rarefaction cools the gas behind it to about 1.78. A floor of 1.9 must stop the run (as an
// EOS-domain failure, not retried) before t_end, naming a zone, with no energy below the floor
// ever committed; without the floor the same run completes and crosses 1.9. A floor of 2.4 is
// already crossed by the initial right state: set-up refuses it.
TEST(Sod, MinEnergyFloorIsEnforced) {
  Problem floored = testing::sod_problem(100);
  floored.materials[0].min_energy = 1.9;
  Simulation sim(std::move(floored));
  std::string message;
  try {
    while (!sim.finished()) {
      sim.step();
      for (double e : sim.specific_internal_energy())
        ASSERT_GE(e, 1.9) << "a committed energy is below the floor at cycle " << sim.cycle();
    }
  } catch (const Error& error) {
    message = error.what();
  }
  EXPECT_FALSE(sim.finished());
  EXPECT_GT(sim.cycle(), 0);
  EXPECT_LT(sim.time(), 0.2);
  EXPECT_NE(message.find("left the domain of its equation of state"), std::string::npos) << message;
  EXPECT_NE(message.find("zone "), std::string::npos) << message;
  std::printf("min_energy 1.9: stopped at cycle %ld, t = %.4g: %s\n", sim.cycle(), sim.time(), message.c_str());

  Simulation free_run(testing::sod_problem(100));
  free_run.advance_to(0.2);
  EXPECT_DOUBLE_EQ(free_run.time(), 0.2);
  double lowest = 1e300;
  for (double e : free_run.specific_internal_energy()) lowest = std::min(lowest, e);
  EXPECT_LT(lowest, 1.9);  // the floor is crossed without it: the check above is not vacuous

  Problem refused = testing::sod_problem(100);
  refused.materials[0].min_energy = 2.4;
  try {
    Simulation never(std::move(refused));
    ADD_FAILURE() << "set-up accepted an initial energy below min_energy";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("initial"), std::string::npos) << error.what();
  }
}

}  // namespace stagger
