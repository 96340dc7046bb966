#pragma once
// Whole-scene checks once everything is read (docs/scenes.md "Warnings", docs/robustness.md):
// settings that make the run impossible are errors naming the key; set-ups that make no
// sense are warnings in Scene::warnings, printed by `stagger check` and at the start of
// `stagger run` (errors would stop legitimate runs).
#include <toml++/toml.h>

#include "stagger/scene.hpp"

namespace stagger::scene_detail {

/// Thresholds of the warnings (docs/scenes.md justifies them).
struct WarningThresholds {
  double min_cycles = 10;                                         ///< a run expected to last fewer cycles
  double max_cycles = 1e8;                                        ///< a run expected to last more cycles
  double yield_over_shear = 10;                                   ///< Y0 / mu above this
  double shear_over_bulk_low = 1e-3, shear_over_bulk_high = 1e3;  ///< mu / K outside
  double speed_over_sound = 10;                                   ///< |v| / c above this (where c > 0)
};

/// Throws stagger::Error "FILE:LINE: key 'boundary[i].tags': ..." for a boundary condition
/// that cannot hold where it lands (hydro/boundary_checks.hpp): before Problem::validate, so
/// that the message has the line.
void check_boundary_geometry(const toml::table& document, const Scene& scene);

/// Throws stagger::Error "FILE:LINE: key '...': ..." for a dump schedule above
/// output.max_dumps or a first time step below dt_min; appends warnings to scene.warnings.
void review_scene(const toml::table& document, Scene& scene, const WarningThresholds& limits = {});

}  // namespace stagger::scene_detail
