/// @file solid_detonation.cpp
/// Planar Chapman-Jouguet detonation with its Taylor wave for JWL products (problem 2,
/// docs/verification.md §9). Derivation: docs/derivations.md section 3.
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

// 8-point Gauss-Legendre on [-1, 1] (Abramowitz & Stegun 25.4.30).
constexpr std::array<double, 8> kNodes{-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                       -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                       0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeights{0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                         0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                         0.2223810344533745, 0.1012285362903763};
constexpr double kPanel = 2e-3;  // width of a Riemann-invariant quadrature panel in V

/// The JWL terms that do not depend on the energy, f(V), and df/dV (docs/algorithm.md §3:
/// p = f(V) + omega E / V with E = rho0 e the energy per initial volume).
double jwl_cold(const Jwl& j, double v) {
  return j.A * (1.0 - j.omega / (j.R1 * v)) * std::exp(-j.R1 * v) +
         j.B * (1.0 - j.omega / (j.R2 * v)) * std::exp(-j.R2 * v);
}
double jwl_cold_derivative(const Jwl& j, double v) {
  return j.A * std::exp(-j.R1 * v) * (j.omega / (j.R1 * v * v) - j.R1 + j.omega / v) +
         j.B * std::exp(-j.R2 * v) * (j.omega / (j.R2 * v * v) - j.R2 + j.omega / v);
}
/// c^2 = dp/drho|_e + p / rho^2 dp/de|_rho = (V^2 / rho0) (-f'(V) + omega E / V^2 + omega p / V).
double jwl_sound_speed_squared(const Jwl& j, double v, double energy_per_volume) {
  const double p = jwl_cold(j, v) + j.omega * energy_per_volume / v;
  return v * v / j.rho0 * (-jwl_cold_derivative(j, v) + j.omega * energy_per_volume / (v * v) + j.omega * p / v);
}

}  // namespace

double CJDetonation::jwl_pressure(double v, double energy_per_volume) const {
  return jwl_cold(parameters_.eos, v) + parameters_.eos.omega * energy_per_volume / v;
}

double CJDetonation::hugoniot_pressure(double v) const {
  // E - E0 = p (1 - V) / 2 (p0 = 0) with p = f + omega E / V, solved for p.
  const Jwl& j = parameters_.eos;
  return (jwl_cold(j, v) + j.omega * parameters_.energy_per_volume / v) / (1.0 - 0.5 * j.omega * (1.0 - v) / v);
}

double CJDetonation::isentrope_pressure(double v) const {
  const Jwl& j = parameters_.eos;
  return j.A * std::exp(-j.R1 * v) + j.B * std::exp(-j.R2 * v) + isentrope_c_ * std::pow(v, -(1.0 + j.omega));
}

double CJDetonation::isentrope_sound_speed(double v) const {
  // c^2 = -dp/dv|_s with v = V / rho0: (V^2 / rho0) (-dp_s/dV).
  const Jwl& j = parameters_.eos;
  const double slope = j.R1 * j.A * std::exp(-j.R1 * v) + j.R2 * j.B * std::exp(-j.R2 * v) +
                       (1.0 + j.omega) * isentrope_c_ * std::pow(v, -(2.0 + j.omega));
  return std::sqrt(v * v / j.rho0 * slope);
}

double CJDetonation::isentrope_velocity(double v) const {
  // u(V) = u_CJ - int_{V_CJ}^{V} c(V') / V' dV' (the invariant u - int c drho / rho).
  auto integral = [&](double a, double b) {
    double sum = 0;
    for (std::size_t g = 0; g < kNodes.size(); ++g) {
      const double w = 0.5 * (a + b) + 0.5 * (b - a) * kNodes[g];
      sum += kWeights[g] * isentrope_sound_speed(w) / w;
    }
    return 0.5 * (b - a) * sum;
  };
  if (panel_v_.empty() || v <= panel_v_.front()) return cj_.velocity - integral(v_cj_, v);
  const auto it = std::upper_bound(panel_v_.begin(), panel_v_.end(), v);
  const auto k = static_cast<std::size_t>(it - panel_v_.begin() - 1);
  return panel_u_[k] - integral(panel_v_[k], v);
}

CJDetonation::CJDetonation(const DetonationParameters& parameters) : parameters_(parameters) {
  const Jwl& j = parameters.eos;
  const double rho0 = j.rho0;
  if (!(rho0 > 0 && j.omega > 0 && j.R1 > 0 && j.R2 > 0 && parameters.energy_per_volume > 0))
    throw Error("CJ detonation: rho0, omega, R1, R2 and the detonation energy must be positive");

  // CJ point: on the Hugoniot, D^2 = p_H / (rho0 (1 - V)), u = D (1 - V); tangency of the
  // Rayleigh line <=> D - u = D V = c (Fickett & Davis ch. 2). h(V) = (D V)^2 - c^2 is < 0 on
  // the strong branch and > 0 on the weak one: bracket from V -> 1 downwards, then bisect.
  auto speed_squared = [&](double v) { return hugoniot_pressure(v) / (rho0 * (1.0 - v)); };
  auto sonic_residual = [&](double v) {
    const double p = hugoniot_pressure(v);
    const double energy = parameters_.energy_per_volume + 0.5 * p * (1.0 - v);
    return speed_squared(v) * v * v - jwl_sound_speed_squared(j, v, energy);
  };
  double high = 0.999;
  double low = high;
  while (sonic_residual(low) > 0) {
    low -= 1e-3;
    if (low < 0.2) throw Error("CJ detonation: no Chapman-Jouguet point found for this JWL fit");
  }
  high = low + 1e-3;
  for (int iteration = 0; iteration < 200 && high - low > 1e-16; ++iteration) {
    const double mid = 0.5 * (low + high);
    (sonic_residual(mid) < 0 ? low : high) = mid;
  }
  v_cj_ = 0.5 * (low + high);
  speed_ = std::sqrt(speed_squared(v_cj_));
  cj_.density = rho0 / v_cj_;
  cj_.pressure = hugoniot_pressure(v_cj_);
  cj_.velocity = speed_ * (1.0 - v_cj_);
  const double e_cj = parameters_.energy_per_volume + 0.5 * cj_.pressure * (1.0 - v_cj_);
  cj_.sound_speed = std::sqrt(jwl_sound_speed_squared(j, v_cj_, e_cj));

  // Isentrope through the CJ point: p_s = A e^{-R1 V} + B e^{-R2 V} + C V^{-(1 + omega)}.
  isentrope_c_ =
      (cj_.pressure - j.A * std::exp(-j.R1 * v_cj_) - j.B * std::exp(-j.R2 * v_cj_)) * std::pow(v_cj_, 1.0 + j.omega);

  // Riemann invariant by panels from V_CJ until u changes sign: the rest state (plateau).
  panel_v_ = {v_cj_};
  panel_u_ = {cj_.velocity};
  while (true) {
    const double a = panel_v_.back();
    const double u_end = isentrope_velocity(a + kPanel);  // integrates over the last panel only
    if (u_end <= 0) break;
    panel_v_.push_back(a + kPanel);
    panel_u_.push_back(u_end);
    if (panel_v_.size() > 100000) throw Error("CJ detonation: the Taylor wave does not reach rest");
  }
  double v_low = panel_v_.back(), v_high = panel_v_.back() + kPanel;
  for (int iteration = 0; iteration < 200 && v_high - v_low > 1e-16; ++iteration) {
    const double mid = 0.5 * (v_low + v_high);
    (isentrope_velocity(mid) > 0 ? v_low : v_high) = mid;
  }
  v_plateau_ = 0.5 * (v_low + v_high);
  plateau_.density = rho0 / v_plateau_;
  plateau_.velocity = 0;
  plateau_.pressure = isentrope_pressure(v_plateau_);
  plateau_.sound_speed = isentrope_sound_speed(v_plateau_);
}

DetonationState CJDetonation::sample(double x, double t) const {
  const double xi = t > 0 ? (x - parameters_.x0) / t : 1e300;
  if (xi > speed_) return {parameters_.eos.rho0, 0.0, 0.0, 0.0};
  if (xi <= plateau_.sound_speed) return plateau_;
  // Fan: x / t = u + c, decreasing along the isentrope from the CJ point (u + c = D) to rest.
  double low = v_cj_, high = v_plateau_;
  for (int iteration = 0; iteration < 200 && high - low > 1e-15; ++iteration) {
    const double mid = 0.5 * (low + high);
    (isentrope_velocity(mid) + isentrope_sound_speed(mid) > xi ? low : high) = mid;
  }
  const double v = 0.5 * (low + high);
  return {parameters_.eos.rho0 / v, isentrope_velocity(v), isentrope_pressure(v), isentrope_sound_speed(v)};
}

}  // namespace stagger
