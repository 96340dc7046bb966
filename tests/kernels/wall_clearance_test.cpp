// The wall check of a step tests only the points whose step is longer than their clearance
// budget (docs/algorithm.md §10, WallClearance): it must find exactly the point the full
// check finds, step after step, on closed walls and on walls with open ends (rays).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>

#include "hydro/boundary.hpp"
#include "hydro/simulation_impl.hpp"
#include "stagger/scene.hpp"
#include "support/files.hpp"
#include "support/scene_toml.hpp"

namespace stagger {
namespace {

namespace fs = std::filesystem;

// Points coast with fixed random velocities (drifting towards the walls) and random steps,
// mostly short, sometimes several zones long; an accepted step commits x += dt v_bar as the
// hydro step does, a rejected one reverses every velocity (the points head back inside).
// Returns the number of steps that crossed a wall.
int compare_checks(Simulation::Impl& s, double zone, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::size_t np = s.x.size();
  for (std::size_t p = 0; p < np; ++p) {
    s.vx[p] = unit(random), s.vy[p] = unit(random) - 0.3;
    s.vx_new[p] = s.vx[p] + 0.1 * unit(random), s.vy_new[p] = s.vy[p] + 0.1 * unit(random);
  }
  int crossings = 0;
  for (int step = 0; step < 3000; ++step) {
    const double dt = zone * (step % 37 == 36 ? 3.0 : 0.05) * (1 + unit(random)) / 2;
    const Index fast = step_wall_crossing(s, dt);
    const Index full = find_wall_crossing(s, dt);
    EXPECT_EQ(fast, full) << "step " << step;
    if (fast != full) return crossings;
    if (full >= 0) {
      ++crossings;
      s.wall_clearance.valid = false;  // as recompute_state after a rejected step
      for (std::size_t p = 0; p < np; ++p)
        s.vx[p] = -s.vx[p], s.vy[p] = -s.vy[p], s.vx_new[p] = -s.vx_new[p], s.vy_new[p] = -s.vy_new[p];
      continue;
    }
    for (std::size_t p = 0; p < np; ++p) {
      s.x[p] = s.x[p] + dt * 0.5 * (s.vx[p] + s.vx_new[p]);
      s.y[p] = s.y[p] + dt * 0.5 * (s.vy[p] + s.vy_new[p]);
    }
    ++s.cycle;
  }
  return crossings;
}

TEST(WallClearance, ClosedBoxFindsWhatTheFullCheckFinds) {
  Simulation::Impl s(load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/sedov.toml").problem);
  ASSERT_FALSE(s.wall_edges.empty());
  ASSERT_TRUE(s.wall_rays.empty());
  const int crossings = compare_checks(s, 0.04, 1);
  EXPECT_GT(crossings, 10);  // both outcomes were exercised
  EXPECT_LT(crossings, 2000);
}

TEST(WallClearance, OpenWallEndsFindWhatTheFullCheckFinds) {
  // A wall along y = 0 only: rays continue it beyond both ends.
  const fs::path dir = fs::temp_directory_path() / ("stagger_clearance_" + std::to_string(::getpid()));
  namespace toml = testing::toml;
  const std::string path = testing::write_text(
      dir / "open.toml", toml::time("1.0") + toml::rectangle("[0.0, 1.0]", "[0.0, 1.0]", 12, 12) + toml::ideal_gas() +
                             toml::gas_region() + toml::bottom_wall_free_elsewhere());
  Simulation::Impl s(load_scene(path).problem);
  fs::remove_all(dir);
  ASSERT_EQ(s.wall_rays.size(), 2u);
  const int crossings = compare_checks(s, 1.0 / 12, 2);
  EXPECT_GT(crossings, 10);
  EXPECT_LT(crossings, 2000);
}

}  // namespace
}  // namespace stagger
