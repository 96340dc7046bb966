// [sources] and [verification]: manufactured sources and exact references from verify.hpp.
// Material constants come from the scene's [[material]] (so that --set changes both the
// run and its reference); the remaining parameters are keys of the table, with the
// defaults of verify.hpp.
#include <cmath>

#include "scene_internal.hpp"
#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace stagger::scene_detail {

namespace {

GasState read_gas_state(Section& parent, const char* key) {
  auto table = parent.subtable(key);
  if (!table)
    parent.fail(key, "missing", std::string("write ") + key + " = { density = 1.0, velocity = 0.0, pressure = 1.0 }");
  GasState state;
  state.density = table->number("density");
  state.velocity = table->number("velocity", 0.0);
  state.pressure = table->number("pressure");
  if (!(state.density > 0)) table->fail("density", "must be > 0");
  if (!(state.pressure >= 0)) table->fail("pressure", "must be >= 0");
  table->finish();
  return state;
}

// The material a reference is about: `material = "name"`, or the first [[material]].
const Material& reference_material(Section& section, const Problem& problem) {
  if (section.has("material")) {
    const std::string name = section.string("material");
    for (const auto& material : problem.materials)
      if (material.name == name) return material;
    std::string names;
    for (const auto& material : problem.materials) names += (names.empty() ? "" : ", ") + material.name;
    section.fail("material", "unknown material '" + name + "'", "materials: " + names);
  }
  return problem.materials.front();
}

template <class Eos>
const Eos& material_eos(Section& section, const Material& material, const char* eos_name) {
  const auto* eos = std::get_if<Eos>(&material.eos);
  if (eos == nullptr)
    section.fail("reference",
                 "this reference needs material '" + material.name + "' to use eos = \"" + eos_name + "\"");
  return *eos;
}

// The strength of a reference whose exact solution is perfectly plastic: the linear-hardening
// model with H = 0.
const LinearHardening& perfectly_plastic(Section& section, const Material& material, const char* what) {
  if (!material.strength)
    section.fail("reference", std::string("the ") + what + " needs material '" + material.name + "' with strength");
  const auto* model = std::get_if<LinearHardening>(&*material.strength);
  if (model == nullptr || model->hardening_modulus != 0)
    section.fail("reference", std::string("the ") + what + "'s exact solution is perfectly plastic: material '" +
                                  material.name + "' needs model = \"linear_hardening\" and hardening_modulus = 0");
  return *model;
}

double positive(Section& section, const char* key, double fallback) {
  const double value = section.number(key, fallback);
  if (!(value > 0)) section.fail(key, "must be > 0");
  return value;
}

// Ideal-gas gamma: the `gamma` key, or the reference material's.
double gas_gamma(Section& section, const Problem& problem) {
  const Material& material = reference_material(section, problem);
  const double fallback = std::get_if<IdealGas>(&material.eos) ? std::get<IdealGas>(material.eos).gamma : 0.0;
  if (!section.has("gamma") && fallback == 0.0)
    section.fail("gamma", "missing (the material is not an ideal gas)", "write gamma = 1.4");
  const double gamma = section.number("gamma", fallback);
  if (!(gamma > 1)) section.fail("gamma", "must be > 1");
  return gamma;
}

AccuracyParameters read_accuracy_parameters(Section& section, const Problem& problem) {
  AccuracyParameters parameters;
  parameters.eos = material_eos<MieGruneisen>(section, reference_material(section, problem), "mie_gruneisen");
  parameters.velocity = section.number("velocity", parameters.velocity);
  parameters.s1 = section.number("s1", parameters.s1);
  parameters.energy = section.number("energy", parameters.energy);
  parameters.amplitude = section.number("amplitude", parameters.amplitude);
  return parameters;
}

}  // namespace

SourceContext read_sources_section(Section& section, Problem& problem) {
  SourceContext context;
  context.kind = section.choice("kind", {"taylor_green", "accuracy"});
  if (problem.options.geometry == CoordinateSystem::rz)
    section.fail("kind",
                 "the \"" + context.kind +
                     "\" source terms are derived for a planar flow and numerics.geometry = \"rz\" (x is the "
                     "radius there)",
                 "run the scene with geometry = \"planar\"");
  if (context.kind == "taylor_green") {
    // The energy source of verify.hpp is derived for gamma = 5/3.
    for (const auto& material : problem.materials) {
      const auto* gas = std::get_if<IdealGas>(&material.eos);
      if (gas == nullptr || std::abs(gas->gamma - 5.0 / 3.0) > 1e-12)
        section.fail("kind", "the Taylor-Green source term assumes an ideal gas with gamma = 5/3 (material '" +
                                 material.name + "' differs)");
    }
    problem.sources = taylor_green_sources();
  } else {
    context.accuracy = read_accuracy_parameters(section, problem);
    problem.sources = accuracy_sources(*context.accuracy);
  }
  section.finish();
  return context;
}

void read_verification_section(Section& section, const Problem& problem, const SourceContext& sources,
                               RunControl& control, VerificationSetup& setup) {
  const std::string reference =
      section.choice("reference", {"shock_tube", "noh", "sedov", "saltzman", "taylor_green", "piston", "be_shell",
                                   "detonation", "accuracy", "taylor_bar"});
  setup.name = reference;
  // The planar references measure a planar flow (a function of x, a periodic square); in rz, x
  // is the radius and the flow is another one (docs/verification.md).
  for (const char* planar : {"shock_tube", "saltzman", "taylor_green", "piston", "detonation", "accuracy"})
    if (reference == planar && problem.options.geometry == CoordinateSystem::rz)
      section.fail("reference",
                   "\"" + reference +
                       "\" is a planar solution and numerics.geometry = \"rz\" (x is the radius there): its errors "
                       "would be meaningless",
                   "run the scene with geometry = \"planar\", or use an rz reference (noh, sedov, be_shell, "
                   "taylor_bar)");
  if (reference == "shock_tube") {
    ShockTubeReference parameters;
    parameters.left = read_gas_state(section, "left");
    parameters.right = read_gas_state(section, "right");
    parameters.gamma = gas_gamma(section, problem);
    parameters.x0 = section.number("x0");
    control.reference = shock_tube_reference(parameters.left, parameters.right, parameters.gamma, parameters.x0);
    setup.parameters = parameters;
  } else if (reference == "noh") {
    NohReference parameters;
    parameters.gamma = gas_gamma(section, problem);
    parameters.density = positive(section, "density", parameters.density);
    parameters.speed = positive(section, "speed", parameters.speed);
    // A planar scene is the cylindrical implosion, an rz scene the spherical one.
    parameters.nu = problem.options.geometry == CoordinateSystem::rz ? 3 : 2;
    control.reference = noh_reference(parameters.gamma, parameters.density, parameters.speed, parameters.nu);
    setup.parameters = parameters;
  } else if (reference == "sedov") {
    SedovReference parameters;
    parameters.gamma = gas_gamma(section, problem);
    double deposited = 0;
    for (const auto& deposit : problem.deposits) deposited += deposit.energy;
    if (!section.has("energy") && deposited == 0)
      section.fail("energy", "missing (the scene has no [[deposit]])", "write energy = 0.244816");
    parameters.density = positive(section, "density", parameters.density);
    parameters.energy_quarter = positive(section, "energy", deposited);
    parameters.nu = problem.options.geometry == CoordinateSystem::rz ? 3 : 2;
    control.reference = sedov_reference(parameters.gamma, parameters.density, parameters.energy_quarter, parameters.nu);
    setup.parameters = parameters;
  } else if (reference == "saltzman") {
    SaltzmanReference parameters;
    parameters.gamma = gas_gamma(section, problem);
    parameters.piston_speed = positive(section, "piston_speed", parameters.piston_speed);
    parameters.density = positive(section, "density", parameters.density);
    control.reference = saltzman_reference(parameters.piston_speed, parameters.gamma, parameters.density);
    setup.parameters = parameters;
  } else if (reference == "taylor_green") {
    TaylorGreenReference parameters;
    parameters.p0 = positive(section, "p0", parameters.p0);
    control.reference = taylor_green_reference(parameters.p0);
    setup.parameters = parameters;
  } else if (reference == "piston") {
    const Material& material = reference_material(section, problem);
    PistonParameters parameters;
    parameters.eos = material_eos<MieGruneisen>(section, material, "mie_gruneisen");
    const LinearHardening& strength = perfectly_plastic(section, material, "piston");
    parameters.shear_modulus = strength.shear_modulus;
    parameters.yield_stress = strength.yield_stress;
    parameters.initial_pressure = section.number("initial_pressure", parameters.initial_pressure);
    parameters.piston_velocity = positive(section, "piston_velocity", parameters.piston_velocity);
    try {
      control.reference = piston_reference(parameters);
    } catch (const Error& failure) {
      section.fail("reference", failure.what());
    }
    setup.parameters = parameters;
  } else if (reference == "be_shell") {
    const Material& material = reference_material(section, problem);
    ShellParameters parameters;
    parameters.density = material_eos<MieGruneisen>(section, material, "mie_gruneisen").rho0;
    parameters.yield_stress = perfectly_plastic(section, material, "shell").yield_stress;
    parameters.inner_radius = positive(section, "inner_radius", parameters.inner_radius);
    parameters.outer_radius = positive(section, "outer_radius", parameters.outer_radius);
    if (!(parameters.outer_radius > parameters.inner_radius)) section.fail("outer_radius", "must exceed inner_radius");
    parameters.velocity = positive(section, "velocity", parameters.velocity);
    // A planar scene is Howell and Ball's cylindrical shell, an rz scene Verney's spherical one.
    parameters.spherical = problem.options.geometry == CoordinateSystem::rz;
    try {
      control.reference = be_shell_reference(parameters);
    } catch (const Error& failure) {
      section.fail("reference", failure.what());
    }
    setup.parameters = parameters;
  } else if (reference == "detonation") {
    const Material& material = reference_material(section, problem);
    DetonationParameters parameters;
    parameters.eos = material_eos<Jwl>(section, material, "jwl");
    if (material.burn) parameters.nominal_speed = material.burn->detonation_speed;
    parameters.energy_per_volume = positive(section, "energy_per_volume", parameters.energy_per_volume);
    parameters.x0 = section.number("x0", parameters.x0);
    try {
      control.reference = detonation_reference(parameters);
    } catch (const Error& failure) {
      section.fail("reference", failure.what());
    }
    setup.parameters = parameters;
  } else if (reference == "taylor_bar") {
    control.reference = taylor_bar_reference();  // diagnostics only: no parameters
  } else {
    if (!sources.accuracy)
      section.fail("reference",
                   "the accuracy reference needs [sources] kind = \"accuracy\" (its parameters are read there)");
    control.reference = accuracy_reference(*sources.accuracy);
    setup.parameters = *sources.accuracy;
  }
  section.finish();
}

}  // namespace stagger::scene_detail
