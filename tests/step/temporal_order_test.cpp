// Second order in time (docs/algorithm.md §1, "Why this form"): a fixed smooth compression
// with the bulk viscosity active, run with fixed dt = h, h/2, h/4 against h/8. A first-order
// slip anywhere in the predictor-corrector (e.g. the predictor energy advanced by dt instead
// of dt/2, or q from v^n instead of v*) brings the observed order down to ~1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "stagger/simulation.hpp"
#include "support/copper.hpp"
#include "support/gas_problem.hpp"

namespace stagger {

namespace {

struct State {
  long cycles = 0;
  std::vector<double> x, vx, vy, e;
};

State state_of(const Simulation& sim) {
  State s;
  s.cycles = sim.cycle();
  s.x.assign(sim.x().begin(), sim.x().end());
  s.vx.assign(sim.velocity_x().begin(), sim.velocity_x().end());
  s.vy.assign(sim.velocity_y().begin(), sim.velocity_y().end());
  s.e.assign(sim.specific_internal_energy().begin(), sim.specific_internal_energy().end());
  return s;
}

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
  const State s = state_of(sim);
  double q_max = 0;
  for (double q : sim.artificial_viscosity()) q_max = std::max(q_max, q);
  EXPECT_GT(q_max, 1e-3) << "the viscosity must be active for the test to mean anything";
  return s;
}

// rz (docs/algorithm.md §19): a cylinder r < 1 of gas at rest in pressure, pushed inwards by
// v_r = -A sin(pi r) (zero on the axis and at the wall r = 1) with an axial shear
// v_z = B sin(pi r) that bends the zones: the hoop terms and the point radii of the force
// geometry (x^{n+1/2}) act every step; the ends z = 0, 0.25 are free. Same fixed-dt ladder as the planar case.
State run_rz_gas_with(double h, Viscosity viscosity) {
  Problem p = testing::gas_problem(testing::rectangle_mesh(0, 1, 0, 0.25, 16, 4, testing::unchecked()), 1.4, 0.0625,
                                   "temporal_order_rz");
  RegionSetup r = testing::uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double) { return -0.5 * std::sin(std::numbers::pi * x); };
  r.velocity_y = [](double x, double) { return 0.3 * std::sin(std::numbers::pi * x); };
  p.regions.push_back(r);
  testing::walls(p, {"right"});  // the bottom and top are free
  p.options.geometry = CoordinateSystem::rz;
  p.options.viscosity = viscosity;
  p.options.dt_max = h;
  Simulation sim(std::move(p));
  sim.advance_to(0.0625);
  return state_of(sim);
}

// The edge viscosity: the tensor q's switch is not smooth in time (below).
State run_rz_gas(double h) {
  return run_rz_gas_with(h, Viscosity::edge);
}

// rz, radial only: the same cylinder pushed inwards by v_r = -A sin(pi r), walls all round
// (the ends z = 0, 0.25 are planes of symmetry), so every point moves radially and the
// radii of the force geometry carry the whole rz part of the step.
State run_rz_radial(double h) {
  Problem p = testing::gas_problem(testing::rectangle_mesh(0, 1, 0, 0.25, 16, 4, testing::unchecked()), 1.4, 0.0625,
                                   "temporal_order_rz_radial");
  RegionSetup r = testing::uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double) { return -0.5 * std::sin(std::numbers::pi * x); };
  p.regions.push_back(r);
  testing::walls(p);
  p.options.geometry = CoordinateSystem::rz;
  p.options.viscosity = Viscosity::edge;
  p.options.dt_max = h;
  Simulation sim(std::move(p));
  sim.advance_to(0.0625);
  return state_of(sim);
}

// rz with strength: a copper cylinder (SI) whose elastic radial and axial motion, v_r = -A
// sin(pi r / R) and v_z = B sin(pi r / R) at t = 0, carries the deviatoric stress, its hoop
// term and the Jaumann rotation; fixed dt = h = 2^-27 s = 7.5e-9 s (the CFL limit is 2e-8 s) on a 1 cm
// cylinder.
//
// Both rz cases use the edge viscosity: the default tensor q switches on at div u = 0 with a
// finite linear term q2 C, so a sheared zone whose compression changes sign sees its force
// jump, and the ladder then shows first order wherever that happens (planar too); the bulk
// and edge viscosities vanish continuously there.
State run_rz_solid(double h) {
  Problem p;
  p.name = "temporal_order_rz_solid";
  p.mesh = testing::rectangle_mesh(0, 0.01, 0, 0.0025, 16, 4, testing::unchecked());
  p.materials.push_back(testing::piston_copper());
  p.materials.back().strength = Strength{45e9, 1e12};  // elastic: the yield cut is not smooth in time
  RegionSetup r;
  r.region = "domain";
  r.material = "copper";
  r.density = constant_field(8930.0);
  r.specific_internal_energy = constant_field(0.0);
  r.velocity_x = [](double x, double) { return -20.0 * std::sin(std::numbers::pi * x / 0.01); };
  r.velocity_y = [](double x, double) { return 10.0 * std::sin(std::numbers::pi * x / 0.01); };
  p.regions.push_back(r);
  testing::walls(p, {"right"});  // the bottom and top are free
  p.options.geometry = CoordinateSystem::rz;
  p.options.viscosity = Viscosity::edge;
  p.options.dt_max = h;
  p.t_end = 64 * 0x1p-27;  // dt = 2^-27 s: every t exact
  Simulation sim(std::move(p));
  sim.advance_to(p.t_end);
  return state_of(sim);
}

// Largest difference of positions, velocities and specific energies.
double difference(const State& a, const State& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.x.size(); ++i)
    d = std::max({d, std::abs(a.x[i] - b.x[i]), std::abs(a.vx[i] - b.vx[i]), std::abs(a.vy[i] - b.vy[i])});
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

// The ladder dt = h, h/2, h/4 against h/8: the observed orders.
struct Orders {
  double coarse, fine, e1, e2, e4;
};
template <class Run>
Orders orders_in_time(Run run, double h, long cycles) {
  const State s1 = run(h), s2 = run(h / 2), s4 = run(h / 4), ref = run(h / 8);
  EXPECT_EQ(s1.cycles, cycles);  // dt was h every cycle
  EXPECT_EQ(ref.cycles, 8 * cycles);
  const double e1 = difference(s1, ref), e2 = difference(s2, ref), e4 = difference(s4, ref);
  return {std::log2(e1 / e2), std::log2(e2 / e4), e1, e2, e4};
}

// Both orders >= 1.9.
template <class Run>
void expect_second_order_in_time(Run run, double h, long cycles) {
  const auto [order_coarse, order_fine, e1, e2, e4] = orders_in_time(run, h, cycles);
  std::printf("temporal order: errors %.3e %.3e %.3e, orders %.3f %.3f\n", e1, e2, e4, order_coarse, order_fine);
  EXPECT_GE(order_coarse, 1.9) << "errors " << e1 << " " << e2 << " " << e4;
  EXPECT_GE(order_fine, 1.9) << "errors " << e1 << " " << e2 << " " << e4;
  EXPECT_GT(e4, 1e3 * std::numeric_limits<double>::epsilon() * 1e-3);  // above the round-off floor
}

TEST(TemporalOrder, RzGasIsSecondOrder) {
  expect_second_order_in_time(run_rz_gas, 1.0 / 512, 32);
  // The same with the default tensor q, for the record (docs/algorithm.md §4.1, "Known limit").
  const Orders tensor = orders_in_time([](double h) { return run_rz_gas_with(h, Viscosity::tensor); }, 1.0 / 512, 32);
  std::printf("with the tensor q: errors %.3e %.3e %.3e, orders %.3f %.3f\n", tensor.e1, tensor.e2, tensor.e4,
              tensor.coarse, tensor.fine);
}

TEST(TemporalOrder, RzRadialCompressionIsSecondOrder) {
  expect_second_order_in_time(run_rz_radial, 1.0 / 512, 32);
}

TEST(TemporalOrder, RzElasticSolidIsSecondOrder) {
  expect_second_order_in_time(run_rz_solid, 0x1p-27, 64);
}

}  // namespace stagger
