#pragma once
// A part on its way from rank 0 to its rank (docs/parallel.md, "Memory"): the large arrays
// (its global numbers, its mesh's arrays) one message each, straight into the receiver's
// vectors; the rest (the mesh's names and tags, then the whole problem's flags, clock and
// walls) as one packed message, read after the part's set-up.
#include <mpi.h>

#include <memory>
#include <string>

#include "hydro/simulation_impl.hpp"
#include "parallel/part.hpp"

namespace stagger::parallel {

// Rank 0: rank `to`'s part (cut from the whole state `g`) to rank `to`.
void send_part(const Simulation::Impl& g, const Part& part, int to, MPI_Comm comm);

// Every other rank: its part's global numbers and mesh arrays into `part` and `mesh`; returns
// the packed rest.
std::string receive_part(Part& part, Mesh& mesh, MPI_Comm comm);

// The packed rest of a part of the whole state `g` whose mesh names are `local`'s.
std::string pack_part(const Simulation::Impl& g, const Mesh& local);

// The mesh's names and tags out of a packed part into `mesh` (`packed` is freed); returns what
// follows them, for set_up_part().
std::string unpack_mesh_names(std::string& packed, Mesh& mesh);

// A part's set-up on its mesh (`problem` carries it), then the whole problem's configuration
// read from `rest`: the flags that decide which arrays exist and which kernel variants run,
// the clock and the walls. Its state arrays are allocated, their values still to come.
std::unique_ptr<Simulation> set_up_part(Problem problem, std::string rest);

// The walls' points in the part's numbering, once its global numbers are in place: a wall
// point off this part becomes -2 - its number.
void number_walls_locally(Simulation::Impl& s);

}  // namespace stagger::parallel
