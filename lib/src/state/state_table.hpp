#pragma once
// The state as one table (docs/architecture.md, "The state table"): every point, zone and
// corner array of State with where it lives, when it exists and what it takes part in. Allocation, checkpoint/restore,
// the swap of new values into the current state and the .vtu dumps iterate over this table; a remap or a halo exchange
// iterates over it too.
#include <span>
#include <vector>

#include "stagger/mesh.hpp"
#include "stagger/simulation.hpp"  // OutputRole
#include "state/state.hpp"

namespace stagger {

enum class Entity { point, zone, corner };

// When an array exists (is sized to its entity); absent arrays stay empty.
enum class Presence {
  always,
  strength,         // some material has strength
  burn,             // some material has a programmed burn
  edge_viscosity,   // numerics.viscosity = "edge"
  half_step,        // x^{n+1/2} kept: strength, edge q, applied pressure or sources
  external,         // applied pressure or a momentum source
  momentum_source,  // manufactured momentum source
  energy_source,    // manufactured energy source
  subzonal,         // numerics.hourglass = "subzonal" or "subzonal_triangles"
  ale,              // ale.mode is not "lagrangian"
  rz,               // numerics.geometry = "rz"
  compensated,      // numerics.compensated_update
  heat_flux,        // numerics.heat_flux_c1 or heat_flux_c2 > 0
};

// What an array takes part in (bit flags).
enum StateFlag : unsigned {
  kCheckpointed = 1u << 0,  // written by Simulation::checkpoint (the rest is recomputed or scratch)
  kRemapped = 1u << 1,      // carried by a remap (the rest is recomputed by recompute_state or scratch)
  kDumped = 1u << 2,        // written to the .vtu dumps under `output_name`
};

using StateArray = std::vector<double> State::*;

struct StateField {
  const char* name;  // the State member (and the field's name in checkpoints)
  StateArray member;
  Entity entity;
  Presence presence;
  unsigned flags = 0;
  double initial = 0.0;       // value at allocation
  StateArray next = nullptr;  // the end-of-step value swapped into `member` at commit
  const char* output_name = nullptr;
  Simulation::OutputRole output_role = Simulation::OutputRole::scalar;
};

// The table, in the order of the dumps (docs/output.md).
std::span<const StateField> state_fields();

bool present(const StepConfig& config, Presence presence);
Index entity_size(const Mesh& mesh, Entity entity);

// Sizes every present array of the table to its entity, filled with its initial value.
void allocate_state(State& s, const StepConfig& config, const Mesh& mesh);
// Commit of a step: the new values become the current ones (swaps, no copies).
void swap_new_into_current(State& s, const StepConfig& config);

}  // namespace stagger
