#pragma once
// A part's halo (docs/parallel.md, "Ghost layers"): which of its zones and points are ghosts
// and who owns them, and the lists the ghost exchange sends and receives. The owners come
// from rank 0 in chunks, so that no other rank holds a map of the whole problem.
#include <mpi.h>

#include <vector>

#include "hydro/simulation_impl.hpp"
#include "parallel/mpi_collective.hpp"

namespace stagger::parallel {

// This rank's ghost points and zones (local), by owner rank.
struct GhostsByOwner {
  std::vector<std::vector<Index>> points, zones;
};

// The ghost flags of part `s` (its global numbers set) from the owner of every zone and point
// (`zone_owner` and `point_owner`: rank 0's, of `global_zones` and `global_points`; empty on
// the other ranks); returns its ghosts by owner.
GhostsByOwner mark_ghosts(Simulation::Impl& s, const std::vector<int>& zone_owner, const std::vector<int>& point_owner,
                          Index global_zones, Index global_points, int rank, int size, MPI_Comm comm);

// The part's zone ranges split into own and ghost runs.
void split_ranges(Simulation::Impl& s);

// ALE: the corners of the part's own zones, whose masses the remap's gather collects.
void list_own_corners(MpiCollective& c, const Simulation::Impl& s);

// The halo lists: this rank's ghosts, as global numbers to their owners, which answer with
// the lists they send; one Neighbour per rank this rank exchanges with (c.fields listed).
void connect_neighbours(MpiCollective& c, const Simulation::Impl& s, const GhostsByOwner& ghosts);

}  // namespace stagger::parallel
