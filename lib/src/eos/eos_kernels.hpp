#pragma once
// Pointwise equations of state, inlined into the zone loops (docs/algorithm.md §3).
// Each returns false when (rho, e) is outside the model's domain, so the caller can stop the
// run with a message naming the zone.
#include <cmath>

#include "stagger/materials.hpp"

namespace stagger::eos {

struct PressureSound {
  double p;
  double c2;  // adiabatic sound speed squared
};

inline bool evaluate(const IdealGas& g, double rho, double e, PressureSound& out) {
  out.p = (g.gamma - 1.0) * rho * e;
  // c^2 = dp/drho|_e + p/rho^2 dp/de|_rho = gamma (gamma-1) e, kept >= 0 for e ~ 0.
  out.c2 = std::max(g.gamma * (g.gamma - 1.0) * e, 0.0);
  return rho > 0.0;
}

// Paper eq. (6): eta = 1 - rho0/rho; the closed-form c^2 = dp/drho|_e + p/rho^2 dp/de|_rho
// (docs/algorithm.md §3).
inline bool evaluate(const MieGruneisen& m, double rho, double e, PressureSound& out) {
  const double eta = 1.0 - m.rho0 / rho;
  const double denom = 1.0 - m.s * eta;
  if (!(denom > 0.0) || !(rho > 0.0)) return false;
  const double u = m.a0 * eta / denom;  // particle-velocity jump on the Hugoniot
  out.p = m.rho0 * m.a0 * m.a0 * eta / (denom * denom) + m.gamma0 * m.rho0 * (e - 0.5 * u * u);
  const double r = m.rho0 / rho;
  out.c2 = r * r * m.a0 * m.a0 * (1.0 + (m.s - m.gamma0) * eta) / (denom * denom * denom) +
           out.p * m.gamma0 * m.rho0 / (rho * rho);
  return out.c2 > 0.0;
}

// JWL products; V = rho0/rho. c^2 = dp/drho|_e + (p/rho^2) omega rho.
inline bool evaluate(const Jwl& j, double rho, double e, PressureSound& out) {
  if (!(rho > 0.0)) return false;
  const double v = j.rho0 / rho;
  const double e1 = std::exp(-j.R1 * v), e2 = std::exp(-j.R2 * v);
  const double t1 = j.A * (1.0 - j.omega / (j.R1 * v)) * e1;
  const double t2 = j.B * (1.0 - j.omega / (j.R2 * v)) * e2;
  out.p = t1 + t2 + j.omega * rho * e;
  // d/dV of the two cold terms
  const double d1 = j.A * (j.omega / (j.R1 * v * v)) * e1 - j.R1 * t1;
  const double d2 = j.B * (j.omega / (j.R2 * v * v)) * e2 - j.R2 * t2;
  const double dp_drho = (d1 + d2) * (-v / rho) + j.omega * e;
  out.c2 = dp_drho + out.p * j.omega / rho;
  return out.c2 > 0.0;
}

// Stiffened gas: c^2 = (gamma - 1)(e + p/rho) = gamma (p + p_inf)/rho, positive while p > -p_inf
// (docs/algorithm.md §3).
inline bool evaluate(const StiffenedGas& g, double rho, double e, PressureSound& out) {
  out.p = (g.gamma - 1.0) * rho * e - g.gamma * g.p_inf;
  out.c2 = g.gamma * (out.p + g.p_inf) / rho;
  return rho > 0.0 && out.c2 > 0.0;
}

}  // namespace stagger::eos
