#pragma once
// The closure of a mixed zone over one Lagrangian step (docs/algorithm.md, "Mixed zones"):
// how the zone's volume change and its compatible internal-energy change are shared among its
// material components. The zone's energy change dE = -dt sum_c f_c . v_bar comes from the
// compatible step (docs/algorithm.md §1) unchanged; the closure only splits it, and the last
// component takes the remainder, so the components' changes sum to the zone's: the total-energy
// audit stays where the pure-zone scheme has it, at round-off.
#include <span>
#include <vector>

#include "stagger/materials.hpp"

namespace stagger::mixed {

enum class Closure {
  pressure_relaxation,  // volume shares that bring the components to a common pressure (default)
  uniform_strain,       // every component strains like the zone: fractions frozen
};

// One material component of a mixed zone.
struct Component {
  const EquationOfState* eos = nullptr;
  double mass = 0;                // constant in the Lagrangian step
  double fraction = 0;            // volume fraction, sum 1 over the zone
  double e = 0;                   // specific internal energy
  double rho = 0, p = 0, c2 = 0;  // from the EOS at (rho, e)
};

// The zone's thermodynamic state from its components.
struct ZoneMixture {
  double p = 0;   // sum f_k p_k
  double c2 = 0;  // sum f_k rho_k c_k^2 / rho: the volume-weighted bulk modulus over the zone density
};

// Advances the components from the zone volume v_old to v_new with the zone's internal-energy
// change d_energy (compatible work, q included). Returns false when a component leaves its
// EOS domain or its volume would not stay positive (the step is then retried or stopped like
// a failing pure zone).
bool advance_components(Closure closure, double v_old, double v_new, double d_energy, std::span<Component> components);

// Sets rho, p, c2 of every component for zone volume v and returns the zone's pressure and
// sound speed; false outside an EOS domain.
bool evaluate_components(double v, std::span<Component> components, ZoneMixture& mixture);

// The volume changes of the pressure-relaxation closure: dV_k from the linearised isentropes
// p_k - (rho_k c_k^2) dV_k / V_k = p_bar with sum dV_k = dV (an instantaneous equilibration,
// the limit of Tipton's relaxation for a relaxation time below the step), limited so that no
// component loses more than half its volume in one step.
void relaxed_volume_changes(double v_old, double dv, std::span<const Component> components, std::vector<double>& dv_k);

}  // namespace stagger::mixed
