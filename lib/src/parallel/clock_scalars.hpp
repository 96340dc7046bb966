#pragma once
// The run's clock scalars (time, time steps, cycle, energy budget) as a distributed run
// moves them: into a part's configuration (rank 0 to its rank) and, at a gather, from a part
// onto rank 0's whole state. Each list is in one place, so that it stays the serial state's.
#include "hydro/simulation_impl.hpp"
#include "parallel/wire.hpp"

namespace stagger::parallel {

// The clock of the whole problem's set-up, in a part's configuration.
void pack_clock(Packer& out, const Simulation::Impl& s);
void unpack_clock(Unpacker& in, Simulation::Impl& s);

// A part's clock onto rank 0's whole state at a gather: the scalars are the same on every
// rank (dt_zone is already global).
void copy_clock(const Simulation::Impl& from, Simulation::Impl& to);

}  // namespace stagger::parallel
