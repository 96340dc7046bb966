// The clock's one serialiser (clock.hpp).
#include "state/clock.hpp"

#include <string>

namespace stagger {

void write_clock(io_detail::ByteWriter& out, const Clock& clock) {
  out.f64(clock.t);
  out.f64(clock.dt_last);
  out.f64(clock.dt_next);
  out.f64(clock.dt_control_prev);
  out.i64(clock.cycle);
  out.u8(clock.have_previous_forces ? 1 : 0);
  out.u8(static_cast<std::uint8_t>(clock.dt_reason));
  out.i64(clock.dt_zone);
  out.f64(clock.energy_initial);
  out.f64(clock.boundary_work);
  out.f64(clock.source_work);
  out.f64(clock.ale_fixup);
}

Clock read_clock(io_detail::ByteReader& in) {
  Clock clock;
  clock.t = in.f64();
  clock.dt_last = in.f64();
  clock.dt_next = in.f64();
  clock.dt_control_prev = in.f64();
  clock.cycle = static_cast<long>(in.i64());
  clock.have_previous_forces = in.u8() != 0;
  const std::uint8_t reason = in.u8();
  if (reason > static_cast<std::uint8_t>(Clock::DtReason::heat_flux))
    in.fail("is corrupt: unknown time-step reason " + std::to_string(reason));
  clock.dt_reason = static_cast<Clock::DtReason>(reason);
  clock.dt_zone = static_cast<Index>(in.i64());
  clock.energy_initial = in.f64();
  clock.boundary_work = in.f64();
  clock.source_work = in.f64();
  clock.ale_fixup = in.f64();
  return clock;
}

}  // namespace stagger
