#pragma once
/// @file scene.hpp
/// Scene files (TOML) translated into a Problem and a RunControl. See docs/scenes.md.
#include <string>
#include <utility>
#include <vector>

#include "stagger/problem.hpp"
#include "stagger/run.hpp"

namespace stagger {

/// A scene file read and resolved: what `stagger run` passes to Simulation and run().
struct Scene {
  std::string file;        ///< path of the scene file
  Problem problem;         ///< the set-up, ready for Simulation (move it in)
  RunControl control;      ///< output settings and the reference solution, for run()
  std::vector<std::string> notes;  ///< repairs made on import (e.g. reoriented zones)
  /// Set-ups that make no sense but may be meant (untagged boundary edges, a run of a few
  /// cycles, unit slips in strength or velocity): one line each, "FILE:LINE: key 'k': ...".
  /// `stagger check` and `stagger run` print them; docs/scenes.md "Warnings".
  std::vector<std::string> warnings;
};

/// Reads, meshes and validates a scene. `overrides` are ("section.key", "value") pairs
/// applied to the TOML before it is interpreted (the CLI's --set). Errors name the file,
/// the line and the key.
Scene load_scene(const std::string& path,
                 const std::vector<std::pair<std::string, std::string>>& overrides = {});

/// A human-readable description of the resolved set-up (`stagger check`).
std::string describe(const Scene& scene);

}  // namespace stagger
