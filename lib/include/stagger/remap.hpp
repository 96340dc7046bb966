#pragma once
/// @file remap.hpp
/// The ALE hook: an optional remap phase called after each Lagrangian step. The Lagrangian
/// phase does not know whether one exists (NUMERICS.md section 10).
#include <span>

#include "stagger/mesh.hpp"

namespace stagger {

/// The Lagrangian state handed to a remap, consistent at the end of a step. A remap may
/// move points and rewrite the conserved fields; it must keep the zone and point masses
/// consistent with what it writes.
struct RemapState {
  const Mesh& mesh;  ///< topology (positions below are the current ones)
  double time;
  long cycle;
  std::span<double> x, y, velocity_x, velocity_y;
  std::span<double> specific_internal_energy;
  std::span<double> stress_xx, stress_yy, stress_xy;  ///< empty without strength
  std::span<const double> zone_mass, point_mass, zone_area;
};

/// Interface of a remap phase. Return true if anything was changed, so that the
/// simulation recomputes geometry, density and pressure.
class Remap {
public:
  virtual ~Remap() = default;
  virtual bool remap(RemapState& state) = 0;
};

/// The default: keeps the Lagrangian mesh as it is.
class NoRemap final : public Remap {
public:
  bool remap(RemapState&) override { return false; }
};

}  // namespace stagger
