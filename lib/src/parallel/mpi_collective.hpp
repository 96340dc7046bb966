#pragma once
// The collective operations of a distributed run on MPI (docs/parallel.md): the
// implementation of hydro/collective.hpp's interface. Reductions are global minima (ties to
// the lowest global zone) and exact sums, so any number of ranks decides as the serial run
// does; the halo exchange iterates over the state table, so a new state array is exchanged
// too; the gather gives rank 0 the whole state for the dumps, the summary and the references.
#include <mpi.h>

#include <memory>
#include <vector>

#include "hydro/collective.hpp"
#include "hydro/simulation_impl.hpp"
#include "state/state_table.hpp"

namespace stagger::parallel {

// Values of one rank's entities that another rank holds as ghosts (or the reverse).
struct Neighbour {
  int rank = 0;
  std::vector<Index> send_points, send_zones, send_corners;  // this rank's owned ones (local)
  std::vector<Index> recv_points, recv_zones, recv_corners;  // this rank's ghosts (local)
  std::vector<double> send, recv;
};

class MpiCollective final : public Collective {
 public:
  MPI_Comm comm = MPI_COMM_NULL;
  int my_rank = 0, size = 1;
  std::vector<Neighbour> neighbours;
  std::vector<const StateField*> fields;           // the present state arrays, in table order
  std::vector<const StateField*> gathered_fields;  // those the whole state on rank 0 serves
  std::vector<const StateField*> remap_fields;     // those an ALE remap changes: the remapped ones, x and y
  std::vector<Index> own_corners;  // ALE only (the corner masses); own points and zones: the ghost flags
  // Rank 0: the whole state (only its gathered arrays, or all of them for an ALE remap), and
  // every rank's owned points, zones and (ALE) corners, global; the gather's buffers are
  // transient (docs/parallel.md, "Memory").
  std::unique_ptr<Simulation> whole;
  std::vector<std::vector<Index>> rank_points, rank_zones, rank_corners;
  // The ALE remap (docs/parallel.md, "ALE"): rank 0 keeps every rank's whole part (owned and
  // ghost points and zones, global) to send it the remapped state.
  std::vector<std::vector<Index>> part_points, part_zones;
  std::vector<MPI_Request> requests;
  // Halo statistics (docs/parallel.md): exchanges, messages and bytes sent, seconds.
  long exchanges = 0, messages = 0;
  double bytes = 0, halo_seconds = 0;

  ~MpiCollective() override;

  int rank() const override { return my_rank; }
  int ranks() const override { return size; }
  std::int64_t min_failure(const Simulation::Impl& s, std::int64_t local_code) override;
  DtChoice min_dt(const Simulation::Impl& s, DtChoice local) override;
  std::string zone_text(const Simulation::Impl& s, Index zone, const std::function<std::string(Index)>& text) override;
  Index min_point(const Simulation::Impl& s, Index local_point) override;
  std::string point_text(const Simulation::Impl& s, Index point,
                         const std::function<std::string(Index)>& text) override;
  void sum(std::span<ExactSum> sums) override;
  std::string agree(const std::string& text) override;
  bool any(bool local) override;
  void exchange(Simulation::Impl& s) override;
  const Simulation* gather(const Simulation::Impl& s) override;

  // Rank 0's whole state gets every rank's owned values of the arrays `list` (of `fields`),
  // one array at a time: the buffers stay one array of the whole problem long.
  void gather_fields(const Simulation::Impl& s, const std::vector<const StateField*>& list);

 private:
  // The text of a global zone or point, worded by its owner: the rank holding it as its own.
  std::string owner_text(const std::vector<Index>& global, const std::vector<unsigned char>& ghost, Index id,
                         const std::function<std::string(Index)>& text);
};

// The present state arrays of part `s`, in table order: those the exchange moves, those the
// gathers serve and those an ALE remap changes.
void list_fields(MpiCollective& c, const Simulation::Impl& s);

// Rank 0: what the gathers need, every rank's owned points and zones (and, for an ALE remap,
// corners) in global order, from the owners of the whole mesh's zones and points; and the
// whole state, whose arrays the first gather fills.
void set_up_gather(MpiCollective& c, std::unique_ptr<Simulation> whole, const std::vector<int>& zone_owner,
                   const std::vector<int>& point_owner);

}  // namespace stagger::parallel
