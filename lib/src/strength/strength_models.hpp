#pragma once
// The strength models as one variant (stagger::StrengthModel, stagger/materials.hpp) and its
// dispatch: each helper visits the variant once, per material or per zone range, and runs the
// model's own function from its file in this folder - never a visit per zone. A new model adds
// its file, its alternative to StrengthModel and its include below (docs/solids.md, "Adding a
// strength model"). The helpers take exactly a StrengthModel (the Variant constraint): a
// model's value does not convert to the variant and come back here.
#include <concepts>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "stagger/materials.hpp"
#include "stagger/mesh.hpp"
#include "stagger/option_table.hpp"
#include "strength/linear_hardening.hpp"

namespace stagger {

template <class M>
concept Variant = std::same_as<M, StrengthModel>;

// The model a [material.strength] without `model` gets (existing scenes read unchanged).
inline constexpr const char* kDefaultStrengthModel = "linear_hardening";

// The scene names of the models, in variant order.
inline const std::vector<const char*>& strength_model_names() {
  static const std::vector<const char*> names = []<std::size_t... I>(std::index_sequence<I...>) {
    return std::vector<const char*>{strength_model_name(std::variant_alternative_t<I, StrengthModel>{})...};
  }
  (std::make_index_sequence<std::variant_size_v<StrengthModel>>{});
  return names;
}

// The model named `name` (one of strength_model_names()) with value-initialised constants.
inline StrengthModel default_strength_model(const std::string& name) {
  StrengthModel model;
  const auto assign_if_named = [&]<std::size_t I>() {
    if (name == strength_model_names()[I]) model = std::variant_alternative_t<I, StrengthModel>{};
  };
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (assign_if_named.template operator()<I>(), ...);
  }
  (std::make_index_sequence<std::variant_size_v<StrengthModel>>{});
  return model;
}

// A model's option table as docs/scenes.md and stagger-options show it.
struct StrengthTableText {
  std::string section, struct_name, markdown;
};

// The option tables of the models, in variant order.
inline std::vector<StrengthTableText> strength_option_table_texts() {
  return []<std::size_t... I>(std::index_sequence<I...>) {
    const auto text = [](const auto& table) {
      return StrengthTableText{table.section, table.struct_name, table.markdown()};
    };
    return std::vector<StrengthTableText>{
        text(strength_option_table_of(std::variant_alternative_t<I, StrengthModel>{}))...};
  }
  (std::make_index_sequence<std::variant_size_v<StrengthModel>>{});
}

template <Variant M>
const char* strength_model_name(const M& model) {
  return std::visit([](const auto& m) { return strength_model_name(m); }, model);
}

template <Variant M>
bool is_default_strength_model(const M& model) {
  return std::string(strength_model_name(model)) == kDefaultStrengthModel;
}

template <Variant M>
double yield_stress(const M& model, const StrengthState& state) {
  return std::visit([&](const auto& m) { return yield_stress(m, state); }, model);
}

template <Variant M>
double shear_modulus(const M& model, const StrengthState& state) {
  return std::visit([&](const auto& m) { return shear_modulus(m, state); }, model);
}

// ZoneModel's strength constants (hydro/step.cpp fills them once per zone range).
template <Variant M>
LinearHardening zone_loop_constants(const M& model) {
  return std::visit([](const auto& m) { return zone_loop_constants(m); }, model);
}

template <Variant M>
void validate_strength_model(const M& model, const std::string& where) {
  std::visit([&](const auto& m) { validate_strength_model(m, where); }, model);
}

// The digest rows; a model other than the default also names itself (hydro/physics_digest.cpp).
template <Variant M>
StrengthDigestRows strength_digest_rows(const M& model) {
  return std::visit([](const auto& m) { return strength_digest_rows(m); }, model);
}

// "key = value, ..." of the model's options (describe()), after "model = NAME, " unless default.
template <Variant M>
std::string strength_echo(const M& model) {
  const std::string prefix =
      is_default_strength_model(model) ? "" : std::string("model = \"") + strength_model_name(model) + "\", ";
  return prefix + std::visit([](const auto& m) { return strength_option_table_of(m).echo(m); }, model);
}

// The ALE's return after a remap over the zones [begin, end) of one material: S back onto the
// yield surface of each zone's state, without plastic flow (docs/algorithm.md §7).
template <Variant M>
void return_to_yield_surface(const M& model, Index begin, Index end, const double* plastic, double* sxx, double* syy,
                             double* sxy) {
  std::visit(
      [&](const auto& m) {
        for (Index z = begin; z < end; ++z) {
          Deviator d{sxx[z], syy[z], sxy[z]};
          return_to_yield_surface(m, StrengthState{plastic[z]}, d);
          sxx[z] = d.xx, syy[z] = d.yy, sxy[z] = d.xy;
        }
      },
      model);
}

}  // namespace stagger
