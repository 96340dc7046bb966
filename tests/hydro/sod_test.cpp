// Sod shock tube: energy audit, the prototype's measured figures, symmetry across y.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "problems.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {

namespace {
double l1_density(const Simulation& sim) {
  const ExactRiemann exact({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.5);
  const Mesh& m = sim.mesh();
  double num = 0, den = 0;
  for (Index z = 0; z < m.num_zones(); ++z) {
    double cx = 0, cy = 0;
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    for (Index k = 0; k < n; ++k) cx += sim.x()[m.corner_point[b + k]] / n, cy += sim.y()[m.corner_point[b + k]] / n;
    num += sim.zone_area()[z] * std::abs(sim.density()[z] - exact.sample(cx, sim.time()).density);
    den += sim.zone_area()[z];
  }
  return num / den;
}
}  // namespace

TEST(Sod, ReproducesThePrototypeAt400ZonesWithEnergyAtRoundOff) {
  Simulation sim(testing::sod_problem(400));
  sim.advance_to(0.2);
  EXPECT_DOUBLE_EQ(sim.time(), 0.2);
  // NUMERICS/VERIFICATION (measured): 1783 cycles, L1_density = 1.467e-3, audit ~1e-15.
  EXPECT_NEAR(static_cast<double>(sim.cycle()), 1783.0, 20.0);
  EXPECT_NEAR(l1_density(sim), 1.467e-3, 0.02e-3);
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
