#pragma once
// The per-material constants the zone loops read (one range of zones = one material).
#include <functional>

#include "hydro/kernels/burn.hpp"

namespace stagger {

struct ZoneModel {
  bool strength = false;
  double mu = 0, yield = 0;  // shear modulus and initial yield stress Y0 (strength)
  double hardening = 0;      // linear hardening modulus H: Y = Y0 + H eps_p (strength)
  bool burn = false;
  BurnModel burn_model;            // (burn)
  double edge_gamma_factor = 0.5;  // the edge viscosity's quadratic factor
  double min_energy = -1e300;      // below it the run stops
};

// Specific energy source s_e(x, y, t) of a manufactured solution.
using EnergySource = std::function<double(double, double, double)>;

}  // namespace stagger
