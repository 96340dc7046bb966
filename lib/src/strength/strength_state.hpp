#pragma once
// What a strength model's yield stress and shear modulus are functions of (docs/solids.md,
// "Strength models"). The equivalent plastic strain today; a model that depends on the strain
// rate or the temperature (Johnson-Cook, Steinberg-Guinan) adds them here, and the callers that
// build a state fill them.
#include <string>
#include <utility>
#include <vector>

namespace stagger {

struct StrengthState {
  double plastic_strain = 0;  // equivalent plastic strain eps_p
};

// A model's entries of the physics digest (hydro/physics_digest.cpp): the key after
// "<material>.strength." and the value, in the order the digest lists them.
using StrengthDigestRows = std::vector<std::pair<std::string, double>>;

}  // namespace stagger
