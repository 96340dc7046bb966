// The per-cycle hooks of the API: the remap phase (ALE hook) and the observer.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numeric>
#include <vector>

#include "api_support.hpp"
#include "stagger/remap.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

using api_test::expect_same_state;
using api_test::shock_tube;

/// An example remap: it moves no point, but checks the contract of stagger::Remap — called
/// once per cycle, after the Lagrangian step, with the simulation's own consistent state.
class CheckingRemap final : public Remap {
 public:
  explicit CheckingRemap(const Simulation& simulation) : simulation_(simulation) {}

  bool remap(RemapState& state) override {
    ++calls;
    const Mesh& mesh = simulation_.mesh();
    const std::size_t points = mesh.num_points(), zones = mesh.num_zones();
    EXPECT_EQ(&state.mesh, &mesh);
    // Time and cycle advance by one cycle per call, and are the simulation's.
    EXPECT_EQ(state.cycle, last_cycle + 1);
    EXPECT_GT(state.time, last_time);
    EXPECT_EQ(state.cycle, simulation_.cycle());
    EXPECT_EQ(state.time, simulation_.time());
    last_cycle = state.cycle;
    last_time = state.time;
    // Sizes: point fields per point, zone fields per zone, no stress without strength.
    for (auto field : {state.x, state.y, state.velocity_x, state.velocity_y}) EXPECT_EQ(field.size(), points);
    EXPECT_EQ(state.point_mass.size(), points);
    EXPECT_EQ(state.zone_mass.size(), zones);
    EXPECT_EQ(state.zone_area.size(), zones);
    EXPECT_EQ(state.specific_internal_energy.size(), zones);
    EXPECT_TRUE(state.stress_xx.empty() && state.stress_yy.empty() && state.stress_xy.empty());
    // Masses positive and conserved; areas positive and those of the current positions.
    for (double m : state.zone_mass) EXPECT_GT(m, 0.0);
    for (double m : state.point_mass) EXPECT_GT(m, 0.0);
    const double mass = std::accumulate(state.zone_mass.begin(), state.zone_mass.end(), 0.0);
    if (initial_mass == 0) initial_mass = mass;
    EXPECT_NEAR(mass, initial_mass, 1e-14 * initial_mass);
    const std::vector<double> areas = zone_areas(mesh, state.x, state.y);
    for (std::size_t z = 0; z < zones; ++z) {
      EXPECT_GT(state.zone_area[z], 0.0);
      EXPECT_NEAR(state.zone_area[z], areas[z], 1e-12 * areas[z]) << "zone " << z;
    }
    // The spans show the simulation's state, not a copy of another time.
    EXPECT_TRUE(api_test::bitwise_equal(state.x, simulation_.x()));
    EXPECT_TRUE(api_test::bitwise_equal(state.specific_internal_energy, simulation_.specific_internal_energy()));
    return false;  // nothing changed
  }

  long calls = 0, last_cycle = 0;
  double last_time = 0, initial_mass = 0;

 private:
  const Simulation& simulation_;
};

constexpr double t_end = 0.08;

TEST(RemapHook, ExampleRemapIsCalledOncePerCycleWithAConsistentState) {
  Simulation simulation(shock_tube(60, t_end));
  auto remap = std::make_shared<CheckingRemap>(simulation);
  simulation.set_remap(remap);
  simulation.advance_to(t_end);
  EXPECT_GT(simulation.cycle(), 50);
  EXPECT_EQ(remap->calls, simulation.cycle());
  EXPECT_EQ(remap->last_time, t_end);
}

TEST(RemapHook, NoRemapAndAPassiveRemapLeaveTheLagrangianSolutionBitwise) {
  Simulation without(shock_tube(60, t_end)), with_stub(shock_tube(60, t_end)), checked(shock_tube(60, t_end));
  with_stub.set_remap(std::make_shared<NoRemap>());
  auto remap = std::make_shared<CheckingRemap>(checked);
  checked.set_remap(remap);
  for (Simulation* s : {&without, &with_stub, &checked}) s->advance_to(t_end);
  expect_same_state(with_stub, without);
  expect_same_state(checked, without);
  EXPECT_EQ(remap->calls, checked.cycle());
}

TEST(RemapHook, RemovingTheRemapStopsTheCalls) {
  Simulation simulation(shock_tube(40, t_end));
  auto remap = std::make_shared<CheckingRemap>(simulation);
  simulation.set_remap(remap);
  for (int i = 0; i < 5; ++i) simulation.step();
  simulation.set_remap(nullptr);
  simulation.advance_to(t_end);
  EXPECT_EQ(remap->calls, 5);
}

TEST(Observer, IsCalledOncePerCycleAfterTheRemapWithTheFinishedCycle) {
  Simulation simulation(shock_tube(60, t_end));
  auto remap = std::make_shared<CheckingRemap>(simulation);
  simulation.set_remap(remap);
  std::vector<long> cycles;
  std::vector<double> times;
  simulation.set_observer([&](const Simulation& s) {
    EXPECT_EQ(&s, &simulation);
    EXPECT_EQ(remap->calls, s.cycle()) << "the remap of this cycle runs before the observer";
    cycles.push_back(s.cycle());
    times.push_back(s.time());
  });
  simulation.advance_to(t_end);
  ASSERT_EQ(static_cast<long>(cycles.size()), simulation.cycle());
  for (std::size_t k = 0; k < cycles.size(); ++k) EXPECT_EQ(cycles[k], static_cast<long>(k) + 1);
  for (std::size_t k = 1; k < times.size(); ++k) EXPECT_GT(times[k], times[k - 1]);
  EXPECT_EQ(times.back(), t_end);
}

TEST(Observer, SeesEveryCycleOfADriverRunAndCanBeRemoved) {
  Simulation simulation(shock_tube(40, t_end));
  long calls = 0;
  simulation.set_observer([&](const Simulation&) { ++calls; });
  RunControl control;
  control.output_directory = std::string(STAGGER_BINARY_DIR) + "/api-observer";
  control.dumps = false;
  control.checkpoints = false;
  const RunResult result = run(simulation, control);
  ASSERT_TRUE(result.completed) << result.message;
  EXPECT_EQ(calls, simulation.cycle());

  Simulation other(shock_tube(40, t_end));
  calls = 0;
  other.set_observer([&](const Simulation&) { ++calls; });
  other.step();
  other.set_observer(nullptr);
  other.advance_to(t_end);
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace stagger

namespace stagger {

TEST(Observer, MovesWithTheSimulation) {
  Simulation first(api_test::shock_tube(20, 0.05));
  const Simulation* seen = nullptr;
  first.set_observer([&seen](const Simulation& s) { seen = &s; });
  Simulation second(std::move(first));
  second.step();
  EXPECT_EQ(seen, &second);
  Simulation third(api_test::shock_tube(10, 0.05));
  third = std::move(second);
  third.step();
  EXPECT_EQ(seen, &third);
}

}  // namespace stagger
