#pragma once
// The state of every part, from rank 0's serial set-up, bit for bit (docs/parallel.md,
// "Determinism" and "Memory"): one message per state array and rank, once every other rank
// has set its part up. Rank 0 sets its own part up last, once the whole state has dropped its
// arrays, its own values of them set aside (an array that is all +0.0 is not copied: its part
// gets zeros), so that the whole state and rank 0's part are never both complete. An ALE
// scene's whole state keeps every array: the serial remap runs on it (docs/parallel.md, "ALE").
#include <mpi.h>

#include <vector>

#include "hydro/simulation_impl.hpp"
#include "parallel/part.hpp"

namespace stagger::parallel {

// Rank 0's own part's values of the arrays the whole state dropped, in table order.
struct OwnState {
  std::vector<std::vector<double>> values;
  std::vector<unsigned char> zero;  // those all +0.0 (not kept)
};

// Rank 0: every other rank q its part's values (zones part_zones[q], points part_points[q]) of
// every present array of the whole state `whole`; its own part's values set aside.
OwnState send_state(Simulation::Impl& whole, const std::vector<std::vector<Index>>& part_zones,
                    const std::vector<std::vector<Index>>& part_points, const Part& own, MPI_Comm comm);

// Every other rank: its part's values of every present array, into its set-up part `s`.
void receive_state(Simulation::Impl& s, MPI_Comm comm);

// Rank 0, its part `s` set up: its values, from `kept` (or, for an ALE scene, from `whole`).
void fill_own_state(Simulation::Impl& s, const Simulation::Impl& whole, const Part& own, OwnState& kept);

}  // namespace stagger::parallel
