#pragma once
/// @file problem.hpp
/// A complete problem set-up in code: mesh, materials per region, initial conditions,
/// boundary conditions, numerical options. A scene file is translated into exactly this.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "stagger/materials.hpp"
#include "stagger/mesh.hpp"

namespace stagger {

/// A scalar field of position, f(x, y).
using SpaceFunction = std::function<double(double x, double y)>;
/// A scalar function of time, f(t).
using TimeFunction = std::function<double(double t)>;

/// Returns a SpaceFunction that is the constant `value` everywhere.
SpaceFunction constant_field(double value);
/// Returns a TimeFunction that is the constant `value` at all times.
TimeFunction constant_in_time(double value);

/// Initial state of one region. Zone fields are evaluated at the zone centre (vertex
/// average), point fields at the points (a point shared by regions takes the first region
/// in Problem::regions that contains it). Give either pressure or specific_internal_energy.
struct RegionSetup {
  std::string region;                              ///< region name in the mesh
  std::string material;                            ///< material name in Problem::materials
  SpaceFunction density;                           ///< rho0(x, y) > 0 (required)
  SpaceFunction pressure;                          ///< or:
  SpaceFunction specific_internal_energy;          ///< (exactly one of the two)
  SpaceFunction velocity_x = constant_field(0.0);  ///< initial point velocity, x component
  SpaceFunction velocity_y = constant_field(0.0);  ///< initial point velocity, y component
  /// Initial deviatoric stress (materials with strength only); empty = zero.
  SpaceFunction stress_xx, stress_yy, stress_xy;
};

/// Internal energy `energy` (total, not specific) deposited at t = 0 (Sedov): with radius 0,
/// shared by mass among the zones that have the point nearest to (x, y) as a vertex; with
/// radius R > 0, a Gaussian in specific energy, zone z getting a share proportional to
/// m_z exp(-(d_z / R)^2), d_z the distance of its vertex average from (x, y).
struct EnergyDeposit {
  double x = 0, y = 0;  ///< where (radius 0: the nearest mesh point is used)
  double energy = 0;    ///< total internal energy added (per unit length in z)
  double radius = 0;    ///< Gaussian radius R (0: the zones around the nearest point)
};

/// What a boundary condition imposes on the points of its tag.
enum class BoundaryKind {
  wall,      ///< v.n = 0 (symmetry plane or rigid wall, any orientation)
  velocity,  ///< v.n = u(t).n, u = (velocity_x(t), velocity_y(t)); tangential free
  free,      ///< traction-free
  pressure,  ///< applied pressure p(t) on the boundary edges
  periodic,  ///< paired with `partner`; points matched by translation
  fixed,     ///< clamped: v = 0, both components (no tangential slip); its work is zero
  /// non-reflecting (acoustic impedance): the pressure p0 + rho c u.n of the zone beside each
  /// edge, u.n its outward normal velocity; its work is boundary work
  transmitting,
};

/// A boundary condition on the points and edges of one mesh tag (a physical curve).
struct BoundaryCondition {
  std::string tag;                         ///< boundary tag name in the mesh
  BoundaryKind kind = BoundaryKind::wall;  ///< what is imposed
  /// Prescribed velocity u(t) (kind velocity).
  TimeFunction velocity_x = constant_in_time(0.0), velocity_y = constant_in_time(0.0);
  TimeFunction pressure = constant_in_time(0.0);  ///< applied pressure p(t) (kind pressure)
  std::string partner;                            ///< periodic: the other tag
  /// transmitting: the far-field pressure p0 is the adjacent zone's at t = 0 (true), or pressure(t)
  bool far_field_from_initial_state = true;
};

/// Artificial viscosity: zone-centred bulk q, the edge-centred viscosity with limiter, or the
/// tensor q from corner strain rates (docs/algorithm.md §4.1).
enum class Viscosity { bulk, edge, tensor };
/// Hourglass control (docs/algorithm.md §6): the paper's viscosity on the mode
/// Gamma = (1,-1,1,-1), or the Flanagan-Belytschko projection (better on distorted quads),
/// or subzonal pressures from constant subzone masses (any polygon; docs/algorithm.md §18)
/// on the median-mesh corners or on the side triangles, whose merit factor is
/// hourglass_coefficient.
enum class Hourglass { gamma, flanagan_belytschko, subzonal, subzonal_triangles };
/// Deviatoric stress update (docs/algorithm.md §7): the paper's rate form, or the objective
/// incremental update S <- R S R^T (Hughes-Winget rotation).
enum class StressUpdate { rate, objective };

/// Coordinates of the 2D mesh: planar (x, y), per unit depth, or axisymmetric rz: x is the
/// radius r >= 0, y the axial coordinate z, x = 0 the axis; masses, volumes and energies are
/// then per radian (docs/algorithm.md §19).
enum class CoordinateSystem { planar, rz };

/// Numerical options (a scene's [numerics]). Ranges, units and meanings: numerics_option_table()
/// in option_table.hpp, which the scene reader, validate() and docs/scenes.md share.
struct HydroOptions {
  double cfl = 0.15;  ///< c_t, in (0, 1)
  // Defaults chosen from measurements over the verification problems (docs/algorithm.md §4.2,
  // docs/verification.md "Default numerics").
  Viscosity viscosity = Viscosity::tensor;
  double q1 = 1.5, q2 = 0.06;           ///< bulk q (quadratic, linear)
  double edge_c1 = 0.5, edge_c2 = 1.0;  ///< edge viscosity (linear, quadratic)
  bool edge_limiter = true;             ///< Christensen limiter for the edge viscosity
  Hourglass hourglass = Hourglass::subzonal_triangles;
  double hourglass_coefficient = 2.0;  ///< Q (subzonal: merit factor); 0 turns hourglass control off
  StressUpdate stress_update = StressUpdate::rate;
  bool fresh_predictor = false;  ///< evaluate f^n afresh each cycle (reference option)
  /// Compensated (two-sum) accumulation of positions and velocities (docs/algorithm.md §20).
  bool compensated_update = false;
  double volume_limit = 0.1;  ///< f_A
  double dt_growth = 1.1;
  double dt_init = 0;   ///< 0 = the CFL value at t = 0
  double dt_max = 0;    ///< 0 = none
  double dt_min = 0;    ///< 0 = 1e-8 t_end
  int max_retries = 3;  ///< halvings of dt for a tangled step, in [0, 30]
  /// Treat a non-positive median-mesh corner area as tangling (docs/algorithm.md §9).
  /// A zone whose vertex-average centre crosses a reflex vertex (the Sedov hot corner on a
  /// Cartesian mesh) trips it while its area is still positive; false checks zone areas only.
  bool check_corner_areas = true;
  CoordinateSystem geometry = CoordinateSystem::planar;  ///< planar or axisymmetric (docs/algorithm.md §19)
  /// Noh's artificial heat flux (docs/algorithm.md §21), kappa = rho l (c1 C + c2 l max(-div u, 0));
  /// off when both are 0 (the default).
  double heat_flux_c1 = 0, heat_flux_c2 = 0;
};

/// How the mesh moves (a scene's [ale]; docs/ale.md): with the material (Lagrangian), rezoned
/// and remapped (ALE), or back to the initial mesh after every step (Eulerian).
enum class AleMode { lagrangian, ale, eulerian };
/// The rezone of ale.mode = "ale" (docs/ale.md, "Rezone"): Winslow with the initial mesh as
/// logical space, towards the initial corner shapes, or Winslow with Knupp's regular layouts.
enum class AleRezone { winslow, reference_jacobian, winslow_regular };
/// The limiter of the remap's piecewise-linear reconstruction.
enum class AleLimiter { barth_jespersen, none };

/// ALE options (a scene's [ale]). Ranges, units and meanings: ale_option_table() in
/// option_table.hpp. mode = lagrangian (the default) leaves the run bitwise Lagrangian.
struct AleOptions {
  AleMode mode = AleMode::lagrangian;
  AleRezone rezone = AleRezone::winslow;
  double relaxation = 0.5;        ///< rezone: fraction of the way from the Lagrangian to the smoothed mesh
  int rezone_iterations = 1;      ///< rezone: smoothing sweeps per remap
  double corner_angle = 0.5;      ///< rezone: boundary points slide where the boundary turns less (degrees)
  double max_move = 0.5;          ///< rezone: largest move of a point per remap, in its shortest edges
  double size_weight = 0;         ///< rezone reference_jacobian: weight of the relative-size term; 0: shapes only
  int remap_every = 0;            ///< remap after every N-th cycle; 0: off
  double quality_trigger = 0.25;  ///< remap when the worst zone shape quality falls below it; 0: off
  AleLimiter limiter = AleLimiter::barth_jespersen;
};

/// Manufactured-solution source terms (docs/algorithm.md §1 steps 3, 4 and 7).
struct Sources {
  /// Momentum source per unit volume (force density) at (x, y, t): point force V_p s.
  std::function<std::array<double, 2>(double x, double y, double t)> momentum;
  /// Specific energy source s_e(x, y, t) (per unit mass and time).
  std::function<double(double x, double y, double t)> energy;
};

/// A complete set-up. Moved into a Simulation, which validates it and keeps it
/// (Simulation::problem()). Boundary points that no BoundaryCondition constrains are
/// traction-free.
struct Problem {
  std::string name = "problem";               ///< used in messages and output file names
  Mesh mesh;                                  ///< from build_mesh (meshgen or your own soup)
  std::vector<Material> materials;            ///< by name
  std::vector<RegionSetup> regions;           ///< one per mesh region, exactly
  std::vector<BoundaryCondition> boundaries;  ///< by tag
  std::vector<EnergyDeposit> deposits;        ///< point energy sources at t = 0 (Sedov)
  std::optional<Sources> sources;             ///< manufactured-solution sources, if any
  HydroOptions options;                       ///< numerics (defaults: docs/scenes.md [numerics])
  AleOptions ale;                             ///< mesh motion (defaults: Lagrangian; docs/ale.md)
  double t_end = 0;                           ///< end time, > 0
  /// Checks names, ranges and completeness; throws stagger::Error with the offending item.
  void validate() const;
};

}  // namespace stagger
