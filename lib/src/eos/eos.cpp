// Pointwise EOS evaluation for set-up, tests and exact solutions.
#include <cmath>
#include <sstream>

#include "eos/eos_kernels.hpp"
#include "stagger/error.hpp"
#include "stagger/materials.hpp"

namespace stagger {

namespace {
eos::PressureSound evaluate_or_throw(const EquationOfState& model, double rho, double e) {
  eos::PressureSound out{};
  const bool ok = std::visit([&](const auto& m) { return eos::evaluate(m, rho, e, out); }, model);
  if (!ok) {
    std::ostringstream msg;
    msg << eos_kind(model) << " EOS: state rho = " << rho << ", e = " << e << " is outside the model's domain";
    throw Error(msg.str());
  }
  return out;
}
}  // namespace

double eos_pressure(const EquationOfState& model, double rho, double e) {
  return evaluate_or_throw(model, rho, e).p;
}

double eos_sound_speed_squared(const EquationOfState& model, double rho, double e) {
  return evaluate_or_throw(model, rho, e).c2;
}

double eos_energy_from_pressure(const EquationOfState& model, double rho, double p) {
  // Every EOS here is affine in e at fixed rho: p = p(rho, 0) + (dp/de) e.
  eos::PressureSound at0{}, at1{};
  const bool ok0 = std::visit([&](const auto& m) { return eos::evaluate(m, rho, 0.0, at0); }, model);
  std::visit([&](const auto& m) { return eos::evaluate(m, rho, 1.0, at1); }, model);
  const double slope = at1.p - at0.p;
  if (!(slope > 0.0) || !std::isfinite(at0.p)) {
    std::ostringstream msg;
    msg << eos_kind(model) << " EOS: cannot invert p = " << p << " at rho = " << rho
        << (ok0 ? "" : " (density outside the model's domain)");
    throw Error(msg.str());
  }
  return (p - at0.p) / slope;
}

std::string eos_kind(const EquationOfState& model) {
  switch (model.index()) {
    case 0:
      return "ideal_gas";
    case 1:
      return "mie_gruneisen";
    case 2:
      return "jwl";
    default:
      return "stiffened_gas";
  }
}

}  // namespace stagger
