// No global mutable state: simulations in two threads of one process give bitwise the
// results each gives alone.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <thread>

#include "api_support.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

using api_test::expect_same_state;
using api_test::shock_tube;

TEST(SideBySide, TwoEqualSimulationsInTwoThreadsMatchOneAlone) {
  Simulation alone(shock_tube(200, 0.2));
  alone.advance_to(0.2);

  Simulation first(shock_tube(200, 0.2)), second(shock_tube(200, 0.2));
  std::thread a([&] { first.advance_to(0.2); });
  std::thread b([&] { second.advance_to(0.2); });
  a.join();
  b.join();
  ASSERT_GT(alone.cycle(), 500);
  expect_same_state(first, alone);
  expect_same_state(second, alone);
}

TEST(SideBySide, DifferentProblemsInTwoThreadsDoNotInterfere) {
  // A Sod tube and a stronger, mirrored tube with another gamma, stepping at the same time.
  auto sod = [] { return shock_tube(100, 0.12); };
  auto other = [] { return shock_tube(60, 0.05, 0.5, 0.2, 2.0, 5.0, 5.0 / 3.0); };
  Simulation sod_alone(sod()), other_alone(other());
  sod_alone.advance_to(0.12);
  other_alone.advance_to(0.05);

  Simulation sod_threaded(sod()), other_threaded(other());
  long sod_observed = 0, other_observed = 0;
  sod_threaded.set_observer([&](const Simulation&) { ++sod_observed; });
  other_threaded.set_observer([&](const Simulation&) { ++other_observed; });
  std::thread a([&] { sod_threaded.advance_to(0.12); });
  std::thread b([&] { other_threaded.advance_to(0.05); });
  a.join();
  b.join();
  expect_same_state(sod_threaded, sod_alone);
  expect_same_state(other_threaded, other_alone);
  EXPECT_EQ(sod_observed, sod_alone.cycle());
  EXPECT_EQ(other_observed, other_alone.cycle());
}

TEST(SideBySide, TwoDriverRunsWithOutputsInTwoThreadsMatchOneAlone) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(STAGGER_BINARY_DIR) / "api-side-by-side";
  fs::remove_all(root);
  auto control_for = [&](const std::string& name) {
    RunControl control;
    control.output_directory = (root / name).string();
    control.name = "sod";
    control.dump_interval = 0.025;
    control.checkpoints = false;
    control.reference = shock_tube_reference({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.5);
    return control;
  };
  Simulation alone(shock_tube(60, 0.1));
  const RunResult alone_result = run(alone, control_for("alone"));
  ASSERT_TRUE(alone_result.completed) << alone_result.message;

  Simulation first(shock_tube(60, 0.1)), second(shock_tube(60, 0.1));
  RunResult first_result, second_result;
  std::thread a([&] { first_result = run(first, control_for("first")); });
  std::thread b([&] { second_result = run(second, control_for("second")); });
  a.join();
  b.join();
  ASSERT_TRUE(first_result.completed) << first_result.message;
  ASSERT_TRUE(second_result.completed) << second_result.message;
  expect_same_state(first, alone);
  expect_same_state(second, alone);
  EXPECT_EQ(first_result.summary.errors, alone_result.summary.errors);
  EXPECT_EQ(second_result.summary.errors, alone_result.summary.errors);
  for (const char* name : {"first", "second"}) EXPECT_TRUE(fs::exists(root / name / "sod.pvd")) << name;
}

}  // namespace
}  // namespace stagger
