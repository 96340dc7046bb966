#pragma once
// The machine's own 1 -> 2 core scaling, beside the code's in `stagger bench scaling`
// (bench_probe.cpp, docs/parallel.md "Speed"): a STREAM-like triad over arrays far larger than
// the caches (the ceiling of a loop that streams from memory) and a register-only compute
// loop (the ceiling of one that does not), each run by 1 process, by 2 processes at once and
// by 1 process with 2 threads.
#include <string>

namespace stagger::cli::bench {

enum class ProbeKind { triad, compute };

struct ProbeResult {
  bool ok = false;      // every worker ran and its results checked
  std::string message;  // why not, when !ok
  double seconds = 0;   // the slowest worker's time for the timed passes
  double work = 0;      // bytes (triad: 24 per element and pass, STREAM's count) or flops (compute)
  double rate() const { return seconds > 0 ? work / seconds : 0; }
};

/// Runs the probe with `workers` processes at once (forked, started together) or, with
/// `threads`, one forked process with `workers` OpenMP threads. The work is split among the
/// workers (strong scaling, as the Sedov runs): triad arrays of `elements` doubles in all
/// (three arrays), `passes` timed passes after one untimed one; compute: `elements` chain
/// updates in all. The bench's own process stays free of OpenMP threads.
ProbeResult run_probe(ProbeKind kind, int workers, bool threads, long elements, int passes);

}  // namespace stagger::cli::bench
