/// @file solid_references.cpp
/// Error norms and diagnostics of the solid and explosive verification problems against
/// their exact solutions (problems 2-5 of docs/verification.md; norms of its §11).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

#include "stagger/error.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

/// Largest x at which the point field u crosses `level` from above (going towards -x, the
/// first point with u >= level), linearly interpolated with the nearest point to its right
/// that is below the level: the middle of a smeared front when level is the mid-jump value.
double crossing_position(std::span<const double> x, std::span<const double> u, double level) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] > x[b]; });
  bool have_below = false;
  double x_below = 0, u_below = 0;
  for (const std::size_t p : order) {
    if (u[p] >= level) {
      if (!have_below || u[p] == u_below) return x[p];
      return x_below + (level - u_below) * (x[p] - x_below) / (u[p] - u_below);
    }
    have_below = true;
    x_below = x[p];
    u_below = u[p];
  }
  return order.empty() ? 0.0 : x[order.back()];
}

const BoundaryTag& find_tag(const Mesh& mesh, const std::string& name) {
  const int tag = mesh.tag_index(name);
  if (tag < 0)
    throw Error("be_shell reference: the mesh (" + mesh.source + ") has no boundary tag \"" + name +
                "\"; tag the inner and outer circles \"inner\" and \"outer\"");
  return mesh.tags[static_cast<std::size_t>(tag)];
}

}  // namespace

Reference piston_reference(const PistonParameters& parameters) {
  const ElasticPlasticPiston piston(parameters);
  return [piston](const Simulation& simulation, NamedValues& errors, NamedValues& diagnostics) {
    const double t = simulation.time();
    point_field_errors(
        simulation, simulation.velocity_x(), [&](double x, double) { return piston.sample(x, t).velocity; }, "velocity",
        errors);
    zone_field_errors(
        simulation, simulation.pressure(), [&](double x, double) { return piston.sample(x, t).pressure; }, "pressure",
        errors);
    zone_field_errors(
        simulation, simulation.density(), [&](double x, double) { return piston.sample(x, t).density; }, "density",
        errors);
    if (simulation.has_strength())
      zone_field_errors(
          simulation, simulation.stress_xx(), [&](double x, double) { return piston.sample(x, t).stress_xx; },
          "deviatoric_stress_xx", errors);
    const double u1 = piston.elastic_state().velocity, u2 = piston.plastic_state().velocity;
    diagnostics.emplace_back("elastic_front", crossing_position(simulation.x(), simulation.velocity_x(), 0.5 * u1));
    diagnostics.emplace_back("plastic_front",
                             crossing_position(simulation.x(), simulation.velocity_x(), 0.5 * (u1 + u2)));
    diagnostics.emplace_back("elastic_front_exact", piston.elastic_wave_speed() * t);
    diagnostics.emplace_back("plastic_front_exact", piston.plastic_wave_speed() * t);
    diagnostics.emplace_back("elastic_velocity_exact", u1);
    diagnostics.emplace_back("elastic_pressure_exact", piston.elastic_state().pressure);
    diagnostics.emplace_back("plastic_pressure_exact", piston.plastic_state().pressure);
    diagnostics.emplace_back("plastic_density_exact", piston.plastic_state().density);
  };
}

Reference be_shell_reference(const ShellParameters& parameters) {
  const HowellBallShell shell(parameters);
  return [shell](const Simulation& simulation, NamedValues&, NamedValues& diagnostics) {
    const double t = simulation.time();
    const Mesh& mesh = simulation.mesh();
    const auto px = simulation.x();
    const auto py = simulation.y();
    double asymmetry = 0;
    for (const char* name : {"inner", "outer"}) {
      const BoundaryTag& tag = find_tag(mesh, name);
      double sum = 0, low = std::numeric_limits<double>::max(), high = 0;
      for (const Index p : tag.points) {
        const double r = std::hypot(px[p], py[p]);
        sum += r;
        low = std::min(low, r);
        high = std::max(high, r);
      }
      const double mean = sum / static_cast<double>(tag.points.size());
      asymmetry = std::max(asymmetry, (high - low) / mean);
      diagnostics.emplace_back(std::string(name) + "_radius", mean);
    }
    diagnostics.emplace_back("inner_radius_exact", shell.inner_radius(t));
    diagnostics.emplace_back("outer_radius_exact", shell.outer_radius(t));
    diagnostics.emplace_back("inner_stopping_radius_exact", shell.inner_stopping_radius());
    diagnostics.emplace_back("outer_stopping_radius_exact", shell.outer_stopping_radius());
    diagnostics.emplace_back("stopping_time_exact", shell.stopping_time());
    diagnostics.emplace_back("asymmetry", asymmetry);
    const EnergyAudit energy = simulation.energy();
    diagnostics.emplace_back("kinetic_energy", energy.kinetic);
    diagnostics.emplace_back("internal_energy", energy.internal);
    // The analytic energy is per full circle (spherical: per full sphere): scale by the simulated
    // sector's share of the mass (in rz the zone masses are per radian, and so is the result).
    const auto mass = simulation.zone_mass();
    const double total_mass = std::accumulate(mass.begin(), mass.end(), 0.0);
    const ShellParameters& p = shell.parameters();
    const double ri = p.inner_radius, ro = p.outer_radius;
    const double full_mass = p.spherical ? p.density * 4.0 / 3.0 * std::numbers::pi * (ro * ro * ro - ri * ri * ri)
                                         : p.density * std::numbers::pi * (ro * ro - ri * ri);
    diagnostics.emplace_back("kinetic_energy_exact", shell.kinetic_energy(t) * total_mass / full_mass);
  };
}

Reference detonation_reference(const DetonationParameters& parameters) {
  const CJDetonation detonation(parameters);
  return [detonation](const Simulation& simulation, NamedValues& errors, NamedValues& diagnostics) {
    const double t = simulation.time();
    const auto pressure = simulation.pressure();
    zone_field_errors(
        simulation, pressure, [&](double x, double) { return detonation.sample(x, t).pressure; }, "pressure", errors);
    const auto centres = zone_centres(simulation.mesh(), simulation.x(), simulation.y());
    const auto area = simulation.zone_area();
    const double x0 = detonation.parameters().x0;
    const double half = 0.5 * detonation.cj_state().pressure;
    double front = x0, peak = 0, plateau_sum = 0, plateau_area = 0;
    for (std::size_t z = 0; z < centres[0].size(); ++z) {
      if (pressure[z] > half) front = std::max(front, centres[0][z]);
      peak = std::max(peak, pressure[z]);
      if (centres[0][z] - x0 < 0.25 * detonation.cj_speed() * t) {
        plateau_sum += area[z] * pressure[z];
        plateau_area += area[z];
      }
    }
    diagnostics.emplace_back("front_position", front);
    diagnostics.emplace_back("front_position_exact", x0 + detonation.cj_speed() * t);
    diagnostics.emplace_back("front_position_nominal", x0 + detonation.parameters().nominal_speed * t);
    diagnostics.emplace_back("peak_pressure", peak);
    diagnostics.emplace_back("cj_pressure_exact", detonation.cj_state().pressure);
    diagnostics.emplace_back("cj_speed_exact", detonation.cj_speed());
    diagnostics.emplace_back("plateau_pressure",
                             plateau_area > 0 ? plateau_sum / plateau_area : std::numeric_limits<double>::quiet_NaN());
    diagnostics.emplace_back("plateau_pressure_exact", detonation.plateau_pressure());
  };
}

Reference accuracy_reference(const AccuracyParameters& parameters) {
  const AccuracySolution solution(parameters);
  return [solution](const Simulation& simulation, NamedValues& errors, NamedValues&) {
    const double t = simulation.time();
    zone_field_errors(
        simulation, simulation.density(), [&](double x, double y) { return solution.density(x, y, t); }, "density",
        errors);
    if (!simulation.has_strength()) return;
    zone_field_errors(
        simulation, simulation.stress_xx(), [&](double x, double y) { return solution.stress_xx(x, y, t); },
        "deviatoric_stress_xx", errors);
    zone_field_errors(
        simulation, simulation.stress_yy(), [&](double x, double y) { return solution.stress_yy(x, y, t); },
        "deviatoric_stress_yy", errors);
    zone_field_errors(
        simulation, simulation.stress_xy(), [&](double x, double y) { return solution.stress_xy(x, y, t); },
        "deviatoric_stress_xy", errors);
  };
}

}  // namespace stagger
