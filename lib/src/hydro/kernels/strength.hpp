#pragma once
// Deviatoric stress: Wilkins' hypo-elastic update (rate or objective form), plane strain
// (docs/algorithm.md §7), and the predictor's return through the strength model's radial return
// (lib/src/strength/). Pointwise, inlined into the zone loops.
#include <algorithm>
#include <cmath>

#include "hydro/kernels/geometry.hpp"
#include "strength/linear_hardening.hpp"

namespace stagger {

// Jaumann rate: dS/dt = 2 mu (D - tr(D)/3 I) + W S - S W, evaluated at stress s.
[[gnu::always_inline]] inline Deviator stress_rate(double mu, const Deviator& s, const VelocityGradient& L) {
  const double spin = L.xy - L.yx;
  return {(4.0 / 3.0) * mu * L.xx - (2.0 / 3.0) * mu * L.yy + s.xy * spin,
          (4.0 / 3.0) * mu * L.yy - (2.0 / 3.0) * mu * L.xx - s.xy * spin,
          mu * (L.xy + L.yx) + 0.5 * (s.yy - s.xx) * spin};
}

// S(t+h) from S(t): either the rate form S + h dS/dt(s_rate, L) (the paper's), or the
// objective incremental update R S R^T + 2 mu D0 h with the Hughes-Winget rotation.
[[gnu::always_inline]] inline Deviator advance_stress(bool objective, double mu, const Deviator& s0,
                                                      const Deviator& s_rate, const VelocityGradient& L, double h) {
  if (!objective) {
    const Deviator r = stress_rate(mu, s_rate, L);
    return {s0.xx + h * r.xx, s0.yy + h * r.yy, s0.xy + h * r.xy};
  }
  const double a = 0.25 * h * (L.xy - L.yx);  // h w / 2 with w = (L_xy - L_yx)/2
  const double cs = (1 - a * a) / (1 + a * a), sn = 2 * a / (1 + a * a);
  Deviator out{cs * cs * s0.xx + 2 * cs * sn * s0.xy + sn * sn * s0.yy,
               sn * sn * s0.xx - 2 * sn * cs * s0.xy + cs * cs * s0.yy,
               -cs * sn * s0.xx + (cs * cs - sn * sn) * s0.xy + sn * cs * s0.yy};
  out.xx += h * ((4.0 / 3.0) * mu * L.xx - (2.0 / 3.0) * mu * L.yy);
  out.yy += h * ((4.0 / 3.0) * mu * L.yy - (2.0 / 3.0) * mu * L.xx);
  out.xy += h * mu * (L.xy + L.yx);
  return out;
}

// Half-step stress of the predictor (step 3): S^{n+1/2} = return(S^n + h dS/dt(S^n, L)),
// L = L(v^n) on x^n, returned onto the surface hardened from eps_p^n; S^n itself for h = 0
// (a force evaluation at t^n). The plastic strain it implies is not kept (step 8 owns it).
[[gnu::always_inline]] inline Deviator predict_stress(bool objective, double mu, double yield0, double hardening,
                                                      double eps_p, const Deviator& s0, const VelocityGradient& L,
                                                      double h) {
  Deviator sh = s0;
  if (h > 0) {
    sh = advance_stress(objective, mu, s0, s0, L, h);
    radial_return(yield0, hardening, eps_p, mu, sh);
  }
  return sh;
}

// Full sound speed C = sqrt(c^2 + 4/3 mu / rho): the EOS's adiabatic c^2 (clipped at 0) plus
// the shear contribution of an elastic solid (mu = 0 for a fluid).
[[gnu::always_inline]] inline double full_sound_speed(double c2, double rho, bool strength, double mu) {
  return std::sqrt(std::max(c2, 0.0) + (strength ? (4.0 / 3.0) * mu / rho : 0.0));
}

}  // namespace stagger
