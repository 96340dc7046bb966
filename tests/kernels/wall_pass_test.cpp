// No point through a wall (docs/algorithm.md §10): a step that would move a point out of the
// domain through a wall fails like a tangled zone, and a run that cannot avoid it stops with
// the point and the wall named and its last good state dumped and marked.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "stagger/run.hpp"
#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// One zone of cold gas (no pressure: the points coast) on a wall along y = 0, free elsewhere.
// The bottom-right point slides along the wall past the wall's initial end; with
// `fall` > 0 the top-right point also falls and, beyond that end, meets the wall's line
// without any zone folding: the free surface rolling onto the wall of a Taylor bar.
constexpr const char* kScene = R"toml(
[time]
end = 1.0
[mesh]
generator = "rectangle"
x = [0.0, 1.0]
y = [0.0, 1.0]
nx = 1
ny = 1
[[material]]
name = "gas"
eos = "ideal_gas"
gamma = 1.4
[[region]]
name = "domain"
material = "gas"
density = 1.0
pressure = 0.0
velocity = ["x * (1 + y)", "-fall * x * y"]
[[boundary]]
tag = "bottom"
type = "wall"
[[boundary]]
tags = ["left", "right", "top"]
type = "free"
[output]
dump_interval = 0.1
)toml";

struct Fold {
  RunResult result;
  double lowest_y = 0;
  fs::path out;
};

Fold run_fold(const std::string& fall) {
  const fs::path dir = fs::temp_directory_path() / ("stagger_wall_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string text = kScene;
  text.replace(text.find("fall"), 4, fall);
  std::ofstream(dir / "fold.toml") << text;
  Scene scene = load_scene((dir / "fold.toml").string());
  Fold fold;
  fold.out = dir / ("out_" + fall);
  fs::remove_all(fold.out);
  scene.control.output_directory = fold.out.string();
  scene.control.progress = false;
  Simulation simulation(std::move(scene.problem));
  fold.result = run(simulation, scene.control);
  fold.lowest_y = 1e300;
  for (const double y : simulation.y()) fold.lowest_y = std::min(fold.lowest_y, y);
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
  // The state left in memory and in the last dump is on the domain's side of the wall.
  EXPECT_GE(fold.lowest_y, 0.0);
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

}  // namespace stagger
