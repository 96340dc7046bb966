#pragma once
// The ALE phase of a distributed run (docs/parallel.md, "ALE"): the decision from every
// rank's zones and a global minimum; the rezone and remap by the serial code on rank 0's
// gathered state; every rank's part (ghosts included) then gets the remapped state.
#include <memory>

#include "hydro/simulation_impl.hpp"
#include "parallel/mpi_collective.hpp"
#include "stagger/remap.hpp"

namespace stagger::parallel {

// The remap hook of a distributed part `s` (its step calls it where the serial step calls its
// remap): the ALE phase above, through the part's collective `c`.
std::shared_ptr<Remap> make_distributed_remap(Simulation::Impl& s, MpiCollective& c);

}  // namespace stagger::parallel
