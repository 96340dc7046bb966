#pragma once
// `stagger run` under mpirun (docs/parallel.md): MPI is started only when the process was
// launched by mpirun (a plain `stagger run` never touches MPI), errors that every rank
// throws alike are reported once by rank 0, and any other error stops every rank.
#include <functional>
#include <string>

#include "stagger/error.hpp"
#include "stagger/problem.hpp"
#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"

namespace stagger::cli {

// An error every rank throws alike: rank 0 reports it, every rank exits with status 1.
struct CollectiveError : Error {
  using Error::Error;
};

struct MpiState {
  bool active = false;  // MPI started (this process runs under mpirun, built with MPI)
  int rank = 0, ranks = 1;
};
MpiState& mpi_state();

// Starts MPI when launched by mpirun (and the build has MPI); else does nothing.
void start_mpi_if_launched();
// MPI_Finalize (if started).
void finish_mpi();
// MPI_Abort: the other ranks may be waiting in a collective operation.
[[noreturn]] void abort_mpi();

// Under mpirun: every rank's digest of what it was started with (the scene file's text, the
// --set values, the output settings `outputs`: --out, --restart, ...) compared with rank
// 0's; a rank started otherwise ends every rank with the same CollectiveError naming it (a
// different scene was silently different physics, a different --out a deadlock). Collective.
void compare_start_on_every_rank(const std::string& scene_path,
                                 const std::vector<std::pair<std::string, std::string>>& overrides,
                                 const std::vector<std::pair<std::string, std::string>>& outputs);

// Runs `work` on every rank; an Error on some rank becomes the same CollectiveError on all.
void on_every_rank(const std::function<void()>& work);
// The scene, read on every rank (errors as on_every_rank's). Under MPI only rank 0 meshes it;
// the other ranks read it without its mesh, standing for it with rank 0's outline (source,
// region and tag names), since distribute() sends them their part (docs/parallel.md, "Memory").
Scene load_scene_on_every_rank(const std::string& path,
                               const std::vector<std::pair<std::string, std::string>>& overrides);
// The Simulation of this rank: the whole problem when serial, this rank's part under MPI.
Simulation distributed_simulation(Problem problem);

// A distributed run's per-rank figures (docs/parallel.md): rank 0 writes DIR/ranks.csv, one row
// per rank: zones and points held, neighbours, the ghost exchanges' messages, bytes and seconds,
// the rank's loop seconds and its peak resident set. Collective; nothing in a serial run.
void write_rank_statistics(const Simulation& simulation, const std::string& directory, double loop_seconds);
// This process's peak resident set so far, in bytes (getrusage; docs/parallel.md, "Memory").
double peak_resident_bytes();

}  // namespace stagger::cli
