#pragma once
// What the distributed set-up (docs/parallel.md) reaches inside a Simulation: its state
// (DistributedAccess is a friend of Simulation), and the rank helpers and the one message tag
// every file of lib/src/parallel/ uses (the run's communicator is its own duplicate, so one
// tag keeps the messages apart from the caller's).
#include <mpi.h>

#include "hydro/simulation_impl.hpp"

namespace stagger {

struct DistributedAccess {
  static Simulation::Impl& impl(Simulation& s) { return *s.impl_; }
  static const Simulation::Impl& impl(const Simulation& s) { return *s.impl_; }
  // A part: the Lagrangian phase of `problem` without the built-in ALE (the distributed
  // remap takes its place, distributed_remap.cpp).
  static Simulation lagrangian_only(Problem problem) {
    return Simulation(std::move(problem), Simulation::LagrangianOnly{});
  }
};

namespace parallel {

constexpr int kHaloTag = 1717;

inline int comm_rank(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}
inline int comm_size(MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  return size;
}

}  // namespace parallel
}  // namespace stagger
