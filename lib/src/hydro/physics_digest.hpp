#pragma once
// The digest of what defines a run's physics (docs/output.md, "Checkpoints"): mesh,
// materials, regions and their initial state, boundary conditions, sources and numerics -
// everything but the end time and the output settings. A checkpoint carries it; a restart
// compares it with the scene it is given and names each entry that differs.
#include <string>
#include <vector>

#include "hydro/simulation_impl.hpp"
#include "io/byte_stream.hpp"

namespace stagger {

// Everything that is fixed at set-up: the problem's parameters and, for the regions, hashes
// of the initial state the set-up computed from their functions (zone masses, energies,
// velocities, stresses), so that a changed density or pressure expression is seen.
// Call at the end of set-up, before the first step.
std::vector<DigestEntry> setup_digest(const Simulation::Impl& s);

// The functions of time that the set-up does not evaluate (prescribed velocity, applied
// pressure, manufactured sources), sampled at 17 times evenly spaced in [0, t_reference].
std::vector<DigestEntry> sampled_digest(const Simulation::Impl& s, double t_reference);

void write_digest(io_detail::ByteWriter& out, const std::vector<DigestEntry>& digest);
std::vector<DigestEntry> read_digest(io_detail::ByteReader& in);

// "" when the two agree; otherwise one line naming every entry that differs, by section
// and key, with both values where they are numbers (at most 12, then a count).
std::string digest_differences(const std::vector<DigestEntry>& saved, const std::vector<DigestEntry>& current);

}  // namespace stagger
