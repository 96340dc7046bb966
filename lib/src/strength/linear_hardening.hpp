#pragma once
// The linear-hardening strength model (stagger::LinearHardening, scene `model =
// "linear_hardening"`): constant shear modulus mu and von Mises yield stress Y = Y0 + H eps_p
// (docs/algorithm.md §7, docs/solids.md). Everything about the model is here and in
// linear_hardening.cpp: its yield stress and shear modulus as functions of the state, the
// radial return the step and the ALE's post-remap return use, its option table, digest rows and
// validation. The pointwise functions are inlined into the zone loops.
#include <cmath>
#include <string>

#include "stagger/materials.hpp"
#include "strength/deviator.hpp"
#include "strength/strength_state.hpp"

namespace stagger {

template <class Options>
struct OptionTable;

// The yield stress hardened to eps_p: Y0 + H eps_p. The one expression of it (the radial
// return below and yield_stress() both use it, so the step and the ALE agree bit for bit).
[[gnu::always_inline]] inline double hardened_yield_stress(double yield0, double hardening, double eps_p) {
  return yield0 + hardening * eps_p;
}

// von Mises radial return with S_zz = -(S_xx + S_yy) in the norm and linear isotropic hardening
// (docs/algorithm.md §7): with the yield stress Y = Y0 + H eps_p at the start of the step and the
// trial norm sigma_eq = sqrt(3/2 S:S) > Y, the plastic strain increment that puts the returned
// stress on the hardened surface, sigma_eq - 3 mu d = Y + H d, is d = (sigma_eq - Y) / (3 mu + H);
// s is scaled onto Y + H d. Returns d (0 inside the surface). H = 0 is bitwise the perfectly
// plastic return (Y + 0 eps_p = Y, 3 mu + 0 = 3 mu). The zone loops call it with the constants
// of their ZoneModel (hydro/kernels/zone_model.hpp).
[[gnu::always_inline]] inline double radial_return(double yield0, double hardening, double eps_p, double mu,
                                                   Deviator& s) {
  const double yield = hardened_yield_stress(yield0, hardening, eps_p);
  const double szz = -(s.xx + s.yy);
  const double j2 = s.xx * s.xx + s.yy * s.yy + szz * szz + 2 * s.xy * s.xy;
  const double seq = std::sqrt(1.5 * j2);
  if (seq <= yield) return 0.0;
  const double stiffness = 3 * mu + hardening;
  const double d = stiffness > 0 ? (seq - yield) / stiffness : 0.0;
  const double f = (yield + hardening * d) / seq;
  s.xx *= f, s.yy *= f, s.xy *= f;
  return d;
}

// ---- the model's interface (strength_models.hpp dispatches on the variant to these) ----

inline const char* strength_model_name(const LinearHardening&) {
  return "linear_hardening";
}

// Y(state) = Y0 + H eps_p.
inline double yield_stress(const LinearHardening& model, const StrengthState& state) {
  return hardened_yield_stress(model.yield_stress, model.hardening_modulus, state.plastic_strain);
}

// mu(state) = mu: constant.
inline double shear_modulus(const LinearHardening& model, const StrengthState&) {
  return model.shear_modulus;
}

// The constants the zone loops read through ZoneModel (mu, Y0, H of radial_return above).
inline LinearHardening zone_loop_constants(const LinearHardening& model) {
  return model;
}

// Puts s back onto the yield surface of `state` without plastic flow (no strain is added and the
// surface does not harden): the ALE's return after a remap, where nothing deformed.
inline void return_to_yield_surface(const LinearHardening& model, const StrengthState& state, Deviator& s) {
  radial_return(yield_stress(model, state), 0.0, 0.0, shear_modulus(model, state), s);
}

// The rows of [material.strength] (stagger::strength_option_table()).
const OptionTable<LinearHardening>& strength_option_table_of(const LinearHardening&);

// Throws stagger::Error naming `where` + the key of the first inadmissible constant.
void validate_strength_model(const LinearHardening& model, const std::string& where);

// shear_modulus, yield_stress and, when not 0, hardening_modulus.
StrengthDigestRows strength_digest_rows(const LinearHardening& model);

}  // namespace stagger
