// The linear-hardening strength model's option table, validation and digest rows
// (linear_hardening.hpp).
#include "strength/linear_hardening.hpp"

#include "hydro/option_rows.hpp"

namespace stagger {

template struct Option<LinearHardening>;
template struct OptionTable<LinearHardening>;

const OptionTable<LinearHardening>& strength_option_table() {
  using namespace option_rows;
  using S = LinearHardening;
  static const OptionTable<LinearHardening> table{
      "material.strength",
      "LinearHardening",
      {
          required_number<&S::shear_modulus>("shear_modulus", at_least(0), "pressure", "shear modulus mu (§7)"),
          required_number<&S::yield_stress>("yield_stress", above(0), "pressure",
                                            "von Mises yield stress Y (§7); a very large value gives an elastic "
                                            "material"),
          number<&S::hardening_modulus>("hardening_modulus", at_least(0), "pressure",
                                        "linear isotropic hardening H: the yield stress is Y + H eps_p with eps_p "
                                        "the equivalent plastic strain (§7); 0 is perfectly plastic"),
      }};
  return table;
}

const OptionTable<LinearHardening>& strength_option_table_of(const LinearHardening&) {
  return strength_option_table();
}

void validate_strength_model(const LinearHardening& model, const std::string& where) {
  strength_option_table().validate(model, where);
}

StrengthDigestRows strength_digest_rows(const LinearHardening& model) {
  StrengthDigestRows rows{{"shear_modulus", model.shear_modulus}, {"yield_stress", model.yield_stress}};
  // Only when set, so digests of scenes without hardening stay as they were.
  if (model.hardening_modulus != 0) rows.emplace_back("hardening_modulus", model.hardening_modulus);
  return rows;
}

}  // namespace stagger
