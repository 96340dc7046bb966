#pragma once
/// @file remap.hpp
/// The ALE hook: an optional remap phase called after each Lagrangian step. The Lagrangian
/// phase does not know whether one exists (docs/algorithm.md §13).
#include <span>

#include "stagger/mesh.hpp"

namespace stagger {

/// The Lagrangian state handed to a remap, consistent at the end of a step. A remap may
/// move points and rewrite the conserved fields, the masses included (a conservative remap
/// moves mass between zones); what it writes must stay consistent (momentum sum m_p v_p,
/// energy sum m_z e_z + kinetic). The spans are valid during the remap() call only.
struct RemapState {
  const Mesh& mesh;                                   ///< topology (positions below are the current ones)
  double time;                                        ///< time at the end of the step just taken
  long cycle;                                         ///< number of that step (1 for the first)
  std::span<double> x, y, velocity_x, velocity_y;     ///< point fields (writable)
  std::span<double> specific_internal_energy;         ///< zone field (writable)
  std::span<double> stress_xx, stress_yy, stress_xy;  ///< empty without strength
  /// Zone and point masses (writable: constant in the Lagrangian phase, moved by a remap).
  std::span<double> zone_mass, point_mass;
  std::span<const double> zone_area;  ///< zone areas of x, y at the call (read-only)
};

/// Interface of a remap phase. Return true if anything was changed, so that the
/// simulation recomputes geometry, density and pressure.
/// Installed with Simulation::set_remap; called once per completed cycle, before the
/// observer. The contract is spelled out in docs/api.md ("The observer and the remap").
class Remap {
 public:
  virtual ~Remap() = default;
  /// Remaps `state` in place. Returns false if nothing changed (the run is then bitwise
  /// that without a remap), true to have geometry, density and pressure recomputed.
  virtual bool remap(RemapState& state) = 0;
};

/// The default: keeps the Lagrangian mesh as it is.
class NoRemap final : public Remap {
 public:
  bool remap(RemapState&) override { return false; }  ///< changes nothing
};

}  // namespace stagger
