// The tensor viscosity in a run (docs/algorithm.md §4.1): Sedov keeps its mirror symmetry about
// the diagonal and its energy audit at round-off. The kernel itself is checked in
// tests/kernels/tensor_viscosity_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "stagger/simulation.hpp"
#include "support/gas_problem.hpp"

namespace stagger {

TEST(TensorViscosity, SedovKeepsItsMirrorSymmetryAndTheAuditAtRoundOff) {
  constexpr int n = 24;
  Problem p = testing::sedov_quarter_problem(n, 0.5);
  p.options.viscosity = Viscosity::tensor;
  p.options.hourglass = Hourglass::subzonal_triangles;
  p.options.hourglass_coefficient = 2;
  Simulation sim(std::move(p));
  sim.advance_to(0.5);
  ASSERT_GT(sim.cycle(), 100);
  // Zone (i, j) of the row-major grid mirrors zone (j, i) in the diagonal x = y.
  const auto rho = sim.density();
  double worst = 0, peak = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      worst = std::max(worst, std::abs(rho[j * n + i] - rho[i * n + j]) / rho[j * n + i]);
      peak = std::max(peak, rho[j * n + i]);
    }
  EXPECT_GT(peak, 2.0);  // a real shock
  EXPECT_LT(worst, 1e-11);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-13);
}

}  // namespace stagger
