#pragma once
// The built-in ALE phase (docs/ale.md): installed behind the remap hook of the Lagrangian
// step (stagger/remap.hpp) when ale.mode is not "lagrangian". It sees the whole state table
// of the simulation; the Lagrangian phase does not know it exists.
#include <memory>

#include "hydro/simulation_impl.hpp"
#include "stagger/remap.hpp"

namespace stagger {

// The ALE phase of `s` (which must outlive it): rezone (or the initial mesh for
// ale.mode = "eulerian"), remap of every field the state table marks remapped, the
// kinetic-energy fix-up. Throws stagger::Error for a state field it cannot carry.
std::shared_ptr<Remap> make_ale_remap(Simulation::Impl& s);

// rz: the planar masses of the massless axis points' corners (docs/algorithm.md §19) from the
// remapped subcell masses (docs/ale.md, "ALE in rz"); at set-up, after every remap and after
// a restore.
void ale_axis_masses(Simulation::Impl& s);

}  // namespace stagger
