#pragma once
// Programmed burn of high explosives (docs/algorithm.md §8): the fraction F in [0, 1] that
// multiplies the JWL pressure.
#include <algorithm>

namespace stagger {

// Per-material burn constants.
struct BurnModel {
  double detonation_speed = 1;
  bool beta_burn = false;         // also F >= (1 - V) / (1 - V_CJ)
  double cj_relative_volume = 1;  // V_CJ = rho0 / rho_CJ
  double rho0 = 1;                // reference density of the products' JWL
};

// LS-DYNA's programmed burn F = (t - t_l) D / L (zero before the lighting time t_l), optionally
// with beta burn; never decreasing (max with the previous value) and clamped to [0, 1].
[[gnu::always_inline]] inline double burn_fraction(double previous, double t, double lighting_time, double burn_length,
                                                   const BurnModel& b, double rho) {
  double f = t > lighting_time ? (t - lighting_time) * b.detonation_speed / burn_length : 0.0;
  if (b.beta_burn && b.cj_relative_volume < 1) {
    const double v = b.rho0 / rho;
    f = std::max(f, (1 - v) / (1 - b.cj_relative_volume));
  }
  return std::clamp(std::max(previous, f), 0.0, 1.0);
}

}  // namespace stagger
