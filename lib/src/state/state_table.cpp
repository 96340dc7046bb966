// The state table (state_table.hpp): one entry per array of State.
#include "state/state_table.hpp"

#include <array>
#include <limits>
#include <utility>

namespace stagger {

namespace {

using I = State;
using Role = Simulation::OutputRole;
constexpr unsigned kC = kCheckpointed, kR = kRemapped, kD = kDumped;
constexpr double kNever = std::numeric_limits<double>::infinity();

// Order: points, zones, corners; the dumped arrays of each entity in the order of the dumps.
// Checkpointed: what the next cycle reads and the set-up cannot recompute (x, v, e, q, the
// lagged corner forces, stress, plastic strain, burn fraction; the masses, which an ALE
// remap changes). Remapped: what a remap must carry to the new mesh; the rest is recomputed
// from it (recompute_state) or is scratch.
const std::array kFields = {
    // Points.
    StateField{"x", &I::x, Entity::point, Presence::always, kC},
    StateField{"y", &I::y, Entity::point, Presence::always, kC},
    StateField{"x_half", &I::x_half, Entity::point, Presence::half_step},
    StateField{"y_half", &I::y_half, Entity::point, Presence::half_step},
    StateField{"vx", &I::vx, Entity::point, Presence::always, kC | kR | kD, 0.0, &I::vx_new, "velocity",
               Role::vector_x},
    StateField{"vy", &I::vy, Entity::point, Presence::always, kC | kR | kD, 0.0, &I::vy_new, "velocity",
               Role::vector_y},
    StateField{"vx_new", &I::vx_new, Entity::point, Presence::always},
    StateField{"vy_new", &I::vy_new, Entity::point, Presence::always},
    StateField{"vx_star", &I::vx_star, Entity::point, Presence::always},
    StateField{"vy_star", &I::vy_star, Entity::point, Presence::always},
    StateField{"point_mass", &I::point_mass, Entity::point, Presence::always, kC | kR},
    StateField{"ext_fx", &I::ext_fx, Entity::point, Presence::external},
    StateField{"ext_fy", &I::ext_fy, Entity::point, Presence::external},
    StateField{"src_fx", &I::src_fx, Entity::point, Presence::momentum_source},
    StateField{"src_fy", &I::src_fy, Entity::point, Presence::momentum_source},
    // Low parts of the compensated update: the state of the accumulation, so checkpointed and
    // exchanged; a remap moves the points and sets them to zero (docs/algorithm.md §20).
    StateField{"x_lo", &I::x_lo, Entity::point, Presence::compensated, kC},
    StateField{"y_lo", &I::y_lo, Entity::point, Presence::compensated, kC},
    StateField{"vx_lo", &I::vx_lo, Entity::point, Presence::compensated, kC, 0.0, &I::vx_lo_new},
    StateField{"vy_lo", &I::vy_lo, Entity::point, Presence::compensated, kC, 0.0, &I::vy_lo_new},
    StateField{"vx_lo_new", &I::vx_lo_new, Entity::point, Presence::compensated},
    StateField{"vy_lo_new", &I::vy_lo_new, Entity::point, Presence::compensated},
    StateField{"axis_ax", &I::axis_ax, Entity::point, Presence::rz, kC},
    StateField{"axis_ay", &I::axis_ay, Entity::point, Presence::rz, kC},
    // Zones.
    StateField{"zone_mass", &I::zone_mass, Entity::zone, Presence::always, kC | kR},
    StateField{"area", &I::area, Entity::zone, Presence::always},
    StateField{"rho", &I::rho, Entity::zone, Presence::always, kD, 0.0, nullptr, "density"},
    StateField{"p", &I::p, Entity::zone, Presence::always, kD, 0.0, nullptr, "pressure"},
    StateField{"e", &I::e, Entity::zone, Presence::always, kC | kR | kD, 0.0, &I::e_new, "specific_internal_energy"},
    StateField{"e_new", &I::e_new, Entity::zone, Presence::always},
    StateField{"q", &I::q, Entity::zone, Presence::always, kC | kD, 0.0, nullptr, "artificial_viscosity"},
    StateField{"c", &I::c, Entity::zone, Presence::always, kD, 0.0, nullptr, "sound_speed"},
    StateField{"rho_half", &I::rho_half, Entity::zone, Presence::edge_viscosity},
    StateField{"c_half", &I::c_half, Entity::zone, Presence::edge_viscosity},
    StateField{"sxx", &I::sxx, Entity::zone, Presence::strength, kC | kR | kD, 0.0, &I::sxx_new, "deviatoric_stress_xx",
               Role::deviator_xx},
    StateField{"syy", &I::syy, Entity::zone, Presence::strength, kC | kR | kD, 0.0, &I::syy_new, "deviatoric_stress_yy",
               Role::deviator_yy},
    StateField{"sxy", &I::sxy, Entity::zone, Presence::strength, kC | kR | kD, 0.0, &I::sxy_new, "deviatoric_stress_xy",
               Role::deviator_xy},
    StateField{"sxx_new", &I::sxx_new, Entity::zone, Presence::strength},
    StateField{"syy_new", &I::syy_new, Entity::zone, Presence::strength},
    StateField{"sxy_new", &I::sxy_new, Entity::zone, Presence::strength},
    StateField{"sxx_half", &I::sxx_half, Entity::zone, Presence::strength},
    StateField{"syy_half", &I::syy_half, Entity::zone, Presence::strength},
    StateField{"sxy_half", &I::sxy_half, Entity::zone, Presence::strength},
    StateField{"plastic", &I::plastic, Entity::zone, Presence::strength, kC | kR | kD, 0.0, &I::plastic_new,
               "plastic_strain"},
    StateField{"plastic_new", &I::plastic_new, Entity::zone, Presence::strength},
    StateField{"grad_xx", &I::grad_xx, Entity::zone, Presence::strength},
    StateField{"grad_xy", &I::grad_xy, Entity::zone, Presence::strength},
    StateField{"grad_yx", &I::grad_yx, Entity::zone, Presence::strength},
    StateField{"grad_yy", &I::grad_yy, Entity::zone, Presence::strength},
    StateField{"burn", &I::burn, Entity::zone, Presence::burn, kC | kR | kD, 0.0, &I::burn_new, "burn_fraction"},
    StateField{"burn_new", &I::burn_new, Entity::zone, Presence::burn},
    StateField{"lighting_time", &I::lighting_time, Entity::zone, Presence::burn, kR, kNever},
    StateField{"burn_length", &I::burn_length, Entity::zone, Presence::burn, kR, 1.0},
    StateField{"source_energy", &I::source_energy, Entity::zone, Presence::energy_source},
    StateField{"heat_kappa", &I::heat_kappa, Entity::zone, Presence::heat_flux},
    StateField{"heat_cx", &I::heat_cx, Entity::zone, Presence::heat_flux},
    StateField{"heat_cy", &I::heat_cy, Entity::zone, Presence::heat_flux},
    StateField{"heat_rate", &I::heat_rate, Entity::zone, Presence::heat_flux},
    // Corners.
    StateField{"corner_fx", &I::corner_fx, Entity::corner, Presence::always, kC},
    StateField{"corner_fy", &I::corner_fy, Entity::corner, Presence::always, kC},
    StateField{"corner_scratch", &I::corner_scratch, Entity::corner, Presence::momentum_source},
    // Constant subzonal masses (set-up; a remap carries them like the zone masses).
    StateField{"corner_mass", &I::corner_mass, Entity::corner, Presence::subzonal, kC | kR},
    // Median-mesh corner masses: constant in the Lagrangian phase, carried by the ALE remap.
    StateField{"ale_corner_mass", &I::ale_corner_mass, Entity::corner, Presence::ale, kC | kR},
};

}  // namespace

std::span<const StateField> state_fields() {
  return kFields;
}

bool present(const StepConfig& s, Presence presence) {
  switch (presence) {
    case Presence::always:
      return true;
    case Presence::strength:
      return s.any_strength;
    case Presence::burn:
      return s.any_burn;
    case Presence::edge_viscosity:
      return s.edge_viscosity;
    case Presence::half_step:
      return s.any_strength || s.edge_viscosity || s.has_external || s.has_sources;
    case Presence::external:
      return s.has_external;
    case Presence::momentum_source:
      return s.has_momentum_source;
    case Presence::energy_source:
      return s.has_energy_source;
    case Presence::subzonal:
      return s.subzonal;
    case Presence::ale:
      return s.ale;
    case Presence::rz:
      return s.rz;
    case Presence::compensated:
      return s.compensated;
    case Presence::heat_flux:
      return s.heat_flux;
  }
  return false;
}

Index entity_size(const Mesh& mesh, Entity entity) {
  switch (entity) {
    case Entity::point:
      return mesh.num_points();
    case Entity::zone:
      return mesh.num_zones();
    case Entity::corner:
      return mesh.num_corners();
  }
  return 0;
}

void allocate_state(State& s, const StepConfig& config, const Mesh& mesh) {
  for (const StateField& f : kFields) {
    if (present(config, f.presence)) (s.*f.member).assign(entity_size(mesh, f.entity), f.initial);
  }
}

void swap_new_into_current(State& s, const StepConfig& config) {
  for (const StateField& f : kFields) {
    if (f.next && present(config, f.presence)) (s.*f.member).swap(s.*f.next);
  }
}

}  // namespace stagger
