// stagger: the command line. Every subcommand is a thin layer over the public API; this
// file only dispatches and turns every error into exit status 1 and ONE line on stderr.
#include <csignal>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <exception>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "bench.hpp"
#include "commands.hpp"
#include "mpi_session.hpp"
#include "stagger/error.hpp"

namespace {

const char* const main_help =
    R"(usage: stagger COMMAND [options]      (stagger COMMAND --help for details)

Staggered-grid Lagrangian hydrodynamics with elastic-plastic strength.

commands:
  run SCENE.toml    run a scene: [--out DIR] [--set KEY=VALUE]... [--threads N]
                    [--restart CHECKPOINT] [--quiet]
  check SCENE.toml  parse, mesh, validate and set up a scene and print the resolved
                    set-up: [--set KEY=VALUE]... [--out DIR]
  mesh IN.geo|.msh  mesh a geometry and report counts and quality: [-o OUT.msh|OUT.vtu]
                    [--set NAME=VALUE]... [--triangles accept|subdivide|reject] [--check]
  bench [SUITE...]  benchmarks (ladders, throughput, stress) into CSVs: [--quick]
                    [--out DIR] [--threads N] (docs/benchmarks.md)

Scene files are TOML (docs/scenes.md); example and verification scenes are in
apps/scenes/. --set KEY=VALUE overrides any value by its dotted path, e.g.
--set mesh.refine=2 --set time.end=0.1 --set numerics.viscosity=edge.

Output contract of 'stagger run' (in --out DIR, default output/<scene name>):
  summary.json   scene, zones, points, cycles, t_end, wall_seconds,
                 zone_cycles_per_second, threads, status ("completed" or the error
                 that stopped the run), energy {initial, final, boundary_work,
                 source_work, ale_fixup, relative_error}, momentum, errors {L1_density, ...} and
                 diagnostics {...} when the scene has a [verification] reference
  history.csv    one row per recorded cycle: time, cycle, dt, kinetic, internal,
                 boundary_work, source_work, total, relative_energy_error,
                 momentum_x, momentum_y, ale_fixup
  <scene>.pvd    ParaView collection listing every dump (timestep, file); the last
                 one at the final time
  *.vtu          unstructured grids, points in double precision; zone fields
                 density, pressure, specific_internal_energy, artificial_viscosity,
                 sound_speed, region, and where present deviatoric_stress_xx/_yy/_xy,
                 von_mises, plastic_strain, burn_fraction; point field velocity
                 (3 components)
  *.checkpoint   restart files (stagger run SCENE --restart FILE continues bitwise)

Exit status: 0 on success; 1 on any error, with one line 'stagger: error: ...' on
stderr naming the file, line and key (or zone, point, cycle and time) and what to do.
)";

using Command = std::function<int(const std::vector<std::string>&)>;

struct Entry {
  const char* name;
  Command command;
};

// The subcommands; `bench` is the harness of apps/bench/.
const std::vector<Entry>& commands() {
  static const std::vector<Entry> table = {
      {"run", stagger::cli::run_command},
      {"check", stagger::cli::check_command},
      {"mesh", stagger::cli::mesh_command},
      {"bench", stagger::cli::bench_command},
  };
  return table;
}

// One line: newlines inside a message become "; ".
std::string one_line(std::string message) {
  for (std::size_t position = 0; (position = message.find('\n', position)) != std::string::npos;)
    message.replace(position, 1, "; ");
  while (!message.empty() && (message.back() == ' ' || message.back() == ';')) message.pop_back();
  return message;
}

// Under mpirun (docs/parallel.md): an error every rank throws alike is reported by rank 0
// and every rank exits; any other error is reported where it happened and stops every rank.
int fail(const std::string& message, bool collective = false) {
  const auto& mpi = stagger::cli::mpi_state();
  std::cout.flush();
  if (!mpi.active || mpi.rank == 0 || !collective) {
    std::cerr << "stagger: error: "
              << (mpi.active && mpi.rank != 0 ? "rank " + std::to_string(mpi.rank) + ": " : std::string())
              << one_line(message) << std::endl;
  }
  if (mpi.active && mpi.ranks > 1 && !collective) stagger::cli::abort_mpi();
  stagger::cli::finish_mpi();
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f) then fails the write (EFBIG), reported like a full disk,
  // instead of killing the process with no message.
  std::signal(SIGXFSZ, SIG_IGN);
#ifdef __GLIBC__
  // A large mesh's arrays come and go in phases (the mesh build, the set-up, a distributed
  // run's parts): with a fixed threshold each is mapped on its own and handed back to the
  // system when freed, where glibc's sliding threshold keeps freed arrays resident in the
  // heap and raises the peak (docs/parallel.md, "Memory").
  mallopt(M_MMAP_THRESHOLD, 256 * 1024);
#endif
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty()) return fail("no command given; see 'stagger --help'");
    if (args[0] == "-h" || args[0] == "--help" || args[0] == "help") {
      std::cout << main_help;
      return 0;
    }
    for (const auto& entry : commands())
      if (args[0] == entry.name) {
        const int status = entry.command(std::vector<std::string>(args.begin() + 1, args.end()));
        stagger::cli::finish_mpi();
        return status;
      }
    std::string names;
    for (const auto& entry : commands()) names += (names.empty() ? "" : ", ") + std::string(entry.name);
    return fail("unknown command '" + args[0] + "'; commands: " + names + " (see 'stagger --help')");
  } catch (const stagger::cli::CollectiveError& error) {
    return fail(error.what(), true);
  } catch (const stagger::Error& error) {
    return fail(error.what());
  } catch (const stagger::cli::UsageError& error) {
    return fail(error.what());
  } catch (const std::string& error) {  // gmsh throws strings
    return fail("gmsh: " + error);
  } catch (const std::exception& error) {
    return fail(std::string("internal error: ") + error.what() + " (please report it)");
  }
}
