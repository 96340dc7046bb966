// stagger-profile: runs a scene and writes zone profiles with the exact solution beside them,
// for the figure scripts of scripts/verification (docs/verification.md).
//
//   stagger-profile SCENE.toml --out DIR [--set section.key=value]... [--times t1,t2,...]
//                   [--history-every N]
//
// For every requested time t (default: the scene's end time), in increasing order, the
// simulation is advanced to exactly t and DIR gets
//   zones_<t>.csv   write_zone_csv() plus exact_* columns at each zone centre, where the
//                   scene's [verification] reference has a pointwise solution;
//   errors_<t>.csv  name,kind,value: the reference's error norms and diagnostics at t.
// A run that stops with an error writes its last good state as the last frame, the error as
// the status of summary.json, and exits with code 3. At the end: frames.csv (frame, time, cycle, files), history.csv
// (energy audit every N cycles, HistoryWriter), summary.json (write_summary at the last time), and for the be_shell
// reference exact_shell.csv (the analytic radii and kinetic energy on a fine grid). The exact solutions are the classes
// of stagger/verify.hpp, built from the parameters that the scene reader resolved (Scene::verification), so the profile
// and summary.json compare against the same reference.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "stagger/error.hpp"
#include "stagger/output.hpp"
#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace {

using stagger::Error;

struct Options {
  std::string scene;
  std::string out;
  std::vector<std::pair<std::string, std::string>> overrides;
  std::vector<double> times;
  int history_every = 1;
};

void usage(std::ostream& stream) {
  stream << "usage: stagger-profile SCENE.toml --out DIR [--set section.key=value]... [--times t1,t2,...]\n"
            "                       [--history-every N]\n";
}

double parse_number(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty()) throw Error("stagger-profile: " + what + ": '" + text + "' is not a number");
  return value;
}

Options parse_arguments(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    auto value = [&](const char* name) {
      if (i + 1 >= argc) throw Error(std::string("stagger-profile: ") + name + " needs a value");
      return std::string(argv[++i]);
    };
    if (argument == "--out") {
      options.out = value("--out");
    } else if (argument == "--set") {
      const std::string assignment = value("--set");
      const auto equals = assignment.find('=');
      if (equals == std::string::npos || equals == 0)
        throw Error("stagger-profile: --set '" + assignment + "': write --set section.key=value");
      options.overrides.emplace_back(assignment.substr(0, equals), assignment.substr(equals + 1));
    } else if (argument == "--times") {
      std::stringstream list(value("--times"));
      std::string item;
      while (std::getline(list, item, ','))
        if (!item.empty()) options.times.push_back(parse_number(item, "--times"));
    } else if (argument == "--history-every") {
      options.history_every = static_cast<int>(parse_number(value("--history-every"), "--history-every"));
      if (options.history_every < 1) throw Error("stagger-profile: --history-every must be >= 1");
    } else if (argument == "-h" || argument == "--help") {
      usage(std::cout);
      std::exit(0);
    } else if (!argument.empty() && argument[0] == '-') {
      throw Error("stagger-profile: unknown option '" + argument + "'");
    } else if (options.scene.empty()) {
      options.scene = argument;
    } else {
      throw Error("stagger-profile: more than one scene given ('" + argument + "')");
    }
  }
  if (options.scene.empty() || options.out.empty()) {
    usage(std::cerr);
    throw Error("stagger-profile: a scene and --out DIR are required");
  }
  return options;
}

// ---- pointwise exact solutions ----

/// Exact zone values at (x, y, t): column name -> value.
using ExactColumns = std::vector<std::pair<std::string, double>>;
using ExactFunction = std::function<ExactColumns(double x, double y, double t)>;

ExactColumns gas_columns(double density, double vx, double vy, double pressure, double gamma) {
  const double energy = density > 0 ? pressure / ((gamma - 1.0) * density) : 0.0;
  return {{"exact_density", density},
          {"exact_pressure", pressure},
          {"exact_specific_internal_energy", energy},
          {"exact_velocity_x", vx},
          {"exact_velocity_y", vy}};
}

ExactColumns radial_columns(const stagger::GasState& state, double x, double y, double gamma) {
  const double r = std::hypot(x, y);
  const double nx = r > 0 ? x / r : 0.0, ny = r > 0 ? y / r : 0.0;
  return gas_columns(state.density, state.velocity * nx, state.velocity * ny, state.pressure, gamma);
}

struct ReferenceSetup {
  ExactFunction exact;                            // empty: no pointwise solution
  std::optional<stagger::HowellBallShell> shell;  // be_shell only
};

// The exact fields of the scene's reference, from the parameters the scene reader resolved
// (Scene::verification: the same objects RunControl::reference evaluates).
ReferenceSetup make_reference(const stagger::VerificationSetup& verification) {
  using namespace stagger;
  ReferenceSetup setup;
  const auto& parameters = verification.parameters;
  if (const auto* tube = std::get_if<ShockTubeReference>(&parameters)) {
    const double gamma = tube->gamma;
    const auto riemann = std::make_shared<ExactRiemann>(tube->left, tube->right, gamma, tube->x0);
    setup.exact = [riemann, gamma](double x, double, double t) {
      const GasState s = riemann->sample(x, t);
      return gas_columns(s.density, s.velocity, 0.0, s.pressure, gamma);
    };
  } else if (const auto* noh_parameters = std::get_if<NohReference>(&parameters)) {
    const double gamma = noh_parameters->gamma;
    const auto noh =
        std::make_shared<NohSolution>(gamma, noh_parameters->density, noh_parameters->speed, noh_parameters->nu);
    setup.exact = [noh, gamma](double x, double y, double t) {
      return radial_columns(noh->state(std::hypot(x, y), t), x, y, gamma);
    };
  } else if (const auto* sedov_parameters = std::get_if<SedovReference>(&parameters)) {
    const double gamma = sedov_parameters->gamma;
    // The scene deposits a quarter of the full-plane energy, or in rz the energy per radian
    // of z >= 0 (verify.hpp sedov_reference).
    const double total = sedov_parameters->nu == 3 ? 4.0 * M_PI * sedov_parameters->energy_quarter
                                                   : 4.0 * sedov_parameters->energy_quarter;
    const auto sedov = std::make_shared<SedovSolution>(gamma, sedov_parameters->nu, sedov_parameters->density, total);
    setup.exact = [sedov, gamma](double x, double y, double t) {
      return radial_columns(sedov->state(std::hypot(x, y), t), x, y, gamma);
    };
  } else if (const auto* saltzman = std::get_if<SaltzmanReference>(&parameters)) {
    const double gamma = saltzman->gamma, u = saltzman->piston_speed, rho0 = saltzman->density;
    setup.exact = [gamma, u, rho0](double x, double, double t) {
      // Strong piston shock into cold gas (Rankine-Hugoniot, p0 = 0): u_s = (gamma+1)/2 u,
      // rho = rho0 (gamma+1)/(gamma-1), p = rho0 u_s u behind it.
      const double shock = 0.5 * (gamma + 1.0) * u * t;
      if (x < shock)
        return gas_columns(rho0 * (gamma + 1.0) / (gamma - 1.0), u, 0.0, rho0 * 0.5 * (gamma + 1.0) * u * u, gamma);
      return gas_columns(rho0, 0.0, 0.0, 0.0, gamma);
    };
  } else if (const auto* taylor_green = std::get_if<TaylorGreenReference>(&parameters)) {
    const double p0 = taylor_green->p0;
    setup.exact = [p0](double x, double y, double) {
      const auto v = taylor_green_velocity(x, y);
      return gas_columns(1.0, v[0], v[1], taylor_green_pressure(x, y, p0), 5.0 / 3.0);
    };
  } else if (const auto* piston_parameters = std::get_if<PistonParameters>(&parameters)) {
    const auto piston = std::make_shared<ElasticPlasticPiston>(*piston_parameters);
    setup.exact = [piston](double x, double, double t) {
      const SolidState s = piston->sample(x, t);
      return ExactColumns{{"exact_density", s.density},
                          {"exact_pressure", s.pressure},
                          {"exact_specific_internal_energy", s.energy},
                          {"exact_velocity_x", s.velocity},
                          {"exact_velocity_y", 0.0},
                          {"exact_deviatoric_stress_xx", s.stress_xx}};
    };
  } else if (const auto* detonation_parameters = std::get_if<DetonationParameters>(&parameters)) {
    const auto detonation = std::make_shared<CJDetonation>(*detonation_parameters);
    setup.exact = [detonation](double x, double, double t) {
      const DetonationState s = detonation->sample(x, t);
      return ExactColumns{{"exact_density", s.density},
                          {"exact_pressure", s.pressure},
                          {"exact_velocity_x", s.velocity},
                          {"exact_velocity_y", 0.0}};
    };
  } else if (const auto* accuracy = std::get_if<AccuracyParameters>(&parameters)) {
    const auto solution = std::make_shared<AccuracySolution>(*accuracy);
    setup.exact = [solution](double x, double y, double t) {
      const double v = solution->parameters().velocity;
      return ExactColumns{{"exact_density", solution->density(x, y, t)},
                          {"exact_pressure", solution->pressure(x, y, t)},
                          {"exact_velocity_x", v},
                          {"exact_velocity_y", v},
                          {"exact_deviatoric_stress_xx", solution->stress_xx(x, y, t)},
                          {"exact_deviatoric_stress_yy", solution->stress_yy(x, y, t)},
                          {"exact_deviatoric_stress_xy", solution->stress_xy(x, y, t)}};
    };
  } else if (const auto* shell = std::get_if<ShellParameters>(&parameters)) {
    setup.shell.emplace(*shell);
  }
  return setup;
}

std::string time_label(double t) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", t);
  return buffer;
}

std::string format(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

// Appends exact_* columns to the zone CSV that write_zone_csv() just wrote.
void append_exact_columns(const std::string& path, const stagger::Simulation& simulation, const ExactFunction& exact) {
  std::ifstream input(path);
  std::string header;
  std::getline(input, header);
  std::vector<std::string> rows;
  for (std::string line; std::getline(input, line);) rows.push_back(line);
  input.close();

  const auto centres = stagger::zone_centres(simulation.mesh(), simulation.x(), simulation.y());
  const double t = simulation.time();
  std::string text;
  for (std::size_t z = 0; z < rows.size(); ++z) {
    const ExactColumns columns = exact(centres[0][z], centres[1][z], t);
    if (z == 0) {
      text = header;
      for (const auto& column : columns) {
        text += ',';
        text += column.first;
      }
      text += '\n';
    }
    text += rows[z];
    for (const auto& column : columns) {
      text += ',';
      text += format(column.second);
    }
    text += '\n';
  }
  stagger::write_file_atomically(path, text);
}

int run(const Options& options) {
  namespace fs = std::filesystem;
  const auto start = std::chrono::steady_clock::now();
  stagger::Scene scene = stagger::load_scene(options.scene, options.overrides);
  const ReferenceSetup reference = make_reference(scene.verification);

  stagger::Simulation simulation(std::move(scene.problem));
  const double t_end = simulation.problem().t_end;
  std::vector<double> times = options.times.empty() ? std::vector<double>{t_end} : options.times;
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  for (double t : times)
    if (t < 0 || t > t_end * (1 + 1e-12))
      throw Error("stagger-profile: --times " + time_label(t) + " lies outside [0, t_end = " + time_label(t_end) + "]");

  fs::create_directories(options.out);
  stagger::HistoryWriter history((fs::path(options.out) / "history.csv").string());
  history.record(simulation);
  long last_recorded = 0;
  simulation.set_observer([&](const stagger::Simulation& s) {
    if (s.cycle() % options.history_every == 0) {
      history.record(s);
      last_recorded = s.cycle();
    }
  });

  std::string frames = "frame,time,cycle,zones_file,errors_file\n";
  stagger::RunSummary summary;
  summary.scene = options.scene;
  double loop_seconds = 0;
  int frame = 0;
  for (double t : times) {
    const auto loop_start = std::chrono::steady_clock::now();
    try {
      if (t > simulation.time()) simulation.advance_to(std::min(t, t_end));
    } catch (const Error& failure) {
      // The state is that of the last good cycle: write it as the last frame and say why.
      summary.status = failure.what();
      std::cerr << "stagger-profile: " << options.scene << ": run stopped: " << failure.what() << "\n";
    }
    loop_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
    const bool stopped = summary.status != "completed";
    const std::string label = time_label(stopped ? simulation.time() : t);
    const std::string zones_file = "zones_" + label + ".csv", errors_file = "errors_" + label + ".csv";
    const std::string zones_path = (fs::path(options.out) / zones_file).string();
    stagger::write_zone_csv(zones_path, simulation);
    if (reference.exact) append_exact_columns(zones_path, simulation, reference.exact);

    summary.errors.clear();
    summary.diagnostics.clear();
    if (scene.control.reference && simulation.time() > 0)
      scene.control.reference(simulation, summary.errors, summary.diagnostics);
    std::string errors = "name,kind,value\n";
    for (const auto& [name, value] : summary.errors) errors += name + ",error," + format(value) + "\n";
    for (const auto& [name, value] : summary.diagnostics) errors += name + ",diagnostic," + format(value) + "\n";
    stagger::write_file_atomically((fs::path(options.out) / errors_file).string(), errors);
    frames += std::to_string(frame++) + "," + format(simulation.time()) + "," + std::to_string(simulation.cycle()) +
              "," + zones_file + "," + errors_file + "\n";
    std::cerr << "stagger-profile: " << options.scene << " t = " << label << " cycle " << simulation.cycle() << "\n";
    if (stopped) break;
  }
  if (last_recorded != simulation.cycle()) history.record(simulation);
  history.flush();
  stagger::write_file_atomically((fs::path(options.out) / "frames.csv").string(), frames);

  if (reference.shell) {
    std::string text = "time,inner_radius,outer_radius,inner_velocity,kinetic_energy\n";
    const int samples = 400;
    for (int k = 0; k <= samples; ++k) {
      const double t = t_end * k / samples;
      text += format(t) + "," + format(reference.shell->inner_radius(t)) + "," +
              format(reference.shell->outer_radius(t)) + "," + format(reference.shell->inner_velocity(t)) + "," +
              format(reference.shell->kinetic_energy(t)) + "\n";
    }
    stagger::write_file_atomically((fs::path(options.out) / "exact_shell.csv").string(), text);
  }

  summary.loop_seconds = loop_seconds;
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stagger::write_summary((fs::path(options.out) / "summary.json").string(), simulation, summary);
  return summary.status == "completed" ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse_arguments(argc, argv));
  } catch (const std::exception& failure) {
    std::cerr << "stagger-profile: error: " << failure.what() << "\n";
    return 1;
  }
}
