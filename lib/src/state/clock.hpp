#pragma once
// The scalars of a run beside its arrays: time, cycle, the time-step history, the energy
// ledger and the ALE fix-up total. One serialiser (write_clock / read_clock) serves the
// checkpoints and the distributed runs' part transfer, so no list of them is written twice.
#include <cstdint>

#include "io/byte_stream.hpp"
#include "stagger/mesh.hpp"  // Index

namespace stagger {

struct Clock {
  // What limited the last dt (Simulation::dt_limit).
  enum class DtReason : std::uint8_t { cfl, growth, initial, maximum, retry, landing, heat_flux };

  double t = 0;                // current time
  double dt_last = 0;          // the last step's dt
  double dt_next = 0;          // the dt the next step tries
  double dt_control_prev = 0;  // the last controlled dt (growth limit)
  long cycle = 0;              // completed cycles
  bool have_previous_forces = false;
  DtReason dt_reason = DtReason::cfl;
  Index dt_zone = -1;  // zone that limited the last CFL/volume candidate
  // The energy ledger (Simulation::energy, docs/algorithm.md §11).
  double energy_initial = 0, boundary_work = 0, source_work = 0;
  double ale_fixup = 0;  // kinetic energy the ALE remap's fix-up moved into internal energy (cumulative)
};

// Every field of the clock, in one fixed order, in the library's binary format.
void write_clock(io_detail::ByteWriter& out, const Clock& clock);
// The inverse of write_clock; a bad value (an unknown dt reason) is an error of `in`'s source.
Clock read_clock(io_detail::ByteReader& in);

}  // namespace stagger
