#pragma once
// `stagger bench`: resolution ladders, throughput and stability stress runs (docs/benchmarks.md).
// Every measured run happens in its own child process (`stagger bench --one ...`, hidden),
// so that its peak RSS (VmHWM) is its own and a crash or hang cannot take the suite down.
#include <string>
#include <utility>
#include <vector>

namespace stagger::cli {

int bench_command(const std::vector<std::string>& args);
extern const char* const bench_help;

namespace bench {

using Overrides = std::vector<std::pair<std::string, std::string>>;
using Measures = std::vector<std::pair<std::string, double>>;

/// One measurement: a scene with overrides, run in a child process.
struct RunSpec {
  std::string suite, scene, option;  ///< labels of the CSV row
  std::string scene_path;
  Overrides overrides;
  int threads = 1;
  long max_cycles = 0;             ///< 0: run to time.end
  bool cycles_are_target = false;  ///< reaching max_cycles counts as completed (throughput, long runs)
  double refine = 1;               ///< ladder coordinate (mesh.refine), for observed orders
  double timeout_seconds = 900;
};

/// What the child reports back.
struct RunRecord {
  RunSpec spec;
  std::string status = "not run";
  long zones = 0, points = 0, cycles = 0;
  double setup_seconds = 0, wall_seconds = 0, zone_cycles_per_second = 0;
  double peak_rss_bytes = 0, baseline_rss_bytes = 0;
  double energy_audit = 0, t_end = 0, time = 0;
  bool has_strength = false, has_burn = false;
  Measures measures;  ///< error norms and derived diagnostic errors
};

/// The hidden `--one` subcommand: runs one scene in this process and prints the record as
/// "key<TAB>value" lines on stdout. Returns the exit code.
int run_one(const std::vector<std::string>& args);

/// Runs `spec` in a child process (this executable, `bench --one`), with a timeout.
RunRecord run_in_child(const RunSpec& spec);

}  // namespace bench
}  // namespace stagger::cli
