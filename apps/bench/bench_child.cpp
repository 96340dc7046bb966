// `stagger bench --one` (one measurement in this process) and the parent's side that runs
// it as a child process with a timeout and parses its report.
#include <fcntl.h>
#include <omp.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "arguments.hpp"
#include "bench.hpp"
#include "stagger/error.hpp"
#include "stagger/run.hpp"
#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"

namespace stagger::cli::bench {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A "VmXXX:   1234 kB" line of /proc/self/status, in bytes (0 if absent).
double proc_status_bytes(const std::string& key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(key + ":", 0) != 0) continue;
    std::istringstream fields(line.substr(key.size() + 1));
    double kilobytes = 0;
    fields >> kilobytes;
    return kilobytes * 1024.0;
  }
  return 0;
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  return text;
}

long parse_long(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  long value = -1;
  try {
    value = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || value < 0) throw UsageError(option + " '" + text + "' is not a non-negative integer");
  return value;
}

// Error norms as they are, plus one relative error per diagnostic that has an exact
// counterpart (`shock_radius` and `shock_radius_exact` give `shock_radius_relerr`), plus
// the symmetry measures, which are errors in themselves (exact value 0).
Measures measures_of(const NamedValues& errors, const NamedValues& diagnostics) {
  Measures measures(errors.begin(), errors.end());
  std::map<std::string, double> by_name(diagnostics.begin(), diagnostics.end());
  for (const auto& [name, value] : diagnostics) {
    const auto exact = by_name.find(name + "_exact");
    if (exact != by_name.end() && exact->second != 0)
      measures.emplace_back(name + "_relerr", std::abs(value - exact->second) / std::abs(exact->second));
    const bool symmetry =
        (name.find("asymmetry") != std::string::npos && name != "asymmetry_groups") || name == "max_y_variation";
    const bool is_error = name.size() > 6 && name.compare(name.size() - 6, 6, "_error") == 0;
    if (symmetry || is_error) measures.emplace_back(name, std::abs(value));
  }
  return measures;
}

void print(const std::string& key, double value) {
  std::printf("%s\t%.17g\n", key.c_str(), value);
}

}  // namespace

int run_one(const std::vector<std::string>& args) {
  const Arguments arguments("stagger bench --one", args,
                            {{"--one", "", false, false},
                             {"--scene", "", true, false},
                             {"--set", "", true, true},
                             {"--threads", "", true, false},
                             {"--cycles", "", true, false},
                             {"--target", "", false, false}});
  if (!arguments.has("--scene")) throw UsageError("'stagger bench --one' needs --scene FILE");
  const long threads = arguments.has("--threads") ? parse_long("--threads", arguments.value("--threads")) : 1;
  if (threads < 1) throw UsageError("--threads must be at least 1");
  omp_set_num_threads(static_cast<int>(threads));
  const long max_cycles = arguments.has("--cycles") ? parse_long("--cycles", arguments.value("--cycles")) : 0;
  const bool cycles_are_target = arguments.flag("--target");
  Overrides overrides;
  for (const auto& text : arguments.values("--set")) overrides.push_back(split_assignment("--set", text));
  overrides.emplace_back("output.dumps", "false");  // the child writes no output (no dump-count limit)

  const double baseline_rss = proc_status_bytes("VmRSS");
  std::string status = "completed";
  const auto setup_start = Clock::now();
  // Set-up errors (a bad scene or override) are reported like run failures: one row each.
  std::unique_ptr<Simulation> simulation;
  Reference reference;
  try {
    Scene scene = load_scene(arguments.value("--scene"), overrides);
    reference = scene.control.reference;
    simulation = std::make_unique<Simulation>(std::move(scene.problem));
  } catch (const Error& error) {
    std::printf("status\tset-up failed: %s\n", one_line(error.what()).c_str());
    print("peak_rss_bytes", proc_status_bytes("VmHWM"));
    return 0;
  }
  const double setup_seconds = seconds_since(setup_start);

  // The timed loop: step() only, no output of any kind.
  const auto loop_start = Clock::now();
  try {
    while (!simulation->finished() && (max_cycles == 0 || simulation->cycle() < max_cycles)) simulation->step();
  } catch (const Error& error) {
    status = "stopped: " + one_line(error.what());
  }
  const double loop_seconds = seconds_since(loop_start);
  if (status == "completed" && !simulation->finished() && !cycles_are_target)
    status = "stopped: cycle cap " + std::to_string(max_cycles) + " reached before time.end";

  const EnergyAudit energy = simulation->energy();
  if (!std::isfinite(energy.total) || !std::isfinite(energy.relative_error))
    status = "NaN: energy is not finite after cycle " + std::to_string(simulation->cycle());
  NamedValues errors, diagnostics;
  if (reference) {
    try {
      reference(*simulation, errors, diagnostics);
    } catch (const Error& error) {
      status += " (reference failed: " + one_line(error.what()) + ")";
    }
  }

  const double zones = static_cast<double>(simulation->mesh().num_zones());
  const double cycles = static_cast<double>(simulation->cycle());
  std::printf("status\t%s\n", status.c_str());
  print("zones", zones);
  print("points", static_cast<double>(simulation->mesh().num_points()));
  print("cycles", cycles);
  print("setup_seconds", setup_seconds);
  print("wall_seconds", loop_seconds);
  print("zone_cycles_per_second", loop_seconds > 0 ? zones * cycles / loop_seconds : 0.0);
  print("peak_rss_bytes", proc_status_bytes("VmHWM"));
  print("baseline_rss_bytes", baseline_rss);
  print("energy_audit", std::abs(energy.relative_error));
  print("t_end", simulation->problem().t_end);
  print("time", simulation->time());
  print("has_strength", simulation->has_strength() ? 1 : 0);
  print("has_burn", simulation->has_burn() ? 1 : 0);
  for (const auto& [name, value] : measures_of(errors, diagnostics)) print("measure." + name, value);
  std::fflush(stdout);
  return 0;
}

RunRecord run_in_child(const RunSpec& spec) {
  RunRecord record;
  record.spec = spec;
  const std::string executable = std::filesystem::read_symlink("/proc/self/exe").string();
  std::vector<std::string> argv_strings = {
      executable, "bench", "--one", "--scene", spec.scene_path, "--threads", std::to_string(spec.threads)};
  for (const auto& [key, value] : spec.overrides) {
    argv_strings.push_back("--set");
    argv_strings.push_back(key + "=" + value);
  }
  if (spec.max_cycles > 0) {
    argv_strings.push_back("--cycles");
    argv_strings.push_back(std::to_string(spec.max_cycles));
  }
  if (spec.cycles_are_target) argv_strings.push_back("--target");
  std::vector<char*> argv;
  for (auto& text : argv_strings) argv.push_back(text.data());
  argv.push_back(nullptr);

  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw Error(std::string("bench: pipe() failed: ") + std::strerror(errno));
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  if (pid < 0) throw Error(std::string("bench: fork() failed: ") + std::strerror(errno));
  if (pid == 0) {
    // Child: stdout into the pipe; stderr stays the parent's (one-line errors show up there).
    dup2(pipe_fds[1], STDOUT_FILENO);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    execv(executable.c_str(), argv.data());
    _exit(127);
  }
  close(pipe_fds[1]);

  std::string output;
  bool timed_out = false;
  const auto start = Clock::now();
  char buffer[4096];
  for (;;) {
    const double left = spec.timeout_seconds - seconds_since(start);
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd descriptor{pipe_fds[0], POLLIN, 0};
    const int ready = poll(&descriptor, 1, static_cast<int>(std::min(left, 1.0) * 1000) + 1);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t count = read(pipe_fds[0], buffer, sizeof buffer);
    if (count <= 0) break;  // EOF: the child closed stdout (exited)
    output.append(buffer, static_cast<std::size_t>(count));
  }
  close(pipe_fds[0]);
  if (timed_out) kill(pid, SIGKILL);
  int wait_status = 0;
  while (waitpid(pid, &wait_status, 0) < 0 && errno == EINTR) {
  }

  std::istringstream lines(output);
  std::string line;
  std::map<std::string, double> numbers;
  bool got_status = false;
  while (std::getline(lines, line)) {
    const auto tab = line.find('\t');
    if (tab == std::string::npos) continue;
    const std::string key = line.substr(0, tab), value = line.substr(tab + 1);
    if (key == "status") {
      record.status = value;
      got_status = true;
    } else if (key.rfind("measure.", 0) == 0) {
      record.measures.emplace_back(key.substr(8), std::strtod(value.c_str(), nullptr));
    } else {
      numbers[key] = std::strtod(value.c_str(), nullptr);
    }
  }
  const auto number = [&](const char* key) { return numbers.count(key) ? numbers[key] : 0.0; };
  record.zones = static_cast<long>(number("zones"));
  record.points = static_cast<long>(number("points"));
  record.cycles = static_cast<long>(number("cycles"));
  record.setup_seconds = number("setup_seconds");
  record.wall_seconds = number("wall_seconds");
  record.zone_cycles_per_second = number("zone_cycles_per_second");
  record.peak_rss_bytes = number("peak_rss_bytes");
  record.baseline_rss_bytes = number("baseline_rss_bytes");
  record.energy_audit = number("energy_audit");
  record.t_end = number("t_end");
  record.time = number("time");
  record.has_strength = number("has_strength") != 0;
  record.has_burn = number("has_burn") != 0;
  if (timed_out)
    record.status = "timeout: killed after " + std::to_string(static_cast<long>(spec.timeout_seconds)) + " s";
  else if (WIFSIGNALED(wait_status))
    record.status =
        "crashed: signal " + std::to_string(WTERMSIG(wait_status)) + " (" + strsignal(WTERMSIG(wait_status)) + ")";
  else if (!got_status)
    record.status = "failed: the child exited with status " + std::to_string(WEXITSTATUS(wait_status)) +
                    " without a report (see the message above)";
  return record;
}

}  // namespace stagger::cli::bench
