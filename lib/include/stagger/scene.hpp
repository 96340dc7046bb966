#pragma once
/// @file scene.hpp
/// Scene files (TOML) translated into a Problem and a RunControl. See docs/scenes.md.
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "stagger/problem.hpp"
#include "stagger/run.hpp"

namespace stagger {

/// Parameters of the gas references, which verify.hpp takes as plain arguments.
struct ShockTubeReference {
  GasState left, right;  ///< states left and right of x0
  double gamma = 1.4, x0 = 0.5;
};
struct NohReference {
  double gamma = 5.0 / 3.0, density = 1.0, speed = 1.0;
  int nu = 2;  ///< 2 cylindrical (planar scene), 3 spherical (numerics.geometry = "rz")
};
struct SedovReference {
  double gamma = 1.4, density = 1.0;
  double energy_quarter = 0.244816;  ///< the energy deposited in the quarter plane (rz: per radian in z >= 0)
  int nu = 2;                        ///< 2 cylindrical (planar scene), 3 spherical (numerics.geometry = "rz")
};
struct SaltzmanReference {
  double piston_speed = 1.0, gamma = 5.0 / 3.0, density = 1.0;
};
struct TaylorGreenReference {
  double p0 = 1.0;
};

/// What a scene's [verification] resolved: the reference's name and its parameters, with
/// the defaults of verify.hpp, the scene's material constants and --set overrides applied.
/// RunControl::reference is the same reference as error norms; tools that need the exact
/// fields themselves (stagger-profile) build the solution classes of verify.hpp from this.
struct VerificationSetup {
  std::string name;  ///< "shock_tube", ..., "accuracy"; empty: the scene has no [verification]
  std::variant<std::monostate, ShockTubeReference, NohReference, SedovReference, SaltzmanReference,
               TaylorGreenReference, PistonParameters, ShellParameters, DetonationParameters, AccuracyParameters>
      parameters;
};

/// A scene file read and resolved: what `stagger run` passes to Simulation and run().
struct Scene {
  std::string file;                ///< path of the scene file
  Problem problem;                 ///< the set-up, ready for Simulation (move it in)
  RunControl control;              ///< output settings and the reference solution, for run()
  std::vector<std::string> notes;  ///< repairs made on import (e.g. reoriented zones)
  VerificationSetup verification;  ///< the [verification] reference and its parameters
  /// Set-ups that make no sense but may be meant (untagged boundary edges, a run of a few
  /// cycles, unit slips in strength or velocity): one line each, "FILE:LINE: key 'k': ...".
  /// `stagger check` and `stagger run` print them; docs/scenes.md "Warnings".
  std::vector<std::string> warnings;
};

/// Reads, meshes and validates a scene. `overrides` are ("section.key", "value") pairs
/// applied to the TOML before it is interpreted (the CLI's --set). Errors name the file,
/// the line and the key.
Scene load_scene(const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides = {});

/// Reads a scene as load_scene does but without meshing it: `outline` (the mesh's source,
/// region names and boundary tag names, no zones or points) stands for the mesh that another
/// process read. For the ranks of a distributed run other than 0, which get their part of the
/// mesh from rank 0 (docs/parallel.md, "Decomposition"): the checks that need the mesh's
/// zones, the whole-problem validation and the warnings are rank 0's alone.
Scene load_scene_without_mesh(const std::string& path,
                              const std::vector<std::pair<std::string, std::string>>& overrides, Mesh outline);

/// A human-readable description of the resolved set-up (`stagger check`).
std::string describe(const Scene& scene);

}  // namespace stagger
