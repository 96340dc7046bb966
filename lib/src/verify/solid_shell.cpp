/// @file solid_shell.cpp
/// Howell & Ball's incompressible rigid-plastic shell collapse (J. Comput. Phys. 175, 2002,
/// "A free-Lagrange augmented Godunov method for the simulation of elastic-plastic solids").
/// Derivation: docs/derivations.md section 2.
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

/// F(r) = (r + C) ln(r + C) - r ln r, so that dF/dr = ln((r + C) / r) = 2 ln(Ro / Ri).
double potential(double r2, double c) {
  return (r2 + c) * std::log(r2 + c) - r2 * std::log(r2);
}

/// dt/dsigma = sigma / |Ri Ri'| with r = Ri^2 = r_stop + sigma^2 and
/// (Ri Ri')^2 ln(Ro/Ri) = beta (F(r) - F(r_stop)): smooth, finite at sigma = 0.
double time_integrand(double sigma, double r2_stop, double c, double beta) {
  const double h = sigma * sigma;
  const double r2 = r2_stop + h;
  // (F(r2) - F(r_stop)) / h, by Taylor expansion where the difference would cancel.
  const double divided = h < 1e-6 * r2_stop
                             ? std::log((r2_stop + c) / r2_stop) + 0.5 * h * (1.0 / (r2_stop + c) - 1.0 / r2_stop)
                             : (potential(r2, c) - potential(r2_stop, c)) / h;
  const double log_ratio = 0.5 * std::log((r2 + c) / r2);
  return std::sqrt(log_ratio / (beta * divided));
}

}  // namespace

HowellBallShell::HowellBallShell(const ShellParameters& parameters) : parameters_(parameters) {
  const ShellParameters& p = parameters;
  if (!(p.inner_radius > 0 && p.outer_radius > p.inner_radius && p.velocity > 0 && p.density > 0 && p.yield_stress > 0))
    throw Error("Howell-Ball shell: need 0 < inner radius < outer radius and positive V0, density, yield stress");
  c_ = p.outer_radius * p.outer_radius - p.inner_radius * p.inner_radius;
  const double r2_0 = p.inner_radius * p.inner_radius;
  const double q0 = p.inner_radius * p.velocity;  // |Ri Ri'| at t = 0
  const double log0 = std::log(p.outer_radius / p.inner_radius);
  // Energy balance in r = Ri^2 (docs/derivations.md eq. 2.5): (Ri Ri')^2 ln(Ro/Ri) =
  // beta (F(r) - F(r_stop)), beta = Y / (sqrt(3) rho).
  const double beta = p.yield_stress / (std::numbers::sqrt3 * p.density);
  const double f_stop = potential(r2_0, c_) - q0 * q0 * log0 / beta;
  if (f_stop <= c_ * std::log(c_))
    throw Error(
        "Howell-Ball shell: the kinetic energy exceeds what plastic work can absorb before the "
        "inner surface reaches the axis (no stopping radius)");
  double low = 0, high = r2_0;
  for (int iteration = 0; iteration < 200 && high - low > 1e-18 * r2_0; ++iteration) {
    const double mid = 0.5 * (low + high);
    (potential(mid, c_) < f_stop ? low : high) = mid;
  }
  const double r2_stop = 0.5 * (low + high);
  inner_stop_ = std::sqrt(r2_stop);

  // t(sigma) with r = r_stop + sigma^2: dt = dr / (2 |Ri Ri'|) = sigma / |Ri Ri'| dsigma, a
  // smooth integrand (|Ri Ri'| ~ sigma near the stop). Cumulative from sigma = 0.
  const double sigma0 = std::sqrt(r2_0 - r2_stop);
  auto integrand = [&](double sigma) { return time_integrand(sigma, r2_stop, c_, beta); };
  sigma_.resize(kIntervals + 1);
  time_.assign(kIntervals + 1, 0.0);
  for (int k = 0; k <= kIntervals; ++k) sigma_[k] = sigma0 * k / kIntervals;
  for (int k = 0; k < kIntervals; ++k) {
    const double a = sigma_[k], b = sigma_[k + 1];
    double sum = 0;
    for (int g = 0; g < 4; ++g) sum += kGaussWeights[g] * integrand(0.5 * (a + b) + 0.5 * (b - a) * kGaussNodes[g]);
    time_[k + 1] = time_[k] + 0.5 * (b - a) * sum;
  }
  stopping_time_ = time_.back();
}

double HowellBallShell::inner_radius_squared(double t) const {
  const double r2_stop = inner_stop_ * inner_stop_;
  if (t >= stopping_time_) return r2_stop;
  if (t <= 0) return parameters_.inner_radius * parameters_.inner_radius;
  const double target = stopping_time_ - t;  // time still to go = T(sigma)
  const auto it = std::upper_bound(time_.begin(), time_.end(), target);
  const auto k = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(it - time_.begin() - 1, 0, kIntervals - 1));
  const double beta = parameters_.yield_stress / (std::numbers::sqrt3 * parameters_.density);
  auto integrand = [&](double sigma) { return time_integrand(sigma, r2_stop, c_, beta); };
  // Newton on T(sigma) = time_[k] + int_{sigma_k}^{sigma} integrand = target.
  const double a = sigma_[k];
  double sigma = a + (sigma_[k + 1] - a) * (target - time_[k]) / (time_[k + 1] - time_[k]);
  for (int iteration = 0; iteration < 8; ++iteration) {
    double sum = 0;
    for (int g = 0; g < 4; ++g)
      sum += kGaussWeights[g] * integrand(0.5 * (a + sigma) + 0.5 * (sigma - a) * kGaussNodes[g]);
    const double value = time_[k] + 0.5 * (sigma - a) * sum;
    sigma -= (value - target) / integrand(sigma);
  }
  return r2_stop + sigma * sigma;
}

double HowellBallShell::velocity_at(double r2) const {
  // |Ri Ri'| = sqrt(beta (F(r2) - F(r_stop)) / ln(Ro / Ri)).
  const double beta = parameters_.yield_stress / (std::numbers::sqrt3 * parameters_.density);
  const double energy = beta * (potential(r2, c_) - potential(inner_stop_ * inner_stop_, c_));
  return energy > 0 ? std::sqrt(energy / (0.5 * std::log((r2 + c_) / r2))) : 0.0;
}

double HowellBallShell::inner_radius(double t) const {
  return std::sqrt(inner_radius_squared(t));
}

double HowellBallShell::outer_radius(double t) const {
  return std::sqrt(inner_radius_squared(t) + c_);
}

double HowellBallShell::outer_stopping_radius() const {
  return std::sqrt(inner_stop_ * inner_stop_ + c_);
}

double HowellBallShell::inner_velocity(double t) const {
  if (t >= stopping_time_) return 0.0;
  const double r2 = inner_radius_squared(t);
  return -velocity_at(r2) / std::sqrt(r2);
}

double HowellBallShell::kinetic_energy(double t) const {
  if (t >= stopping_time_) return 0.0;
  const double r2 = inner_radius_squared(t);
  const double q = velocity_at(r2);
  return std::numbers::pi * parameters_.density * q * q * 0.5 * std::log((r2 + c_) / r2);
}

double HowellBallShell::dissipation_rate(double t) const {
  if (t >= stopping_time_) return 0.0;
  const double r2 = inner_radius_squared(t);
  // int (2 / sqrt(3)) Y |Ri Ri'| / r^2 2 pi r dr over the shell.
  return 4.0 * std::numbers::pi / std::numbers::sqrt3 * parameters_.yield_stress * velocity_at(r2) * 0.5 *
         std::log((r2 + c_) / r2);
}

}  // namespace stagger
