// The run's clock scalars on the move in a distributed run (clock_scalars.hpp).
#include "parallel/clock_scalars.hpp"

namespace stagger::parallel {

void pack_clock(Packer& out, const Simulation::Impl& s) {
  out.value(s.t), out.value(s.dt_last), out.value(s.dt_next), out.value(s.dt_control_prev);
  out.value(s.cycle), out.value(s.have_previous_forces), out.value(s.dt_zone);
  out.value(s.energy_initial), out.value(s.boundary_work), out.value(s.source_work);
}

void unpack_clock(Unpacker& in, Simulation::Impl& s) {
  in.value(s.t), in.value(s.dt_last), in.value(s.dt_next), in.value(s.dt_control_prev);
  in.value(s.cycle), in.value(s.have_previous_forces), in.value(s.dt_zone);
  in.value(s.energy_initial), in.value(s.boundary_work), in.value(s.source_work);
}

void copy_clock(const Simulation::Impl& from, Simulation::Impl& to) {
  to.t = from.t, to.dt_last = from.dt_last, to.dt_next = from.dt_next, to.dt_control_prev = from.dt_control_prev;
  to.cycle = from.cycle, to.have_previous_forces = from.have_previous_forces;
  to.energy_initial = from.energy_initial, to.boundary_work = from.boundary_work, to.source_work = from.source_work;
  to.dt_reason = from.dt_reason, to.dt_zone = from.dt_zone, to.ale_fixup = from.ale_fixup;
}

}  // namespace stagger::parallel
