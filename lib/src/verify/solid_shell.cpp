/// @file solid_shell.cpp
/// Howell & Ball's incompressible rigid-plastic shell collapse (J. Comput. Phys. 175, 2002,
/// "A free-Lagrange augmented Godunov method for the simulation of elastic-plastic solids"),
/// and its spherical analogue, Verney's problem (D. Verney, "Evaluation de la limite elastique
/// du cuivre et de l'uranium par des experiences d'implosion lente", Behaviour of Dense Media
/// under High Dynamic Pressures, IUTAM Symposium, Paris, 1968). Derivation: docs/derivations.md
/// sections 2 and 2.1.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

// 4-point Gauss-Legendre on [-1, 1] (Abramowitz & Stegun 25.4.30).
constexpr std::array<double, 4> kGaussNodes{-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                            0.8611363115940526};
constexpr std::array<double, 4> kGaussWeights{0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                              0.3478548451374538};
constexpr int kIntervals = 2000;

/// F(s) = (s + C) ln(s + C) - s ln s, so that dF/ds = ln((s + C) / s) = n ln(Ro / Ri) with
/// s = Ri^n, C = Ro^n - Ri^n (n = 2 cylindrical, 3 spherical).
double potential(double s, double c) {
  return (s + c) * std::log(s + c) - s * std::log(s);
}

}  // namespace

double HowellBallShell::shape(double s) const {
  // Cylinder: ln(Ro/Ri); sphere: 1/Ri - 1/Ro (docs/derivations.md eqs. 2.1 and 2.6).
  return parameters_.spherical ? 1.0 / std::cbrt(s) - 1.0 / std::cbrt(s + c_) : 0.5 * std::log((s + c_) / s);
}

double HowellBallShell::power(double r) const {
  return parameters_.spherical ? r * r * r : r * r;
}

double HowellBallShell::radius(double s) const {
  return parameters_.spherical ? std::cbrt(s) : std::sqrt(s);
}

HowellBallShell::HowellBallShell(const ShellParameters& parameters) : parameters_(parameters) {
  const ShellParameters& p = parameters;
  if (!(p.inner_radius > 0 && p.outer_radius > p.inner_radius && p.velocity > 0 && p.density > 0 && p.yield_stress > 0))
    throw Error("Howell-Ball shell: need 0 < inner radius < outer radius and positive V0, density, yield stress");
  n_ = p.spherical ? 3.0 : 2.0;
  c_ = power(p.outer_radius) - power(p.inner_radius);
  const double s0 = power(p.inner_radius);
  // |Ri^(n-1) Ri'| at t = 0
  const double q0 = (p.spherical ? p.inner_radius * p.inner_radius : p.inner_radius) * p.velocity;
  // Energy balance in s = Ri^n (docs/derivations.md eqs. 2.4 and 2.8): Q^2 shape(s) =
  // beta (F(s) - F(s_stop)), beta = Y / (sqrt(3) rho) (cylinder), 4 Y / (9 rho) (sphere).
  beta_ = p.spherical ? 4.0 * p.yield_stress / (9.0 * p.density) : p.yield_stress / (std::numbers::sqrt3 * p.density);
  const double shape0 = p.spherical ? shape(s0) : std::log(p.outer_radius / p.inner_radius);
  const double f_stop = potential(s0, c_) - q0 * q0 * shape0 / beta_;
  if (f_stop <= c_ * std::log(c_))
    throw Error(std::string(p.spherical ? "Verney" : "Howell-Ball") +
                " shell: the kinetic energy exceeds what plastic work can absorb before the "
                "inner surface reaches the axis (no stopping radius)");
  double low = 0, high = s0;
  for (int iteration = 0; iteration < 200 && high - low > 1e-18 * s0; ++iteration) {
    const double mid = 0.5 * (low + high);
    (potential(mid, c_) < f_stop ? low : high) = mid;
  }
  const double s_stop = 0.5 * (low + high);
  inner_stop_ = radius(s_stop);

  // t(sigma) with s = s_stop + sigma^2: dt = ds / (n |Q|) = (2 sigma / n) / |Q| dsigma, a
  // smooth integrand (|Q| ~ sigma near the stop). Cumulative from sigma = 0.
  const double sigma0 = std::sqrt(s0 - s_stop);
  sigma_.resize(kIntervals + 1);
  time_.assign(kIntervals + 1, 0.0);
  for (int k = 0; k <= kIntervals; ++k) sigma_[k] = sigma0 * k / kIntervals;
  for (int k = 0; k < kIntervals; ++k) {
    const double a = sigma_[k], b = sigma_[k + 1];
    double sum = 0;
    for (int g = 0; g < 4; ++g)
      sum += kGaussWeights[g] * time_integrand(0.5 * (a + b) + 0.5 * (b - a) * kGaussNodes[g], s_stop);
    time_[k + 1] = time_[k] + 0.5 * (b - a) * sum;
  }
  stopping_time_ = time_.back();
}

double HowellBallShell::time_integrand(double sigma, double s_stop) const {
  // dt/dsigma = (2 / n) sigma / |Q| with s = s_stop + sigma^2 and Q^2 shape(s) =
  // beta (F(s) - F(s_stop)): smooth, finite at sigma = 0.
  const double h = sigma * sigma;
  const double s = s_stop + h;
  // (F(s) - F(s_stop)) / h, by Taylor expansion where the difference would cancel.
  const double divided = h < 1e-6 * s_stop
                             ? std::log((s_stop + c_) / s_stop) + 0.5 * h * (1.0 / (s_stop + c_) - 1.0 / s_stop)
                             : (potential(s, c_) - potential(s_stop, c_)) / h;
  return (2.0 / n_) * std::sqrt(shape(s) / (beta_ * divided));
}

double HowellBallShell::inner_power(double t) const {
  const double s_stop = power(inner_stop_);
  if (t >= stopping_time_) return s_stop;
  if (t <= 0) return power(parameters_.inner_radius);
  const double target = stopping_time_ - t;  // time still to go = T(sigma)
  const auto it = std::upper_bound(time_.begin(), time_.end(), target);
  const auto k = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(it - time_.begin() - 1, 0, kIntervals - 1));
  // Newton on T(sigma) = time_[k] + int_{sigma_k}^{sigma} integrand = target.
  const double a = sigma_[k];
  double sigma = a + (sigma_[k + 1] - a) * (target - time_[k]) / (time_[k + 1] - time_[k]);
  for (int iteration = 0; iteration < 8; ++iteration) {
    double sum = 0;
    for (int g = 0; g < 4; ++g)
      sum += kGaussWeights[g] * time_integrand(0.5 * (a + sigma) + 0.5 * (sigma - a) * kGaussNodes[g], s_stop);
    const double value = time_[k] + 0.5 * (sigma - a) * sum;
    sigma -= (value - target) / time_integrand(sigma, s_stop);
  }
  return s_stop + sigma * sigma;
}

double HowellBallShell::velocity_at(double s) const {
  // |Q| = sqrt(beta (F(s) - F(s_stop)) / shape(s)).
  const double energy = beta_ * (potential(s, c_) - potential(power(inner_stop_), c_));
  return energy > 0 ? std::sqrt(energy / shape(s)) : 0.0;
}

double HowellBallShell::inner_radius(double t) const {
  return radius(inner_power(t));
}

double HowellBallShell::outer_radius(double t) const {
  return radius(inner_power(t) + c_);
}

double HowellBallShell::outer_stopping_radius() const {
  return radius(power(inner_stop_) + c_);
}

double HowellBallShell::inner_velocity(double t) const {
  if (t >= stopping_time_) return 0.0;
  const double s = inner_power(t);
  const double r = radius(s);
  return -velocity_at(s) / (parameters_.spherical ? r * r : r);
}

double HowellBallShell::kinetic_energy(double t) const {
  if (t >= stopping_time_) return 0.0;
  const double s = inner_power(t);
  const double q = velocity_at(s);
  // Cylinder: pi rho Q^2 ln(Ro/Ri) per unit length; sphere: 2 pi rho Q^2 (1/Ri - 1/Ro).
  return (parameters_.spherical ? 2.0 : 1.0) * std::numbers::pi * parameters_.density * q * q * shape(s);
}

double HowellBallShell::dissipation_rate(double t) const {
  if (t >= stopping_time_) return 0.0;
  const double s = inner_power(t);
  const double log_ratio = std::log((s + c_) / s) / n_;  // ln(Ro / Ri)
  // Cylinder: int (2 / sqrt(3)) Y |Q| / r^2 2 pi r dr; sphere: int 2 Y |Q| / r^3 4 pi r^2 dr.
  const double factor = parameters_.spherical ? 8.0 * std::numbers::pi : 4.0 * std::numbers::pi / std::numbers::sqrt3;
  return factor * parameters_.yield_stress * velocity_at(s) * log_ratio;
}

}  // namespace stagger
