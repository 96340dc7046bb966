/// @file solid_accuracy.cpp
/// The paper's smooth manufactured solution (section 5.3; docs/algorithm.md §15: a momentum
/// source makes it exact). Derivation: docs/derivations.md section 4.
#include <cmath>
#include <numbers>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Mie-Grueneisen p(rho, e) and dp/drho at constant e (paper eq. 6, docs/algorithm.md §3),
/// kept local so that the exact solution is independent of the EOS code it verifies.
double mg_pressure(const MieGruneisen& m, double rho, double e) {
  const double eta = 1.0 - m.rho0 / rho;
  const double d = 1.0 - m.s * eta;
  const double strain = m.a0 * eta / d;
  return m.rho0 * m.a0 * m.a0 * eta / (d * d) + m.gamma0 * m.rho0 * (e - 0.5 * strain * strain);
}
double mg_pressure_density_derivative(const MieGruneisen& m, double rho) {
  // dp/deta|_e = rho0 a0^2 (1 + (s - Gamma0) eta) / (1 - s eta)^3, deta/drho = rho0 / rho^2.
  const double eta = 1.0 - m.rho0 / rho;
  const double d = 1.0 - m.s * eta;
  return m.rho0 * m.a0 * m.a0 * (1.0 + (m.s - m.gamma0) * eta) / (d * d * d) * m.rho0 / (rho * rho);
}

}  // namespace

AccuracySolution::AccuracySolution(const AccuracyParameters& parameters) : parameters_(parameters) {
  if (!(parameters.eos.rho0 > 0) || std::abs(parameters.amplitude) >= 0.5)
    throw Error("accuracy solution: need rho0 > 0 and |amplitude| < 0.5 (positive density)");
}

double AccuracySolution::density(double x, double y, double t) const {
  const double a = parameters_.velocity;
  return parameters_.eos.rho0 * (1.0 - parameters_.amplitude * std::sin(kTwoPi * (x - a * t)) -
                                 parameters_.amplitude * std::cos(kTwoPi * (y - a * t)));
}

double AccuracySolution::pressure(double x, double y, double t) const {
  return mg_pressure(parameters_.eos, density(x, y, t), parameters_.energy);
}

double AccuracySolution::stress_xx(double x, double y, double t) const {
  const double a = parameters_.velocity;
  return parameters_.s1 * (std::cos(kTwoPi * (x - a * t)) - std::sin(kTwoPi * (y - a * t)));
}

double AccuracySolution::stress_yy(double x, double y, double t) const {
  const double a = parameters_.velocity;
  return -parameters_.s1 * (std::sin(kTwoPi * (x - a * t)) - std::cos(kTwoPi * (y - a * t)));
}

double AccuracySolution::stress_xy(double x, double y, double t) const {
  return stress_xx(x, y, t) + stress_yy(x, y, t);  // the paper's s_zr = s_zz + s_rr
}

std::array<double, 2> AccuracySolution::momentum_source(double x, double y, double t) const {
  // rho Dv/Dt = div sigma + b with Dv/Dt = 0, sigma = S - p I: b = -div sigma_exact.
  const double a = parameters_.velocity, s1 = parameters_.s1, k = kTwoPi;
  const double cx = std::cos(k * (x - a * t)), sx = std::sin(k * (x - a * t));
  const double cy = std::cos(k * (y - a * t)), sy = std::sin(k * (y - a * t));
  const double rho0 = parameters_.eos.rho0, amplitude = parameters_.amplitude;
  const double drho_dx = -rho0 * amplitude * k * cx;
  const double drho_dy = rho0 * amplitude * k * sy;
  const double dp_drho = mg_pressure_density_derivative(parameters_.eos, density(x, y, t));
  const double dsxx_dx = -s1 * k * sx;
  const double dsyy_dy = -s1 * k * sy;
  // S_xy = s1 (cos kX - sin kY - sin kX + cos kY).
  const double dsxy_dx = s1 * k * (-sx - cx);
  const double dsxy_dy = s1 * k * (-cy - sy);
  const double div_x = dsxx_dx + dsxy_dy - dp_drho * drho_dx;
  const double div_y = dsxy_dx + dsyy_dy - dp_drho * drho_dy;
  return {-div_x, -div_y};
}

Sources accuracy_sources(const AccuracyParameters& parameters) {
  const AccuracySolution solution(parameters);
  Sources sources;
  sources.momentum = [solution](double x, double y, double t) { return solution.momentum_source(x, y, t); };
  sources.energy = [](double, double, double) { return 0.0; };
  return sources;
}

}  // namespace stagger
