// Second order in time (docs/algorithm.md §1, "Why this form"): a fixed smooth compression
// with the bulk viscosity active, run with fixed dt = h, h/2, h/4 against h/8. A first-order
// slip anywhere in the predictor-corrector (e.g. the predictor energy advanced by dt instead
// of dt/2, or q from v^n instead of v*) brings the observed order down to ~1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "stagger/simulation.hpp"
#include "support/gas_problem.hpp"

namespace stagger {

namespace {

struct State {
  long cycles = 0;
  std::vector<double> x, vx, e;
};

// Gas at rest in pressure, pushed by v_x = -A sin(pi x) against the wall x = 0 of a closed
// tube: the left half compresses (q on, div v < 0), the right half expands. dt_max = h below
// the CFL limit fixes dt = h; h = 2^-k and t_end = 2^-4 make every t exact.
State run(double h) {
  Problem p = testing::gas_problem(testing::rectangle_mesh(0, 1, 0, 0.0625, 32, 2, testing::unchecked()), 1.4, 0.0625,
                                   "temporal_order");
  RegionSetup r = testing::uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double) { return -0.5 * std::sin(std::numbers::pi * x); };
  p.regions.push_back(r);
  testing::walls(p);
  p.options.dt_max = h;
  Simulation sim(std::move(p));
  sim.advance_to(0.0625);
  State s;
  s.cycles = sim.cycle();
  s.x.assign(sim.x().begin(), sim.x().end());
  s.vx.assign(sim.velocity_x().begin(), sim.velocity_x().end());
  s.e.assign(sim.specific_internal_energy().begin(), sim.specific_internal_energy().end());
  double q_max = 0;
  for (double q : sim.artificial_viscosity()) q_max = std::max(q_max, q);
  EXPECT_GT(q_max, 1e-3) << "the viscosity must be active for the test to mean anything";
  return s;
}

// Largest difference of positions, velocities and specific energies.
double difference(const State& a, const State& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.x.size(); ++i)
    d = std::max({d, std::abs(a.x[i] - b.x[i]), std::abs(a.vx[i] - b.vx[i])});
  for (std::size_t i = 0; i < a.e.size(); ++i) d = std::max(d, std::abs(a.e[i] - b.e[i]));
  return d;
}

}  // namespace

TEST(TemporalOrder, SecondOrderWithCompressionAndViscosity) {
  const double h = 1.0 / 512;
  const State s1 = run(h), s2 = run(h / 2), s4 = run(h / 4), ref = run(h / 8);
  EXPECT_EQ(s1.cycles, 32);  // dt was h every cycle
  EXPECT_EQ(ref.cycles, 256);
  const double e1 = difference(s1, ref), e2 = difference(s2, ref), e4 = difference(s4, ref);
  const double order_coarse = std::log2(e1 / e2), order_fine = std::log2(e2 / e4);
  RecordProperty("order_coarse", std::to_string(order_coarse));
  RecordProperty("order_fine", std::to_string(order_fine));
  EXPECT_GE(order_coarse, 1.8) << "errors " << e1 << " " << e2 << " " << e4;
  EXPECT_GE(order_fine, 1.8) << "errors " << e1 << " " << e2 << " " << e4;
  // ...and not the round-off floor: the differences are far above 1e-12.
  EXPECT_GT(e4, 1e-10);
}

}  // namespace stagger
