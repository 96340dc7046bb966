#pragma once
// The step's messages (diagnostics.cpp): every error the Lagrangian step throws for a zone, a
// point or a time step is worded here.
#include <cstdint>
#include <string>

#include "hydro/simulation_impl.hpp"

namespace stagger {

// A zone failure's code (zone_status.hpp) as an error: "cycle, t: zone ... <what>".
[[noreturn]] void throw_zone_failure(const Simulation::Impl& s, std::int64_t code, const std::string& what_step);
// Remedies for a tangled step that the scene has not already taken (docs/algorithm.md §9).
std::string tangling_remedies(const HydroOptions& o, AleMode ale_mode);
// dt below dt_min: the limiting zone and what to do.
[[noreturn]] void throw_dt_collapse(const Simulation::Impl& s, double dt);
// A step still tangled after the retries: the tangled zone, or the point through a wall.
[[noreturn]] void throw_tangled_step(Simulation::Impl& s, double dt_taken, int attempt);

}  // namespace stagger
