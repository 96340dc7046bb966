// Results are bitwise identical for any thread count (fixed-order gathers, no atomics).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <vector>

#include "stagger/simulation.hpp"
#include "support/gas_problem.hpp"

namespace stagger {

namespace {
std::vector<double> run_sedov(int threads) {
  omp_set_num_threads(threads);
  Problem p = testing::sedov_quarter_problem(70, 1.0, testing::unchecked());  // 4900 zones: threads engage (> 4096)
  p.options.viscosity = Viscosity::edge;
  p.options.check_corner_areas = false;
  Simulation sim(std::move(p));
  for (int i = 0; i < 100; ++i) sim.step();
  std::vector<double> state;
  for (auto field :
       {sim.x(), sim.y(), sim.velocity_x(), sim.velocity_y(), sim.specific_internal_energy(), sim.pressure()})
    state.insert(state.end(), field.begin(), field.end());
  state.push_back(sim.energy().relative_error);
  state.push_back(sim.dt());
  return state;
}
}  // namespace

TEST(Determinism, OneAndTwoThreadsGiveBitwiseTheSameState) {
  const auto one = run_sedov(1), two = run_sedov(2);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
}

}  // namespace stagger
