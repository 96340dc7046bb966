// Mixed-zone closure (closure.hpp).
#include "mixed/closure.hpp"

#include <algorithm>
#include <cmath>

#include "eos/eos_kernels.hpp"

namespace stagger::mixed {

bool evaluate_components(double v, std::span<Component> components, ZoneMixture& mixture) {
  double p = 0, bulk = 0, mass = 0;
  for (Component& k : components) {
    k.rho = k.mass / (k.fraction * v);
    eos::PressureSound ps{};
    if (!std::visit([&](const auto& model) { return eos::evaluate(model, k.rho, k.e, ps); }, *k.eos)) return false;
    k.p = ps.p;
    k.c2 = ps.c2;
    p += k.fraction * k.p;
    bulk += k.fraction * k.rho * k.c2;
    mass += k.mass;
  }
  mixture.p = p;
  mixture.c2 = bulk * v / mass;
  return true;
}

void relaxed_volume_changes(double v_old, double dv, std::span<const Component> components, std::vector<double>& dv_k) {
  const std::size_t n = components.size();
  dv_k.assign(n, 0.0);
  // p_bar = (sum V_k p_k / B_k - dV) / sum V_k / B_k, B_k = rho_k c_k^2.
  double weighted_p = 0, compliance = 0;
  for (const Component& k : components) {
    const double volume = k.fraction * v_old, bulk = std::max(k.rho * k.c2, 1e-300);
    weighted_p += volume * k.p / bulk;
    compliance += volume / bulk;
  }
  const double p_bar = (weighted_p - dv) / compliance;
  double assigned = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Component& k = components[i];
    const double volume = k.fraction * v_old, bulk = std::max(k.rho * k.c2, 1e-300);
    dv_k[i] = std::max(volume * (k.p - p_bar) / bulk, -0.5 * volume);
    assigned += dv_k[i];
  }
  dv_k[n - 1] = dv - assigned;  // the volumes add up to the zone's
}

bool advance_components(Closure closure, double v_old, double v_new, double d_energy, std::span<Component> components) {
  const std::size_t n = components.size();
  const double dv = v_new - v_old;
  std::vector<double> dv_k(n);
  if (closure == Closure::uniform_strain) {
    for (std::size_t i = 0; i < n; ++i) dv_k[i] = components[i].fraction * dv;
  } else {
    relaxed_volume_changes(v_old, dv, components, dv_k);
  }
  // Each component's own p dV; what the zone's compatible change holds beyond their sum (q's
  // work and the compatible correction) is shared by volume fraction; the last component
  // takes the remainder, so the shares sum to d_energy.
  double own = 0;
  for (std::size_t i = 0; i < n; ++i) own += -components[i].p * dv_k[i];
  const double rest = d_energy - own;
  double assigned = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double share = -components[i].p * dv_k[i] + components[i].fraction * rest;
    components[i].e += share / components[i].mass;
    assigned += share;
  }
  components[n - 1].e += (d_energy - assigned) / components[n - 1].mass;
  for (std::size_t i = 0; i < n; ++i) {
    const double volume = components[i].fraction * v_old + dv_k[i];
    if (!(volume > 0)) return false;
    components[i].fraction = volume / v_new;
  }
  ZoneMixture mixture;
  return evaluate_components(v_new, components, mixture);
}

}  // namespace stagger::mixed
