#pragma once
// The copper of apps/scenes/piston.toml (Mie-Gruneisen, elastic-perfectly plastic, SI units).
#include "stagger/materials.hpp"

namespace stagger::testing {

inline Material piston_copper() {
  Material m;
  m.name = "copper";
  m.eos = MieGruneisen{8930.0, 3940.0, 2.0, 1.49};
  m.strength = Strength{45e9, 90e6};
  return m;
}

}  // namespace stagger::testing
