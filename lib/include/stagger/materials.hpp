#pragma once
/// @file materials.hpp
/// Material models: equations of state (pointwise p(rho, e) and c^2(rho, e)), strength
/// (Wilkins hypo-elastic, von Mises) and programmed burn. docs/algorithm.md §3, §7, §8.
#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace stagger {

/// p = (gamma - 1) rho e.
struct IdealGas {
  double gamma = 1.4;  ///< ratio of specific heats, > 1
};

/// Mie-Grueneisen (paper eq. 6), eta = 1 - rho0/rho.
struct MieGruneisen {
  double rho0 = 0;    ///< reference density
  double a0 = 0;      ///< bulk sound speed (Hugoniot intercept c0)
  double gamma0 = 0;  ///< Grueneisen coefficient Gamma0
  double s = 0;       ///< Hugoniot slope (U_s = a0 + s u_p)
};

/// JWL; V = rho0/rho; p_JWL = A(1-w/(R1 V))e^{-R1 V} + B(1-w/(R2 V))e^{-R2 V} + w rho e.
struct Jwl {
  double A = 0, B = 0;    ///< pressure coefficients
  double R1 = 0, R2 = 0;  ///< decay constants
  double omega = 0;       ///< Grueneisen coefficient of the products
  double rho0 = 0;        ///< unreacted density
};

/// Stiffened gas (Harlow and Amsden 1971; Menikoff and Plohr, Rev. Mod. Phys. 61, 1989):
/// p = (gamma - 1) rho e - gamma p_inf, for water and other liquids; p_inf = 0 is the ideal gas.
struct StiffenedGas {
  double gamma = 4.4;  ///< > 1
  double p_inf = 0;    ///< stiffening pressure, >= 0
};

/// One of the equations of state above (std::visit or std::get_if to inspect).
using EquationOfState = std::variant<IdealGas, MieGruneisen, Jwl, StiffenedGas>;

/// Elastic-plastic strength, the linear-hardening model (scene `model = "linear_hardening"`, the
/// default): shear modulus mu and von Mises yield stress Y = Y0 + H eps_p with linear isotropic
/// hardening (H = 0: elastic-perfectly-plastic). docs/solids.md, "Strength models".
struct LinearHardening {
  double shear_modulus = 0;      ///< mu, >= 0
  double yield_stress = 0;       ///< Y0 (sqrt(3/2 S:S) <= Y), > 0 (strength_option_table())
  double hardening_modulus = 0;  ///< H >= 0: dY / d(equivalent plastic strain)
};

/// The linear-hardening model under its former name (set-ups written before the strength
/// models were a variant: `material.strength = Strength{mu, Y0, H}`).
using Strength = LinearHardening;

/// One of the strength models above (std::visit or std::get_if to inspect); each model lives in
/// lib/src/strength/ (docs/solids.md, "Adding a strength model").
using StrengthModel = std::variant<LinearHardening>;

/// Programmed burn (LS-DYNA style): lighting time = distance to the nearest detonator
/// (points, or a plane through `plane_point` with normal `plane_normal`) / detonation_speed.
struct Burn {
  double detonation_speed = 0;                 ///< D_CJ
  std::vector<std::array<double, 2>> points;   ///< detonation points
  std::optional<std::array<double, 4>> plane;  ///< (x0, y0, nx, ny): a detonation line
  double time_offset = 0;                      ///< lighting time added to every zone
  bool beta_burn = false;                      ///< also burn on compression
  double cj_relative_volume = 0;               ///< V_CJ/V0 for the beta burn
};

/// A named material: one EOS, optional strength and burn.
struct Material {
  std::string name;                       ///< referred to by RegionSetup::material
  EquationOfState eos = IdealGas{};       ///< the pointwise p(rho, e)
  std::optional<StrengthModel> strength;  ///< none: a fluid (no deviatoric stress)
  std::optional<Burn> burn;               ///< programmed burn (JWL products only)
  double min_energy = -1e300;             ///< floor reported as an error when crossed (EOS domain)
};

/// Pointwise EOS evaluation (used by set-up, tests and the exact solutions).
double eos_pressure(const EquationOfState& eos, double rho, double e);
/// Adiabatic sound speed squared c^2 = dp/drho|_e + p/rho^2 dp/de|_rho.
double eos_sound_speed_squared(const EquationOfState& eos, double rho, double e);
/// Specific internal energy giving pressure p at density rho (inverse of eos_pressure in e).
double eos_energy_from_pressure(const EquationOfState& eos, double rho, double p);
/// Name of the EOS kind ("ideal_gas", "mie_gruneisen", "jwl", "stiffened_gas").
std::string eos_kind(const EquationOfState& eos);

}  // namespace stagger
