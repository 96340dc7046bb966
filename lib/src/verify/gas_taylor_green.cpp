/// @file gas_taylor_green.cpp
/// The 2D Taylor-Green vortex of Dobrev, Kolev & Rieben, "High-order curvilinear finite
/// element methods for Lagrangian hydrodynamics", SIAM J. Sci. Comput. 34(5), B606-B641
/// (2012), sec. 6.1 (Laghos problem 0), with gamma = 5/3 and rho = 1 on [0,1]^2.
///
/// Derivation of the energy source (checked numerically in tests/verify/gas_exact.cpp):
/// v = (sin(pi x) cos(pi y), -cos(pi x) sin(pi y)) has div v = 0, so rho = 1 stays exact; and
/// v.grad v = (pi/2)(sin(2 pi x), sin(2 pi y)) = -grad p for p = p0 + (cos 2 pi x + cos 2 pi y)/4,
/// so the steady v satisfies the momentum equation without a source. The internal energy
/// e = p / ((gamma - 1) rho) is steady, so De/dt = v.grad e, while the energy equation gives
/// De/dt = -(p/rho) div v + s_e = s_e. Hence
///   s_e = v.grad p / (gamma - 1) = -(3 pi / 2) cos(pi x) cos(pi y) (sin^2(pi x) - sin^2(pi y)),
/// and with cos 3a = cos a (1 - 4 sin^2 a) this is
///   s_e = (3 pi / 8) [cos(3 pi x) cos(pi y) - cos(pi x) cos(3 pi y)],
/// the source of Dobrev et al. (independent of p0).
#include <cmath>
#include <numbers>

#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {

using std::numbers::pi;

std::array<double, 2> taylor_green_velocity(double x, double y) {
  return {std::sin(pi * x) * std::cos(pi * y), -std::cos(pi * x) * std::sin(pi * y)};
}

double taylor_green_pressure(double x, double y, double p0) {
  return p0 + 0.25 * (std::cos(2.0 * pi * x) + std::cos(2.0 * pi * y));
}

double taylor_green_energy_source(double x, double y) {
  return 3.0 * pi / 8.0 * (std::cos(3.0 * pi * x) * std::cos(pi * y) - std::cos(pi * x) * std::cos(3.0 * pi * y));
}

Sources taylor_green_sources() {
  Sources sources;
  sources.energy = [](double x, double y, double) { return taylor_green_energy_source(x, y); };
  return sources;  // no momentum source: the momentum equation holds exactly
}

Reference taylor_green_reference(double p0) {
  return [p0](const Simulation& simulation, NamedValues& errors, NamedValues&) {
    point_velocity_errors(simulation, taylor_green_velocity, "velocity", errors);
    zone_field_errors(
        simulation, simulation.pressure(), [p0](double x, double y) { return taylor_green_pressure(x, y, p0); },
        "pressure", errors);
    zone_field_errors(
        simulation, simulation.density(), [](double, double) { return 1.0; }, "density", errors);
  };
}

}  // namespace stagger
