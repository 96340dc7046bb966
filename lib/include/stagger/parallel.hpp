#pragma once
/// @file parallel.hpp
/// Distributed runs on MPI (docs/parallel.md): a Problem split over the ranks of a
/// communicator by METIS, each rank stepping its zones and their ghosts, with the same bits
/// as the serial run on any number of ranks. Part of the stagger_parallel library (built
/// when MPI and METIS are found, CMake option STAGGER_MPI).
#include <mpi.h>

#include <functional>

#include "stagger/simulation.hpp"

namespace stagger {

/// Sets up `problem` over the ranks of `comm` (collective: every rank passes the same
/// problem, e.g. from the same scene) and returns this rank's part: its zones (partitioned by
/// METIS) with the ghost layers the step needs. Rank 0 sets up the whole problem and sends
/// each rank its part; the other ranks use only the non-mesh parts of theirs, so their mesh
/// may be an outline (load_scene_without_mesh). On one rank it is a serial Simulation.
/// Throws stagger::Error, the same on every rank, for a set-up error or a problem that a
/// distributed run cannot take (periodic boundaries, fewer zones than ranks). An ALE remap
/// runs on rank 0 on the gathered state (docs/parallel.md, "ALE").
/// The communicator is duplicated: the run's messages never mix with the caller's.
Simulation distribute(Problem problem, MPI_Comm comm);

/// What one rank of a distributed run holds and what its ghost exchanges cost
/// (docs/parallel.md, "Measurements"); all zero for a serial Simulation.
struct HaloStatistics {
  long owned_zones = 0, ghost_zones = 0, owned_points = 0, ghost_points = 0;
  int neighbours = 0;  ///< ranks this rank exchanges ghosts with
  long exchanges = 0;  ///< ghost exchanges (one per cycle, plus fresh force evaluations)
  long messages = 0;   ///< messages sent (one per neighbour and exchange)
  double bytes = 0;    ///< bytes sent
  double seconds = 0;  ///< wall time inside the exchanges (packing, waiting, unpacking)
};
HaloStatistics halo_statistics(const Simulation& part);

/// Runs `work` on every rank of `comm` (collective); if it throws stagger::Error on some
/// ranks, every rank throws the error of the lowest of them, so that a failure in one rank's
/// part of a set-up (reading a file, meshing) stops every rank with the same message.
void on_every_rank(MPI_Comm comm, const std::function<void()>& work);

}  // namespace stagger
