#pragma once
// The collective operations of a distributed run (docs/parallel.md): what the step asks of
// the other ranks. A serial Simulation has none (Simulation::Impl::collective is null); the
// MPI implementation is in the stagger_parallel library (lib/src/parallel/), so the serial
// library carries no MPI symbols. Zone numbers crossing this interface are global (the
// serial run's) where the comments say so; the step calls every function on every rank in
// the same order.
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "hydro/exact_sum.hpp"
#include "hydro/kernels/time_step.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

class Collective {
 public:
  virtual ~Collective() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // The lowest failure code over the ranks: a code of this rank's zones (local numbering,
  // kNoFailure for none) in, the global code of the lowest failing global zone out.
  virtual std::int64_t min_failure(const Simulation::Impl& s, std::int64_t local_code) = 0;
  // The smallest time-step candidate over the ranks, ties to the lowest global zone: this
  // rank's choice (local zone) in, the global choice (global zone) out.
  virtual DtChoice min_dt(const Simulation::Impl& s, DtChoice local) = 0;
  // Text about global zone `zone`, made by its owner (`text` gets the owner's local index)
  // and handed to every rank.
  virtual std::string zone_text(const Simulation::Impl& s, Index zone,
                                const std::function<std::string(Index)>& text) = 0;
  // The lowest global point over the ranks: a local point (-1: none) in, a global one out.
  virtual Index min_point(const Simulation::Impl& s, Index local_point) = 0;
  // Text about global point `point`, made by its owner, handed to every rank.
  virtual std::string point_text(const Simulation::Impl& s, Index point,
                                 const std::function<std::string(Index)>& text) = 0;
  // Exact sums over the ranks, in place.
  virtual void sum(std::span<ExactSum> sums) = 0;
  // Ghost points, zones and corners get their owners' values of every present state array.
  virtual void exchange(Simulation::Impl& s) = 0;
  // Every rank passes a text; every rank gets the text of the lowest rank whose text is not
  // empty (empty when none is): errors met on some ranks, decisions of some ranks.
  virtual std::string agree(const std::string& text) = 0;
  // Whether `local` is true on any rank (one integer reduction): a decision of some ranks.
  virtual bool any(bool local) = 0;
  // Rank 0: the whole state, gathered into a serial Simulation (null on the other ranks).
  virtual const Simulation* gather(const Simulation::Impl& s) = 0;
};

}  // namespace stagger
