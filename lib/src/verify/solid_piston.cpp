/// @file solid_piston.cpp
/// Exact two-wave solution of the copper elastic-plastic piston (docs/verification.md §7).
/// Derivation: docs/derivations.md section 1.
#include <cmath>
#include <sstream>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

/// Mie-Grueneisen pressure without its energy term, f(rho) = p(rho, 0) (paper eq. 6,
/// docs/algorithm.md §3): p(rho, e) = f(rho) + Gamma0 rho0 e. Kept local so that the exact
/// solution does not depend on the EOS code it verifies.
double mg_cold_pressure(const MieGruneisen& eos, double rho) {
  const double eta = 1.0 - eos.rho0 / rho;
  const double d = 1.0 - eos.s * eta;
  if (d <= 0) {
    std::ostringstream message;
    message << "piston exact solution: Mie-Grueneisen state rho = " << rho
            << " outside the EOS domain (1 - s eta <= 0); lower the piston velocity";
    throw Error(message.str());
  }
  const double strain = eos.a0 * eta / d;
  return eos.rho0 * eos.a0 * eos.a0 * eta / (d * d) - 0.5 * eos.gamma0 * eos.rho0 * strain * strain;
}

/// Rankine-Hugoniot energy condition e1 - e0 = (P0 + P1)(V0 - V1)/2 with the normal stress
/// P = p - S_xx and p = f(rho) + Gamma0 rho0 e, solved for e1 (it is linear in e1).
double hugoniot_energy(const MieGruneisen& eos, const SolidState& ahead, double rho1, double s1) {
  const double p_ahead = ahead.pressure - ahead.stress_xx;
  const double dv = 1.0 / ahead.density - 1.0 / rho1;
  const double g = eos.gamma0 * eos.rho0;
  return (ahead.energy + 0.5 * (p_ahead + mg_cold_pressure(eos, rho1) - s1) * dv) / (1.0 - 0.5 * g * dv);
}

/// The state behind a shock of density rho1 and stress s1 running into `ahead` (towards +x),
/// and the shock speed (lab frame): mass m = rho (D - u) and momentum m (u1 - u0) = P1 - P0.
SolidState shocked_state(const MieGruneisen& eos, const SolidState& ahead, double rho1, double s1, double& speed) {
  SolidState behind;
  behind.density = rho1;
  behind.stress_xx = s1;
  behind.energy = hugoniot_energy(eos, ahead, rho1, s1);
  behind.pressure = mg_cold_pressure(eos, rho1) + eos.gamma0 * eos.rho0 * behind.energy;
  const double dp = (behind.pressure - s1) - (ahead.pressure - ahead.stress_xx);
  const double dv = 1.0 / ahead.density - 1.0 / rho1;
  const double mass_flux = std::sqrt(dp / dv);
  behind.velocity = ahead.velocity + mass_flux * dv;
  speed = ahead.velocity + mass_flux / ahead.density;
  return behind;
}

}  // namespace

ElasticPlasticPiston::ElasticPlasticPiston(const PistonParameters& parameters) : parameters_(parameters) {
  const MieGruneisen& eos = parameters.eos;
  const double mu = parameters.shear_modulus;
  const double yield = parameters.yield_stress;
  if (eos.rho0 <= 0 || eos.a0 <= 0 || mu <= 0 || yield <= 0)
    throw Error("piston exact solution: rho0, a0, shear modulus and yield stress must be positive");

  initial_.density = eos.rho0;
  initial_.pressure = parameters.initial_pressure;
  initial_.energy = parameters.initial_pressure / (eos.gamma0 * eos.rho0);  // f(rho0) = 0

  // Elastic path in uniaxial strain: dS_xx/dt = (4 mu / 3) du/dx = -(4 mu / 3) (1/rho) drho/dt
  // (docs/algorithm.md §7 with L_yy = 0), so S_xx = (4 mu / 3) ln(rho0 / rho), S_yy = S_zz =
  // -S_xx / 2 and sqrt(3/2 S:S) = 3/2 |S_xx|: yield at S_xx = -2Y/3, rho = rho0 exp(Y / (2 mu)).
  const double s_yield = -2.0 * yield / 3.0;
  const double rho_elastic = eos.rho0 * std::exp(yield / (2.0 * mu));
  elastic_ = shocked_state(eos, initial_, rho_elastic, s_yield, elastic_speed_);

  const double up = parameters.piston_velocity;
  if (up <= elastic_.velocity) {
    std::ostringstream message;
    message << "piston exact solution: piston velocity " << up << " does not exceed the elastic limit velocity "
            << elastic_.velocity << " (single elastic wave, not a two-wave problem)";
    throw Error(message.str());
  }

  // Plastic shock: S_xx stays on the yield surface; find rho2 with u2 = piston velocity by
  // bisection in eta2 (the velocity jump grows monotonically with the compression).
  const double eta1 = 1.0 - eos.rho0 / rho_elastic;
  double eta_low = eta1;
  double eta_high = (eos.s > 1.0 ? 1.0 / eos.s : 1.0) * (1.0 - 1e-9);
  double speed = 0;
  auto velocity_at = [&](double eta) {
    return shocked_state(eos, elastic_, eos.rho0 / (1.0 - eta), s_yield, speed).velocity;
  };
  if (velocity_at(eta_high) < up) throw Error("piston exact solution: piston velocity beyond the EOS domain");
  for (int iteration = 0; iteration < 200 && eta_high - eta_low > 1e-17; ++iteration) {
    const double eta = 0.5 * (eta_low + eta_high);
    (velocity_at(eta) < up ? eta_low : eta_high) = eta;
  }
  const double eta2 = 0.5 * (eta_low + eta_high);
  plastic_ = shocked_state(eos, elastic_, eos.rho0 / (1.0 - eta2), s_yield, plastic_speed_);
  if (plastic_speed_ >= elastic_speed_)
    throw Error("piston exact solution: the plastic shock overtakes the elastic precursor (overdriven)");
}

SolidState ElasticPlasticPiston::sample(double x, double t) const {
  if (t <= 0 || x > elastic_speed_ * t) return initial_;
  if (x > plastic_speed_ * t) return elastic_;
  return plastic_;
}

}  // namespace stagger
