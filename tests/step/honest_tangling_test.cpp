// Honest tangling (docs/algorithm.md §9): whatever the options, a run that cannot go on stops
// with the zone named, and what it leaves behind - the state in memory, the last dump, the
// .pvd and summary.json - is the last good state, with no crossing zone in it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "hydro/kernels/zone_validity.hpp"
#include "stagger/run.hpp"
#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"
#include "support/files.hpp"
#include "support/run_scene.hpp"

namespace stagger {
namespace {

namespace fs = std::filesystem;

using testing::read_text;

Index crossing_zones(const Simulation& simulation) {
  const Mesh& mesh = simulation.mesh();
  const auto x = simulation.x(), y = simulation.y();
  Index count = 0;
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    ZoneVertices v;
    for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c, ++v.n) {
      v.x[v.n] = x[mesh.corner_point[c]];
      v.y[v.n] = y[mesh.corner_point[c]];
    }
    count += zone_crosses(v) ? 1 : 0;
  }
  return count;
}

// The blast in a box with the old default numerics (bulk q, gamma hourglass): it tangles within
// ~50 cycles. With the corner-area check off it used to "complete" with hundreds of
// self-crossing zones.
void expect_honest_stop(bool check_corner_areas) {
  const fs::path out = fs::temp_directory_path() /
                       ("stagger_tangle_" + std::to_string(check_corner_areas) + "_" + std::to_string(::getpid()));
  fs::remove_all(out);
  Scene scene = load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/blast_box.toml",
                           {{"numerics.viscosity", "bulk"},
                            {"numerics.hourglass", "gamma"},
                            {"numerics.hourglass_coefficient", "0.1"},
                            {"numerics.check_corner_areas", check_corner_areas ? "true" : "false"},
                            {"time.end", "0.3"},
                            {"output.dump_interval", "0.01"}});
  const testing::SceneRun scene_run = testing::run_scene(std::move(scene), out);
  const Simulation& simulation = scene_run.simulation;
  const RunResult& result = scene_run.result;

  ASSERT_FALSE(result.completed) << "the gamma-hourglass blast was expected to tangle";
  EXPECT_LT(simulation.time(), 0.3);
  EXPECT_NE(result.message.find("tangled"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("zone "), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("last good state"), std::string::npos) << result.message;
  // The remedy offered is one the scene has not taken.
  EXPECT_NE(result.message.find("subzonal_triangles"), std::string::npos) << result.message;
  EXPECT_EQ(crossing_zones(simulation), 0);
  for (const double a : simulation.zone_area()) ASSERT_GT(a, 0);

  // The last dump is the state in memory, marked in the .pvd and the summary.
  const std::string pvd = read_text(out / "blast_box.pvd");
  EXPECT_NE(pvd.find("<!-- last good state"), std::string::npos);
  EXPECT_EQ(pvd.find("--", pvd.find("<!-- last good state") + 4), pvd.find("-->", pvd.find("<!-- last good state")));
  ASSERT_FALSE(result.summary.last_dump.empty());
  EXPECT_TRUE(result.summary.last_good_state);
  EXPECT_EQ(result.summary.last_dump_time, simulation.time());
  EXPECT_TRUE(fs::exists(out / result.summary.last_dump));
  EXPECT_NE(read_text(out / "summary.json").find("\"last_good_state\""), std::string::npos);
  fs::remove_all(out);
}

TEST(HonestTangling, AFailedRunLeavesItsLastGoodStateMarked) {
  expect_honest_stop(true);
}

TEST(HonestTangling, CrossingZonesStopTheRunEvenWithTheCornerCheckOff) {
  expect_honest_stop(false);
}

TEST(HonestTangling, ACompletedRunHasNoLastGoodStateMark) {
  const fs::path out = fs::temp_directory_path() / ("stagger_tangle_ok_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const RunResult result =
      testing::run_scene(load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/sod.toml", {{"time.end", "0.02"}}),
                         out)
          .result;
  ASSERT_TRUE(result.completed) << result.message;
  EXPECT_FALSE(result.summary.last_good_state);
  EXPECT_EQ(read_text(out / "summary.json").find("last_good_state"), std::string::npos);
  EXPECT_EQ(read_text(out / "sod.pvd").find("last good state"), std::string::npos);
  fs::remove_all(out);
}

}  // namespace
}  // namespace stagger
