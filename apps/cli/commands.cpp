// stagger run / check / mesh: thin layers over the public API (scene.hpp, simulation.hpp,
// run.hpp, output.hpp, meshgen.hpp, mesh.hpp).
#include "commands.hpp"

#include <malloc.h>
#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "arguments.hpp"
#include "mpi_session.hpp"
#include "stagger/error.hpp"
#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/output.hpp"
#include "stagger/run.hpp"
#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"

namespace stagger::cli {

const char* const run_help =
    R"(usage: stagger run SCENE.toml [options]

Loads the scene, runs it to time.end and writes the output directory:
  summary.json, history.csv, <scene>.pvd with its .vtu dumps, and checkpoints.

options:
  --out DIR             output directory (default: output/<scene name>)
  --set KEY=VALUE       override a scene value by its dotted TOML path, e.g.
                        --set mesh.refine=2 --set numerics.cfl=0.1
                        --set region[0].density=2 (repeatable; VALUE is a TOML
                        value: number, true/false, "string", [array]; a bare word
                        is taken as a string)
  --threads N           number of OpenMP threads (default: OpenMP's choice)
  --restart CHECKPOINT  continue from a checkpoint written by an earlier run
  --replace             take an output directory that holds another scene's results
                        by removing them (without it such a directory is refused)
  --quiet               no progress line and no summary (errors still go to stderr)
  -h, --help            this help

The output directory is locked for the run (a second run into it fails, naming the
first one's pid); a fresh run removes the previous run's <scene>.pvd,
<scene>_NNNNNN.vtu and checkpoint there first. Nothing else is removed. Warnings about the set-up (docs/scenes.md) are printed
on stderr before the first step.

A progress line (cycle, time, dt, ETA) is shown on stderr: refreshed in place on a
terminal, one line every 10 s otherwise (logs). At the end
a summary is printed: cycles, final time, zone-cycles per second, the energy audit and
any error norms. Exit status: 0 if the run reached time.end, 1 otherwise (the reason is
one line on stderr and in summary.json's "status").

SIGINT (Ctrl-C) or SIGTERM ends the run after the cycle in progress: a checkpoint and a
final dump are written, summary.json's status is "interrupted", and the exit status is
130 (SIGINT) or 143 (SIGTERM). A second signal ends the program at once (every file
written is whole: each is written under a private name and renamed).
)";

const char* const check_help =
    R"(usage: stagger check SCENE.toml [--set KEY=VALUE]... [--out DIR]

Parses the scene, meshes it, validates every value, sets up the initial state (without
stepping) and prints the resolved set-up (mesh counts and quality, materials, regions,
boundary conditions, numerical options, outputs). Also checks that the output directory
could be created and written (nothing is created) and that the dump schedule stays
within output.max_dumps. Set-ups that make no sense but may be meant (untagged boundary
edges, fewer than 10 cycles, unit slips in strength or velocity) are printed as
'stagger: warning:' lines on stderr. Exit status 0 if the scene is valid (also with
warnings); otherwise 1 with the same one-line error that 'stagger run' would give.

options:
  --set KEY=VALUE   as for 'stagger run'
  --out DIR         the output directory to check (default: output/<scene name>)
  -h, --help        this help
)";

const char* const mesh_help =
    R"(usage: stagger mesh IN.geo|IN.msh [options]

Meshes a .geo file with gmsh (or reads a .msh), checks and orients it, and prints the
zone, point, region and tag counts and the mesh quality (areas, aspect ratio, smallest
angle, non-convex zones).

options:
  -o, --output OUT.msh|OUT.vtu   write the mesh (MSH 4.1, or VTK with the region zone
                                 field and one point field per boundary tag)
  --set NAME=VALUE               override a .geo parameter (like gmsh -setnumber)
  --triangles accept|subdivide|reject
                                 what to do with triangles left after recombination
                                 (default accept)
  --check                        exit 1 if any zone is non-convex
  --gmsh-time-limit SECONDS      wall-time limit of the gmsh child process (default 600;
                                 0: none)
  --gmsh-memory-limit MIB        memory (address-space) limit of the gmsh child process
                                 (default 8192; 0: none)
  --max-points N                 refuse a .geo whose mesh would have more points, as
                                 estimated from its curves' mesh (default 5e6; 0: none)
  --allow-geo-commands           allow .geo commands that reach outside the mesh
                                 (SystemCall, Printf > file, Exit, Sleep, Save, ...):
                                 this runs arbitrary code, use it on trusted files only
  -h, --help                     this help
)";

namespace {

bool wants_help(const std::vector<std::string>& args) {
  for (const auto& arg : args)
    if (arg == "-h" || arg == "--help") return true;
  return false;
}

std::string single_positional(const Arguments& arguments, const std::string& command, const std::string& what) {
  if (arguments.positional().size() != 1)
    throw UsageError("'" + command + "' needs exactly one " + what + " (got " +
                     std::to_string(arguments.positional().size()) + "); see '" + command + " --help'");
  return arguments.positional().front();
}

std::vector<std::pair<std::string, std::string>> overrides_of(const Arguments& arguments) {
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const auto& text : arguments.values("--set")) overrides.push_back(split_assignment("--set", text));
  return overrides;
}

std::string number(double value, int precision = 6) {
  std::ostringstream out;
  out.precision(precision);
  out << value;
  return out.str();
}

// The checks `run` makes before it writes anything, shared with `check` so that both give
// the same message: the output directory must be creatable and writable. Nothing is created.
void check_output_directory(const std::string& directory) {
  namespace fs = std::filesystem;
  const fs::path path = directory.empty() ? fs::path(".") : fs::path(directory);
  fs::path existing = path;  // the nearest part of the path that exists
  std::error_code error;
  while (!existing.empty() && !fs::exists(existing, error)) existing = existing.parent_path();
  if (existing.empty()) existing = ".";
  const std::string what = "cannot create output directory '" + path.string() + "': ";
  const std::string todo = "; choose a writable output directory (--out)";
  if (!fs::is_directory(existing, error)) throw Error(what + "'" + existing.string() + "' is not a directory" + todo);
  if (::access(existing.c_str(), W_OK | X_OK) != 0)
    throw Error(what + "'" + existing.string() + "' is not writable" + todo);
}

// Set-ups that make no sense but may be meant: one line each on stderr, for check and run.
void print_warnings(const Scene& scene) {
  std::cout.flush();
  for (const auto& warning : scene.warnings) std::cerr << "stagger: warning: " << warning << "\n";
}

// Builds the Simulation; its set-up errors (which the scene reader cannot see, e.g. periodic
// sides that do not match) are located at the scene file, the same for `run` and `check`.
Simulation set_up(Problem problem, const std::string& scene_file, bool distributed = true) {
  try {
    if (!distributed) return Simulation(std::move(problem));
    return distributed_simulation(std::move(problem));  // under mpirun: this rank's part
  } catch (const CollectiveError& failure) {
    throw CollectiveError(scene_file + ": set-up failed: " + failure.what());
  } catch (const Error& failure) {
    throw Error(scene_file + ": set-up failed: " + failure.what());
  }
}

}  // namespace

int run_command(const std::vector<std::string>& args) {
  if (wants_help(args)) {
    std::cout << run_help;
    return 0;
  }
  const Arguments arguments("stagger run", args,
                            {{"--out", "", true, false},
                             {"--set", "", true, true},
                             {"--threads", "", true, false},
                             {"--restart", "", true, false},
                             {"--replace", "", false, false},
                             {"--quiet", "", false, false}});
  const std::string scene_path = single_positional(arguments, "stagger run", "scene file");
  if (arguments.has("--threads")) {
    const std::string text = arguments.value("--threads");
    std::size_t used = 0;
    int threads = 0;
    try {
      threads = std::stoi(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || threads < 1 || threads > 4096)
      throw UsageError("--threads '" + text + "' is not a positive integer");
    omp_set_num_threads(threads);
  }
  const bool quiet = arguments.flag("--quiet");
  // Under mpirun rank 0 reads and meshes the scene, the other ranks read it without its mesh;
  // rank 0 reports (docs/parallel.md).
  start_mpi_if_launched();
  const bool root = mpi_state().rank == 0;
  compare_start_on_every_rank(scene_path, overrides_of(arguments),
                              {{"--out", arguments.has("--out") ? arguments.value("--out") : ""},
                               {"--restart", arguments.has("--restart") ? arguments.value("--restart") : ""},
                               {"--replace", arguments.flag("--replace") ? "yes" : ""}});
  Scene scene;
  RunControl control;
  scene = load_scene_on_every_rank(scene_path, overrides_of(arguments));
  on_every_rank([&] {
    control = scene.control;
    if (arguments.has("--out")) control.output_directory = arguments.value("--out");
    check_output_directory(control.output_directory);
  });
  malloc_trim(0);             // the mesh build's temporaries, before the set-up (docs/parallel.md, "Memory")
  control.progress = !quiet;  // every 0.2 s on a terminal, a line every 10 s in a log
  control.replace = arguments.flag("--replace");
  control.handle_signals = true;
  for (const auto& note : scene.notes)
    if (!quiet && root) std::cerr << "stagger: note: " << note << "\n";
  if (root) print_warnings(scene);

  Simulation simulation = set_up(std::move(scene.problem), scene_path);
  RunResult result;
  try {
    result = arguments.has("--restart") ? resume(simulation, control, arguments.value("--restart"))
                                        : run(simulation, control);
  } catch (const RestartError& error) {
    throw CollectiveError(error.what());  // the same on every rank
  }
  write_rank_statistics(simulation, control.output_directory, result.summary.loop_seconds);
  const EnergyAudit energy = simulation.energy();  // collective in a distributed run
  const Simulation* whole = simulation.gather();   // the whole state (rank 0)
  if (!quiet && whole) {
    const Simulation& simulation = *whole;
    const RunSummary& summary = result.summary;
    const double zone_cycles =
        static_cast<double>(simulation.mesh().num_zones()) * static_cast<double>(simulation.cycle());
    std::cout << "stagger run: " << control.name << (result.completed ? " completed" : " STOPPED") << "\n";
    std::cout << "  cycles " << simulation.cycle() << ", t = " << number(simulation.time(), 10) << " of "
              << number(simulation.problem().t_end, 10) << ", last dt " << number(simulation.dt()) << "\n";
    std::cout << "  zones " << simulation.mesh().num_zones() << ", threads " << summary.threads
              << (summary.ranks > 1 ? ", ranks " + std::to_string(summary.ranks) : std::string()) << ", wall "
              << number(summary.wall_seconds, 4) << " s, loop " << number(summary.loop_seconds, 4) << " s, "
              << number(summary.loop_seconds > 0 ? zone_cycles / summary.loop_seconds : 0.0, 4) << " zone-cycles/s\n";
    std::cout << "  energy: initial " << number(energy.initial, 10) << ", final " << number(energy.total, 10)
              << ", boundary work " << number(energy.boundary_work) << ", source work " << number(energy.source_work)
              << ", relative error " << number(energy.relative_error, 3) << "\n";
    for (const auto& [name, value] : summary.errors) std::cout << "  error " << name << " = " << number(value) << "\n";
    for (const auto& [name, value] : summary.diagnostics)
      std::cout << "  diagnostic " << name << " = " << number(value) << "\n";
    std::cout << "  output: " << control.output_directory << "\n";
  }
  if (result.signal != 0) {  // every rank stops alike, at the same cycle
    if (root) std::cerr << "stagger: " << result.message << "\n";
    return 128 + result.signal;
  }
  if (!result.completed) throw CollectiveError("run stopped: " + result.message);  // every rank stops alike
  return 0;
}

int check_command(const std::vector<std::string>& args) {
  if (wants_help(args)) {
    std::cout << check_help;
    return 0;
  }
  const Arguments arguments("stagger check", args, {{"--set", "", true, true}, {"--out", "", true, false}});
  const std::string scene_path = single_positional(arguments, "stagger check", "scene file");
  // Under mpirun the ranks compare how they were started, then rank 0 alone checks (a serial
  // set-up) and prints; its error stops every rank alike.
  start_mpi_if_launched();
  compare_start_on_every_rank(scene_path, overrides_of(arguments),
                              {{"--out", arguments.has("--out") ? arguments.value("--out") : ""}});
  on_every_rank([&] {
    if (mpi_state().rank != 0) return;
    const Scene scene = load_scene(scene_path, overrides_of(arguments));
    // The same checks as `run` before its first step: output directory, then the set-up.
    check_output_directory(arguments.has("--out") ? arguments.value("--out") : scene.control.output_directory);
    static_cast<void>(set_up(scene.problem, scene_path, false));
    std::cout << describe(scene);
    print_warnings(scene);
    std::cout << "scene is valid" << (scene.warnings.empty() ? "" : " (with warnings, on stderr)") << "\n";
  });
  return 0;
}

int mesh_command(const std::vector<std::string>& args) {
  if (wants_help(args)) {
    std::cout << mesh_help;
    return 0;
  }
  const Arguments arguments("stagger mesh", args,
                            {{"--output", "-o", true, false},
                             {"--set", "", true, true},
                             {"--triangles", "", true, false},
                             {"--check", "", false, false},
                             {"--gmsh-time-limit", "", true, false},
                             {"--gmsh-memory-limit", "", true, false},
                             {"--max-points", "", true, false},
                             {"--allow-geo-commands", "", false, false}});
  const std::string input = single_positional(arguments, "stagger mesh", "mesh file (.geo or .msh)");
  meshgen::GeoOptions options;
  for (const auto& [flag, limit] :
       {std::pair{"--gmsh-time-limit", &options.time_limit_seconds},
        std::pair{"--gmsh-memory-limit", &options.memory_limit_mib}, std::pair{"--max-points", &options.max_points}}) {
    if (!arguments.has(flag)) continue;
    const std::string text = arguments.value(flag);
    std::size_t used = 0;
    try {
      *limit = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || !(*limit >= 0) || !std::isfinite(*limit))
      throw UsageError(std::string(flag) + " '" + text + "': give a number >= 0 (0: no limit)");
  }
  options.allow_commands = arguments.flag("--allow-geo-commands");
  for (const auto& text : arguments.values("--set")) {
    const auto [name, value_text] = split_assignment("--set", text);
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(value_text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != value_text.size() || !std::isfinite(value))
      throw UsageError("--set " + text + ": '" + value_text + "' is not a finite number");
    options.parameters.emplace_back(name, value);
  }
  if (arguments.has("--triangles")) {
    const std::string policy = arguments.value("--triangles");
    if (policy == "accept")
      options.triangles = meshgen::TrianglePolicy::accept;
    else if (policy == "subdivide")
      options.triangles = meshgen::TrianglePolicy::subdivide;
    else if (policy == "reject")
      options.triangles = meshgen::TrianglePolicy::reject;
    else
      throw UsageError("--triangles '" + policy + "': use accept, subdivide or reject");
  }
  std::string output;
  if (arguments.has("--output")) {
    output = arguments.value("--output");
    const std::string extension = std::filesystem::path(output).extension().string();
    if (extension != ".msh" && extension != ".vtu")
      throw UsageError("-o '" + output + "': the output must end in .msh or .vtu");
  }
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const PolygonSoup soup = meshgen::read_mesh_file(input, options);
  const auto t1 = Clock::now();
  MeshBuildReport report;
  const Mesh mesh = build_mesh(soup, {}, &report);
  const auto t2 = Clock::now();
  const MeshQuality quality = mesh_quality(mesh);
  const double read_seconds = std::chrono::duration<double>(t1 - t0).count();
  const double build_seconds = std::chrono::duration<double>(t2 - t1).count();

  std::cout << "mesh " << input << ": " << mesh.num_zones() << " zones (" << quality.quads << " quads, "
            << quality.triangles << " triangles, " << quality.other_polygons << " other polygons), "
            << mesh.num_points() << " points\n";
  std::cout << "regions:";
  for (Index r = 0; r < mesh.num_regions(); ++r)
    std::cout << " " << mesh.region_names[r] << " (" << mesh.region_zone_begin[r + 1] - mesh.region_zone_begin[r]
              << " zones)";
  std::cout << "\ntags:";
  for (const auto& tag : mesh.tags) std::cout << " " << tag.name << " (" << tag.edges.size() << " edges)";
  std::cout << "\nquality: area " << number(quality.min_area) << " .. " << number(quality.max_area)
            << ", max aspect ratio " << number(quality.max_aspect_ratio) << ", min angle "
            << number(quality.min_angle_degrees) << " deg, non-convex zones " << quality.non_convex_zones << "\n";
  if (report.reoriented_zones > 0) std::cout << "note: " << report.reoriented_zones << " zones reoriented to CCW\n";
  if (report.dropped_points > 0) std::cout << "note: " << report.dropped_points << " unused points dropped\n";
  for (const auto& note : report.notes) std::cout << "note: " << note << "\n";
  std::cout << "timing: read/mesh " << number(read_seconds) << " s (gmsh for .geo/.msh), CGAL topology "
            << number(report.topology_seconds) << " s, other checks and arrays "
            << number(build_seconds - report.topology_seconds) << " s\n";
  if (!output.empty()) {
    // Atomic like every output (temporary name, checked, fdatasync, rename): gmsh does not report
    // write errors, so the file must end with its last section marker to count as written.
    if (std::filesystem::path(output).extension() == ".msh")
      write_file_atomically(
          output, [&](const std::string& temporary) { meshgen::write_msh(temporary, mesh); }, "$EndElements\n");
    else
      write_mesh_vtu(output, mesh);  // atomic and checked by the VTK writer
    std::cout << "wrote " << output << "\n";
  }
  if (arguments.flag("--check") && quality.non_convex_zones > 0)
    throw Error(input + ": " + std::to_string(quality.non_convex_zones) +
                " non-convex zone(s); refine or smooth the mesh (see the quality report above)");
  return 0;
}

}  // namespace stagger::cli
