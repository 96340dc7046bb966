// Distributed runs (docs/parallel.md): the problem split over MPI ranks by METIS, each rank
// stepping its own zones and a few layers of ghost zones with the serial kernels, and the
// collective operations the step asks for (lib/src/hydro/collective.hpp). This file composes
// the set-up from its stages; each concept has its file in lib/src/parallel/:
//   partition (METIS, owners), part (ghost layers, local numbering), part_transfer and
//   state_transfer (a part and its state from rank 0), halo (ghost flags, exchange lists),
//   mpi_collective (reductions, the exchange, the gathers), distributed_remap (the ALE phase).
//
// Why the bits are the serial ones (docs/parallel.md, "Determinism"):
//  - rank 0 sets up the whole problem as the serial run does and sends each rank its part of
//    that state, so the initial state is the serial one bit for bit;
//  - a rank's zones, points and corners keep the serial (global) order, so each point sums
//    its corner forces in the serial order;
//  - ghost layers are deep enough that a rank's own zones and points see only correct
//    values during a step; after the step the owners' values overwrite the ghosts' (the
//    exchange iterates over the state table, so a new state array is exchanged too);
//  - failures and the time step are global minima (ties to the lowest global zone), and
//    totals are exact sums (hydro/exact_sum.hpp).
#include <malloc.h>

#include <climits>
#include <memory>
#include <string>
#include <vector>

#include "parallel/distributed_access.hpp"
#include "parallel/distributed_remap.hpp"
#include "parallel/halo.hpp"
#include "parallel/mpi_collective.hpp"
#include "parallel/part.hpp"
#include "parallel/part_transfer.hpp"
#include "parallel/partition.hpp"
#include "parallel/state_transfer.hpp"
#include "stagger/error.hpp"
#include "stagger/parallel.hpp"

namespace stagger {

namespace parallel {
namespace {

// The set-up's working state from stage to stage; rank 0 alone holds the whole problem's.
struct Distribution {
  MPI_Comm comm = MPI_COMM_NULL;  // the run's own (the collective's duplicate)
  int rank = 0, size = 1;
  std::vector<int> owner;                                   // rank 0: global zone -> rank
  std::unique_ptr<Simulation> whole;                        // rank 0: the serial set-up
  Simulation::Impl* g = nullptr;                            // rank 0: its state
  Index global_zones = 0, global_points = 0;                // the whole mesh's
  std::vector<std::vector<Index>> part_zones, part_points;  // rank 0: every other part's, global
  Part part;                                                // this rank's
  Problem part_problem;                                     // this rank's part's, its mesh to come
  std::unique_ptr<Simulation> local;                        // this rank's part, once set up
};

void reject_periodic_boundaries(const Problem& problem) {
  for (const auto& bc : problem.boundaries)
    if (bc.kind == BoundaryKind::periodic)
      throw Error("periodic boundary '" + bc.tag + "': a distributed run cannot take periodic boundaries yet " +
                  "(docs/parallel.md); run on one rank");
}

// The part's problem: everything but the mesh and the energy deposits (their energy comes
// with the copied state).
Problem part_problem_of(const Problem& problem) {
  Problem part_problem;
  part_problem.name = problem.name;
  part_problem.materials = problem.materials;
  part_problem.regions = problem.regions;
  part_problem.boundaries = problem.boundaries;
  part_problem.sources = problem.sources;
  part_problem.options = problem.options;
  part_problem.t_end = problem.t_end;
  part_problem.ale = problem.ale;
  return part_problem;
}

std::unique_ptr<MpiCollective> make_collective(MPI_Comm comm, int rank, int size) {
  auto collective = std::make_unique<MpiCollective>();
  MPI_Comm_dup(comm, &collective->comm);
  collective->my_rank = rank;
  collective->size = size;
  return collective;
}

// Rank 0 partitions the scene's mesh (its errors reach every rank). METIS runs before the
// set-up (which keeps the mesh's connectivity), so that its work space is handed back before
// the whole state is built (docs/parallel.md, "Memory").
void partition(Distribution& d, const Problem& problem) {
  on_every_rank(d.comm, [&] {
    if (d.rank != 0) return;  // the other ranks' mesh may be an outline (load_scene_without_mesh)
    if (problem.mesh.num_zones() < d.size)
      throw Error("the mesh has " + std::to_string(problem.mesh.num_zones()) + " zones, fewer than the " +
                  std::to_string(d.size) + " ranks");
    d.owner = partition_zones(problem.mesh, d.size);
  });
  malloc_trim(0);
}

// Rank 0 sets up the whole problem as the serial run does (its errors reach every rank); the
// other ranks drop their copy of the mesh, so they never hold more than the scene's mesh and
// their part.
void set_up_whole(Distribution& d, Problem& problem) {
  on_every_rank(d.comm, [&] {
    if (d.rank == 0) d.whole = std::make_unique<Simulation>(std::move(problem));
  });
  problem = Problem{};
  malloc_trim(0);  // the other ranks' copy of the mesh, before their part arrives
  d.g = d.rank == 0 ? &DistributedAccess::impl(*d.whole) : nullptr;
}

// The whole mesh's sizes on every rank; an error on every rank if METIS left one without zones.
void broadcast_sizes(Distribution& d) {
  int sizes[3] = {d.g ? d.g->mesh().num_zones() : 0, d.g ? d.g->mesh().num_points() : 0, -1};
  if (d.g) {
    std::vector<Index> per_rank(d.size, 0);
    for (int o : d.owner) ++per_rank[o];
    for (int q = d.size - 1; q >= 0; --q)
      if (per_rank[q] == 0) sizes[2] = q;
  }
  MPI_Bcast(sizes, 3, MPI_INT, 0, d.comm);
  d.global_zones = sizes[0], d.global_points = sizes[1];
  if (sizes[2] >= 0) throw Error("METIS left rank " + std::to_string(sizes[2]) + " without zones; run on fewer ranks");
}

// Rank 0 cuts each other rank's part (mesh, walls, configuration) and sends it, and keeps its
// own part's zones and points (its mesh it cuts once the whole state is gone); every other
// rank receives its part and returns what follows the mesh's names, for its set-up.
std::string deliver_parts(Distribution& d) {
  if (!d.g) {
    std::string packed = receive_part(d.part, d.part_problem.mesh, d.comm);
    return unpack_mesh_names(packed, d.part_problem.mesh);
  }
  // Two layers: the corner forces of the zones around this rank's points and their predicted
  // velocities; a third for the edge viscosity's neighbours (docs/parallel.md).
  const int layers = d.g->edge_viscosity ? 3 : 2;
  d.part_zones.resize(d.size);
  d.part_points.resize(d.size);
  for (int q = d.size - 1; q >= 1; --q) {
    Part part = make_part(d.g->mesh(), d.owner, q, layers);
    send_part(*d.g, part, q, d.comm);
    d.part_zones[q] = std::move(part.zones);
    d.part_points[q] = std::move(part.points);
  }
  // Rank 0's own zones and points; the global-to-local maps are rebuilt for its mesh.
  d.part = make_part(d.g->mesh(), d.owner, 0, layers);
  d.part.zone_local = {};
  d.part.point_local = {};
  malloc_trim(0);  // the parts' meshes and the other ranks' packed parts
  return {};
}

// Rank 0's own mesh, cut now that the whole state's arrays are gone; returns what follows its
// mesh's names, for its set-up.
std::string cut_own_mesh(Distribution& d) {
  number_part(d.part, d.global_zones, d.global_points);
  std::string packed = pack_part(*d.g, part_names(d.g->mesh(), d.part));
  std::string rest = unpack_mesh_names(packed, d.part_problem.mesh);
  Mesh& mine = d.part_problem.mesh;
  part_mesh_arrays(d.g->mesh(), d.part, [&](auto member, auto& v) { (mine.*member).swap(v); });
  d.part.zone_local = {};
  d.part.point_local = {};
  return rest;
}

// The ranks for which `here` is true set their part up (collective: errors reach every rank).
void set_up_part_where(Distribution& d, bool here, std::string& rest) {
  on_every_rank(d.comm, [&] {
    if (here) d.local = set_up_part(std::move(d.part_problem), std::move(rest));
  });
}

// Every rank's part set up (on its mesh, `rest` its configuration) with the serial set-up's
// state, bit for bit (state_transfer.hpp): the other ranks set their parts up and receive;
// rank 0 sets its own up last, from the values it set aside.
void set_up_every_part(Distribution& d, std::string& rest) {
  set_up_part_where(d, d.rank != 0, rest);
  OwnState kept;
  if (d.g)
    kept = send_state(*d.g, d.part_zones, d.part_points, d.part, d.comm);
  else
    receive_state(DistributedAccess::impl(*d.local), d.comm);
  malloc_trim(0);
  if (d.g) rest = cut_own_mesh(d);
  set_up_part_where(d, d.rank == 0, rest);
  if (d.g) fill_own_state(DistributedAccess::impl(*d.local), *d.g, d.part, kept);
}

// The part's global numbers (ascending): a binary search finds a global zone or point in it.
// The ALE remap sends every part its remapped state: rank 0 keeps every part's numbers.
void adopt_global_numbers(Distribution& d, MpiCollective& c) {
  Simulation::Impl& s = DistributedAccess::impl(*d.local);
  s.global_zone = std::move(d.part.zones);
  s.global_point = std::move(d.part.points);
  d.part = Part{};
  if (d.g && d.g->remap) {
    d.part_zones[0] = s.global_zone;
    d.part_points[0] = s.global_point;
    c.part_zones = std::move(d.part_zones);
    c.part_points = std::move(d.part_points);
  }
  d.part_zones = {};
  d.part_points = {};
  number_walls_locally(s);
}

// What the collective needs: ownership (the owner of every zone and point, from rank 0), the
// halo lists and the gathers.
void set_up_collective(Distribution& d, MpiCollective& c) {
  Simulation::Impl& s = DistributedAccess::impl(*d.local);
  std::vector<int> point_owner;
  if (d.g) point_owner = point_owners(d.g->mesh(), d.owner);
  const GhostsByOwner ghosts =
      mark_ghosts(s, d.owner, point_owner, d.global_zones, d.global_points, d.rank, d.size, d.comm);
  split_ranges(s);
  if (s.problem.ale.mode != AleMode::lagrangian) list_own_corners(c, s);
  list_fields(c, s);
  connect_neighbours(c, s, ghosts);
  if (d.rank == 0) set_up_gather(c, std::move(d.whole), d.owner, point_owner);
}

}  // namespace
}  // namespace parallel

void on_every_rank(MPI_Comm comm, const std::function<void()>& work) {
  const int rank = parallel::comm_rank(comm);
  std::string message;
  int failed = INT_MAX;
  try {
    work();
  } catch (const Error& error) {
    message = error.what();
    failed = rank;
  }
  int lowest = INT_MAX;
  MPI_Allreduce(&failed, &lowest, 1, MPI_INT, MPI_MIN, comm);
  if (lowest == INT_MAX) return;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, lowest, comm);
  message.resize(length);
  MPI_Bcast(message.data(), length, MPI_CHAR, lowest, comm);
  throw Error(message);
}

Simulation distribute(Problem problem, MPI_Comm comm) {
  using namespace parallel;
  const int size = comm_size(comm), rank = comm_rank(comm);
  if (size == 1) return Simulation(std::move(problem));
  reject_periodic_boundaries(problem);
  auto collective = make_collective(comm, rank, size);
  Distribution d;
  d.comm = collective->comm, d.rank = rank, d.size = size;
  d.part_problem = part_problem_of(problem);
  partition(d, problem);
  set_up_whole(d, problem);
  broadcast_sizes(d);
  // The parts' meshes and configurations first; the state arrays follow once every rank has
  // set its part up, one message per array, so that no rank holds its part's state twice
  // (docs/parallel.md, "Memory").
  std::string rest = deliver_parts(d);
  set_up_every_part(d, rest);
  adopt_global_numbers(d, *collective);
  set_up_collective(d, *collective);
  d.whole.reset();
  d.owner = {};
  Simulation::Impl& s = DistributedAccess::impl(*d.local);
  // ALE: the distributed remap, which runs the whole problem's on rank 0.
  if (s.problem.ale.mode != AleMode::lagrangian) s.remap = make_distributed_remap(s, *collective);
  s.collective = std::move(collective);
  malloc_trim(0);  // hand the set-up's and the distribution's temporaries back to the OS
  return std::move(*d.local);
}

}  // namespace stagger
