#pragma once
// A loaded scene run to its end (or to the error that stops it), as `stagger run` does.
#include <filesystem>
#include <utility>

#include "stagger/run.hpp"
#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"

namespace stagger::testing {

struct SceneRun {
  Simulation simulation;  ///< the state the run left in memory
  RunResult result;
};

/// Runs `scene` with its outputs in `out` and no progress line.
inline SceneRun run_scene(Scene scene, const std::filesystem::path& out) {
  scene.control.output_directory = out.string();
  scene.control.progress = false;
  SceneRun scene_run{Simulation(std::move(scene.problem)), {}};
  scene_run.result = run(scene_run.simulation, scene.control);
  return scene_run;
}

}  // namespace stagger::testing
