// No point through a wall (docs/algorithm.md §10): a step that would move a point out of the
// domain through a wall fails like a tangled zone, and a run that cannot avoid it stops with
// the point and the wall named and its last good state dumped and marked.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "stagger/error.hpp"
#include "stagger/run.hpp"
#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"
#include "support/files.hpp"
#include "support/gas_problem.hpp"
#include "support/run_scene.hpp"
#include "support/scene_toml.hpp"

namespace stagger {
namespace {

namespace fs = std::filesystem;

using testing::read_text;

// One zone of cold gas (no pressure: the points coast) on a wall along y = 0, free elsewhere.
// The bottom-right point slides along the wall past the wall's initial end; with
// `fall` > 0 the top-right point also falls and, beyond that end, meets the wall's line
// without any zone folding: the free surface rolling onto the wall of a Taylor bar. The
// numerics are pinned so that the points coast exactly (no viscosity, no hourglass forces) at
// a fixed dt with no time-step floor: the crossing is kinematics, whatever the defaults are
// (with them, a change of the viscosity or of the dt control could stop the run on a
// time-step collapse first).
std::string fold_scene(const std::string& fall) {
  namespace toml = testing::toml;
  return toml::time("1.0") + toml::rectangle("[0.0, 1.0]", "[0.0, 1.0]", 1, 1) + toml::ideal_gas() +
         toml::gas_region("1.0", "0.0") + "velocity = [\"x * (1 + y)\", \"-" + fall + " * x * y\"]\n" +
         toml::bottom_wall_free_elsewhere() + "[output]\ndump_interval = 0.1\n" +
         "[numerics]\nviscosity = \"bulk\"\nq1 = 0.0\nq2 = 0.0\nhourglass_coefficient = 0.0\n"
         "dt_init = 0.01\ndt_max = 0.01\ndt_min = 1e-12\nmax_retries = 3\n";
}

struct Fold {
  RunResult result;
  double lowest_y = 0;
  fs::path out;
};

Fold run_fold(const std::string& fall) {
  const fs::path dir = fs::temp_directory_path() / ("stagger_wall_" + std::to_string(::getpid()));
  const std::string path = testing::write_text(dir / "fold.toml", fold_scene(fall));
  Fold fold;
  fold.out = dir / ("out_" + fall);
  fs::remove_all(fold.out);
  testing::SceneRun scene_run = testing::run_scene(load_scene(path), fold.out);
  fold.result = std::move(scene_run.result);
  fold.lowest_y = 1e300;
  for (const double y : scene_run.simulation.y()) fold.lowest_y = std::min(fold.lowest_y, y);
  return fold;
}

}  // namespace

TEST(WallPass, APointThroughTheWallStopsTheRunWithTheLastGoodStateMarked) {
  const Fold fold = run_fold("1.2");
  const RunResult& r = fold.result;
  ASSERT_FALSE(r.completed) << "the falling point went through the wall unnoticed";
  // Point 3 (top right) falls through y = 0 beyond the wall's open end, point 1 at (1, 0).
  EXPECT_NE(r.message.find("point 3 moved"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("through the wall 'bottom'"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("open end, point 1"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("retries"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("last good state"), std::string::npos) << r.message;
  // The state left in memory and in the last dump is on the domain's side of the wall, within
  // the wall's round-off tolerance (1e-9 of the extent, about 2.7, docs/algorithm.md §10: the
  // coasting point stops 9e-10 below the line, where the step that would pass was refused).
  EXPECT_GE(fold.lowest_y, -3e-9);
  EXPECT_TRUE(r.summary.last_good_state);
  EXPECT_TRUE(fs::exists(fold.out / r.summary.last_dump));
  EXPECT_NE(read_text(fold.out / "fold.pvd").find("<!-- last good state"), std::string::npos);
  fs::remove_all(fold.out.parent_path());
}

TEST(WallPass, SlidingAlongTheWallPastItsEndIsNotACrossing) {
  // No fall: the wall's end point slides along y = 0 to x = 2, a wall length past the wall's
  // initial end, and the free points stay above it.
  const Fold fold = run_fold("0.0");
  ASSERT_TRUE(fold.result.completed) << fold.result.message;
  EXPECT_EQ(fold.lowest_y, 0.0);
  fs::remove_all(fold.out.parent_path());
}

// A wall is a body beyond its open ends (the ray), but not where the mesh's own boundary goes
// on along the wall's line: a box whose bottom is a wall for x < 0.5 and free for x > 0.5.
// The gas pushes the free half down through y = 0; the wall's ray over the free half used to
// call that "through the wall" and stop the run. Its ray there is dropped: the run completes
// and the free half moves below y = 0, while the wall half stays on it.
TEST(WallPass, AWallIsNotExtendedOverAFreeBoundaryOnItsLine) {
  Problem p = testing::gas_problem(testing::rectangle_mesh(1.0, 1.0, 8, 8), 1.4, 0.1);
  p.regions.push_back(testing::uniform_region(1.0, 10.0));
  // Split "bottom" at x = 0.5 into "bottom" (the wall) and "bottom_free".
  Mesh& mesh = p.mesh;
  BoundaryTag& bottom = mesh.tags[mesh.tag_index("bottom")];
  BoundaryTag free_part{"bottom_free", {}, {}};
  std::vector<std::array<Index, 2>> wall_edges;
  for (const auto& e : bottom.edges) (mesh.x[e[0]] + mesh.x[e[1]] > 1.0 ? free_part.edges : wall_edges).push_back(e);
  const auto points_of = [](const std::vector<std::array<Index, 2>>& edges) {
    std::vector<Index> points;
    for (const auto& e : edges) points.insert(points.end(), {e[0], e[1]});
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    return points;
  };
  bottom.edges = wall_edges;
  bottom.points = points_of(wall_edges);
  free_part.points = points_of(free_part.edges);
  mesh.tags.push_back(free_part);
  testing::walls(p, {"bottom", "left"});
  testing::boundaries(p, {"bottom_free", "right", "top"}, BoundaryKind::free);
  Simulation sim(std::move(p));
  ASSERT_NO_THROW(sim.advance_to(0.1));
  double lowest_free = 0, lowest_wall = 0;
  for (Index q = 0; q < static_cast<Index>(sim.y().size()); ++q) {
    if (sim.problem().mesh.y[q] != 0) continue;
    (sim.problem().mesh.x[q] > 0.5 ? lowest_free : lowest_wall) =
        std::min(sim.problem().mesh.x[q] > 0.5 ? lowest_free : lowest_wall, sim.y()[q]);
  }
  EXPECT_LT(lowest_free, -1e-3);
  EXPECT_EQ(lowest_wall, 0.0);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

}  // namespace stagger
