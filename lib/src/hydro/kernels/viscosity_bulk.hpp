#pragma once
// Zone-centred bulk artificial viscosity (docs/algorithm.md §4).
namespace stagger {

// q = rho l |div v| (q2 C + q1 l |div v|) in compression (div v < 0), zero in expansion:
// q2 is the linear coefficient (on the sound speed C), q1 the quadratic one.
[[gnu::always_inline]] inline double bulk_viscosity(double rho, double l, double div, double C, double q1, double q2) {
  return div < 0 ? rho * l * (-div) * (q2 * C + q1 * l * (-div)) : 0.0;
}

}  // namespace stagger
