#pragma once
/// @file verify.hpp
/// Exact and analytic solutions of the verification problems, and error norms.
/// docs/verification.md §11 defines the norms: area-weighted means over the compared zones.
#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "stagger/output.hpp"
#include "stagger/problem.hpp"

namespace stagger {

class Simulation;

/// A primitive 1D gas state.
struct GasState {
  double density = 0, velocity = 0, pressure = 0;
};

/// Exact solution of the 1D Riemann problem for ideal gases (Toro, "Riemann Solvers and
/// Numerical Methods for Fluid Dynamics", 3rd ed., ch. 4), interface at x0 at t = 0.
class ExactRiemann {
 public:
  ExactRiemann(GasState left, GasState right, double gamma, double x0 = 0.5);
  /// State at (x, t), t > 0.
  GasState sample(double x, double t) const;
  double star_pressure() const { return p_star_; }
  double star_velocity() const { return u_star_; }
  /// Densities of the star region left and right of the contact.
  double star_density_left() const { return rho_star_left_; }
  double star_density_right() const { return rho_star_right_; }
  /// Positions at time t of every wave edge, ascending: left wave head and tail, contact,
  /// right wave tail and head (head == tail for a shock). Between two of them the solution
  /// is smooth (for exact piecewise integration).
  std::array<double, 5> wave_positions(double t) const;

 private:
  GasState left_, right_;
  double gamma_, x0_;
  double p_star_ = 0, u_star_ = 0;
  double c_left_ = 0, c_right_ = 0;
  double rho_star_left_ = 0, rho_star_right_ = 0;
};

/// One side of a two-material Riemann problem: a stiffened gas p = (gamma - 1) rho e - gamma p_inf
/// (p_inf = 0: an ideal gas).
struct StiffenedSide {
  GasState state;
  double gamma = 1.4, p_inf = 0;
};

/// Exact solution of the 1D Riemann problem between two stiffened gases, each with its own gamma
/// and p_inf: Toro's ch. 4 solver with every pressure shifted by its side's p_inf (the stiffened
/// gas is an ideal gas in p + p_inf; Ivings, Causon and Toro, Int. J. Numer. Meth. Fluids 28,
/// 1998; Plohr, AIAA J. 26, 1988). Interface at x0 at t = 0; sample() as ExactRiemann's.
class StiffenedRiemann {
 public:
  StiffenedRiemann(StiffenedSide left, StiffenedSide right, double x0 = 0.5);
  GasState sample(double x, double t) const;
  double star_pressure() const { return p_star_; }
  double star_velocity() const { return u_star_; }
  double star_density_left() const { return rho_star_[0]; }
  double star_density_right() const { return rho_star_[1]; }

 private:
  StiffenedSide side_[2];
  double x0_;
  double p_star_ = 0, u_star_ = 0;
  double c_[2] = {0, 0}, rho_star_[2] = {0, 0};
};

/// A reference solution: fills error norms and diagnostics for the current state.
using Reference = std::function<void(const Simulation&, NamedValues& errors, NamedValues& diagnostics)>;

/// Area-weighted L1 / L2 / Linf of a zone field against an exact function of (x, y) at zone
/// centres, appended as L1_<name>, L2_<name>, Linf_<name>.
void zone_field_errors(const Simulation& simulation, std::span<const double> field,
                       const std::function<double(double, double)>& exact, const std::string& name,
                       NamedValues& errors);

/// The Sod-type shock tube along x (any ideal-gas Riemann problem): L1/L2/Linf of density,
/// velocity (x component at the points, area-weighted by the point's median area) and pressure.
/// Diagnostic `max_y_variation`: zones grouped into columns by equal centre x (to 1e-9 of the
/// domain length), max over columns and their zones of |rho - column mean| / column mean.
Reference shock_tube_reference(GasState left, GasState right, double gamma, double x0);

// ---- gas dynamics (verifygas) ----

// Geometry and norms on an explicit geometry (topology of `mesh`, positions x, y), so that
// they can be used and tested without a Simulation.

/// Zone centres (vertex average, docs/algorithm.md §2) for positions x, y.
std::array<std::vector<double>, 2> zone_centres(const Mesh& mesh, std::span<const double> x, std::span<const double> y);
/// Zone areas (shoelace, docs/algorithm.md §2) for positions x, y.
std::vector<double> zone_areas(const Mesh& mesh, std::span<const double> x, std::span<const double> y);
/// Median-dual area of every point: the sum of its corner areas, a corner being the
/// quadrilateral (point, mid-edge to the next vertex, zone centre, mid-edge to the previous
/// vertex) of docs/algorithm.md §2.
std::vector<double> point_dual_areas(const Mesh& mesh, std::span<const double> x, std::span<const double> y);

/// Appends L1_<name>, L2_<name>, Linf_<name> of the differences (their absolute values are
/// used) weighted by `weights` (docs/verification.md §11). Entries with
/// weight <= 0 are skipped by L1/L2 but not by Linf. Throws stagger::Error on size mismatch
/// or when the total weight is not positive.
void append_norms(std::span<const double> weights, std::span<const double> differences, const std::string& name,
                  NamedValues& errors);

/// Point counterpart of zone_field_errors: a point field against exact(x_p, y_p), weighted
/// by the point's median-dual area (point_dual_areas on the current positions).
void point_field_errors(const Simulation& simulation, std::span<const double> field,
                        const std::function<double(double, double)>& exact, const std::string& name,
                        NamedValues& errors);
/// Point velocity against an exact vector field: norms of the magnitude |v_p - v_exact(x_p)|,
/// appended as L1_<name>, L2_<name>, Linf_<name>.
void point_velocity_errors(const Simulation& simulation,
                           const std::function<std::array<double, 2>(double, double)>& exact, const std::string& name,
                           NamedValues& errors);

/// Where a zone field falls through `threshold` going outward in `coordinate` (r, x, ...):
/// every pair of zones sharing an edge whose inner zone (smaller coordinate at its centre)
/// has field >= threshold and whose outer zone has field < threshold gives one crossing, by
/// linear interpolation of the field between the two centres. `position` is the mean over
/// all crossings (so over rays / rows for structured meshes), `crossings` their number
/// (0: no front found, position = 0).
struct FrontCrossing {
  double position = 0;
  int crossings = 0;
};
/// Crossings whose interpolated position is below `min_position` are ignored (e.g. the
/// wall-heating dip at the Noh centre, which crosses the threshold too).
FrontCrossing front_crossing(const Mesh& mesh, std::span<const double> x, std::span<const double> y,
                             std::span<const double> field, double threshold,
                             const std::function<double(double, double)>& coordinate, double min_position = -1e300);

/// Groups indices whose values agree within `tolerance` (values sorted, consecutive values
/// closer than the tolerance chained into one group). Used for "rings" and "columns".
std::vector<std::vector<Index>> group_by_value(std::span<const double> values, double tolerance);

/// Cylindrical (nu = 2) or spherical (nu = 3) Noh implosion (Noh, J. Comput. Phys. 72, 1987):
/// ideal gas, cold (p = 0) gas of density rho0 moving inward at speed u0. The shock moves out
/// at D = u0 (gamma - 1) / 2; behind it the gas is at rest with density
/// rho0 ((gamma + 1)/(gamma - 1))^nu and specific internal energy u0^2 / 2; ahead of it the
/// density is rho0 (1 + u0 t / r)^(nu - 1).
class NohSolution {
 public:
  NohSolution(double gamma = 5.0 / 3.0, double rho0 = 1.0, double u0 = 1.0, int nu = 2);
  double shock_radius(double t) const;
  double post_shock_density() const;
  /// Density, radial velocity and pressure at radius r, time t > 0.
  GasState state(double r, double t) const;

 private:
  double gamma_, rho0_, u0_;
  int nu_;
};

/// Noh errors: L1/L2/Linf_density at the zone centres. Diagnostics: `shock_radius` (mean
/// front_crossing in r of the density through the mean of the exact plateau and pre-shock
/// values at the shock, 10 for gamma = 5/3), `shock_radius_exact`, `plateau_density`
/// (area-weighted mean density of the zones with 0.25 R_s < r < 0.75 R_s, R_s exact: the band
/// 0.05 < r < 0.15 at t = 0.6), `asymmetry` (max over groups of zones with equal centre radius,
/// to 1e-9 relative, of (max - min) / mean density, zones with r > 0.25 R_s only; on a polar
/// mesh the groups are rings, on a Cartesian mesh pairs of zones mirrored about the diagonal,
/// so there it measures the mirror symmetry) and `asymmetry_groups` (the number of groups).
/// nu = 2 cylindrical (planar scenes), nu = 3 spherical (geometry = "rz"; the half-way density
/// of the shock uses the pre-shock rho0 ((gamma+1)/(gamma-1))^(nu-1)).
Reference noh_reference(double gamma = 5.0 / 3.0, double rho0 = 1.0, double u0 = 1.0, int nu = 2);

/// The Sedov-Taylor-von Neumann point blast in a uniform ideal gas (Sedov, "Similarity and
/// Dimensional Methods in Mechanics", 1959; closed forms of Kamm & Timmes, LA-UR-07-2849,
/// 2007, eqs. 29-47, "standard" case only). nu = 1 planar (energy per unit area, both sides),
/// 2 cylindrical (energy per unit length of the full plane), 3 spherical. The shock radius
/// is R(t) = (E / (alpha rho0))^(1/(nu+2)) t^(2/(nu+2)); alpha comes from quadrature of the
/// energy integral (alpha = xi0^-(nu+2) in Sedov's notation): 0.98407 for gamma = 1.4, nu = 2.
class SedovSolution {
 public:
  SedovSolution(double gamma, int nu = 2, double rho0 = 1.0, double energy = 1.0);
  double alpha() const { return alpha_; }
  double shock_radius(double t) const;
  /// Density just behind the shock, rho0 (gamma + 1)/(gamma - 1).
  double post_shock_density() const;
  /// Density, radial velocity and pressure at radius r, time t > 0 (ambient outside).
  GasState state(double r, double t) const;
  /// The similarity functions at lambda = r / R in [0, 1]: u / u2, rho / rho2, p / p2.
  std::array<double, 3> similarity(double lambda) const;

 private:
  struct Functions {
    double lambda, f, g, h;
  };
  Functions functions_of_w(double w) const;  // parametrised by w = C V - 1 (Kamm eq. 35)
  double w_of_lambda(double lambda) const;
  double gamma_, rho0_, energy_;
  int nu_;
  double a0_, a1_, a2_, a3_, a4_, a5_;  // Kamm eqs. 42-47 (omega = 0)
  double A_, B_, C_, D_, E_;            // Kamm eqs. 33-37
  double w2_ = 0, alpha_ = 0;
};

/// Sedov errors (cylindrical, full-plane energy 4 energy_quarter; the scene deposits
/// energy_quarter in the quarter [0, L]^2): L1/L2/Linf_density at the zone centres.
/// Diagnostics: `shock_radius` (mean front_crossing in r of the density through the half-way
/// value between ambient rho0 and the peak zone density), `shock_radius_exact`,
/// `shock_radius_error` ((numerical - exact)/exact), `peak_density` (max zone density),
/// `peak_density_exact` (rho0 (gamma + 1)/(gamma - 1)).
/// nu = 3 (geometry = "rz"): spherical, energy_quarter the energy per radian of the half
/// space z >= 0 (the sphere's energy / (4 pi)).
Reference sedov_reference(double gamma = 1.4, double rho0 = 1.0, double energy_quarter = 0.244816, int nu = 2);

/// Saltzman piston (docs/verification.md §4): piston at x = u t from x = 0 into gas of density
/// rho0 at rest, strong shock at x_s = (gamma + 1)/2 u t, density rho0 (gamma+1)/(gamma-1)
/// behind (4 for gamma = 5/3). Errors: L1/L2/Linf_density at the zone centres. Diagnostics:
/// `shock_position` (mean front_crossing in x through the half-way density), `shock_position_exact`,
/// `plateau_density` (area-weighted mean density of the zones between piston and shock whose
/// centre lies more than two of their own widths, A_z / y-extent, from the piston and from
/// the exact shock), `inner_row_max_density_error` (max |rho - rho_exact| over those zones
/// that touch neither the bottom nor the top of the domain, the extreme y of all points).
Reference saltzman_reference(double piston_speed = 1.0, double gamma = 5.0 / 3.0, double rho0 = 1.0);

/// Taylor-Green vortex (Dobrev, Kolev & Rieben, SIAM J. Sci. Comput. 34(5), 2012, sec. 6.1;
/// Laghos problem 0) on [0,1]^2: rho = 1, v = (sin(pi x) cos(pi y), -cos(pi x) sin(pi y)),
/// p = p0 + (cos(2 pi x) + cos(2 pi y)) / 4, steady. It satisfies mass and momentum exactly
/// (div v = 0, v.grad v = -grad p); the energy equation needs the source below.
std::array<double, 2> taylor_green_velocity(double x, double y);
double taylor_green_pressure(double x, double y, double p0 = 1.0);
/// s_e = v.grad(e) with e = p/((gamma-1) rho), gamma = 5/3:
/// (3 pi / 8) [cos(3 pi x) cos(pi y) - cos(pi x) cos(3 pi y)] (derived in gas_taylor_green.cpp).
double taylor_green_energy_source(double x, double y);
/// The sources of the Taylor-Green scene: that energy source, no momentum source.
Sources taylor_green_sources();
/// Taylor-Green errors: L1/L2/Linf_velocity (points, magnitude of the vector error),
/// L1/L2/Linf_pressure and _density (zones) against the steady exact fields.
Reference taylor_green_reference(double p0 = 1.0);

// ---- solids and explosives (verifysolid) ----
// Derivations and the numbers these produce: docs/derivations.md.

/// A 1D state of a solid in uniaxial strain along x: density, velocity, pressure,
/// deviatoric stress S_xx (S_yy = S_zz = -S_xx / 2) and specific internal energy.
struct SolidState {
  double density = 0, velocity = 0, pressure = 0, stress_xx = 0, energy = 0;
};

/// The copper elastic-plastic piston (docs/verification.md §7; the set-up of Maire et al.,
/// "A nominally second-order cell-centered Lagrangian scheme for simulating elastic-plastic
/// flows on two-dimensional unstructured grids", JCP 235, 2013, section 6; Wilkins, "Calculation
/// of elastic-plastic flow", Methods Comput. Phys. 3, 1964).
struct PistonParameters {
  MieGruneisen eos{8930.0, 3940.0, 2.0, 1.49};
  double shear_modulus = 45e9;    ///< mu
  double yield_stress = 90e6;     ///< Y (von Mises, sqrt(3/2 S:S) with S_zz kept)
  double initial_pressure = 1e5;  ///< p0 at rho0 (e0 = p0 / (Gamma0 rho0))
  double piston_velocity = 20.0;  ///< along +x, from x = 0 at t = 0
};

/// Exact two-wave solution of the piston problem for the continuum that the scheme
/// discretises (docs/algorithm.md §3, §7): hypo-elastic S_xx = (4 mu / 3) ln(rho0 / rho)
/// along the elastic path (the rate equation integrated in uniaxial strain), von Mises
/// yield at |S_xx| = 2Y/3, Mie-Grueneisen pressure. Both waves are shocks satisfying the
/// Rankine-Hugoniot conditions for mass, momentum and total energy with the normal stress
/// -sigma_xx = p - S_xx; the plastic shock keeps S_xx = -2Y/3. Throws stagger::Error when the
/// piston is too slow to yield the material (a single elastic wave) or the EOS domain is left.
class ElasticPlasticPiston {
 public:
  explicit ElasticPlasticPiston(const PistonParameters& parameters = {});
  const SolidState& initial_state() const { return initial_; }
  const SolidState& elastic_state() const { return elastic_; }
  const SolidState& plastic_state() const { return plastic_; }
  double elastic_wave_speed() const { return elastic_speed_; }  ///< lab frame
  double plastic_wave_speed() const { return plastic_speed_; }  ///< lab frame
  /// State at (x, t): plastic for x < plastic speed * t, elastic up to the precursor, initial
  /// ahead of it (x behind the piston face returns the plastic state).
  SolidState sample(double x, double t) const;
  const PistonParameters& parameters() const { return parameters_; }

 private:
  PistonParameters parameters_;
  SolidState initial_, elastic_, plastic_;
  double elastic_speed_ = 0, plastic_speed_ = 0;
};

/// Errors L1/L2/Linf of velocity (x, points, weighted by median-dual area), pressure, density
/// and deviatoric_stress_xx (zones); diagnostics elastic_front / plastic_front (largest x where
/// the point velocity crosses half the elastic jump, resp. the mean of the elastic and plastic
/// velocities: the middle of a smeared shock), their exact positions elastic_front_exact and
/// plastic_front_exact, and elastic_velocity_exact, elastic_pressure_exact,
/// plastic_pressure_exact, plastic_density_exact.
Reference piston_reference(const PistonParameters& parameters = {});

/// Howell & Ball's beryllium shell (JCP 175, 2002; docs/verification.md §8), or with
/// `spherical` its spherical analogue, Verney's problem (docs/derivations.md section 2.1).
struct ShellParameters {
  double inner_radius = 0.08, outer_radius = 0.1;
  double velocity = 417.1;  ///< V0: initial radial velocity -V0 Ri / r (spherical: -V0 Ri^2 / r^2)
  double density = 1845.0;
  double yield_stress = 330e6;
  bool spherical = false;  ///< a spherical shell (an rz scene) instead of a cylindrical one
};

/// Incompressible, rigid-perfectly-plastic collapse of a thick cylindrical shell (plane
/// strain, von Mises with sigma_eq = sqrt(3/2 S:S) = Y, i.e. shear yield k = Y / sqrt(3)).
/// The kinetic energy per unit length of a full circle, pi rho (Ri Ri')^2 ln(Ro/Ri), decreases
/// at the plastic dissipation rate (4 pi / sqrt(3)) Y |Ri Ri'| ln(Ro/Ri); integrating in
/// r = Ri^2 gives the velocity in closed form and the time by quadrature. With
/// `spherical` (Verney 1968): a thick spherical shell, kinetic energy of the full sphere
/// 2 pi rho (Ri^2 Ri')^2 (1/Ri - 1/Ro), dissipation 8 pi Y |Ri^2 Ri'| ln(Ro/Ri), integrated
/// in s = Ri^3 (docs/derivations.md section 2.1). Energies are per unit length of the full
/// circle, resp. of the full sphere.
class HowellBallShell {
 public:
  explicit HowellBallShell(const ShellParameters& parameters = {});
  double inner_radius(double t) const;    ///< stays at the stopping radius after stopping_time
  double outer_radius(double t) const;    ///< Ro^2 - Ri^2 (spherical: Ro^3 - Ri^3) is constant
  double inner_velocity(double t) const;  ///< dRi/dt (negative, 0 after stopping)
  /// Kinetic energy per unit length of the full circle (spherical: of the full sphere).
  double kinetic_energy(double t) const;
  /// Plastic dissipation rate per unit length of the full circle (spherical: of the full sphere).
  double dissipation_rate(double t) const;
  double stopping_time() const { return stopping_time_; }
  double inner_stopping_radius() const { return inner_stop_; }
  double outer_stopping_radius() const;
  const ShellParameters& parameters() const { return parameters_; }

 private:
  double inner_power(double t) const;                        // s = Ri^n (n = 2, spherical 3) at time t
  double velocity_at(double s) const;                        // |Ri^(n-1) Ri'| as a function of s
  double time_integrand(double sigma, double s_stop) const;  // dt/dsigma, s = s_stop + sigma^2
  double shape(double s) const;                              // K / (k rho Q^2): ln(Ro/Ri), spherical 1/Ri - 1/Ro
  double radius(double s) const;                             // s^(1/n)
  double power(double r) const;                              // r^n
  ShellParameters parameters_;
  double n_ = 2;     // the power: 2 cylindrical, 3 spherical
  double c_ = 0;     // Ro^n - Ri^n
  double beta_ = 0;  // Q^2 shape(s) = beta (F(s) - F(s_stop))
  double inner_stop_ = 0, stopping_time_ = 0;
  std::vector<double> sigma_, time_;  // s = Ri_stop^n + sigma^2; time_[k] = t(sigma_[k])
};

/// Diagnostics inner_radius / outer_radius (mean radius sqrt(x^2 + y^2) of the points of the mesh
/// tags "inner" / "outer"; in rz the spherical radius), inner_radius_exact / outer_radius_exact, asymmetry (max over
/// the two tags of (max r - min r) / mean r), kinetic_energy, internal_energy, kinetic_energy_exact (the analytic one
/// scaled to the simulated sector by its mass), and inner/outer_stopping_radius_exact, stopping_time_exact.
Reference be_shell_reference(const ShellParameters& parameters = {});

/// A Taylor bar moving in -y onto the rigid wall y = y0 (the lowest y of the initial mesh):
/// no exact solution, diagnostics only (docs/solids.md §8): final_length (top - y0),
/// length_ratio (to the initial length), impact_face_width (the x extent of the points on the
/// wall), max_width (the x extent of the bar), max_plastic_strain.
Reference taylor_bar_reference();

/// Composition B with the JWL fit of the paper's section 5.2, in cm-g-us (pressure in Mbar,
/// energy per volume in Mbar cc/cc = 100 kJ/cc).
struct DetonationParameters {
  Jwl eos{5.242, 0.07678, 4.2, 1.1, 0.34, 1.712};
  double energy_per_volume = 0.085;  ///< E0 = rho0 e0 (8.5 kJ/cc)
  double x0 = 0;                     ///< detonation plane (and rigid wall) position
  double nominal_speed = 0.798;      ///< the paper's D_CJ (the programmed burn's lighting speed)
};

/// A point of the products' flow: density, velocity, pressure, sound speed.
struct DetonationState {
  double density = 0, velocity = 0, pressure = 0, sound_speed = 0;
};

/// The planar Chapman-Jouguet detonation from a rigid wall with its Taylor wave (Fickett &
/// Davis, "Detonation", 1979, ch. 2; Zel'dovich 1940; Taylor 1950). The CJ point is where the
/// Rayleigh line p = rho0 D^2 (1 - V) touches the products' Hugoniot
/// E - E0 = p (1 - V) / 2 (V = rho0 / rho), i.e. D V = c. Behind it the centred simple wave
/// x / t = u + c with u - int c d(rho)/rho constant runs down the JWL isentrope
/// p = A e^{-R1 V} + B e^{-R2 V} + C V^{-(1+omega)} through the CJ point to rest (u = 0), a
/// plateau that reaches x / t = c_plateau.
class CJDetonation {
 public:
  explicit CJDetonation(const DetonationParameters& parameters = {});
  /// The CJ state implied by the JWL fit (velocity in the lab frame, behind the front).
  const DetonationState& cj_state() const { return cj_; }
  double cj_speed() const { return speed_; }           ///< D implied by the fit
  double cj_relative_volume() const { return v_cj_; }  ///< V_CJ = rho0 / rho_CJ
  const DetonationState& plateau_state() const { return plateau_; }
  double plateau_pressure() const { return plateau_.pressure; }
  /// Products' Hugoniot pressure at relative volume V (from the unreacted state at p = 0).
  double hugoniot_pressure(double relative_volume) const;
  /// Pressure and sound speed on the isentrope through the CJ point.
  double isentrope_pressure(double relative_volume) const;
  double isentrope_sound_speed(double relative_volume) const;
  /// Flow velocity on the Taylor wave at relative volume V (the Riemann invariant).
  double isentrope_velocity(double relative_volume) const;
  /// State at (x, t), t > 0: plateau, Taylor wave, CJ front at x0 + D t, unreacted ahead
  /// (rho0, u = 0, p = 0: the programmed burn's unburnt state).
  DetonationState sample(double x, double t) const;
  const DetonationParameters& parameters() const { return parameters_; }

 private:
  double jwl_pressure(double relative_volume, double energy_per_volume) const;
  DetonationParameters parameters_;
  DetonationState cj_, plateau_;
  double speed_ = 0, v_cj_ = 0, v_plateau_ = 0, isentrope_c_ = 0;
  std::vector<double> panel_v_, panel_u_;  // Riemann-invariant quadrature panels
};

/// Errors L1/L2/Linf of pressure (zones) against CJDetonation; diagnostics front_position
/// (largest zone-centre x with pressure above half the exact P_CJ), front_position_exact
/// (x0 + D t, D implied by the fit), front_position_nominal (x0 + nominal_speed t),
/// peak_pressure, cj_pressure_exact, cj_speed_exact, plateau_pressure (area-weighted mean over
/// the zones with centre x - x0 < D t / 4) and plateau_pressure_exact.
Reference detonation_reference(const DetonationParameters& parameters = {});

/// The paper's smooth accuracy test (section 5.3 with the errata of docs/algorithm.md §15): on the periodic
/// unit square, with X = x - a t, Y = y - a t,
///   rho = rho0 (1 - 0.1 sin 2 pi X - 0.1 cos 2 pi Y), u = v = a, e = e0,
///   S_xx = s1 (cos 2 pi X - sin 2 pi Y), S_yy = -s1 (sin 2 pi X - cos 2 pi Y),
///   S_xy = S_xx + S_yy, p = p_MG(rho, e0),
/// exact under the momentum source b = -div sigma_exact (rho Dv/Dt = div sigma + b = 0).
struct AccuracyParameters {
  MieGruneisen eos{8930.0, 3940.0, 2.0, 1.49};
  double velocity = 1e4;  ///< a (both components)
  double s1 = 60e6;
  double energy = 1e-14;  ///< e0
  double amplitude = 0.1;
};

class AccuracySolution {
 public:
  explicit AccuracySolution(const AccuracyParameters& parameters = {});
  double density(double x, double y, double t) const;
  double pressure(double x, double y, double t) const;
  double stress_xx(double x, double y, double t) const;
  double stress_yy(double x, double y, double t) const;
  double stress_xy(double x, double y, double t) const;
  /// Momentum source (force per unit volume) -div sigma_exact at (x, y, t).
  std::array<double, 2> momentum_source(double x, double y, double t) const;
  const AccuracyParameters& parameters() const { return parameters_; }

 private:
  AccuracyParameters parameters_;
};

/// The source terms of the accuracy test (momentum as above, zero energy source).
Sources accuracy_sources(const AccuracyParameters& parameters = {});
/// Errors L1/L2/Linf of density and deviatoric_stress_xx/yy/xy at the simulation's time.
Reference accuracy_reference(const AccuracyParameters& parameters = {});

}  // namespace stagger
